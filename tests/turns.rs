//! Objects that turn (docs/scenes.md#objects-that-turn,
//! docs/guide.md#objects-that-turn): the scene fields and their errors,
//! the footprint in relations, the evaluator, `score --json`, `check` and
//! pictures, and synthesis choosing orientations (a box that fits only
//! turned, tiny packings found by exhaustive search).

use crate::support::{rccpack, scratch, stderr, stdout, write_file};
use rccpack::relations::{relation_bits, Contact, Relation};
use rccpack::scene::{Object, Rect, Scene, SceneErrorKind, Space};
use rccpack::synth::brute_force;
use rccpack::synth::{synthesize, verify_solution, Status, SynthOptions};
use rccpack::{evaluate, parse_rules, render_svg, RenderOptions, RuleSet};

fn scene(w: i64, h: i64, objects: Vec<Object>) -> Scene {
    Scene::new(
        Space {
            x: 0,
            y: 0,
            width: w,
            height: h,
        },
        10,
        objects,
    )
    .expect("valid scene")
}

// ---- the scene fields -------------------------------------------------------

#[test]
fn turned_objects_keep_their_size_and_occupy_the_footprint() {
    let s = Scene::from_json(
        r#"{"space":{"width":60,"height":40},"objects":[
            {"id":"a","class":"A","x":0,"y":0,"width":20,"height":10,"turned":true},
            {"id":"b","class":"A","width":20,"height":10,"turnable":true},
            {"id":"w","class":"W","x":30,"y":30,"width":10,"height":30,"fixed":true,"turned":true}]}"#,
    )
    .expect("valid");
    let a = &s.objects[0];
    assert_eq!(
        (a.width, a.height, a.turned, a.turnable),
        (20, 10, true, false)
    );
    assert_eq!(a.footprint(), (10, 20));
    assert_eq!(a.rect(), Some(Rect::new(0, 0, 10, 20)));
    assert!(s.objects[1].turnable && !s.objects[1].turned);
    assert_eq!(s.objects[1].footprint(), (20, 10));
    // A fixed object may lie turned: 30 × 10 from (30, 30).
    assert_eq!(s.objects[2].rect(), Some(Rect::new(30, 30, 30, 10)));
    // Written back as read; false fields left out.
    let again = Scene::from_json(&s.to_json()).expect("round trip");
    assert_eq!(again, s);
    let text = s.to_json();
    assert_eq!(text.matches("\"turned\": true").count(), 2, "{text}");
    assert_eq!(text.matches("\"turnable\": true").count(), 1, "{text}");
    assert!(!text.contains("false"), "{text}");
}

#[test]
fn a_turned_object_is_checked_inside_the_space_and_for_overlaps_by_its_footprint() {
    // 10 × 30 turned is 30 wide: past a 20-wide space.
    let e = Scene::from_json(
        r#"{"space":{"width":20,"height":40},"objects":[
            {"class":"A","x":0,"y":0,"width":10,"height":30,"turned":true}]}"#,
    )
    .expect_err("outside");
    assert_eq!(
        (e.kind(), e.path()),
        (SceneErrorKind::Outside, "objects[0]")
    );
    // Turned, a at (0, 0) covers x 0..20: it overlaps b at (10, 0).
    let e = Scene::from_json(
        r#"{"space":{"width":40,"height":40},"objects":[
            {"id":"a","class":"A","x":0,"y":0,"width":10,"height":20,"turned":true},
            {"id":"b","class":"A","x":10,"y":0,"width":10,"height":10}]}"#,
    )
    .expect_err("overlap");
    assert_eq!(e.kind(), SceneErrorKind::Overlap);
}

#[test]
fn turned_on_an_unplaced_object_and_turnable_on_a_fixed_one_are_refused_by_field() {
    let e = Scene::from_json(
        r#"{"space":{"width":40,"height":40},"objects":[
            {"class":"A","x":0,"y":0,"width":10,"height":10},
            {"id":"b","class":"A","width":10,"height":20,"turned":true}]}"#,
    )
    .expect_err("turned, unplaced");
    assert_eq!(
        (e.kind(), e.path()),
        (SceneErrorKind::BadTurn, "objects[1].turned")
    );
    assert!(
        e.to_string().contains("`b` is turned but has no position"),
        "{e}"
    );
    let e = Scene::from_json(
        r#"{"space":{"width":40,"height":40},"objects":[
            {"id":"w","class":"W","x":0,"y":0,"width":10,"height":20,"fixed":true,"turnable":true}]}"#,
    )
    .expect_err("fixed, turnable");
    assert_eq!(
        (e.kind(), e.path()),
        (SceneErrorKind::BadTurn, "objects[0].turnable")
    );
    for (field, value) in [("turned", "1"), ("turnable", "\"yes\""), ("turned", "null")] {
        let text = format!(
            r#"{{"space":{{"width":40,"height":40}},"objects":[
                {{"class":"A","x":0,"y":0,"width":10,"height":20,"{field}":{value}}}]}}"#
        );
        let e = Scene::from_json(&text).expect_err("not a boolean");
        assert_eq!(e.kind(), SceneErrorKind::Json, "{field}: {value}");
        assert_eq!(e.path(), format!("objects[0].{field}"));
        assert!(e.to_string().contains("expected a boolean"), "{e}");
    }
}

#[test]
fn bad_turns_exit_1_naming_the_file_and_field() {
    let dir = scratch("turns-bad");
    let rules_file = write_file(&dir, "r.rcc", "rule a_west: DR_W(A, *)\n");
    let cases = [
        (
            r#"{"space":{"width":40,"height":40},"objects":[
                {"class":"A","width":10,"height":20,"turned":true}]}"#,
            "objects[0].turned",
        ),
        (
            r#"{"space":{"width":40,"height":40},"objects":[
                {"class":"A","x":0,"y":0,"width":10,"height":20,"turned":"yes"}]}"#,
            "objects[0].turned",
        ),
        (
            r#"{"space":{"width":40,"height":40},"objects":[
                {"class":"A","width":10,"height":20,"turnable":1}]}"#,
            "objects[0].turnable",
        ),
        (
            r#"{"space":{"width":40,"height":40},"objects":[
                {"class":"W","x":0,"y":0,"width":10,"height":20,"fixed":true,"turnable":true}]}"#,
            "objects[0].turnable",
        ),
    ];
    for (i, (text, field)) in cases.iter().enumerate() {
        let file = write_file(&dir, &format!("bad{i}.json"), text);
        let svg = dir.join(format!("bad{i}.svg"));
        let svg = svg.to_str().expect("utf-8");
        for cmd in [
            vec!["check", rules_file.as_str(), "--scene", file.as_str()],
            vec!["score", file.as_str(), "--rules", rules_file.as_str()],
            vec!["render", file.as_str(), "-o", svg],
        ] {
            let o = rccpack(&cmd);
            assert_eq!(o.status.code(), Some(1), "{cmd:?}: {}", stderr(&o));
            let err = stderr(&o);
            assert!(
                err.contains(&format!("bad{i}.json")) && err.contains(field),
                "{cmd:?}: {err}"
            );
            assert!(!err.contains("panicked"), "{err}");
        }
    }
}

// ---- relations and the evaluator ----------------------------------------------

fn rules(text: &str) -> RuleSet {
    parse_rules(text).expect("rules parse")
}

/// The hand table: `a` (A, 20 wide and 10 high) at (0, 0), `b` (B, 10×10)
/// at (10, 10), `c` (C, 10×10) at (0, 20). Turned, `a` covers
/// [0, 10]×[0, 20]: b touches its east side along part of it and c sits on
/// it; unturned it covers [0, 20]×[0, 10]: b sits on it and c is above it,
/// apart.
#[test]
fn relations_and_the_evaluator_read_the_footprint_hand_table() {
    let set = rules(
        "rule a_touches_b_west: EC_W(A, B)\n\
         rule a_flush_b_west: FL_W(A, B)\n\
         rule a_west_of_b: DR_W(A, B)\n\
         rule c_on_a: EC_N(C, A)\n\
         rule b_on_a: EC_N(B, A)\n\
         rule c_north_of_a: DR_N(C, A)\n",
    );
    let build = |turned: bool| {
        let mut a = Object::placed("a", "A", 0, 0, 20, 10);
        a.turned = turned;
        scene(
            60,
            40,
            vec![
                a,
                Object::placed("b", "B", 10, 10, 10, 10),
                Object::placed("c", "C", 0, 20, 10, 10),
            ],
        )
    };
    //           EC_W   FL_W   DR_W   c on a  b on a  DR_N(C, A)
    let table = [
        (true, [true, true, true, true, false, true]),
        (false, [false, false, false, false, true, true]),
    ];
    for (turned, want) in table {
        let s = build(turned);
        for contact in [Contact::Point, Contact::Edge] {
            let ev = evaluate(&s, &set, contact);
            let got: Vec<bool> = ev.rules.iter().map(|r| r.satisfied == r.subjects).collect();
            assert_eq!(got, want, "turned {turned}, {contact:?}");
        }
    }
}

/// A turned 40×20 (width 40, height 20) touches, flanks and aligns with
/// exactly what a 20×40 at the same place would, against every object
/// of a ring of neighbours, under every relation and both contact modes;
/// the evaluator's and `score --json`'s verdicts agree too.
#[test]
fn a_turned_40x20_touches_what_a_20x40_would() {
    // Around [40, 60]×[50, 90]: below, east, north (two), west, a
    // corner, and one far away.
    let neighbours = vec![
        Object::placed("n1", "N", 40, 40, 20, 10),
        Object::placed("n2", "N", 60, 50, 10, 20),
        Object::placed("n3", "N", 40, 90, 10, 10),
        Object::placed("n4", "N", 50, 90, 30, 10),
        Object::placed("n5", "N", 20, 50, 20, 20),
        Object::placed("n6", "N", 60, 40, 10, 10),
        Object::placed("n7", "N", 0, 0, 30, 10),
    ];
    let with = |o: Object| {
        let mut v = vec![o];
        v.extend(neighbours.iter().cloned());
        scene(100, 100, v)
    };
    // Turned, t covers [40, 60]×[50, 90], exactly like the upright one.
    let turned_scene = with(Object::placed("t", "T", 40, 50, 40, 20).with_turned());
    let upright_scene = with(Object::placed("t", "T", 40, 50, 20, 40));
    let (tr, ur) = (
        turned_scene.objects[0].rect().expect("placed"),
        upright_scene.objects[0].rect().expect("placed"),
    );
    assert_eq!(tr, ur);
    let mut touching = 0;
    for n in &neighbours {
        let r = n.rect().expect("placed");
        for contact in [Contact::Point, Contact::Edge] {
            assert_eq!(
                relation_bits(&tr, &r, contact),
                relation_bits(&ur, &r, contact)
            );
            touching += usize::from(
                Relation::ALL
                    .iter()
                    .filter(|rel| rel.name().starts_with("EC"))
                    .any(|rel| rccpack::relations::holds(*rel, &tr, &r, contact)),
            );
        }
    }
    assert!(touching >= 6, "the ring touches t: {touching}");
    let set = rules(
        "rule t_touches: EC_N(T, N) | EC_S(T, N) | EC_E(T, N) | EC_W(T, N)\n\
         rule t_flush: FL_E(T, N) | FL_W(T, N)\n\
         rule n_near_t: EC_N(N, T) | EC_S(N, T) | EC_E(N, T) | EC_W(N, T)\n\
         rule t_aligned: AL_S(T, N) | AL_N(T, N)\n",
    );
    for contact in [Contact::Point, Contact::Edge] {
        let a = evaluate(&turned_scene, &set, contact);
        let b = evaluate(&upright_scene, &set, contact);
        assert_eq!(a, b, "{contact:?}");
    }
    // And the command line's report.
    let dir = scratch("turns-40x20");
    let rules_file = write_file(
        &dir,
        "r.rcc",
        "rule n_near_t: EC_N(N, T) | EC_S(N, T) | EC_E(N, T) | EC_W(N, T)\n\
         rule t_flush: FL_E(T, N) | FL_W(T, N)\n",
    );
    let t = write_file(&dir, "turned.json", &turned_scene.to_json());
    let u = write_file(&dir, "upright.json", &upright_scene.to_json());
    let score = |f: &str| {
        let o = rccpack(&["score", f, "--rules", &rules_file, "--json"]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        stdout(&o)
    };
    assert_eq!(score(&t), score(&u));
    assert!(score(&t).contains("\"n_near_t\""));
    let o = rccpack(&["check", &rules_file, "--scene", &t]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn a_turned_object_is_drawn_with_its_footprint_and_a_mark() {
    let mut a = Object::placed("a", "A", 0, 0, 20, 10);
    a.turned = true;
    let s = scene(40, 40, vec![a, Object::placed("b", "A", 20, 0, 20, 10)]);
    let opts = RenderOptions {
        scale: 2.0,
        ..RenderOptions::default()
    };
    let svg = render_svg(&s, None, &opts);
    let group = |id: &str| {
        let start = svg
            .find(&format!("data-id=\"{id}\""))
            .unwrap_or_else(|| panic!("{id} drawn"));
        let end = start + svg[start..].find("</g>").expect("group closed");
        svg[start..end].to_string()
    };
    let (ga, gb) = (group("a"), group("b"));
    // 10 × 20 at scale 2: 20 wide, 40 high; b 40 wide, 20 high.
    assert!(ga.contains("width=\"20\" height=\"40\""), "{ga}");
    assert!(gb.contains("width=\"40\" height=\"20\""), "{gb}");
    assert!(ga.contains("turn-mark") && !gb.contains("turn-mark"));
    assert!(svg.contains("class=\"object movable turned\" data-id=\"a\""));
}

// ---- synthesis ------------------------------------------------------------------

/// The 30 × 30 box of docs/guide.md#objects-that-turn: four 20 × 10 blocks
/// and one 10 × 10. Lying flat, a 30-wide row holds one 20-wide block, so
/// three rows hold three: the fourth fits only when some stand on end
/// (the pinwheel).
fn pinwheel(turnable: bool) -> Scene {
    let mut objects: Vec<Object> = (0..4)
        .map(|i| {
            let mut o = Object::movable(&format!("l{i}"), "L", 20, 10);
            o.turnable = turnable;
            o
        })
        .collect();
    objects.push(Object::movable("s", "S", 10, 10));
    scene(30, 30, objects)
}

#[test]
fn a_box_that_fits_only_turned_is_proven_flat_and_packed_turned() {
    let none = RuleSet::default();
    let opts = SynthOptions::default();
    let flat = synthesize(&pinwheel(false), &none, &opts).expect("solve");
    assert_eq!(flat.status, Status::Infeasible);
    assert!(flat.conflict.expect("conflict").objects_cannot_fit);
    let problem = pinwheel(true);
    let r = synthesize(&problem, &none, &opts).expect("solve");
    assert_eq!(r.status, Status::Optimal);
    let sol = r.scene.expect("layout");
    verify_solution(&problem, &sol, &none, Contact::Point).expect("verified");
    let turned = sol.objects.iter().filter(|o| o.turned).count();
    assert!((1..=3).contains(&turned), "{}", sol.to_json());
    assert!(sol.objects.iter().all(|o| o.width == 20 || o.id == "s"));
    // Brute force agrees both ways.
    let bf = brute_force::solve(&pinwheel(false), &none, Contact::Point).expect("tiny");
    assert!(!bf.feasible);
    let bf = brute_force::solve(&problem, &none, Contact::Point).expect("tiny");
    assert!(bf.feasible);
}

#[test]
fn hard_orientation_rules_over_the_chosen_footprint() {
    // Two turnable 20×10 L blocks in a 20 × 20 box: flat they stack (one
    // on the other), turned they stand side by side. "Every L touches an
    // L on its east or west side" holds only turned.
    let set = rules("rule side_by_side hard: EC_E(L, L) | EC_W(L, L)\n");
    let mut objects = Vec::new();
    for i in 0..2 {
        let mut o = Object::movable(&format!("l{i}"), "L", 20, 10);
        o.turnable = true;
        objects.push(o);
    }
    let problem = scene(20, 20, objects);
    for contact in [Contact::Point, Contact::Edge] {
        let opts = SynthOptions {
            contact,
            ..SynthOptions::default()
        };
        let r = synthesize(&problem, &set, &opts).expect("solve");
        assert_eq!(r.status, Status::Optimal, "{contact:?}");
        let sol = r.scene.expect("layout");
        verify_solution(&problem, &sol, &set, contact).expect("verified");
        assert!(sol.objects.iter().all(|o| o.turned), "{}", sol.to_json());
        // Without the turn it is infeasible, and the rule is the conflict.
        let mut flat = problem.clone();
        for o in &mut flat.objects {
            o.turnable = false;
        }
        let r = synthesize(&flat, &set, &opts).expect("solve");
        assert_eq!(r.status, Status::Infeasible);
        assert_eq!(
            r.conflict.expect("conflict").hard_rules,
            vec!["side_by_side".to_string()]
        );
    }
}

#[test]
fn synth_writes_turned_in_the_layout_and_emits_the_orientation_variables() {
    let dir = scratch("turns-cli");
    let problem = write_file(&dir, "problem.json", &pinwheel(true).to_json());
    let rules_file = write_file(&dir, "none.rcc", "");
    let out = dir.join("layout.json");
    let o = rccpack(&[
        "synth",
        &problem,
        "--rules",
        &rules_file,
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let layout = Scene::from_json(&std::fs::read_to_string(&out).expect("written")).expect("valid");
    assert!(layout.objects.iter().any(|o| o.turned));
    assert!(layout
        .objects
        .iter()
        .filter(|o| o.class == "L")
        .all(|o| o.turnable));
    let flat = write_file(&dir, "flat.json", &pinwheel(false).to_json());
    let o = rccpack(&["synth", &flat, "--rules", &rules_file, "-o", "-"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let emit = dir.join("model.json");
    let o = rccpack(&[
        "synth",
        &problem,
        "--rules",
        &rules_file,
        "--emit",
        emit.to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let model: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&emit).expect("emitted")).expect("json");
    let turns: Vec<&serde_json::Value> = (model["vars"].as_array().expect("vars").iter())
        .filter(|v| v["axis"] == "turn")
        .collect();
    let ls = layout.objects.iter().filter(|o| o.class == "L").count();
    assert_eq!(
        turns.len(),
        ls,
        "one orientation variable per turnable block"
    );
    assert!(turns.iter().all(|v| v["ub"] == 1));
}

#[test]
fn sample_is_not_broken_by_turnable_objects() {
    // The box-packing problem with every movable block turnable (they
    // are square: nothing to turn) plus two turnable 20×10 blocks: the
    // sampler draws valid, distinct layouts with the best score of the
    // layouts it draws (orientations as given), each one verified.
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing");
    let mut problem =
        Scene::from_json(&std::fs::read_to_string(format!("{dir}/problem.json")).expect("read"))
            .expect("valid");
    for o in problem.objects.iter_mut().filter(|o| !o.fixed) {
        o.turnable = true;
    }
    for i in 0..2 {
        problem
            .objects
            .push(Object::movable(&format!("l{i}"), "L", 20, 10).with_turnable());
    }
    let set = rules("rule l_low: DR_S(L, R)\n");
    let opts = rccpack::SampleOptions {
        quality: rccpack::Quality::Optimum,
        seed: 3,
        ..rccpack::SampleOptions::default()
    };
    let layouts: Vec<Scene> = rccpack::sample(&problem, &set, &opts)
        .expect("sampler")
        .take(8)
        .collect::<Result<_, _>>()
        .expect("layouts");
    assert_eq!(layouts.len(), 8);
    let mut keys = std::collections::BTreeSet::new();
    for s in &layouts {
        verify_solution(&problem, s, &set, Contact::Point).expect("verified");
        assert_eq!(evaluate(s, &set, Contact::Point).score, 1.0);
        assert!(keys.insert(rccpack::sample::canonical_key(&problem, s)));
    }
}

/// The packing benchmark's inputs: problems that fit only turned, found by
/// the exhaustive cell search of `support::turn_packing` (no solver) and
/// kept in `tests/fixtures/turns/packings.json` (regenerate with
/// `RCCPACK_BLESS=1` only on purpose). On each, the engine proves that
/// the blocks do not fit flat, and packs them turned, optimal and
/// verified; brute force agrees where it can enumerate.
#[test]
fn packings_that_fit_only_turned_are_proven_flat_and_packed_turned() {
    use crate::support::turn_packing::{flat, packings};
    let found = packings(16);
    assert_eq!(found.len(), 16);
    let text = rccpack::scene::scenes_to_json(&found);
    let file = crate::support::path("tests/fixtures/turns/packings.json");
    if std::env::var_os("RCCPACK_BLESS").is_some() {
        std::fs::create_dir_all(file.parent().expect("folder")).expect("folder");
        std::fs::write(&file, &text).expect("written");
    }
    assert_eq!(
        std::fs::read_to_string(&file).expect("the fixture"),
        text,
        "the search's problems changed"
    );
    let none = RuleSet::default();
    let opts = SynthOptions::default();
    let mut by_brute_force = 0;
    for (i, problem) in found.iter().enumerate() {
        let r = synthesize(&flat(problem), &none, &opts).expect("solve");
        assert_eq!(r.status, Status::Infeasible, "packing {i} flat");
        assert!(r.conflict.expect("conflict").objects_cannot_fit);
        let r = synthesize(problem, &none, &opts).expect("solve");
        assert_eq!(r.status, Status::Optimal, "packing {i} turned");
        let sol = r.scene.expect("layout");
        verify_solution(problem, &sol, &none, Contact::Point).expect("verified");
        assert!(sol.objects.iter().any(|o| o.turned), "packing {i}");
        if let Ok(bf) = brute_force::solve(problem, &none, Contact::Point) {
            assert!(bf.feasible, "packing {i}");
            let bf = brute_force::solve(&flat(problem), &none, Contact::Point).expect("smaller");
            assert!(!bf.feasible, "packing {i}");
            by_brute_force += 1;
        }
    }
    assert!(by_brute_force >= 8, "{by_brute_force}");
}

// ---- the language and learning ---------------------------------------------------

#[test]
fn orientation_statements_parse_print_read_and_evaluate() {
    let text = "rule l_on_end: turned(L)\n\
                rule r_flat: !turned(R)\n\
                rule l_on_end_or_low: turned(L) | EC_S(L, W)\n\
                rule few_turned: at most 1 R: turned(R)\n";
    let set = rules(text);
    assert_eq!(rccpack::rules::print_rules(&set), text);
    let read: Vec<String> = set
        .rules
        .iter()
        .map(|r| rccpack::infer::statement_reading(r.scope, &r.formula))
        .collect();
    assert_eq!(read[0], "every L lies turned");
    assert_eq!(read[1], "no R lies turned");
    assert_eq!(read[3], "at most 1 R lies turned");
    // A square never lies turned: `turned` on a 10×10 is its footprint.
    let s = scene(
        80,
        40,
        vec![
            Object::placed("l1", "L", 0, 0, 20, 10).with_turned(),
            Object::placed("l2", "L", 20, 0, 20, 10),
            Object::placed("r1", "R", 50, 0, 10, 10).with_turned(),
            Object::placed("r2", "R", 60, 0, 10, 20).with_turned(),
            Object::fixed_at("w", "W", 0, 30, 80, 10),
        ],
    );
    let ev = evaluate(&s, &set, Contact::Point);
    let by = |name: &str| {
        let r = ev.rules.iter().find(|r| r.name == name).expect("rule");
        (r.satisfied, r.subjects)
    };
    assert_eq!(by("l_on_end"), (1, 2));
    assert_eq!(by("r_flat"), (1, 2), "r1 is square: not turned");
    assert_eq!(by("few_turned"), (1, 1));
    // Bad subjects are refused where they are written.
    for bad in [
        "rule x: turned(*)\n",
        "rule x: turned(@w)\n",
        "rule x: turned(A, B)\n",
    ] {
        assert!(parse_rules(bad).is_err(), "{bad}");
    }
    let mixed = parse_rules("rule x: turned(A) | EC_S(B, W)\n");
    assert!(mixed.is_err(), "one subject per rule");
}

/// Demonstrations of 3 L blocks (20 × 10, turnable) and 2 R blocks in a
/// 100 × 100 box, the Ls turned as `turned(d, i)` says.
fn orientation_demos(turned: impl Fn(usize, usize) -> bool) -> Vec<Scene> {
    (0..5)
        .map(|d| {
            let mut objects = Vec::new();
            let slot = |k: usize| {
                let k = (k + d * 2) % 9;
                (10 + 30 * (k % 3) as i64, 10 + 30 * (k / 3) as i64)
            };
            for i in 0..3 {
                let (x, y) = slot(i);
                let mut o = Object::placed(&format!("l{i}"), "L", x, y, 20, 10).with_turnable();
                o.turned = turned(d, i);
                objects.push(o);
            }
            for i in 0..2 {
                let (x, y) = slot(3 + i);
                objects.push(Object::placed(&format!("r{i}"), "R", x, y, 10, 10));
            }
            scene(100, 100, objects)
        })
        .collect()
}

#[test]
fn a_demonstrators_habit_of_standing_blocks_on_end_is_learned() {
    let params = rccpack::LearnParams::default();
    let names = |demos: &[Scene]| -> Vec<String> {
        rccpack::learn(demos, None, &params)
            .expect("learned")
            .rules()
            .rules
            .iter()
            .map(|r| r.name.clone())
            .collect()
    };
    let always = names(&orientation_demos(|_, _| true));
    assert!(always.contains(&"L_turned".to_string()), "{always:?}");
    assert!(!always.contains(&"L_not_turned".to_string()));
    let never = names(&orientation_demos(|_, _| false));
    assert!(never.contains(&"L_not_turned".to_string()), "{never:?}");
    // Half of them, as a coin would: neither.
    let half = names(&orientation_demos(|d, i| (d + i) % 2 == 0));
    assert!(
        !half
            .iter()
            .any(|n| n.starts_with("L_turned") || n.starts_with("L_not_turned")),
        "{half:?}"
    );
    // No class that turns: no orientation statement is even a candidate.
    let plain: Vec<Scene> = orientation_demos(|_, _| false)
        .into_iter()
        .map(|mut s| {
            for o in &mut s.objects {
                o.turnable = false;
            }
            s
        })
        .collect();
    let statements = rccpack::infer::templates::generate(&plain);
    assert!(statements.rules.iter().all(|r| !r.formula.mentions_turns()));
}

#[test]
fn a_learned_habit_is_kept_by_synthesis() {
    // Learned from demonstrations that stand every L on end, the rules
    // place a problem's turnable Ls turned.
    let demos = orientation_demos(|_, _| true);
    let learned = rccpack::learn(&demos, None, &rccpack::LearnParams::default()).expect("learned");
    let set = learned.rules();
    assert!(set.rules.iter().any(|r| r.name == "L_turned"));
    // 1× and 2× the demonstrations' blocks.
    for copies in 1..=2 {
        let mut problem = demos[0].clone();
        problem.objects = (0..copies)
            .flat_map(|k| {
                demos[0].objects.iter().map(move |o| Object {
                    id: format!("{}_{k}", o.id),
                    x: None,
                    y: None,
                    turned: false,
                    ..o.clone()
                })
            })
            .collect();
        let opts = SynthOptions {
            stop: rccpack::stop::Stop::never().with_nodes(200_000),
            ..SynthOptions::default()
        };
        let r = synthesize(&problem, &set, &opts).expect("solve");
        assert!(
            matches!(r.status, Status::Optimal | Status::Feasible),
            "{copies}×"
        );
        let sol = r.scene.expect("layout");
        verify_solution(&problem, &sol, &set, Contact::Point).expect("verified");
        let ls: Vec<&Object> = sol.objects.iter().filter(|o| o.class == "L").collect();
        assert_eq!(ls.len(), 3 * copies);
        assert!(ls.iter().all(|o| o.turned), "{copies}×: {}", sol.to_json());
    }
}

#[test]
fn a_layout_keeping_every_rule_is_optimal_over_every_orientation() {
    // Flat keeps every rule: the one model (an orientation variable per
    // turnable block) proves it optimal at once, over every orientation.
    let set = rules("rule l_west: DR_W(L, S)\nrule k_south: DR_S(K, S)\n");
    let mut objects = Vec::new();
    for i in 0..2 {
        objects.push(Object::movable(&format!("l{i}"), "L", 20, 10).with_turnable());
        objects.push(Object::movable(&format!("k{i}"), "K", 10, 30).with_turnable());
    }
    objects.push(Object::movable("s", "S", 10, 10));
    let problem = scene(80, 80, objects);
    let turning = synthesize(&problem, &set, &SynthOptions::default()).expect("solve");
    let flat = synthesize(
        &crate::support::turn_packing::flat(&problem),
        &set,
        &SynthOptions::default(),
    )
    .expect("solve");
    assert_eq!(turning.status, Status::Optimal);
    assert_eq!(turning.score_bound, Some(1.0));
    assert!(flat.stats.nodes > 0);
    assert_eq!(flat.status, Status::Optimal);
    verify_solution(
        &problem,
        turning.scene.as_ref().expect("layout"),
        &set,
        Contact::Point,
    )
    .expect("verified");
}

#[test]
fn orientation_choices_past_256_are_solved_by_the_model() {
    // 3 classes × 7 turnable blocks: 8³ = 512 orientation choices, past
    // what enumerating them tried; the model's orientation variables
    // solve it whatever the rules ask.
    let mut objects = Vec::new();
    for class in ["A", "B", "C"] {
        for i in 0..7 {
            objects.push(
                Object::movable(&format!("{}{i}", class.to_lowercase()), class, 20, 10)
                    .with_turnable(),
            );
        }
    }
    objects.push(Object::movable("s", "S", 10, 10));
    let problem = scene(200, 200, objects);
    let kept = rules("rule a_west: DR_W(A, S)\n");
    let r = synthesize(&problem, &kept, &SynthOptions::default()).expect("flat keeps every rule");
    assert_eq!(r.status, Status::Optimal);
    verify_solution(
        &problem,
        r.scene.as_ref().expect("layout"),
        &kept,
        Contact::Point,
    )
    .expect("verified");
    let on_end = rules("rule a_on_end: turned(A)\nrule b_flat: !turned(B)\n");
    let r = synthesize(&problem, &on_end, &SynthOptions::default()).expect("solved");
    assert_eq!(r.status, Status::Optimal);
    assert_eq!(r.evaluation.as_ref().map(|e| e.score), Some(1.0));
    let sol = r.scene.expect("layout");
    verify_solution(&problem, &sol, &on_end, Contact::Point).expect("verified");
    for o in &sol.objects {
        match o.class.as_str() {
            "A" => assert!(o.turned, "{}", o.id),
            "B" => assert!(!o.turned, "{}", o.id),
            _ => {}
        }
    }
}
