//! The sixteen directional relations between rectangles, defined once in
//! [`TABLE`], and their lifting to classes with target quantifiers
//! (docs/language.md).
//!
//! # Background
//!
//! Region Connection Calculus distinguishes regions that are *discrete*
//! (`DR`: interiors disjoint) from regions that are *externally connected*
//! (`EC`: they touch but interiors do not overlap). We augment each with a
//! direction `N`, `S`, `E`, `W` (north is +y). The second edition adds
//! *flush* contact (`FL`: touching along the whole of the shorter edge) and
//! edge *alignment* (`AL`: one edge of each on one line).
//!
//! # The one table
//!
//! [`TABLE`] holds every relation as data: its name, its default quantifier
//! and its condition, a disjunction of conjunctions of comparisons between
//! the edges `x, x2, y, y2` of the two rectangles, per contact mode. Every
//! other form is derived from it or tested against it:
//!
//! - [`relation_bits`], the fast path used by evaluation and learning, is
//!   written by hand and checked against [`RelationDef::holds`] on every order
//!   type of two rectangles (`tests/relations.rs`);
//! - the synthesis model (`synth::model`) encodes each [`Cmp`] as a bound on
//!   a coordinate difference, so its literals are the table's conditions;
//! - [`implies`] (used by learning to mark implied rules) is computed from
//!   the table by enumerating every order type of two rectangles;
//! - English readings take [`RelationDef::verb`].
//!
//! # Practical
//!
//! All sixteen relations between an ordered pair fit in one `u16`
//! ([`relation_bits`], bit `Relation::index()`). A [`ClassAtoms`] table holds,
//! per placed object and per target (a class or `*`), how many target
//! objects there are and, per relation, how many of them stand in it
//! ([`TargetCount`]); every quantifier of docs/language.md#quantifiers is then one comparison.
//! Landmark targets (`@ID`) are resolved per scene to an object index and
//! read the pair's bits directly.
//!
//! # How to extend
//!
//! A new relation is one entry in [`TABLE`] (name, default quantifier,
//! condition, English verb), a [`Kind`] variant, and its case in
//! [`relation_bits`]; the bit test fails until the fast path agrees with the
//! table. Seventeen or more relations need a wider mask than `u16`.

use crate::scene::Rect;
use std::fmt;

mod atoms;
mod bits;

pub use atoms::{ClassAtoms, ClassIndex, TargetCount};
pub use bits::{holds, implies, order_types, relation_bits};

/// A compass direction; north is +y, east is +x.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Dir {
    /// +y
    N,
    /// −y
    S,
    /// +x
    E,
    /// −x
    W,
}

impl Dir {
    /// All four, in `N S E W` order.
    pub const ALL: [Dir; 4] = [Dir::N, Dir::S, Dir::E, Dir::W];
    /// The opposite direction.
    pub const fn opposite(self) -> Dir {
        match self {
            Dir::N => Dir::S,
            Dir::S => Dir::N,
            Dir::E => Dir::W,
            Dir::W => Dir::E,
        }
    }
    /// One-letter name.
    pub const fn letter(self) -> char {
        match self {
            Dir::N => 'N',
            Dir::S => 'S',
            Dir::E => 'E',
            Dir::W => 'W',
        }
    }
    /// English word ("north").
    pub const fn word(self) -> &'static str {
        match self {
            Dir::N => "north",
            Dir::S => "south",
            Dir::E => "east",
            Dir::W => "west",
        }
    }
    /// Index in [`Dir::ALL`].
    pub const fn index(self) -> usize {
        match self {
            Dir::N => 0,
            Dir::S => 1,
            Dir::E => 2,
            Dir::W => 3,
        }
    }
}

/// The kind of a relation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    /// Discrete from, in a direction.
    DR,
    /// Externally connected, on a side.
    EC,
    /// Flush contact: touching along the whole of the shorter edge.
    FL,
    /// Edge alignment: the two edges on one side lie on one line.
    AL,
}

impl Kind {
    /// All four, in bit order.
    pub const ALL: [Kind; 4] = [Kind::DR, Kind::EC, Kind::FL, Kind::AL];
    /// Index in [`Kind::ALL`].
    pub const fn index(self) -> usize {
        match self {
            Kind::DR => 0,
            Kind::EC => 1,
            Kind::FL => 2,
            Kind::AL => 3,
        }
    }
}

/// A quantifier over the target objects of an atom (docs/language.md#quantifiers) or over the
/// subject objects of a scene-level rule (docs/language.md#scene-rules).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Quant {
    /// `every`: all of them (true when there is none).
    Every,
    /// `some`: at least one.
    Some,
    /// `no`: none.
    No,
    /// `at least K`.
    AtLeast(u32),
    /// `at most K`.
    AtMost(u32),
}

/// The largest `K` of `at least K` / `at most K` (docs/language.md#syntax).
pub const MAX_COUNT: u32 = 65_535;

impl Quant {
    /// Whether `c` of `m` objects standing in the relation satisfies the
    /// quantifier.
    #[inline]
    pub const fn holds(self, c: u32, m: u32) -> bool {
        match self {
            Quant::Every => c == m,
            Quant::Some => c >= 1,
            Quant::No => c == 0,
            Quant::AtLeast(k) => c >= k,
            Quant::AtMost(k) => c <= k,
        }
    }
}

impl fmt::Display for Quant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Quant::Every => f.write_str("every"),
            Quant::Some => f.write_str("some"),
            Quant::No => f.write_str("no"),
            Quant::AtLeast(k) => write!(f, "at least {k}"),
            Quant::AtMost(k) => write!(f, "at most {k}"),
        }
    }
}

/// One of the sixteen directional relations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Relation {
    /// `DR`, `EC`, `FL` or `AL`.
    pub kind: Kind,
    /// The direction.
    pub dir: Dir,
}

/// A mask of relations, bit `Relation::index()`.
pub type RelBits = u16;

impl Relation {
    /// All sixteen, in bit order: `DR_N DR_S DR_E DR_W EC_N … FL_N … AL_N …`.
    pub const ALL: [Relation; 16] = {
        let mut out = [Relation::new(Kind::DR, Dir::N); 16];
        let mut i = 0;
        while i < 16 {
            out[i] = Relation::new(Kind::ALL[i / 4], Dir::ALL[i % 4]);
            i += 1;
        }
        out
    };

    /// The eight relations of the first edition (`DR`, `EC`).
    pub const FIRST_EDITION: [Relation; 8] = {
        let mut out = [Relation::new(Kind::DR, Dir::N); 8];
        let mut i = 0;
        while i < 8 {
            out[i] = Relation::ALL[i];
            i += 1;
        }
        out
    };

    /// Build a relation.
    pub const fn new(kind: Kind, dir: Dir) -> Self {
        Relation { kind, dir }
    }

    /// Bit index 0..16.
    pub const fn index(self) -> usize {
        self.kind.index() * 4 + self.dir.index()
    }

    /// The bit `1 << index()`.
    pub const fn bit(self) -> RelBits {
        1 << self.index()
    }

    /// Its entry in [`TABLE`].
    pub(crate) const fn def(self) -> &'static RelationDef {
        &TABLE[self.index()]
    }

    /// The converse: `DR_N(a,b) ⇔ DR_S(b,a)`, `FL_E(a,b) ⇔ FL_W(b,a)`. `AL`
    /// is symmetric: `AL_N(a,b) ⇔ AL_N(b,a)`.
    pub const fn converse(self) -> Relation {
        match self.kind {
            Kind::AL => self,
            _ => Relation::new(self.kind, self.dir.opposite()),
        }
    }

    /// The default quantifier of the class lifting (docs/language.md#quantifiers): `every` for
    /// `DR`, `some` for the others.
    pub const fn default_quant(self) -> Quant {
        self.def().default_quant
    }

    /// Whether the default lifting is universal (`DR`).
    pub const fn is_universal(self) -> bool {
        matches!(self.default_quant(), Quant::Every)
    }

    /// The name as written in `.rcc` files, e.g. `DR_N`.
    pub const fn name(self) -> &'static str {
        self.def().name
    }

    /// Parse a relation name such as `EC_W`.
    pub fn from_name(s: &str) -> Option<Relation> {
        Relation::ALL.into_iter().find(|r| r.name() == s)
    }
}

impl fmt::Display for Relation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How `EC` decides that the projections on the shared side meet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Contact {
    /// Closures share at least one point (corner touches count). RCC's own EC.
    #[default]
    Point,
    /// A shared edge of positive length.
    Edge,
}

impl Contact {
    /// Both modes.
    pub const ALL: [Contact; 2] = [Contact::Point, Contact::Edge];
}

impl std::str::FromStr for Contact {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "point" => Ok(Contact::Point),
            "edge" => Ok(Contact::Edge),
            _ => Err(format!(
                "unknown contact mode `{s}`; expected `point` or `edge`"
            )),
        }
    }
}

impl fmt::Display for Contact {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Contact::Point => "point",
            Contact::Edge => "edge",
        })
    }
}

/// An axis of the plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// East–west.
    X,
    /// North–south.
    Y,
}

/// Which rectangle of the ordered pair `(a, b)` a coordinate belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// The subject `a`.
    A,
    /// The other object `b`.
    B,
}

/// An edge coordinate of a rectangle: `x`, `x2 = x + width`, `y`,
/// `y2 = y + height`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Edge {
    /// West edge `x`.
    X,
    /// East edge `x2`.
    X2,
    /// South edge `y`.
    Y,
    /// North edge `y2`.
    Y2,
}

impl Edge {
    /// The axis the coordinate lies on.
    pub const fn axis(self) -> Axis {
        match self {
            Edge::X | Edge::X2 => Axis::X,
            Edge::Y | Edge::Y2 => Axis::Y,
        }
    }
    /// Whether it is the far edge (`x2`, `y2`): the near edge plus the size.
    pub(crate) const fn is_far(self) -> bool {
        matches!(self, Edge::X2 | Edge::Y2)
    }
    /// Its value on `r`.
    pub const fn of(self, r: &Rect) -> i64 {
        match self {
            Edge::X => r.x,
            Edge::X2 => r.x2(),
            Edge::Y => r.y,
            Edge::Y2 => r.y2(),
        }
    }
}

/// A comparison operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Op {
    /// `>=`
    Ge,
    /// `>`
    Gt,
    /// `<=`
    Le,
    /// `<`
    Lt,
    /// `==`
    Eq,
}

/// One comparison `lhs OP rhs` between edge coordinates of the two
/// rectangles. Both sides always lie on the same axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Cmp {
    /// Left-hand coordinate.
    pub lhs: (Side, Edge),
    /// The operator.
    pub op: Op,
    /// Right-hand coordinate.
    pub rhs: (Side, Edge),
}

impl Cmp {
    /// Whether it holds for the pair `(a, b)`.
    pub fn holds(&self, a: &Rect, b: &Rect) -> bool {
        let pick = |s: Side| match s {
            Side::A => a,
            Side::B => b,
        };
        let l = self.lhs.1.of(pick(self.lhs.0));
        let r = self.rhs.1.of(pick(self.rhs.0));
        match self.op {
            Op::Ge => l >= r,
            Op::Gt => l > r,
            Op::Le => l <= r,
            Op::Lt => l < r,
            Op::Eq => l == r,
        }
    }
}

/// A condition: a disjunction of conjunctions of comparisons.
pub type Condition = &'static [&'static [Cmp]];

/// One relation's definition: the single source of its meaning.
#[derive(Debug, Clone, Copy)]
pub struct RelationDef {
    /// The relation.
    pub rel: Relation,
    /// Its `.rcc` name.
    pub name: &'static str,
    /// The quantifier an atom without one uses (docs/language.md#quantifiers).
    pub default_quant: Quant,
    /// The condition under `point` contact.
    pub point: Condition,
    /// The condition under `edge` contact.
    pub edge: Condition,
    /// English: what the subject does to the target, `{d}` for the
    /// direction word ("touches the {d} side of").
    pub verb: &'static str,
}

impl RelationDef {
    /// The condition for `contact`.
    pub const fn condition(&self, contact: Contact) -> Condition {
        match contact {
            Contact::Point => self.point,
            Contact::Edge => self.edge,
        }
    }
    /// Whether `rel(a, b)` holds, read straight off the condition (the
    /// reference that [`relation_bits`] is tested against).
    pub fn holds(&self, a: &Rect, b: &Rect, contact: Contact) -> bool {
        self.condition(contact)
            .iter()
            .any(|conj| conj.iter().all(|c| c.holds(a, b)))
    }
    /// The English verb phrase with the direction filled in.
    pub(crate) fn verb_phrase(&self) -> String {
        self.verb.replace("{d}", self.rel.dir.word())
    }
}

const fn cmp(l: Side, le: Edge, op: Op, r: Side, re: Edge) -> Cmp {
    Cmp {
        lhs: (l, le),
        op,
        rhs: (r, re),
    }
}

mod conditions {
    use super::Edge::{X, X2, Y, Y2};
    use super::Op::{Eq, Ge, Le, Lt};
    use super::Side::{A, B};
    use super::{cmp, Cmp};

    // Projections meet (point: closed intervals share a point; edge: open
    // intervals overlap), and one extent contains the other (flush).
    macro_rules! meet_point {
        ($lo:ident, $hi:ident) => {
            [cmp(A, $lo, Le, B, $hi), cmp(B, $lo, Le, A, $hi)]
        };
    }
    macro_rules! meet_edge {
        ($lo:ident, $hi:ident) => {
            [cmp(A, $lo, Lt, B, $hi), cmp(B, $lo, Lt, A, $hi)]
        };
    }
    macro_rules! contained {
        ($lo:ident, $hi:ident) => {
            [cmp(B, $lo, Le, A, $lo), cmp(A, $hi, Le, B, $hi)]
        };
    }
    macro_rules! contains {
        ($lo:ident, $hi:ident) => {
            [cmp(A, $lo, Le, B, $lo), cmp(B, $hi, Le, A, $hi)]
        };
    }
    macro_rules! cat {
        ($first:expr, $rest:expr) => {{
            let r = $rest;
            [$first, r[0], r[1]]
        }};
    }

    pub(super) const DR_N: &[&[Cmp]] = &[&[cmp(A, Y, Ge, B, Y2)]];
    pub(super) const DR_S: &[&[Cmp]] = &[&[cmp(A, Y2, Le, B, Y)]];
    pub(super) const DR_E: &[&[Cmp]] = &[&[cmp(A, X, Ge, B, X2)]];
    pub(super) const DR_W: &[&[Cmp]] = &[&[cmp(A, X2, Le, B, X)]];

    pub(super) const EC_N_P: &[&[Cmp]] = &[&cat!(cmp(A, Y, Eq, B, Y2), meet_point!(X, X2))];
    pub(super) const EC_S_P: &[&[Cmp]] = &[&cat!(cmp(A, Y2, Eq, B, Y), meet_point!(X, X2))];
    pub(super) const EC_E_P: &[&[Cmp]] = &[&cat!(cmp(A, X, Eq, B, X2), meet_point!(Y, Y2))];
    pub(super) const EC_W_P: &[&[Cmp]] = &[&cat!(cmp(A, X2, Eq, B, X), meet_point!(Y, Y2))];
    pub(super) const EC_N_E: &[&[Cmp]] = &[&cat!(cmp(A, Y, Eq, B, Y2), meet_edge!(X, X2))];
    pub(super) const EC_S_E: &[&[Cmp]] = &[&cat!(cmp(A, Y2, Eq, B, Y), meet_edge!(X, X2))];
    pub(super) const EC_E_E: &[&[Cmp]] = &[&cat!(cmp(A, X, Eq, B, X2), meet_edge!(Y, Y2))];
    pub(super) const EC_W_E: &[&[Cmp]] = &[&cat!(cmp(A, X2, Eq, B, X), meet_edge!(Y, Y2))];

    pub(super) const FL_N: &[&[Cmp]] = &[
        &cat!(cmp(A, Y, Eq, B, Y2), contained!(X, X2)),
        &cat!(cmp(A, Y, Eq, B, Y2), contains!(X, X2)),
    ];
    pub(super) const FL_S: &[&[Cmp]] = &[
        &cat!(cmp(A, Y2, Eq, B, Y), contained!(X, X2)),
        &cat!(cmp(A, Y2, Eq, B, Y), contains!(X, X2)),
    ];
    pub(super) const FL_E: &[&[Cmp]] = &[
        &cat!(cmp(A, X, Eq, B, X2), contained!(Y, Y2)),
        &cat!(cmp(A, X, Eq, B, X2), contains!(Y, Y2)),
    ];
    pub(super) const FL_W: &[&[Cmp]] = &[
        &cat!(cmp(A, X2, Eq, B, X), contained!(Y, Y2)),
        &cat!(cmp(A, X2, Eq, B, X), contains!(Y, Y2)),
    ];

    pub(super) const AL_N: &[&[Cmp]] = &[&[cmp(A, Y2, Eq, B, Y2)]];
    pub(super) const AL_S: &[&[Cmp]] = &[&[cmp(A, Y, Eq, B, Y)]];
    pub(super) const AL_E: &[&[Cmp]] = &[&[cmp(A, X2, Eq, B, X2)]];
    pub(super) const AL_W: &[&[Cmp]] = &[&[cmp(A, X, Eq, B, X)]];
}

const fn def(
    kind: Kind,
    dir: Dir,
    name: &'static str,
    point: Condition,
    edge: Condition,
    verb: &'static str,
) -> RelationDef {
    RelationDef {
        rel: Relation::new(kind, dir),
        name,
        default_quant: match kind {
            Kind::DR => Quant::Every,
            _ => Quant::Some,
        },
        point,
        edge,
        verb,
    }
}

/// Every relation, in bit order: the one place a relation's meaning is
/// written (docs/language.md#relations and docs/language.md#relations).
pub const TABLE: [RelationDef; 16] = {
    use conditions as c;
    use Dir::{E, N, S, W};
    use Kind::{AL, DR, EC, FL};
    const DRV: &str = "is {d} of";
    const ECV: &str = "touches the {d} side of";
    const FLV: &str = "lies flush on the {d} side of";
    const ALV: &str = "has its {d} edge in line with";
    [
        def(DR, N, "DR_N", c::DR_N, c::DR_N, DRV),
        def(DR, S, "DR_S", c::DR_S, c::DR_S, DRV),
        def(DR, E, "DR_E", c::DR_E, c::DR_E, DRV),
        def(DR, W, "DR_W", c::DR_W, c::DR_W, DRV),
        def(EC, N, "EC_N", c::EC_N_P, c::EC_N_E, ECV),
        def(EC, S, "EC_S", c::EC_S_P, c::EC_S_E, ECV),
        def(EC, E, "EC_E", c::EC_E_P, c::EC_E_E, ECV),
        def(EC, W, "EC_W", c::EC_W_P, c::EC_W_E, ECV),
        def(FL, N, "FL_N", c::FL_N, c::FL_N, FLV),
        def(FL, S, "FL_S", c::FL_S, c::FL_S, FLV),
        def(FL, E, "FL_E", c::FL_E, c::FL_E, FLV),
        def(FL, W, "FL_W", c::FL_W, c::FL_W, FLV),
        def(AL, N, "AL_N", c::AL_N, c::AL_N, ALV),
        def(AL, S, "AL_S", c::AL_S, c::AL_S, ALV),
        def(AL, E, "AL_E", c::AL_E, c::AL_E, ALV),
        def(AL, W, "AL_W", c::AL_W, c::AL_W, ALV),
    ]
};
