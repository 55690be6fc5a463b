//! Packing benchmark of objects that turn: `cargo bench --bench turns`.
//!
//! The sixteen tiny problems of `tests/fixtures/turns/packings.json`,
//! found by exhaustive search on the grid (`tests/support/turn_packing.rs`,
//! no solver): blocks that fit the box only when some stand on end. For
//! each, the engine proves that they do not fit flat (no block turnable)
//! and packs them with turns (optimal, verified); the table gives both
//! times (CPU time of the solving thread), the nodes, and how many
//! orientation choices the turned solve tried.
//!
//! `cargo bench --bench turns -- tasks [SECONDS]` then solves the first
//! four realistic tasks of `rccpack-bench tasks` (seed 0, sizes 1× and
//! 1.5×, score only, the demonstrations as warm start) as generated and
//! with every oblong block `turnable`, under the same time limit per
//! problem (default 10 s; shared by the orientation choices), every layout
//! verified: the statuses, scores and wall times side by side.

#[path = "../../tests/support/mod.rs"]
mod support;

use rccpack::relations::Contact;
use rccpack::rules::RuleSet;
use rccpack::scene::Scene;
use rccpack::synth::{synthesize, verify_solution, Status, SynthOptions, SynthResult};
use support::turn_packing::{flat, packings};

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

/// The engine tuning of `RCCPACK_*` (`RCCPACK_TURNS=enumerate` compares
/// the enumeration of orientations); a value that is not a choice ends
/// the run.
fn tuning() -> rccpack::synth::Tuning {
    rccpack::synth::Tuning::from_env().unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1)
    })
}

/// The best of three timed solves (the result of the last).
fn timed(problem: &Scene, rules: &RuleSet) -> (SynthResult, f64) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..3 {
        let t0 = cpu_ms();
        let opts = SynthOptions {
            tuning: tuning(),
            ..SynthOptions::default()
        };
        let r = synthesize(problem, rules, &opts).expect("valid problem");
        best = best.min(cpu_ms() - t0);
        last = Some(r);
    }
    (last.expect("solved"), best)
}

/// `Π (n + 1)` over the groups of turnable blocks of one class and size.
fn choices(problem: &Scene) -> u64 {
    let mut groups: Vec<((String, i64, i64), u64)> = Vec::new();
    for o in problem
        .objects
        .iter()
        .filter(|o| o.turnable && o.is_oblong())
    {
        let key = (o.class.clone(), o.width, o.height);
        match groups.iter_mut().find(|g| g.0 == key) {
            Some(g) => g.1 += 1,
            None => groups.push((key, 1)),
        }
    }
    groups.iter().map(|g| g.1 + 1).product()
}

/// The realistic tasks, flat and turnable.
fn tasks(seconds: u64) {
    use rccpack_bench::tasks::{generate_task, solve_options, TasksConfig};
    let mut cfg = TasksConfig::quick(0, std::time::Duration::from_secs(seconds));
    cfg.tasks = 4;
    cfg.example_counts = Vec::new();
    // `RCCPACK_TURNS=enumerate` compares the enumeration of orientations.
    cfg.tuning = tuning();
    println!("| problem | objects | turnable | choices | flat: status | score | s | turnable: status | score | s | turned |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for index in 0..cfg.tasks {
        let task = generate_task(&cfg, index).expect("a task");
        let opts = solve_options(&cfg, &task.demos, false);
        for p in &task.problems {
            let mut turnable = p.scene.clone();
            for o in turnable
                .objects
                .iter_mut()
                .filter(|o| !o.fixed && o.is_oblong())
            {
                o.turnable = true;
            }
            let n_turnable = turnable.objects.iter().filter(|o| o.turnable).count();
            let run = |scene: &Scene| {
                let t0 = std::time::Instant::now();
                let r = synthesize(scene, &task.rules, &opts);
                let secs = t0.elapsed().as_secs_f64();
                match r {
                    Ok(r) => {
                        if let Some(sol) = &r.scene {
                            verify_solution(scene, sol, &task.rules, Contact::Point)
                                .expect("verified");
                        }
                        let turned = r
                            .scene
                            .as_ref()
                            .map_or(0, |s| s.objects.iter().filter(|o| o.turned).count());
                        (
                            format!("{:?}", r.status).to_lowercase(),
                            r.evaluation
                                .map_or("-".into(), |e| format!("{:.3}", e.score)),
                            format!("{secs:.2}"),
                            turned,
                        )
                    }
                    Err(e) => (format!("refused: {e}"), "-".into(), "-".into(), 0),
                }
            };
            let (fs, fsc, ft, _) = run(&p.scene);
            let (ts, tsc, tt, turned) = run(&turnable);
            println!(
                "| {} | {} | {n_turnable} | {} | {fs} | {fsc} | {ft} | {ts} | {tsc} | {tt} | {turned} |",
                p.name,
                p.movable,
                choices(&turnable),
            );
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    if args.first().map(String::as_str) == Some("tasks") {
        let seconds = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10);
        tasks(seconds);
        return;
    }
    let none = RuleSet::default();
    println!("| # | box | blocks | flat: status | flat ms | turned: status | turned ms | nodes | choices | turned blocks |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let (mut flat_total, mut turned_total) = (0.0, 0.0);
    for (i, problem) in packings(16).iter().enumerate() {
        let (f, f_ms) = timed(&flat(problem), &none);
        let (t, t_ms) = timed(problem, &none);
        assert_eq!(f.status, Status::Infeasible, "packing {i}: flat");
        assert_eq!(t.status, Status::Optimal, "packing {i}: turned");
        let sol = t.scene.as_ref().expect("a layout");
        verify_solution(problem, sol, &none, Contact::Point).expect("verified");
        let blocks: Vec<String> = {
            let mut sizes: Vec<(i64, i64, usize)> = Vec::new();
            for o in &problem.objects {
                match sizes.iter_mut().find(|s| (s.0, s.1) == (o.width, o.height)) {
                    Some(s) => s.2 += 1,
                    None => sizes.push((o.width, o.height, 1)),
                }
            }
            sizes
                .iter()
                .map(|(w, h, n)| format!("{n}×{w}×{h}"))
                .collect()
        };
        println!(
            "| {i} | {}×{} | {} | infeasible | {f_ms:.2} | optimal | {t_ms:.2} | {} | {} | {} |",
            problem.space.width,
            problem.space.height,
            blocks.join(" "),
            t.stats.nodes,
            choices(problem),
            sol.objects.iter().filter(|o| o.turned).count()
        );
        flat_total += f_ms;
        turned_total += t_ms;
    }
    println!(
        "\n16 problems: every flat one proven infeasible in {flat_total:.1} ms in all, every turned one packed and proven optimal in {turned_total:.1} ms in all (CPU, best of 3)."
    );
}
