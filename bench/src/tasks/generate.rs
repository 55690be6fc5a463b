//! Generated tasks and the bundled example as tasks: classes, style, box,
//! demonstrations, learned rules and problems, all drawn from the task's
//! seeded stream.

use super::place::{block, box_for, make_demos, BoxGeom};
use super::style::{ClassSpec, Corner, Habit, Orientation, WallSide};
use super::{
    groups, scaled, size_label, BenchTask, TaskGenError, TaskProblem, TaskSeries, TasksConfig,
    BLOCK_SIZES, BOX_FOR, EXAMPLE_DEMOS, EXAMPLE_PROBLEM, TASK_CLASSES,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::infer::{learn, LearnParams, Templates};
use rccpack::rules::RuleSet;
use rccpack::scene::{scenes_from_json, Scene};

/// The habits of a task's classes (anchors not shared).
fn draw_habits(k: usize, rng: &mut ChaCha8Rng) -> Vec<Habit> {
    let mut walls = vec![WallSide::S, WallSide::W, WallSide::E, WallSide::N];
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
                    Habit::Band { wall: WallSide::N }
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

pub(crate) fn task_rng(seed: u64, task: usize) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(task as u64 + 1);
    rng
}

/// Learn with the default parameters and `templates`; the rules and their
/// `.rcc` text.
pub(super) fn learn_with(
    demos: &[Scene],
    task: usize,
    templates: Templates,
) -> Result<(RuleSet, String), TaskGenError> {
    let params = LearnParams {
        templates,
        ..LearnParams::default()
    };
    let learned =
        learn(demos, None, &params).map_err(|error| TaskGenError::Learn { task, error })?;
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
pub fn generate_task(cfg: &TasksConfig, index: usize) -> Result<BenchTask, TaskGenError> {
    let mut rng = task_rng(cfg.seed, index);
    // `--turnable`: the orientation habits from a stream of their own, so
    // that the flat tasks' draws are untouched.
    let mut turns = cfg.turnable.then(|| turn_rng(cfg.seed, index));
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
                    orientation: Orientation::Fixed,
                }
            })
            .collect();
        let mut classes = classes;
        if let Some(r) = turns.as_mut() {
            orient(&mut classes, r);
        }
        // The blocks as the demonstrations lay them.
        let laid = laid(&classes);
        let geom = box_for(&laid, largest, &mut rng);
        let Some(mut demos) = make_demos(&geom, &laid, &mut rng) else {
            continue;
        };
        for d in &mut demos {
            turn_blocks(d, &classes);
        }
        let (rules, rcc) = learn_with(&demos, index, cfg.templates)?;
        let style = style_text(&classes);
        let mut problems = problems_in(&geom, &classes, &cfg.sizes, &format!("task{index:02}"));
        for p in &mut problems {
            turn_blocks(&mut p.scene, &classes);
        }
        return Ok(BenchTask {
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
    Err(TaskGenError::Unplaceable {
        task: index,
        tries: TRIES,
    })
}

/// The stream of task `task`'s orientation habits (`--turnable`).
fn turn_rng(seed: u64, task: usize) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream((1u64 << 40) + task as u64);
    rng
}

/// Every oblong class turns; a fair coin per class says whether the
/// demonstrator stands its blocks on end or lays them flat.
fn orient(classes: &mut [ClassSpec], rng: &mut ChaCha8Rng) {
    for c in classes.iter_mut().filter(|c| c.width != c.height) {
        c.orientation = if rng.random_bool(0.5) {
            Orientation::OnEnd
        } else {
            Orientation::Flat
        };
    }
}

/// The classes with the footprint the demonstrations give their blocks
/// (a class stood on end: height × width).
fn laid(classes: &[ClassSpec]) -> Vec<ClassSpec> {
    let mut out = classes.to_vec();
    for c in out
        .iter_mut()
        .filter(|c| c.orientation == Orientation::OnEnd)
    {
        (c.width, c.height) = (c.height, c.width);
    }
    out
}

/// The blocks of `scene` (placed by [`laid`] sizes, or unplaced) as their
/// class's orientation has them: `turnable` when the class turns, and a
/// placed block of a class stood on end its own size, `turned`.
fn turn_blocks(scene: &mut Scene, classes: &[ClassSpec]) {
    for o in scene.objects.iter_mut().filter(|o| !o.fixed) {
        let Some(c) = classes.iter().find(|c| c.class == o.class) else {
            continue;
        };
        match c.orientation {
            Orientation::Fixed => {}
            Orientation::Flat => o.turnable = true,
            Orientation::OnEnd => {
                o.turnable = true;
                if o.is_placed() {
                    (o.width, o.height) = (c.width, c.height);
                    o.turned = true;
                }
            }
        }
    }
}

/// The style in words, e.g. `R 20x20 ≤4: band on the S wall; G 30x30 ≤3:
/// north of R`.
pub(super) fn style_text(classes: &[ClassSpec]) -> String {
    classes
        .iter()
        .map(|c| {
            format!(
                "{} {}x{} ≤{}{}: {}",
                c.class,
                c.width,
                c.height,
                c.max_count,
                match c.orientation {
                    Orientation::Fixed => "",
                    Orientation::Flat => " turnable, laid flat",
                    Orientation::OnEnd => " turnable, stood on end",
                },
                c.habit.describe(classes)
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The problems of a task: for every size `m` of `sizes`, `⌈m·M_c⌉`
/// unplaced blocks of each class in the task's box, named `{stem}-{m}x`.
pub(super) fn problems_in(
    geom: &BoxGeom,
    classes: &[ClassSpec],
    sizes: &[f64],
    stem: &str,
) -> Vec<TaskProblem> {
    sizes
        .iter()
        .enumerate()
        .map(|(si, &m)| {
            let mut scene = geom.scene();
            for c in classes {
                let n = scaled(c.max_count, m);
                scene
                    .objects
                    .extend((0..n).map(|j| block(&c.class, j, c.width, c.height, None)));
            }
            let movable = scene.objects.iter().filter(|o| !o.fixed).count();
            TaskProblem {
                size_index: si,
                size: size_label(m),
                name: format!("{stem}-{}", size_label(m)),
                scene,
                movable,
            }
        })
        .collect()
}

/// The bundled example with `counts` blocks per class (same classes and
/// sizes as its `problem.json`, in its box), rules learned from its
/// `demos.json`.
pub fn example_task(counts: &[usize], templates: Templates) -> Result<BenchTask, TaskGenError> {
    let demos =
        scenes_from_json(EXAMPLE_DEMOS).map_err(|e| TaskGenError::Example(e.to_string()))?;
    let base =
        Scene::from_json(EXAMPLE_PROBLEM).map_err(|e| TaskGenError::Example(e.to_string()))?;
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
    Ok(BenchTask {
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
pub fn all_tasks(cfg: &TasksConfig) -> Result<Vec<BenchTask>, TaskGenError> {
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
