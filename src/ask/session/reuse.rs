//! What a session reuses between checks (with
//! [`AskOptions::reuse`](super::AskOptions::reuse)): a pool of layouts of
//! the problem that answers later checks through the evaluator, and the
//! proofs found so far.

use super::Asker;
use crate::ask::probe::Probe;
use crate::infer::english::rule_implies;
use crate::rules::RuleSet;
use crate::scene::Scene;
use std::collections::BTreeSet;

/// With `reuse`, a check first gets this many search nodes on the
/// checker of the scan, which has learned from every earlier solve; when
/// they do not decide it, a fresh checker holding only the premises and
/// the rule (a smaller model) gets the full budget
/// ([`ProbeOptions::check_nodes`](crate::ask::ProbeOptions::check_nodes)).
/// The long-lived engine can slow down by orders of magnitude on a proof
/// that a fresh one settles in a few hundred nodes, while building one
/// costs 10–30 ms. Node counts, so still deterministic.
pub(super) const FIRST_TRY_NODES: u64 = 1_000;

/// At most this many layouts are kept in the pool (a pool check costs a
/// look at every layout's row).
pub(super) const MAX_POOL: usize = 4096;

/// Layouts of the problem (see [`Asker::settled`]).
#[derive(Debug, Clone, Default)]
pub(super) struct Pool {
    pub(super) scenes: Vec<Scene>,
    /// Per layout, per held rule: whether it holds (evaluated for the
    /// current held rules; cleared when they change).
    pub(super) holds: Vec<Vec<bool>>,
}

impl Asker {
    /// A pool layout that breaks rule `k` and keeps every held rule but
    /// those in `removed`, as a probe.
    pub(super) fn pool_probe(&self, k: usize, removed: &[bool]) -> Option<Probe> {
        let n = self.held.rules.len();
        let premise = |j: usize| j != k && !removed.get(j).copied().unwrap_or(false);
        let pool = self.pool_holds();
        let at = pool
            .holds
            .iter()
            .position(|h| !h[k] && (0..n).filter(|&j| premise(j)).all(|j| h[j]))?;
        let scene = pool.scenes[at].clone();
        drop(pool);
        Some(self.probe_of(&[k], scene))
    }

    /// `scene` (a layout of the problem) as the probe of the held rules
    /// `targets` (`targets[0]` names it): the objects breaking any of them,
    /// its resemblance cost.
    pub(super) fn probe_of(&self, targets: &[usize], scene: Scene) -> Probe {
        let asked = RuleSet::new(
            targets
                .iter()
                .map(|&j| self.held.rules[j].clone())
                .collect(),
        );
        let mut broken: Vec<String> = Vec::new();
        for r in crate::eval::evaluate(&scene, &asked, self.opts.probe.contact).rules {
            for v in r.violators {
                if !broken.contains(&v) {
                    broken.push(v);
                }
            }
        }
        Probe {
            rule: self.held.rules[targets[0]].name.clone(),
            cost: self
                .like
                .as_ref()
                .map_or(0, |l| l.cost(&self.problem, &scene)),
            scene,
            broken,
            time_ms: 0.0,
            edit: None,
        }
    }

    /// The key of held rule `k` that stays the same when learning is
    /// redone: its statement text.
    pub(super) fn text(&self, k: usize) -> String {
        let r = &self.held.rules[k];
        crate::infer::statement_text(r.scope, &r.formula)
    }

    /// Whether each held rule holds in each pool layout (rows in pool
    /// order), brought up to date with the pool.
    pub(super) fn pool_holds(&self) -> std::cell::Ref<'_, Pool> {
        {
            let mut pool = self.pool.borrow_mut();
            let pool = &mut *pool;
            while pool.holds.len() < pool.scenes.len() {
                let scene = &pool.scenes[pool.holds.len()];
                let ev = crate::eval::evaluate(scene, &self.held, self.opts.probe.contact);
                pool.holds
                    .push(ev.rules.iter().map(|r| r.satisfied == r.subjects).collect());
            }
        }
        self.pool.borrow()
    }

    /// Keep a layout of the problem that a solve found (with `reuse`).
    pub(super) fn remember(&self, scene: Scene) {
        if self.opts.reuse {
            let mut pool = self.pool.borrow_mut();
            if pool.scenes.len() < MAX_POOL && !pool.scenes.contains(&scene) {
                pool.scenes.push(scene);
            }
        }
    }

    /// What is already known about "does rule `k` have a probe when the
    /// rules in `removed` may break with it" without a solve (with
    /// `reuse`): `Some(true)` when a pool layout breaks `k` and keeps every
    /// premise (the other rules not removed) — the evaluator decides, so
    /// the layout is a probe; `Some(false)` when a proof of the session
    /// showed that fewer premises imply `k`, or one premise alone implies
    /// it (syntactically or proven).
    pub(super) fn settled(&self, k: usize, removed: &[bool]) -> Option<bool> {
        if !self.opts.reuse {
            return None;
        }
        let n = self.held.rules.len();
        let premise = |j: usize| j != k && !removed.get(j).copied().unwrap_or(false);
        let pool = self.pool_holds();
        if pool
            .holds
            .iter()
            .any(|h| !h[k] && (0..n).filter(|&j| premise(j)).all(|j| h[j]))
        {
            return Some(true);
        }
        drop(pool);
        let text = self.text(k);
        let premises: BTreeSet<String> = (0..n)
            .filter(|&j| premise(j))
            .map(|j| self.text(j))
            .collect();
        if self
            .proofs
            .borrow()
            .iter()
            .any(|(r, by)| *r == text && by.is_subset(&premises))
        {
            return Some(false);
        }
        let rk = &self.held.rules[k];
        let alone = self.alone.borrow();
        let implied = (0..n).filter(|&j| premise(j)).any(|j| {
            let rj = &self.held.rules[j];
            alone.get(&(self.text(j), text.clone())) == Some(&Some(true))
                || rule_implies(
                    (rj.scope, &rj.formula),
                    (rk.scope, &rk.formula),
                    self.opts.learn.contact,
                )
        });
        implied.then_some(false)
    }
}
