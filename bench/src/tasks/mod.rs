//! Realistic tasks (`rccpack-bench tasks`): demonstrations made the
//! way a person makes them, rules learned from them with the default
//! templates, and problems with more objects than any demonstration showed.
//!
//! # Generated tasks
//!
//! Task `t` draws everything from `ChaCha8Rng::seed_from_u64(seed)` on
//! stream `t + 1`:
//!
//! 1. **Classes.** 2–4 block classes (`R`, `G`, `B`, `Y`, in that order),
//!    each with one block size (mostly 20×20; also 30×30, 30×20, 20×30,
//!    40×20), and per class the largest count `M_c` a demonstration shows
//!    (2–6, adjusted so that `10 ≤ Σ M_c ≤ 20`).
//! 2. **A hidden style.** Per class one [`Habit`]: a band against a wall, a
//!    cluster in a corner, a stack standing on the floor, a connected
//!    cluster anywhere, or a group north of an earlier class (resting on
//!    it). Anchors (walls, corners) are not shared between classes.
//! 3. **One box** (four fixed walls of class `W` on a table, grid 10) sized
//!    for the task's largest problem: interior area ≈ 2.25× the blocks'
//!    total area at `max(3, largest size)` times `M_c` blocks per class,
//!    aspect 1, 1.25 or 1.5 (wide or tall), every side long enough for a
//!    band; free table around the box about as wide as the box. The
//!    demonstrations and every problem of the task share this box, so the
//!    absolute positions of resemblance (docs/guide.md#layouts-like-the-demonstrations)
//!    mean the same in both.
//! 4. **Demonstrations.** 3–5 complete scenes; per class 2..=`M_c` blocks
//!    (one demonstration shows `M_c`), placed procedurally by the class's
//!    habit with random offsets (where along the wall, which shape of
//!    corner cluster, where the stack stands, …). Every demonstration is on
//!    the grid, inside the box and overlap-free ([`Scene::validate`]).
//! 5. **Rules.** [`learn`](rccpack::infer::learn) with [`LearnParams::default`](rccpack::infer::LearnParams::default) (second-edition
//!    templates, 1000 samples, cutoff 0.01).
//! 6. **Problems.** For every size `m` in the configuration, `⌈m·M_c⌉`
//!    unplaced blocks of each class in the task's box.
//!
//! With [`TasksConfig::turnable`] (`--turnable`), every oblong class's
//! blocks are `turnable` (in the problems and the demonstrations), and per
//! such class a coin from a stream of its own (so the classes, habits and
//! box are drawn as without it) says whether the demonstrator lays every
//! block flat or stands every one on end ([`Orientation`]): the meant
//! statement is then "no A lies turned" or "every A lies turned".
//!
//! # The bundled example, scaled
//!
//! `examples/box-packing` (compiled in): rules learned from its
//! `demos.json`, problems with 5, 6, 8, 12 blocks of each class (same
//! sizes) in its box.
//!
//! # Solving
//!
//! Every problem is solved with the engine in two modes: score only, and
//! with `like` = the demonstrations (docs/guide.md#layouts-like-the-demonstrations). Both get
//! `SynthOptions::warm_start` = the demonstrations unless the configuration
//! says otherwise. Every layout is re-checked by the checker. Peers solve
//! the emitted (score-only) model and are compared with the score-only run.

mod generate;
mod place;
mod report;
mod solve;
mod style;

use super::peers::Peer;
pub use super::{SolveFn, Solver, VerifyFn};
use rccpack::infer::{InferError, Templates};
use rccpack::rules::RuleSet;
use rccpack::scene::Scene;
use serde::Serialize;
use std::time::Duration;

pub(crate) use generate::draw_maxes;
pub use generate::{all_tasks, example_task, generate_task};
use generate::{learn_with, problems_in, style_text};
pub use place::BoxGeom;
pub(crate) use place::{block, box_for, make_demos_n};
use place::{demo_scene, rotated, Placer};
pub use report::{
    row_line, summarize, table_text, PeerCell, TaskReport, TasksReport, TasksSummary,
};
pub use solve::{
    peer_not_applicable, run_tasks, solve_once, solve_options, solve_peer, SolveRow, TaskRow,
    TasksEvent, PEER_NOT_APPLICABLE,
};
pub use style::{ClassSpec, Corner, Habit, Orientation, WallSide};

pub mod groups;

/// The block classes of generated tasks, in order (a task with `k` classes
/// uses the first `k`).
pub const TASK_CLASSES: [&str; 4] = ["R", "G", "B", "Y"];

/// Grid step of every scene.
pub const GRID: i64 = 10;

/// Thickness of the walls.
pub const WALL: i64 = 10;

/// The sizes a class's blocks may have (20×20 three times as likely).
pub(crate) const BLOCK_SIZES: [(i64, i64); 7] = [
    (20, 20),
    (20, 20),
    (20, 20),
    (30, 30),
    (30, 20),
    (20, 30),
    (40, 20),
];

/// The smallest multiplier the box of a task is sized for (so that the
/// problems of a seed do not depend on which sizes a run asks for, up to 3).
pub const BOX_FOR: f64 = 3.0;

/// The bundled example's demonstrations (compiled in).
pub const EXAMPLE_DEMOS: &str = include_str!("../../../examples/box-packing/demos.json");

/// The bundled example's problem (compiled in).
pub const EXAMPLE_PROBLEM: &str = include_str!("../../../examples/box-packing/problem.json");

/// Which series a problem belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TaskSeries {
    /// Generated tasks.
    Tasks,
    /// The bundled example, scaled.
    Example,
    /// Group-style tasks ([`groups`]).
    Groups,
}

impl TaskSeries {
    /// `tasks` or `example`.
    pub fn name(self) -> &'static str {
        match self {
            TaskSeries::Tasks => "tasks",
            TaskSeries::Example => "example",
            TaskSeries::Groups => "groups",
        }
    }
}

/// One problem of a task.
#[derive(Debug, Clone, PartialEq)]
pub struct TaskProblem {
    /// Index of its size in the configuration's sizes (or example counts).
    pub size_index: usize,
    /// `1x`, `1.5x`, … or `5/class`.
    pub size: String,
    /// File name stem: `task03-1.5x`, `example-8`.
    pub name: String,
    /// Walls fixed, blocks unplaced.
    pub scene: Scene,
    /// Movable objects.
    pub movable: usize,
}

/// One task: demonstrations, learned rules, problems.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchTask {
    /// Generated tasks or the bundled example.
    pub series: TaskSeries,
    /// Index within its series.
    pub index: usize,
    /// Its classes (empty for the bundled example).
    pub classes: Vec<ClassSpec>,
    /// The style in words, e.g. `R: band on the S wall; G: north of R`.
    pub style: String,
    /// The demonstrations (complete scenes in the task's box).
    pub demos: Vec<Scene>,
    /// The learned rules, as `rccpack learn` writes them.
    pub rcc: String,
    /// The learned rules.
    pub rules: RuleSet,
    /// Its problems, smallest first.
    pub problems: Vec<TaskProblem>,
}

/// Why a task cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TaskGenError {
    /// Learning failed.
    #[error("task {task}: learning failed: {error}")]
    Learn {
        /// Task index.
        task: usize,
        /// The learner's error.
        error: InferError,
    },
    /// No style could be placed (should not happen: the box is large).
    #[error("task {task}: no demonstrations could be placed after {tries} styles")]
    Unplaceable {
        /// Task index.
        task: usize,
        /// Styles tried.
        tries: usize,
    },
    /// The bundled example did not load.
    #[error("the bundled example: {0}")]
    Example(String),
}

/// Benchmark parameters.
#[derive(Debug, Clone, Serialize)]
pub struct TasksConfig {
    /// Seed of every random choice (and of the solver).
    pub seed: u64,
    /// Per-solve time limit (each mode, each peer).
    #[serde(serialize_with = "super::thesis::ser_secs")]
    pub time_limit: Duration,
    /// Generated tasks.
    pub tasks: usize,
    /// Multipliers of the demonstrations' largest count per class.
    pub sizes: Vec<f64>,
    /// Blocks per class of the bundled example's problems (empty: no
    /// example series).
    pub example_counts: Vec<usize>,
    /// Also solve with `like` = the demonstrations.
    pub like: bool,
    /// Hand the demonstrations to `SynthOptions::warm_start`.
    pub warm_start: bool,
    /// Large-neighbourhood search (`SynthOptions::lns`).
    pub lns: bool,
    /// Peer solvers on the score-only model.
    #[serde(serialize_with = "super::thesis::ser_peers")]
    pub peers: Vec<Peer>,
    /// Group-style tasks ([`groups`]), after the others.
    pub groups: usize,
    /// The templates rules are learned with.
    #[serde(serialize_with = "ser_templates")]
    pub templates: Templates,
    /// Generated tasks: the oblong classes' blocks turn, and the
    /// demonstrator lays each such class flat or stands it on end
    /// ([`Orientation`]); off, the tasks are those of earlier versions.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub turnable: bool,
    /// Engine tuning of every solve (never changes an answer; the
    /// command filled it from `RCCPACK_*` variables).
    #[serde(skip)]
    pub tuning: rccpack::synth::Tuning,
}

fn ser_templates<S: serde::Serializer>(t: &Templates, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&t.to_string())
}

impl TasksConfig {
    /// The full benchmark: 10 tasks at 1×, 1.5×, 2×, 3×, the bundled
    /// example at 5, 6, 8, 12 per class, both modes, warm start, LNS.
    pub fn full(seed: u64, time_limit: Duration) -> Self {
        TasksConfig {
            seed,
            time_limit,
            tasks: 10,
            sizes: vec![1.0, 1.5, 2.0, 3.0],
            example_counts: vec![5, 6, 8, 12],
            like: true,
            warm_start: true,
            lns: true,
            peers: Vec::new(),
            groups: 0,
            templates: Templates::default(),
            turnable: false,
            tuning: rccpack::synth::Tuning::default(),
        }
    }

    /// A smoke run: 2 tasks at 1× and 1.5×, the example at 5 per class.
    pub fn quick(seed: u64, time_limit: Duration) -> Self {
        TasksConfig {
            tasks: 2,
            sizes: vec![1.0, 1.5],
            example_counts: vec![5],
            ..Self::full(seed, time_limit)
        }
    }
}

/// `1x`, `1.5x`, `2x`.
pub fn size_label(m: f64) -> String {
    format!("{m}x")
}

/// `⌈m·count⌉`, at least 1.
pub fn scaled(count: usize, m: f64) -> usize {
    ((count as f64 * m - 1e-9).ceil() as usize).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaled_counts() {
        assert_eq!(scaled(4, 1.0), 4);
        assert_eq!(scaled(5, 1.5), 8);
        assert_eq!(scaled(3, 1.5), 5);
        assert_eq!(scaled(6, 3.0), 18);
        assert_eq!(size_label(1.5), "1.5x");
        assert_eq!(size_label(2.0), "2x");
    }

    #[test]
    fn box_scene_is_valid() {
        let g = BoxGeom {
            width: 200,
            height: 200,
            margin: 190,
        };
        let s = g.scene();
        s.validate().unwrap();
        assert_eq!((s.space.width, s.space.height), (600, 600));
        // The same walls as the bundled example's.
        let base = Scene::from_json(EXAMPLE_PROBLEM).unwrap();
        let walls: Vec<_> = base.objects.iter().filter(|o| o.fixed).cloned().collect();
        assert_eq!(s.objects, walls);
    }
}
