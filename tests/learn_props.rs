//! Laws of the posterior (docs/guide.md) and of candidate selection, as
//! property tests with named strategies.

use proptest::prelude::*;
use rccpack::eval::evaluate;
use rccpack::infer::Posterior;
use rccpack::infer::{learn, LearnParams};
use rccpack::relations::Contact;
use rccpack::rules::{Rule, RuleSet};
use rccpack::scene::{Object, Scene, Space};
use std::collections::BTreeMap;

/// The smallest posterior written to a `.rcc` file (docs/guide.md#learning).
const P_FLOOR: f64 = 1e-300;

/// A chance rate `q ∈ [0, 1]`.
fn chance_rate() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(1.0), 0.0..=1.0f64, 1e-6..1e-2f64]
}

/// A chance rate strictly inside (0, 0.99], where `L` moves visibly with `n`.
fn moderate_rate() -> impl Strategy<Value = f64> {
    1e-4..=0.99f64
}

/// An object count `n`.
fn object_count() -> impl Strategy<Value = u64> {
    prop_oneof![0..50u64, 0..100_000u64]
}

/// A floor `ε ∈ (0, 1)`.
fn epsilon() -> impl Strategy<Value = f64> {
    1e-9..0.5f64
}

/// A prior `π ∈ (0, 1)`.
fn prior() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.5), 1e-6..(1.0 - 1e-6)]
}

/// A (q, n) pair whose direct product `qⁿ` is a normal double.
fn representable_product() -> impl Strategy<Value = (f64, u64)> {
    (1e-3..=1.0f64, 0..100u64)
}

/// A demonstration as its objects: ((x, y), class index).
type DemoCells = Vec<((i64, i64), usize)>;

/// 3–9 of the 36 cells of a 60×60 region with grid 10, each with a class.
fn demo_scene() -> impl Strategy<Value = DemoCells> {
    let cells: Vec<(i64, i64)> = (0..6)
        .flat_map(|x| (0..6).map(move |y| (x * 10, y * 10)))
        .collect();
    proptest::sample::subsequence(cells, 3..10)
        .prop_flat_map(|cs| {
            let n = cs.len();
            (Just(cs), proptest::collection::vec(0..3usize, n))
        })
        .prop_map(|(cs, classes)| cs.into_iter().zip(classes).collect())
}

/// Two to four demonstrations and a permutation of them.
fn demo_set() -> impl Strategy<Value = (Vec<DemoCells>, Vec<usize>)> {
    proptest::collection::vec(demo_scene(), 2..5).prop_flat_map(|demos| {
        let n = demos.len();
        (Just(demos), Just((0..n).collect::<Vec<_>>()).prop_shuffle())
    })
}

fn build(cells: &[((i64, i64), usize)]) -> Scene {
    let names = ["A", "B", "W"];
    let mut objects: Vec<Object> = cells
        .iter()
        .enumerate()
        .map(|(i, &((x, y), c))| Object {
            id: format!("o{i}"),
            class: names[c].into(),
            x: Some(x),
            y: Some(y),
            width: 10,
            height: 10,
            fixed: c == 2,
            turnable: false,
            turned: false,
        })
        .collect();
    // One landmark shared by every demonstration (scene-level templates).
    objects.push(Object::fixed_at("w_land", "W", 90, 50, 10, 10));
    // Every demonstration has every class (a movable A and B somewhere).
    for (k, c) in ["A", "B", "W"].iter().enumerate() {
        if !objects.iter().any(|o| o.class == *c) {
            objects.push(Object {
                id: format!("extra{k}"),
                class: (*c).into(),
                x: Some(60 + 10 * k as i64),
                y: Some(0),
                width: 10,
                height: 10,
                fixed: *c == "W",
                turnable: false,
                turned: false,
            });
        }
    }
    Scene {
        space: Space {
            x: 0,
            y: 0,
            width: 100,
            height: 60,
        },
        grid: 10,
        objects,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Law: 0 ≤ P ≤ 1, and the written P lies in [1e-300, 1].
    #[test]
    fn posterior_lies_in_the_unit_interval(q in chance_rate(), eps in epsilon(), n in object_count(), pi in prior()) {
        let p = Posterior::new(q, eps, n, pi);
        let post = 10f64.powf(p.log10_posterior);
        prop_assert!((0.0..=1.0).contains(&post));
        prop_assert!(p.log10_posterior <= 0.0);
        prop_assert!((P_FLOOR..=1.0).contains(&p.written()));
    }

    /// Law: P falls when n grows (strictly while p < 1 is visible).
    #[test]
    fn posterior_falls_when_n_grows(q in moderate_rate(), n in 0..10_000u64, k in 1..100u64, pi in prior()) {
        let a = Posterior::new(q, 1e-12, n, pi).log10_posterior;
        let b = Posterior::new(q, 1e-12, n + k, pi).log10_posterior;
        prop_assert!(b < a, "n {n} → {}: {a} → {b}", n + k);
    }

    /// Law: P falls when q falls (for n ≥ 1).
    #[test]
    fn posterior_falls_when_q_falls(q in moderate_rate(), f in 0.01..0.99f64, n in 1..10_000u64, pi in prior()) {
        let a = Posterior::new(q, 1e-12, n, pi).log10_posterior;
        let b = Posterior::new(q * f, 1e-12, n, pi).log10_posterior;
        prop_assert!(b < a);
    }

    /// Law: log space equals the direct product where `qⁿ` does not
    /// underflow: `L = qⁿ` and `P = πL/(πL + 1 − π)` to 1e-9 relative.
    #[test]
    fn log_space_equals_direct_product((q, n) in representable_product(), pi in prior()) {
        let direct_l = q.powi(n as i32);
        let direct_p = pi * direct_l / (pi * direct_l + 1.0 - pi);
        let post = Posterior::new(q, 1e-12, n, pi);
        let l = 10f64.powf(post.log10_likelihood);
        prop_assert!((l - direct_l).abs() <= 1e-9 * direct_l, "L {l} vs {direct_l}");
        let p = 10f64.powf(post.log10_posterior);
        prop_assert!((p - direct_p).abs() <= 1e-9 * direct_p, "P {p} vs {direct_p}");
    }

    /// Law: P is never below the floor implied by ε:
    /// `P ≥ π εⁿ / (π εⁿ + 1 − π)` up to rounding, and ≥ 1e-300 once written.
    #[test]
    fn posterior_never_below_the_epsilon_floor(q in chance_rate(), eps in epsilon(), n in object_count(), pi in prior()) {
        let p = Posterior::new(q, eps, n, pi);
        prop_assert_eq!(p.p, q.max(eps));
        prop_assert!(p.p >= eps);
        // `q = ε`: `L = εⁿ`.
        let floor = Posterior::new(eps, eps, n, pi).log10_posterior;
        prop_assert!(p.log10_posterior >= floor - 1e-9 * floor.abs().max(1.0));
        prop_assert!(p.written() >= P_FLOOR);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Law: permuting the demonstrations changes neither which statements
    /// are candidates nor their object counts `n`.
    #[test]
    fn permuting_demonstrations_keeps_candidates_and_n((demos, perm) in demo_set()) {
        let scenes: Vec<Scene> = demos.iter().map(|d| build(d)).collect();
        let permuted: Vec<Scene> = perm.iter().map(|&i| scenes[i].clone()).collect();
        let params = LearnParams { samples: 3, ..LearnParams::default() };
        let key = |demos: &[Scene]| -> BTreeMap<String, (bool, u64)> {
            learn(demos, None, &params)
                .unwrap()
                .statements
                .into_iter()
                .map(|s| (s.name, (s.candidate, s.n)))
                .collect()
        };
        prop_assert_eq!(key(&scenes), key(&permuted));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Law: candidates are what the evaluator says — every candidate
    /// (per-object or scene-level) holds in every demonstration, and every
    /// other statement fails in the demonstration its provenance names,
    /// where the object named (if any) is one the evaluator names as a
    /// violator. And the numbers add up: `satisfied ≤` the trials (`N_A`
    /// objects, or `d_r` scenes for a scene-level statement), `q` is their
    /// ratio, `p = max(ε, q)`, and `n = d` for a scene-level statement.
    #[test]
    fn candidates_agree_with_the_evaluator((demos, _) in demo_set(), samples in 1..40usize) {
        let scenes: Vec<Scene> = demos.iter().map(|d| build(d)).collect();
        let params = LearnParams { samples, ..LearnParams::default() };
        let learned = learn(&scenes, None, &params).unwrap();
        prop_assert!(learned.statements.iter().any(|s| s.scope.is_scene()));
        for s in &learned.statements {
            let rule = Rule::new(s.name.clone(), s.formula.clone()).with_scope(s.scope);
            let set = RuleSet::new(vec![rule]);
            match &s.broken_by {
                None => {
                    for d in &scenes {
                        let ev = evaluate(d, &set, Contact::Point);
                        prop_assert_eq!(ev.rules[0].satisfied, ev.rules[0].subjects, "{}", s.name);
                    }
                }
                Some(p) => {
                    for d in &scenes[..p.demo] {
                        let ev = evaluate(d, &set, Contact::Point);
                        prop_assert_eq!(ev.rules[0].satisfied, ev.rules[0].subjects, "{}", s.name);
                    }
                    let ev = evaluate(&scenes[p.demo], &set, Contact::Point);
                    prop_assert!(ev.rules[0].satisfied < ev.rules[0].subjects, "{}", s.name);
                    if let Some(o) = &p.object {
                        prop_assert_eq!(ev.rules[0].violators.first(), Some(o), "{}", s.name);
                    }
                }
            }
            if let (Some(sat), Some(q), Some(post)) = (s.satisfied, s.q, s.posterior) {
                let (trials, eps) = if s.scope.is_scene() {
                    prop_assert_eq!(s.n, scenes.len() as u64);
                    (samples as u64, learned.scene_epsilon)
                } else {
                    let c = learned.classes.iter().find(|c| c.class == s.subject).unwrap();
                    prop_assert_eq!(s.n, c.demo_objects);
                    (c.sample_objects, c.epsilon)
                };
                prop_assert!(sat <= trials);
                prop_assert_eq!(q, sat as f64 / trials.max(1) as f64);
                prop_assert_eq!(post.p, q.max(eps));
            }
        }
    }
}
