//! Fuzz harnesses, shared by the cargo-fuzz targets in `fuzz/`
//! and by `tests/fuzz_replay.rs`, which replays every committed corpus and
//! regression file on stable Rust.
//!
//! Each harness takes arbitrary bytes and returns normally for every input
//! on which the program behaves as the docs say; a panic (including a failed
//! assertion here) is a bug. Compiled only with the `fuzzing` feature.
//!
//! | harness | input | checks |
//! |---|---|---|
//! | [`scene`] | scene / demonstrations JSON | no panic; a valid scene round-trips through save/load; relations agree with the table; evaluation and rendering do not panic; scores in `[0, 1]` |
//! | [`rules`] | `.rcc` text | no panic; every error span inside the input; parse → print → parse gives the same rules; check and evaluate against a small scene |
//! | [`learn`] | structured (`arbitrary`) demonstrations | the learned file parses and every demonstration satisfies every learned rule |
//! | [`synth`] | structured tiny problem and rules, coordinates also extreme | on success `verify` passes and the score equals brute force's optimum; on refusal a typed error |
//! | [`studio`] (also feature `studio`) | requests (method, path, body) | a status code below 500, never a panic, nothing written outside the task folder |

use crate::eval::evaluate;
use crate::relations::{relation_bits, Contact, Quant, Relation};
use crate::rules::{
    check_classes, parse_rules, print_rules, Atom, Formula, Rule, RuleSet, Scope, Strength, Target,
};
use crate::scene::{scenes_from_json, scenes_to_json, Object, Scene, Space};
use arbitrary::{Result as AResult, Unstructured};

// ---- scene -----------------------------------------------------------------

/// A fixed rule set over a scene's classes: every relation with every
/// quantifier against `*`, the first class and a landmark, plus a
/// scene-level rule, for the first two classes.
fn fixed_rules(scene: &Scene) -> RuleSet {
    let classes = scene.classes();
    let mut rules = Vec::new();
    let landmark = scene.objects.iter().find(|o| o.fixed).map(|o| o.id.clone());
    for (ci, subject) in classes.iter().take(2).enumerate() {
        let target = classes[0].to_string();
        let quants = [
            Quant::Every,
            Quant::Some,
            Quant::No,
            Quant::AtLeast(2),
            Quant::AtMost(1),
        ];
        for (ri, rel) in Relation::ALL.into_iter().enumerate() {
            let q = quants[ri % quants.len()];
            let mut atoms = vec![
                Formula::Atom(Atom::quantified(rel, *subject, q, Target::Any)),
                Formula::Atom(Atom::new(rel, *subject, Target::Class(target.clone()))),
            ];
            if let Some(id) = &landmark {
                atoms.push(Formula::Atom(Atom::new(
                    rel,
                    *subject,
                    Target::Landmark(id.clone()),
                )));
            }
            let f = if ri % 2 == 0 {
                Formula::Or(atoms)
            } else {
                Formula::not(Formula::And(atoms))
            };
            let strength = match ri % 3 {
                0 => Strength::Hard,
                1 => Strength::Weight(1.5),
                _ => Strength::P(0.01),
            };
            rules.push(Rule::new(format!("r{ci}_{ri}"), f).with_strength(strength));
        }
        let f = Formula::Atom(Atom::new(
            Relation::ALL[ci],
            *subject,
            Target::Class(subject.to_string()),
        ));
        rules.push(Rule::new(format!("s{ci}"), f).with_scope(Scope::Scene(Quant::AtLeast(1))));
    }
    RuleSet::new(rules)
}

/// Everything a valid scene must survive.
fn check_valid_scene(s: &Scene) {
    let again = Scene::from_json(&s.to_json()).expect("a saved valid scene loads again");
    assert_eq!(&again, s, "save/load round trip");
    // Relations: the fast bit path agrees with the table's conditions.
    let rects: Vec<_> = s.objects.iter().filter_map(Object::rect).take(24).collect();
    for contact in Contact::ALL {
        for a in &rects {
            for b in &rects {
                let bits = relation_bits(a, b, contact);
                for rel in Relation::ALL {
                    assert_eq!(
                        bits & rel.bit() != 0,
                        rel.def().holds(a, b, contact),
                        "{rel} on {a:?} {b:?} ({contact})"
                    );
                }
            }
        }
    }
    if s.objects.len() <= 64 {
        let rules = fixed_rules(s);
        for contact in Contact::ALL {
            let e = evaluate(s, &rules, contact);
            assert!((0.0..=1.0).contains(&e.score), "score {}", e.score);
            assert!(e.satisfied_weight <= e.total_weight + 1e-9);
            for r in &e.rules {
                assert!(r.satisfied <= r.subjects.max(1));
            }
            let _ = serde_json::to_string(&e).expect("an evaluation serialises");
        }
        let svg =
            crate::render::render_svg(s, Some(&rules), &crate::render::RenderOptions::default());
        assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"));
    }
}

/// Bytes → scene and demonstrations JSON → validate → relations →
/// evaluate a fixed rule set; a valid scene round-trips.
pub fn scene(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Scene::from_json(text) {
        Ok(s) => check_valid_scene(&s),
        Err(e) => {
            let _ = e.to_string();
        }
    }
    match scenes_from_json(text) {
        Ok(scenes) => {
            let again = scenes_from_json(&scenes_to_json(&scenes)).expect("saved scenes load");
            assert_eq!(again, scenes, "demonstrations round trip");
            for s in &scenes {
                check_valid_scene(s);
            }
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
}

// ---- rules -----------------------------------------------------------------

/// The small scene the `rules` harness checks against: classes R, G, B, W
/// with a fixed wall `w` (a landmark).
fn small_scene() -> Scene {
    Scene::from_json(
        r#"{"space":{"width":60,"height":60},"grid":10,"objects":[
        {"id":"w","class":"W","x":0,"y":0,"width":60,"height":10,"fixed":true},
        {"id":"r1","class":"R","x":0,"y":10,"width":10,"height":10},
        {"id":"r2","class":"R","x":10,"y":10,"width":10,"height":10},
        {"id":"g1","class":"G","x":30,"y":10,"width":20,"height":10},
        {"id":"b1","class":"B","x":0,"y":20,"width":10,"height":10},
        {"id":"b2","class":"B","width":10,"height":10}]}"#,
    )
    .unwrap_or_else(|e| unreachable!("the built-in scene is valid: {e}"))
}

fn spans_inside(e: &crate::rules::RulesError, src: &str) {
    assert!(!e.diagnostics.is_empty(), "an error has a diagnostic");
    for d in &e.diagnostics {
        assert!(
            d.span.start <= d.span.end && d.span.end <= src.len(),
            "span {:?} outside the input of {} bytes: {}",
            d.span,
            src.len(),
            d.message
        );
    }
    let _ = e.render("fuzz.rcc", src, false);
}

/// Bytes → parse → check against a small scene → print → re-parse equal.
pub fn rules(data: &[u8]) {
    let Ok(src) = std::str::from_utf8(data) else {
        return;
    };
    let set = match parse_rules(src) {
        Ok(set) => set,
        Err(e) => return spans_inside(&e, src),
    };
    let printed = print_rules(&set);
    let again = match parse_rules(&printed) {
        Ok(a) => a,
        Err(e) => {
            panic!("printed rules do not parse: {e}\n--- input\n{src}\n--- printed\n{printed}")
        }
    };
    assert!(
        set.same_rules(&again),
        "print/parse round trip changed the rules\n--- input\n{src}\n--- printed\n{printed}"
    );
    assert_eq!(print_rules(&again), printed, "printing is a fixed point");
    let scene = small_scene();
    if let Err(e) = check_classes(&set, &scene) {
        spans_inside(&e, src);
    }
    for contact in Contact::ALL {
        let e = evaluate(&scene, &set, contact);
        assert!((0.0..=1.0).contains(&e.score), "score {}", e.score);
    }
}

// ---- structured inputs -----------------------------------------------------

const CLASSES: [&str; 3] = ["A", "B", "W"];

fn quant(u: &mut Unstructured) -> AResult<Quant> {
    Ok(match u.int_in_range(0..=5)? {
        0 => Quant::Every,
        1 => Quant::Some,
        2 => Quant::No,
        3 => Quant::AtLeast(u.int_in_range(0..=3)?),
        4 => Quant::AtMost(u.int_in_range(0..=3)?),
        _ => {
            if u.arbitrary()? {
                Quant::AtLeast(crate::relations::MAX_COUNT)
            } else {
                Quant::AtMost(crate::relations::MAX_COUNT)
            }
        }
    })
}

fn formula(u: &mut Unstructured, subject: &str, ids: &[String], depth: u32) -> AResult<Formula> {
    let pick = if depth == 0 {
        0
    } else {
        u.int_in_range(0..=3)?
    };
    Ok(match pick {
        0 => {
            let rel = *u.choose(&Relation::ALL)?;
            let target = match u.int_in_range(0..=2)? {
                0 => Target::Any,
                1 if !ids.is_empty() => Target::Landmark(u.choose(ids)?.clone()),
                _ => Target::Class(u.choose(&CLASSES)?.to_string()),
            };
            if matches!(target, Target::Landmark(_)) || u.arbitrary()? {
                Formula::Atom(Atom::new(rel, subject, target))
            } else {
                Formula::Atom(Atom::quantified(rel, subject, quant(u)?, target))
            }
        }
        1 => Formula::not(formula(u, subject, ids, depth - 1)?),
        k => {
            let n = u.int_in_range(2..=3)?;
            let v = (0..n)
                .map(|_| formula(u, subject, ids, depth - 1))
                .collect::<AResult<Vec<_>>>()?;
            if k == 2 {
                Formula::And(v)
            } else {
                Formula::Or(v)
            }
        }
    })
}

fn rule_set(u: &mut Unstructured, fixed_ids: &[String], max: usize) -> AResult<RuleSet> {
    let n = u.int_in_range(0..=max)?;
    let mut rules = Vec::with_capacity(n);
    for i in 0..n {
        let subject = *u.choose(&CLASSES[..2])?;
        let f = formula(u, subject, fixed_ids, 2)?;
        let strength = match u.int_in_range(0..=4)? {
            0 => Strength::Hard,
            1 => Strength::Weight(f64::from(u.int_in_range(1u8..=3)?)),
            2 => Strength::Weight(2.5),
            3 => Strength::P(*u.choose(&[0.5, 0.01, 1e-8, 1e-300])?),
            _ => Strength::Weight(1.0),
        };
        let scope = if u.ratio(1, 4)? {
            Scope::of(quant(u)?)
        } else {
            Scope::Each
        };
        rules.push(
            Rule::new(format!("r{i}"), f)
                .with_strength(strength)
                .with_scope(scope),
        );
    }
    Ok(RuleSet::new(rules))
}

// ---- learn -----------------------------------------------------------------

fn demos(u: &mut Unstructured) -> AResult<Vec<Scene>> {
    let grid = *u.choose(&[1i64, 5, 10])?;
    let w = u.int_in_range(1..=6)? * 10;
    let h = u.int_in_range(1..=6)? * 10;
    let space = Space {
        x: *u.choose(&[0i64, -20, 7])?,
        y: *u.choose(&[0i64, 30, -5])?,
        width: w,
        height: h,
    };
    let fixed = if u.arbitrary()? {
        vec![Object::fixed_at(
            "w",
            "W",
            space.x,
            space.y,
            space.width.min(20),
            10.min(h),
        )]
    } else {
        Vec::new()
    };
    let n_demos = u.int_in_range(1..=3)?;
    let mut out = Vec::new();
    for _ in 0..n_demos {
        let mut objects = fixed.clone();
        for i in 0..u.int_in_range(1..=4)? {
            let size = *u.choose(&[(10i64, 10i64), (20, 10), (5, 5)])?;
            let class = *u.choose(&CLASSES[..2])?;
            let o = Object {
                id: format!("{class}{i}"),
                class: class.into(),
                x: Some(space.x + u.int_in_range(0..=w / grid)? * grid),
                y: Some(space.y + u.int_in_range(0..=h / grid)? * grid),
                width: size.0,
                height: size.1,
                fixed: false,
                turnable: false,
                turned: false,
            };
            let r = o.rect().unwrap_or_else(|| unreachable!("placed"));
            let fits = r.inside(&space.rect())
                && objects
                    .iter()
                    .filter_map(Object::rect)
                    .all(|p| !p.interiors_overlap(&r));
            if fits {
                objects.push(o);
            }
        }
        out.push(Scene {
            space,
            grid,
            objects,
        });
    }
    Ok(out)
}

fn learn_inner(u: &mut Unstructured) -> AResult<()> {
    use crate::infer::{learn as run_learn, LearnParams};
    let demos = demos(u)?;
    // Given statements only in forms the parser reads back (so that the
    // learned file can parse): built with every form of the AST, kept when
    // print → parse gives them back. Forms the grammar does not have yet
    // join in by themselves once it does.
    let statements = if u.ratio(1, 3)? {
        let set = rule_set(u, &[], 6)?;
        parse_rules(&print_rules(&set))
            .ok()
            .filter(|p| p.same_rules(&set))
            .map(|_| set)
    } else {
        None
    };
    let params = LearnParams {
        samples: u.int_in_range(1..=12)?,
        cutoff: *u.choose(&[0.01, 0.5, 0.999])?,
        seed: u.arbitrary()?,
        contact: *u.choose(&Contact::ALL)?,
        ..LearnParams::default()
    };
    let learned = match run_learn(&demos, statements.as_ref(), &params) {
        Ok(l) => l,
        Err(e) => {
            // A typed refusal (e.g. objects the null model cannot place).
            let _ = e.to_string();
            return Ok(());
        }
    };
    let text = learned.to_rcc();
    let parsed = match parse_rules(&text) {
        Ok(p) => p,
        Err(e) => panic!("the learned file does not parse: {e}\n{text}"),
    };
    assert!(
        parsed.same_rules(&learned.rules()),
        "the learned file means its rules\n{text}"
    );
    let _ = learned.report_json();
    for (d, scene) in demos.iter().enumerate() {
        let e = evaluate(scene, &parsed, params.contact);
        for r in &e.rules {
            let holds = match &r.scene {
                Some(_) => r.satisfied == 1,
                None => r.satisfied == r.subjects,
            };
            assert!(
                holds,
                "demonstration {d} breaks learned rule `{}` ({:?})\n{text}\n{}",
                r.name,
                r.violators,
                scene.to_json()
            );
        }
    }
    Ok(())
}

/// A few small random demonstrations → learn with few samples → the
/// learned file parses and every demonstration satisfies every learned
/// rule.
pub fn learn(data: &[u8]) {
    let _ = learn_inner(&mut Unstructured::new(data));
}

// ---- synth ------------------------------------------------------------------

mod synth;
pub use synth::synth;

// ---- studio (feature `studio`) ---------------------------------------------

#[cfg(feature = "studio")]
mod studio;
#[cfg(feature = "studio")]
pub use studio::studio;
