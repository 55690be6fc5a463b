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
use rccpack::rules::{parse_rules, RuleSet, Strength};
use rccpack::scene::{scenes_from_json, Scene};
use rccpack::stop::Stop;
use rccpack::synth::{synthesize, SynthOptions};
use std::time::Duration;

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
        let mut rules: Vec<_> = oracle
            .rules
            .iter()
            .cloned()
            .map(|mut r| {
                r.strength = Strength::Hard;
                r
            })
            .collect();
        for h in &held.rules {
            if let Some(mut n) = negation(h) {
                n.strength = Strength::Weight(1.0);
                rules.push(n);
            }
        }
        let opts = SynthOptions {
            stop: Stop::after(Duration::from_secs(20)),
            ..SynthOptions::default()
        };
        let r = synthesize(&problem, &RuleSet::new(rules), &opts).unwrap();
        let scene = r.scene.unwrap();
        let ev = evaluate(&scene, &held, Contact::Point);
        let broken: Vec<_> = ev
            .rules
            .iter()
            .filter(|x| x.satisfied != x.subjects)
            .map(|x| x.name.clone())
            .collect();
        println!(
            "round {round}: held {} status {:?} broken {}: {:?}",
            held.rules.len(),
            r.status,
            broken.len(),
            broken
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

/// The lower bound of one generated task: (meant held rules, those that
/// need a question of their own, undecided in the limit, whether a habit
/// can break).
fn task_bound(index: usize) -> (usize, usize, usize, bool) {
    use rccpack_bench::tasks::{generate_task, TasksConfig};
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
    let hard = |r: &rccpack::rules::Rule| {
        let mut r = r.clone();
        r.strength = Strength::Hard;
        r
    };
    let breaks = |rules: Vec<rccpack::rules::Rule>| -> Option<bool> {
        let opts = SynthOptions {
            stop: Stop::after(Duration::from_secs(10)).with_nodes(200_000),
            ..SynthOptions::default()
        };
        let r = synthesize(problem, &RuleSet::new(rules), &opts).unwrap();
        match r.status {
            rccpack::synth::Status::Optimal | rccpack::synth::Status::Feasible => Some(true),
            rccpack::synth::Status::Infeasible => Some(false),
            _ => None,
        }
    };
    let meant: Vec<&rccpack::rules::Rule> = oracle
        .rules
        .iter()
        .filter(|r| held.rules.iter().any(|h| h.name == r.name))
        .collect();
    let (mut alone, mut unknown) = (0, 0);
    for r in &meant {
        let Some(neg) = negation(r) else { continue };
        let mut rules: Vec<_> = meant
            .iter()
            .filter(|o| o.name != r.name)
            .map(|o| hard(o))
            .collect();
        rules.push(hard(&neg));
        match breaks(rules) {
            Some(true) => alone += 1,
            Some(false) => {}
            None => unknown += 1,
        }
    }
    // Some habit can break while every meant rule holds.
    let mut rules: Vec<_> = meant.iter().map(|o| hard(o)).collect();
    for h in held
        .rules
        .iter()
        .filter(|h| !meant.iter().any(|m| m.name == h.name))
    {
        if let Some(mut n) = negation(h) {
            n.strength = Strength::Weight(1.0);
            rules.push(n);
        }
    }
    let habit = rules.len() > meant.len() && {
        let opts = SynthOptions {
            stop: Stop::after(Duration::from_secs(10)).with_nodes(200_000),
            ..SynthOptions::default()
        };
        let r = synthesize(problem, &RuleSet::new(rules), &opts).unwrap();
        r.scene.is_some_and(|s| {
            evaluate(&s, &held, Contact::Point)
                .rules
                .iter()
                .any(|x| x.satisfied != x.subjects)
        })
    };
    (meant.len(), alone, unknown, habit)
}

fn main() {
    if std::env::args().any(|a| a == "tasks") {
        println!("task    held  meant  need a question alone  undecided  a habit breaks  bound");
        let mut bounds = Vec::new();
        for i in 0..10 {
            let held = {
                use rccpack_bench::tasks::{generate_task, TasksConfig};
                let cfg = TasksConfig {
                    sizes: vec![1.0],
                    ..TasksConfig::full(0, Duration::from_secs(10))
                };
                let task = generate_task(&cfg, i).unwrap();
                learn(&task.demos, None, &LearnParams::default())
                    .unwrap()
                    .rules()
                    .rules
                    .len()
            };
            let (meant, alone, unknown, habit) = task_bound(i);
            let bound = alone + usize::from(habit);
            bounds.push(bound);
            println!(
                "task{i:02} {held:>5} {meant:>6} {alone:>22} {unknown:>10} {:>15} {bound:>6}",
                if habit { "yes" } else { "no" }
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
