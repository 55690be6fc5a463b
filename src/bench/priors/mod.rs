//! Priors learned across tasks, measured on a population of demonstrators
//! (`rccpack bench priors`, issue 30).
//!
//! # Population
//!
//! Every task is drawn from `ChaCha8Rng::seed_from_u64(seed)` on a stream of
//! its own, with the generator of [`super::tasks`] (box, block sizes,
//! counts, placement by habit), but with two differences that make a
//! library of such tasks look like the work of many people:
//!
//! * **Class names vary.** Each task names its 2–4 classes with names drawn
//!   (without repetition) from [`CLASS_POOL`], so what carries across tasks
//!   is the *kind* of a statement, never its class names.
//! * **Styles are far from uniform.** Each class's habit is drawn with the
//!   weights of [`HABIT_WEIGHTS`]: a connected cluster and a band on the
//!   floor (the south wall) are common, "north of an earlier class" is
//!   frequent, bands on the other walls, corners and stacks are rare. As in
//!   `bench tasks`, anchors are not shared (one class per wall or corner,
//!   one stack) and "north of" needs an earlier class with room above it;
//!   a habit that is not available drops out and the others keep their
//!   weights.
//!
//! # Ground truth
//!
//! A task's style is demonstrated [`PriorsBenchConfig::truth_demos`] times
//! (default 40). Its **truth** is what [`learn`] keeps from all of them
//! with the default parameters and the uniform prior: with 40
//! demonstrations a chance habit (the cluster happened to touch the west
//! wall in the three scenes shown) is broken by some scene and vanishes,
//! while the intended placement and its consequences (inside the box, on
//! the floor, touching its own class) remain. The task itself shows only
//! the first few of these scenes: 3–5 for a library task (drawn), 4 for a
//! held-out task. So every truth rule is a candidate of the task's
//! demonstrations, and a library task's kept rules (its `learned.rcc`,
//! what a person keeps after `ask`) are its truth rules.
//!
//! # Conditions
//!
//! Population tasks `1..=L+H` (L the largest library size, H the held-out
//! count) are split by a seeded shuffle: H held-out tasks, the rest the
//! library; a library of size `s` is the first `s` library tasks, so the
//! libraries are nested. Each held-out task is learned from its four
//! demonstrations under:
//!
//! * **uniform** — no priors (every statement's prior 1/2);
//! * **learned** — priors from the library, counted and combined by
//!   [`crate::priors::task_counts`] and [`crate::priors::combine`] (the
//!   code `rccpack priors` runs);
//! * **shuffled** — the same library with each task's kept rules replaced
//!   by as many candidates of *other* kinds (kinds none of its kept rules
//!   has), drawn at random: the same number of kept rules per task, so
//!   the pooled rates are alike, but the kinds are wrong;
//! * **true** — priors from a large library of the same population
//!   ([`PriorsBenchConfig::true_library`] tasks on streams of their own):
//!   the population's frequencies, the upper bound.
//!
//! # Metrics
//!
//! Per condition, summed over the held-out tasks:
//!
//! * **truth** — truth rules that are candidates of the held-out
//!   demonstrations (all of them, by construction);
//! * **recall** — of these, the ones learned, or implied
//!   (`rule_implies`, syntactically) by a learned truth rule;
//! * **rare** — truth rules whose most specific kind is *rare in the
//!   population*: kept in fewer than [`PriorsBenchConfig::rare_percent`] %
//!   (default 15) of the tasks of the true library; **rare recall** as
//!   recall, over these;
//! * **spurious** — learned rules that are neither truth rules nor implied
//!   by a truth rule (habits of the few demonstrations shown);
//! * **truth ruled out** — truth rules whose kind the priors ruled out (left
//!   out of the statements, so they cannot be learned);
//! * **questions** (unless `--no-ask`; uniform and the largest learned
//!   library only, because a loop takes half a minute to two minutes; on
//!   every held-out task unless [`PriorsBenchConfig::ask_tasks`] says
//!   fewer) — the question loop ([`crate::ask::Asker`]) on the task's
//!   problem (its box with each class's largest count, unplaced),
//!   with the truth as the oracle: a probe is accepted iff every truth rule
//!   holds for every object. It stops when no question is left or after
//!   [`PriorsBenchConfig::max_questions`] (a capped task counts the cap).
//!   Every question runs under the default node budget with no wall-clock
//!   cap and probe searches without a time limit, so the questions do not
//!   depend on the machine or the thread count.
//!
//! Everything is integers or comes from seeded streams, and results are
//! gathered in task order: the same seed gives the same report on any
//! number of threads.

use super::tasks::{
    block, box_for, draw_maxes, make_demos_n, BoxGeom, ClassSpec, Corner, Habit, WallSide,
    BLOCK_SIZES, BOX_FOR,
};
use crate::ask::{AskOptions, Asker, ProbeOptions, QuestionBudget};
use crate::eval::evaluate;
use crate::infer::english::rule_implies;
use crate::infer::{self, learn, learn_with_priors, templates, InferError, LearnParams};
use crate::priors::{self, Kind, PriorParams, Priors, TaskCounts};
use crate::rules::{print_rules, Formula, Rule, RuleSet, Scope};
use crate::scene::{scenes_to_json, Scene};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet, HashSet};
use std::sync::Arc;

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
const TRUE_STREAMS: u64 = 1 << 32;
/// Streams of the shuffled control's draws: this plus the task's stream.
const SHUFFLE_STREAMS: u64 = 1 << 40;
/// Rows of the spurious-kind table in the markdown.
const SPURIOUS_SHOWN: usize = 12;
/// Tries to draw a style whose demonstrations can all be placed.
const TRIES: usize = 20;

/// What the benchmark runs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PriorsBenchConfig {
    /// Seed of every random choice.
    pub seed: u64,
    /// Library sizes, each a prefix of the library (default 5, 10, 20, 40).
    pub library_sizes: Vec<usize>,
    /// Held-out tasks (default 12).
    pub held_out: usize,
    /// Demonstrations of a held-out task (default 4).
    pub held_out_demos: usize,
    /// Demonstrations the truth is learned from (default 40).
    pub truth_demos: usize,
    /// Tasks of the true-frequency library (default 200).
    pub true_library: usize,
    /// Run the question loop (uniform and the largest learned library).
    pub ask: bool,
    /// Stop the question loop after this many questions (default 40).
    pub max_questions: usize,
    /// Run the question loop on the first this many held-out tasks
    /// (`None`, the default: on all of them).
    pub ask_tasks: Option<usize>,
    /// A truth rule is *rare* when its kind was kept in fewer than this
    /// percentage of the true library's tasks (default 15).
    pub rare_percent: u64,
    /// The estimator's parameters (strength, rule-out threshold, template
    /// set, contact mode; learning uses the same set and mode).
    #[serde(serialize_with = "ser_params")]
    pub params: PriorParams,
}

fn ser_params<S: serde::Serializer>(p: &PriorParams, s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeStruct;
    let mut st = s.serialize_struct("PriorParams", 4)?;
    st.serialize_field("strength", &p.strength)?;
    st.serialize_field("rule_out_after", &p.rule_out_after)?;
    st.serialize_field("templates", &p.templates.to_string())?;
    st.serialize_field("contact", &format!("{:?}", p.contact).to_lowercase())?;
    st.end()
}

impl PriorsBenchConfig {
    /// The full benchmark: libraries of 5, 10, 20, 40 tasks, 12 held-out
    /// tasks of 4 demonstrations, truth from 40, a true library of 200,
    /// the question loop capped at 40.
    pub fn full(seed: u64) -> Self {
        PriorsBenchConfig {
            seed,
            library_sizes: vec![5, 10, 20, 40],
            held_out: 12,
            held_out_demos: 4,
            truth_demos: 40,
            true_library: 200,
            ask: true,
            max_questions: 40,
            ask_tasks: None,
            rare_percent: 15,
            params: PriorParams::default(),
        }
    }

    /// The largest library size (0 without any).
    pub fn largest(&self) -> usize {
        self.library_sizes.iter().copied().max().unwrap_or(0)
    }

    /// Check the sizes; the error names the setting.
    pub fn validate(&self) -> Result<(), PriorsBenchError> {
        let bad = |what: &str| Err(PriorsBenchError::Config(what.to_string()));
        if self.library_sizes.is_empty() || self.library_sizes.contains(&0) {
            return bad("library sizes: give at least one, each at least 1");
        }
        if self.held_out == 0 {
            return bad("held-out tasks: at least 1");
        }
        if self.held_out_demos == 0 || self.held_out_demos > self.truth_demos {
            return bad("held-out demonstrations: at least 1 and at most the truth's");
        }
        if self.truth_demos < 5 {
            return bad("truth demonstrations: at least 5 (a library task shows up to 5)");
        }
        if self.true_library == 0 {
            return bad("true library: at least 1 task");
        }
        Ok(())
    }

    fn learn_params(&self) -> LearnParams {
        LearnParams {
            templates: self.params.templates,
            contact: self.params.contact,
            ..LearnParams::default()
        }
    }
}

/// Why the benchmark stopped.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PriorsBenchError {
    /// A setting is out of range.
    #[error("bench priors: {0}")]
    Config(String),
    /// Learning failed on a task.
    #[error("population task {stream}: learning failed: {error}")]
    Learn {
        /// The task's stream.
        stream: u64,
        /// The learner's error.
        error: InferError,
    },
    /// No style of the task could be demonstrated.
    #[error("population task {stream}: no style could be demonstrated after {TRIES} tries")]
    Unplaceable {
        /// The task's stream.
        stream: u64,
    },
    /// The question loop failed on a held-out task.
    #[error("population task {stream}: the question loop failed: {message}")]
    Ask {
        /// The task's stream.
        stream: u64,
        /// What went wrong.
        message: String,
    },
}

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

/// The generated statements of a task's demonstrations with, per
/// statement, its most specific kind and whether it is a candidate.
struct Statements {
    set: RuleSet,
    kinds: Vec<String>,
    candidate: Vec<bool>,
}

impl Statements {
    fn of(demos: &[Scene], params: &PriorParams, stream: u64) -> Result<Self, PriorsBenchError> {
        let (set, origins) = templates::generate_with_origins(demos, params.templates);
        let candidate = infer::candidate_flags(demos, &set, params.contact)
            .map_err(|error| PriorsBenchError::Learn { stream, error })?;
        let classes = templates::demo_classes(demos);
        let movable = |c: &str| classes.iter().any(|(n, m)| n == c && *m);
        let kinds = origins.iter().map(|o| Kind::of(o, movable).key()).collect();
        Ok(Statements {
            set,
            kinds,
            candidate,
        })
    }

    /// Index of the statement with `rule`'s scope and formula.
    fn index_of(&self, rule: &Rule) -> Option<usize> {
        self.set
            .rules
            .iter()
            .position(|s| s.scope == rule.scope && s.formula == rule.formula)
    }
}

/// A task's counts as `rccpack priors` makes them from a folder holding
/// its demonstrations and `kept` as `learned.rcc`.
fn counts_of(
    task: &PopTask,
    kept: &RuleSet,
    params: &PriorParams,
) -> Result<TaskCounts, PriorsBenchError> {
    let demos_text = scenes_to_json(&task.demos);
    let kept_text = print_rules(kept);
    let hash = priors::estimate::input_hash(&[&demos_text, &kept_text]);
    priors::task_counts(&task.demos, kept, &[], params, hash).map_err(|error| {
        PriorsBenchError::Learn {
            stream: task.stream,
            error,
        }
    })
}

/// The rules a person keeps for a library task: its truth rules that are
/// candidates of its demonstrations.
fn kept_rules(task: &PopTask, params: &PriorParams) -> Result<RuleSet, PriorsBenchError> {
    let flags =
        infer::candidate_flags(&task.demos, &task.truth, params.contact).map_err(|error| {
            PriorsBenchError::Learn {
                stream: task.stream,
                error,
            }
        })?;
    Ok(RuleSet::new(
        task.truth
            .rules
            .iter()
            .zip(flags)
            .filter(|(_, c)| *c)
            .map(|(r, _)| r.clone())
            .collect(),
    ))
}

/// The shuffled control's kept rules for a library task: as many
/// candidates as it keeps, drawn among the candidates of kinds none of its
/// kept rules has (all of them when there are fewer).
fn shuffled_rules(
    task: &PopTask,
    kept: &RuleSet,
    cfg: &PriorsBenchConfig,
) -> Result<RuleSet, PriorsBenchError> {
    let st = Statements::of(&task.demos, &cfg.params, task.stream)?;
    let kept_kinds: BTreeSet<&str> = kept
        .rules
        .iter()
        .filter_map(|r| st.index_of(r))
        .map(|i| st.kinds[i].as_str())
        .collect();
    let mut others: Vec<usize> = (0..st.set.rules.len())
        .filter(|&i| st.candidate[i] && !kept_kinds.contains(st.kinds[i].as_str()))
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    rng.set_stream(SHUFFLE_STREAMS.saturating_add(task.stream));
    let n = kept.rules.len().min(others.len());
    for i in 0..n {
        let j = rng.random_range(i..others.len());
        others.swap(i, j);
    }
    others.truncate(n);
    others.sort_unstable();
    Ok(RuleSet::new(
        others
            .into_iter()
            .map(|i| st.set.rules[i].clone())
            .collect(),
    ))
}

/// A learning condition.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Condition {
    /// No priors.
    Uniform,
    /// Priors from the library.
    Learned,
    /// Priors from the library with its kept rules replaced by other
    /// kinds.
    Shuffled,
    /// Priors from the true-frequency library.
    True,
}

impl Condition {
    /// Its name in the table.
    pub fn name(self) -> &'static str {
        match self {
            Condition::Uniform => "uniform",
            Condition::Learned => "learned",
            Condition::Shuffled => "shuffled",
            Condition::True => "true",
        }
    }
}

/// What learning on one held-out task gave under one condition.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Outcome {
    /// Truth rules that are candidates of the demonstrations.
    pub truth: usize,
    /// Of these, learned (or implied by a learned truth rule).
    pub recalled: usize,
    /// Truth rules of a kind rare in the population.
    pub rare: usize,
    /// Of these, recalled.
    pub rare_recalled: usize,
    /// Rules learned.
    pub learned: usize,
    /// Learned rules neither in the truth nor implied by a truth rule.
    pub spurious: usize,
    /// Truth rules whose kind the priors ruled out.
    pub truth_ruled_out: usize,
    /// Statements left out (ruled-out kinds).
    pub left_out: usize,
}

impl Outcome {
    fn add(&mut self, o: &Outcome) {
        self.truth = self.truth.saturating_add(o.truth);
        self.recalled = self.recalled.saturating_add(o.recalled);
        self.rare = self.rare.saturating_add(o.rare);
        self.rare_recalled = self.rare_recalled.saturating_add(o.rare_recalled);
        self.learned = self.learned.saturating_add(o.learned);
        self.spurious = self.spurious.saturating_add(o.spurious);
        self.truth_ruled_out = self.truth_ruled_out.saturating_add(o.truth_ruled_out);
        self.left_out = self.left_out.saturating_add(o.left_out);
    }
}

/// A held-out task with what every condition needs: its truth rules that
/// are candidates of its demonstrations, each with whether its kind is
/// rare.
struct HeldOut {
    task: PopTask,
    st: Statements,
    truth: Vec<(Rule, bool)>,
}

impl HeldOut {
    fn new(
        task: PopTask,
        true_priors: &Priors,
        cfg: &PriorsBenchConfig,
    ) -> Result<Self, PriorsBenchError> {
        let st = Statements::of(&task.demos, &cfg.params, task.stream)?;
        let truth = task
            .truth
            .rules
            .iter()
            .filter_map(|r| {
                let i = st.index_of(r)?;
                let rare = is_rare(true_priors, &st.kinds[i], cfg.rare_percent);
                st.candidate[i].then(|| (r.clone(), rare))
            })
            .collect();
        Ok(HeldOut { task, st, truth })
    }

    fn is_truth(&self, scope: Scope, f: &Formula) -> bool {
        self.truth
            .iter()
            .any(|(t, _)| t.scope == scope && t.formula == *f)
    }

    /// Recall and spurious rules of `rules` (learned or held).
    fn score(&self, rules: &RuleSet, contact: crate::relations::Contact) -> Outcome {
        let held: HashSet<(Scope, &Formula)> =
            rules.rules.iter().map(|r| (r.scope, &r.formula)).collect();
        let held_truth: Vec<&Rule> = rules
            .rules
            .iter()
            .filter(|r| self.is_truth(r.scope, &r.formula))
            .collect();
        let mut o = Outcome {
            learned: rules.rules.len(),
            ..Outcome::default()
        };
        for (t, rare) in &self.truth {
            let recalled = held.contains(&(t.scope, &t.formula))
                || held_truth
                    .iter()
                    .any(|h| rule_implies((h.scope, &h.formula), (t.scope, &t.formula), contact));
            o.add(&Outcome {
                truth: 1,
                recalled: usize::from(recalled),
                rare: usize::from(*rare),
                rare_recalled: usize::from(*rare && recalled),
                ..Outcome::default()
            });
        }
        o.spurious = self.spurious(rules, contact).count();
        o
    }

    /// The rules of `rules` that are neither truth rules nor implied by
    /// one.
    fn spurious<'a>(
        &'a self,
        rules: &'a RuleSet,
        contact: crate::relations::Contact,
    ) -> impl Iterator<Item = &'a Rule> + 'a {
        rules.rules.iter().filter(move |r| {
            !self.is_truth(r.scope, &r.formula)
                && !self
                    .task
                    .truth
                    .rules
                    .iter()
                    .any(|t| rule_implies((t.scope, &t.formula), (r.scope, &r.formula), contact))
        })
    }

    /// The kinds of the spurious rules of `rules`.
    fn spurious_kinds(&self, rules: &RuleSet, contact: crate::relations::Contact) -> Vec<String> {
        self.spurious(rules, contact)
            .map(|r| {
                self.st
                    .index_of(r)
                    .map_or_else(|| "(given)".to_string(), |i| self.st.kinds[i].clone())
            })
            .collect()
    }
}

/// Whether `kind` was kept in fewer than `percent` % of the true
/// library's tasks (a kind it never saw is rare).
fn is_rare(true_priors: &Priors, kind: &str, percent: u64) -> bool {
    let kept = true_priors
        .kinds
        .binary_search_by(|e| e.kind.as_str().cmp(kind))
        .map_or(0, |i| true_priors.kinds[i].tasks_kept);
    kept.saturating_mul(100) < percent.saturating_mul(true_priors.tasks)
}

/// Learn `h`'s rules under `priors` and score them.
fn learn_outcome(
    h: &HeldOut,
    priors: Option<&Priors>,
    cfg: &PriorsBenchConfig,
) -> Result<(Outcome, Vec<String>), PriorsBenchError> {
    let learned = learn_with_priors(&h.task.demos, None, &cfg.learn_params(), priors, None, None)
        .map_err(|error| PriorsBenchError::Learn {
        stream: h.task.stream,
        error,
    })?;
    let rules = learned.rules();
    let mut o = h.score(&rules, cfg.params.contact);
    let kinds = h.spurious_kinds(&rules, cfg.params.contact);
    if let Some(used) = &learned.priors {
        let out: BTreeSet<&str> = used.ruled_out.iter().map(|r| r.name.as_str()).collect();
        o.left_out = out.len();
        o.truth_ruled_out = h
            .truth
            .iter()
            .filter(|(t, _)| out.contains(t.name.as_str()))
            .count();
    }
    Ok((o, kinds))
}

/// What the question loop gave on one held-out task.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct AskOutcome {
    /// Questions answered.
    pub questions: usize,
    /// Stopped by [`PriorsBenchConfig::max_questions`] with questions left.
    pub capped: bool,
    /// The held rules before the first question.
    pub before: Outcome,
    /// The held rules after the last one.
    pub after: Outcome,
}

/// The task's problem: its box with each class's largest count, unplaced.
pub fn problem_scene(task: &PopTask) -> Scene {
    let mut scene = task.geom.scene();
    for c in &task.classes {
        scene
            .objects
            .extend((0..c.max_count).map(|j| block(&c.class, j, c.width, c.height, None)));
    }
    scene
}

/// Whether every truth rule holds for every object of `scene` (the oracle).
fn oracle(scene: &Scene, truth: &RuleSet, contact: crate::relations::Contact) -> bool {
    evaluate(scene, truth, contact)
        .rules
        .iter()
        .all(|r| r.satisfied == r.subjects)
}

/// The question loop on `h` under `priors` with the truth as the oracle.
fn ask_outcome(
    h: &HeldOut,
    priors: Option<Arc<Priors>>,
    cfg: &PriorsBenchConfig,
) -> Result<AskOutcome, PriorsBenchError> {
    let contact = cfg.params.contact;
    let stream = h.task.stream;
    let fail = |e: crate::ask::AskError| PriorsBenchError::Ask {
        stream,
        message: e.to_string(),
    };
    let opts = AskOptions {
        learn: cfg.learn_params(),
        probe: ProbeOptions {
            contact,
            time_limit: None,
            ..ProbeOptions::default()
        },
        budget: QuestionBudget {
            wall: None,
            ..QuestionBudget::default()
        },
        priors,
        ..AskOptions::default()
    };
    let mut asker = Asker::new(
        problem_scene(&h.task),
        h.task.demos.clone(),
        None,
        Vec::new(),
        opts,
    )
    .map_err(fail)?;
    let before = h.score(asker.held(), contact);
    let mut capped = false;
    while let Some(q) = asker.next_question().map_err(fail)? {
        if asker.progress().asked >= cfg.max_questions {
            capped = true;
            break;
        }
        let accepted = oracle(&q.probe.scene, &h.task.truth, contact);
        asker.answer(&q, accepted).map_err(fail)?;
    }
    Ok(AskOutcome {
        questions: asker.progress().asked,
        capped,
        before,
        after: h.score(asker.held(), contact),
    })
}

/// One condition and library size, over the held-out tasks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// The condition.
    pub condition: Condition,
    /// Tasks in its library (0 for uniform).
    pub library: usize,
    /// Summed over the held-out tasks.
    pub total: Outcome,
    /// Per held-out task, in the order of [`PriorsBenchReport::held_out`].
    pub per_task: Vec<Outcome>,
    /// The spurious rules per kind, over the held-out tasks.
    pub spurious_kinds: BTreeMap<String, usize>,
}

/// The question loop under one condition, over the held-out tasks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AskRow {
    /// The condition.
    pub condition: Condition,
    /// Tasks in its library (0 for uniform).
    pub library: usize,
    /// Median questions per task (a capped task counts the cap).
    pub median_questions: f64,
    /// Tasks stopped by the cap.
    pub capped: usize,
    /// The held rules before the questions, summed.
    pub before: Outcome,
    /// The held rules after them, summed.
    pub after: Outcome,
    /// Per held-out task.
    pub per_task: Vec<AskOutcome>,
}

/// One task of the population, as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TaskLine {
    /// Its stream.
    pub stream: u64,
    /// `library` (with its position in the library) or `held-out`.
    pub role: String,
    /// The style in words.
    pub style: String,
    /// Demonstrations shown.
    pub demos: usize,
    /// Truth rules.
    pub truth: usize,
}

/// One of the targets, checked on this run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Target {
    /// What the target asks.
    pub target: String,
    /// Whether it holds here.
    pub holds: bool,
    /// The numbers it was decided on.
    pub measured: String,
}

/// Everything the benchmark measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PriorsBenchReport {
    /// The configuration.
    pub config: PriorsBenchConfig,
    /// The habit weights of the population.
    pub weights: HabitWeights,
    /// How often each habit was drawn, over the library and held-out
    /// classes (`band S`, `cluster`, …).
    pub habits: BTreeMap<String, usize>,
    /// The held-out tasks.
    pub held_out: Vec<TaskLine>,
    /// The library tasks, in library order.
    pub library: Vec<TaskLine>,
    /// Per condition and library size.
    pub rows: Vec<Row>,
    /// The question loop (empty with `ask` off).
    pub ask: Vec<AskRow>,
    /// The targets at the largest library size.
    pub targets: Vec<Target>,
    /// The spurious rules per kind, uniform against the largest learned
    /// library, with that library's evidence about the kind.
    pub spurious_kinds: Vec<SpuriousKind>,
}

/// Spurious rules of one kind, uniform against learned priors.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpuriousKind {
    /// The most specific kind.
    pub kind: String,
    /// Spurious rules of the kind with the uniform prior.
    pub uniform: usize,
    /// With priors from the largest library.
    pub learned: usize,
    /// Tasks of that library that kept a rule of the kind.
    pub tasks_kept: u64,
    /// Tasks of that library with a candidate of the kind.
    pub tasks: u64,
    /// The prior the library gives the kind (its own node or the nearest
    /// ancestor's).
    pub prior: f64,
}

/// The prior `p` gives the node `key`: its own, or its nearest ancestor's.
fn prior_of(p: &Priors, key: &str) -> f64 {
    let mut k = Some(key.to_string());
    while let Some(node) = k {
        if let Ok(i) = p.kinds.binary_search_by(|e| e.kind.as_str().cmp(&node)) {
            return p.kinds[i].prior;
        }
        k = priors::kind::parent_key(&node);
    }
    p.root().prior
}

/// The spurious rules per kind (most uniform ones first).
fn spurious_table(rows: &[Row], priors: Option<&Priors>) -> Vec<SpuriousKind> {
    let (Some(u), Some(l), Some(p)) = (
        rows.iter().find(|r| r.condition == Condition::Uniform),
        rows.iter().rfind(|r| r.condition == Condition::Learned),
        priors,
    ) else {
        return Vec::new();
    };
    let kinds: BTreeSet<&String> = u
        .spurious_kinds
        .keys()
        .chain(l.spurious_kinds.keys())
        .collect();
    let mut out: Vec<SpuriousKind> = kinds
        .into_iter()
        .map(|k| {
            let entry = p
                .kinds
                .binary_search_by(|e| e.kind.as_str().cmp(k))
                .ok()
                .map(|i| &p.kinds[i]);
            let prior = prior_of(p, k);
            SpuriousKind {
                kind: k.clone(),
                uniform: u.spurious_kinds.get(k).copied().unwrap_or(0),
                learned: l.spurious_kinds.get(k).copied().unwrap_or(0),
                tasks_kept: entry.map_or(0, |e| e.tasks_kept),
                tasks: entry.map_or(0, |e| e.tasks),
                prior,
            }
        })
        .collect();
    out.sort_by(|a, b| {
        (b.uniform.max(b.learned), b.uniform)
            .cmp(&(a.uniform.max(a.learned), a.uniform))
            .then_with(|| a.kind.cmp(&b.kind))
    });
    out
}

/// Progress messages (to stderr in the command line).
pub type Progress<'a> = &'a (dyn Fn(&str) + Sync);

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
fn make_tasks(
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

/// Counts of every task of a library: real (truth kept) and shuffled.
fn library_counts(
    cfg: &PriorsBenchConfig,
    tasks: &[PopTask],
    shuffled: bool,
) -> Result<Vec<TaskCounts>, PriorsBenchError> {
    let out: Vec<Result<TaskCounts, PriorsBenchError>> = tasks
        .par_iter()
        .map(|t| {
            let kept = kept_rules(t, &cfg.params)?;
            let kept = if shuffled {
                shuffled_rules(t, &kept, cfg)?
            } else {
                kept
            };
            counts_of(t, &kept, &cfg.params)
        })
        .collect();
    out.into_iter().collect()
}

fn task_line(t: &PopTask, role: String) -> TaskLine {
    TaskLine {
        stream: t.stream,
        role,
        style: t.style.clone(),
        demos: t.demos.len(),
        truth: t.truth.rules.len(),
    }
}

fn habit_name(h: &Habit) -> String {
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

/// A library task's kept rules (its `learned.rcc`): its truth rules that
/// are candidates of its demonstrations.
pub fn library_kept(task: &PopTask, cfg: &PriorsBenchConfig) -> Result<RuleSet, PriorsBenchError> {
    kept_rules(task, &cfg.params)
}

/// Run the benchmark (on the current rayon pool).
pub fn run(
    cfg: &PriorsBenchConfig,
    progress: Progress<'_>,
) -> Result<PriorsBenchReport, PriorsBenchError> {
    let (tasks, library) = population(cfg, progress)?;
    let true_jobs: Vec<(u64, Shown)> = (0..cfg.true_library as u64)
        .map(|i| (TRUE_STREAMS.saturating_add(i), Shown::Library))
        .collect();
    let true_tasks = make_tasks(cfg, &true_jobs, "true library", progress)?;
    progress("counting the libraries");
    let real = library_counts(cfg, &library, false)?;
    let shuffled = library_counts(cfg, &library, true)?;
    let true_priors = priors::combine(&library_counts(cfg, &true_tasks, false)?, &cfg.params);
    drop(true_tasks);
    let mut habits: BTreeMap<String, usize> = BTreeMap::new();
    for t in tasks.iter().chain(&library) {
        for c in &t.classes {
            let n = habits.entry(habit_name(&c.habit)).or_default();
            *n = n.saturating_add(1);
        }
    }
    let held_lines: Vec<TaskLine> = tasks
        .iter()
        .map(|t| task_line(t, "held-out".into()))
        .collect();
    let lib_lines: Vec<TaskLine> = library
        .iter()
        .enumerate()
        .map(|(i, t)| task_line(t, format!("library {}", i.saturating_add(1))))
        .collect();
    let held: Vec<HeldOut> = tasks
        .into_iter()
        .map(|t| HeldOut::new(t, &true_priors, cfg))
        .collect::<Result<_, _>>()?;
    let mut conditions: Vec<(Condition, usize, Option<Arc<Priors>>)> =
        vec![(Condition::Uniform, 0, None)];
    for &s in &cfg.library_sizes {
        let s = s.min(real.len());
        let p = |c: &[TaskCounts]| Some(Arc::new(priors::combine(&c[..s], &cfg.params)));
        conditions.push((Condition::Learned, s, p(&real)));
        conditions.push((Condition::Shuffled, s, p(&shuffled)));
    }
    let true_arc = Arc::new(true_priors);
    conditions.push((Condition::True, cfg.true_library, Some(true_arc)));
    let rows = learn_rows(cfg, &held, &conditions, progress)?;
    let asked_tasks = cfg.ask_tasks.unwrap_or(held.len()).min(held.len());
    let ask = if cfg.ask && asked_tasks > 0 {
        let largest = conditions
            .iter()
            .rfind(|c| c.0 == Condition::Learned)
            .cloned();
        let asked: Vec<_> = conditions.iter().take(1).cloned().chain(largest).collect();
        ask_rows(cfg, &held[..asked_tasks], &asked, progress)?
    } else {
        Vec::new()
    };
    let targets = targets(cfg, &rows, &ask);
    let largest = conditions
        .iter()
        .rfind(|c| c.0 == Condition::Learned)
        .and_then(|c| c.2.clone());
    let spurious_kinds = spurious_table(&rows, largest.as_deref());
    Ok(PriorsBenchReport {
        config: cfg.clone(),
        weights: HABIT_WEIGHTS,
        habits,
        held_out: held_lines,
        library: lib_lines,
        rows,
        ask,
        targets,
        spurious_kinds,
    })
}

/// Learn every held-out task under every condition.
fn learn_rows(
    cfg: &PriorsBenchConfig,
    held: &[HeldOut],
    conditions: &[(Condition, usize, Option<Arc<Priors>>)],
    progress: Progress<'_>,
) -> Result<Vec<Row>, PriorsBenchError> {
    let pairs: Vec<(usize, usize)> = (0..conditions.len())
        .flat_map(|c| (0..held.len()).map(move |t| (c, t)))
        .collect();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let outcomes: Vec<Result<(Outcome, Vec<String>), PriorsBenchError>> = pairs
        .par_iter()
        .map(|&(c, t)| {
            let o = learn_outcome(&held[t], conditions[c].2.as_deref(), cfg);
            let k = done
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed)
                .saturating_add(1);
            if k % 10 == 0 || k == pairs.len() {
                progress(&format!("learning: {k}/{} (task, condition)", pairs.len()));
            }
            o
        })
        .collect();
    let outcomes: Vec<(Outcome, Vec<String>)> = outcomes.into_iter().collect::<Result<_, _>>()?;
    Ok(conditions
        .iter()
        .zip(outcomes.chunks(held.len().max(1)))
        .map(|((condition, library, _), per_task)| {
            let mut total = Outcome::default();
            let mut spurious_kinds: BTreeMap<String, usize> = BTreeMap::new();
            for (o, kinds) in per_task {
                total.add(o);
                for k in kinds {
                    let n = spurious_kinds.entry(k.clone()).or_default();
                    *n = n.saturating_add(1);
                }
            }
            Row {
                condition: *condition,
                library: *library,
                total,
                per_task: per_task.iter().map(|p| p.0).collect(),
                spurious_kinds,
            }
        })
        .collect())
}

/// The question loop on every held-out task under each condition.
fn ask_rows(
    cfg: &PriorsBenchConfig,
    held: &[HeldOut],
    conditions: &[(Condition, usize, Option<Arc<Priors>>)],
    progress: Progress<'_>,
) -> Result<Vec<AskRow>, PriorsBenchError> {
    let pairs: Vec<(usize, usize)> = (0..conditions.len())
        .flat_map(|c| (0..held.len()).map(move |t| (c, t)))
        .collect();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let outcomes: Vec<Result<AskOutcome, PriorsBenchError>> = pairs
        .par_iter()
        .map(|&(c, t)| {
            let started = std::time::Instant::now();
            let o = ask_outcome(&held[t], conditions[c].2.clone(), cfg);
            let k = done
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed)
                .saturating_add(1);
            let asked = o.as_ref().map_or(0, |o| o.questions);
            progress(&format!(
                "asking: {k}/{} — task {} {}: {asked} questions, {:.1} s",
                pairs.len(),
                held[t].task.stream,
                conditions[c].0.name(),
                started.elapsed().as_secs_f64()
            ));
            o
        })
        .collect();
    let outcomes: Vec<AskOutcome> = outcomes.into_iter().collect::<Result<_, _>>()?;
    Ok(conditions
        .iter()
        .zip(outcomes.chunks(held.len().max(1)))
        .map(|((condition, library, _), per_task)| {
            let mut before = Outcome::default();
            let mut after = Outcome::default();
            for o in per_task {
                before.add(&o.before);
                after.add(&o.after);
            }
            let qs: Vec<f64> = per_task.iter().map(|o| o.questions as f64).collect();
            AskRow {
                condition: *condition,
                library: *library,
                median_questions: super::thesis::median(&qs),
                capped: per_task.iter().filter(|o| o.capped).count(),
                before,
                after,
                per_task: per_task.to_vec(),
            }
        })
        .collect())
}

/// The targets, at the largest library size.
fn targets(cfg: &PriorsBenchConfig, rows: &[Row], ask: &[AskRow]) -> Vec<Target> {
    let largest = cfg.largest();
    let find = |c: Condition| {
        rows.iter()
            .rfind(|r| r.condition == c && (c == Condition::Uniform || r.library <= largest))
    };
    let (Some(u), Some(l), Some(s)) = (
        find(Condition::Uniform),
        find(Condition::Learned),
        find(Condition::Shuffled),
    ) else {
        return Vec::new();
    };
    let (u, l, s) = (&u.total, &l.total, &s.total);
    let n = rows
        .iter()
        .rfind(|r| r.condition == Condition::Learned)
        .map_or(0, |r| r.library);
    let mut out = vec![
        Target {
            target: format!("spurious rules with priors from {n} tasks ≤ half of uniform's"),
            holds: l.spurious.saturating_mul(2) <= u.spurious,
            measured: format!("{} vs {}", l.spurious, u.spurious),
        },
        Target {
            target: "recall not lower than uniform's".into(),
            holds: l.recalled >= u.recalled,
            measured: format!("{}/{} vs {}/{}", l.recalled, l.truth, u.recalled, u.truth),
        },
        Target {
            target: "rare true rules kept (rare recall not lower than uniform's)".into(),
            holds: l.rare_recalled >= u.rare_recalled,
            measured: format!(
                "{}/{} vs {}/{}",
                l.rare_recalled, l.rare, u.rare_recalled, u.rare
            ),
        },
        Target {
            target: "the shuffled control does worse than the real library (more spurious or lower recall, better on neither)".into(),
            holds: (s.spurious > l.spurious || s.recalled < l.recalled)
                && s.spurious >= l.spurious
                && s.recalled <= l.recalled,
            measured: format!(
                "spurious {} vs {}, recall {}/{} vs {}/{}",
                s.spurious, l.spurious, s.recalled, s.truth, l.recalled, l.truth
            ),
        },
    ];
    if let (Some(au), Some(al)) = (
        ask.iter().find(|a| a.condition == Condition::Uniform),
        ask.iter().find(|a| a.condition == Condition::Learned),
    ) {
        out.push(Target {
            target: "fewer questions with priors (median per task)".into(),
            holds: al.median_questions < au.median_questions,
            measured: format!("{} vs {}", al.median_questions, au.median_questions),
        });
    }
    out
}

mod markdown;
pub use markdown::table_markdown;
