//! A property test of a small pick-order planner over layouts that keep the
//! bundled example's learned rules (issue 24).
//!
//! The planner decides in which order a gripper puts the blocks of a
//! layout into the box. A block comes down from the north (+y) along its
//! own column and must not sweep through a block that is already in place
//! (the gripper lifts it over the walls). The property: for every layout a
//! person would accept — here, every layout that keeps every rule learned
//! from `examples/box-packing/demos.json` — every block can be placed in
//! the planned order without crossing an already-placed one.
//!
//! `cargo run --example pick_order` runs it and also shows a wrong planner
//! (north to south) failing, with the simplest failing layout that
//! proptest's shrinking finds. `cargo test` runs it too (`test = true`).

use proptest::test_runner::{Config, TestCaseError, TestError, TestRunner};
use rccpack::sample::strategy::layouts;
use rccpack::sample::{Quality, SampleOptions};
use rccpack::scene::{scenes_from_json, Scene};
use rccpack::{learn, LearnParams, RuleSet};

/// The planner under test: south to north, then west to east.
fn plan(scene: &Scene) -> Vec<usize> {
    let mut order: Vec<usize> = (0..scene.objects.len())
        .filter(|&i| !scene.objects[i].fixed)
        .collect();
    order.sort_by_key(|&i| {
        let o = &scene.objects[i];
        (o.y, o.x)
    });
    order
}

/// A wrong planner: north to south (it forgets that a block on top of
/// another must come last).
fn plan_north_first(scene: &Scene) -> Vec<usize> {
    let mut order = plan(scene);
    order.reverse();
    order
}

/// The first block whose way down from the north crosses a block placed
/// before it, if any.
fn first_crossing(scene: &Scene, order: &[usize]) -> Option<(String, String)> {
    for (k, &i) in order.iter().enumerate() {
        let a = scene.objects[i].rect()?;
        for &j in &order[..k] {
            let b = scene.objects[j].rect()?;
            // b's interior meets the column above a's final position.
            let same_column = b.x < a.x2() && a.x < b.x2();
            if same_column && b.y2() > a.y2() {
                return Some((scene.objects[i].id.clone(), scene.objects[j].id.clone()));
            }
        }
    }
    None
}

/// The bundled example's problem and the rules learned from its
/// demonstrations.
fn task() -> (Scene, RuleSet) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing");
    let read = |f: &str| std::fs::read_to_string(format!("{dir}/{f}")).expect("example file");
    let demos = scenes_from_json(&read("demos.json")).expect("demos");
    let problem = Scene::from_json(&read("problem.json")).expect("problem");
    let rules = learn(&demos, None, &LearnParams::default())
        .expect("learning")
        .rules();
    (problem, rules)
}

/// Run the property for `planner` over 64 layouts of score 1 (from a pool
/// of 200 distinct sampled layouts).
fn check(planner: fn(&Scene) -> Vec<usize>) -> Result<(), TestError<Scene>> {
    let (problem, rules) = task();
    let opts = SampleOptions {
        quality: Quality::AllRules,
        seed: 24,
        ..SampleOptions::default()
    };
    let strategy = layouts(&problem, &rules, &opts, 200).expect("layouts of the example");
    let mut runner = TestRunner::new(Config {
        cases: 64,
        failure_persistence: None,
        ..Config::default()
    });
    runner.run(&strategy, |scene| {
        match first_crossing(&scene, &planner(&scene)) {
            None => Ok(()),
            Some((a, b)) => Err(TestCaseError::fail(format!("{a} crosses {b}"))),
        }
    })
}

fn main() {
    match check(plan) {
        Ok(()) => println!("planner: every sampled layout can be packed in the planned order"),
        Err(e) => {
            eprintln!("planner failed: {e}");
            std::process::exit(1);
        }
    }
    match check(plan_north_first) {
        Ok(()) => println!("north first: no failure found"),
        Err(TestError::Fail(why, scene)) => {
            let placed: Vec<String> = scene
                .objects
                .iter()
                .filter(|o| !o.fixed)
                .map(|o| format!("{}@({},{})", o.id, o.x.unwrap_or(0), o.y.unwrap_or(0)))
                .collect();
            println!("north first fails ({why}); simplest failing layout: {placed:?}");
        }
        Err(e) => println!("north first: {e}"),
    }
}

#[test]
fn the_planner_packs_every_sampled_layout() {
    check(plan).unwrap();
}

#[test]
fn the_north_first_planner_is_caught() {
    assert!(matches!(check(plan_north_first), Err(TestError::Fail(..))));
}
