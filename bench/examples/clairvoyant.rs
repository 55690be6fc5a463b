//! The fewest questions a session on the bundled box could ask, for a
//! clairvoyant asker: `cargo run --release -p rccpack-bench --example
//! clairvoyant`.
//!
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

fn main() {
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
