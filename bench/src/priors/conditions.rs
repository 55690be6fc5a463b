//! The priors a held-out task is learned under: uniform, learned from the
//! library, the shuffled control and the true frequencies; a library task's
//! kept rules and their counts.

use super::population::PopTask;
use super::{PriorsBenchConfig, PriorsBenchError};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use rccpack::infer::templates;
use rccpack::priors::{Kind, PriorParams, TaskCounts};
use rccpack::rules::{print_rules, Rule, RuleSet};
use rccpack::scene::{scenes_to_json, Scene};
use rccpack::{infer, priors};
use serde::Serialize;
use std::collections::BTreeSet;

/// Streams of the shuffled control's draws: this plus the task's stream.
const SHUFFLE_STREAMS: u64 = 1 << 40;

/// The generated statements of a task's demonstrations with, per
/// statement, its most specific kind and whether it is a candidate.
pub(super) struct Statements {
    /// The generated statements.
    pub(super) set: RuleSet,
    /// Per statement, its most specific kind.
    pub(super) kinds: Vec<String>,
    /// Per statement, whether it is a candidate.
    pub(super) candidate: Vec<bool>,
}

impl Statements {
    /// The statements of `demos` (task `stream`) under `params`.
    pub(super) fn of(
        demos: &[Scene],
        params: &PriorParams,
        stream: u64,
    ) -> Result<Self, PriorsBenchError> {
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
    pub(super) fn index_of(&self, rule: &Rule) -> Option<usize> {
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

/// Counts of every task of a library: real (truth kept) and shuffled.
pub(super) fn library_counts(
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

/// A library task's kept rules (its `learned.rcc`): its truth rules that
/// are candidates of its demonstrations.
pub fn library_kept(task: &PopTask, cfg: &PriorsBenchConfig) -> Result<RuleSet, PriorsBenchError> {
    kept_rules(task, &cfg.params)
}
