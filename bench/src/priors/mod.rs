//! Priors learned across tasks, measured on a population of demonstrators
//! (`rccpack-bench priors`).
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
//! (default 40). Its **truth** is what [`learn`](rccpack::infer::learn) keeps from all of them
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
//!   [`rccpack::priors::task_counts`] and [`rccpack::priors::combine`] (the
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
//!   fewer) — the question loop ([`rccpack::ask::Asker`]) on the task's
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

mod conditions;
mod outcomes;
mod population;
mod report;

pub use markdown::table_markdown;
use rayon::prelude::*;
use rccpack::infer::{InferError, LearnParams};
use rccpack::priors;
use rccpack::priors::{PriorParams, Priors, TaskCounts};
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::Arc;

use conditions::library_counts;
pub use conditions::{library_kept, Condition};
use outcomes::{ask_outcome, learn_outcome, HeldOut};
pub use outcomes::{problem_scene, AskOutcome, Outcome};
pub use population::{
    draw_population_habits, population, population_task, HabitWeights, PopTask, Shown, CLASS_POOL,
    HABIT_WEIGHTS,
};
use population::{habit_name, make_tasks, TRIES, TRUE_STREAMS};
use report::{spurious_table, targets, task_line, SPURIOUS_SHOWN};
pub use report::{AskRow, PriorsBenchReport, Row, SpuriousKind, Target, TaskLine};

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
    /// Group questions in the loop ([`rccpack::ask::AskOptions::groups`], on
    /// by default).
    pub ask_groups: bool,
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
            ask_groups: true,
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

/// Progress messages (to stderr in the command line).
pub type Progress<'a> = &'a (dyn Fn(&str) + Sync);

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

mod markdown;
