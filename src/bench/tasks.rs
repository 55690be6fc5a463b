//! Realistic tasks (`rccpack bench tasks`, issue 20): demonstrations made the
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
//!    demonstrations and every problem of the task share this box, so SPEC
//!    §12's absolute resemblance positions mean the same in both.
//! 4. **Demonstrations.** 3–5 complete scenes; per class 2..=`M_c` blocks
//!    (one demonstration shows `M_c`), placed procedurally by the class's
//!    habit with random offsets (where along the wall, which shape of
//!    corner cluster, where the stack stands, …). Every demonstration is on
//!    the grid, inside the box and overlap-free ([`Scene::validate`]).
//! 5. **Rules.** [`learn`] with [`LearnParams::default`] (second-edition
//!    templates, 1000 samples, cutoff 0.01).
//! 6. **Problems.** For every size `m` in the configuration, `⌈m·M_c⌉`
//!    unplaced blocks of each class in the task's box.
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
//! with `like` = the demonstrations (SPEC §12). Both get
//! `SynthOptions::warm_start` = the demonstrations unless the configuration
//! says otherwise. Every layout is re-checked by the checker. Peers solve
//! the emitted (score-only) model and are compared with the score-only run.

use super::peers::{self, Peer, PeerStatus};
use super::thesis::{median, PeerRow};
use crate::infer::{learn, InferError, LearnParams, Templates};
use crate::relations::Contact;
use crate::resemblance::ResemblanceTarget;
use crate::rules::RuleSet;
use crate::scene::{scenes_from_json, Object, Rect, Scene, Space};
use crate::synth::{Status, SynthOptions};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use std::time::{Duration, Instant};

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
pub const EXAMPLE_DEMOS: &str = include_str!("../../examples/box-packing/demos.json");
/// The bundled example's problem (compiled in).
pub const EXAMPLE_PROBLEM: &str = include_str!("../../examples/box-packing/problem.json");

/// A side of the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Side {
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
    fn east(self) -> bool {
        matches!(self, Corner::SE | Corner::NE)
    }
    fn north(self) -> bool {
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
        wall: Side,
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
    /// Group tasks ([`groups`]): one row anywhere in the box.
    Row,
    /// Group tasks: one column, against a wall (`W` or `E`) or anywhere.
    Column {
        /// The wall it stands against, if any.
        wall: Option<Side>,
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
}

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
pub struct Task {
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
pub enum TaskError {
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

/// The box of a task: interior `width × height`, `margin` of free table
/// around the walls, grid 10.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BoxGeom {
    /// Interior width.
    pub width: i64,
    /// Interior height.
    pub height: i64,
    /// Free table between the walls and the edge of the space.
    pub margin: i64,
}

impl BoxGeom {
    /// The interior as a rectangle.
    pub fn interior(&self) -> Rect {
        let lo = self.margin + WALL;
        Rect::new(lo, lo, self.width, self.height)
    }

    /// The empty box: four fixed walls `w_south`, `w_north`, `w_west`,
    /// `w_east` of class `W`.
    pub fn scene(&self) -> Scene {
        let lo = self.margin;
        let inner = self.margin + WALL;
        let wall = |id: &str, x, y, w, h| Object::fixed_at(id, "W", x, y, w, h);
        Scene {
            space: Space {
                x: 0,
                y: 0,
                width: self.width + 2 * (WALL + self.margin),
                height: self.height + 2 * (WALL + self.margin),
            },
            grid: GRID,
            objects: vec![
                wall("w_south", lo, lo, self.width + 2 * WALL, WALL),
                wall(
                    "w_north",
                    lo,
                    inner + self.height,
                    self.width + 2 * WALL,
                    WALL,
                ),
                wall("w_west", lo, inner, WALL, self.height),
                wall("w_east", inner + self.width, inner, WALL, self.height),
            ],
        }
    }
}

fn round_up(v: f64) -> i64 {
    ((v / GRID as f64).ceil() as i64) * GRID
}

/// The box for `classes` (see the module doc, step 3).
pub(crate) fn box_for(classes: &[ClassSpec], largest: f64, rng: &mut ChaCha8Rng) -> BoxGeom {
    let area: i64 = classes
        .iter()
        .map(|c| scaled(c.max_count, largest) as i64 * c.width * c.height)
        .sum();
    let target = 2.25 * area as f64;
    let aspect = [1.0, 1.25, 1.5][rng.random_range(0..3usize)];
    let wide = rng.random_bool(0.5);
    let long = round_up((target * aspect).sqrt());
    let short = round_up(target / long as f64);
    let (mut w, mut h) = if wide { (long, short) } else { (short, long) };
    // Room for the longest band or stack of a demonstration, and more.
    let need = classes
        .iter()
        .map(|c| c.max_count as i64 * c.width.max(c.height) + 2 * GRID)
        .max()
        .unwrap_or(0)
        .max(100);
    w = w.max(need);
    h = h.max(need);
    BoxGeom {
        width: w,
        height: h,
        margin: w.max(h) - GRID,
    }
}

/// A demonstration being built: the occupied rectangles and the interior.
struct Placer {
    interior: Rect,
    taken: Vec<Rect>,
}

impl Placer {
    fn free(&self, r: Rect) -> bool {
        let i = self.interior;
        r.x >= i.x
            && r.y >= i.y
            && r.x + r.w <= i.x + i.w
            && r.y + r.h <= i.y + i.h
            && self.taken.iter().all(|t| !overlaps(*t, r))
    }

    /// All of `rs` free and pairwise apart.
    fn all_free(&self, rs: &[Rect]) -> bool {
        rs.iter()
            .enumerate()
            .all(|(k, r)| self.free(*r) && rs[..k].iter().all(|q| !overlaps(*q, *r)))
    }
}

fn overlaps(a: Rect, b: Rect) -> bool {
    a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h
}

/// Grid positions `lo, lo+10, …, ≤ hi`, rotated to start at a random one.
fn rotated(lo: i64, hi: i64, rng: &mut ChaCha8Rng) -> Vec<i64> {
    if hi < lo {
        return Vec::new();
    }
    let n = ((hi - lo) / GRID + 1) as usize;
    let start = rng.random_range(0..n);
    (0..n)
        .map(|k| lo + ((start + k) % n) as i64 * GRID)
        .collect()
}

/// Place `n` blocks of `spec` by its habit; `placed` holds the blocks of
/// the earlier classes (for `NorthOf`). `None` when no room was found.
fn place_class(
    p: &Placer,
    spec: &ClassSpec,
    n: usize,
    placed: &[Vec<Rect>],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Rect>> {
    let (w, h) = (spec.width, spec.height);
    let i = p.interior;
    let (x0, y0, x1, y1) = (i.x, i.y, i.x + i.w, i.y + i.h);
    match spec.habit {
        Habit::Band { wall } => {
            let horizontal = matches!(wall, Side::N | Side::S);
            let (lo, hi) = if horizontal {
                (x0, x1 - n as i64 * w)
            } else {
                (y0, y1 - n as i64 * h)
            };
            for off in rotated(lo, hi, rng) {
                let rs: Vec<Rect> = (0..n as i64)
                    .map(|k| match wall {
                        Side::S => Rect::new(off + k * w, y0, w, h),
                        Side::N => Rect::new(off + k * w, y1 - h, w, h),
                        Side::W => Rect::new(x0, off + k * h, w, h),
                        Side::E => Rect::new(x1 - w, off + k * h, w, h),
                    })
                    .collect();
                if p.all_free(&rs) {
                    return Some(rs);
                }
            }
            None
        }
        Habit::Corner { corner } => {
            let lo_cols = (n as f64).sqrt().ceil() as usize;
            let mut options: Vec<usize> = (lo_cols.max(1)..=n).collect();
            // Prefer compact shapes; shuffle within the first few.
            let keep = options.len().min(3);
            options.truncate(keep);
            let first = rng.random_range(0..options.len());
            options.rotate_left(first);
            let column_major = rng.random_bool(0.5);
            for cols in options {
                let rs: Vec<Rect> = (0..n)
                    .map(|k| {
                        let (a, b) = ((k % cols) as i64, (k / cols) as i64);
                        let (cx, cy) = if column_major { (b, a) } else { (a, b) };
                        let x = if corner.east() {
                            x1 - (cx + 1) * w
                        } else {
                            x0 + cx * w
                        };
                        let y = if corner.north() {
                            y1 - (cy + 1) * h
                        } else {
                            y0 + cy * h
                        };
                        Rect::new(x, y, w, h)
                    })
                    .collect();
                if p.all_free(&rs) {
                    return Some(rs);
                }
            }
            None
        }
        Habit::Stack => {
            let per_col = (((y1 - y0) / h) as usize).clamp(1, n);
            let cols = n.div_ceil(per_col) as i64;
            for off in rotated(x0, x1 - cols * w, rng) {
                let rs: Vec<Rect> = (0..n)
                    .map(|k| {
                        let (c, r) = ((k / per_col) as i64, (k % per_col) as i64);
                        Rect::new(off + c * w, y0 + r * h, w, h)
                    })
                    .collect();
                if p.all_free(&rs) {
                    return Some(rs);
                }
            }
            None
        }
        Habit::Cluster => {
            for _ in 0..50 {
                let x = *rotated(x0, x1 - w, rng).first()?;
                let y = *rotated(y0, y1 - h, rng).first()?;
                if let Some(rs) = grow(p, Rect::new(x, y, w, h), n, y0, rng) {
                    return Some(rs);
                }
            }
            None
        }
        Habit::Row | Habit::Column { .. } | Habit::Block => groups::place_group(p, spec, n, rng),
        Habit::NorthOf { class } => {
            let other = placed.get(class)?;
            let top = other.iter().map(|r| r.y + r.h).max()?;
            // Rest on a topmost block of the other class, else anywhere
            // along that height.
            let mut starts: Vec<Rect> = other
                .iter()
                .filter(|r| r.y + r.h == top)
                .map(|r| Rect::new(r.x, top, w, h))
                .collect();
            let k = starts.len();
            if k > 0 {
                let first = rng.random_range(0..k);
                starts.rotate_left(first);
            }
            starts.extend(
                rotated(x0, x1 - w, rng)
                    .into_iter()
                    .map(|x| Rect::new(x, top, w, h)),
            );
            for s in starts.into_iter().take(60) {
                if let Some(rs) = grow(p, s, n, top, rng) {
                    return Some(rs);
                }
            }
            None
        }
    }
}

/// A connected cluster of `n` blocks (each flush against an earlier one)
/// from `start`, every block at `y ≥ floor`.
fn grow(p: &Placer, start: Rect, n: usize, floor: i64, rng: &mut ChaCha8Rng) -> Option<Vec<Rect>> {
    let ok =
        |rs: &[Rect], r: Rect| r.y >= floor && p.free(r) && rs.iter().all(|q| !overlaps(*q, r));
    if !ok(&[], start) {
        return None;
    }
    let mut rs = vec![start];
    while rs.len() < n {
        let mut cands = Vec::new();
        for q in &rs {
            for (dx, dy) in [(q.w, 0), (-q.w, 0), (0, q.h), (0, -q.h)] {
                let c = Rect::new(q.x + dx, q.y + dy, q.w, q.h);
                if ok(&rs, c) && !cands.contains(&c) {
                    cands.push(c);
                }
            }
        }
        if cands.is_empty() {
            return None;
        }
        // Favour compact growth a little: pick among the candidates
        // touching the most blocks, half of the time.
        let pick = if rng.random_bool(0.5) {
            let touching = |c: &Rect| {
                rs.iter()
                    .filter(|q| {
                        (q.x == c.x && (q.y + q.h == c.y || c.y + c.h == q.y))
                            || (q.y == c.y && (q.x + q.w == c.x || c.x + c.w == q.x))
                    })
                    .count()
            };
            let best = cands.iter().map(touching).max().unwrap_or(0);
            let top: Vec<Rect> = cands
                .iter()
                .copied()
                .filter(|c| touching(c) == best)
                .collect();
            top[rng.random_range(0..top.len())]
        } else {
            cands[rng.random_range(0..cands.len())]
        };
        rs.push(pick);
    }
    Some(rs)
}

pub(crate) fn block(class: &str, k: usize, w: i64, h: i64, at: Option<Rect>) -> Object {
    Object {
        id: format!("{}{}", class.to_ascii_lowercase(), k + 1),
        class: class.to_string(),
        x: at.map(|r| r.x),
        y: at.map(|r| r.y),
        width: w,
        height: h,
        fixed: false,
    }
}

/// The habits of a task's classes (anchors not shared).
fn draw_habits(k: usize, rng: &mut ChaCha8Rng) -> Vec<Habit> {
    let mut walls = vec![Side::S, Side::W, Side::E, Side::N];
    let mut corners = vec![Corner::SW, Corner::SE, Corner::NE, Corner::NW];
    let mut stack_used = false;
    let mut out: Vec<Habit> = Vec::new();
    for i in 0..k {
        let mut options: Vec<Habit> = Vec::new();
        if !walls.is_empty() {
            options.push(Habit::Band {
                wall: walls[rng.random_range(0..walls.len())],
            });
        }
        if !corners.is_empty() {
            options.push(Habit::Corner {
                corner: corners[rng.random_range(0..corners.len())],
            });
        }
        if !stack_used {
            options.push(Habit::Stack);
        }
        options.push(Habit::Cluster);
        // North of an earlier class that leaves room above it.
        let refs: Vec<usize> = (0..i)
            .filter(|&j| {
                !matches!(
                    out[j],
                    Habit::Band { wall: Side::N }
                        | Habit::Corner {
                            corner: Corner::NW | Corner::NE
                        }
                )
            })
            .collect();
        if !refs.is_empty() {
            let class = refs[rng.random_range(0..refs.len())];
            // Twice as likely: it is the relation between classes.
            options.push(Habit::NorthOf { class });
            options.push(Habit::NorthOf { class });
        }
        let h = options[rng.random_range(0..options.len())];
        match h {
            Habit::Band { wall } => walls.retain(|w| *w != wall),
            Habit::Corner { corner } => corners.retain(|c| *c != corner),
            Habit::Stack => stack_used = true,
            _ => {}
        }
        out.push(h);
    }
    out
}

/// The demonstrations of a task, or `None` when a placement failed.
fn make_demos(geom: &BoxGeom, classes: &[ClassSpec], rng: &mut ChaCha8Rng) -> Option<Vec<Scene>> {
    let d = rng.random_range(3..=5usize);
    make_demos_n(geom, classes, d, rng)
}

/// `d` demonstrations of `classes` in `geom`'s box, each class placed by
/// its habit (one demonstration per class shows its largest count), or
/// `None` when a placement failed.
pub(crate) fn make_demos_n(
    geom: &BoxGeom,
    classes: &[ClassSpec],
    d: usize,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Scene>> {
    if d == 0 {
        return None;
    }
    // Per demonstration and class, the count; one demonstration per class
    // shows the largest.
    let mut counts: Vec<Vec<usize>> = (0..d)
        .map(|_| {
            classes
                .iter()
                .map(|c| rng.random_range(2..=c.max_count))
                .collect()
        })
        .collect();
    for (ci, c) in classes.iter().enumerate() {
        let at = rng.random_range(0..d);
        counts[at][ci] = c.max_count;
    }
    let mut demos = Vec::with_capacity(d);
    for row in &counts {
        let mut done = None;
        for _attempt in 0..20 {
            let mut p = Placer {
                interior: geom.interior(),
                taken: Vec::new(),
            };
            let mut placed: Vec<Vec<Rect>> = Vec::new();
            let mut ok = true;
            for (ci, c) in classes.iter().enumerate() {
                match place_class(&p, c, row[ci], &placed, rng) {
                    Some(rs) => {
                        p.taken.extend(rs.iter().copied());
                        placed.push(rs);
                    }
                    None => {
                        ok = false;
                        break;
                    }
                }
            }
            if ok {
                done = Some(placed);
                break;
            }
        }
        let placed = done?;
        let mut scene = geom.scene();
        for (c, rs) in classes.iter().zip(&placed) {
            scene.objects.extend(
                rs.iter()
                    .enumerate()
                    .map(|(k, r)| block(&c.class, k, c.width, c.height, Some(*r))),
            );
        }
        demos.push(scene);
    }
    Some(demos)
}

pub(crate) fn task_rng(seed: u64, task: usize) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(task as u64 + 1);
    rng
}

/// Learn with the default parameters and `templates`; the rules and their
/// `.rcc` text.
fn learn_with(
    demos: &[Scene],
    task: usize,
    templates: Templates,
) -> Result<(RuleSet, String), TaskError> {
    let params = LearnParams {
        templates,
        ..LearnParams::default()
    };
    let learned = learn(demos, None, &params).map_err(|error| TaskError::Learn { task, error })?;
    Ok((learned.rules(), learned.to_rcc()))
}

/// Per class of `k`, the largest count a demonstration shows: 2–6 each,
/// adjusted so that the sum is between 10 and 20 (see the module doc,
/// step 1).
pub(crate) fn draw_maxes(k: usize, rng: &mut ChaCha8Rng) -> Vec<usize> {
    let mut maxes: Vec<usize> = (0..k).map(|_| rng.random_range(2..=6usize)).collect();
    while maxes.iter().sum::<usize>() < 10 {
        let i = (0..k).filter(|&i| maxes[i] < 6).min_by_key(|&i| maxes[i]);
        match i {
            Some(i) => maxes[i] += 1,
            None => break,
        }
    }
    while maxes.iter().sum::<usize>() > 20 {
        let i = (0..k)
            .max_by_key(|&i| (maxes[i], usize::MAX - i))
            .unwrap_or(0);
        maxes[i] -= 1;
    }
    maxes
}

/// Generated task `index` of `cfg` (deterministic in `cfg.seed`, `index`,
/// and `cfg.sizes`' values).
pub fn generate_task(cfg: &TasksConfig, index: usize) -> Result<Task, TaskError> {
    let mut rng = task_rng(cfg.seed, index);
    let largest = cfg.sizes.iter().copied().fold(BOX_FOR, f64::max);
    const TRIES: usize = 20;
    for _ in 0..TRIES {
        let k = rng.random_range(2..=4usize);
        let maxes = draw_maxes(k, &mut rng);
        let habits = draw_habits(k, &mut rng);
        let classes: Vec<ClassSpec> = (0..k)
            .map(|i| {
                let (w, h) = BLOCK_SIZES[rng.random_range(0..BLOCK_SIZES.len())];
                ClassSpec {
                    class: TASK_CLASSES[i].to_string(),
                    width: w,
                    height: h,
                    max_count: maxes[i],
                    habit: habits[i],
                }
            })
            .collect();
        let geom = box_for(&classes, largest, &mut rng);
        let Some(demos) = make_demos(&geom, &classes, &mut rng) else {
            continue;
        };
        let (rules, rcc) = learn_with(&demos, index, cfg.templates)?;
        let style = classes
            .iter()
            .map(|c| {
                format!(
                    "{} {}x{} ≤{}: {}",
                    c.class,
                    c.width,
                    c.height,
                    c.max_count,
                    c.habit.describe(&classes)
                )
            })
            .collect::<Vec<_>>()
            .join("; ");
        let problems = cfg
            .sizes
            .iter()
            .enumerate()
            .map(|(si, &m)| {
                let mut scene = geom.scene();
                for c in &classes {
                    let n = scaled(c.max_count, m);
                    scene
                        .objects
                        .extend((0..n).map(|j| block(&c.class, j, c.width, c.height, None)));
                }
                let movable = scene.objects.iter().filter(|o| !o.fixed).count();
                TaskProblem {
                    size_index: si,
                    size: size_label(m),
                    name: format!("task{index:02}-{}", size_label(m)),
                    scene,
                    movable,
                }
            })
            .collect();
        return Ok(Task {
            series: TaskSeries::Tasks,
            index,
            classes,
            style,
            demos,
            rcc,
            rules,
            problems,
        });
    }
    Err(TaskError::Unplaceable {
        task: index,
        tries: TRIES,
    })
}

/// The bundled example with `counts` blocks per class (same classes and
/// sizes as its `problem.json`, in its box), rules learned from its
/// `demos.json`.
pub fn example_task(counts: &[usize], templates: Templates) -> Result<Task, TaskError> {
    let demos = scenes_from_json(EXAMPLE_DEMOS).map_err(|e| TaskError::Example(e.to_string()))?;
    let base = Scene::from_json(EXAMPLE_PROBLEM).map_err(|e| TaskError::Example(e.to_string()))?;
    let (rules, rcc) = learn_with(&demos, 0, templates)?;
    // Classes and sizes in order of first appearance.
    let mut kinds: Vec<(String, i64, i64)> = Vec::new();
    for o in base.objects.iter().filter(|o| !o.fixed) {
        if !kinds.iter().any(|k| k.0 == o.class) {
            kinds.push((o.class.clone(), o.width, o.height));
        }
    }
    let problems = counts
        .iter()
        .enumerate()
        .map(|(si, &n)| {
            let mut scene = base.clone();
            scene.objects.retain(|o| o.fixed);
            for (c, w, h) in &kinds {
                scene
                    .objects
                    .extend((0..n).map(|j| block(c, j, *w, *h, None)));
            }
            let movable = scene.objects.iter().filter(|o| !o.fixed).count();
            TaskProblem {
                size_index: si,
                size: format!("{n}/class"),
                name: format!("example-{n}"),
                scene,
                movable,
            }
        })
        .collect();
    Ok(Task {
        series: TaskSeries::Example,
        index: 0,
        classes: Vec::new(),
        style: "examples/box-packing".into(),
        demos,
        rcc,
        rules,
        problems,
    })
}

/// Every task of the configuration: the generated ones, then the bundled
/// example (when `example_counts` is not empty).
pub fn all_tasks(cfg: &TasksConfig) -> Result<Vec<Task>, TaskError> {
    let mut out = (0..cfg.tasks)
        .map(|i| generate_task(cfg, i))
        .collect::<Result<Vec<_>, _>>()?;
    if !cfg.example_counts.is_empty() {
        out.push(example_task(&cfg.example_counts, cfg.templates)?);
    }
    for i in 0..cfg.groups {
        out.push(groups::generate_group_task(cfg, i)?);
    }
    Ok(out)
}

pub use super::{SolveFn, Solver, VerifyFn};

/// The options of a solve: score only (`like = None`) or with the
/// demonstrations as like-scenes.
pub fn solve_options(cfg: &TasksConfig, demos: &[Scene], like: bool) -> SynthOptions {
    let mut opts = SynthOptions {
        contact: Contact::Point,
        time_limit: Some(cfg.time_limit),
        seed: cfg.seed,
        like: like.then(|| ResemblanceTarget::new(demos)),
        ..SynthOptions::default()
    };
    if cfg.warm_start {
        opts.warm_start = demos.to_vec();
    }
    if !cfg.lns {
        opts.lns = None;
    }
    opts
}

/// One solve of one problem.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SolveRow {
    /// How it ended (`None`: the engine returned an error).
    pub status: Option<Status>,
    /// Wall time around the call, ms.
    pub time_ms: f64,
    /// Search nodes.
    pub nodes: u64,
    /// Evaluator score of the layout.
    pub score: Option<f64>,
    /// Resemblance cost (with `like`).
    pub cost: Option<u64>,
    /// Whether the cost is proven minimal (with `like`).
    pub cost_proven: Option<bool>,
    /// Whether the layout passed the checker (`None`: no layout).
    pub verified: Option<bool>,
    /// The checker's complaint or the engine's error.
    pub error: Option<String>,
    /// Group tasks: of the classes demonstrated with a group shape, how
    /// many keep it in the layout, `[kept, classes]`.
    pub shapes_kept: Option<[usize; 2]>,
    /// The layout (not written to `tasks.json`).
    #[serde(skip)]
    pub layout: Option<Scene>,
}

/// Solve `scene` once with `opts` and check the layout.
pub fn solve_once(
    engine: Solver<'_>,
    scene: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
) -> SolveRow {
    let t0 = Instant::now();
    let res = (engine.solve)(scene, rules, opts);
    let time_ms = t0.elapsed().as_secs_f64() * 1e3;
    let mut row = SolveRow {
        status: None,
        time_ms,
        nodes: 0,
        score: None,
        cost: None,
        cost_proven: None,
        verified: None,
        error: None,
        shapes_kept: None,
        layout: None,
    };
    match res {
        Err(e) => row.error = Some(e.to_string()),
        Ok(r) => {
            row.status = Some(r.status);
            row.nodes = r.stats.nodes;
            row.score = r.evaluation.as_ref().map(|e| e.score);
            if let Some(rs) = &r.resemblance {
                row.cost = Some(rs.cost);
                row.cost_proven = Some(rs.proven);
            }
            if let Some(sol) = &r.scene {
                match (engine.verify)(scene, sol, rules, opts.contact) {
                    Ok(()) => row.verified = Some(true),
                    Err(e) => {
                        row.verified = Some(false);
                        row.error = Some(e);
                    }
                }
            }
            row.layout = r.scene;
        }
    }
    row
}

/// Run `peer` on the emitted (score-only) model of a problem; its layout
/// is scored by the evaluator and checked.
pub fn solve_peer(
    engine: Solver<'_>,
    cfg: &TasksConfig,
    scene: &Scene,
    rules: &RuleSet,
    peer: Peer,
) -> PeerRow {
    let mut row = PeerRow {
        peer: peer.name().into(),
        status: None,
        time_ms: 0.0,
        process_ms: 0.0,
        score: None,
        verified: None,
        error: None,
    };
    let opts = solve_options(cfg, &[], false);
    let e = match crate::synth::emit::emitted(scene, rules, &opts) {
        Ok(e) => e,
        Err(e) => {
            row.error = Some(e.to_string());
            return row;
        }
    };
    match peers::solve(peer, &e, cfg.time_limit) {
        Err(e) => row.error = Some(e.to_string()),
        Ok(r) => {
            row.status = Some(r.status);
            row.time_ms = r.time_ms;
            row.process_ms = r.process_ms;
            if let Some(v) = &r.values {
                let sol = e.model.scene(scene, v);
                row.score = Some(crate::eval::evaluate(&sol, rules, opts.contact).score);
                match (engine.verify)(scene, &sol, rules, opts.contact) {
                    Ok(()) => row.verified = Some(true),
                    Err(msg) => {
                        row.verified = Some(false);
                        row.error = Some(msg);
                    }
                }
            }
        }
    }
    row
}

/// One problem, solved.
#[derive(Debug, Clone, Serialize)]
pub struct TaskRow {
    /// Generated tasks or the bundled example.
    pub series: TaskSeries,
    /// Task index.
    pub task: usize,
    /// Size index (for grouping).
    pub size_index: usize,
    /// `1.5x`, `8/class`.
    pub size: String,
    /// File name stem.
    pub name: String,
    /// Movable objects.
    pub movable: usize,
    /// Learned rules.
    pub rules: usize,
    /// The score-only solve.
    pub score_only: SolveRow,
    /// The solve with `like` = the demonstrations.
    pub like: Option<SolveRow>,
    /// The peers on the score-only model.
    pub peers: Vec<PeerRow>,
}

/// What the benchmark is doing, for a progress bar.
#[derive(Debug, Clone)]
pub enum TasksEvent {
    /// A problem was solved: one line about it.
    Solved {
        /// Problems solved.
        done: usize,
        /// Problems in all.
        total: usize,
        /// e.g. `task03-1.5x (31 objects): score-only optimal 1.000 in 0.2 s; …`.
        line: String,
    },
    /// A problem is about to be solved (`done` solved before it).
    Solving {
        /// Problems solved.
        done: usize,
        /// Problems in all.
        total: usize,
        /// e.g. `task03-1.5x like`.
        label: String,
    },
}

/// A task as written to `tasks.json`.
#[derive(Debug, Clone, Serialize)]
pub struct TaskReport {
    /// Series.
    pub series: TaskSeries,
    /// Index.
    pub index: usize,
    /// The style in words.
    pub style: String,
    /// The classes and their habits.
    pub classes: Vec<ClassSpec>,
    /// Demonstrations.
    pub demos: usize,
    /// Learned rules.
    pub rules: usize,
}

/// Everything the benchmark measured.
#[derive(Debug, Clone, Serialize)]
pub struct TasksReport {
    /// The configuration.
    pub config: TasksConfig,
    /// The tasks.
    pub tasks: Vec<TaskReport>,
    /// One row per problem.
    pub rows: Vec<TaskRow>,
    /// One line per (series, size).
    pub summary: Vec<TasksSummary>,
}

/// Solve every problem of `tasks` (score only, with `like`, peers), one
/// solver at a time.
pub fn run_tasks(
    engine: Solver<'_>,
    cfg: &TasksConfig,
    tasks: &[Task],
    progress: &mut dyn FnMut(&TasksEvent),
) -> TasksReport {
    let total: usize = tasks.iter().map(|t| t.problems.len()).sum();
    let mut rows = Vec::with_capacity(total);
    for t in tasks {
        let score_opts = solve_options(cfg, &t.demos, false);
        let like_opts = solve_options(cfg, &t.demos, true);
        for p in &t.problems {
            let done = rows.len();
            let label = |what: &str| TasksEvent::Solving {
                done,
                total,
                label: format!("{} {what}", p.name),
            };
            let kept = |mut row: SolveRow, opts: &SynthOptions| {
                if t.series == TaskSeries::Groups {
                    row.shapes_kept = row.layout.as_ref().map(|l| {
                        let (k, n) = groups::shapes_kept(t, l, opts.contact);
                        [k, n]
                    });
                }
                row.layout = None;
                row
            };
            progress(&label("score-only"));
            let score_only = kept(
                solve_once(engine, &p.scene, &t.rules, &score_opts),
                &score_opts,
            );
            let like = cfg.like.then(|| {
                progress(&label("like"));
                kept(
                    solve_once(engine, &p.scene, &t.rules, &like_opts),
                    &like_opts,
                )
            });
            let peers = cfg
                .peers
                .iter()
                .map(|&peer| {
                    progress(&label(peer.name()));
                    solve_peer(engine, cfg, &p.scene, &t.rules, peer)
                })
                .collect();
            let row = TaskRow {
                series: t.series,
                task: t.index,
                size_index: p.size_index,
                size: p.size.clone(),
                name: p.name.clone(),
                movable: p.movable,
                rules: t.rules.rules.len(),
                score_only,
                like,
                peers,
            };
            progress(&TasksEvent::Solved {
                done: done + 1,
                total,
                line: row_line(&row),
            });
            rows.push(row);
        }
    }
    progress(&TasksEvent::Solving {
        done: total,
        total,
        label: "done".into(),
    });
    TasksReport {
        config: cfg.clone(),
        tasks: tasks
            .iter()
            .map(|t| TaskReport {
                series: t.series,
                index: t.index,
                style: t.style.clone(),
                classes: t.classes.clone(),
                demos: t.demos.len(),
                rules: t.rules.rules.len(),
            })
            .collect(),
        summary: summarize(&rows),
        rows,
    }
}

/// One line about a solved problem, e.g. `task03-1.5x (31 objects, 42
/// rules): score-only optimal 1.000 0.2s; like optimal 1.000 cost 12 0.4s;
/// cp-sat optimal 1.000 3.1s`.
pub fn row_line(r: &TaskRow) -> String {
    let solve = |s: &SolveRow| {
        let status = s
            .status
            .map(|st| format!("{st:?}").to_lowercase())
            .unwrap_or_else(|| "ERROR".into());
        let score = s.score.map(|v| format!(" {v:.3}")).unwrap_or_default();
        let cost = s
            .cost
            .map(|c| {
                format!(
                    " cost {c}{}",
                    if s.cost_proven == Some(true) { "" } else { "?" }
                )
            })
            .unwrap_or_default();
        let bad = if s.verified == Some(false) || s.status.is_none() {
            " !!FAILED"
        } else {
            ""
        };
        format!("{status}{score}{cost} {}{bad}", ms(s.time_ms))
    };
    let mut line = format!(
        "{} ({} objects, {} rules): score-only {}",
        r.name,
        r.movable,
        r.rules,
        solve(&r.score_only)
    );
    if let Some(l) = &r.like {
        line.push_str(&format!("; like {}", solve(l)));
    }
    for p in &r.peers {
        let status = p
            .status
            .map(|st| format!("{st:?}").to_lowercase())
            .unwrap_or_else(|| "failed".into());
        let score = p.score.map(|v| format!(" {v:.3}")).unwrap_or_default();
        line.push_str(&format!("; {} {status}{score} {}", p.peer, ms(p.time_ms)));
    }
    line
}

/// One peer's aggregates in one (series, size) cell.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PeerCell {
    /// The peer.
    pub peer: String,
    /// Proved optimal by the peer.
    pub proven: usize,
    /// Median peer solve time, ms (time-outs at the limit).
    pub median_ms: f64,
    /// Problems where rccpack's score-only score is below the peer's.
    pub rccpack_below: usize,
    /// Problems where rccpack's score-only score is above the peer's.
    pub rccpack_above: usize,
    /// Peer failures or layouts the checker rejected.
    pub failures: usize,
}

/// Aggregates of one (series, size) cell.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TasksSummary {
    /// Series.
    pub series: TaskSeries,
    /// Size index.
    pub size_index: usize,
    /// Size label.
    pub size: String,
    /// Problems.
    pub problems: usize,
    /// Fewest movable objects.
    pub movable_min: usize,
    /// Most movable objects.
    pub movable_max: usize,
    /// Fewest learned rules.
    pub rules_min: usize,
    /// Most learned rules.
    pub rules_max: usize,
    /// Score-only solves proved optimal.
    pub proven: usize,
    /// Median score-only wall time, ms.
    pub median_ms: f64,
    /// Largest score-only wall time, ms.
    pub max_ms: f64,
    /// Median score-only score.
    pub median_score: Option<f64>,
    /// Lowest score-only score.
    pub min_score: Option<f64>,
    /// `like` solves whose score is proven optimal and cost proven minimal.
    pub like_proven: Option<usize>,
    /// Median `like` wall time, ms.
    pub like_median_ms: Option<f64>,
    /// `like` median over score-only median.
    pub like_ratio: Option<f64>,
    /// Solver errors (both modes).
    pub errors: usize,
    /// Layouts the checker rejected (both modes).
    pub check_failures: usize,
    /// Per peer.
    pub peers: Vec<PeerCell>,
    /// Group tasks: demonstrated shapes kept over shapes, score-only.
    pub shapes_kept: Option<[usize; 2]>,
    /// Group tasks: demonstrated shapes kept over shapes, with `like`.
    pub like_shapes_kept: Option<[usize; 2]>,
}

/// One [`TasksSummary`] per (series, size), in series then size order.
pub fn summarize(rows: &[TaskRow]) -> Vec<TasksSummary> {
    let mut keys: Vec<(TaskSeries, usize)> =
        rows.iter().map(|r| (r.series, r.size_index)).collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .map(|(series, si)| {
            let cell: Vec<&TaskRow> = rows
                .iter()
                .filter(|r| r.series == series && r.size_index == si)
                .collect();
            let times: Vec<f64> = cell.iter().map(|r| r.score_only.time_ms).collect();
            let scores: Vec<f64> = cell.iter().filter_map(|r| r.score_only.score).collect();
            let likes: Vec<&SolveRow> = cell.iter().filter_map(|r| r.like.as_ref()).collect();
            let like_times: Vec<f64> = likes.iter().map(|l| l.time_ms).collect();
            let solves = || {
                cell.iter()
                    .flat_map(|r| std::iter::once(&r.score_only).chain(r.like.as_ref()))
            };
            let mut peer_names: Vec<String> = cell
                .iter()
                .flat_map(|r| r.peers.iter().map(|p| p.peer.clone()))
                .collect();
            peer_names.dedup();
            peer_names.sort();
            peer_names.dedup();
            let score = |s: Option<f64>| s.unwrap_or(f64::NEG_INFINITY);
            let peers = peer_names
                .into_iter()
                .map(|peer| {
                    let pc: Vec<(&TaskRow, &PeerRow)> = cell
                        .iter()
                        .filter_map(|r| r.peers.iter().find(|p| p.peer == peer).map(|p| (*r, p)))
                        .collect();
                    let pt: Vec<f64> = pc.iter().map(|(_, p)| p.time_ms).collect();
                    PeerCell {
                        proven: pc
                            .iter()
                            .filter(|(_, p)| p.status == Some(PeerStatus::Optimal))
                            .count(),
                        median_ms: median(&pt),
                        rccpack_below: pc
                            .iter()
                            .filter(|(r, p)| score(r.score_only.score) < score(p.score) - 1e-9)
                            .count(),
                        rccpack_above: pc
                            .iter()
                            .filter(|(r, p)| score(p.score) < score(r.score_only.score) - 1e-9)
                            .count(),
                        failures: pc
                            .iter()
                            .filter(|(_, p)| p.status.is_none() || p.verified == Some(false))
                            .count(),
                        peer,
                    }
                })
                .collect();
            let so_median = median(&times);
            let sum_kept = |rows: &mut dyn Iterator<Item = &SolveRow>| {
                rows.filter_map(|s| s.shapes_kept)
                    .reduce(|a, b| [a[0] + b[0], a[1] + b[1]])
            };
            let like_median = (!likes.is_empty()).then(|| median(&like_times));
            TasksSummary {
                series,
                size_index: si,
                size: cell[0].size.clone(),
                problems: cell.len(),
                movable_min: cell.iter().map(|r| r.movable).min().unwrap_or(0),
                movable_max: cell.iter().map(|r| r.movable).max().unwrap_or(0),
                rules_min: cell.iter().map(|r| r.rules).min().unwrap_or(0),
                rules_max: cell.iter().map(|r| r.rules).max().unwrap_or(0),
                proven: cell
                    .iter()
                    .filter(|r| r.score_only.status == Some(Status::Optimal))
                    .count(),
                median_ms: so_median,
                max_ms: times.iter().copied().fold(0.0, f64::max),
                median_score: (!scores.is_empty()).then(|| median(&scores)),
                min_score: scores.iter().copied().reduce(f64::min),
                like_proven: (!likes.is_empty()).then(|| {
                    likes
                        .iter()
                        .filter(|l| {
                            l.status == Some(Status::Optimal) && l.cost_proven == Some(true)
                        })
                        .count()
                }),
                like_median_ms: like_median,
                like_ratio: like_median.map(|m| m / so_median),
                errors: solves().filter(|s| s.status.is_none()).count(),
                check_failures: solves().filter(|s| s.verified == Some(false)).count(),
                peers,
                shapes_kept: sum_kept(&mut cell.iter().map(|r| &r.score_only)),
                like_shapes_kept: sum_kept(&mut likes.iter().copied()),
            }
        })
        .collect()
}

fn ms(v: f64) -> String {
    if v.is_nan() {
        "-".into()
    } else if v >= 1000.0 {
        format!("{:.1}s", v / 1000.0)
    } else {
        format!("{v:.0}ms")
    }
}

fn range(a: usize, b: usize) -> String {
    if a == b {
        a.to_string()
    } else {
        format!("{a}-{b}")
    }
}

/// The summary as fixed-width text tables: rccpack's, then the peers'.
pub fn table_text(summary: &[TasksSummary]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<8} {:<8} {:>5} {:>7} {:>7} {:>7} {:>8} {:>8} {:>6} {:>6} {:>8} {:>8} {:>6}",
        "series",
        "size",
        "probs",
        "objects",
        "rules",
        "proven",
        "median",
        "max",
        "med_sc",
        "min_sc",
        "like_pr",
        "like_med",
        "like/so"
    );
    for r in summary {
        let f3 = |v: Option<f64>| v.map(|v| format!("{v:.3}")).unwrap_or_else(|| "-".into());
        let _ = writeln!(
            s,
            "{:<8} {:<8} {:>5} {:>7} {:>7} {:>7} {:>8} {:>8} {:>6} {:>6} {:>8} {:>8} {:>6}{}",
            r.series.name(),
            r.size,
            r.problems,
            range(r.movable_min, r.movable_max),
            range(r.rules_min, r.rules_max),
            format!("{}/{}", r.proven, r.problems),
            ms(r.median_ms),
            ms(r.max_ms),
            f3(r.median_score),
            f3(r.min_score),
            r.like_proven
                .map(|p| format!("{p}/{}", r.problems))
                .unwrap_or_else(|| "-".into()),
            r.like_median_ms.map(ms).unwrap_or_else(|| "-".into()),
            r.like_ratio
                .map(|v| format!("{v:.2}"))
                .unwrap_or_else(|| "-".into()),
            if r.errors + r.check_failures > 0 {
                format!(
                    "  !! errors {} check failures {}",
                    r.errors, r.check_failures
                )
            } else {
                String::new()
            }
        );
    }
    if summary.iter().any(|r| r.shapes_kept.is_some()) {
        let _ = writeln!(
            s,
            "\n{:<8} {:<8} {:>5} {:>14} {:>14}",
            "series", "size", "probs", "shapes_so", "shapes_like"
        );
        let share = |v: Option<[usize; 2]>| match v {
            Some([k, n]) if n > 0 => format!("{k}/{n} {:.0}%", 100.0 * k as f64 / n as f64),
            _ => "-".into(),
        };
        for r in summary.iter().filter(|r| r.shapes_kept.is_some()) {
            let _ = writeln!(
                s,
                "{:<8} {:<8} {:>5} {:>14} {:>14}",
                r.series.name(),
                r.size,
                r.problems,
                share(r.shapes_kept),
                share(r.like_shapes_kept)
            );
        }
    }
    if summary.iter().any(|r| !r.peers.is_empty()) {
        let _ = writeln!(
            s,
            "\n{:<8} {:<8} {:<7} {:>7} {:>8} {:>7} {:>8} {:>9} {:>9}",
            "series",
            "size",
            "peer",
            "proven",
            "median",
            "rcc_pr",
            "rcc_med",
            "rcc_below",
            "rcc_above"
        );
        for r in summary {
            for p in &r.peers {
                let _ = writeln!(
                    s,
                    "{:<8} {:<8} {:<7} {:>7} {:>8} {:>7} {:>8} {:>9} {:>9}{}",
                    r.series.name(),
                    r.size,
                    p.peer,
                    format!("{}/{}", p.proven, r.problems),
                    ms(p.median_ms),
                    format!("{}/{}", r.proven, r.problems),
                    ms(r.median_ms),
                    p.rccpack_below,
                    p.rccpack_above,
                    if p.failures > 0 {
                        format!("  failures {}", p.failures)
                    } else {
                        String::new()
                    }
                );
            }
        }
    }
    s
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
