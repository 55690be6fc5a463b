//! Laws of the relation algebra (docs/language.md), each a named property.

use proptest::prelude::*;
use rccpack::relations::{
    holds, relation_bits, ClassAtoms, ClassIndex, Contact, Dir, Kind, Relation,
};
use rccpack::scene::{Object, Rect, Scene, Space};

/// Small rectangles on a small integer range, so that touching and corner
/// contact happen often.
fn rect_strategy() -> impl Strategy<Value = Rect> {
    (-6i64..6, -6i64..6, 1i64..5, 1i64..5).prop_map(|(x, y, w, h)| Rect::new(x, y, w, h))
}

fn contact_strategy() -> impl Strategy<Value = Contact> {
    prop_oneof![Just(Contact::Point), Just(Contact::Edge)]
}

fn relation_strategy() -> impl Strategy<Value = Relation> {
    (0usize..16).prop_map(|i| Relation::ALL[i])
}

/// A scene of up to 7 rectangles (overlaps allowed: atoms are defined for any
/// placed objects) of classes A, B, C, some unplaced.
fn scene_strategy() -> impl Strategy<Value = Scene> {
    prop::collection::vec(
        (rect_strategy(), 0usize..3, prop::bool::weighted(0.85)),
        1..7,
    )
    .prop_map(|v| Scene {
        space: Space {
            x: -20,
            y: -20,
            width: 40,
            height: 40,
        },
        grid: 1,
        objects: v
            .into_iter()
            .enumerate()
            .map(|(i, (r, c, placed))| Object {
                id: format!("o{i}"),
                class: ["A", "B", "C"][c].to_string(),
                x: placed.then_some(r.x),
                y: placed.then_some(r.y),
                width: r.w,
                height: r.h,
                fixed: false,
                turnable: false,
                turned: false,
            })
            .collect(),
    })
}

proptest! {
    #[test]
    fn law_ec_implies_dr(a in rect_strategy(), b in rect_strategy(), c in contact_strategy()) {
        for d in Dir::ALL {
            if holds(Relation::new(Kind::EC, d), &a, &b, c) {
                prop_assert!(holds(Relation::new(Kind::DR, d), &a, &b, c));
            }
        }
    }

    #[test]
    fn law_non_overlapping_implies_some_dr(a in rect_strategy(), b in rect_strategy(), c in contact_strategy()) {
        let some_dr = Dir::ALL.iter().any(|&d| holds(Relation::new(Kind::DR, d), &a, &b, c));
        prop_assert_eq!(some_dr, !a.interiors_overlap(&b));
    }

    #[test]
    fn law_converse(a in rect_strategy(), b in rect_strategy(), c in contact_strategy(), r in relation_strategy()) {
        // DR_N(a,b) ⇔ DR_S(b,a), DR_E(a,b) ⇔ DR_W(b,a); the same for EC.
        prop_assert_eq!(holds(r, &a, &b, c), holds(r.converse(), &b, &a, c));
    }

    #[test]
    fn law_edge_contact_implies_point_contact(a in rect_strategy(), b in rect_strategy()) {
        let edge = relation_bits(&a, &b, Contact::Edge);
        let point = relation_bits(&a, &b, Contact::Point);
        prop_assert_eq!(edge & !point, 0, "edge bits {:08b} point bits {:08b}", edge, point);
        // DR does not depend on the contact mode at all.
        prop_assert_eq!(edge & 0x0F, point & 0x0F);
    }

    #[test]
    fn law_translation_invariance(a in rect_strategy(), b in rect_strategy(), dx in -100i64..100, dy in -100i64..100, c in contact_strategy()) {
        let a2 = Rect::new(a.x + dx, a.y + dy, a.w, a.h);
        let b2 = Rect::new(b.x + dx, b.y + dy, b.w, b.h);
        prop_assert_eq!(relation_bits(&a, &b, c), relation_bits(&a2, &b2, c));
    }

    #[test]
    fn law_dr_directions_exclusive_pairwise(a in rect_strategy(), b in rect_strategy(), c in contact_strategy()) {
        // a cannot be both (strictly discrete) north and south of b: sizes ≥ 1.
        let bits = relation_bits(&a, &b, c);
        prop_assert!(!(bits & 1 != 0 && bits & 2 != 0));
        prop_assert!(!(bits & 4 != 0 && bits & 8 != 0));
    }

    #[test]
    fn law_class_atoms_match_naive_reference(scene in scene_strategy(), c in contact_strategy()) {
        let classes = ClassIndex::of_scene(&scene);
        let table = ClassAtoms::new(&scene, &classes, c);
        for (i, o) in scene.objects.iter().enumerate() {
            let Some(ro) = o.rect() else {
                prop_assert!(table.bits(i, None).is_none());
                continue;
            };
            let targets: Vec<Option<&str>> =
                ["A", "B", "C"].iter().map(|s| Some(*s)).chain(std::iter::once(None)).collect();
            for t in targets {
                let others: Vec<Rect> = scene
                    .objects
                    .iter()
                    .enumerate()
                    .filter(|(j, b)| *j != i && t.is_none_or(|t| b.class == t))
                    .filter_map(|(_, b)| b.rect())
                    .collect();
                for r in Relation::ALL {
                    let naive = if r.is_universal() {
                        others.iter().all(|b| holds(r, &ro, b, c))
                    } else {
                        others.iter().any(|b| holds(r, &ro, b, c))
                    };
                    let ti = t.and_then(|t| classes.get(t));
                    // A class absent from the scene has no objects at all.
                    let got = if t.is_some() && ti.is_none() {
                        r.is_universal()
                    } else {
                        table.holds(i, r, ti)
                    };
                    prop_assert_eq!(got, naive, "object {} rel {} target {:?}", o.id, r, t);
                }
            }
        }
    }
}

#[test]
fn relation_names_round_trip() {
    for r in Relation::ALL {
        assert_eq!(Relation::from_name(r.name()), Some(r));
        assert_eq!(1u16 << r.index(), r.bit());
    }
    assert_eq!(Relation::from_name("DR_X"), None);
}

#[test]
fn corner_touch_counts_only_in_point_mode() {
    let a = Rect::new(10, 10, 10, 10);
    let b = Rect::new(0, 0, 10, 10); // a's south-west corner touches b's north-east corner
    let ec_n = Relation::new(Kind::EC, Dir::N);
    let ec_e = Relation::new(Kind::EC, Dir::E);
    assert!(holds(ec_n, &a, &b, Contact::Point));
    assert!(holds(ec_e, &a, &b, Contact::Point));
    assert!(!holds(ec_n, &a, &b, Contact::Edge));
    assert!(!holds(ec_e, &a, &b, Contact::Edge));
}

#[test]
fn an_object_never_relates_to_itself() {
    // A lone object: DR atoms against its own class hold vacuously, EC fail.
    let scene = Scene::from_json(r#"{"space":{"width":50,"height":50},"objects":[{"class":"A","x":0,"y":0,"width":10,"height":10}]}"#).unwrap();
    let classes = ClassIndex::of_scene(&scene);
    let t = ClassAtoms::new(&scene, &classes, Contact::Point);
    assert_eq!(t.bits(0, Some(0)), Some(0x0F));
    assert_eq!(t.bits(0, None), Some(0x0F));
}

// ---- The one table (docs/language.md#relations): every derived form agrees with it. ----

use rccpack::relations::{implies, order_types, TABLE};

#[test]
fn table_is_in_bit_order_with_names_and_default_quantifiers() {
    for (i, d) in TABLE.iter().enumerate() {
        assert_eq!(d.rel.index(), i);
        assert_eq!(d.rel, Relation::ALL[i]);
        assert_eq!(d.name, format!("{:?}_{}", d.rel.kind, d.rel.dir.letter()));
        let every = d.rel.kind == Kind::DR;
        assert_eq!(d.default_quant == rccpack::relations::Quant::Every, every);
    }
}

/// The hand-written fast path equals the table's conditions on every order
/// type of two rectangles (which decides every comparison of edges), in
/// both contact modes.
#[test]
fn relation_bits_equal_the_table_on_every_order_type() {
    let mut n = 0;
    for (a, b) in order_types() {
        for c in [Contact::Point, Contact::Edge] {
            let bits = relation_bits(&a, &b, c);
            for d in &TABLE {
                assert_eq!(
                    bits & d.rel.bit() != 0,
                    d.holds(&a, &b, c),
                    "{} on {a:?} {b:?} ({c})",
                    d.name
                );
            }
            n += 1;
        }
    }
    assert_eq!(n, 2 * 36 * 36);
}

proptest! {
    #[test]
    fn law_relation_bits_equal_the_table(a in rect_strategy(), b in rect_strategy(), c in contact_strategy()) {
        let bits = relation_bits(&a, &b, c);
        for d in &TABLE {
            prop_assert_eq!(bits & d.rel.bit() != 0, d.holds(&a, &b, c), "{}", d.name);
        }
    }

    #[test]
    fn law_fl_implies_ec_in_both_modes(a in rect_strategy(), b in rect_strategy(), c in contact_strategy()) {
        for d in Dir::ALL {
            if holds(Relation::new(Kind::FL, d), &a, &b, c) {
                prop_assert!(holds(Relation::new(Kind::EC, d), &a, &b, c), "FL_{} without EC", d.letter());
            }
        }
    }

    #[test]
    fn law_fl_converse(a in rect_strategy(), b in rect_strategy(), c in contact_strategy()) {
        let fl = |d| Relation::new(Kind::FL, d);
        prop_assert_eq!(holds(fl(Dir::N), &a, &b, c), holds(fl(Dir::S), &b, &a, c));
        prop_assert_eq!(holds(fl(Dir::E), &a, &b, c), holds(fl(Dir::W), &b, &a, c));
    }

    #[test]
    fn law_al_symmetric(a in rect_strategy(), b in rect_strategy(), c in contact_strategy()) {
        for d in Dir::ALL {
            let al = Relation::new(Kind::AL, d);
            prop_assert_eq!(holds(al, &a, &b, c), holds(al, &b, &a, c));
        }
    }

    #[test]
    fn law_fl_and_al_do_not_depend_on_contact(a in rect_strategy(), b in rect_strategy()) {
        let mask: u16 = 0xFF00;
        prop_assert_eq!(relation_bits(&a, &b, Contact::Point) & mask, relation_bits(&a, &b, Contact::Edge) & mask);
    }

    #[test]
    fn law_same_size_flush_is_exactly_aligned(x in -6i64..6, y in -6i64..6, w in 1i64..5, h in 1i64..5, dx in -6i64..6, c in contact_strategy()) {
        // two blocks of one size: FL_N means exactly on top (AL_W and AL_E).
        let a = Rect::new(x + dx, y + h, w, h);
        let b = Rect::new(x, y, w, h);
        let fl_n = holds(Relation::new(Kind::FL, Dir::N), &a, &b, c);
        prop_assert_eq!(fl_n, dx == 0);
        if fl_n {
            prop_assert!(holds(Relation::new(Kind::AL, Dir::W), &a, &b, c));
            prop_assert!(holds(Relation::new(Kind::AL, Dir::E), &a, &b, c));
        }
    }

    /// `implies` (computed from the table over order types) is sound on
    /// arbitrary rectangles.
    #[test]
    fn law_implies_is_sound(a in rect_strategy(), b in rect_strategy(), c in contact_strategy(), p in relation_strategy(), q in relation_strategy()) {
        if implies(p, q, c) && holds(p, &a, &b, c) {
            prop_assert!(holds(q, &a, &b, c), "{} => {} fails", p, q);
        }
    }
}

#[test]
fn implies_knows_the_chain_fl_ec_dr_and_nothing_false() {
    for c in [Contact::Point, Contact::Edge] {
        for d in Dir::ALL {
            let r = |k| Relation::new(k, d);
            assert!(implies(r(Kind::FL), r(Kind::EC), c));
            assert!(implies(r(Kind::EC), r(Kind::DR), c));
            assert!(implies(r(Kind::FL), r(Kind::DR), c));
            assert!(!implies(r(Kind::EC), r(Kind::FL), c));
            assert!(!implies(r(Kind::DR), r(Kind::EC), c));
            assert!(!implies(r(Kind::AL), r(Kind::DR), c));
        }
        // Implications that are complete: each is witnessed by an order type.
        for p in Relation::ALL {
            for q in Relation::ALL {
                if !implies(p, q, c) {
                    assert!(
                        order_types().any(|(a, b)| holds(p, &a, &b, c) && !holds(q, &a, &b, c)),
                        "{p} does not imply {q}, but no counterexample"
                    );
                }
            }
        }
    }
    // Edge contact is stricter than point contact: a corner touch is EC in
    // point mode only.
    let ec_n = Relation::new(Kind::EC, Dir::N);
    let dr_e = Relation::new(Kind::DR, Dir::E);
    assert!(!implies(ec_n, dr_e, Contact::Point));
}

// ---- Quantifiers, landmarks and scene-level rules (docs/language.md). ----

use rccpack::eval::Evaluator;
use rccpack::relations::Quant;
use rccpack::rules::{Atom, Formula, Rule, RuleSet, Scope, Target};

fn class_strategy() -> impl Strategy<Value = &'static str> {
    prop_oneof![Just("A"), Just("B"), Just("C")]
}

fn quant_strategy() -> impl Strategy<Value = Quant> {
    prop_oneof![
        Just(Quant::Every),
        Just(Quant::Some),
        Just(Quant::No),
        (0u32..5).prop_map(Quant::AtLeast),
        (0u32..5).prop_map(Quant::AtMost),
    ]
}

/// Truth of `rel(class of obj, q target)` for every placed object, by the
/// evaluator.
fn atom_truth(scene: &Scene, atom: Atom, c: Contact) -> Vec<Option<bool>> {
    let f = Formula::Atom(atom.clone());
    let rules = RuleSet::new(vec![Rule::new("r", f.clone())]);
    let ev = Evaluator::new(scene, &rules, c);
    let cf = ev.compile(&f);
    scene
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| (o.is_placed() && o.class == atom.subject).then(|| ev.satisfies(i, &cf)))
        .collect()
}

fn q_atom(rel: Relation, s: &str, q: Quant, t: &str) -> Atom {
    Atom::quantified(rel, s, q, Target::Class(t.into()))
}

proptest! {
    #[test]
    fn law_quantified_atoms_count_like_the_naive_reference(scene in scene_strategy(), c in contact_strategy(), r in relation_strategy(), s in class_strategy(), t in class_strategy(), q in quant_strategy()) {
        let got = atom_truth(&scene, q_atom(r, s, q, t), c);
        for (i, o) in scene.objects.iter().enumerate() {
            let Some(g) = got[i] else { continue };
            let ro = o.rect().unwrap();
            let others: Vec<Rect> = scene.objects.iter().enumerate()
                .filter(|(j, b)| *j != i && b.class == t)
                .filter_map(|(_, b)| b.rect()).collect();
            let m = others.len() as u32;
            let k = others.iter().filter(|b| holds(r, &ro, b, c)).count() as u32;
            let want = match q {
                Quant::Every => k == m,
                Quant::Some => k >= 1,
                Quant::No => k == 0,
                Quant::AtLeast(n) => k >= n,
                Quant::AtMost(n) => k <= n,
            };
            prop_assert_eq!(g, want, "{} {}", o.id, q);
        }
    }

    #[test]
    fn law_no_is_at_most_0_and_some_is_at_least_1(scene in scene_strategy(), c in contact_strategy(), r in relation_strategy(), s in class_strategy(), t in class_strategy()) {
        prop_assert_eq!(atom_truth(&scene, q_atom(r, s, Quant::No, t), c), atom_truth(&scene, q_atom(r, s, Quant::AtMost(0), t), c));
        prop_assert_eq!(atom_truth(&scene, q_atom(r, s, Quant::Some, t), c), atom_truth(&scene, q_atom(r, s, Quant::AtLeast(1), t), c));
    }

    #[test]
    fn law_every_is_at_least_m(scene in scene_strategy(), c in contact_strategy(), r in relation_strategy(), s in class_strategy(), t in class_strategy()) {
        let every = atom_truth(&scene, q_atom(r, s, Quant::Every, t), c);
        for (i, o) in scene.objects.iter().enumerate() {
            let Some(e) = every[i] else { continue };
            let m = scene.objects.iter().enumerate().filter(|(j, b)| *j != i && b.class == t && b.is_placed()).count() as u32;
            let at_least = atom_truth(&scene, q_atom(r, s, Quant::AtLeast(m), t), c)[i];
            prop_assert_eq!(Some(e), at_least, "{}", o.id);
        }
    }

    #[test]
    fn law_not_some_is_no(scene in scene_strategy(), c in contact_strategy(), r in relation_strategy(), s in class_strategy(), t in class_strategy()) {
        let some = atom_truth(&scene, q_atom(r, s, Quant::Some, t), c);
        let no = atom_truth(&scene, q_atom(r, s, Quant::No, t), c);
        let not_some: Vec<Option<bool>> = some.iter().map(|v| v.map(|b| !b)).collect();
        prop_assert_eq!(not_some, no);
    }

    #[test]
    fn law_default_quantifier_is_the_first_edition_lifting(scene in scene_strategy(), c in contact_strategy(), r in relation_strategy(), s in class_strategy(), t in class_strategy()) {
        let implicit = atom_truth(&scene, Atom::new(r, s, Target::Class(t.into())), c);
        let explicit = atom_truth(&scene, q_atom(r, s, r.default_quant(), t), c);
        prop_assert_eq!(implicit, explicit);
    }

    /// A landmark is the pairwise relation with one fixed object; the
    /// subject itself, or an id no fixed object has, is an empty target.
    #[test]
    fn law_landmark_is_the_pair_relation(mut scene in scene_strategy(), c in contact_strategy(), r in relation_strategy(), s in class_strategy(), lm in 0usize..7) {
        let lm = lm % scene.objects.len();
        scene.objects[lm].fixed = true;
        let id = scene.objects[lm].id.clone();
        let got = atom_truth(&scene, Atom::new(r, s, Target::Landmark(id)), c);
        for (i, o) in scene.objects.iter().enumerate() {
            let Some(g) = got[i] else { continue };
            let want = match scene.objects[lm].rect() {
                Some(l) if i != lm => holds(r, &o.rect().unwrap(), &l, c),
                _ => r.is_universal(),
            };
            prop_assert_eq!(g, want, "{} vs landmark {}", o.id, lm);
        }
        let missing = atom_truth(&scene, Atom::new(r, s, Target::Landmark("nobody".into())), c);
        prop_assert!(missing.iter().flatten().all(|&v| v == r.is_universal()));
    }

    /// `Q A: φ` holds iff the number of A objects satisfying φ meets Q; it is
    /// one term of weight w in the score.
    #[test]
    fn law_scene_rules_count_subjects(scene in scene_strategy(), c in contact_strategy(), r in relation_strategy(), s in class_strategy(), t in class_strategy(), q in quant_strategy(), w in 1u32..4) {
        let f = Formula::Atom(Atom::new(r, s, Target::Class(t.into())));
        let each = Rule::new("each", f.clone());
        let scene_rule = Rule::new("scene", f.clone())
            .with_scope(Scope::of(q))
            .with_strength(rccpack::rules::Strength::Weight(f64::from(w)));
        let rules = RuleSet::new(vec![each, scene_rule]);
        let e = Evaluator::new(&scene, &rules, c).evaluate(&rules);
        let (each_r, scene_r) = (&e.rules[0], &e.rules[1]);
        let (k, m) = (each_r.satisfied as u32, each_r.subjects as u32);
        let holds_q = q.holds(k, m);
        match Scope::of(q) {
            Scope::Each => prop_assert_eq!(scene_r, &rccpack::eval::RuleReport { name: "scene".into(), weight: f64::from(w), ..each_r.clone() }),
            Scope::Group => prop_assert!(false, "Scope::of never gives a group scope"),
            Scope::Scene(_) => {
                prop_assert_eq!(scene_r.subjects, 1);
                prop_assert_eq!(scene_r.satisfied, usize::from(holds_q));
                let expected_total = each_r.subjects as f64 + f64::from(w);
                prop_assert!((e.total_weight - expected_total).abs() < 1e-9);
                let sr = scene_r.scene.as_ref().unwrap();
                prop_assert_eq!((sr.satisfying, sr.objects), (k as usize, m as usize));
                if !holds_q && matches!(q, Quant::No | Quant::AtMost(_)) {
                    prop_assert_eq!(scene_r.violators.len(), k as usize);
                } else {
                    prop_assert!(scene_r.violators.is_empty());
                }
            }
        }
    }
}
