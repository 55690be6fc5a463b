//! Group-style tasks (`rccpack-bench tasks --groups N`): demonstrations in
//! which every class forms one row, one column or one compact block, and
//! problems with more blocks of a class than any demonstration shows.
//!
//! # Background
//!
//! Per-object rules ("every R lies flush north or south of some other R")
//! hold for a column split in two, so with more objects than the
//! demonstrations showed a layout can keep every learned rule and still
//! break the shape a person sees at a glance. The third-edition group
//! statements (`column(R)`, [`rccpack::shapes`]) say it of the class as a
//! whole. This series measures whether layouts keep the demonstrated
//! shapes: [`shapes_kept`] checks every layout against the habit each class
//! was demonstrated with, with the evaluator's own semantics
//! ([`rccpack::shapes::check`]).
//!
//! # Generated tasks
//!
//! Group task `t` draws from `ChaCha8Rng::seed_from_u64(seed)` on stream
//! [`GROUP_STREAM`]` + t` (the ordinary tasks' streams are untouched):
//!
//! 1. 2–3 classes (`R`, `G`, `B`), 20×20 blocks mostly (sometimes 30×20 or
//!    20×30), each with a largest demonstrated count of 3 or 4 and one habit
//!    of [`Habit::Row`], [`Habit::Column`] (against the west or east wall
//!    half of the time) or [`Habit::Block`] (`⌈√n⌉` columns filled row by
//!    row: 3 → an L in a 2×2 box, 4 → 2×2), no two classes the same habit
//!    when there are three;
//! 2. a box as for the ordinary tasks, widened so that a run of the largest
//!    problem's count fits;
//! 3. 3–5 demonstrations, per class 3..=max blocks at random places;
//! 4. rules learned with the configuration's templates;
//! 5. problems at the configuration's sizes (the full run: 1×, 1.5×, 2×).
//!
//! # How to extend
//!
//! A new shape habit needs a [`Habit`] variant, a placement in
//! `place_group` and the [`ShapeKind`] it shows in [`habit_shape`].

use super::{
    box_for, demo_scene, learn_with, problems_in, rotated, scaled, style_text, BenchTask, BoxGeom,
    ClassSpec, Habit, Placer, TaskGenError, TaskSeries, TasksConfig, WallSide, GRID,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::relations::Contact;
use rccpack::scene::{Rect, Scene};
use rccpack::shapes::{self, ShapeKind};

/// The first random stream of group tasks.
pub const GROUP_STREAM: u64 = 1 << 32;

/// The group shape a habit demonstrates, if any.
pub fn habit_shape(h: Habit) -> Option<ShapeKind> {
    match h {
        Habit::Row => Some(ShapeKind::Row),
        Habit::Column { .. } => Some(ShapeKind::Column),
        Habit::Block => Some(ShapeKind::Block),
        _ => None,
    }
}

/// Place `n` blocks of `spec` by a group habit (`None`: no room found).
pub(super) fn place_group(
    p: &Placer,
    spec: &ClassSpec,
    n: usize,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Rect>> {
    let (w, h) = (spec.width, spec.height);
    let i = p.interior;
    let (x0, y0, x1, y1) = (i.x, i.y, i.x + i.w, i.y + i.h);
    let n64 = n as i64;
    // (columns, rows) of the shape and the cell of block k.
    let (cols, rows) = match spec.habit {
        Habit::Row => (n64, 1),
        Habit::Column { .. } => (1, n64),
        Habit::Block => {
            let c = (n as f64).sqrt().ceil() as i64;
            (c, (n64 + c - 1) / c)
        }
        _ => return None,
    };
    let cell = |k: i64| match spec.habit {
        Habit::Row => (k, 0),
        Habit::Column { .. } => (0, k),
        _ => (k % cols, k / cols),
    };
    let xs: Vec<i64> = match spec.habit {
        Habit::Column {
            wall: Some(WallSide::W),
        } => vec![x0],
        Habit::Column { wall: Some(_) } => vec![x1 - w],
        _ => rotated(x0, x1 - cols * w, rng),
    };
    let ys = rotated(y0, y1 - rows * h, rng);
    for &x in xs.iter().take(40) {
        for &y in ys.iter().take(10) {
            let rs: Vec<Rect> = (0..n64)
                .map(|k| {
                    let (c, r) = cell(k);
                    Rect::new(x + c * w, y + r * h, w, h)
                })
                .collect();
            if p.all_free(&rs) {
                return Some(rs);
            }
        }
    }
    None
}

fn draw_group_habits(k: usize, rng: &mut ChaCha8Rng) -> Vec<Habit> {
    let column = |rng: &mut ChaCha8Rng| Habit::Column {
        wall: match rng.random_range(0..4) {
            0 => Some(WallSide::W),
            1 => Some(WallSide::E),
            _ => None,
        },
    };
    let mut out: Vec<Habit> = Vec::with_capacity(k);
    while out.len() < k {
        let h = match rng.random_range(0..3) {
            0 => Habit::Row,
            1 => column(rng),
            _ => Habit::Block,
        };
        let same = out
            .iter()
            .filter(|o| std::mem::discriminant(*o) == std::mem::discriminant(&h))
            .count();
        // Two columns against the same wall would stand in each other's way.
        let clash = matches!(h, Habit::Column { wall: Some(_) }) && out.contains(&h);
        if (k < 3 || same == 0) && !clash {
            out.push(h);
        }
    }
    out
}

/// Group task `index` of `cfg` (deterministic in `cfg.seed`, `index`,
/// `cfg.sizes`' values and `cfg.templates`).
pub fn generate_group_task(cfg: &TasksConfig, index: usize) -> Result<BenchTask, TaskGenError> {
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    rng.set_stream(GROUP_STREAM + index as u64);
    let largest = cfg.sizes.iter().copied().fold(1.0, f64::max);
    const TRIES: usize = 20;
    for _ in 0..TRIES {
        let k = rng.random_range(2..=3usize);
        let classes = draw_group_classes(k, &mut rng);
        let geom = group_box(&classes, largest, &mut rng);
        let Some(demos) = group_demos(&geom, &classes, &mut rng) else {
            continue;
        };
        let (rules, rcc) = learn_with(&demos, index, cfg.templates)?;
        let style = style_text(&classes);
        let problems = problems_in(&geom, &classes, &cfg.sizes, &format!("group{index:02}"));
        return Ok(BenchTask {
            series: TaskSeries::Groups,
            index,
            classes,
            style,
            demos,
            rcc,
            rules,
            problems,
        });
    }
    Err(TaskGenError::Unplaceable {
        task: index,
        tries: TRIES,
    })
}

/// The `k` classes of a group task: habits first, then per class a block
/// size (20×20 three times as likely) and a largest count of 3 or 4.
fn draw_group_classes(k: usize, rng: &mut ChaCha8Rng) -> Vec<ClassSpec> {
    let habits = draw_group_habits(k, rng);
    (0..k)
        .map(|i| {
            let (w, h) =
                [(20, 20), (20, 20), (20, 20), (30, 20), (20, 30)][rng.random_range(0..5usize)];
            ClassSpec {
                class: ["R", "G", "B"][i].to_string(),
                width: w,
                height: h,
                max_count: rng.random_range(3..=4),
                habit: habits[i],
                orientation: crate::tasks::Orientation::Fixed,
            }
        })
        .collect()
}

/// The box of a group task: [`box_for`] at `max(2, largest)`, widened for
/// the longest run of the largest problem and a block.
fn group_box(classes: &[ClassSpec], largest: f64, rng: &mut ChaCha8Rng) -> BoxGeom {
    let mut geom = box_for(classes, largest.max(2.0), rng);
    let run = classes
        .iter()
        .map(|c| scaled(c.max_count, largest) as i64 * c.width.max(c.height) + 2 * GRID)
        .max()
        .unwrap_or(0);
    geom.width = geom.width.max(run);
    geom.height = geom.height.max(run);
    geom.margin = geom.width.max(geom.height) - GRID;
    geom
}

/// 3–5 demonstrations, the first showing every class's largest count, or
/// `None` when one could not be placed.
fn group_demos(geom: &BoxGeom, classes: &[ClassSpec], rng: &mut ChaCha8Rng) -> Option<Vec<Scene>> {
    let d = rng.random_range(3..=5usize);
    let mut demos = Vec::with_capacity(d);
    for di in 0..d {
        let placed = (0..20).find_map(|_| place_group_demo(geom, classes, di == 0, rng))?;
        demos.push(demo_scene(geom, classes, &placed));
    }
    Some(demos)
}

/// One attempt at a demonstration's blocks, per class by its group habit
/// (`largest`: every class at its largest count, else 3..=largest).
fn place_group_demo(
    geom: &BoxGeom,
    classes: &[ClassSpec],
    largest: bool,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Vec<Rect>>> {
    let mut p = Placer {
        interior: geom.interior(),
        taken: Vec::new(),
    };
    let mut all: Vec<Vec<Rect>> = Vec::new();
    for c in classes {
        let n = if largest {
            c.max_count
        } else {
            rng.random_range(3..=c.max_count)
        };
        let rs = place_group(&p, c, n, rng)?;
        p.taken.extend(rs.iter().copied());
        all.push(rs);
    }
    Some(all)
}

/// Of the classes of `task` demonstrated with a group habit, how many keep
/// their shape in `layout`: `(kept, classes)`.
pub fn shapes_kept(task: &BenchTask, layout: &Scene, contact: Contact) -> (usize, usize) {
    let mut kept = 0;
    let mut total = 0;
    for c in &task.classes {
        let Some(kind) = habit_shape(c.habit) else {
            continue;
        };
        total += 1;
        let rects: Vec<Rect> = layout
            .objects
            .iter()
            .filter(|o| o.class == c.class)
            .filter_map(|o| o.rect())
            .collect();
        kept += usize::from(shapes::check(kind, &rects, contact).holds);
    }
    (kept, total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn group_demonstrations_show_their_shapes() {
        let mut cfg = TasksConfig::quick(0, std::time::Duration::from_secs(1));
        cfg.sizes = vec![1.0, 2.0];
        for t in 0..4 {
            let task = generate_group_task(&cfg, t).unwrap();
            for d in &task.demos {
                d.validate().unwrap();
                let (kept, total) = shapes_kept(&task, d, Contact::Point);
                assert_eq!(kept, total, "task {t}: {}", task.style);
                assert!(total >= 2);
            }
            assert_eq!(task.problems.len(), 2);
            // Same seed, same task.
            assert_eq!(generate_group_task(&cfg, t).unwrap().demos, task.demos);
        }
    }
}
