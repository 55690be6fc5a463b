//! One [`Object`]: class, size, position, fixed/turnable/turned, and its footprint.

use super::Rect;

/// One object: a class, a size and, when placed, a position.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Object {
    /// Unique id within the scene.
    pub id: String,
    /// Class name, e.g. `R`.
    pub class: String,
    /// Min x when placed.
    pub x: Option<i64>,
    /// Min y when placed.
    pub y: Option<i64>,
    /// Width, ≥ 1.
    pub width: i64,
    /// Height, ≥ 1.
    pub height: i64,
    /// A fixed object never moves (walls).
    pub fixed: bool,
    /// A movable object that may be placed turned by 90° (docs/scenes.md#turns).
    pub turnable: bool,
    /// A placed object lying turned by 90°: its footprint is
    /// `height × width` ([`Object::footprint`]).
    pub turned: bool,
}

impl Object {
    /// An unplaced movable object (what a problem asks to place).
    pub fn movable(id: &str, class: &str, width: i64, height: i64) -> Self {
        Object {
            id: id.into(),
            class: class.into(),
            x: None,
            y: None,
            width,
            height,
            fixed: false,
            turnable: false,
            turned: false,
        }
    }

    /// A placed movable object (as in a demonstration).
    pub fn placed(id: &str, class: &str, x: i64, y: i64, width: i64, height: i64) -> Self {
        Object {
            x: Some(x),
            y: Some(y),
            ..Object::movable(id, class, width, height)
        }
    }

    /// A fixed, placed object (a wall).
    pub fn fixed_at(id: &str, class: &str, x: i64, y: i64, width: i64, height: i64) -> Self {
        Object {
            id: id.into(),
            class: class.into(),
            x: Some(x),
            y: Some(y),
            width,
            height,
            fixed: true,
            turnable: false,
            turned: false,
        }
    }

    /// The same object, allowed to turn (builder style).
    #[must_use]
    pub fn with_turnable(mut self) -> Self {
        self.turnable = true;
        self
    }

    /// The same object, lying turned (builder style).
    #[must_use]
    pub fn with_turned(mut self) -> Self {
        self.turned = true;
        self
    }

    /// The footprint `(w, h)` the object occupies: `(width, height)`, or
    /// `(height, width)` when it lies turned. Every geometric consumer
    /// (relations, evaluation, synthesis, rendering) goes through this.
    pub const fn footprint(&self) -> (i64, i64) {
        if self.turned {
            (self.height, self.width)
        } else {
            (self.width, self.height)
        }
    }

    /// Whether the object has a position.
    pub const fn is_placed(&self) -> bool {
        self.x.is_some() && self.y.is_some()
    }
    /// The occupied rectangle (the [`Object::footprint`] at the
    /// position), when placed.
    pub fn rect(&self) -> Option<Rect> {
        let (w, h) = self.footprint();
        Some(Rect::new(self.x?, self.y?, w, h))
    }

    /// Whether the object's two sides differ, so that turning it changes
    /// its footprint.
    pub const fn is_oblong(&self) -> bool {
        self.width != self.height
    }
}
