//! Demonstrations as they are really recorded (`rccpack-bench noisy`):
//! the generated tasks of [`super::tasks`] and the bundled example, each
//! learned from its exact demonstrations and from four recorded variants,
//! with the rules compared.
//!
//! | variant | what changes |
//! |---|---|
//! | `jitter` | every movable block moved by up to ±[`NoisyConfig::jitter`] px on each axis, in tenths of a pixel (a camera; no snapping) |
//! | `slip` | one block of one demonstration moved to a free grid place where it breaks at least one rule learned from the exact demonstrations |
//! | `both` | the slip, then the jitter |
//! | `rough` | the jitter, and one block in five (each with probability [`NoisyConfig::rough_share`]) off by 5–6 px on one axis |
//!
//! Per task and variant: how many of the exact rules are learned again
//! (recall), how many rules appear that the exact demonstrations do not
//! give (extra), whether the slipped block is named among the suspects (and
//! first), and, for the slip, whether a layout of the task's first problem
//! solved with the slipped rules keeps every exact rule that the layout
//! solved with the exact rules keeps.
//!
//! The learner is injected ([`LearnFn`]): it takes the demonstrations as
//! JSON (fractions included) and returns the learned rules and the
//! suspects, so the benchmark measures exactly what `rccpack learn` does.

use super::tasks::{self, BenchTask, TaskGenError, TasksConfig};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::eval::evaluate;
use rccpack::relations::Contact;
use rccpack::rules::RuleSet;
use rccpack::scene::{scenes_to_json, Scene};
use rccpack::synth::synthesize;
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeSet;
use std::time::Duration;

/// A suspect as the learner names it: demonstration index (from 0) and
/// object id.
pub type Suspect = (usize, String);

/// The learner: demonstrations (a JSON array of scenes, coordinates may be
/// fractional) → the learned rules and the suspects, most suspect first;
/// an error as text.
pub type LearnFn<'a> = &'a (dyn Fn(&Value) -> Result<(RuleSet, Vec<Suspect>), String> + Sync);

/// The benchmark's parameters.
#[derive(Debug, Clone, Serialize)]
pub struct NoisyConfig {
    /// Seed of the tasks and of every change made to them.
    pub seed: u64,
    /// Generated tasks (0..tasks).
    pub tasks: usize,
    /// Also the bundled example.
    pub example: bool,
    /// Largest jitter per axis, px.
    pub jitter: f64,
    /// Share of blocks off by 5–6 px in the `rough` variant.
    pub rough_share: f64,
    /// Time limit of each solve of the slip check.
    #[serde(serialize_with = "super::thesis::ser_secs")]
    pub time_limit: Duration,
}

impl NoisyConfig {
    /// Ten generated tasks and the example, ±3 px, one block in five rough,
    /// 10 s per solve.
    pub fn full(seed: u64) -> Self {
        NoisyConfig {
            seed,
            tasks: 10,
            example: true,
            jitter: 3.0,
            rough_share: 0.2,
            time_limit: Duration::from_secs(10),
        }
    }
}

/// A recorded variant of the demonstrations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Variant {
    /// The exact demonstrations, learned by the learner measured (the
    /// reference is the thesis's learner on them).
    Exact,
    /// Every movable block jittered.
    Jitter,
    /// One slipped block.
    Slip,
    /// The slip and the jitter.
    Both,
    /// Jitter, and some blocks 5–6 px off.
    Rough,
}

impl Variant {
    /// Every variant, in table order.
    pub const ALL: [Variant; 5] = [
        Variant::Exact,
        Variant::Jitter,
        Variant::Slip,
        Variant::Both,
        Variant::Rough,
    ];

    /// Its name in the table.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Exact => "exact",
            Variant::Jitter => "jitter",
            Variant::Slip => "slip",
            Variant::Both => "both",
            Variant::Rough => "rough",
        }
    }
}

/// Where the slip was put.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Slip {
    /// The demonstration (from 0).
    pub demonstration: usize,
    /// The object's id.
    pub object: String,
    /// Its place in the exact demonstration.
    pub from: (i64, i64),
    /// Where it was put.
    pub to: (i64, i64),
    /// The exact rules the moved block breaks.
    pub breaks: Vec<String>,
}

/// One variant of one task, learned.
#[derive(Debug, Clone, Serialize)]
pub struct VariantRow {
    /// The variant.
    pub variant: Variant,
    /// Learning refused the demonstrations (the error).
    pub error: Option<String>,
    /// Exact rules learned again.
    pub kept: usize,
    /// Rules the exact demonstrations do not give.
    pub extra: usize,
    /// The exact rules not learned again.
    pub lost: Vec<String>,
    /// Suspects named, in order.
    pub suspects: Vec<Suspect>,
    /// The slip is among the suspects (`None`: no slip in this variant).
    pub slip_named: Option<bool>,
    /// The slip is the first suspect.
    pub slip_first: Option<bool>,
}

/// One task.
#[derive(Debug, Clone, Serialize)]
pub struct NoisyRow {
    /// `task03` or `example`.
    pub name: String,
    /// Rules the reference learner learns from the exact demonstrations.
    pub exact: usize,
    /// Suspects named on the exact demonstrations (should be none).
    pub exact_suspects: usize,
    /// Where the slip was put (`None`: no free place breaks a rule).
    pub slip: Option<Slip>,
    /// Every variant, in [`Variant::ALL`] order.
    pub variants: Vec<VariantRow>,
    /// Exact rules kept by every object of the layout solved with the
    /// exact rules, and of those, how many the layout solved with the
    /// slipped rules keeps too (`None`: not measured).
    pub run_kept: Option<(usize, usize)>,
}

/// The whole run.
#[derive(Debug, Clone, Serialize)]
pub struct NoisyReport {
    /// The parameters.
    pub config: NoisyConfig,
    /// One row per task.
    pub rows: Vec<NoisyRow>,
}

/// Why the benchmark cannot run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum NoisyError {
    /// A task could not be made.
    #[error(transparent)]
    Task(#[from] TaskGenError),
    /// The exact demonstrations of a task could not be learned.
    #[error("{task}: the exact demonstrations: {error}")]
    Exact {
        /// The task.
        task: String,
        /// The learner's error.
        error: String,
    },
}

fn rng_for(seed: u64, task: usize, variant: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6e6f_6973_7921);
    rng.set_stream((task as u64) * 8 + variant);
    rng
}

/// The demonstrations as JSON values (integers as they are).
fn to_values(demos: &[Scene]) -> Vec<Value> {
    match serde_json::from_str(&scenes_to_json(demos)) {
        Ok(Value::Array(v)) => v,
        _ => Vec::new(),
    }
}

/// A coordinate moved by `d` px, kept to tenths of a pixel.
fn moved(v: &Value, d: f64) -> Value {
    let x = v.as_f64().unwrap_or(0.0) + d;
    let tenths = (x * 10.0).round() / 10.0;
    serde_json::Number::from_f64(tenths).map_or(Value::Null, Value::Number)
}

/// Every movable block of `demos` moved by up to ±`px` on each axis; with
/// `rough > 0`, each block with that probability off by 5–6 px on one
/// axis instead.
pub fn jittered(demos: &[Value], px: f64, rough: f64, rng: &mut ChaCha8Rng) -> Value {
    let mut out = demos.to_vec();
    for scene in &mut out {
        let Some(objects) = scene.get_mut("objects").and_then(Value::as_array_mut) else {
            continue;
        };
        for o in objects {
            if o.get("fixed").and_then(Value::as_bool) == Some(true) {
                continue;
            }
            let mut d = [rng.random_range(-px..=px), rng.random_range(-px..=px)];
            if rough > 0.0 && rng.random_range(0.0..1.0) < rough {
                let axis = rng.random_range(0..2usize);
                let sign = if rng.random_range(0..2u8) == 0 {
                    -1.0
                } else {
                    1.0
                };
                d[axis] = sign * rng.random_range(5.0..=6.0);
            }
            for (key, d) in ["x", "y"].into_iter().zip(d) {
                if let Some(v) = o.get(key).cloned() {
                    o[key] = moved(&v, d);
                }
            }
        }
    }
    Value::Array(out)
}

/// The exact rules broken by some object of `scene`.
fn broken(scene: &Scene, rules: &RuleSet) -> BTreeSet<String> {
    evaluate(scene, rules, Contact::Point)
        .rules
        .iter()
        .filter(|r| r.satisfied < r.subjects)
        .map(|r| r.name.clone())
        .collect()
}

/// One block of one demonstration moved to a free grid place where the
/// demonstration breaks at least one exact rule it kept; tried in a random
/// order of demonstrations, blocks and places. `None` when no place does.
pub fn slip(demos: &[Scene], rules: &RuleSet, rng: &mut ChaCha8Rng) -> Option<(Vec<Scene>, Slip)> {
    let mut order: Vec<(usize, usize)> = demos
        .iter()
        .enumerate()
        .flat_map(|(d, s)| {
            s.objects
                .iter()
                .enumerate()
                .filter(|(_, o)| !o.fixed)
                .map(move |(i, _)| (d, i))
        })
        .collect();
    shuffle(&mut order, rng);
    for (d, i) in order {
        let scene = &demos[d];
        let before = broken(scene, rules);
        let sp = scene.space.rect();
        let o = &scene.objects[i];
        let g = scene.grid;
        let mut places: Vec<(i64, i64)> = Vec::new();
        let (ow, oh) = o.footprint();
        let mut x = sp.x;
        while x + ow <= sp.x + sp.w {
            let mut y = sp.y;
            while y + oh <= sp.y + sp.h {
                places.push((x, y));
                y += g;
            }
            x += g;
        }
        shuffle(&mut places, rng);
        for (x, y) in places {
            if (Some(x), Some(y)) == (o.x, o.y) {
                continue;
            }
            let mut s = scene.clone();
            s.objects[i].x = Some(x);
            s.objects[i].y = Some(y);
            if s.validate().is_err() {
                continue;
            }
            let now = broken(&s, rules);
            let breaks: Vec<String> = now.difference(&before).cloned().collect();
            if breaks.is_empty() {
                continue;
            }
            let mut out = demos.to_vec();
            out[d] = s;
            let info = Slip {
                demonstration: d,
                object: o.id.clone(),
                from: (o.x.unwrap_or(0), o.y.unwrap_or(0)),
                to: (x, y),
                breaks,
            };
            return Some((out, info));
        }
    }
    None
}

fn shuffle<T>(v: &mut [T], rng: &mut ChaCha8Rng) {
    for i in (1..v.len()).rev() {
        let j = rng.random_range(0..=i);
        v.swap(i, j);
    }
}

fn names(rules: &RuleSet) -> BTreeSet<String> {
    rules.rules.iter().map(|r| r.name.clone()).collect()
}

/// Learn one variant and compare it with the exact rules.
fn compare(
    variant: Variant,
    demos: &Value,
    exact: &BTreeSet<String>,
    slip: Option<&Slip>,
    learn: LearnFn,
) -> (VariantRow, Option<RuleSet>) {
    let (rules, suspects) = match learn(demos) {
        Ok(x) => x,
        Err(error) => {
            let row = VariantRow {
                variant,
                error: Some(error),
                kept: 0,
                extra: 0,
                lost: exact.iter().cloned().collect(),
                suspects: Vec::new(),
                slip_named: slip.map(|_| false),
                slip_first: slip.map(|_| false),
            };
            return (row, None);
        }
    };
    let got = names(&rules);
    let is_slip = |s: &Suspect, sl: &Slip| s.0 == sl.demonstration && s.1 == sl.object;
    let row = VariantRow {
        variant,
        error: None,
        kept: exact.intersection(&got).count(),
        extra: got.difference(exact).count(),
        lost: exact.difference(&got).cloned().collect(),
        slip_named: slip.map(|sl| suspects.iter().any(|s| is_slip(s, sl))),
        slip_first: slip.map(|sl| suspects.first().is_some_and(|s| is_slip(s, sl))),
        suspects,
    };
    (row, Some(rules))
}

/// Exact rules every object of a layout of `problem` keeps, solved with
/// `rules` and the demonstrations (warm start and like-scenes).
fn kept_by_layout(
    problem: &Scene,
    rules: &RuleSet,
    exact: &RuleSet,
    demos: &[Scene],
    cfg: &NoisyConfig,
) -> Option<BTreeSet<String>> {
    let tcfg = TasksConfig {
        lns: true,
        warm_start: true,
        ..TasksConfig::full(cfg.seed, cfg.time_limit)
    };
    let opts = tasks::solve_options(&tcfg, demos, true);
    let result = synthesize(problem, rules, &opts).ok()?;
    let layout = result.scene?;
    let all = names(exact);
    Some(all.difference(&broken(&layout, exact)).cloned().collect())
}

/// One task: the exact rules, then every variant.
pub fn run_task(
    name: &str,
    index: usize,
    task: &BenchTask,
    cfg: &NoisyConfig,
    [reference, learn]: [LearnFn; 2],
) -> Result<NoisyRow, NoisyError> {
    let exact_json = Value::Array(to_values(&task.demos));
    let (exact_rules, _) = reference(&exact_json).map_err(|error| NoisyError::Exact {
        task: name.to_string(),
        error,
    })?;
    let exact = names(&exact_rules);
    let slipped = slip(&task.demos, &exact_rules, &mut rng_for(cfg.seed, index, 0));
    let mut variants = Vec::new();
    let mut slip_rules = None;
    for (k, variant) in Variant::ALL.into_iter().enumerate() {
        let mut rng = rng_for(cfg.seed, index, k as u64 + 1);
        let (demos, sl) = match variant {
            Variant::Exact => (exact_json.clone(), None),
            Variant::Jitter => (
                jittered(&to_values(&task.demos), cfg.jitter, 0.0, &mut rng),
                None,
            ),
            Variant::Rough => (
                jittered(
                    &to_values(&task.demos),
                    cfg.jitter,
                    cfg.rough_share,
                    &mut rng,
                ),
                None,
            ),
            Variant::Slip | Variant::Both => {
                let Some((demos, sl)) = &slipped else {
                    continue;
                };
                let v = to_values(demos);
                let json = if variant == Variant::Both {
                    jittered(&v, cfg.jitter, 0.0, &mut rng)
                } else {
                    Value::Array(v)
                };
                (json, Some(sl))
            }
        };
        let (row, rules) = compare(variant, &demos, &exact, sl, learn);
        if variant == Variant::Slip {
            slip_rules = rules;
        }
        variants.push(row);
    }
    let run_kept = match (&slipped, &slip_rules, task.problems.first()) {
        (Some((demos, _)), Some(rules), Some(p)) => {
            let base = kept_by_layout(&p.scene, &exact_rules, &exact_rules, &task.demos, cfg);
            let now = kept_by_layout(&p.scene, rules, &exact_rules, demos, cfg);
            match (base, now) {
                (Some(b), Some(n)) => Some((b.len(), b.intersection(&n).count())),
                _ => None,
            }
        }
        _ => None,
    };
    Ok(NoisyRow {
        name: name.to_string(),
        exact: exact.len(),
        exact_suspects: variants
            .iter()
            .find(|v| v.variant == Variant::Exact)
            .map_or(0, |v| v.suspects.len()),
        slip: slipped.map(|(_, s)| s),
        variants,
        run_kept,
    })
}

/// The whole benchmark: the exact rules from `reference` (the thesis's
/// learner), every variant from `learn`; `progress` is told each task as
/// it ends.
pub fn run(
    cfg: &NoisyConfig,
    learn: [LearnFn; 2],
    progress: &dyn Fn(&NoisyRow),
) -> Result<NoisyReport, NoisyError> {
    let tcfg = TasksConfig {
        tasks: cfg.tasks,
        sizes: vec![1.0],
        example_counts: vec![5],
        ..TasksConfig::full(cfg.seed, cfg.time_limit)
    };
    let mut rows = Vec::new();
    for i in 0..cfg.tasks {
        let task = tasks::generate_task(&tcfg, i)?;
        let row = run_task(&format!("task{i:02}"), i, &task, cfg, learn)?;
        progress(&row);
        rows.push(row);
    }
    if cfg.example {
        let task = tasks::example_task(&[5], tcfg.templates)?;
        let row = run_task("example", cfg.tasks, &task, cfg, learn)?;
        progress(&row);
        rows.push(row);
    }
    Ok(NoisyReport {
        config: cfg.clone(),
        rows,
    })
}

mod table;
pub use table::table_markdown;

#[cfg(test)]
mod tests {
    use super::*;

    fn small_task() -> BenchTask {
        let cfg = TasksConfig {
            tasks: 1,
            sizes: vec![1.0],
            ..TasksConfig::quick(0, Duration::from_secs(1))
        };
        tasks::generate_task(&cfg, 0).expect("task 0")
    }

    #[test]
    fn a_slip_breaks_an_exact_rule_it_names_and_stays_on_the_grid() {
        let task = small_task();
        let mut rng = rng_for(0, 0, 0);
        let (demos, sl) = slip(&task.demos, &task.rules, &mut rng).expect("a slip");
        let d = &demos[sl.demonstration];
        d.validate().expect("a valid scene");
        let o = d
            .objects
            .iter()
            .find(|o| o.id == sl.object)
            .expect("the object");
        assert_eq!((o.x, o.y), (Some(sl.to.0), Some(sl.to.1)));
        assert!(d.on_grid(o));
        let before = broken(&task.demos[sl.demonstration], &task.rules);
        let after = broken(d, &task.rules);
        assert!(!sl.breaks.is_empty());
        for b in &sl.breaks {
            assert!(after.contains(b) && !before.contains(b), "{b}");
        }
        // Every other demonstration is untouched.
        for (i, s) in demos.iter().enumerate() {
            if i != sl.demonstration {
                assert_eq!(s, &task.demos[i]);
            }
        }
    }

    #[test]
    fn jitter_moves_movable_blocks_within_the_bound_in_tenths() {
        let task = small_task();
        let exact = to_values(&task.demos);
        let j = jittered(&exact, 3.0, 0.0, &mut rng_for(0, 0, 1));
        let j = j.as_array().expect("array");
        let mut moved_any = false;
        for (a, b) in exact.iter().zip(j) {
            for (oa, ob) in a["objects"]
                .as_array()
                .expect("objects")
                .iter()
                .zip(b["objects"].as_array().expect("objects"))
            {
                for k in ["x", "y"] {
                    let (va, vb) = (oa[k].as_f64().expect("x"), ob[k].as_f64().expect("x"));
                    if oa.get("fixed").and_then(Value::as_bool) == Some(true) {
                        assert_eq!(va, vb);
                    }
                    assert!((va - vb).abs() <= 3.0 + 1e-9, "{va} {vb}");
                    assert!(((vb * 10.0).round() - vb * 10.0).abs() < 1e-6);
                    moved_any |= va != vb;
                }
            }
        }
        assert!(moved_any);
        // Same seed, same output.
        let again = jittered(&exact, 3.0, 0.0, &mut rng_for(0, 0, 1));
        assert_eq!(again.as_array().expect("array"), j);
    }

    #[test]
    fn rough_blocks_are_five_to_six_px_off_on_one_axis() {
        let task = small_task();
        let exact = to_values(&task.demos);
        let j = jittered(&exact, 3.0, 1.0, &mut rng_for(0, 0, 4));
        for (a, b) in exact.iter().zip(j.as_array().expect("array")) {
            for (oa, ob) in a["objects"]
                .as_array()
                .expect("objects")
                .iter()
                .zip(b["objects"].as_array().expect("objects"))
            {
                if oa.get("fixed").and_then(Value::as_bool) == Some(true) {
                    continue;
                }
                let d: Vec<f64> = ["x", "y"]
                    .iter()
                    .map(|k| (oa[*k].as_f64().expect("x") - ob[*k].as_f64().expect("x")).abs())
                    .collect();
                let far = d.iter().filter(|v| **v >= 4.95).count();
                assert_eq!(far, 1, "{d:?}");
                assert!(d.iter().all(|v| *v <= 6.05), "{d:?}");
            }
        }
    }
}
