//! The plane: [`Rect`] (closed integer rectangles) and [`Space`] (the table).

use serde::{Deserialize, Serialize};

/// An axis-aligned rectangle with integer min corner and size.
///
/// It occupies the closed set `[x, x+w] × [y, y+h]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Rect {
    /// Min x (west edge).
    pub x: i64,
    /// Min y (south edge).
    pub y: i64,
    /// Width, ≥ 1.
    pub w: i64,
    /// Height, ≥ 1.
    pub h: i64,
}

impl Rect {
    /// A rectangle from its min corner and size.
    pub const fn new(x: i64, y: i64, w: i64, h: i64) -> Self {
        Rect { x, y, w, h }
    }
    /// East edge `x + w` (saturating: exact for every rectangle of a
    /// validated scene, and no overflow for one built in code).
    pub const fn x2(&self) -> i64 {
        self.x.saturating_add(self.w)
    }
    /// North edge `y + h` (saturating, like [`Rect::x2`]).
    pub const fn y2(&self) -> i64 {
        self.y.saturating_add(self.h)
    }
    /// Whether the interiors of `self` and `other` overlap (touching is fine).
    pub const fn interiors_overlap(&self, other: &Rect) -> bool {
        self.x < other.x2() && other.x < self.x2() && self.y < other.y2() && other.y < self.y2()
    }
    /// Whether `self` lies inside `outer` (closed containment).
    pub const fn inside(&self, outer: &Rect) -> bool {
        self.x >= outer.x && self.y >= outer.y && self.x2() <= outer.x2() && self.y2() <= outer.y2()
    }
}

/// The table on which objects are laid out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Space {
    /// Min x; defaults to 0.
    #[serde(default, deserialize_with = "super::int")]
    pub x: i64,
    /// Min y; defaults to 0.
    #[serde(default, deserialize_with = "super::int")]
    pub y: i64,
    /// Width, ≥ 1.
    #[serde(deserialize_with = "super::int")]
    pub width: i64,
    /// Height, ≥ 1.
    #[serde(deserialize_with = "super::int")]
    pub height: i64,
}

impl Space {
    /// The space as a rectangle.
    pub const fn rect(&self) -> Rect {
        Rect::new(self.x, self.y, self.width, self.height)
    }
}
