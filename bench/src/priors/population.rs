//! The population of demonstrators: class names drawn from [`CLASS_POOL`],
//! habits drawn with [`HABIT_WEIGHTS`], each task's truth learned from many
//! demonstrations of its style, and the held-out / library split.

use super::{PriorsBenchConfig, PriorsBenchError, Progress};
use crate::tasks::{
    box_for, draw_maxes, make_demos_n, BoxGeom, ClassSpec, Corner, Habit, WallSide, BLOCK_SIZES,
    BOX_FOR,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use rccpack::infer::learn;
use rccpack::rules::RuleSet;
use rccpack::scene::Scene;
use serde::Serialize;

/// The names a task's classes are drawn from (without repetition).
pub const CLASS_POOL: [&str; 12] = [
    "red", "blue", "green", "yellow", "crate", "box", "can", "jar", "cup", "tray", "bolt", "nut",
];

/// Relative weights of the habits a class is drawn with (a weight per
/// habit that is available; see the module doc). Per class with an earlier
/// class to stand on, they are percentages: cluster 30, band on the floor
/// 24, north of an earlier class 20, a band on each other wall 4, each
/// corner 2, a stack 6.
pub const HABIT_WEIGHTS: HabitWeights = HabitWeights {
    cluster: 30,
    band_south: 24,
    north_of: 20,
    band_other: 4,
    corner: 2,
    stack: 6,
};

/// Relative weights of the habits (see [`HABIT_WEIGHTS`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct HabitWeights {
    /// A connected cluster anywhere.
    pub cluster: u32,
    /// A band on the south wall (the floor).
    pub band_south: u32,
    /// North of an earlier class (one weight, the class drawn uniformly).
    pub north_of: u32,
    /// A band on the west, east or north wall (each).
    pub band_other: u32,
    /// A cluster in a corner (each corner).
    pub corner: u32,
    /// A stack on the floor.
    pub stack: u32,
}

/// Streams of the true library's tasks start here (the population's
/// library and held-out tasks use streams `1..=L+H`).
pub(super) const TRUE_STREAMS: u64 = 1 << 32;

/// Tries to draw a style whose demonstrations can all be placed.
pub(super) const TRIES: usize = 20;

/// One task of the population.
#[derive(Debug, Clone, PartialEq)]
pub struct PopTask {
    /// Its stream (its identity in the population).
    pub stream: u64,
    /// Its classes, names and habits.
    pub classes: Vec<ClassSpec>,
    /// Its box.
    pub geom: BoxGeom,
    /// The style in words.
    pub style: String,
    /// The demonstrations the task shows.
    pub demos: Vec<Scene>,
    /// The truth: rules learned from [`PriorsBenchConfig::truth_demos`]
    /// demonstrations of the style.
    pub truth: RuleSet,
}

/// The habits of `k` classes, drawn with [`HABIT_WEIGHTS`] (anchors not
/// shared, "north of" only above a class that leaves room).
pub fn draw_population_habits(k: usize, rng: &mut ChaCha8Rng) -> Vec<Habit> {
    let w = HABIT_WEIGHTS;
    let mut walls = vec![WallSide::S, WallSide::W, WallSide::E, WallSide::N];
    let mut corners = vec![Corner::SW, Corner::SE, Corner::NE, Corner::NW];
    let mut stack_used = false;
    let mut out: Vec<Habit> = Vec::new();
    for i in 0..k {
        let mut options: Vec<(Habit, u32)> = vec![(Habit::Cluster, w.cluster)];
        for &wall in &walls {
            let weight = if wall == WallSide::S {
                w.band_south
            } else {
                w.band_other
            };
            options.push((Habit::Band { wall }, weight));
        }
        options.extend(
            corners
                .iter()
                .map(|&corner| (Habit::Corner { corner }, w.corner)),
        );
        if !stack_used {
            options.push((Habit::Stack, w.stack));
        }
        let refs: Vec<usize> = (0..i)
            .filter(|&j| {
                !matches!(
                    out[j],
                    Habit::Band { wall: WallSide::N }
                        | Habit::Corner {
                            corner: Corner::NW | Corner::NE
                        }
                )
            })
            .collect();
        if !refs.is_empty() {
            let class = refs[rng.random_range(0..refs.len())];
            options.push((Habit::NorthOf { class }, w.north_of));
        }
        let total: u32 = options.iter().map(|o| o.1).sum();
        let mut pick = rng.random_range(0..total.max(1));
        let mut h = Habit::Cluster;
        for (habit, weight) in options {
            if pick < weight {
                h = habit;
                break;
            }
            pick -= weight;
        }
        match h {
            Habit::Band { wall } => walls.retain(|x| *x != wall),
            Habit::Corner { corner } => corners.retain(|c| *c != corner),
            Habit::Stack => stack_used = true,
            _ => {}
        }
        out.push(h);
    }
    out
}

/// `k` distinct class names from [`CLASS_POOL`].
fn draw_names(k: usize, rng: &mut ChaCha8Rng) -> Vec<String> {
    let mut pool: Vec<&str> = CLASS_POOL.to_vec();
    let mut out = Vec::with_capacity(k);
    for _ in 0..k.min(pool.len()) {
        let i = rng.random_range(0..pool.len());
        out.push(pool.swap_remove(i).to_string());
    }
    out
}

/// How many demonstrations a task shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shown {
    /// A library task: 3–5, drawn.
    Library,
    /// A held-out task: this many.
    HeldOut(usize),
}

/// Population task `stream` of `seed`: its style, its demonstrations and
/// its truth (see the module doc).
pub fn population_task(
    cfg: &PriorsBenchConfig,
    stream: u64,
    shown: Shown,
) -> Result<PopTask, PriorsBenchError> {
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    rng.set_stream(stream);
    for _ in 0..TRIES {
        let k = rng.random_range(2..=4usize);
        let maxes = draw_maxes(k, &mut rng);
        let habits = draw_population_habits(k, &mut rng);
        let names = draw_names(k, &mut rng);
        let classes: Vec<ClassSpec> = (0..k)
            .map(|i| {
                let (width, height) = BLOCK_SIZES[rng.random_range(0..BLOCK_SIZES.len())];
                ClassSpec {
                    class: names[i].clone(),
                    width,
                    height,
                    max_count: maxes[i],
                    habit: habits[i],
                    orientation: crate::tasks::Orientation::Fixed,
                }
            })
            .collect();
        let geom = box_for(&classes, BOX_FOR, &mut rng);
        let Some(mut demos) = make_demos_n(&geom, &classes, cfg.truth_demos, &mut rng) else {
            continue;
        };
        let learned = learn(&demos, None, &cfg.learn_params())
            .map_err(|error| PriorsBenchError::Learn { stream, error })?;
        let d = match shown {
            Shown::Library => rng.random_range(3..=5usize),
            Shown::HeldOut(d) => d,
        };
        demos.truncate(d);
        let style = classes
            .iter()
            .map(|c| format!("{}: {}", c.class, c.habit.describe(&classes)))
            .collect::<Vec<_>>()
            .join("; ");
        return Ok(PopTask {
            stream,
            classes,
            geom,
            style,
            demos,
            truth: learned.rules(),
        });
    }
    Err(PriorsBenchError::Unplaceable { stream })
}

/// The held-out streams (sorted) and the library streams (in library
/// order) of the population, split by a seeded shuffle.
fn split(cfg: &PriorsBenchConfig) -> (Vec<u64>, Vec<u64>) {
    let n = cfg.largest().saturating_add(cfg.held_out) as u64;
    let mut streams: Vec<u64> = (1..=n).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    rng.set_stream(0);
    for i in 0..streams.len() {
        let j = rng.random_range(i..streams.len());
        streams.swap(i, j);
    }
    let library = streams.split_off(cfg.held_out.min(streams.len()));
    streams.sort_unstable();
    (streams, library)
}

/// Make the tasks `jobs` on rayon's threads, in order.
pub(super) fn make_tasks(
    cfg: &PriorsBenchConfig,
    jobs: &[(u64, Shown)],
    what: &str,
    progress: Progress<'_>,
) -> Result<Vec<PopTask>, PriorsBenchError> {
    let done = std::sync::atomic::AtomicUsize::new(0);
    let out: Vec<Result<PopTask, PriorsBenchError>> = jobs
        .par_iter()
        .map(|&(stream, shown)| {
            let t = population_task(cfg, stream, shown);
            let k = done
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed)
                .saturating_add(1);
            if k % 10 == 0 || k == jobs.len() {
                progress(&format!("{what}: {k}/{} tasks", jobs.len()));
            }
            t
        })
        .collect();
    out.into_iter().collect()
}

pub(super) fn habit_name(h: &Habit) -> String {
    match h {
        Habit::Band { wall } => format!("band {wall:?}"),
        Habit::Corner { .. } => "corner".into(),
        Habit::Stack => "stack".into(),
        Habit::Cluster => "cluster".into(),
        Habit::NorthOf { .. } => "north of".into(),
        other => format!("{other:?}").to_lowercase(),
    }
}

/// The held-out tasks (by stream) and the library tasks (in library
/// order) of the population, made on the current rayon pool.
pub fn population(
    cfg: &PriorsBenchConfig,
    progress: Progress<'_>,
) -> Result<(Vec<PopTask>, Vec<PopTask>), PriorsBenchError> {
    cfg.validate()?;
    let (held_streams, lib_streams) = split(cfg);
    let mut jobs: Vec<(u64, Shown)> = held_streams
        .iter()
        .map(|&s| (s, Shown::HeldOut(cfg.held_out_demos)))
        .collect();
    jobs.extend(lib_streams.iter().map(|&s| (s, Shown::Library)));
    let mut tasks = make_tasks(cfg, &jobs, "population", progress)?;
    let library = tasks.split_off(held_streams.len());
    Ok((tasks, library))
}
