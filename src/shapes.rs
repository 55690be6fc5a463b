//! Statements about a class as a whole (fourth edition): the objects of a
//! class form **one group**, **one row**, **one column** or **one compact
//! block**. This module is the one definition of what each means; the
//! evaluator, learning, the synthesis model and the English readings all
//! follow it (the model is tested against it on every layout of small
//! problems).
//!
//! # Background
//!
//! Every rule of the first three editions is about each object ("every R
//! lies flush north or south of some other R"). Such rules cannot say that
//! *all* the Rs form one shape: five reds stacked two and three with a gap
//! keep "every R has a flush neighbour north or south", yet a person sees
//! two columns. A *group statement* is about the set of placed objects of
//! one class, like the scene-level rules of the second edition: it holds
//! or not for the whole scene, and counts once in the score.
//!
//! # The definitions
//!
//! Let `C` be the placed objects of the class and `m` their number. With
//! `m < 2` every group statement holds (there is nothing to connect).
//! Two objects are *adjacent* for a shape when:
//!
//! | shape | adjacent when | and the whole class |
//! |---|---|---|
//! | `group(C)` | they touch flush (`FL` in some direction) | is one component |
//! | `row(C)` | they touch flush east or west (`FL_E`/`FL_W`) and their south edges are on one line (`AL_S`) | is one component |
//! | `column(C)` | they touch flush north or south (`FL_N`/`FL_S`) and their west edges are on one line (`AL_W`) | is one component |
//! | `block(C)` | they touch flush (as `group`) | is one component whose bounding box fits `k × ⌈m/k⌉` cells, either way round |
//!
//! A *cell* of a block is the largest width by the largest height among
//! the class's objects, and `k = ⌈√m⌉`. So a block of 4 fits 2×2 cells, of
//! 5 or 6 fits 3×2 (or 2×3; five leaves one cell empty), of 7 to 9 fits
//! 3×3, of 10 to 12 fits 4×3: the shape the demonstrations showed with 4
//! generalises to the most square box that holds the objects, never to a
//! line. A corner touch, or a contact along part of an edge only (`EC`
//! without `FL`), never connects: flush contact is what demonstrators make
//! when they pack a shape.
//!
//! *Violators* (what a report names) are the objects outside the largest
//! component (ties go to the component with the earliest object); a block
//! that is one component but too spread out has no component to blame and
//! names none.
//!
//! # How to extend
//!
//! A new shape is a [`ShapeKind`] variant with its name, its adjacency in
//! [`adjacent`] (a combination of relations of [`crate::relations::TABLE`],
//! so the synthesis model can build it from the same pair literals) and,
//! if it constrains the bounding box, its boxes in [`block_boxes`]'s
//! manner; the parser takes every name of [`ShapeKind::ALL`].

use crate::relations::{relation_bits, Contact, Dir, Kind, RelBits, Relation};
use crate::scene::Rect;
use std::fmt;

/// Which shape a group statement asks of its class.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ShapeKind {
    /// `group(C)`: one component under flush contact.
    Group,
    /// `row(C)`: one run east–west, south edges on one line.
    Row,
    /// `column(C)`: one run north–south, west edges on one line.
    Column,
    /// `block(C)`: one component in the most square box that holds them.
    Block,
}

impl ShapeKind {
    /// All four, in the order templates generate them.
    pub const ALL: [ShapeKind; 4] = [
        ShapeKind::Group,
        ShapeKind::Row,
        ShapeKind::Column,
        ShapeKind::Block,
    ];

    /// The keyword in `.rcc` files.
    pub const fn name(self) -> &'static str {
        match self {
            ShapeKind::Group => "group",
            ShapeKind::Row => "row",
            ShapeKind::Column => "column",
            ShapeKind::Block => "block",
        }
    }

    /// The kind with this keyword.
    pub fn from_name(s: &str) -> Option<ShapeKind> {
        ShapeKind::ALL.into_iter().find(|k| k.name() == s)
    }

    /// The relations whose disjunction (over the four directions of
    /// contact) makes two objects adjacent, and the alignment that must
    /// hold as well: `(contacts, alignment)`.
    pub(crate) fn adjacency(self) -> (&'static [Relation], Option<Relation>) {
        const ALL: [Relation; 4] = [
            Relation::new(Kind::FL, Dir::N),
            Relation::new(Kind::FL, Dir::S),
            Relation::new(Kind::FL, Dir::E),
            Relation::new(Kind::FL, Dir::W),
        ];
        const EW: [Relation; 2] = [
            Relation::new(Kind::FL, Dir::E),
            Relation::new(Kind::FL, Dir::W),
        ];
        const NS: [Relation; 2] = [
            Relation::new(Kind::FL, Dir::N),
            Relation::new(Kind::FL, Dir::S),
        ];
        match self {
            ShapeKind::Group | ShapeKind::Block => (&ALL, None),
            ShapeKind::Row => (&EW, Some(Relation::new(Kind::AL, Dir::S))),
            ShapeKind::Column => (&NS, Some(Relation::new(Kind::AL, Dir::W))),
        }
    }

    /// What the shape says, for English readings: "form one column".
    pub(crate) const fn verb(self) -> &'static str {
        match self {
            ShapeKind::Group => "form one group, each touching another flush",
            ShapeKind::Row => "form one row, each flush against the next, south edges on one line",
            ShapeKind::Column => {
                "form one column, each flush against the next, west edges on one line"
            }
            ShapeKind::Block => {
                "form one compact block (2×2 for 4, 3×2 for 5 or 6, 3×3 for 7 to 9)"
            }
        }
    }
}

impl fmt::Display for ShapeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Whether `a` and `b` are adjacent for `kind` (see the module's table).
pub fn adjacent(kind: ShapeKind, a: &Rect, b: &Rect, contact: Contact) -> bool {
    let bits = relation_bits(a, b, contact);
    let (contacts, align) = kind.adjacency();
    let mask: RelBits = contacts.iter().fold(0, |m, r| m | r.bit());
    bits & mask != 0 && align.is_none_or(|r| bits & r.bit() != 0)
}

/// The boxes, in cells `(columns, rows)`, that a block of `m` objects may
/// fill: `k × ⌈m/k⌉` and its transpose, `k = ⌈√m⌉` (one box when they are
/// the same; none for `m < 2`).
pub fn block_boxes(m: usize) -> Vec<(u64, u64)> {
    if m < 2 {
        return Vec::new();
    }
    let m = m as u64;
    let mut k = m.isqrt();
    if k * k < m {
        k += 1;
    }
    let other = m.div_ceil(k);
    if other == k {
        vec![(k, k)]
    } else {
        vec![(k, other), (other, k)]
    }
}

/// The cell of a block: the largest width and the largest height.
pub(crate) fn block_cell(rects: &[Rect]) -> (i64, i64) {
    let w = rects.iter().map(|r| r.w).max().unwrap_or(0);
    let h = rects.iter().map(|r| r.h).max().unwrap_or(0);
    (w, h)
}

/// The verdict on one group statement.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ShapeCheck {
    /// Whether the statement holds.
    pub holds: bool,
    /// The components under the shape's adjacency, as indices into the
    /// rectangles given, largest first (ties: earliest object first); each
    /// sorted.
    pub components: Vec<Vec<usize>>,
    /// For a block: the bounding box `(width, height)` and whether it fits
    /// one of [`block_boxes`].
    pub bbox: Option<((i64, i64), bool)>,
}

impl ShapeCheck {
    /// The objects outside the largest component (what a report names),
    /// sorted.
    pub(crate) fn off_main(&self) -> Vec<usize> {
        let mut v: Vec<usize> = self.components.iter().skip(1).flatten().copied().collect();
        v.sort_unstable();
        v
    }
}

/// Decide `kind` over the placed objects of one class (`rects`, in scene
/// order).
pub fn check(kind: ShapeKind, rects: &[Rect], contact: Contact) -> ShapeCheck {
    let m = rects.len();
    // Union–find over the adjacency.
    let mut parent: Vec<usize> = (0..m).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for i in 0..m {
        for j in i + 1..m {
            if adjacent(kind, &rects[i], &rects[j], contact) {
                let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                if a != b {
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
    }
    let mut comps: Vec<Vec<usize>> = Vec::new();
    let mut slot: Vec<Option<usize>> = vec![None; m];
    for i in 0..m {
        let r = find(&mut parent, i);
        match slot[r] {
            Some(c) => comps[c].push(i),
            None => {
                slot[r] = Some(comps.len());
                comps.push(vec![i]);
            }
        }
    }
    // Stable: equal sizes keep the order of their first object.
    comps.sort_by_key(|c| std::cmp::Reverse(c.len()));
    let connected = comps.len() <= 1;
    let bbox = (kind == ShapeKind::Block && m >= 2).then(|| {
        let x0 = rects.iter().map(|r| r.x).min().unwrap_or(0);
        let y0 = rects.iter().map(|r| r.y).min().unwrap_or(0);
        let x1 = rects.iter().map(|r| r.x2()).max().unwrap_or(0);
        let y1 = rects.iter().map(|r| r.y2()).max().unwrap_or(0);
        let (w, h) = (x1.saturating_sub(x0), y1.saturating_sub(y0));
        let (cw, ch) = block_cell(rects);
        let fits = block_boxes(m).into_iter().any(|(a, b)| {
            i128::from(w) <= i128::from(a) * i128::from(cw)
                && i128::from(h) <= i128::from(b) * i128::from(ch)
        });
        ((w, h), fits)
    });
    let holds = m < 2 || (connected && bbox.is_none_or(|(_, fits)| fits));
    ShapeCheck {
        holds,
        components: comps,
        bbox,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(x: i64, y: i64) -> Rect {
        Rect::new(x, y, 10, 10)
    }

    #[test]
    fn boxes_generalise_from_four() {
        assert_eq!(block_boxes(0), vec![]);
        assert_eq!(block_boxes(1), vec![]);
        assert_eq!(block_boxes(2), vec![(2, 1), (1, 2)]);
        assert_eq!(block_boxes(3), vec![(2, 2)]);
        assert_eq!(block_boxes(4), vec![(2, 2)]);
        assert_eq!(block_boxes(5), vec![(3, 2), (2, 3)]);
        assert_eq!(block_boxes(6), vec![(3, 2), (2, 3)]);
        assert_eq!(block_boxes(7), vec![(3, 3)]);
        assert_eq!(block_boxes(9), vec![(3, 3)]);
        assert_eq!(block_boxes(10), vec![(4, 3), (3, 4)]);
        assert_eq!(block_boxes(16), vec![(4, 4)]);
        // Every box holds its objects and leaves fewer empty cells than
        // its shorter side.
        for m in 2..200usize {
            for (a, b) in block_boxes(m) {
                let area = a * b;
                assert!(area >= m as u64 && area - (m as u64) < a.min(b), "{m}");
            }
        }
    }

    #[test]
    fn a_split_column_is_two_components() {
        let rects = [r(0, 0), r(0, 10), r(0, 30), r(0, 40), r(0, 50)];
        let c = check(ShapeKind::Column, &rects, Contact::Point);
        assert!(!c.holds);
        assert_eq!(c.components, vec![vec![2, 3, 4], vec![0, 1]]);
        assert_eq!(c.off_main(), vec![0, 1]);
        let joined = [r(0, 0), r(0, 10), r(0, 20), r(0, 30), r(0, 40)];
        assert!(check(ShapeKind::Column, &joined, Contact::Point).holds);
        // Offset by a step: not one column (west edges differ) though a
        // group under flush contact is lost too (partial contact).
        let offset = [r(0, 0), r(5, 10)];
        assert!(!check(ShapeKind::Column, &offset, Contact::Point).holds);
        assert!(!check(ShapeKind::Group, &offset, Contact::Point).holds);
    }

    #[test]
    fn corners_never_connect() {
        let diag = [r(0, 0), r(10, 10)];
        for mode in Contact::ALL {
            for k in ShapeKind::ALL {
                assert!(!check(k, &diag, mode).holds, "{k} {mode}");
            }
        }
    }

    #[test]
    fn fewer_than_two_hold() {
        for k in ShapeKind::ALL {
            assert!(check(k, &[], Contact::Point).holds);
            assert!(check(k, &[r(0, 0)], Contact::Edge).holds);
        }
    }

    #[test]
    fn five_in_a_three_by_two_box_is_a_block_and_a_row_of_five_is_not() {
        let five = [r(0, 0), r(10, 0), r(20, 0), r(0, 10), r(10, 10)];
        let c = check(ShapeKind::Block, &five, Contact::Point);
        assert!(c.holds);
        assert_eq!(c.bbox, Some(((30, 20), true)));
        let row = [r(0, 0), r(10, 0), r(20, 0), r(30, 0), r(40, 0)];
        let c = check(ShapeKind::Block, &row, Contact::Point);
        assert!(!c.holds && c.off_main().is_empty());
        assert!(check(ShapeKind::Row, &row, Contact::Point).holds);
        assert!(check(ShapeKind::Group, &row, Contact::Point).holds);
        assert!(!check(ShapeKind::Column, &row, Contact::Point).holds);
    }
}
