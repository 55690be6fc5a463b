//! The eight directional relations between rectangles and their lifting to
//! classes (SPEC §3–§4).
//!
//! # Background
//!
//! Region Connection Calculus distinguishes regions that are *discrete*
//! (`DR`: interiors disjoint) from regions that are *externally connected*
//! (`EC`: they touch but interiors do not overlap). We augment each with a
//! direction `N`, `S`, `E`, `W` (north is +y).
//!
//! # Practical
//!
//! All eight relations between an ordered pair fit in one byte
//! ([`relation_bits`], bit `Relation::index()`). A [`ClassAtoms`] table holds,
//! per placed object and per target (a class or `*`), one byte whose bits are
//! the *class* atoms of §4: `DR_d` bits are the AND over every other object of
//! the target, `EC_d` bits the OR. Building it is `O(n²)`; afterwards every
//! atom of every rule is one lookup, which is what learning needs.
//!
//! # How to extend
//!
//! A new relation takes a free bit (bits 8+ need a wider mask type), a name in
//! [`Relation::ALL`], a case in [`relation_bits`], and its class-lifting
//! quantifier in [`Relation::is_universal`].

use crate::scene::{Rect, Scene};
use std::fmt;

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
}

/// Discrete or externally connected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    /// Discrete from, in a direction.
    DR,
    /// Externally connected, on a side.
    EC,
}

/// One of the eight directional relations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Relation {
    /// `DR` or `EC`.
    pub kind: Kind,
    /// The direction.
    pub dir: Dir,
}

impl Relation {
    /// All eight, in bit order: `DR_N DR_S DR_E DR_W EC_N EC_S EC_E EC_W`.
    pub const ALL: [Relation; 8] = [
        Relation::new(Kind::DR, Dir::N),
        Relation::new(Kind::DR, Dir::S),
        Relation::new(Kind::DR, Dir::E),
        Relation::new(Kind::DR, Dir::W),
        Relation::new(Kind::EC, Dir::N),
        Relation::new(Kind::EC, Dir::S),
        Relation::new(Kind::EC, Dir::E),
        Relation::new(Kind::EC, Dir::W),
    ];

    /// Build a relation.
    pub const fn new(kind: Kind, dir: Dir) -> Self {
        Relation { kind, dir }
    }

    /// Bit index 0..8.
    pub const fn index(self) -> usize {
        let k = match self.kind {
            Kind::DR => 0,
            Kind::EC => 4,
        };
        k + match self.dir {
            Dir::N => 0,
            Dir::S => 1,
            Dir::E => 2,
            Dir::W => 3,
        }
    }

    /// The bit `1 << index()`.
    pub const fn bit(self) -> u8 {
        1 << self.index()
    }

    /// The converse: `DR_N(a,b) ⇔ DR_S(b,a)`.
    pub const fn converse(self) -> Relation {
        Relation::new(self.kind, self.dir.opposite())
    }

    /// Class lifting: `DR` atoms quantify over *every* target object (true when
    /// there is none); `EC` atoms ask for *at least one*.
    pub const fn is_universal(self) -> bool {
        matches!(self.kind, Kind::DR)
    }

    /// The name as written in `.rcc` files, e.g. `DR_N`.
    pub fn name(self) -> &'static str {
        const NAMES: [&str; 8] = ["DR_N", "DR_S", "DR_E", "DR_W", "EC_N", "EC_S", "EC_E", "EC_W"];
        NAMES[self.index()]
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

impl std::str::FromStr for Contact {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "point" => Ok(Contact::Point),
            "edge" => Ok(Contact::Edge),
            _ => Err(format!("unknown contact mode `{s}`; expected `point` or `edge`")),
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

/// Whether intervals `[a1, a2]` and `[b1, b2]` meet under `contact`.
#[inline]
pub const fn projections_meet(a1: i64, a2: i64, b1: i64, b2: i64, contact: Contact) -> bool {
    match contact {
        Contact::Point => a1 <= b2 && b1 <= a2,
        Contact::Edge => a1 < b2 && b1 < a2,
    }
}

/// All eight relations of `(a, b)` as one byte (bit `Relation::index()`).
#[inline]
pub fn relation_bits(a: &Rect, b: &Rect, contact: Contact) -> u8 {
    let mut bits = 0u8;
    let (ax2, ay2, bx2, by2) = (a.x2(), a.y2(), b.x2(), b.y2());
    if a.y >= by2 {
        bits |= 1; // DR_N
    }
    if ay2 <= b.y {
        bits |= 2; // DR_S
    }
    if a.x >= bx2 {
        bits |= 4; // DR_E
    }
    if ax2 <= b.x {
        bits |= 8; // DR_W
    }
    let xm = projections_meet(a.x, ax2, b.x, bx2, contact);
    let ym = projections_meet(a.y, ay2, b.y, by2, contact);
    if a.y == by2 && xm {
        bits |= 16; // EC_N
    }
    if ay2 == b.y && xm {
        bits |= 32; // EC_S
    }
    if a.x == bx2 && ym {
        bits |= 64; // EC_E
    }
    if ax2 == b.x && ym {
        bits |= 128; // EC_W
    }
    bits
}

/// Whether `rel(a, b)` holds.
#[inline]
pub fn holds(rel: Relation, a: &Rect, b: &Rect, contact: Contact) -> bool {
    relation_bits(a, b, contact) & rel.bit() != 0
}

/// Mask of the `DR` bits (the universally quantified ones).
pub const DR_MASK: u8 = 0x0F;
/// Mask of the `EC` bits (the existentially quantified ones).
pub const EC_MASK: u8 = 0xF0;

/// The identity of class lifting: what an atom byte is when the target has no
/// object (all `DR` true, all `EC` false).
pub const EMPTY_TARGET: u8 = DR_MASK;

/// Combine one pair's relation byte into a running class-atom byte:
/// `DR` bits AND, `EC` bits OR.
#[inline]
pub const fn lift(acc: u8, pair: u8) -> u8 {
    (acc & (pair | EC_MASK)) | (pair & EC_MASK)
}

/// Class names interned to dense indices for one evaluation.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ClassIndex {
    names: Vec<String>,
}

impl ClassIndex {
    /// The classes of a scene, in order of first appearance.
    pub fn of_scene(scene: &Scene) -> Self {
        ClassIndex {
            names: scene.classes().into_iter().map(String::from).collect(),
        }
    }
    /// Intern a name (adds it when new) and return its index.
    pub fn intern(&mut self, name: &str) -> usize {
        match self.get(name) {
            Some(i) => i,
            None => {
                self.names.push(name.to_string());
                self.names.len() - 1
            }
        }
    }
    /// Index of a class name.
    pub fn get(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }
    /// Number of classes.
    pub fn len(&self) -> usize {
        self.names.len()
    }
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }
    /// Name of class `i`.
    pub fn name(&self, i: usize) -> &str {
        &self.names[i]
    }
    /// All names.
    pub fn names(&self) -> &[String] {
        &self.names
    }
}

/// Per placed object and per target (every class, then `*`), the byte of
/// class-atom values of SPEC §4.
///
/// Object indices are indices into `scene.objects`; unplaced objects have no
/// row (they take no part in evaluation).
#[derive(Debug, Clone)]
pub struct ClassAtoms {
    /// Number of targets per row = classes + 1 (the last is `*`).
    stride: usize,
    /// `row[i]`: row start of object `i` in `bytes`, or `usize::MAX` if unplaced.
    row: Vec<usize>,
    /// Class index of each object.
    class_of: Vec<usize>,
    bytes: Vec<u8>,
}

impl ClassAtoms {
    /// Build the table for `scene` with the given class index (every class of
    /// the scene must be in it; extra classes simply have no objects).
    pub fn new(scene: &Scene, classes: &ClassIndex, contact: Contact) -> Self {
        let n = scene.objects.len();
        let stride = classes.len() + 1;
        let class_of: Vec<usize> = scene
            .objects
            .iter()
            .map(|o| classes.get(&o.class).expect("class index covers the scene"))
            .collect();
        let rects: Vec<Option<Rect>> = scene.objects.iter().map(|o| o.rect()).collect();
        let mut row = vec![usize::MAX; n];
        let mut next = 0;
        for i in 0..n {
            if rects[i].is_some() {
                row[i] = next;
                next += stride;
            }
        }
        let mut bytes = vec![EMPTY_TARGET; next];
        for i in 0..n {
            let Some(a) = rects[i] else { continue };
            let base = row[i];
            for j in 0..n {
                if i == j {
                    continue;
                }
                let Some(b) = rects[j] else { continue };
                let bits = relation_bits(&a, &b, contact);
                let t = base + class_of[j];
                bytes[t] = lift(bytes[t], bits);
                let any = base + stride - 1;
                bytes[any] = lift(bytes[any], bits);
            }
        }
        ClassAtoms {
            stride,
            row,
            class_of,
            bytes,
        }
    }

    /// The atom byte of object `obj` against `target` (`None` = `*`), or
    /// `None` when the object is unplaced.
    #[inline]
    pub fn byte(&self, obj: usize, target: Option<usize>) -> Option<u8> {
        let r = *self.row.get(obj)?;
        if r == usize::MAX {
            return None;
        }
        let t = match target {
            None => self.stride - 1,
            Some(t) if t < self.stride - 1 => t,
            // A class the table does not know has no objects.
            Some(_) => return Some(EMPTY_TARGET),
        };
        Some(self.bytes[r + t])
    }

    /// Whether the class atom `rel(obj's class, target)` holds for `obj`.
    /// Unplaced objects satisfy nothing.
    #[inline]
    pub fn holds(&self, obj: usize, rel: Relation, target: Option<usize>) -> bool {
        self.byte(obj, target).is_some_and(|b| b & rel.bit() != 0)
    }

    /// Class index of object `obj`.
    pub fn class_of(&self, obj: usize) -> usize {
        self.class_of[obj]
    }
}
