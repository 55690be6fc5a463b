//! The fewest questions a session could ask, for a clairvoyant asker:
//! `cargo run --release -p rccpack-bench --example clairvoyant [-- tasks]`.
//!
//! `tasks`: for the first ten generated tasks of seed 0 (as in `cargo bench
//! --bench ask`: the rules learned with the defaults held, those learned at
//! a 10× stricter cutoff meant), the meant held rules a layout of the
//! problem can break while keeping every other meant rule. Each needs a
//! "not acceptable" of its own (else nothing tells it from a habit), so
//! their count is a lower bound on the questions of any session asking
//! with layouts of the problem; one more when some habit can break.
//!
//! Without an argument, on the bundled box:
//! A meant rule needs a "not acceptable" of its own (a rejected group says
//! only that one of its rules is meant), so the pilot's meant rules that
//! are held and not implied cost one question each. The habits cost at
//! least as many questions as layouts are needed to break them all while
//! keeping every pilot rule: this example finds such layouts greedily
//! (the pilot rules hard, breaking each held rule soft), adds each as a
//! demonstration (as an accepted probe would be) and learns again, until
//! no held rule can break.
use rccpack::ask::negation;
use rccpack::eval::evaluate;
use rccpack::infer::{learn, LearnParams};
use rccpack::relations::Contact;
use rccpack::rules::{parse_rules, Rule, RuleSet, Strength};
use rccpack::scene::{scenes_from_json, Scene};
use rccpack::stop::Stop;
use rccpack::synth::{synthesize, Status, SynthOptions};
use rccpack_bench::tasks::{generate_task, TasksConfig};
use std::time::Duration;

/// `r` kept hard.
fn hard(r: &Rule) -> Rule {
    Rule {
        strength: Strength::Hard,
        ..r.clone()
    }
}

/// A layout of `problem` keeping every rule of `keep` and breaking as many
/// of `soft` as it can (each weighing 1), within `limit`; with the solve's
/// status.
fn breaking_layout<'a>(
    problem: &Scene,
    keep: impl IntoIterator<Item = &'a Rule>,
    soft: impl IntoIterator<Item = &'a Rule>,
    limit: Stop,
) -> (Status, Option<Scene>) {
    let mut rules: Vec<Rule> = keep.into_iter().map(hard).collect();
    for h in soft {
        if let Some(mut n) = negation(h) {
            n.strength = Strength::Weight(1.0);
            rules.push(n);
        }
    }
    let opts = SynthOptions {
        stop: limit,
        ..SynthOptions::default()
    };
    let r = synthesize(problem, &RuleSet::new(rules), &opts).unwrap();
    (r.status, r.scene)
}

/// The rules of `held` that `scene` breaks.
fn broken(scene: &Scene, held: &RuleSet) -> Vec<String> {
    evaluate(scene, held, Contact::Point)
        .rules
        .iter()
        .filter(|x| x.satisfied != x.subjects)
        .map(|x| x.name.clone())
        .collect()
}

fn box_packing() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/box-packing");
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
    let problem = Scene::from_json(&read("problem.json")).unwrap();
    let mut demos = scenes_from_json(&read("demos.json")).unwrap();
    let oracle = parse_rules(&read("pilot.rcc")).unwrap();
    let params = LearnParams {
        cutoff: 0.01,
        ..LearnParams::default()
    };
    for round in 0..20 {
        let held = learn(&demos, None, &params).unwrap().rules();
        let limit = Stop::after(Duration::from_secs(20));
        let (status, scene) = breaking_layout(&problem, &oracle.rules, &held.rules, limit);
        let scene = scene.unwrap();
        let broken = broken(&scene, &held);
        println!(
            "round {round}: held {} status {status:?} broken {}: {broken:?}",
            held.rules.len(),
            broken.len(),
        );
        if broken.is_empty() {
            println!(
                "{round} layouts keeping the pilot's rules break every held rule that can break; {} rules held after",
                held.rules.len()
            );
            break;
        }
        demos.push(scene);
    }
}

/// One generated task's lower bound.
struct Bound {
    held: usize,
    meant: usize,
    /// Meant rules a layout breaks while every other meant rule holds.
    alone: usize,
    /// Meant rules the limit did not decide.
    undecided: usize,
    /// Some habit breaks while every meant rule holds.
    habit: bool,
}

/// The lower bound of generated task `index`.
fn task_bound(index: usize) -> Bound {
    let cfg = TasksConfig {
        sizes: vec![1.0],
        ..TasksConfig::full(0, Duration::from_secs(10))
    };
    let task = generate_task(&cfg, index).unwrap();
    let problem = &task.problems[0].scene;
    let held = learn(&task.demos, None, &LearnParams::default())
        .unwrap()
        .rules();
    let strict = LearnParams {
        cutoff: 0.001,
        ..LearnParams::default()
    };
    let oracle = learn(&task.demos, None, &strict).unwrap().rules();
    let is_held = |r: &&Rule| held.rules.iter().any(|h| h.name == r.name);
    let meant: Vec<&Rule> = oracle.rules.iter().filter(is_held).collect();
    let limit = || Stop::after(Duration::from_secs(10)).with_nodes(200_000);
    let (mut alone, mut undecided) = (0, 0);
    for r in &meant {
        let Some(neg) = negation(r) else { continue };
        let mut rules: Vec<Rule> = meant
            .iter()
            .filter(|o| o.name != r.name)
            .map(|o| hard(o))
            .collect();
        rules.push(hard(&neg));
        let opts = SynthOptions {
            stop: limit(),
            ..SynthOptions::default()
        };
        match synthesize(problem, &RuleSet::new(rules), &opts)
            .unwrap()
            .status
        {
            Status::Optimal | Status::Feasible => alone += 1,
            Status::Infeasible => {}
            _ => undecided += 1,
        }
    }
    let habits = held
        .rules
        .iter()
        .filter(|h| !meant.iter().any(|m| m.name == h.name));
    let (_, scene) = breaking_layout(problem, meant.iter().copied(), habits, limit());
    Bound {
        held: held.rules.len(),
        meant: meant.len(),
        alone,
        undecided,
        habit: scene.is_some_and(|s| !broken(&s, &held).is_empty()),
    }
}

fn main() {
    if std::env::args().any(|a| a == "tasks") {
        println!("task    held  meant  need a question alone  undecided  a habit breaks  bound");
        let mut bounds = Vec::new();
        for i in 0..10 {
            let b = task_bound(i);
            let bound = b.alone + usize::from(b.habit);
            bounds.push(bound);
            println!(
                "task{i:02} {:>5} {:>6} {:>22} {:>10} {:>15} {bound:>6}",
                b.held,
                b.meant,
                b.alone,
                b.undecided,
                if b.habit { "yes" } else { "no" }
            );
        }
        bounds.sort_unstable();
        println!(
            "bound: {} questions in all, median {}",
            bounds.iter().sum::<usize>(),
            (bounds[4] + bounds[5]) as f64 / 2.0
        );
    } else {
        box_packing();
    }
}
