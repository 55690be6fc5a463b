//! The table's derived forms: the hand-written fast path of all sixteen
//! relations of a pair as one bit mask, and implication between relations
//! computed from [`TABLE`] over every order type of two rectangles.

use super::{Contact, RelBits, Relation, TABLE};
use crate::scene::Rect;
use std::sync::OnceLock;

/// Every order type of two rectangles: all pairs with coordinates in
/// `0..4` on each axis (four edge values per axis take at most four distinct
/// values, and every condition of [`TABLE`] compares edges only).
pub fn order_types() -> impl Iterator<Item = (Rect, Rect)> {
    let spans: Vec<(i64, i64)> = (0..4)
        .flat_map(|lo| (lo + 1..4).map(move |hi| (lo, hi - lo)))
        .collect();
    let axis: Vec<((i64, i64), (i64, i64))> = spans
        .iter()
        .flat_map(|&a| spans.iter().map(move |&b| (a, b)))
        .collect();
    let ys = axis.clone();
    axis.into_iter().flat_map(move |(ax, bx)| {
        ys.clone().into_iter().map(move |(ay, by)| {
            (
                Rect::new(ax.0, ay.0, ax.1, ay.1),
                Rect::new(bx.0, by.0, bx.1, by.1),
            )
        })
    })
}

/// Whether `p(a, b) ⇒ q(a, b)` for every pair of rectangles under
/// `contact`, computed from [`TABLE`] over every order type.
pub fn implies(p: Relation, q: Relation, contact: Contact) -> bool {
    static MATRIX: OnceLock<[[RelBits; 16]; 2]> = OnceLock::new();
    let m = MATRIX.get_or_init(|| {
        let mut m = [[RelBits::MAX; 16]; 2];
        for (ci, contact) in Contact::ALL.into_iter().enumerate() {
            for (a, b) in order_types() {
                let bits: RelBits = TABLE
                    .iter()
                    .filter(|d| d.holds(&a, &b, contact))
                    .fold(0, |acc, d| acc | d.rel.bit());
                for r in Relation::ALL {
                    if bits & r.bit() != 0 {
                        m[ci][r.index()] &= bits;
                    }
                }
            }
        }
        m
    });
    let ci = match contact {
        Contact::Point => 0,
        Contact::Edge => 1,
    };
    m[ci][p.index()] & q.bit() != 0
}

/// Whether intervals `[a1, a2]` and `[b1, b2]` meet under `contact`.
#[inline]
const fn projections_meet(a1: i64, a2: i64, b1: i64, b2: i64, contact: Contact) -> bool {
    match contact {
        Contact::Point => a1 <= b2 && b1 <= a2,
        Contact::Edge => a1 < b2 && b1 < a2,
    }
}

/// Whether one of `[a1, a2]`, `[b1, b2]` contains the other.
#[inline]
const fn nested(a1: i64, a2: i64, b1: i64, b2: i64) -> bool {
    (b1 <= a1 && a2 <= b2) || (a1 <= b1 && b2 <= a2)
}

/// All sixteen relations of `(a, b)` as one mask (bit `Relation::index()`).
///
/// The fast path of [`TABLE`]: `tests/relations.rs` checks it against
/// [`RelationDef::holds`](super::RelationDef::holds) on every order type, in both contact modes.
#[inline]
pub fn relation_bits(a: &Rect, b: &Rect, contact: Contact) -> RelBits {
    let mut bits: RelBits = 0;
    let (ax2, ay2, bx2, by2) = (a.x2(), a.y2(), b.x2(), b.y2());
    if a.y >= by2 {
        bits |= 1; // DR_N
    }
    if ay2 <= b.y {
        bits |= 1 << 1; // DR_S
    }
    if a.x >= bx2 {
        bits |= 1 << 2; // DR_E
    }
    if ax2 <= b.x {
        bits |= 1 << 3; // DR_W
    }
    let xm = projections_meet(a.x, ax2, b.x, bx2, contact);
    let ym = projections_meet(a.y, ay2, b.y, by2, contact);
    let xn = nested(a.x, ax2, b.x, bx2);
    let yn = nested(a.y, ay2, b.y, by2);
    if a.y == by2 {
        bits |= (xm as RelBits) << 4 | (xn as RelBits) << 8; // EC_N, FL_N
    }
    if ay2 == b.y {
        bits |= (xm as RelBits) << 5 | (xn as RelBits) << 9; // EC_S, FL_S
    }
    if a.x == bx2 {
        bits |= (ym as RelBits) << 6 | (yn as RelBits) << 10; // EC_E, FL_E
    }
    if ax2 == b.x {
        bits |= (ym as RelBits) << 7 | (yn as RelBits) << 11; // EC_W, FL_W
    }
    bits |= ((ay2 == by2) as RelBits) << 12; // AL_N
    bits |= ((a.y == b.y) as RelBits) << 13; // AL_S
    bits |= ((ax2 == bx2) as RelBits) << 14; // AL_E
    bits |= ((a.x == b.x) as RelBits) << 15; // AL_W
    bits
}

/// Whether `rel(a, b)` holds.
#[inline]
pub fn holds(rel: Relation, a: &Rect, b: &Rect, contact: Contact) -> bool {
    relation_bits(a, b, contact) & rel.bit() != 0
}
