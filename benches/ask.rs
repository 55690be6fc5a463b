//! Question benchmark (SPEC §13): `cargo bench --bench ask [-- FILTER…]
//! [--compare] [--no-probes]`.
//!
//! For each bundled task (box-packing with `pilot.rcc`, shelf with
//! `intended.rcc` as the oracle) and several learning cutoffs (more rules
//! held at a larger cutoff): the time of every probe search on the first
//! held set (one per held rule: a probe, or the proof that none exists),
//! then a whole session answered by the oracle (accepted ⇔ every oracle
//! rule holds for every object), with the time until each question is
//! ready (the probe searches of the rules skipped on the way included).
//!
//! Then the first six generated realistic tasks of seed 0
//! (`rccpack::bench::tasks`, their 1× problem, rules learned with the
//! defaults). Their hidden style has no rule form, so the oracle is the
//! rules learned from the same demonstrations at a 10× stricter cutoff
//! ([`TASK_ORACLE_CUTOFF`]): the rules with the strongest evidence stand
//! for what the person meant, and a probe is accepted iff it keeps all of
//! them. Only their first [`TASK_QUESTIONS`] questions are timed; the
//! last line sums up every question of those tasks.
//!
//! A FILTER is `TASK` or `TASK@CUTOFF` (`box-packing`, `shelf@0.01`,
//! `task03`, `tasks` for all six). `--compare` runs every session twice,
//! alternating, with `AskOptions::reuse` off (every check a solve, the
//! implementation before issue 20's item 5) and on (the default), and says
//! whether both asked the same questions with the same answers.
//! `--no-probes` skips the probe-search columns.

use rccpack::ask::{find_probe, AskOptions, Asker, ProbeOptions, ProbeOutcome};
use rccpack::bench::tasks::{generate_task, TasksConfig};
use rccpack::eval::evaluate;
use rccpack::infer::{learn, LearnParams};
use rccpack::relations::Contact;
use rccpack::resemblance::Likeness;
use rccpack::rules::{parse_rules, RuleSet};
use rccpack::scene::{scenes_from_json, Scene};
use std::path::Path;
use std::time::{Duration, Instant};

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

fn keeps(scene: &Scene, oracle: &RuleSet) -> bool {
    evaluate(scene, oracle, Contact::Point)
        .rules
        .iter()
        .all(|r| r.satisfied == r.subjects)
}

/// `RCCPACK_DEBUG=1`: the library's `log::debug!` lines on standard error
/// (every check, proof and probe search of the session, timed).
struct DebugLog;

impl log::Log for DebugLog {
    fn enabled(&self, m: &log::Metadata) -> bool {
        m.target().starts_with("rccpack")
    }
    fn log(&self, r: &log::Record) {
        if self.enabled(r.metadata()) {
            eprintln!("{}", r.args());
        }
    }
    fn flush(&self) {}
}

/// Whether the series (task, cutoff) is selected by the arguments: none
/// (every series), or `TASK` / `TASK@CUTOFF` (e.g. `shelf@0.01`).
fn selected(task: &str, cutoff: f64) -> bool {
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    filters.is_empty()
        || filters.iter().any(|f| match f.split_once('@') {
            Some((t, c)) => t == task && c.parse::<f64>().ok() == Some(cutoff),
            None => f == task,
        })
}

/// The cutoff of the generated tasks' oracle (the session learns with the
/// default, 0.01).
const TASK_ORACLE_CUTOFF: f64 = 0.001;

/// How many generated tasks (of seed 0).
const TASKS: usize = 6;

/// The first this many questions of each generated task are timed (their
/// checks are much slower than the bundled tasks': a whole session of six
/// tasks would take hours).
const TASK_QUESTIONS: usize = 5;

/// A series: name, learning cutoffs, problem, demonstrations, oracle.
type Series = (String, Vec<f64>, Scene, Vec<Scene>, RuleSet);

/// One session's numbers.
struct Session {
    asked: usize,
    dropped: usize,
    ready: Vec<f64>,
    total: f64,
    /// (rule, accepted) per question.
    transcript: Vec<(String, bool)>,
}

fn session(
    problem: &Scene,
    demos: &[Scene],
    params: &LearnParams,
    reuse: bool,
    oracle: &RuleSet,
    max_questions: usize,
) -> Session {
    let started = Instant::now();
    let mut asker = Asker::new(
        problem.clone(),
        demos.to_vec(),
        None,
        Vec::new(),
        AskOptions {
            learn: *params,
            reuse,
            ..AskOptions::default()
        },
    )
    .unwrap();
    let mut ready = Vec::new();
    let mut transcript = Vec::new();
    loop {
        let t = Instant::now();
        let Some(q) = asker.next_question().unwrap() else {
            break;
        };
        ready.push(t.elapsed().as_secs_f64() * 1e3);
        log::debug!(
            target: "rccpack::bench",
            "bench: question {} about {} ready in {:.1} ms",
            ready.len(),
            q.rule,
            ready.last().copied().unwrap_or(0.0)
        );
        let ok = keeps(&q.probe.scene, oracle);
        transcript.push((q.rule.clone(), ok));
        asker.answer(&q, ok).unwrap();
        if ready.len() >= max_questions {
            break;
        }
    }
    let p = asker.progress();
    Session {
        asked: p.asked,
        dropped: p.dropped,
        ready,
        total: started.elapsed().as_secs_f64(),
        transcript,
    }
}

/// Probe searches of every held rule: (found, median ms, max ms).
fn probe_times(problem: &Scene, demos: &[Scene], held: &RuleSet) -> (usize, f64, f64) {
    let opts = ProbeOptions {
        like: Some(Likeness::new(demos)),
        ..ProbeOptions::default()
    };
    let mut probe_ms = Vec::new();
    let mut found = 0;
    for k in 0..held.rules.len() {
        let t = Instant::now();
        let o = find_probe(problem, held, k, &opts).unwrap();
        probe_ms.push(t.elapsed().as_secs_f64() * 1e3);
        found += usize::from(matches!(o, ProbeOutcome::Probe(_)));
    }
    (found, median(probe_ms.clone()), max(&probe_ms))
}

fn main() {
    static LOGGER: DebugLog = DebugLog;
    if std::env::var_os("RCCPACK_DEBUG").is_some() && log::set_logger(&LOGGER).is_ok() {
        log::set_max_level(log::LevelFilter::Debug);
    }
    let flag = |f: &str| std::env::args().any(|a| a == f);
    let compare = flag("--compare");
    let probes = !flag("--no-probes");
    println!(
        "{:<12} {:>7} {:>5} {:>6} {:>7} {:>9} {:>9} {:>6} {:>7} {:>9} {:>9} {:>8}",
        "task",
        "cutoff",
        "held",
        "reuse",
        "probes",
        "probe med",
        "probe max",
        "asked",
        "dropped",
        "ready med",
        "ready max",
        "total s"
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut series: Vec<Series> = Vec::new();
    for (task, oracle_file) in [("box-packing", "pilot.rcc"), ("shelf", "intended.rcc")] {
        let dir = root.join(task);
        let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
        series.push((
            task.to_string(),
            vec![0.001, 0.01, 0.1, 0.3],
            Scene::from_json(&read("problem.json")).unwrap(),
            scenes_from_json(&read("demos.json")).unwrap(),
            parse_rules(&read(oracle_file)).unwrap(),
        ));
    }
    let cfg = TasksConfig {
        sizes: vec![1.0],
        ..TasksConfig::full(0, Duration::from_secs(10))
    };
    for i in 0..TASKS {
        let name = format!("task{i:02}");
        if !selected(&name, LearnParams::default().cutoff) && !selected("tasks", 0.0) {
            continue;
        }
        let task = generate_task(&cfg, i).unwrap();
        let strict = LearnParams {
            cutoff: TASK_ORACLE_CUTOFF,
            ..LearnParams::default()
        };
        let oracle = learn(&task.demos, None, &strict).unwrap().rules();
        series.push((
            name,
            vec![LearnParams::default().cutoff],
            task.problems[0].scene.clone(),
            task.demos.clone(),
            oracle,
        ));
    }
    let mut all_tasks: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    for (task, cutoffs, problem, demos, oracle) in &series {
        for &cutoff in cutoffs {
            let in_tasks = task.starts_with("task") && selected("tasks", 0.0);
            if !(selected(task, cutoff) || in_tasks) {
                continue;
            }
            let params = LearnParams {
                cutoff,
                ..LearnParams::default()
            };
            let held = learn(demos, None, &params).unwrap().rules();
            let (found, probe_med, probe_max) = if probes {
                probe_times(problem, demos, &held)
            } else {
                (0, 0.0, 0.0)
            };
            let modes: &[bool] = if compare { &[false, true] } else { &[true] };
            let mut transcripts = Vec::new();
            for &reuse in modes {
                let cap = if task.starts_with("task") {
                    TASK_QUESTIONS
                } else {
                    100
                };
                let s = session(problem, demos, &params, reuse, oracle, cap);
                println!(
                    "{:<12} {:>7} {:>5} {:>6} {:>7} {:>9.1} {:>9.1} {:>6} {:>7} {:>9.1} {:>9.1} {:>8.1}",
                    task,
                    cutoff,
                    held.rules.len(),
                    if reuse { "on" } else { "off" },
                    found,
                    probe_med,
                    probe_max,
                    s.asked,
                    s.dropped,
                    median(s.ready.clone()),
                    max(&s.ready),
                    s.total
                );
                if task.starts_with("task") {
                    all_tasks[usize::from(reuse)].extend(s.ready.iter().copied());
                }
                transcripts.push(s.transcript);
            }
            if compare {
                println!(
                    "{:<12} {:>7} same questions and answers: {}",
                    task,
                    cutoff,
                    if transcripts[0] == transcripts[1] {
                        "yes"
                    } else {
                        "NO"
                    }
                );
            }
        }
    }
    for (reuse, ready) in all_tasks.iter().enumerate() {
        if !ready.is_empty() {
            println!(
                "generated tasks 0-{}, reuse {}: {} questions, ready median {:.1} ms, max {:.1} ms",
                TASKS - 1,
                if reuse == 1 { "on" } else { "off" },
                ready.len(),
                median(ready.clone()),
                max(ready)
            );
        }
    }
}
