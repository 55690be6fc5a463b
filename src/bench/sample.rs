//! How diverse and how uniform [`crate::sample::sample()`]'s layouts are
//! (`rccpack bench sample`).
//!
//! * [`enumerate`] — every layout of a **tiny** problem by brute force
//!   (every grid position of every unplaced object, overlaps skipped, hard
//!   rules and the §6 numerator from the evaluator), one per canonical
//!   layout ([`crate::sample::canonical_key`]);
//! * [`uniformity`] — the first layout drawn with each of `draws` seeds,
//!   counted per layout and compared with uniform by a chi-square test;
//! * [`diversity`] — pairwise distances and positions covered among the
//!   layouts one run draws;
//! * [`tiny_problems`] — the small problems the bench and the tests use.

use crate::eval::evaluate;
use crate::relations::Contact;
use crate::rules::{parse_rules, RuleSet};
use crate::sample::{canonical_key, sample, Quality, Repair, SampleOptions};
use crate::scene::{Object, Scene, Space};
use crate::synth::brute_force::grid_positions;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

/// A canonical layout key (see [`canonical_key`]).
pub use crate::sample::LayoutKey as Key;

fn repair(random: bool) -> Repair {
    if random {
        Repair::Random
    } else {
        Repair::Activity
    }
}

/// Every layout of `problem` that keeps the hard rules, with its §6
/// numerator, one per canonical layout; `None` when more than `limit`
/// assignments would have to be tried.
pub fn enumerate(
    problem: &Scene,
    rules: &RuleSet,
    contact: Contact,
    limit: u128,
) -> Option<Vec<(Key, f64)>> {
    let free: Vec<usize> = (0..problem.objects.len())
        .filter(|&i| !problem.objects[i].is_placed())
        .collect();
    let domains: Vec<Vec<(i64, i64)>> = free
        .iter()
        .map(|&i| {
            let o = &problem.objects[i];
            grid_positions(problem, o.width, o.height)
        })
        .collect();
    let size = domains
        .iter()
        .fold(1u128, |a, d| a.saturating_mul(d.len() as u128));
    if size > limit {
        return None;
    }
    let mut out: BTreeMap<Key, f64> = BTreeMap::new();
    let mut idx = vec![0usize; free.len()];
    let mut scene = problem.clone();
    if domains.iter().any(|d| d.is_empty()) {
        return Some(Vec::new());
    }
    loop {
        for (k, &i) in free.iter().enumerate() {
            let (x, y) = domains[k][idx[k]];
            scene.objects[i].x = Some(x);
            scene.objects[i].y = Some(y);
        }
        if scene.validate().is_ok() {
            let e = evaluate(&scene, rules, contact);
            if e.hard_ok() {
                out.entry(canonical_key(problem, &scene))
                    .or_insert(e.satisfied_weight);
            }
        }
        // Next assignment (odometer).
        let mut k = 0;
        loop {
            if k == idx.len() {
                return Some(out.into_iter().collect());
            }
            idx[k] += 1;
            if idx[k] < domains[k].len() {
                break;
            }
            idx[k] = 0;
            k += 1;
        }
    }
}

/// The chance that a chi-square variable with `dof` degrees of freedom is
/// at least `x` (the upper regularised incomplete gamma `Q(dof/2, x/2)`).
pub fn chi_square_p(x: f64, dof: f64) -> f64 {
    if dof <= 0.0 {
        return 1.0;
    }
    gamma_q(dof / 2.0, x / 2.0)
}

fn ln_gamma(x: f64) -> f64 {
    // Lanczos (g = 7, n = 9).
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, &c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Upper regularised incomplete gamma `Q(a, x)` (series below `a + 1`,
/// continued fraction above).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let lg = ln_gamma(a);
    if x < a + 1.0 {
        let (mut sum, mut term, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..1000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - lg).exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..1000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (-x + a * x.ln() - lg).exp() * h
    }
}

/// [`uniformity`]'s result.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Uniformity {
    /// Layouts of the quality asked for (brute force).
    pub layouts: usize,
    /// Draws: the first layout of each of this many seeds.
    pub draws: usize,
    /// Distinct layouts among the draws.
    pub reached: usize,
    /// What a uniform sampler reaches in as many draws, on average:
    /// `layouts·(1 − (1 − 1/layouts)^draws)`.
    pub uniform_reached: f64,
    /// Pearson's chi-square statistic against uniform.
    pub chi_square: f64,
    /// Its p-value (`layouts − 1` degrees of freedom).
    pub p_value: f64,
    /// The largest and smallest count of one layout.
    pub max_count: usize,
    /// (0 when some layout was never drawn.)
    pub min_count: usize,
    /// Whether a full run (draw until exhausted) returned exactly the
    /// brute-force layouts.
    pub exhaustive_ok: bool,
}

/// Draw the first layout of `draws_per_layout × layouts` seeds (0, 1, …)
/// and compare the frequencies with uniform over every layout of the optimum score found by
/// brute force (`random`: [`Repair::Random`], else [`Repair::Activity`]);
/// also run the sampler to the end once and check that it
/// returns exactly those layouts. `None` when the problem is too large for
/// brute force or has no layout.
pub fn uniformity(
    problem: &Scene,
    rules: &RuleSet,
    quality: Quality,
    random: bool,
    draws_per_layout: usize,
) -> Option<Uniformity> {
    let contact = Contact::Point;
    let all = enumerate(problem, rules, contact, 2_000_000)?;
    let best = all
        .iter()
        .map(|(_, n)| *n)
        .fold(f64::NEG_INFINITY, f64::max);
    let total = evaluate(&problem_filled(problem, &all)?, rules, contact).total_weight;
    let keep = |n: f64| match quality {
        Quality::Optimum => crate::synth::brute_force::approx_eq(n, best),
        Quality::AllRules => crate::synth::brute_force::approx_eq(n, total),
        Quality::MinScore(x) => total <= 0.0 || n / total >= x - 1e-9,
    };
    let target: BTreeSet<Key> = all
        .into_iter()
        .filter(|(_, n)| keep(*n))
        .map(|(k, _)| k)
        .collect();
    if target.is_empty() {
        return None;
    }
    let opts = |seed| SampleOptions {
        quality,
        seed,
        contact,
        repair: repair(random),
        ..SampleOptions::default()
    };
    let full: BTreeSet<Key> = sample(problem, rules, &opts(0))
        .ok()?
        .map_while(Result::ok)
        .map(|s| canonical_key(problem, &s))
        .collect();
    let exhaustive_ok = full == target;
    let draws = draws_per_layout * target.len();
    let mut counts: BTreeMap<&Key, usize> = target.iter().map(|k| (k, 0)).collect();
    for seed in 0..draws as u64 {
        let first = sample(problem, rules, &opts(seed)).ok()?.next()?.ok()?;
        *counts.get_mut(&canonical_key(problem, &first))? += 1;
    }
    let m = target.len();
    let e = draws as f64 / m as f64;
    let chi_square: f64 = counts.values().map(|&c| (c as f64 - e).powi(2) / e).sum();
    Some(Uniformity {
        layouts: m,
        draws,
        reached: counts.values().filter(|&&c| c > 0).count(),
        uniform_reached: m as f64 * (1.0 - (1.0 - 1.0 / m as f64).powi(draws as i32)),
        chi_square,
        p_value: chi_square_p(chi_square, (m - 1) as f64),
        max_count: counts.values().copied().max().unwrap_or(0),
        min_count: counts.values().copied().min().unwrap_or(0),
        exhaustive_ok,
    })
}

/// Some complete scene of `problem` (for the §6 denominator, which does
/// not depend on the positions).
fn problem_filled(problem: &Scene, all: &[(Key, f64)]) -> Option<Scene> {
    let (key, _) = all.first()?;
    let mut s = problem.clone();
    let mut pos: BTreeMap<(String, i64, i64), Vec<(i64, i64)>> = key
        .iter()
        .map(|(c, w, h, v)| ((c.clone(), *w, *h), v.clone()))
        .collect();
    for o in s.objects.iter_mut().filter(|o| !o.is_placed()) {
        let (x, y) = pos.get_mut(&(o.class.clone(), o.width, o.height))?.pop()?;
        o.x = Some(x);
        o.y = Some(y);
    }
    Some(s)
}

/// How spread out a set of layouts of one problem is.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Spread {
    /// Layouts.
    pub layouts: usize,
    /// Distinct layouts among them ([`canonical_key`]).
    pub distinct: usize,
    /// Mean distance between two layouts: the sum over movable objects
    /// (matched by id) of `(|dx| + |dy|) / grid`.
    pub mean_distance: f64,
    /// The smallest such distance (0 when a layout repeats).
    pub min_distance: f64,
    /// Per class of movable objects: distinct positions taken, over all
    /// layouts.
    pub positions_per_class: BTreeMap<String, usize>,
}

/// Pairwise distances and positions covered among `layouts` (complete
/// scenes of `problem`).
pub fn spread(problem: &Scene, layouts: &[Scene]) -> Spread {
    let g = problem.grid.max(1) as f64;
    let movable: Vec<usize> = (0..problem.objects.len())
        .filter(|&i| !problem.objects[i].is_placed())
        .collect();
    let dist = |a: &Scene, b: &Scene| -> f64 {
        movable
            .iter()
            .map(|&i| {
                let (p, q) = (&a.objects[i], &b.objects[i]);
                let dx = (p.x.unwrap_or(0) - q.x.unwrap_or(0)).abs();
                let dy = (p.y.unwrap_or(0) - q.y.unwrap_or(0)).abs();
                (dx + dy) as f64 / g
            })
            .sum()
    };
    let (mut sum, mut pairs, mut min) = (0.0, 0usize, f64::INFINITY);
    for i in 0..layouts.len() {
        for j in i + 1..layouts.len() {
            let d = dist(&layouts[i], &layouts[j]);
            sum += d;
            pairs += 1;
            min = min.min(d);
        }
    }
    let mut per_class: BTreeMap<String, BTreeSet<(i64, i64)>> = BTreeMap::new();
    for s in layouts {
        for &i in &movable {
            let o = &s.objects[i];
            per_class
                .entry(o.class.clone())
                .or_default()
                .insert((o.x.unwrap_or(0), o.y.unwrap_or(0)));
        }
    }
    let distinct: BTreeSet<Key> = layouts.iter().map(|s| canonical_key(problem, s)).collect();
    Spread {
        layouts: layouts.len(),
        distinct: distinct.len(),
        mean_distance: if pairs > 0 { sum / pairs as f64 } else { 0.0 },
        min_distance: if pairs > 0 { min } else { 0.0 },
        positions_per_class: per_class.into_iter().map(|(c, s)| (c, s.len())).collect(),
    }
}

/// One sampler run: its layouts' spread and its time.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Diversity {
    /// Spread of the layouts.
    #[serde(flatten)]
    pub spread: Spread,
    /// Wall time of the whole run (the optimum included), in ms.
    pub total_ms: f64,
    /// `total_ms / layouts`.
    pub ms_per_layout: f64,
    /// The time limit stopped the run before `n` layouts.
    pub limit_struck: bool,
}

/// Draw up to `n` layouts with `opts` and measure how spread out they are;
/// also returns the layouts. A limit (`opts.time_limit`) ends the run with
/// what was found ([`Diversity::limit_struck`]).
pub fn diversity(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SampleOptions,
    n: usize,
) -> Result<(Diversity, Vec<Scene>), crate::sample::SampleError> {
    let start = Instant::now();
    let mut layouts = Vec::with_capacity(n);
    let mut limit_struck = false;
    for item in sample(problem, rules, opts)?.take(n) {
        match item {
            Ok(s) => layouts.push(s),
            Err(crate::sample::SampleError::LimitReached { found }) if found > 0 => {
                limit_struck = true;
                break;
            }
            Err(e) => return Err(e),
        }
    }
    let total_ms = start.elapsed().as_secs_f64() * 1000.0;
    let d = Diversity {
        spread: spread(problem, &layouts),
        total_ms,
        ms_per_layout: total_ms / layouts.len().max(1) as f64,
        limit_struck,
    };
    Ok((d, layouts))
}

/// The baseline's run: CP-SAT with randomised search, one solve per seed
/// (`benches/peers/cpsat_sample.py`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct Baseline {
    /// Spread of the layouts (repeats included).
    #[serde(flatten)]
    pub spread: Spread,
    /// CP-SAT's summed solve time, in ms (model building and the Python
    /// start excluded).
    pub solve_ms: f64,
    /// Wall time of the whole process, in ms.
    pub process_ms: f64,
    /// Layouts that failed the verifier or the quality (should be 0).
    pub invalid: usize,
}

/// Run the CP-SAT baseline for `n` layouts whose integer objective is at
/// least that of `like_this` (a layout of the quality wanted), seeds
/// `seed..seed + n`. `Err` says why it could not run (no `python3`, no
/// `ortools`, a script error).
pub fn cpsat_baseline(
    problem: &Scene,
    rules: &RuleSet,
    contact: Contact,
    like_this: &Scene,
    n: usize,
    seed: u64,
) -> Result<Baseline, String> {
    let opts = crate::synth::SynthOptions {
        contact,
        ..crate::synth::SynthOptions::default()
    };
    let e = crate::synth::emit::emitted(problem, rules, &opts).map_err(|e| e.to_string())?;
    let vals_of = |s: &Scene| crate::sample::grid_values(&e.model, s);
    let target = e
        .objective_of(&vals_of(like_this))
        .ok_or("the layout does not fit the model")?;
    let path = std::env::temp_dir().join(format!(
        "rccpack-sample-baseline-{}-{seed}.json",
        std::process::id()
    ));
    crate::fsutil::atomic_write(&path, crate::synth::emit::to_json(&e))
        .map_err(|e| e.to_string())?;
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/peers/cpsat_sample.py");
    let start = Instant::now();
    let out = std::process::Command::new("python3")
        .arg(script)
        .arg(&path)
        .args(["--min-objective", &target.to_string()])
        .args(["--n", &n.to_string(), "--seed", &seed.to_string()])
        .output();
    let _ = std::fs::remove_file(&path);
    let out = out.map_err(|e| format!("cannot run python3: {e}"))?;
    let process_ms = start.elapsed().as_secs_f64() * 1000.0;
    if !out.status.success() {
        return Err(String::from_utf8_lossy(&out.stderr).trim().to_string());
    }
    #[derive(serde::Deserialize)]
    struct Line {
        layouts: Vec<Vec<i64>>,
        time_s: f64,
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let line: Line = serde_json::from_str(text.lines().last().unwrap_or(""))
        .map_err(|e| format!("cannot read the script's answer: {e}"))?;
    let mut invalid = 0;
    let mut layouts = Vec::new();
    for v in &line.layouts {
        if v.len() != e.model.vars.len() {
            invalid += 1;
            continue;
        }
        let s = e.model.scene(problem, v);
        let ok = crate::synth::verify_solution(problem, &s, rules, contact).is_ok()
            && e.objective_of(v).is_some_and(|o| o >= target);
        if ok {
            layouts.push(s);
        } else {
            invalid += 1;
        }
    }
    Ok(Baseline {
        spread: spread(problem, &layouts),
        solve_ms: line.time_s * 1000.0,
        process_ms,
        invalid,
    })
}

fn block(id: &str, class: &str, w: i64, h: i64) -> Object {
    Object {
        id: id.into(),
        class: class.into(),
        x: None,
        y: None,
        width: w,
        height: h,
        fixed: false,
    }
}

/// Small problems whose layouts brute force enumerates in milliseconds:
/// `(name, problem, rules)`.
pub fn tiny_problems() -> Vec<(&'static str, Scene, RuleSet)> {
    let space = |w, h| Space {
        x: 0,
        y: 0,
        width: w,
        height: h,
    };
    let scene = |sp, objects| Scene {
        space: sp,
        grid: 10,
        objects,
    };
    let rules = |t: &str| parse_rules(t).expect("the tiny rules parse");
    vec![
        (
            "two-touching",
            // Two interchangeable blocks that touch, on a 5×4 table.
            scene(
                space(50, 40),
                vec![block("a1", "A", 10, 10), block("a2", "A", 10, 10)],
            ),
            rules("rule touch: EC_N(A, A) | EC_S(A, A) | EC_E(A, A) | EC_W(A, A)\n"),
        ),
        (
            "b-on-wall",
            // A blue north of a red, the blue touching the east wall.
            scene(
                space(50, 50),
                vec![
                    Object::fixed_at("wall", "W", 40, 0, 10, 50),
                    block("r1", "R", 10, 10),
                    block("b1", "B", 10, 10),
                ],
            ),
            rules(
                "rule b_north: DR_N(B, R)\n\
                 rule b_wall weight 2: EC_W(B, W)\n",
            ),
        ),
        (
            "row-of-three",
            // Three in one row, flush, on a 6×3 table (optimum below 1 is
            // impossible to avoid for the corner rule).
            scene(
                space(60, 30),
                vec![
                    block("g1", "G", 10, 10),
                    block("g2", "G", 10, 10),
                    block("g3", "G", 20, 10),
                ],
            ),
            rules(
                "rule row: AL_S(G, every G)\n\
                 rule flush: FL_E(G, G) | FL_W(G, G)\n",
            ),
        ),
    ]
}

/// What `rccpack bench sample` runs.
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

/// Run the bench; `note` hears what is being measured.
pub fn run_bench(cfg: &BenchConfig, note: &mut dyn FnMut(&str)) -> BenchReport {
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
    let mut rows = Vec::new();
    for (name, problem, rules, quality, random_search) in problems {
        note(&format!("diversity: {name}"));
        let opts = SampleOptions {
            quality,
            seed: cfg.seed,
            repair: repair(random_search),
            // Never panics on an unchecked value (the command line checks it).
            time_limit: Some(crate::limits::time_limit(cfg.time_limit_s).unwrap_or(
                std::time::Duration::from_secs_f64(crate::limits::MAX_TIME_LIMIT_SECS),
            )),
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

/// The report as two plain-text tables.
pub fn report_text(r: &BenchReport) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "uniformity (first layout of each seed vs uniform over the brute-force optimum layouts)"
    );
    let _ = writeln!(
        s,
        "{:<24} {:>7} {:>6} {:>8} {:>9} {:>9} {:>10} {:>9} {:>10}",
        "problem", "layouts", "draws", "reached", "uniform", "chi2", "p", "min/max", "exhaustive"
    );
    for (name, u) in &r.uniformity {
        match u {
            Some(u) => {
                let _ = writeln!(
                    s,
                    "{:<24} {:>7} {:>6} {:>8} {:>9.1} {:>9.1} {:>10.2e} {:>9} {:>10}",
                    name,
                    u.layouts,
                    u.draws,
                    u.reached,
                    u.uniform_reached,
                    u.chi_square,
                    u.p_value,
                    format!("{}/{}", u.min_count, u.max_count),
                    if u.exhaustive_ok { "all" } else { "MISSED" }
                );
            }
            None => {
                let _ = writeln!(s, "{name:<24} (not measured)");
            }
        }
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "diversity ({} layouts per problem; distance in grid steps, objects matched by id)",
        r.config.n
    );
    let _ = writeln!(
        s,
        "{:<30} {:>4} {:<8} {:>8} {:>7} {:>7} {:>10} {:>9}  positions per class",
        "problem", "objs", "who", "distinct", "mean d", "min d", "ms/layout", "total ms"
    );
    for p in &r.problems {
        let classes = |sp: &Spread| -> String {
            sp.positions_per_class
                .iter()
                .map(|(c, n)| format!("{c}:{n}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        match &p.sampler {
            Some(d) => {
                let _ = writeln!(
                    s,
                    "{:<30} {:>4} {:<8} {:>8} {:>7.1} {:>7.1} {:>10.2} {:>9.1}  {}{}",
                    p.name,
                    p.movable,
                    "sample",
                    d.spread.distinct,
                    d.spread.mean_distance,
                    d.spread.min_distance,
                    d.ms_per_layout,
                    d.total_ms,
                    classes(&d.spread),
                    if d.limit_struck { " (time limit)" } else { "" }
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "{:<30} {:>4} {:<8} {}",
                    p.name,
                    p.movable,
                    "sample",
                    p.error.as_deref().unwrap_or("-")
                );
            }
        }
        match &p.baseline {
            Some(Ok(b)) => {
                let n = b.spread.layouts.max(1) as f64;
                let _ = writeln!(
                    s,
                    "{:<30} {:>4} {:<8} {:>8} {:>7.1} {:>7.1} {:>10.2} {:>9.1}  {}{}",
                    "",
                    "",
                    "cp-sat",
                    b.spread.distinct,
                    b.spread.mean_distance,
                    b.spread.min_distance,
                    b.solve_ms / n,
                    b.process_ms,
                    classes(&b.spread),
                    if b.invalid > 0 {
                        format!(" ({} invalid)", b.invalid)
                    } else {
                        String::new()
                    }
                );
            }
            Some(Err(e)) => {
                let _ = writeln!(s, "{:<30} {:>4} {:<8} not run: {e}", "", "", "cp-sat");
            }
            None => {}
        }
    }
    s
}
