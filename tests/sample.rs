//! `rccpack::sample`: every layout valid (evaluator and the
//! independent verifier), distinct, of the quality asked for; determinism;
//! exhaustion agrees with brute force; "no layout" is reported.

use rccpack::eval::evaluate;
use rccpack::relations::Contact;
use rccpack::rules::{parse_rules, RuleSet};
use rccpack::sample::{canonical_key, sample, Quality, Repair, SampleError, SampleOptions, State};
use rccpack::scene::{scenes_from_json, Scene};
use rccpack::synth::verify_solution;
use rccpack::{learn, LearnParams};
use rccpack_bench::sample::{enumerate, tiny_problems, uniformity};
use std::collections::BTreeSet;

fn box_task() -> (Scene, RuleSet) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing");
    let demos =
        scenes_from_json(&std::fs::read_to_string(format!("{dir}/demos.json")).unwrap()).unwrap();
    let problem =
        Scene::from_json(&std::fs::read_to_string(format!("{dir}/problem.json")).unwrap()).unwrap();
    let rules = learn(&demos, None, &LearnParams::default())
        .unwrap()
        .rules();
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
        assert!(
            keys.insert(canonical_key(problem, s)),
            "a layout came twice"
        );
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
    let activity = SampleOptions {
        repair: Repair::Activity,
        ..opts(Quality::AllRules, 7)
    };
    let layouts: Vec<Scene> = sample(&problem, &rules, &activity)
        .unwrap()
        .take(20)
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(layouts.len(), 20);
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

/// What drawing to the end must return, per quality, from every layout
/// brute force finds (its key and numerator): the optimum ones for
/// `Optimum`, all of them for `MinScore(0)`.
fn wanted(
    all: &[(rccpack::sample::LayoutKey, f64)],
) -> Vec<(Quality, BTreeSet<rccpack::sample::LayoutKey>)> {
    let best = all
        .iter()
        .map(|(_, n)| *n)
        .fold(f64::NEG_INFINITY, f64::max);
    let keys = |keep: &dyn Fn(f64) -> bool| -> BTreeSet<_> {
        all.iter()
            .filter(|(_, n)| keep(*n))
            .map(|(k, _)| k.clone())
            .collect()
    };
    vec![
        (Quality::Optimum, keys(&|n| (n - best).abs() < 1e-9)),
        (Quality::MinScore(0.0), keys(&|_| true)),
    ]
}

#[test]
fn drawing_to_the_end_returns_exactly_the_brute_force_layouts() {
    for (name, problem, rules) in tiny_problems() {
        let all = enumerate(&problem, &rules, Contact::Point, 1 << 22).unwrap();
        let total = rules.rules.len();
        assert!(total > 0);
        for (quality, want) in wanted(&all) {
            for repair in [Repair::Random, Repair::Activity] {
                let o = SampleOptions {
                    repair,
                    ..opts(quality, 1)
                };
                let mut sampler = sample(&problem, &rules, &o).unwrap();
                let got: Vec<Scene> = sampler.by_ref().collect::<Result<_, _>>().unwrap();
                assert_eq!(sampler.state(), State::Exhausted, "{name}");
                check_all(&problem, &rules, &got, 0.0);
                let keys: BTreeSet<_> = got.iter().map(|s| canonical_key(&problem, s)).collect();
                assert_eq!(keys, want, "{name} {quality:?} {repair:?}");
            }
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

/// The run's stop reaches the search for every next layout: cancelled
/// after the first layout, the sampler ends with the limit and that one
/// layout counted.
#[test]
fn a_cancelled_stop_ends_sampling_after_the_layouts_found() {
    let (problem, rules) = box_task();
    let stop = rccpack::stop::Stop::never().cancellable();
    let o = SampleOptions {
        stop: stop.clone(),
        ..opts(Quality::AllRules, 0)
    };
    let mut s = sample(&problem, &rules, &o).unwrap();
    let first = s.next().expect("a layout").expect("no error");
    check_all(&problem, &rules, &[first], 1.0);
    stop.cancel();
    let rest: Vec<_> = s.collect();
    assert!(
        matches!(rest[..], [Err(SampleError::LimitReached { found: 1 })]),
        "{rest:?}"
    );
}

#[test]
fn first_draws_cover_every_tiny_layout() {
    for (name, problem, rules) in tiny_problems() {
        for random in [false, true] {
            let u = uniformity(&problem, &rules, Quality::Optimum, random, 5).unwrap();
            assert!(u.exhaustive_ok, "{name}");
            eprintln!("{name} (random {random}): {u:?}");
        }
    }
}

// ---- strategies: every shrunk value stays valid ---------------------------

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, TestRunner};
use rccpack::sample::strategy::{demo_scenes, layouts, ruleset_strategy};

/// Generate `cases` values of `strategy` and shrink each all the way
/// (always simplifying, as if every value failed), checking `valid` on the
/// first value and on every shrunk one.
fn shrink_all<S: Strategy>(strategy: &S, cases: usize, valid: impl Fn(&S::Value)) {
    let mut runner = TestRunner::new(Config::default());
    for _ in 0..cases {
        let mut tree = strategy.new_tree(&mut runner).unwrap();
        valid(&tree.current());
        let mut steps = 0;
        while tree.simplify() && steps < 200 {
            valid(&tree.current());
            steps += 1;
        }
    }
}

#[test]
fn shrunk_layouts_still_keep_every_rule() {
    let (problem, rules) = box_task();
    let s = layouts(&problem, &rules, &opts(Quality::AllRules, 1), 40).unwrap();
    shrink_all(&s, 10, |scene| {
        verify_solution(&problem, scene, &rules, Contact::Point).unwrap();
        assert_eq!(evaluate(scene, &rules, Contact::Point).score, 1.0);
    });
}

#[test]
fn shrunk_demo_scenes_stay_valid_and_keep_the_rules() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing");
    let demos =
        scenes_from_json(&std::fs::read_to_string(format!("{dir}/demos.json")).unwrap()).unwrap();
    // Without rules: valid complete scenes, never more objects than a demo.
    shrink_all(&demo_scenes(demos.clone(), None), 10, |s| {
        s.validate().unwrap();
        assert!(s.is_complete());
    });
    // Keeping rules: every object that remains keeps them.
    let rules =
        parse_rules("rule r_low: DR_S(R, B)\nrule b_apart hard: EC_N(B, no B) & EC_S(B, no B)\n")
            .unwrap();
    shrink_all(
        &demo_scenes(demos, Some((rules.clone(), Contact::Point))),
        10,
        |s| {
            s.validate().unwrap();
            let e = evaluate(s, &rules, Contact::Point);
            assert!(e.hard_ok() && e.score == 1.0, "{e:?}");
        },
    );
}

#[test]
fn shrunk_rule_sets_print_and_parse_back() {
    shrink_all(&ruleset_strategy(), 20, |rs| {
        let text = rccpack::rules::print_rules(rs);
        assert!(parse_rules(&text).unwrap().same_rules(rs), "{text}");
    });
}

// ---- Arbitrary ------------------------------------------------------------

#[test]
fn arbitrary_scenes_rules_and_tasks_are_valid_inputs() {
    use arbitrary::{Arbitrary, Unstructured};
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(24);
    for _ in 0..300 {
        let bytes: Vec<u8> = (0..rng.random_range(0..400))
            .map(|_| rng.random())
            .collect();
        let mut u = Unstructured::new(&bytes);
        let scene = Scene::arbitrary(&mut u).unwrap();
        scene.validate().unwrap();
        Scene::from_json(&scene.to_json()).unwrap();
        let rules = RuleSet::arbitrary(&mut u).unwrap();
        let text = rccpack::rules::print_rules(&rules);
        assert!(parse_rules(&text).unwrap().same_rules(&rules), "{text}");
        let task = rccpack::sample::arbitrary::Task::arbitrary(&mut u).unwrap();
        task.problem.validate().unwrap();
        rccpack::rules::check_classes(&task.rules, &task.problem).unwrap();
    }
}

#[test]
fn a_problem_with_nothing_to_place_has_exactly_one_layout() {
    let (_, problem, rules) = tiny_problems().remove(1);
    let mut placed = problem.clone();
    for (i, o) in placed.objects.iter_mut().enumerate() {
        if !o.fixed {
            o.x = Some(10 * i as i64);
            o.y = Some(0);
        }
    }
    for quality in [Quality::Optimum, Quality::MinScore(0.0)] {
        let mut s = sample(&placed, &rules, &opts(quality, 0)).unwrap();
        let got: Vec<Scene> = s.by_ref().collect::<Result<_, _>>().unwrap();
        assert_eq!(got, vec![placed.clone()]);
        assert_eq!(s.state(), State::Exhausted);
    }
}

#[test]
fn like_scenes_keep_validity_and_determinism() {
    let (problem, rules) = box_task();
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing");
    let demos =
        scenes_from_json(&std::fs::read_to_string(format!("{dir}/demos.json")).unwrap()).unwrap();
    let o = SampleOptions {
        like: demos,
        ..opts(Quality::AllRules, 2)
    };
    let run = || -> Vec<Scene> {
        sample(&problem, &rules, &o)
            .unwrap()
            .take(20)
            .collect::<Result<_, _>>()
            .unwrap()
    };
    let a = run();
    check_all(&problem, &rules, &a, 1.0);
    assert_eq!(a, run());
}

/// The CP-SAT baseline of `bench sample`.
#[test]
#[ignore = "needs CP-SAT (python3 with ortools): run by .ci/run"]
fn cpsat_baseline_layouts_are_valid() {
    crate::support::require_peer(rccpack_bench::peers::Peer::CpSat);
    let (_, problem, rules) = tiny_problems().remove(0);
    let first = sample(&problem, &rules, &opts(Quality::Optimum, 0))
        .unwrap()
        .next()
        .unwrap()
        .unwrap();
    let b = rccpack_bench::sample::cpsat_baseline(&problem, &rules, Contact::Point, &first, 5, 0)
        .unwrap();
    assert_eq!((b.spread.layouts, b.invalid), (5, 0));
}

/// A tiny problem with two turnable 20×10 blocks `L` and a square `S` in
/// a 30×30 box, and every orientation of it (the turned blocks given
/// `turned`, the others not turnable), for brute force.
fn turnable_problem() -> (Scene, Vec<Scene>) {
    use rccpack::scene::{Object, Space};
    let space = Space {
        x: 0,
        y: 0,
        width: 30,
        height: 30,
    };
    let objects = vec![
        Object::movable("l0", "L", 20, 10).with_turnable(),
        Object::movable("l1", "L", 20, 10).with_turnable(),
        Object::movable("s", "S", 10, 10),
    ];
    let problem = Scene::new(space, 10, objects).unwrap();
    let oriented = every_orientation(&problem);
    (problem, oriented)
}

/// `problem` in every orientation of its turnable objects: each subset of
/// them given `turned`, the others not turnable.
fn every_orientation(problem: &Scene) -> Vec<Scene> {
    let turnable: Vec<usize> = (0..problem.objects.len())
        .filter(|&i| problem.objects[i].turnable)
        .collect();
    (0..1u32 << turnable.len())
        .map(|m| {
            let mut p = problem.clone();
            for (k, &i) in turnable.iter().enumerate() {
                let o = &mut p.objects[i];
                o.turned = m & (1 << k) != 0;
                o.turnable = o.turned;
            }
            p
        })
        .collect()
}

#[test]
fn a_box_that_fits_only_turned_is_sampled_turned_to_the_last_layout() {
    // Four 20×10 blocks and a 10×10 one fill a 30×30 box only when a
    // block stands on end (docs/guide.md#objects-that-turn).
    use rccpack::scene::{Object, Space};
    let space = Space {
        x: 0,
        y: 0,
        width: 30,
        height: 30,
    };
    let mut objects = vec![Object::movable("s", "S", 10, 10)];
    objects.extend((0..4).map(|i| Object::movable(&format!("l{i}"), "L", 20, 10).with_turnable()));
    let problem = Scene::new(space, 10, objects).unwrap();
    let rules = RuleSet::new(Vec::new());
    let mut want = BTreeSet::new();
    for p in every_orientation(&problem) {
        want.extend(
            enumerate(&p, &rules, Contact::Point, 1 << 22)
                .unwrap()
                .into_iter()
                .map(|(k, _)| k),
        );
    }
    assert!(!want.is_empty());
    let mut sampler = sample(&problem, &rules, &opts(Quality::AllRules, 3)).unwrap();
    let got: Vec<Scene> = sampler.by_ref().collect::<Result<_, _>>().unwrap();
    assert_eq!(sampler.state(), State::Exhausted);
    check_all(&problem, &rules, &got, 1.0);
    assert!(got.iter().all(|s| turned_ls(s) >= 1));
    let keys: BTreeSet<_> = got.iter().map(|s| canonical_key(&problem, s)).collect();
    assert_eq!(keys, want);
}

/// How many `L` blocks lie turned in a layout.
fn turned_ls(s: &Scene) -> usize {
    s.objects
        .iter()
        .filter(|o| o.class == "L" && o.turned)
        .count()
}

#[test]
fn turnable_blocks_are_sampled_in_both_orientations_and_drawing_to_the_end_finds_every_layout() {
    // Brute force over every orientation of every block: the layouts
    // keeping the hard rule, with their numerators.
    let (problem, oriented) = turnable_problem();
    let rules = parse_rules("rule s_low hard: !DR_N(S, L)\nrule l_touch: EC_N(L, *)\n").unwrap();
    let mut all: Vec<(rccpack::sample::LayoutKey, f64)> = Vec::new();
    for p in &oriented {
        all.extend(enumerate(p, &rules, Contact::Point, 1 << 22).unwrap());
    }
    for (quality, want) in wanted(&all) {
        let mut sampler = sample(&problem, &rules, &opts(quality, 5)).unwrap();
        let got: Vec<Scene> = sampler.by_ref().collect::<Result<_, _>>().unwrap();
        assert_eq!(sampler.state(), State::Exhausted, "{quality:?}");
        check_all(&problem, &rules, &got, 0.0);
        let keys: BTreeSet<_> = got.iter().map(|s| canonical_key(&problem, s)).collect();
        assert_eq!(keys, want, "{quality:?}");
        // Every number of turned blocks occurs among the layouts.
        let counts: BTreeSet<usize> = got.iter().map(turned_ls).collect();
        assert_eq!(counts, BTreeSet::from([0, 1, 2]), "{quality:?}");
    }
}

#[test]
fn turnable_blocks_lie_turned_in_a_fair_share_of_the_first_samples_same_seed_same_layouts() {
    // The bundled example with four turnable 20×10 blocks added: the first
    // layouts drawn turn some of them and leave others flat.
    let (mut problem, mut rules) = box_task();
    for i in 0..4 {
        problem
            .objects
            .push(rccpack::scene::Object::movable(&format!("l{i}"), "L", 20, 10).with_turnable());
    }
    rules
        .rules
        .extend(parse_rules("rule l_low: DR_S(L, R)\n").unwrap().rules);
    let draw = |seed| -> Vec<Scene> {
        sample(&problem, &rules, &opts(Quality::AllRules, seed))
            .unwrap()
            .take(30)
            .collect::<Result<_, _>>()
            .unwrap()
    };
    let layouts = draw(11);
    assert_eq!(layouts.len(), 30);
    check_all(&problem, &rules, &layouts, 1.0);
    let turned: usize = layouts.iter().map(turned_ls).sum();
    let share = turned as f64 / (4.0 * layouts.len() as f64);
    assert!((0.2..=0.8).contains(&share), "turned share {share}");
    assert_eq!(draw(11), layouts, "same seed, same layouts");
}

#[test]
fn a_hard_orientation_rule_is_kept_by_every_sample() {
    let (problem, _) = turnable_problem();
    for (text, want) in [
        ("rule on_end hard: turned(L)\n", 2),
        ("rule flat hard: !turned(L)\n", 0),
    ] {
        let rules = parse_rules(text).unwrap();
        let mut sampler = sample(&problem, &rules, &opts(Quality::MinScore(0.0), 2)).unwrap();
        let got: Vec<Scene> = sampler.by_ref().collect::<Result<_, _>>().unwrap();
        assert_eq!(sampler.state(), State::Exhausted);
        assert!(!got.is_empty());
        check_all(&problem, &rules, &got, 0.0);
        assert!(got.iter().all(|s| turned_ls(s) == want), "{text}");
    }
}
