//! The report of `bench priors`: one row per (task, condition), the
//! question rows, the per-task lines, the targets and the spurious kinds.

use super::conditions::Condition;
use super::outcomes::{AskOutcome, Outcome};
use super::population::{HabitWeights, PopTask};
use super::PriorsBenchConfig;
use rccpack::priors;
use rccpack::priors::Priors;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// Rows of the spurious-kind table in the markdown.
pub(super) const SPURIOUS_SHOWN: usize = 12;

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
pub(super) fn spurious_table(rows: &[Row], priors: Option<&Priors>) -> Vec<SpuriousKind> {
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

pub(super) fn task_line(t: &PopTask, role: String) -> TaskLine {
    TaskLine {
        stream: t.stream,
        role,
        style: t.style.clone(),
        demos: t.demos.len(),
        truth: t.truth.rules.len(),
    }
}

/// The targets, at the largest library size.
pub(super) fn targets(cfg: &PriorsBenchConfig, rows: &[Row], ask: &[AskRow]) -> Vec<Target> {
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
