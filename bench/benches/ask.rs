//! Question benchmark: `cargo bench --bench ask [-- FILTER…] [--compare]
//! [--no-probes] [--questions N] [--think S]`.
//!
//! For each bundled task (box-packing with `pilot.rcc`, shelf with
//! `intended.rcc` as the oracle) and several learning cutoffs (more rules
//! held at a larger cutoff): the time of every probe search on the first
//! held set (one per held rule: a probe, or the proof that none exists),
//! then a whole session answered by the oracle (accepted ⇔ every oracle
//! rule holds for every object), with the time until each question is
//! ready (the probe searches of the rules skipped on the way included),
//! and until the session says it has no more questions.
//!
//! Then the first ten generated realistic tasks of seed 0
//! (`rccpack_bench::tasks`, their 1× problem, rules learned with the
//! defaults). Their hidden style has no rule form, so the oracle is the
//! rules learned from the same demonstrations at a 10× stricter cutoff
//! ([`TASK_ORACLE_CUTOFF`]): the rules with the strongest evidence stand
//! for what the person meant, and a probe is accepted iff it keeps all of
//! them. At most `--questions N` questions (default 15) are asked per
//! session; the last line sums up every question of those tasks.
//!
//! After each session, two columns judge its result on the problem with
//! [`JUDGE_LAYOUTS`] sampled layouts each: *recall* counts the oracle rules
//! that no layout keeping the final held rules breaks, *spurious* the held
//! rules that some layout keeping the oracle breaks (a rule the person
//! never meant and the questions left standing).
//!
//! A FILTER is `TASK` or `TASK@CUTOFF` (`box-packing`, `shelf@0.01`,
//! `task03`, `tasks` for all ten). `--compare` runs every session twice,
//! alternating: `plain` (no demonstration edits, no question budget: every
//! check and probe search runs to its own limits) and `budget` (the
//! defaults). `--no-probes` skips the probe-search columns; `--no-groups`
//! asks about one rule per question (no group questions); `--transcript`
//! prints every question (rule, answer, evidence, group); `--think S` is a
//! person who answers S seconds after each question is shown while the
//! look-ahead computes the next question for both answers on two threads
//! (the ready columns are then the waits that person sees).

#[path = "../../tests/support/mod.rs"]
mod support;

use rccpack::ask::{find_probe, AskOptions, Asker, ProbeOptions, ProbeOutcome, QuestionBudget};
use rccpack::eval::evaluate;
use rccpack::infer::{learn, LearnParams};
use rccpack::relations::Contact;
use rccpack::resemblance::ResemblanceTarget;
use rccpack::rules::{parse_rules, RuleSet};
use rccpack::sample::{sample, Quality, SampleOptions};
use rccpack::scene::{scenes_from_json, Scene};
use rccpack_bench::tasks::{generate_task, TasksConfig};
use std::path::Path;
use std::time::{Duration, Instant};
use support::median;

/// CPU seconds of this process so far (every thread): what a question
/// costs on a machine shared with other work.
fn cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to write.
    unsafe {
        libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t);
    }
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
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
const TASKS: usize = 10;

/// Sampled layouts per judgement (recall, spurious).
const JUDGE_LAYOUTS: usize = 30;

/// A session stops after this long (a plain session on a hard task can run
/// for an hour).
const SESSION_CAP: Duration = Duration::from_secs(600);

/// A series: name, learning cutoffs, problem, demonstrations, oracle.
type Series = (String, Vec<f64>, Scene, Vec<Scene>, RuleSet);

/// One session's numbers.
struct Session {
    asked: usize,
    dropped: usize,
    edits: usize,
    deferred: usize,
    ready: Vec<f64>,
    /// CPU milliseconds per question.
    cpu: Vec<f64>,
    total: f64,
    capped: bool,
    /// (rule, accepted) per question.
    transcript: Vec<(String, bool)>,
    held: RuleSet,
}

/// `--think S`: a person who answers S seconds after a question is shown,
/// while the look-ahead computes the next question for both answers on two
/// threads (as `rccpack ask` does); a question is then ready after what is
/// left of its branch.
fn think_time() -> Option<Duration> {
    let args: Vec<String> = std::env::args().collect();
    let i = args.iter().position(|a| a == "--think")?;
    let s: f64 = args
        .get(i + 1)
        .and_then(|v| v.parse().ok())
        .expect("--think SECONDS");
    Some(Duration::from_secs_f64(s))
}

/// The options of a `plain` (`budget == false`) or `budget` session.
fn options(params: &LearnParams, budget: bool) -> AskOptions {
    let groups = !std::env::args().any(|a| a == "--no-groups");
    let opts = options_with(params, budget);
    AskOptions { groups, ..opts }
}

fn options_with(params: &LearnParams, budget: bool) -> AskOptions {
    if budget {
        AskOptions {
            learn: *params,
            ..AskOptions::default()
        }
    } else {
        AskOptions {
            learn: *params,
            edits: false,
            budget: QuestionBudget {
                nodes: u64::MAX,
                wall: None,
            },
            ..AskOptions::default()
        }
    }
}

/// Layouts of `problem` keeping every rule of `rules` (at most
/// [`JUDGE_LAYOUTS`]; none when it has none).
fn layouts(problem: &Scene, demos: &[Scene], rules: &RuleSet) -> Vec<Scene> {
    let mut hard = rules.clone();
    for r in &mut hard.rules {
        r.strength = rccpack::rules::Strength::Hard;
    }
    let opts = SampleOptions {
        quality: Quality::AllRules,
        like: demos.to_vec(),
        layout_node_limit: Some(20_000),
        stop: rccpack::stop::Stop::after(Duration::from_secs(20)),
        ..SampleOptions::default()
    };
    match sample(problem, &hard, &opts) {
        Ok(s) => s.take(JUDGE_LAYOUTS).filter_map(Result::ok).collect(),
        Err(_) => Vec::new(),
    }
}

/// (recall: oracle rules no layout keeping `held` breaks, of all;
/// spurious: held rules some layout keeping `oracle` breaks).
fn judge(problem: &Scene, demos: &[Scene], held: &RuleSet, oracle: &RuleSet) -> (usize, usize) {
    let broken_in = |scenes: &[Scene], rules: &RuleSet| -> Vec<bool> {
        let mut out = vec![false; rules.rules.len()];
        for s in scenes {
            for (i, r) in evaluate(s, rules, Contact::Point).rules.iter().enumerate() {
                out[i] |= r.satisfied < r.subjects;
            }
        }
        out
    };
    let kept = broken_in(&layouts(problem, demos, held), oracle)
        .iter()
        .filter(|b| !**b)
        .count();
    let spurious = broken_in(&layouts(problem, demos, oracle), held)
        .iter()
        .filter(|b| **b)
        .count();
    (kept, spurious)
}

fn session(
    problem: &Scene,
    demos: &[Scene],
    params: &LearnParams,
    budget: bool,
    oracle: &RuleSet,
    max_questions: usize,
) -> Session {
    let started = Instant::now();
    let mut asker = Asker::new(
        problem.clone(),
        demos.to_vec(),
        None,
        Vec::new(),
        options(params, budget),
    )
    .unwrap();
    let mut edits = 0;
    let mut capped = false;
    let mut ready = Vec::new();
    let mut cpu = Vec::new();
    let mut transcript = Vec::new();
    let think = think_time();
    // With `--think`: the question the look-ahead computed, with the wait
    // the person saw for it.
    let mut next: Option<(Option<rccpack::ask::Question>, f64)> = None;
    loop {
        let t = Instant::now();
        let c = cpu_seconds();
        let (q, waited) = next.take().unwrap_or_else(|| {
            let q = asker.next_question().unwrap();
            (q, t.elapsed().as_secs_f64() * 1e3)
        });
        let Some(q) = q else {
            // The wait for "no more questions" is a wait too.
            ready.push(waited);
            cpu.push((cpu_seconds() - c) * 1e3);
            break;
        };
        ready.push(waited);
        cpu.push((cpu_seconds() - c) * 1e3);
        log::debug!(
            target: "rccpack_bench",
            "bench: question {} about {} ready in {:.1} ms",
            ready.len(),
            q.rule,
            ready.last().copied().unwrap_or(0.0)
        );
        let ok = keeps(&q.probe.scene, oracle);
        if std::env::args().any(|a| a == "--transcript") {
            let post = |name: &str| {
                asker
                    .learned()
                    .statements
                    .iter()
                    .find(|s| s.name == name)
                    .and_then(|s| s.posterior)
                    .map_or(f64::NAN, |p| p.log10_posterior)
            };
            println!(
                "  q{:<3} {:<5} {:>8.2} {} {}  group {:?} also {:?}",
                ready.len(),
                if ok { "yes" } else { "no" },
                post(&q.rule),
                q.rule,
                q.statement,
                q.group_names(),
                q.also_broken
            );
        }
        edits += usize::from(q.probe.edit.is_some());
        transcript.push((q.rule.clone(), ok));
        if let Some(think) = think {
            // The person looks for `think`, then answers; the wait is what
            // is left of the branch of that answer.
            let ahead = asker.look_ahead(&q, 2);
            std::thread::sleep(think);
            let t = Instant::now();
            let (after, q) = ahead.answer(ok).unwrap();
            asker = after;
            next = Some((q, t.elapsed().as_secs_f64() * 1e3));
        } else {
            asker.answer(&q, ok).unwrap();
        }
        if ready.len() >= max_questions {
            break;
        }
        if started.elapsed() > SESSION_CAP {
            capped = true;
            break;
        }
    }
    let p = asker.progress();
    Session {
        asked: p.asked,
        dropped: p.dropped,
        edits,
        deferred: p.unknown,
        ready,
        cpu,
        total: started.elapsed().as_secs_f64(),
        capped,
        transcript,
        held: asker.learned().rules(),
    }
}

/// Probe searches of every held rule: (found, median ms, max ms).
fn probe_times(problem: &Scene, demos: &[Scene], held: &RuleSet) -> (usize, f64, f64) {
    let opts = ProbeOptions {
        like: Some(ResemblanceTarget::new(demos)),
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
    (found, median(&probe_ms), max(&probe_ms))
}

fn main() {
    static LOGGER: DebugLog = DebugLog;
    if std::env::var_os("RCCPACK_DEBUG").is_some() && log::set_logger(&LOGGER).is_ok() {
        log::set_max_level(log::LevelFilter::Debug);
    }
    let flag = |f: &str| std::env::args().any(|a| a == f);
    let compare = flag("--compare");
    let probes = !flag("--no-probes");
    let args: Vec<String> = std::env::args().collect();
    let questions: usize = args
        .iter()
        .position(|a| a == "--questions")
        .and_then(|i| args.get(i + 1))
        .map_or(15, |v| v.parse().expect("--questions N"));
    println!(
        "{:<12} {:>7} {:>5} {:>6} {:>7} {:>9} {:>9} {:>6} {:>7} {:>5} {:>5} {:>9} {:>9} {:>8} {:>8} {:>8} {:>7} {:>8}",
        "task",
        "cutoff",
        "held",
        "mode",
        "probes",
        "probe med",
        "probe max",
        "asked",
        "dropped",
        "edits",
        "defer",
        "ready med",
        "ready max",
        "cpu med",
        "cpu max",
        "total s",
        "recall",
        "spurious"
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
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
    let mut all_asked = [0usize; 2];
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
            for &budget in modes {
                let cap = if task.starts_with("task") {
                    questions
                } else {
                    100
                };
                let s = session(problem, demos, &params, budget, oracle, cap);
                let (recall, spurious) = judge(problem, demos, &s.held, oracle);
                println!(
                    "{:<12} {:>7} {:>5} {:>6} {:>7} {:>9.1} {:>9.1} {:>6} {:>7} {:>5} {:>5} {:>9.1} {:>9.1} {:>8.1} {:>8.1} {:>8.1} {:>7} {:>8}",
                    task,
                    cutoff,
                    held.rules.len(),
                    if budget { "budget" } else { "plain" },
                    found,
                    probe_med,
                    probe_max,
                    format!("{}{}", s.asked, if s.capped { "+" } else { "" }),
                    s.dropped,
                    s.edits,
                    s.deferred,
                    median(&s.ready),
                    max(&s.ready),
                    median(&s.cpu),
                    max(&s.cpu),
                    s.total,
                    format!("{recall}/{}", oracle.rules.len()),
                    spurious
                );
                if task.starts_with("task") {
                    all_tasks[usize::from(budget)].extend(s.ready.iter().copied());
                    all_asked[usize::from(budget)] += s.asked;
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
                        "no"
                    }
                );
            }
        }
    }
    for (budget, ready) in all_tasks.iter().enumerate() {
        if !ready.is_empty() {
            println!(
                "generated tasks 0-{}, {}: {} questions, ready median {:.1} ms, max {:.1} ms (the ends of the sessions included)",
                TASKS - 1,
                if budget == 1 { "budget" } else { "plain" },
                all_asked[budget],
                median(ready),
                max(ready)
            );
        }
    }
}
