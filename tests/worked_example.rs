//! docs/language.md#class-rules on a hand-built context like the thesis's Figure 3-2: two B
//! blocks resting on a row of three R blocks.
//!
//! ```text
//!  y=40 +----+----+
//!       | b1 | b2 |
//!  y=20 +----+----+----+
//!       | r1 | r2 | r3 |
//!  y=0  +----+----+----+
//!       x=0  20   40   60
//! ```

use crate::support::formulas::atom;
use rccpack::eval::Evaluator;
use rccpack::relations::{Contact, Dir, Kind, Relation};
use rccpack::rules::{Formula, Rule, RuleSet};
use rccpack::scene::Scene;

fn scene() -> Scene {
    Scene::from_json(
        r#"{"space":{"width":100,"height":100},"objects":[
        {"id":"r1","class":"R","x":0,"y":0,"width":20,"height":20},
        {"id":"r2","class":"R","x":20,"y":0,"width":20,"height":20},
        {"id":"r3","class":"R","x":40,"y":0,"width":20,"height":20},
        {"id":"b1","class":"B","x":0,"y":20,"width":20,"height":20},
        {"id":"b2","class":"B","x":20,"y":20,"width":20,"height":20}]}"#,
    )
    .unwrap()
}

/// Ids of the objects (of the atom's subject class) that satisfy `f`.
fn holders(scene: &Scene, f: &Formula, contact: Contact) -> Vec<String> {
    let rules = RuleSet::new(vec![Rule::new("f", f.clone())]);
    let ev = Evaluator::new(scene, &rules, contact);
    let c = ev.compile(f);
    scene
        .objects
        .iter()
        .enumerate()
        .filter(|(i, o)| o.class == f.subject() && ev.satisfies(*i, &c))
        .map(|(_, o)| o.id.clone())
        .collect()
}

#[test]
fn blues_are_north_of_every_red() {
    let s = scene();
    assert_eq!(
        holders(&s, &atom("DR_N", "B", "R"), Contact::Point),
        ["b1", "b2"]
    );
    // ...and rest on at least one red.
    assert_eq!(
        holders(&s, &atom("EC_N", "B", "R"), Contact::Point),
        ["b1", "b2"]
    );
    assert_eq!(
        holders(&s, &atom("EC_N", "B", "R"), Contact::Edge),
        ["b1", "b2"]
    );
}

#[test]
fn reds_under_a_blue() {
    let s = scene();
    // r3 touches b2 only at the corner (40, 20): it counts in point mode.
    let ec_s = atom("EC_S", "R", "B");
    assert_eq!(holders(&s, &ec_s, Contact::Point), ["r1", "r2", "r3"]);
    assert_eq!(holders(&s, &ec_s, Contact::Edge), ["r1", "r2"]);
    // Only r3 is east of every blue; nothing is west of every blue.
    assert_eq!(holders(&s, &atom("DR_E", "R", "B"), Contact::Point), ["r3"]);
    assert!(holders(&s, &atom("DR_W", "R", "B"), Contact::Point).is_empty());
}

#[test]
fn same_class_and_any_targets_exclude_the_object_itself() {
    let s = scene();
    // b1 touches b2 on b2's west side; b2 touches b1 on b1's east side.
    assert_eq!(holders(&s, &atom("EC_W", "B", "B"), Contact::Point), ["b1"]);
    assert_eq!(holders(&s, &atom("EC_E", "B", "B"), Contact::Point), ["b2"]);
    // DR_N(B, B): b1 is not north of b2 (same row), so nobody.
    assert!(holders(&s, &atom("DR_N", "B", "B"), Contact::Point).is_empty());
    // DR_S(R, *) fails for everyone since the reds see each other side by side.
    assert!(holders(&s, &atom("DR_S", "R", "*"), Contact::Point).is_empty());
    // A class with no objects: DR holds vacuously, EC never.
    assert_eq!(
        holders(&s, &atom("DR_N", "B", "Q"), Contact::Point),
        ["b1", "b2"]
    );
    assert!(holders(&s, &atom("EC_N", "B", "Q"), Contact::Point).is_empty());
}

#[test]
fn formulas_and_score() {
    let s = scene();
    // "touches another blue on any side"
    let touches = Formula::Or(
        Dir::ALL
            .iter()
            .map(|&d| atom(Relation::new(Kind::EC, d), "B", "B"))
            .collect(),
    );
    assert_eq!(holders(&s, &touches, Contact::Point), ["b1", "b2"]);
    // !DR_N(R, B): every red is south of the blues, so not north of them: all hold.
    let not_north = Formula::not(atom("DR_N", "R", "B"));
    assert_eq!(holders(&s, &not_north, Contact::Point), ["r1", "r2", "r3"]);

    let rules = RuleSet::new(vec![
        Rule::new("b_touch", touches),
        Rule::new("r_east", atom("DR_E", "R", "B"))
            .with_strength(rccpack::rules::Strength::Weight(2.0)),
    ]);
    let e = rccpack::eval::evaluate(&s, &rules, Contact::Point);
    // numerator: 2 blues × 1 + 1 red × 2 = 4; denominator 2 × 1 + 3 × 2 = 8.
    assert_eq!(e.satisfied_weight, 4.0);
    assert_eq!(e.total_weight, 8.0);
    assert_eq!(e.score, 0.5);
    assert_eq!(e.rules[1].violators, ["r1", "r2"]);
}

#[test]
fn unplaced_objects_take_no_part() {
    let mut s = scene();
    s.objects[2].x = None; // r3 unplaced
    s.objects[2].y = None;
    assert_eq!(
        holders(&s, &atom("DR_E", "R", "B"), Contact::Point),
        Vec::<String>::new()
    );
    let rules = RuleSet::new(vec![Rule::new("r", atom("DR_S", "R", "B"))]);
    let e = rccpack::eval::evaluate(&s, &rules, Contact::Point);
    assert_eq!(e.rules[0].subjects, 2);
}
