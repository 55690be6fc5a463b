//! Laws of the relation algebra (SPEC §3–§4), each a named property.

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
    (0usize..8).prop_map(|i| Relation::ALL[i])
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
