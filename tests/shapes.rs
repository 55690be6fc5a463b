//! Group statements (third edition): `group(C)`, `row(C)`, `column(C)`,
//! `block(C)` — semantics on a hand-made table of tiny scenes, the
//! evaluator's report, the parser round trip, learning (a shape shown by
//! chance is not learned, one shown every time is) and a layout with more
//! objects than the demonstrations. The engine's encoding is checked
//! against brute force in `synth_differential::*group_shapes*`.

use rccpack::eval::Evaluator;
use rccpack::infer::{learn, LearnParams};
use rccpack::relations::Contact;
use rccpack::rules::{parse_rules, print_rules, RuleSet};
use rccpack::scene::{Object, Scene, Space};
use rccpack::shapes::{self, ShapeKind};
use rccpack::synth::{synthesize, verify_solution, Status, SynthOptions};

fn space(w: i64, h: i64) -> Space {
    Space {
        x: 0,
        y: 0,
        width: w,
        height: h,
    }
}

/// A scene of 10×10 `R` blocks at the given grid cells (column, row; y up).
fn scene_of(cells: &[(i64, i64)]) -> Scene {
    let objects = cells
        .iter()
        .enumerate()
        .map(|(i, &(c, r))| Object::placed(&format!("r{i}"), "R", 10 * c, 10 * r, 10, 10))
        .collect();
    Scene {
        space: space(100, 100),
        grid: 10,
        objects,
    }
}

fn holds(kind: ShapeKind, cells: &[(i64, i64)], contact: Contact) -> bool {
    let scene = scene_of(cells);
    let rects: Vec<_> = scene.objects.iter().filter_map(|o| o.rect()).collect();
    let direct = shapes::check(kind, &rects, contact).holds;
    // The evaluator, through the parser, must say the same.
    let rules = parse_rules(&format!("rule s: {}(R)\n", kind.name())).unwrap();
    let e = Evaluator::new(&scene, &rules, contact).evaluate(&rules);
    assert_eq!(
        e.rules[0].satisfied == 1,
        direct,
        "{kind:?} {cells:?} evaluator vs shapes::check"
    );
    direct
}

/// `(cells, group, row, column, block)`.
#[allow(clippy::type_complexity)]
const TABLE: &[(&[(i64, i64)], bool, bool, bool, bool)] = &[
    // zero and one object: vacuous
    (&[], true, true, true, true),
    (&[(3, 3)], true, true, true, true),
    // two side by side / stacked / apart / diagonal
    (&[(0, 0), (1, 0)], true, true, false, true),
    (&[(0, 0), (0, 1)], true, false, true, true),
    (&[(0, 0), (2, 0)], false, false, false, false),
    (&[(0, 0), (1, 1)], false, false, false, false),
    // three in a row, in a column, an L
    (&[(0, 0), (1, 0), (2, 0)], true, true, false, false),
    (&[(4, 0), (4, 1), (4, 2)], true, false, true, false),
    (&[(0, 0), (1, 0), (0, 1)], true, false, false, true),
    // a column with a gap (the split column)
    (
        &[(0, 0), (0, 1), (0, 3), (0, 4), (0, 5)],
        false,
        false,
        false,
        false,
    ),
    // 2×2, and five as a 3×2 block minus one cell, and as an L of five
    (&[(0, 0), (1, 0), (0, 1), (1, 1)], true, false, false, true),
    (
        &[(0, 0), (1, 0), (2, 0), (0, 1), (1, 1)],
        true,
        false,
        false,
        true,
    ),
    (
        &[(0, 0), (0, 1), (0, 2), (1, 0), (2, 0)],
        true,
        false,
        false,
        false,
    ),
    // four in a line is one group and one row, but not a block (2×2)
    (&[(0, 0), (1, 0), (2, 0), (3, 0)], true, true, false, false),
    // two pairs apart
    (
        &[(0, 0), (1, 0), (5, 5), (6, 5)],
        false,
        false,
        false,
        false,
    ),
];

#[test]
fn semantics_table_in_both_contact_modes() {
    for &(cells, g, r, c, b) in TABLE {
        for contact in [Contact::Point, Contact::Edge] {
            assert_eq!(
                holds(ShapeKind::Group, cells, contact),
                g,
                "group {cells:?}"
            );
            assert_eq!(holds(ShapeKind::Row, cells, contact), r, "row {cells:?}");
            assert_eq!(
                holds(ShapeKind::Column, cells, contact),
                c,
                "column {cells:?}"
            );
            assert_eq!(
                holds(ShapeKind::Block, cells, contact),
                b,
                "block {cells:?}"
            );
        }
    }
}

/// Blocks of different sizes: a row needs south edges on one line, a
/// column west edges on one line.
#[test]
fn rows_and_columns_align_their_edges() {
    let mk = |objs: Vec<Object>| -> Vec<rccpack::scene::Rect> {
        objs.iter().filter_map(|o| o.rect()).collect()
    };
    let aligned = mk(vec![
        Object::placed("a", "R", 0, 0, 10, 20),
        Object::placed("b", "R", 10, 0, 10, 10),
    ]);
    let offset = mk(vec![
        Object::placed("a", "R", 0, 0, 10, 20),
        Object::placed("b", "R", 10, 10, 10, 10),
    ]);
    for contact in [Contact::Point, Contact::Edge] {
        assert!(shapes::check(ShapeKind::Row, &aligned, contact).holds);
        assert!(!shapes::check(ShapeKind::Row, &offset, contact).holds);
        assert!(shapes::check(ShapeKind::Group, &offset, contact).holds);
    }
}

/// The block's box grows with the count: 4 → 2×2, 5–6 → 3×2, 9 → 3×3.
#[test]
fn block_boxes_generalise_from_four_to_more() {
    assert_eq!(shapes::block_boxes(4), vec![(2, 2)]);
    assert_eq!(shapes::block_boxes(5), vec![(3, 2), (2, 3)]);
    assert_eq!(shapes::block_boxes(6), vec![(3, 2), (2, 3)]);
    assert_eq!(shapes::block_boxes(9), vec![(3, 3)]);
}

#[test]
fn the_report_names_the_objects_off_the_main_group() {
    let scene = scene_of(&[(0, 0), (0, 1), (0, 3), (0, 4), (0, 5)]);
    let rules = parse_rules("rule c: column(R)\nrule n: not group(R)\n").unwrap();
    let e = Evaluator::new(&scene, &rules, Contact::Point).evaluate(&rules);
    let c = &e.rules[0];
    assert_eq!((c.subjects, c.satisfied), (1, 0));
    assert_eq!(c.violators, vec!["r0".to_string(), "r1".to_string()]);
    let g = c.group.as_ref().expect("a group report");
    assert_eq!(g.groups.len(), 2);
    assert_eq!(g.groups[0], vec!["r2", "r3", "r4"]);
    // The negation holds: the Rs do not form one group.
    assert_eq!(e.rules[1].satisfied, 1);
    let json = serde_json::to_value(&e).unwrap();
    assert!(json["rules"][0]["group"]["groups"].is_array(), "{json}");
}

#[test]
fn parser_round_trip_and_errors() {
    let text =
        "rule a: column(R)\nrule b hard: not block(G)\nrule c weight 2: row(B)\nrule d: group(R)\n";
    let rules = parse_rules(text).unwrap();
    assert_eq!(rules.rules.len(), 4);
    assert!(rules.rules.iter().all(|r| r.is_group()));
    let printed = print_rules(&rules);
    let again = parse_rules(&printed).unwrap();
    assert_eq!(print_rules(&again), printed);
    for r in rules.rules.iter().zip(&again.rules) {
        assert!(r.0.same_rule(r.1));
    }
    for bad in [
        "rule a: column(*)\n",
        "rule a: column(@f)\n",
        "rule a: column()\n",
    ] {
        let e = parse_rules(bad).unwrap_err();
        let (line, col) = e.diagnostics[0].line_col(bad);
        assert_eq!(line, 1, "{bad}: {e}");
        assert!(col >= 9, "{bad}: column {col}: {e}");
    }
}

fn box_scene(w: i64, h: i64, cells: &[(i64, i64)], class: &str) -> Scene {
    Scene {
        space: space(w, h),
        grid: 10,
        objects: cells
            .iter()
            .enumerate()
            .map(|(i, &(c, r))| Object::placed(&format!("o{i}"), class, 10 * c, 10 * r, 10, 10))
            .collect(),
    }
}

fn learned_names(demos: &[Scene]) -> Vec<String> {
    let l = learn(demos, None, &LearnParams::default()).unwrap();
    l.rules().rules.iter().map(|r| r.name.clone()).collect()
}

/// Two objects in a 3×1 strip touch in two of three placements: a row of
/// two there is chance, not intent.
#[test]
fn a_shape_shown_by_chance_is_not_learned() {
    let demos = vec![
        box_scene(30, 10, &[(0, 0), (1, 0)], "R"),
        box_scene(30, 10, &[(1, 0), (2, 0)], "R"),
        box_scene(30, 10, &[(0, 0), (1, 0)], "R"),
    ];
    let names = learned_names(&demos);
    assert!(
        !names.iter().any(|n| n.starts_with("R_one_")),
        "learned {names:?}"
    );
    let l = learn(&demos, None, &LearnParams::default()).unwrap();
    let row = l.statements.iter().find(|s| s.name == "R_one_row").unwrap();
    assert!(row.candidate);
    assert!(row.q.unwrap() > 0.5, "chance of a row of two: {:?}", row.q);
}

/// A column shown every time, with 3 and 4 objects in a roomy box, is
/// learned; a column shown once is not.
#[test]
fn a_shape_shown_every_time_is_learned() {
    let demos = vec![
        box_scene(100, 100, &[(2, 1), (2, 2), (2, 3)], "R"),
        box_scene(100, 100, &[(7, 4), (7, 5), (7, 6), (7, 7)], "R"),
        box_scene(100, 100, &[(4, 0), (4, 1), (4, 2), (4, 3)], "R"),
    ];
    let names = learned_names(&demos);
    assert!(names.contains(&"R_one_column".to_string()), "{names:?}");
    assert!(names.contains(&"R_one_group".to_string()), "{names:?}");
    assert!(!names.contains(&"R_one_row".to_string()), "{names:?}");
    let mut once = demos.clone();
    once[1] = box_scene(100, 100, &[(1, 4), (5, 5), (7, 6), (3, 8)], "R");
    once[2] = box_scene(100, 100, &[(0, 0), (2, 1), (4, 2), (9, 3)], "R");
    let names = learned_names(&once);
    assert!(!names.iter().any(|n| n.starts_with("R_one_")), "{names:?}");
}

/// More objects than any demonstration: a hard `block(G)` keeps five greens
/// in one compact block (3×2 minus one cell), and the evaluator agrees.
#[test]
fn five_blocks_keep_the_block_shape() {
    let objects = (0..5)
        .map(|i| Object::movable(&format!("g{i}"), "G", 10, 10))
        .collect();
    let scene = Scene {
        space: space(60, 60),
        grid: 10,
        objects,
    };
    for contact in [Contact::Point, Contact::Edge] {
        let rules: RuleSet = parse_rules("rule b hard: block(G)\n").unwrap();
        let opts = SynthOptions {
            contact,
            ..SynthOptions::default()
        };
        let r = synthesize(&scene, &rules, &opts).unwrap();
        assert_eq!(r.status, Status::Optimal);
        let sol = r.scene.unwrap();
        verify_solution(&scene, &sol, &rules, contact).unwrap();
        let rects: Vec<_> = sol.objects.iter().filter_map(|o| o.rect()).collect();
        let c = shapes::check(ShapeKind::Block, &rects, contact);
        assert!(c.holds, "{sol:?}");
        let ((w, h), fits) = c.bbox.unwrap();
        assert!(fits);
        assert!((w, h) == (30, 20) || (w, h) == (20, 30), "{w}×{h}");
    }
}

/// `ask` can probe a group statement: a layout that breaks the column and
/// keeps the other held rules; and a column implied by the others is
/// reported as implied.
#[test]
fn ask_probes_a_group_statement() {
    use rccpack::ask::{find_probe, ProbeOptions, ProbeOutcome};
    let objects = (0..4)
        .map(|i| Object::movable(&format!("r{i}"), "R", 10, 10))
        .collect();
    let problem = Scene {
        space: space(50, 50),
        grid: 10,
        objects,
    };
    let held = parse_rules(
        "rule c: column(R)\nrule n: FL_N(R, R) | FL_S(R, R)\nrule a: AL_W(R, every R)\n",
    )
    .unwrap();
    let opts = ProbeOptions::default();
    // Breaking `c` alone: a split column keeps `n` (each has a partner
    // above or below) and `a` (one line).
    match find_probe(&problem, &held, 0, &opts).unwrap() {
        ProbeOutcome::Probe(p) => {
            let one = RuleSet::new(vec![held.rules[0].clone()]);
            let e = Evaluator::new(&p.scene, &one, Contact::Point).evaluate(&one);
            assert_eq!(e.rules[0].satisfied, 0, "{:?}", p.scene);
            let rest = RuleSet::new(held.rules[1..].to_vec());
            let e = Evaluator::new(&p.scene, &rest, Contact::Point).evaluate(&rest);
            assert!(e.rules.iter().all(|r| r.satisfied == r.subjects));
            assert!(!p.broken.is_empty(), "the objects off the main column");
        }
        o => panic!("expected a probe, got {o:?}"),
    }
    // With three objects a split column cannot keep `n`: implied.
    let mut three = problem.clone();
    three.objects.truncate(3);
    match find_probe(&three, &held, 0, &opts).unwrap() {
        // (`by` is filled only when the options ask for an explanation.)
        ProbeOutcome::Implied { .. } => {}
        o => panic!("expected implied, got {o:?}"),
    }
}

/// Hardening, third pass, item 10: on a scene without the class, the note
/// names the rules that cannot hold (a scene rule that needs a subject, a
/// negated group statement) instead of saying every rule holds vacuously,
/// and a group statement about the class gets the note too.
#[test]
fn the_absent_class_note_names_the_rules_that_cannot_hold() {
    let dir = crate::support::scratch("shapes-absent-class");
    let rules = crate::support::write_file(
        &dir,
        "r.rcc",
        "# learned by rccpack (a test)\nrule a: DR_N(Q, R)\nrule b: some Q: DR_N(Q, R)\nrule c: not group(Q)\n",
    );
    let problem = crate::support::path("examples/box-packing/problem.json");
    let o = crate::support::rccpack(&["score", problem.to_str().unwrap(), "--rules", &rules]);
    let err = crate::support::stderr(&o);
    assert!(
        err.contains("note: the problem has no objects of class Q; its rules hold vacuously, except `b`, `c`, which need one and cannot hold"),
        "{err}"
    );
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(out.contains("b            1        0/1"), "{out}");
    // A group statement alone is noted too.
    let only = crate::support::write_file(
        &dir,
        "g.rcc",
        "# learned by rccpack (a test)\nrule g: group(Q)\n",
    );
    let o = crate::support::rccpack(&["score", problem.to_str().unwrap(), "--rules", &only]);
    let err = crate::support::stderr(&o);
    assert!(
        err.contains("note: the problem has no objects of class Q; its rules hold vacuously\n"),
        "{err}"
    );
}
