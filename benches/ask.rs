//! Question benchmark (SPEC §13): `cargo bench --bench ask`.
//!
//! For each bundled task (box-packing with `pilot.rcc`, shelf with
//! `intended.rcc` as the oracle) and several learning cutoffs (more rules
//! held at a larger cutoff): the time of every probe search on the first
//! held set (one per held rule: a probe, or the proof that none exists),
//! then a whole session answered by the oracle (accepted ⇔ every oracle
//! rule holds for every object), with the time until each question is
//! ready (the probe searches of the rules skipped on the way included).

use rccpack::ask::{find_probe, AskOptions, Asker, ProbeOptions, ProbeOutcome};
use rccpack::eval::evaluate;
use rccpack::infer::{learn, LearnParams};
use rccpack::relations::Contact;
use rccpack::resemblance::Likeness;
use rccpack::rules::{parse_rules, RuleSet};
use rccpack::scene::{scenes_from_json, Scene};
use std::path::Path;
use std::time::Instant;

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

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    println!(
        "{:<12} {:>7} {:>5} {:>7} {:>9} {:>9} {:>6} {:>7} {:>9} {:>9} {:>8}",
        "task",
        "cutoff",
        "held",
        "probes",
        "probe med",
        "probe max",
        "asked",
        "dropped",
        "ready med",
        "ready max",
        "total s"
    );
    for (task, oracle_file) in [("box-packing", "pilot.rcc"), ("shelf", "intended.rcc")] {
        let dir = root.join(task);
        let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
        let demos = scenes_from_json(&read("demos.json")).unwrap();
        let problem = Scene::from_json(&read("problem.json")).unwrap();
        let oracle = parse_rules(&read(oracle_file)).unwrap();
        for cutoff in [0.001, 0.01, 0.1, 0.3] {
            let params = LearnParams {
                cutoff,
                ..LearnParams::default()
            };
            let held = learn(&demos, None, &params).unwrap().rules();
            let opts = ProbeOptions {
                like: Some(Likeness::new(&demos)),
                ..ProbeOptions::default()
            };
            let mut probe_ms = Vec::new();
            let mut found = 0;
            for k in 0..held.rules.len() {
                let t = Instant::now();
                let o = find_probe(&problem, &held, k, &opts).unwrap();
                probe_ms.push(t.elapsed().as_secs_f64() * 1e3);
                found += usize::from(matches!(o, ProbeOutcome::Probe(_)));
            }
            let started = Instant::now();
            let mut asker = Asker::new(
                problem.clone(),
                demos.clone(),
                None,
                Vec::new(),
                AskOptions {
                    learn: params,
                    ..AskOptions::default()
                },
            )
            .unwrap();
            let mut ready = Vec::new();
            loop {
                let t = Instant::now();
                let Some(q) = asker.next_question().unwrap() else {
                    break;
                };
                ready.push(t.elapsed().as_secs_f64() * 1e3);
                let ok = keeps(&q.probe.scene, &oracle);
                asker.answer(&q, ok).unwrap();
                if ready.len() >= 100 {
                    break;
                }
            }
            let p = asker.progress();
            println!(
                "{:<12} {:>7} {:>5} {:>7} {:>9.1} {:>9.1} {:>6} {:>7} {:>9.1} {:>9.1} {:>8.1}",
                task,
                cutoff,
                held.rules.len(),
                found,
                median(probe_ms.clone()),
                max(&probe_ms),
                p.asked,
                p.dropped,
                median(ready.clone()),
                max(&ready),
                started.elapsed().as_secs_f64()
            );
        }
    }
}
