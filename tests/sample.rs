//! `rccpack::sample` (issue 24): every layout valid (evaluator and the
//! independent verifier), distinct, of the quality asked for; determinism;
//! exhaustion agrees with brute force; "no layout" is reported.

use rccpack::bench::sample::{enumerate, tiny_problems, uniformity};
use rccpack::eval::evaluate;
use rccpack::relations::Contact;
use rccpack::rules::{parse_rules, RuleSet};
use rccpack::sample::{canonical_key, sample, Quality, SampleError, SampleOptions, State};
use rccpack::scene::{scenes_from_json, Scene};
use rccpack::synth::verify::verify_solution;
use rccpack::{learn, LearnParams};
use std::collections::BTreeSet;

fn box_task() -> (Scene, RuleSet) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing");
    let demos = scenes_from_json(&std::fs::read_to_string(format!("{dir}/demos.json")).unwrap())
        .unwrap();
    let problem =
        Scene::from_json(&std::fs::read_to_string(format!("{dir}/problem.json")).unwrap())
            .unwrap();
    let rules = learn(&demos, None, &LearnParams::default()).unwrap().rules();
    (problem, rules)
}

fn opts(quality: Quality, seed: u64) -> SampleOptions {
    SampleOptions {
        quality,
        seed,
        ..SampleOptions::default()
    }
}

/// Every layout passes the verifier, has the score asked for, and no two
/// are the same layout.
fn check_all(problem: &Scene, rules: &RuleSet, layouts: &[Scene], min: f64) {
    let mut keys = BTreeSet::new();
    for s in layouts {
        verify_solution(problem, s, rules, Contact::Point).unwrap();
        let e = evaluate(s, rules, Contact::Point);
        assert!(e.hard_ok());
        assert!(e.score >= min - 1e-9, "score {} < {min}", e.score);
        assert!(keys.insert(canonical_key(problem, s)), "a layout came twice");
    }
}

#[test]
fn box_example_all_rules_layouts_are_valid_distinct_and_score_one() {
    let (problem, rules) = box_task();
    let layouts: Vec<Scene> = sample(&problem, &rules, &opts(Quality::AllRules, 7))
        .unwrap()
        .take(60)
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(layouts.len(), 60);
    check_all(&problem, &rules, &layouts, 1.0);
}

#[test]
fn same_seed_same_layouts_other_seed_other_order() {
    let (problem, rules) = box_task();
    let run = |seed| -> Vec<Scene> {
        sample(&problem, &rules, &opts(Quality::Optimum, seed))
            .unwrap()
            .take(15)
            .collect::<Result<_, _>>()
            .unwrap()
    };
    let a = run(3);
    // On another thread: no dependence on the thread or the pool.
    let b = std::thread::scope(|s| s.spawn(|| run(3)).join().unwrap());
    assert_eq!(a, b);
    assert_ne!(a, run(4));
}

#[test]
fn drawing_to_the_end_returns_exactly_the_brute_force_layouts() {
    for (name, problem, rules) in tiny_problems() {
        let all = enumerate(&problem, &rules, Contact::Point, 1 << 22).unwrap();
        let best = all.iter().map(|(_, n)| *n).fold(f64::NEG_INFINITY, f64::max);
        let total = rules.rules.len();
        assert!(total > 0);
        for (quality, keep) in [
            (
                Quality::Optimum,
                Box::new(|n: f64| (n - best).abs() < 1e-9) as Box<dyn Fn(f64) -> bool>,
            ),
            (Quality::MinScore(0.0), Box::new(|_| true)),
        ] {
            let want: BTreeSet<_> = all
                .iter()
                .filter(|(_, n)| keep(*n))
                .map(|(k, _)| k.clone())
                .collect();
            let mut sampler = sample(&problem, &rules, &opts(quality, 1)).unwrap();
            let got: Vec<Scene> = sampler.by_ref().collect::<Result<_, _>>().unwrap();
            assert_eq!(sampler.state(), State::Exhausted, "{name}");
            check_all(&problem, &rules, &got, 0.0);
            let keys: BTreeSet<_> = got.iter().map(|s| canonical_key(&problem, s)).collect();
            assert_eq!(keys, want, "{name} {quality:?}");
        }
    }
}

#[test]
fn min_score_layouts_reach_it_and_all_are_found() {
    let (name, problem, rules) = tiny_problems().remove(1);
    let all = enumerate(&problem, &rules, Contact::Point, 1 << 22).unwrap();
    let total = 3.0; // b_north (1) + b_wall (2), one blue
    let want = all.iter().filter(|(_, n)| n / total >= 0.3).count();
    let got: Vec<Scene> = sample(&problem, &rules, &opts(Quality::MinScore(0.3), 0))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    check_all(&problem, &rules, &got, 0.3);
    assert_eq!(got.len(), want, "{name}");
}

#[test]
fn no_score_one_layout_and_infeasible_are_reported() {
    let (_, problem, _) = tiny_problems().remove(0);
    // Two As cannot both be west of each other.
    let rules = parse_rules("rule west: DR_W(A, A)\n").unwrap();
    let mut s = sample(&problem, &rules, &opts(Quality::AllRules, 0)).unwrap();
    match s.next() {
        Some(Err(SampleError::NoLayout { best, .. })) => assert!((best - 0.5).abs() < 1e-9),
        other => panic!("{other:?}"),
    }
    assert!(s.next().is_none());
    let hard = parse_rules("rule west hard: DR_W(A, A)\n").unwrap();
    let mut s = sample(&problem, &hard, &opts(Quality::Optimum, 0)).unwrap();
    assert!(matches!(s.next(), Some(Err(SampleError::Infeasible(_)))));
    assert!(matches!(
        sample(&problem, &rules, &opts(Quality::MinScore(1.5), 0)),
        Err(SampleError::BadMinScore(_))
    ));
}

#[test]
fn a_node_limit_ends_with_limit_reached() {
    let (problem, rules) = box_task();
    let o = SampleOptions {
        layout_node_limit: Some(0),
        ..opts(Quality::AllRules, 0)
    };
    let items: Vec<_> = sample(&problem, &rules, &o).unwrap().collect();
    assert!(matches!(
        items.last(),
        Some(Err(SampleError::LimitReached { .. }))
    ));
}

#[test]
fn first_draws_cover_every_tiny_layout() {
    for (name, problem, rules) in tiny_problems() {
        let u = uniformity(&problem, &rules, Quality::Optimum, 20 * 12).unwrap();
        assert!(u.exhaustive_ok, "{name}");
        eprintln!("{name}: {u:?}");
    }
}
