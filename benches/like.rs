//! Resemblance benchmark (docs/guide.md#layouts-like-the-demonstrations): `cargo bench --bench like`.
//!
//! Problems: for each bundled task (box-packing, shelf), its `problem.json`
//! and, per demonstration, that demonstration with its movable objects
//! unplaced (18 problems). Rules: those learned from all the task's
//! demonstrations (default templates, 1000 samples). Like-scenes: the
//! task's demonstrations, leaving out the one the problem came from (so the
//! answer is not simply "put everything back"). Per problem the median of 5
//! solves, score-only and with `--like`, both to proven optimality; the
//! report gives the medians over problems and the ratio.

#[path = "../tests/support/mod.rs"]
mod support;

use rccpack::infer::{learn, LearnParams};
use rccpack::resemblance::ResemblanceTarget;
use rccpack::scene::{scenes_from_json, Scene};
use rccpack::synth::{synthesize, Status, SynthOptions};
use std::path::Path;
use std::time::{Duration, Instant};
use support::median;

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut rows = Vec::new();
    for task in ["box-packing", "shelf"] {
        let dir = root.join(task);
        let demos =
            scenes_from_json(&std::fs::read_to_string(dir.join("demos.json")).unwrap()).unwrap();
        let problem =
            Scene::from_json(&std::fs::read_to_string(dir.join("problem.json")).unwrap()).unwrap();
        let rules = learn(&demos, None, &LearnParams::default())
            .unwrap()
            .rules();
        let mut problems = vec![(format!("{task}/problem"), problem, demos.clone())];
        for (i, d) in demos.iter().enumerate() {
            let mut p = d.clone();
            for o in p.objects.iter_mut().filter(|o| !o.fixed) {
                o.x = None;
                o.y = None;
            }
            let others: Vec<Scene> = demos
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, s)| s.clone())
                .collect();
            problems.push((format!("{task}/demo{i}"), p, others));
        }
        for (name, p, like) in problems {
            let like = ResemblanceTarget::new(&like);
            let mut plain = Vec::new();
            let mut with = Vec::new();
            let mut cost = 0;
            for _ in 0..5 {
                let t = Instant::now();
                let r = synthesize(&p, &rules, &SynthOptions::default()).unwrap();
                plain.push(t.elapsed());
                assert_eq!(r.status, Status::Optimal, "{name}");
                let t = Instant::now();
                let opts = SynthOptions {
                    like: Some(like.clone()),
                    ..SynthOptions::default()
                };
                let r2 = synthesize(&p, &rules, &opts).unwrap();
                with.push(t.elapsed());
                assert_eq!(r2.status, Status::Optimal, "{name}");
                let res = r2.resemblance.unwrap();
                assert!(res.proven, "{name}");
                assert_eq!(
                    r.evaluation.unwrap().satisfied_weight,
                    r2.evaluation.unwrap().satisfied_weight
                );
                cost = res.cost;
            }
            let (a, b) = (median(&plain), median(&with));
            println!("{name:24} score-only {:8.2} ms   with --like {:8.2} ms   ratio {:5.2}   cost {cost}", ms(a), ms(b), ms(b) / ms(a));
            rows.push((a, b));
        }
    }
    let ratios: Vec<f64> = rows.iter().map(|(a, b)| ms(*b) / ms(*a)).collect();
    let mut r = ratios.clone();
    r.sort_by(f64::total_cmp);
    println!(
        "median over {} problems: score-only {:.2} ms, with --like {:.2} ms, median ratio {:.2}, max ratio {:.2}",
        rows.len(),
        ms(median(&rows.iter().map(|r| r.0).collect::<Vec<_>>())),
        ms(median(&rows.iter().map(|r| r.1).collect::<Vec<_>>())),
        r[r.len() / 2],
        r[r.len() - 1]
    );
}
