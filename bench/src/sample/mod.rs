//! How diverse and how uniform [`rccpack::sample::sample()`]'s layouts are
//! (`rccpack-bench sample`).
//!
//! * [`enumerate`] — every layout of a **tiny** problem by brute force
//!   (every grid position of every unplaced object, overlaps skipped, hard
//!   rules and the numerator from the evaluator), one per canonical
//!   layout ([`rccpack::sample::canonical_key`]);
//! * [`uniformity`] — the first layout drawn with each of `draws` seeds,
//!   counted per layout and compared with uniform by a chi-square test;
//! * [`diversity`] — pairwise distances and positions covered among the
//!   layouts one run draws;
//! * [`tiny_problems`] — the small problems the bench and the tests use.

mod diversity;
mod problems;
mod report;
mod uniformity;

use rccpack::relations::Contact;
use rccpack::rules::RuleSet;
/// A canonical layout key (see [`canonical_key`](rccpack::sample::canonical_key)).
pub use rccpack::sample::LayoutKey as Key;
use rccpack::sample::{Quality, Repair, SampleOptions};
use rccpack::scene::Scene;

pub use diversity::{cpsat_baseline, diversity, spread, Baseline, Diversity, Spread};
pub use problems::tiny_problems;
pub use report::report_text;
pub use uniformity::{chi_square_p, enumerate, uniformity, Uniformity};

fn repair(random: bool) -> Repair {
    if random {
        Repair::Random
    } else {
        Repair::Activity
    }
}

/// What `rccpack-bench sample` runs.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchConfig {
    /// Seed of the sampler (and the first seed of the baseline).
    pub seed: u64,
    /// Layouts per problem.
    pub n: usize,
    /// Uniformity: draws per layout of each tiny problem.
    pub draws_per_layout: usize,
    /// Generated realistic tasks (their 1× problem each).
    pub tasks: usize,
    /// Run the CP-SAT baseline.
    pub baseline: bool,
    /// Per problem, a time limit for the sampler run.
    pub time_limit_s: f64,
}

/// One problem of the diversity part.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ProblemRow {
    /// `example-3/all-rules`, `task00-1x/optimum`, …
    pub name: String,
    /// Movable objects.
    pub movable: usize,
    /// The sampler's run (`None`: it failed, see `error`).
    pub sampler: Option<Diversity>,
    /// Why the sampler gave no layout.
    pub error: Option<String>,
    /// The CP-SAT baseline (`Err`: why it did not run).
    pub baseline: Option<Result<Baseline, String>>,
}

/// The whole report (`sample.json`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchReport {
    /// The configuration.
    pub config: BenchConfig,
    /// Per tiny problem: the uniformity test.
    pub uniformity: Vec<(String, Option<Uniformity>)>,
    /// Per problem: diversity.
    pub problems: Vec<ProblemRow>,
}

/// The uniformity test on every tiny problem, with activity and random
/// search.
fn uniformity_rows(
    cfg: &BenchConfig,
    note: &mut dyn FnMut(&str),
) -> Vec<(String, Option<Uniformity>)> {
    let mut uniformity_rows = Vec::new();
    for (name, problem, rules) in tiny_problems() {
        for random in [false, true] {
            let name = format!("{name} ({})", if random { "random" } else { "activity" });
            note(&format!("uniformity: {name}"));
            let u = uniformity(
                &problem,
                &rules,
                Quality::Optimum,
                random,
                cfg.draws_per_layout,
            );
            uniformity_rows.push((name, u));
        }
    }
    uniformity_rows
}

/// The problems of the diversity measurement: the bundled example at 3
/// and 5 per class, and the first problem of each generated task.
fn diversity_problems(cfg: &BenchConfig) -> Vec<(String, Scene, RuleSet, Quality, bool)> {
    let mut problems: Vec<(String, Scene, RuleSet, Quality, bool)> = Vec::new();
    if let Ok(t) = super::tasks::example_task(&[3, 5], Default::default()) {
        for p in &t.problems {
            for (q, what) in [
                (Quality::AllRules, "all-rules"),
                (Quality::Optimum, "optimum"),
            ] {
                for random in [false, true] {
                    let name = format!("{}/{what}{}", p.name, if random { "+random" } else { "" });
                    problems.push((name, p.scene.clone(), t.rules.clone(), q, random));
                }
            }
        }
    }
    let tcfg = super::tasks::TasksConfig::quick(cfg.seed, std::time::Duration::from_secs(10));
    for i in 0..cfg.tasks {
        if let Ok(t) = super::tasks::generate_task(&tcfg, i) {
            if let Some(p) = t.problems.first() {
                for random in [false, true] {
                    problems.push((
                        format!("{}/optimum{}", p.name, if random { "+random" } else { "" }),
                        p.scene.clone(),
                        t.rules.clone(),
                        Quality::Optimum,
                        random,
                    ));
                }
            }
        }
    }
    problems
}

/// Run the bench; `note` hears what is being measured.
pub fn run_bench(cfg: &BenchConfig, note: &mut dyn FnMut(&str)) -> BenchReport {
    let uniformity_rows = uniformity_rows(cfg, note);
    let problems = diversity_problems(cfg);
    let mut rows = Vec::new();
    for (name, problem, rules, quality, random_search) in problems {
        note(&format!("diversity: {name}"));
        let opts = SampleOptions {
            quality,
            seed: cfg.seed,
            repair: repair(random_search),
            // Never panics on an unchecked value (the command line checks it).
            stop: rccpack::stop::Stop::after(
                rccpack::limits::time_limit(cfg.time_limit_s).unwrap_or(
                    std::time::Duration::from_secs_f64(rccpack::limits::MAX_TIME_LIMIT_SECS),
                ),
            ),
            ..SampleOptions::default()
        };
        let movable = problem.objects.iter().filter(|o| !o.is_placed()).count();
        let (sampler, error, first) = match diversity(&problem, &rules, &opts, cfg.n) {
            Ok((d, layouts)) => (Some(d), None, layouts.into_iter().next()),
            Err(e) => (None, Some(e.to_string()), None),
        };
        let baseline = match (&first, cfg.baseline && !random_search) {
            (Some(f), true) => {
                note(&format!("baseline: {name}"));
                Some(cpsat_baseline(
                    &problem,
                    &rules,
                    Contact::Point,
                    f,
                    cfg.n,
                    cfg.seed,
                ))
            }
            _ => None,
        };
        rows.push(ProblemRow {
            name,
            movable,
            sampler,
            error,
            baseline,
        });
    }
    BenchReport {
        config: cfg.clone(),
        uniformity: uniformity_rows,
        problems: rows,
    }
}
