//! The hidden style of a generated task: per class a [`Habit`] (a band against
//! a wall, a corner cluster, a stack, a cluster, north of another class, or a
//! group shape) and the class's block size and largest count.

use serde::Serialize;

/// A side of the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum WallSide {
    /// The north wall (top, +y).
    N,
    /// The south wall (the floor).
    S,
    /// The east wall.
    E,
    /// The west wall.
    W,
}

/// A corner of the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Corner {
    /// South-west.
    SW,
    /// South-east.
    SE,
    /// North-west.
    NW,
    /// North-east.
    NE,
}

impl Corner {
    pub(super) fn east(self) -> bool {
        matches!(self, Corner::SE | Corner::NE)
    }
    pub(super) fn north(self) -> bool {
        matches!(self, Corner::NW | Corner::NE)
    }
}

/// How a class's blocks are placed in every demonstration (the hidden
/// "intended" style).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "habit", rename_all = "snake_case")]
pub enum Habit {
    /// One contiguous row (or column) against a wall, anywhere along it.
    Band {
        /// The wall.
        wall: WallSide,
    },
    /// A compact cluster filling a corner, row by row.
    Corner {
        /// The corner.
        corner: Corner,
    },
    /// A column standing on the floor (spilling into a neighbouring column
    /// when the box is not high enough), anywhere along the floor.
    Stack,
    /// A connected cluster (every block flush against another) anywhere.
    Cluster,
    /// A connected cluster north of every block of an earlier class,
    /// resting on its topmost block.
    NorthOf {
        /// Index of the other class.
        class: usize,
    },
    /// Group tasks ([`groups`](super::groups)): one row anywhere in the box.
    Row,
    /// Group tasks: one column, against a wall (`W` or `E`) or anywhere.
    Column {
        /// The wall it stands against, if any.
        wall: Option<WallSide>,
    },
    /// Group tasks: one compact block, `⌈√n⌉` columns filled row by row.
    Block,
}

impl Habit {
    /// In words, with the class names.
    pub fn describe(&self, classes: &[ClassSpec]) -> String {
        match self {
            Habit::Band { wall } => format!("band on the {wall:?} wall"),
            Habit::Corner { corner } => format!("{corner:?} corner"),
            Habit::Stack => "stack on the floor".into(),
            Habit::Cluster => "cluster".into(),
            Habit::NorthOf { class } => format!("north of {}", classes[*class].class),
            Habit::Row => "one row".into(),
            Habit::Column { wall: None } => "one column".into(),
            Habit::Column { wall: Some(w) } => format!("one column on the {w:?} wall"),
            Habit::Block => "one block".into(),
        }
    }
}

/// One block class of a task.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClassSpec {
    /// Its name (`R`, `G`, …).
    pub class: String,
    /// Block width.
    pub width: i64,
    /// Block height.
    pub height: i64,
    /// The largest count a demonstration shows.
    pub max_count: usize,
    /// How the demonstrations place it.
    pub habit: Habit,
    /// Whether its blocks turn (`bench tasks --turnable`), and how the
    /// demonstrations lay them.
    #[serde(skip_serializing_if = "Orientation::is_fixed")]
    pub orientation: Orientation,
}

/// Whether a class's blocks turn (`bench tasks --turnable`: the oblong
/// classes do), and the demonstrator's orientation habit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Orientation {
    /// Not turnable: square blocks, or a run without `--turnable`.
    #[default]
    Fixed,
    /// Turnable; every demonstration lays every block flat.
    Flat,
    /// Turnable; every demonstration stands every block on end (turned).
    OnEnd,
}

impl Orientation {
    /// Not turnable.
    pub fn is_fixed(&self) -> bool {
        *self == Orientation::Fixed
    }

    /// The orientation statement a demonstrator with this habit means:
    /// `turned(A)` ("every A lies turned") or `!turned(A)` ("no A lies
    /// turned"); `None` when the blocks do not turn.
    pub fn meant(&self, class: &str) -> Option<rccpack::rules::Formula> {
        let t = rccpack::rules::Formula::Turned(class.to_string());
        match self {
            Orientation::Fixed => None,
            Orientation::Flat => Some(rccpack::rules::Formula::not(t)),
            Orientation::OnEnd => Some(t),
        }
    }
}
