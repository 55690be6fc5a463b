//! The bundled box-packing example: the data is well formed and every
//! demonstration keeps all twelve pilot rules.

use crate::support::formulas::atom;
use rccpack::eval::evaluate;
use rccpack::relations::{Contact, Dir, Kind, Relation};
use rccpack::rules::{Formula, Rule, RuleSet};
use rccpack::scene::{scenes_from_json, Scene};
use std::collections::BTreeMap;

fn example_file(name: &str) -> String {
    crate::support::read(format!("examples/box-packing/{name}"))
}

fn demos() -> Vec<Scene> {
    scenes_from_json(&example_file("demos.json")).expect("demos.json is valid")
}

fn ec(dir: Dir, s: &str, t: &str) -> Formula {
    atom(Relation::new(Kind::EC, dir), s, t)
}

fn dr(dir: Dir, s: &str, t: &str) -> Formula {
    atom(Relation::new(Kind::DR, dir), s, t)
}

/// The twelve pilot rules of `pilot.rcc`, built through the AST.
fn pilot_rules_ast() -> RuleSet {
    use Dir::*;
    let mut rules = vec![
        Rule::new("blue_north_of_red", dr(N, "B", "R")),
        Rule::new("green_east_of_red", dr(E, "G", "R")),
        Rule::new("green_east_of_blue", dr(E, "G", "B")),
    ];
    let names = [("B", "blue"), ("R", "red"), ("G", "green")];
    for (c, n) in names {
        rules.push(Rule::new(
            format!("{n}_touches_{n}"),
            Formula::Or(Dir::ALL.iter().map(|&d| ec(d, c, c)).collect()),
        ));
    }
    for (c, n) in names {
        let pair = |a: Dir, b: Dir| Formula::And(vec![ec(a, c, "*"), ec(b, c, "*")]);
        rules.push(Rule::new(
            format!("{n}_in_corner"),
            Formula::Or(vec![pair(N, W), pair(W, S), pair(S, E), pair(E, N)]),
        ));
    }
    for (c, n) in names {
        rules.push(Rule::new(
            format!("{n}_inside_box"),
            Formula::And(
                Dir::ALL
                    .iter()
                    .map(|&d| Formula::not(dr(d, c, "W")))
                    .collect(),
            ),
        ));
    }
    RuleSet::new(rules)
}

fn assert_all_demos_perfect(rules: &RuleSet) {
    assert_eq!(rules.rules.len(), 12);
    for (i, d) in demos().iter().enumerate() {
        let ev = evaluate(d, rules, Contact::Point);
        for r in &ev.rules {
            assert!(
                r.violators.is_empty(),
                "demo {i}: rule {} broken by {:?}",
                r.name,
                r.violators
            );
            assert!(r.subjects > 0, "demo {i}: rule {} has no subjects", r.name);
        }
        assert_eq!(ev.score, 1.0, "demo {i}");
        assert!(
            ev.off_grid.is_empty(),
            "demo {i}: off grid {:?}",
            ev.off_grid
        );
    }
}

#[test]
fn demos_are_complete_on_grid_and_varied() {
    let demos = demos();
    assert_eq!(demos.len(), 8);
    let mut count_profiles = Vec::new();
    for (i, d) in demos.iter().enumerate() {
        d.validate().unwrap();
        assert!(d.is_complete(), "demo {i} is incomplete");
        assert_eq!((d.space.width, d.space.height, d.grid), (600, 600, 10));
        let walls: Vec<_> = d.objects.iter().filter(|o| o.class == "W").collect();
        assert_eq!(walls.len(), 4, "demo {i}");
        assert!(walls.iter().all(|w| w.fixed));
        let mut counts = BTreeMap::new();
        for o in d.objects.iter().filter(|o| !o.fixed) {
            assert!(d.on_grid(o), "demo {i}: {} off grid", o.id);
            assert_eq!((o.width, o.height), (20, 20), "demo {i}: {}", o.id);
            let r = o.rect().unwrap();
            assert!(
                r.x >= 200 && r.x2() <= 400 && r.y >= 200 && r.y2() <= 400,
                "demo {i}: {} outside the box",
                o.id
            );
            *counts.entry(o.class.as_str()).or_insert(0usize) += 1;
        }
        assert_eq!(counts.keys().copied().collect::<Vec<_>>(), ["B", "G", "R"]);
        assert!(
            counts.values().all(|&n| (2..=4).contains(&n)),
            "demo {i}: {counts:?}"
        );
        count_profiles.push(counts);
    }
    for class in ["R", "G", "B"] {
        let mut seen: Vec<usize> = count_profiles.iter().map(|c| c[class]).collect();
        seen.sort();
        seen.dedup();
        assert!(seen.len() >= 2, "counts of {class} never vary");
    }
    let mut distinct = count_profiles.clone();
    distinct.dedup();
    assert!(distinct.len() >= 4);
}

#[test]
fn every_demo_scores_one_against_ast_pilot_rules() {
    assert_all_demos_perfect(&pilot_rules_ast());
}

#[test]
fn ast_pilot_rules_are_not_trivial() {
    // Swapping red and blue must break `blue_north_of_red`: the check above
    // is not vacuous.
    let rules = pilot_rules_ast();
    let mut d = demos().remove(0);
    for o in &mut d.objects {
        o.class = match o.class.as_str() {
            "R" => "B".into(),
            "B" => "R".into(),
            c => c.into(),
        };
    }
    let ev = evaluate(&d, &rules, Contact::Point);
    assert!(ev.score < 1.0);
    assert!(!ev.rules[0].violators.is_empty());
}

#[test]
fn every_demo_scores_one_against_parsed_pilot_rcc() {
    let parsed = rccpack::rules::parse_rules(&example_file("pilot.rcc")).expect("pilot.rcc parses");
    assert!(
        parsed.same_rules(&pilot_rules_ast()),
        "pilot.rcc differs from the AST copy in this test"
    );
    for d in demos() {
        rccpack::rules::check_classes(&parsed, &d).expect("classes exist");
    }
    assert_all_demos_perfect(&parsed);
}

#[test]
fn problem_has_nine_unplaced_blocks() {
    let p = Scene::from_json(&example_file("problem.json")).expect("problem.json is valid");
    let walls = &demos()[0].objects[..4];
    assert_eq!(
        &p.objects[..4],
        walls,
        "problem walls differ from the demos'"
    );
    let movable: Vec<_> = p.objects.iter().filter(|o| !o.fixed).collect();
    assert_eq!(movable.len(), 9);
    assert!(movable.iter().all(|o| !o.is_placed()));
    for class in ["R", "G", "B"] {
        let ids: Vec<_> = movable
            .iter()
            .filter(|o| o.class == class)
            .map(|o| o.id.as_str())
            .collect();
        let lower = class.to_ascii_lowercase();
        assert_eq!(ids, [1, 2, 3].map(|i| format!("{lower}{i}")));
    }
}
