//! Learning (docs/guide.md#learning): the worked check, the null model against exact
//! enumeration, determinism across thread counts, the box-packing example
//! and typed errors for bad input.

use crate::support::formulas::atom;
use crate::support::table;
use rccpack::eval::Evaluator;
use rccpack::infer::templates::generate_set;
use rccpack::infer::Posterior;
use rccpack::infer::{learn, InferError, LearnParams, NullModel, Templates};
use rccpack::relations::{Contact, Dir, Kind, Relation};
use rccpack::rules::{parse_rules, Formula, Rule, RuleSet, Scope, Target};
use rccpack::scene::{scenes_from_json, Object, Scene};

fn obj(id: &str, class: &str, x: i64, y: i64, w: i64, h: i64, fixed: bool) -> Object {
    Object {
        id: id.into(),
        class: class.into(),
        x: Some(x),
        y: Some(y),
        width: w,
        height: h,
        fixed,
        turnable: false,
        turned: false,
    }
}

/// docs/guide.md#learning worked check: chance rates 0.4 / 0.01 / 0.3 with 4 / 4 / 3
/// objects; only the second rule is learned at cutoff 0.01.
#[test]
fn worked_check_of_spec_section_7() {
    let cases = [(0.4, 4u64), (0.01, 4), (0.3, 3)];
    let unnormalised = [0.0256, 1e-8, 0.027];
    let normalised = [0.0256 / 1.0256, 1e-8 / (1.0 + 1e-8), 0.027 / 1.027];
    let mut learned = Vec::new();
    for (i, &(q, n)) in cases.iter().enumerate() {
        let p = Posterior::new(q, 1e-9, n, 0.5);
        let l = 10f64.powf(p.log10_likelihood);
        assert!(
            (l - unnormalised[i]).abs() <= 1e-12 * unnormalised[i],
            "L[{i}] = {l}"
        );
        let post = p.written();
        assert!(
            (post - normalised[i]).abs() <= 1e-12 * normalised[i],
            "P[{i}] = {post}"
        );
        learned.push(p.learned(0.01));
        // The unnormalised product gives the same decision.
        assert_eq!(unnormalised[i] < 0.01, p.learned(0.01));
    }
    assert!((normalised[0] - 0.02496).abs() < 1e-5);
    assert!((normalised[2] - 0.02629).abs() < 1e-5);
    assert_eq!(learned, [false, true, false]);
}

/// One movable 10×10 `M` and one fixed 10×10 `F` in a 60×40 space.
fn small_demo(fixed_x: i64, fixed_y: i64) -> Scene {
    table(
        60,
        40,
        vec![
            obj("f", "F", fixed_x, fixed_y, 10, 10, true),
            obj("m", "M", 0, 30, 10, 10, false),
        ],
    )
}

/// The exact fraction of free grid positions of `m` where `f` holds.
fn exact_fraction(demo: &Scene, f: &Formula) -> f64 {
    let rules = RuleSet::new(vec![Rule::new("x", f.clone())]);
    let fixed = demo.objects[0].rect().unwrap();
    let (mut hits, mut total) = (0u32, 0u32);
    for kx in 0..=(60 - 10) / 10 {
        for ky in 0..=(40 - 10) / 10 {
            let mut s = demo.clone();
            s.objects[1].x = Some(kx * 10);
            s.objects[1].y = Some(ky * 10);
            if s.objects[1].rect().unwrap().interiors_overlap(&fixed) {
                continue;
            }
            total += 1;
            let ev = Evaluator::new(&s, &rules, Contact::Point);
            if ev.satisfies(1, &ev.compile(f)) {
                hits += 1;
            }
        }
    }
    f64::from(hits) / f64::from(total)
}

fn check_null_model(fixed_x: i64, fixed_y: i64) {
    let demo = small_demo(fixed_x, fixed_y);
    let statements = [
        atom("DR_N", "M", "F"),
        atom("EC_N", "M", "F"),
        Formula::Or(
            Dir::ALL
                .iter()
                .map(|&d| atom(Relation::new(Kind::EC, d), "M", "F"))
                .collect(),
        ),
    ];
    let set = RuleSet::new(
        statements
            .iter()
            .enumerate()
            .map(|(i, f)| Rule::new(format!("s{i}"), f.clone()))
            .collect(),
    );
    // Score the sampled scenes directly (the demonstration itself need not
    // satisfy the statements).
    let samples = 20_000;
    let model = NullModel::new(std::slice::from_ref(&demo), 7).unwrap();
    let mut hits = vec![0u32; statements.len()];
    for i in 0..samples {
        let s = model.scene(i).unwrap();
        assert_eq!(s.objects[0], demo.objects[0], "fixed objects stay");
        let m = s.objects[1].rect().unwrap();
        assert!(!m.interiors_overlap(&s.objects[0].rect().unwrap()));
        assert!(m.inside(&s.space.rect()));
        assert_eq!(m.x % 10, 0);
        assert_eq!(m.y % 10, 0);
        let ev = Evaluator::new(&s, &set, Contact::Point);
        for (k, f) in statements.iter().enumerate() {
            if ev.satisfies(1, &ev.compile(f)) {
                hits[k] += 1;
            }
        }
    }
    for (k, f) in statements.iter().enumerate() {
        let exact = exact_fraction(&demo, f);
        let est = f64::from(hits[k]) / samples as f64;
        let se = (exact * (1.0 - exact) / samples as f64).sqrt();
        assert!(
            (est - exact).abs() <= 4.0 * se,
            "statement {k}: sampled {est}, exact {exact}, se {se}"
        );
    }
}

/// DR_N, EC_N and "touches" chance rates agree with exact enumeration
/// (grid-aligned fixed object: the cell bitset).
#[test]
fn null_model_matches_exact_enumeration_on_grid() {
    check_null_model(20, 10);
}

/// The same with a fixed object off the grid (the checked scan).
#[test]
fn null_model_matches_exact_enumeration_off_grid() {
    check_null_model(25, 15);
}

/// The chance rate `q` reported by `learn` is the sampled fraction: with a
/// demonstration that satisfies DR_N(M, F), `q` lies within 4 standard
/// errors of the exact rate.
#[test]
fn learn_chance_rate_matches_exact_enumeration() {
    let mut demo = small_demo(20, 10);
    demo.objects[1].x = Some(20);
    demo.objects[1].y = Some(20); // on top of F: DR_N and EC_N hold
    let statements = [atom("DR_N", "M", "F"), atom("EC_N", "M", "F")];
    let set = RuleSet::new(vec![
        Rule::new("m_north", statements[0].clone()),
        Rule::new("m_on_top", statements[1].clone()),
    ]);
    let params = LearnParams {
        samples: 20_000,
        ..LearnParams::default()
    };
    let learned = learn(std::slice::from_ref(&demo), Some(&set), &params).unwrap();
    for (k, f) in statements.iter().enumerate() {
        let s = &learned.statements[k];
        assert!(s.candidate);
        let exact = exact_fraction(&demo, f);
        let se = (exact * (1.0 - exact) / 20_000.0).sqrt();
        let q = s.q.unwrap();
        assert!(
            (q - exact).abs() <= 4.0 * se,
            "{}: q {q}, exact {exact}",
            s.name
        );
    }
}

/// A fixed 10×10 `f` and two movable `M` of different sizes (10×10 and
/// 20×10) in a 70×40 space: the two placement orders differ.
fn scene_level_demo() -> Scene {
    table(
        70,
        40,
        vec![
            obj("f", "F", 30, 20, 10, 10, true),
            obj("m1", "M", 40, 20, 10, 10, false),
            obj("m2", "M", 0, 0, 20, 10, false),
        ],
    )
}

fn scene_level_statements() -> RuleSet {
    use rccpack::infer::templates::{atom as t_atom, touches};
    use rccpack::relations::Quant;
    let f = Target::Landmark("f".into());
    let any = Target::Any;
    RuleSet::new(vec![
        Rule::new("some_touch", touches("M", &f)).with_scope(Scope::Scene(Quant::Some)),
        Rule::new("none_touch", touches("M", &f)).with_scope(Scope::Scene(Quant::No)),
        Rule::new("both_touch", touches("M", &f)).with_scope(Scope::Scene(Quant::AtLeast(2))),
        Rule::new("one_east", t_atom(Kind::EC, Dir::E, "M", &any))
            .with_scope(Scope::Scene(Quant::AtMost(1))),
        Rule::new("some_flush_east", t_atom(Kind::FL, Dir::E, "M", &any))
            .with_scope(Scope::Scene(Quant::Some)),
    ])
}

/// The exact probability, under the null model of docs/guide.md#learning (a random order of
/// the movable objects, each at a uniformly random free grid position), that
/// each scene-level rule of `rules` holds.
fn exact_scene_rates(demo: &Scene, rules: &RuleSet) -> Vec<f64> {
    let space = demo.space.rect();
    let positions = |s: &Scene, i: usize| -> Vec<(i64, i64)> {
        let o = &s.objects[i];
        let mut out = Vec::new();
        for kx in 0..=(space.w - o.width) / s.grid {
            for ky in 0..=(space.h - o.height) / s.grid {
                let r = rccpack::scene::Rect::new(kx * s.grid, ky * s.grid, o.width, o.height);
                let free = s
                    .objects
                    .iter()
                    .enumerate()
                    .filter(|&(j, p)| j != i && p.is_placed())
                    .all(|(_, p)| !p.rect().unwrap().interiors_overlap(&r));
                if free {
                    out.push((r.x, r.y));
                }
            }
        }
        out
    };
    let mut rates = vec![0.0; rules.rules.len()];
    for order in [[1usize, 2], [2, 1]] {
        let mut s = demo.clone();
        for &i in &order {
            s.objects[i].x = None;
            s.objects[i].y = None;
        }
        let firsts = positions(&s, order[0]);
        for &(x, y) in &firsts {
            let mut s1 = s.clone();
            s1.objects[order[0]].x = Some(x);
            s1.objects[order[0]].y = Some(y);
            let seconds = positions(&s1, order[1]);
            for &(x2, y2) in &seconds {
                let mut s2 = s1.clone();
                s2.objects[order[1]].x = Some(x2);
                s2.objects[order[1]].y = Some(y2);
                let ev = Evaluator::new(&s2, rules, Contact::Point);
                let w = 0.5 / firsts.len() as f64 / seconds.len() as f64;
                for (k, r) in rules.rules.iter().enumerate() {
                    if ev.evaluate_rule(r).satisfied == 1 {
                        rates[k] += w;
                    }
                }
            }
        }
    }
    rates
}

/// docs/guide.md#learning: the chance rate of a scene-level statement is the fraction of
/// null scenes in which it holds — checked against exact enumeration of the
/// null model on a tiny scene, both through the null model's counts and
/// through `learn`'s reported `q` (with `n = d`, `p = max(0.5 / d_r, q)`).
#[test]
fn scene_level_chance_rate_matches_exact_enumeration() {
    let demo = scene_level_demo();
    let rules = scene_level_statements();
    let exact = exact_scene_rates(&demo, &rules);
    assert!(exact.iter().all(|&e| e > 0.0 && e < 1.0), "{exact:?}");
    let samples = 20_000;
    let mut classes = rccpack::relations::ClassIndex::of_scene(&demo);
    classes.intern_landmark("f");
    let compiled: Vec<rccpack::eval::CompiledRule> = rules
        .rules
        .iter()
        .map(|r| rccpack::eval::CompiledRule::compile(r, &mut classes.clone()))
        .collect();
    let model = NullModel::new(std::slice::from_ref(&demo), 11).unwrap();
    let counts = model
        .count(samples, &classes, &compiled, Contact::Point)
        .unwrap();
    for (k, r) in rules.rules.iter().enumerate() {
        let est = counts[k] as f64 / samples as f64;
        let se = (exact[k] * (1.0 - exact[k]) / samples as f64).sqrt();
        assert!(
            (est - exact[k]).abs() <= 4.0 * se,
            "{}: sampled {est}, exact {}, se {se}",
            r.name,
            exact[k]
        );
    }
    // Through `learn`: the demonstration satisfies some_touch, one_east
    // and some_flush_east (m1 lies flush on f's east side; m2 is alone).
    let learned = learn(
        std::slice::from_ref(&demo),
        Some(&rules),
        &LearnParams {
            samples,
            seed: 11,
            ..LearnParams::default()
        },
    )
    .unwrap();
    let cands: Vec<&str> = learned
        .statements
        .iter()
        .filter(|s| s.candidate)
        .map(|s| s.name.as_str())
        .collect();
    assert_eq!(cands, ["some_touch", "one_east", "some_flush_east"]);
    for (k, s) in learned.statements.iter().enumerate() {
        assert_eq!(s.n, 1, "n = d for a scene-level statement");
        if let Some(q) = s.q {
            assert_eq!(s.satisfied, Some(counts[k]), "the same null scenes");
            assert_eq!(q, counts[k] as f64 / samples as f64);
            let p = s.posterior.unwrap().p;
            assert_eq!(p, q.max(0.5 / samples as f64));
        }
    }
    assert_eq!(learned.scene_epsilon, 0.5 / samples as f64);
}

/// A broken scene-level statement names its demonstration, and an object
/// only where one is to blame: for `no`, the first object that satisfies
/// the formula; for `some`, none.
#[test]
fn broken_scene_level_statements_name_the_demonstration() {
    let mut other = scene_level_demo();
    other.objects[1].x = Some(60); // m1 leaves f: nothing touches f
    other.objects[1].y = Some(30);
    let demos = [scene_level_demo(), other];
    let rules = scene_level_statements();
    let learned = learn(
        &demos,
        Some(&rules),
        &LearnParams {
            samples: 20,
            ..LearnParams::default()
        },
    )
    .unwrap();
    let by = |name: &str| {
        learned
            .statements
            .iter()
            .find(|s| s.name == name)
            .unwrap()
            .broken_by
            .clone()
    };
    let prov = |demo: usize, object: Option<&str>| {
        Some(rccpack::infer::Provenance {
            demo,
            object: object.map(String::from),
        })
    };
    assert_eq!(by("some_touch"), prov(1, None));
    assert_eq!(by("none_touch"), prov(0, Some("m1")));
    assert_eq!(by("both_touch"), prov(0, None));
    assert_eq!(by("one_east"), None);
    let report: serde_json::Value = serde_json::from_str(&learned.report_json()).unwrap();
    let st = &report["statements"];
    assert_eq!(st[0]["broken_by"], serde_json::json!({"demo": 1}));
    assert_eq!(
        st[1]["broken_by"],
        serde_json::json!({"demo": 0, "object": "m1"})
    );
    assert_eq!(st[0]["scope"], "some");
    assert_eq!(st[2]["scope"], "at least 2");
    assert_eq!(st[3]["n"], 2);
    assert_eq!(
        st[0]["formula"],
        "some M: EC_N(M, @f) | EC_S(M, @f) | EC_E(M, @f) | EC_W(M, @f)"
    );
    assert_eq!(st[0]["english"], "at least one M touches f");
}

/// A given statement naming a landmark that some demonstration lacks is bad
/// input naming the rule, the id and the demonstration.
#[test]
fn statement_naming_an_absent_landmark_is_an_error() {
    let demos = synthetic_demos();
    let f = Target::Landmark("nope".into());
    let set = RuleSet::new(vec![Rule::new(
        "x",
        rccpack::infer::templates::touches("B", &f),
    )]);
    let e = err(&demos, Some(&set));
    assert_eq!(
        e.to_string(),
        "rule `x` names landmark `@nope`, which is not a fixed object of demonstration [0]"
    );
}

/// Three small demonstrations: B north of R, everything inside the walls.
fn synthetic_demos() -> Vec<Scene> {
    let walls = |v: &mut Vec<Object>| {
        v.push(obj("ws", "W", 40, 40, 80, 10, true));
        v.push(obj("wn", "W", 40, 110, 80, 10, true));
        v.push(obj("ww", "W", 40, 50, 10, 60, true));
        v.push(obj("we", "W", 110, 50, 10, 60, true));
    };
    let layouts: [&[(&str, i64, i64)]; 3] = [
        &[("R", 50, 50), ("R", 70, 50), ("B", 50, 90), ("B", 70, 90)],
        &[
            ("R", 50, 50),
            ("B", 90, 90),
            ("B", 70, 90),
            ("R", 90, 50),
            ("R", 50, 70),
        ],
        &[("R", 70, 50), ("B", 50, 70), ("B", 50, 90)],
    ];
    layouts
        .iter()
        .map(|l| {
            let mut v = Vec::new();
            walls(&mut v);
            for (i, &(c, x, y)) in l.iter().enumerate() {
                v.push(obj(&format!("{c}{i}"), c, x, y, 20, 20, false));
            }
            table(160, 160, v)
        })
        .collect()
}

/// Same seed ⇒ identical result, `.rcc` text and report with 1 and with 2
/// threads.
#[test]
fn same_seed_same_output_with_one_and_two_threads() {
    let demos = synthetic_demos();
    let params = LearnParams {
        samples: 500,
        seed: 42,
        ..LearnParams::default()
    };
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| learn(&demos, None, &params).unwrap())
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one, two);
    assert_eq!(one.to_rcc(), two.to_rcc());
    assert_eq!(one.report_json(), two.report_json());
    // The second-edition templates are in use, scene-level ones included.
    assert!(one
        .statements
        .iter()
        .any(|s| s.scope.is_scene() && s.candidate && s.satisfied.is_some()));
    assert!(one.statements.iter().any(|s| s.name == "B_row"));
    // And a different seed gives different chance counts.
    let other = learn(&demos, None, &LearnParams { seed: 43, ..params }).unwrap();
    assert_ne!(
        one.statements
            .iter()
            .map(|s| s.satisfied)
            .collect::<Vec<_>>(),
        other
            .statements
            .iter()
            .map(|s| s.satisfied)
            .collect::<Vec<_>>()
    );
}

/// The bundled example with the second-edition templates: the same output
/// with 1 and 2 threads.
#[test]
fn box_packing_same_output_with_one_and_two_threads() {
    let demos = box_packing_demos();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| learn(&demos, None, &LearnParams::default()).unwrap())
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one, two);
    assert_eq!(one.report_json(), two.report_json());
}

/// The learned file parses back to the same rules, strongest first, with
/// posteriors below the cutoff.
#[test]
fn learned_file_parses_back() {
    let demos = synthetic_demos();
    let params = LearnParams {
        templates: Templates::Second,
        ..LearnParams::default()
    };
    let learned = learn(&demos, None, &params).unwrap();
    let text = learned.to_rcc();
    let parsed = parse_rules(&text).unwrap();
    assert!(parsed.same_rules(&learned.rules()), "{text}");
    assert!(!parsed.rules.is_empty());
    let ps: Vec<f64> = parsed
        .rules
        .iter()
        .map(|r| match r.strength {
            rccpack::rules::Strength::P(p) => p,
            _ => panic!("p modifier expected"),
        })
        .collect();
    assert!(ps.windows(2).all(|w| w[0] <= w[1]), "strongest first");
    assert!(ps.iter().all(|&p| p > 0.0 && p < 0.01));
    // B north of R and inside the walls are among them.
    let names: Vec<&str> = parsed.rules.iter().map(|r| r.name.as_str()).collect();
    for n in ["B_dr_n_R", "B_inside_W", "R_inside_W"] {
        assert!(names.contains(&n), "{n} not learned:\n{text}");
    }
    // The report holds every statement.
    let report: serde_json::Value = serde_json::from_str(&learned.report_json()).unwrap();
    assert_eq!(
        report["statements"].as_array().unwrap().len(),
        learned.statements.len()
    );
}

/// Generated template names are readable identifiers, unique, with the
/// first edition's shapes present in every edition and the second
/// edition's shapes present from the second on (docs/guide.md#learning).
#[test]
fn template_names_are_readable() {
    let demos = synthetic_demos();
    for which in [Templates::First, Templates::Second, Templates::Third] {
        let set = generate_set(&demos, which);
        let names: Vec<&str> = set.rules.iter().map(|r| r.name.as_str()).collect();
        for n in [
            "B_dr_n_R",
            "B_ec_s_B",
            "B_touches_B",
            "B_inside_W",
            "B_not_dr_e_any",
            "B_corner",
            "R_touches_any",
        ] {
            assert!(names.contains(&n), "{n} missing");
        }
        assert!(!names.iter().any(|n| n.starts_with("W_")), "W is fixed");
        assert!(names
            .iter()
            .all(|n| rccpack::infer::templates::is_identifier(n)));
        let mut uniq = names.clone();
        uniq.sort();
        uniq.dedup();
        assert_eq!(uniq.len(), names.len());
        let second = [
            "B_fl_n_R",
            "B_touches_flush_B",
            "B_contacts_flush_B",
            "R_apart_B",
            "B_row",
            "B_column",
            "B_neighbour_ew",
            "B_neighbour_ns",
            "B_some_touch_ws",
            "R_none_touch_we",
        ];
        match which {
            // 2 movable subjects × 4 targets (B, R, W, *) × (12 + 2) + 2 corners.
            Templates::First => {
                assert_eq!(names.len(), 2 * 4 * 14 + 2);
                assert!(second.iter().all(|n| !names.contains(n)));
                assert!(set.rules.iter().all(|r| r.scope == Scope::Each));
            }
            // … + 2 × 4 × (4 FL + flush + contacts flush + apart)
            //   + 2 × (row, column, 2 neighbours) + 2 × 4 walls × (some, no).
            Templates::Second => {
                assert_eq!(names.len(), 2 * 4 * 14 + 2 + 2 * 4 * 7 + 2 * 4 + 2 * 4 * 2);
                for n in second {
                    assert!(names.contains(&n), "{n} missing");
                }
            }
            // … + 2 × (one group, row, column, block), at the end of each
            // subject's statements.
            Templates::Third => {
                assert_eq!(
                    names.len(),
                    2 * 4 * 14 + 2 + 2 * 4 * 7 + 2 * 4 + 2 * 4 * 2 + 2 * 4
                );
                for n in second.iter().chain(&[
                    "B_one_group",
                    "B_one_row",
                    "R_one_column",
                    "R_one_block",
                ]) {
                    assert!(names.contains(n), "{n} missing");
                }
                let old = generate_set(&demos, Templates::Second);
                let kept: Vec<&str> = set
                    .rules
                    .iter()
                    .filter(|r| !r.is_group())
                    .map(|r| r.name.as_str())
                    .collect();
                let old: Vec<&str> = old.rules.iter().map(|r| r.name.as_str()).collect();
                assert_eq!(kept, old, "the third edition keeps the second, in order");
            }
        }
    }
}

/// The second edition keeps every first-edition statement (docs/guide.md#learning: "it must
/// keep these"), with the same name, scope and formula, in the same
/// relative order.
#[test]
fn second_edition_templates_keep_the_first() {
    for demos in [synthetic_demos(), box_packing_demos()] {
        let first = generate_set(&demos, Templates::First);
        let second = generate_set(&demos, Templates::Second);
        let positions: Vec<usize> = first
            .rules
            .iter()
            .map(|r| {
                second
                    .rules
                    .iter()
                    .position(|s| s.same_rule(r))
                    .unwrap_or_else(|| panic!("{} missing", r.name))
            })
            .collect();
        assert!(positions.windows(2).all(|w| w[0] < w[1]));
        // No two statements share scope and formula.
        let mut seen = std::collections::HashSet::new();
        for r in &second.rules {
            assert!(
                seen.insert((r.scope, r.formula.clone())),
                "{} repeats",
                r.name
            );
        }
    }
}

/// Landmark templates use the fixed objects present, fixed, with that id in
/// every demonstration, whose id is an identifier.
#[test]
fn landmarks_are_the_shared_fixed_objects() {
    let mut demos = synthetic_demos();
    // `wn` has another id in demonstration 1, `we` is missing from 2, and
    // demonstration 0 has an extra wall with an id that is no identifier.
    demos[1].objects[1].id = "wn1".into();
    demos[2].objects.remove(3);
    demos[0]
        .objects
        .push(obj("w-x", "W", 140, 140, 10, 10, true));
    assert_eq!(
        rccpack::infer::templates::demo_landmarks(&demos),
        ["ws", "ww"]
    );
    let set = generate_set(&demos, Templates::Second);
    let lm: Vec<String> = set.landmarks();
    assert_eq!(lm, ["ws", "ww"]);
    let scene_level: Vec<&str> = set
        .rules
        .iter()
        .filter(|r| r.scope.is_scene())
        .map(|r| r.name.as_str())
        .collect();
    assert_eq!(
        scene_level,
        [
            "R_some_touch_ws",
            "R_none_touch_ws",
            "R_some_touch_ww",
            "R_none_touch_ww",
            "B_some_touch_ws",
            "B_none_touch_ws",
            "B_some_touch_ww",
            "B_none_touch_ww"
        ]
    );
}

// ---- the bundled example ---------------------------------------------------

fn box_packing_demos() -> Vec<Scene> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/box-packing/demos.json"
    );
    let text = std::fs::read_to_string(path).expect("examples/box-packing/demos.json");
    scenes_from_json(&text).unwrap()
}

/// On `examples/box-packing/demos.json`, with generated templates of both
/// editions, every one of the thesis's 12 pilot rules is learned at the
/// default cutoff.
#[test]
fn box_packing_example_learns_the_pilot_rules() {
    let demos = box_packing_demos();
    for which in [Templates::Second, Templates::First] {
        box_packing_learns_the_pilot_rules(&demos, which);
    }
}

fn box_packing_learns_the_pilot_rules(demos: &[Scene], which: Templates) {
    let params = LearnParams {
        templates: which,
        ..LearnParams::default()
    };
    let learned = learn(demos, None, &params).unwrap();
    let names: Vec<&str> = learned
        .order
        .iter()
        .map(|&k| learned.statements[k].name.as_str())
        .collect();
    let mut pilot = vec!["B_dr_n_R", "G_dr_e_R", "G_dr_e_B"];
    let per_class = [
        "B_touches_B",
        "R_touches_R",
        "G_touches_G",
        "B_corner",
        "R_corner",
        "G_corner",
        "B_inside_W",
        "R_inside_W",
        "G_inside_W",
    ];
    pilot.extend(per_class);
    let missing: Vec<&&str> = pilot.iter().filter(|n| !names.contains(n)).collect();
    assert!(
        missing.is_empty(),
        "not learned: {missing:?}\n{}",
        learned.to_rcc()
    );
    // The learned rules score 1 on every demonstration; so does the file,
    // which parses back to them.
    let rules = learned.rules();
    for d in demos {
        assert_eq!(
            rccpack::eval::evaluate(d, &rules, Contact::Point).score,
            1.0
        );
    }
    let parsed = parse_rules(&learned.to_rcc()).unwrap();
    assert!(parsed.same_rules(&rules));
}

// ---- bad input -------------------------------------------------------------

fn err(demos: &[Scene], set: Option<&RuleSet>) -> InferError {
    learn(
        demos,
        set,
        &LearnParams {
            samples: 10,
            ..LearnParams::default()
        },
    )
    .unwrap_err()
}

#[test]
fn empty_demonstrations_are_an_error() {
    let e = err(&[], None);
    assert_eq!(e, InferError::NoDemonstrations);
    assert!(e.to_string().contains("no demonstrations"), "{e}");
}

#[test]
fn incomplete_demonstration_is_an_error() {
    let mut demos = synthetic_demos();
    demos[1].objects[5].x = None;
    demos[1].objects[5].y = None;
    let e = err(&demos, None);
    assert!(matches!(
        e,
        InferError::IncompleteDemonstration { demo: 1, .. }
    ));
    assert_eq!(
        e.to_string(),
        "demonstration [1] is incomplete: object `B1` has no position; every object of a demonstration must be placed"
    );
}

#[test]
fn demonstrations_with_different_spaces_are_an_error() {
    let mut demos = synthetic_demos();
    demos[2].space.width = 200;
    let e = err(&demos, None);
    assert_eq!(
        e.to_string(),
        "demonstration [2] has space 0,0 200x160, but demonstration [0] has space 0,0 160x160; all demonstrations must share one space"
    );
}

#[test]
fn statement_naming_an_absent_class_is_an_error() {
    let demos = synthetic_demos();
    let set = RuleSet::new(vec![Rule::new("q_north", atom("DR_N", "B", "Q"))]);
    let e = err(&demos, Some(&set));
    assert_eq!(
        e.to_string(),
        "rule `q_north` names class `Q`, which no demonstration has (classes: W, R, B)"
    );
}

/// A demonstration placed off the grid whose objects fit nowhere on it:
/// two 15-wide objects in a 30-wide space have only grid x ∈ {0, 10}.
#[test]
fn unplaceable_objects_are_an_error() {
    let demo = table(
        30,
        10,
        vec![
            obj("a", "M", 0, 0, 15, 10, false),
            obj("b", "M", 15, 0, 15, 10, false),
        ],
    );
    let e = err(std::slice::from_ref(&demo), None);
    assert!(matches!(e, InferError::CannotPlace { demo: 0, .. }), "{e}");
    let text = e.to_string();
    assert!(
        text.starts_with("the null model cannot place object `")
            && text.ends_with("of demonstration [0] at random: no free grid position found in 1000 tries, 100 times over"),
        "{text}"
    );
}

#[test]
fn bad_parameters_name_the_parameter() {
    let demos = synthetic_demos();
    let cases: [(LearnParams, (&str, &str)); 5] = [
        (
            LearnParams {
                cutoff: 1.5,
                ..Default::default()
            },
            ("cutoff", "1.5"),
        ),
        (
            LearnParams {
                cutoff: 0.0,
                ..Default::default()
            },
            ("cutoff", "0"),
        ),
        (
            LearnParams {
                samples: 0,
                ..Default::default()
            },
            ("samples", "0"),
        ),
        (
            LearnParams {
                prior: 1.0,
                ..Default::default()
            },
            ("prior", "1"),
        ),
        (
            LearnParams {
                epsilon: Some(f64::NAN),
                ..Default::default()
            },
            ("epsilon", "NaN"),
        ),
    ];
    for (p, (name, bad)) in cases {
        match learn(&demos, None, &p).unwrap_err() {
            InferError::BadParameter { param, value, .. } => {
                assert_eq!((param, value.as_str()), (name, bad));
            }
            e => panic!("expected BadParameter for {name}, got {e:?}"),
        }
    }
}

/// A learned scene-level rule is written with its `Q A:` after the head
/// (comments and line wrapping kept), exactly once.
#[test]
fn learned_scene_level_rules_are_written_with_their_quantifier() {
    use rccpack::infer::statement_text;
    use rccpack::relations::Quant;
    use rccpack::rules::print_rule;
    let f = Target::Landmark("w_south".into());
    let mut rule = Rule::new(
        "R_some_touch_w_south",
        rccpack::infer::templates::touches("R", &f),
    )
    .with_scope(Scope::Scene(Quant::Some))
    .with_strength(rccpack::rules::Strength::P(1e-10));
    rule.comments = vec!["at least one R touches w_south".into(), "a: b".into()];
    let text = print_rule(&rule);
    assert!(
        text.starts_with(
            "# at least one R touches w_south\n# a: b\nrule R_some_touch_w_south p 1e-10: some R: EC_N(R, @w_south)"
        ),
        "{text}"
    );
    assert_eq!(text.matches("some R:").count(), 1);
    assert_eq!(
        print_rule(&rule.clone().with_scope(Scope::Each)),
        rccpack::rules::print_rule(&rule.with_scope(Scope::Each))
    );
    assert_eq!(
        statement_text(Scope::Scene(Quant::AtLeast(2)), &atom("FL_N", "G", "G")),
        "at least 2 G: FL_N(G, G)"
    );
}
