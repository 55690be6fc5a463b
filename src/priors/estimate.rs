//! Counting a task's candidates and kept rules per kind, and the
//! estimator: empirical-Bayes shrinkage down the kind hierarchy, and
//! ruling kinds out.
//!
//! # The estimator
//!
//! Every node of the hierarchy (see [`super::kind`]) sums, over the
//! library, the candidates of its kinds (`c`), how many of them the person
//! kept (`k`) and how many of those were confirmed (`# confirmed`, `f`);
//! a confirmed rule counts twice (`c_w = c + f`, `k_w = k + f`). Its prior
//! (the probability that a candidate of the kind is a rule) is
//!
//! ```text
//! prior(node) = (k_w + m · prior(parent)) / (c_w + m),   prior(parent of root) = 1/2
//! ```
//!
//! a beta-binomial posterior mean whose prior mean is the parent's
//! estimate (the library's own pooled rate: empirical Bayes) and whose
//! strength `m` ([`PriorParams::strength`], default 4 pseudo-candidates)
//! says how many candidates a kind needs before its own rate outweighs
//! its parent's. It is strictly inside (0, 1) for any counts. A kind the
//! library never saw gets its nearest ancestor's prior.
//!
//! A node is *ruled out* when it was a candidate in at least
//! [`PriorParams::rule_out_after`] tasks (default 10) and never kept; a
//! node below a ruled-out node is ruled out too. A kind kept even once is
//! never ruled out (its ancestors were kept as well).

use super::kind::{self, Kind};
use super::Priors;
pub use crate::infer::priors::{fnv1a, PriorParams, FNV_BASIS};
use crate::infer::{self, templates, InferError};
use crate::rules::RuleSet;
use crate::scene::Scene;
use std::collections::{BTreeMap, HashSet};

/// One kind's evidence in one task (or summed over tasks).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Count {
    /// Candidates of the kind (statements every demonstration satisfies).
    pub candidates: u64,
    /// Of these, rules the person kept (in `learned.rcc`).
    pub kept: u64,
    /// Of these, rules marked `# confirmed`.
    pub confirmed: u64,
}

/// What one task contributes: per most specific kind key, its [`Count`],
/// and a hash of the task's inputs.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct TaskCounts {
    /// FNV-1a 64 of the task's input texts ([`input_hash`]).
    pub hash: u64,
    /// Per kind key (only kinds with at least one candidate).
    pub kinds: BTreeMap<String, Count>,
}

/// The hash of one task's inputs: each part's length and bytes, in order
/// (`demos.json`, `learned.rcc`).
pub fn input_hash(parts: &[&str]) -> u64 {
    let mut h = FNV_BASIS;
    for p in parts {
        h = fnv1a(h, &(p.len() as u64).to_le_bytes());
        h = fnv1a(h, p.as_bytes());
    }
    h
}

/// Count one task: its generated statements (`params.templates`), which of
/// them are candidates (every demonstration satisfies them, as `learn`
/// finds them), and which candidates are among `kept` (same scope and
/// formula; `confirmed`: names of kept rules marked `# confirmed`).
pub fn task_counts(
    demos: &[Scene],
    kept: &RuleSet,
    confirmed: &[String],
    params: &PriorParams,
    hash: u64,
) -> Result<TaskCounts, InferError> {
    infer::check_demos(demos)?;
    let estimate = templates::estimate_set(demos, params.templates);
    if estimate > crate::limits::MAX_STATEMENTS {
        return Err(InferError::TooManyStatements {
            statements: estimate,
            classes: templates::demo_classes(demos).len(),
        });
    }
    let (set, origins) = templates::generate_with_origins(demos, params.templates);
    let flags = infer::candidate_flags(demos, &set, params.contact)?;
    let classes = templates::demo_classes(demos);
    let movable = |c: &str| classes.iter().any(|(n, m)| n == c && *m);
    let kept_set: HashSet<_> = kept.rules.iter().map(|r| (r.scope, &r.formula)).collect();
    let confirmed_set: HashSet<_> = kept
        .rules
        .iter()
        .filter(|r| confirmed.contains(&r.name))
        .map(|r| (r.scope, &r.formula))
        .collect();
    let mut kinds: BTreeMap<String, Count> = BTreeMap::new();
    for ((rule, origin), cand) in set.rules.iter().zip(&origins).zip(flags) {
        if !cand {
            continue;
        }
        let c = kinds.entry(Kind::of(origin, movable).key()).or_default();
        c.candidates += 1;
        let key = (rule.scope, &rule.formula);
        if kept_set.contains(&key) {
            c.kept += 1;
            if confirmed_set.contains(&key) {
                c.confirmed += 1;
            }
        }
    }
    Ok(TaskCounts { hash, kinds })
}

/// A node's sums over the library.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NodeCounts {
    /// Summed [`Count`].
    pub count: Count,
    /// Tasks with at least one candidate of the node.
    pub tasks: u64,
    /// Tasks that kept at least one of them.
    pub tasks_kept: u64,
}

/// Sum tasks into the nodes of the hierarchy (every ancestor of every
/// counted kind, the root always). Order-independent: integer sums.
pub fn sum_nodes(tasks: &[TaskCounts]) -> BTreeMap<String, NodeCounts> {
    let mut nodes: BTreeMap<String, NodeCounts> = BTreeMap::new();
    nodes.insert(kind::ROOT.to_string(), NodeCounts::default());
    for t in tasks {
        // Per task first, so that `tasks` counts the task once per node.
        let mut mine: BTreeMap<String, Count> = BTreeMap::new();
        for (key, c) in &t.kinds {
            let mut k = Some(key.clone());
            while let Some(node) = k {
                let e = mine.entry(node.clone()).or_default();
                e.candidates = e.candidates.saturating_add(c.candidates);
                e.kept = e.kept.saturating_add(c.kept);
                e.confirmed = e.confirmed.saturating_add(c.confirmed);
                k = kind::parent_key(&node);
            }
        }
        for (node, c) in mine {
            let e = nodes.entry(node).or_default();
            e.count.candidates = e.count.candidates.saturating_add(c.candidates);
            e.count.kept = e.count.kept.saturating_add(c.kept);
            e.count.confirmed = e.count.confirmed.saturating_add(c.confirmed);
            if c.candidates > 0 {
                e.tasks = e.tasks.saturating_add(1);
            }
            if c.kept > 0 {
                e.tasks_kept = e.tasks_kept.saturating_add(1);
            }
        }
    }
    nodes
}

/// The estimate of every node: `(prior, ruled_out)`, parents before
/// children (keys sort so: a parent's key is a prefix of its children's).
pub fn estimate(
    nodes: &BTreeMap<String, NodeCounts>,
    strength: u32,
    rule_out_after: u64,
) -> BTreeMap<String, (f64, bool)> {
    let m = f64::from(strength.max(1));
    let mut out: BTreeMap<String, (f64, bool)> = BTreeMap::new();
    let mut keys: Vec<&String> = nodes.keys().collect();
    keys.sort_by_key(|k| {
        (
            k.matches('/').count() + usize::from(k.as_str() != kind::ROOT),
            *k,
        )
    });
    for key in keys {
        let n = &nodes[key];
        let (parent_prior, parent_out) = kind::parent_key(key)
            .and_then(|p| out.get(&p).copied())
            .unwrap_or((0.5, false));
        let kw = n.count.kept.saturating_add(n.count.confirmed) as f64;
        let cw = n.count.candidates.saturating_add(n.count.confirmed) as f64;
        let prior = (kw + m * parent_prior) / (cw + m);
        // The root is never ruled out: a library that kept nothing says
        // nothing about which kinds are rules.
        let own_out = key != kind::ROOT
            && rule_out_after > 0
            && n.tasks >= rule_out_after
            && n.count.kept == 0;
        out.insert(key.clone(), (prior, parent_out || own_out));
    }
    out
}

/// Combine the tasks of a library into [`Priors`] (the order of `tasks`
/// does not matter).
pub fn combine(tasks: &[TaskCounts], params: &PriorParams) -> Priors {
    let nodes = sum_nodes(tasks);
    let mut hashes: Vec<u64> = tasks.iter().map(|t| t.hash).collect();
    hashes.sort_unstable();
    let mut inputs = FNV_BASIS;
    for h in hashes {
        inputs = fnv1a(inputs, &h.to_le_bytes());
    }
    Priors::from_nodes(params, tasks.len() as u64, inputs, nodes)
}
