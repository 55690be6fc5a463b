//! Synthesis strategies benchmark: `cargo bench --bench synth [-- study|scale]
//! [--quick] [--slow] [--limit SECONDS]`.
//!
//! Both search strategies (`UpperBoundFirst`, `ImproveFromFirst`), each with
//! symmetry breaking and redundant constraints on, with symmetry breaking
//! only, and with neither, in CPU time of the solving thread:
//!
//! - `study`: 250 thesis-like problems (the box, 2–6 blocks, 1–5 rules per
//!   class drawn from the pilot rules and the templates), 5 s each; the
//!   median and largest time and how many were not proven optimal.
//!   `--slow` prints every problem over 100 ms with its rules.
//! - `scale`: the pilot rules on 24 and 48 blocks in a larger box, three
//!   seeds each under `--limit` seconds (default 20); the median time and
//!   per seed the status, score and time to the first solution.
//!
//! `--quick` runs only the default options (and the default strategy for
//! `scale`). No argument runs both series.

#[path = "../tests/support/mod.rs"]
mod support;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::rules::{Formula, Rule, RuleSet, Strength};
use rccpack::scene::Scene;
use rccpack::synth::{synthesize, Status, Strategy, SynthOptions, SynthResult};
use std::time::Duration;
use support::box_packing::{box_problem, corner, obj, pilot_rules};
use support::formulas::{and, atom, not, or};
use support::median;

/// The three option sets compared: (symmetry breaking, redundant).
const OPTIONS: [(bool, bool); 3] = [(true, true), (true, false), (false, false)];

/// CPU time of this thread in ms (robust against a loaded machine).
fn cpu_ms() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid, writable timespec.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 * 1e3 + t.tv_nsec as f64 / 1e6
}

fn solve(problem: &Scene, rules: &RuleSet, opts: &SynthOptions) -> SynthResult {
    synthesize(problem, rules, opts).expect("valid problem")
}

/// The command line after `cargo bench`'s own `--bench`.
struct Args {
    series: Vec<String>,
    quick: bool,
    slow: bool,
    limit: u64,
}

fn args() -> Args {
    let all: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    let limit = all.iter().position(|a| a == "--limit").map_or(20, |i| {
        all.get(i + 1)
            .and_then(|v| v.parse().ok())
            .expect("--limit SECONDS")
    });
    Args {
        series: all
            .iter()
            .filter(|a| !a.starts_with("--") && a.parse::<u64>().is_err())
            .cloned()
            .collect(),
        quick: all.iter().any(|a| a == "--quick"),
        slow: all.iter().any(|a| a == "--slow"),
        limit,
    }
}

fn main() {
    let a = args();
    let run = |s: &str| a.series.is_empty() || a.series.iter().any(|x| x == s);
    if run("study") {
        study(&a);
    }
    if run("scale") {
        scale(&a);
    }
}

/// Every template statement of subject `a` against `classes` and `*`.
fn templates(a: &str, classes: &[&str]) -> Vec<Formula> {
    let mut out = Vec::new();
    for b in classes.iter().copied().chain(["*"]) {
        for d in ["N", "S", "E", "W"] {
            out.push(atom(&format!("DR_{d}"), a, b));
            out.push(atom(&format!("EC_{d}"), a, b));
            out.push(not(atom(&format!("DR_{d}"), a, b)));
        }
        out.push(or(["EC_N", "EC_S", "EC_E", "EC_W"]
            .iter()
            .map(|r| atom(r, a, b))
            .collect()));
        out.push(and(["DR_N", "DR_S", "DR_E", "DR_W"]
            .iter()
            .map(|r| not(atom(r, a, b)))
            .collect()));
    }
    out.push(corner(a));
    out
}

/// A thesis-study-like problem: the box, 2–6 objects, 1–5 rules per class
/// drawn from the pilot rules and the templates.
fn study_problem(seed: u64) -> (Scene, RuleSet) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = rng.random_range(2..=6);
    let mut p = box_problem(0);
    for i in 0..n {
        let c = ["R", "G", "B"][rng.random_range(0..3)];
        p.objects.push(obj(
            &format!("{}{i}", c.to_lowercase()),
            c,
            20,
            20,
            None,
            false,
        ));
    }
    let pilot = pilot_rules();
    let mut rules = Vec::new();
    for c in ["R", "G", "B"] {
        let mut pool: Vec<Formula> = pilot
            .rules
            .iter()
            .filter(|r| r.subject() == c)
            .map(|r| r.formula.clone())
            .collect();
        pool.extend(templates(c, &["R", "G", "B", "W"]));
        for j in 0..rng.random_range(1..=5) {
            let f = if rng.random_range(0..2) == 0 {
                pool[rng.random_range(0..3)].clone()
            } else {
                pool[rng.random_range(0..pool.len())].clone()
            };
            let pv = 10f64.powf(-rng.random_range(2.0..12.0));
            rules.push(Rule::new(format!("{c}{j}"), f).with_strength(Strength::P(pv)));
        }
    }
    (p, RuleSet::new(rules))
}

/// The box grown to `inner`×`inner` inside, `per_class` blocks of each class.
fn scale_problem(per_class: usize, inner: i64) -> Scene {
    let mut p = box_problem(per_class);
    let (x0, y0) = (100, 100);
    p.space.width = inner + 2 * x0 + 20;
    p.space.height = inner + 2 * y0 + 20;
    p.objects[0] = obj("w_south", "W", inner + 20, 10, Some((x0, y0)), true);
    p.objects[1] = obj(
        "w_north",
        "W",
        inner + 20,
        10,
        Some((x0, y0 + 10 + inner)),
        true,
    );
    p.objects[2] = obj("w_west", "W", 10, inner, Some((x0, y0 + 10)), true);
    p.objects[3] = obj(
        "w_east",
        "W",
        10,
        inner,
        Some((x0 + 10 + inner, y0 + 10)),
        true,
    );
    p
}

/// The study series: 250 thesis-like problems per strategy and options.
fn study(a: &Args) {
    let quick = a.quick;
    for strategy in [Strategy::UpperBoundFirst, Strategy::ImproveFromFirst] {
        for (sym, red) in OPTIONS {
            if quick && !(sym && red) {
                continue;
            }
            let mut times = Vec::new();
            let mut not_opt = 0;
            for seed in 0..250 {
                let (p, rules) = study_problem(seed);
                let opts = SynthOptions {
                    strategy,
                    symmetry_breaking: sym,
                    redundant: red,
                    stop: rccpack::stop::Stop::after(Duration::from_secs(5)),
                    ..Default::default()
                };
                let c0 = cpu_ms();
                let r = solve(&p, &rules, &opts);
                if r.status != Status::Optimal {
                    not_opt += 1;
                }
                let dt = cpu_ms() - c0;
                if dt > 100.0 && a.slow {
                    println!(
                        "  slow seed {seed}: {dt:.0} ms, {} objects, nodes {}, conflicts {}, score {:?}, first {:?} ms",
                        p.objects.len() - 4,
                        r.stats.nodes,
                        r.stats.conflicts,
                        r.evaluation.as_ref().map(|e| e.score),
                        r.stats.time_to_first_ms
                    );
                    for rule in &rules.rules {
                        println!("    {}", rccpack::rules::print_rule(rule));
                    }
                }
                times.push(dt);
            }
            let max = times.iter().cloned().fold(0.0, f64::max);
            println!(
                "study {strategy:?} sym={sym} red={red}: CPU median {:.2} ms, max {:.1} ms, not optimal {not_opt}",
                median(&times),
                max
            );
        }
    }
}

/// The scale series: the pilot rules on 24 and 48 blocks.
fn scale(a: &Args) {
    let (limit, quick) = (a.limit, a.quick);
    for (per_class, inner) in [(8usize, 200i64), (16, 300)] {
        for strategy in [Strategy::UpperBoundFirst, Strategy::ImproveFromFirst] {
            if quick && strategy != Strategy::UpperBoundFirst {
                continue;
            }
            for (sym, red) in OPTIONS {
                if quick && !(sym && red) {
                    continue;
                }
                let p = scale_problem(per_class, inner);
                let mut times = Vec::new();
                let mut scores = Vec::new();
                for seed in 0..3 {
                    let opts = SynthOptions {
                        strategy,
                        seed,
                        symmetry_breaking: sym,
                        redundant: red,
                        stop: rccpack::stop::Stop::after(Duration::from_secs(limit)),
                        ..Default::default()
                    };
                    let c0 = cpu_ms();
                    let r = solve(&p, &pilot_rules(), &opts);
                    times.push(cpu_ms() - c0);
                    scores.push(format!(
                        "{:?}/{:.4}/first {:.0}ms",
                        r.status,
                        r.evaluation.map(|e| e.score).unwrap_or(f64::NAN),
                        r.stats.time_to_first_ms.unwrap_or(f64::NAN)
                    ));
                }
                println!(
                    "scale n={} {strategy:?} sym={sym} red={red}: CPU median {:.1} ms {:?}",
                    per_class * 3,
                    median(&times),
                    scores
                );
            }
        }
    }
}
