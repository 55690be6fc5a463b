//! The checks a scan makes: does a rule have a probe when some rules may
//! break with it, does one rule alone imply another, and the probe
//! searches themselves (on the problem, or as an edit of a demonstration).

use super::reuse::FIRST_TRY_NODES;
use super::{AskError, Asker, Known};
use crate::ask::checker::{Checked, ProbeChecker};
use crate::ask::edit::EditSearch;
use crate::ask::probe::{search_probe, Probe, ProbeOptions, ProbeOutcome};
use crate::infer::english::rule_implies;
use crate::rules::RuleSet;
use std::collections::BTreeSet;

/// The classes a rule is about (subject and target classes), `None` when it
/// is about any object (`*`) or a landmark.
fn classes(r: &crate::rules::Rule) -> Option<BTreeSet<&str>> {
    let mut out = BTreeSet::new();
    if let Some((shape, _)) = r.formula.shape() {
        out.insert(shape.class.as_str());
    }
    for a in r.formula.atoms() {
        out.insert(a.subject.as_str());
        match &a.target {
            crate::rules::Target::Class(c) => {
                out.insert(c.as_str());
            }
            crate::rules::Target::Any | crate::rules::Target::Landmark(_) => return None,
        }
    }
    Some(out)
}

/// Whether two rules may constrain one another: they share a class, or one
/// is about any object.
pub(super) fn related(a: &crate::rules::Rule, b: &crate::rules::Rule) -> bool {
    match (classes(a), classes(b)) {
        (Some(x), Some(y)) => !x.is_disjoint(&y),
        _ => true,
    }
}

impl Asker {
    /// Whether another held rule implies rule `k` on every scene
    /// (syntactically) and is not implied by it.
    pub(super) fn syntactically_implied(&self, k: usize) -> bool {
        let r = &self.held.rules[k];
        let contact = self.opts.learn.contact;
        let implies = |a: &crate::rules::Rule, b: &crate::rules::Rule| {
            rule_implies((a.scope, &a.formula), (b.scope, &b.formula), contact)
        };
        self.held
            .rules
            .iter()
            .enumerate()
            .any(|(j, h)| j != k && implies(h, r) && !implies(r, h))
    }

    pub(super) fn checker<'c>(
        &self,
        checker: &'c mut Option<ProbeChecker>,
    ) -> Result<&'c mut ProbeChecker, AskError> {
        Ok(match checker {
            Some(c) => c,
            None => {
                let t = std::time::Instant::now();
                let c = ProbeChecker::new(&self.problem, &self.held, &self.opts.probe)?;
                self.weight.set(c.weight());
                log::debug!(
                    "ask: checker built in {:.1} ms (weight {})",
                    t.elapsed().as_secs_f64() * 1e3,
                    c.weight()
                );
                checker.insert(c)
            }
        })
    }

    /// The options of a probe search under the question's budget: the
    /// demonstrations to resemble, the nodes the meter grants now and its
    /// deadline; `None` when the budget is spent.
    pub(super) fn probe_search_options(&self) -> Option<ProbeOptions> {
        let mut opts = ProbeOptions {
            like: self.like.clone(),
            ..self.opts.probe.clone()
        };
        let meter = self.meter.borrow();
        let want = opts.stop.nodes().unwrap_or(u64::MAX);
        let grant = meter.grant(want, self.weight.get())?;
        opts.stop = opts.stop.nodes_at_most(Some(grant)).by(meter.deadline());
        Some(opts)
    }

    /// The probe for rule `k` keeping every held rule but `k` and those in
    /// `equivalent`.
    pub(super) fn search(&self, k: usize, equivalent: &[bool]) -> Result<Known, AskError> {
        let Some(opts) = self.probe_search_options() else {
            return Ok(Known::Unknown);
        };
        let keep: Vec<usize> = (0..self.held.rules.len())
            .filter(|&j| j == k || !equivalent[j])
            .collect();
        let set = RuleSet::new(keep.iter().map(|&j| self.held.rules[j].clone()).collect());
        let at = keep.iter().position(|&j| j == k).expect("kept");
        let t = std::time::Instant::now();
        let (found, nodes) = search_probe(&self.problem, &set, at, &opts)?;
        self.meter.borrow_mut().spend(nodes, self.weight.get());
        log::debug!(
            "ask: probe search {} ({} may break): {} in {:.1} ms",
            self.held.rules[k].name,
            self.held.rules.len() - keep.len(),
            match &found {
                ProbeOutcome::Probe(_) => "probe",
                ProbeOutcome::Implied { .. } => "implied",
                ProbeOutcome::Unknown => "unknown",
            },
            t.elapsed().as_secs_f64() * 1e3
        );
        Ok(match found {
            ProbeOutcome::Probe(p) => {
                self.remember(p.scene.clone());
                Known::Probe(p)
            }
            ProbeOutcome::Implied { .. } => Known::Implied,
            // A layout a check found is a probe too (not the most like
            // the demonstrations, but the budget found no better).
            ProbeOutcome::Unknown => match self.pool_probe(k, equivalent) {
                Some(p) => Known::Probe(p),
                None => Known::Unknown,
            },
        })
    }

    /// [`ProbeChecker::has_probe`], making a new checker after a limit.
    pub(super) fn check(
        &self,
        checker: &mut Option<ProbeChecker>,
        k: usize,
        removed: &[bool],
    ) -> Result<Option<bool>, AskError> {
        let key = self.check_key(k, removed);
        if let Some(v) = self.known_check(&key, k, removed) {
            return Ok(Some(v));
        }
        let Some(checked) = self.solve_check(checker, k, removed, &key)? else {
            // The question's budget is spent: undecided, not remembered.
            return Ok(None);
        };
        Ok(self.record_check(checker, key, k, removed, checked))
    }

    /// The memo key of a check: the rule's name and the names of the rules
    /// allowed to break with it.
    fn check_key(&self, k: usize, removed: &[bool]) -> (String, Vec<String>) {
        (
            self.held.rules[k].name.clone(),
            (0..self.held.rules.len())
                .filter(|&j| removed.get(j).copied().unwrap_or(false))
                .map(|j| self.held.rules[j].name.clone())
                .collect(),
        )
    }

    /// A check answered without a solve: decided before, or settled by
    /// what the session reuses (then remembered as decided).
    fn known_check(&self, key: &(String, Vec<String>), k: usize, removed: &[bool]) -> Option<bool> {
        if let Some(&v) = self.checks.borrow().get(key) {
            return Some(v);
        }
        let v = self.settled(k, removed)?;
        log::debug!(
            "ask: check {} ({} may break): {v} without a solve",
            key.0,
            key.1.len()
        );
        self.checks.borrow_mut().insert(key.clone(), v);
        Some(v)
    }

    /// The solve of a check under the question's budget: with `reuse` a
    /// short first try on the checker of the scan, then the full budget on
    /// a fresh one of the premises and the rule only (see
    /// `FIRST_TRY_NODES`). `None` when the budget is spent.
    fn solve_check(
        &self,
        checker: &mut Option<ProbeChecker>,
        k: usize,
        removed: &[bool],
        key: &(String, Vec<String>),
    ) -> Result<Option<Checked>, AskError> {
        let t = std::time::Instant::now();
        let c = self.checker(checker)?;
        let Some((want, grant, deadline)) = self.check_grant(c) else {
            return Ok(None);
        };
        let first = if self.opts.reuse {
            FIRST_TRY_NODES.min(grant)
        } else {
            grant
        };
        c.set_deadline(deadline);
        let before = c.nodes();
        let mut checked = c.has_probe_within(k, removed, Some(first));
        let w = c.weight();
        self.meter.borrow_mut().spend(c.nodes() - before, w);
        let more = self.meter.borrow().grant(want, w);
        if let (true, Checked::Stopped, Some(more)) = (self.opts.reuse, &checked, more) {
            log::debug!(
                "ask: check {} stopped at the first try after {:.1} ms: a fresh checker",
                key.0,
                t.elapsed().as_secs_f64() * 1e3
            );
            // Later checks must not depend on how far this one got.
            *checker = None;
            checked = self.fresh_check(k, removed, deadline, more)?;
        }
        log::debug!(
            "ask: check {} ({} may break): {} in {:.1} ms",
            key.0,
            key.1.len(),
            checked.name(),
            t.elapsed().as_secs_f64() * 1e3
        );
        Ok(Some(checked))
    }

    /// The nodes a check on `c` may use: what it wants (the check budget,
    /// at most half of what is left: an undecided check leaves the other
    /// half to the demonstrations' edits and the probe search), what the
    /// question's meter grants now, and the meter's deadline; `None` when
    /// the question's budget is spent.
    pub(super) fn check_grant(
        &self,
        c: &ProbeChecker,
    ) -> Option<(u64, u64, Option<std::time::Instant>)> {
        let want = self
            .opts
            .probe
            .check_nodes
            .unwrap_or(u64::MAX)
            .min(self.meter.borrow().half_nodes(c.weight()));
        let deadline = self.meter.borrow().deadline();
        let grant = self.meter.borrow().grant(want, c.weight())?;
        Some((want, grant, deadline))
    }

    /// A check on a fresh checker of the premises and the rule only (a
    /// smaller model), with `nodes` nodes.
    fn fresh_check(
        &self,
        k: usize,
        removed: &[bool],
        deadline: Option<std::time::Instant>,
        nodes: u64,
    ) -> Result<Checked, AskError> {
        let keep: Vec<usize> = (0..self.held.rules.len())
            .filter(|&j| j == k || !removed.get(j).copied().unwrap_or(false))
            .collect();
        let set = RuleSet::new(keep.iter().map(|&j| self.held.rules[j].clone()).collect());
        let at = keep.iter().position(|&j| j == k).expect("kept");
        let mut fresh = ProbeChecker::new(&self.problem, &set, &self.opts.probe)?;
        fresh.set_deadline(deadline);
        let checked = fresh.has_probe_within(at, &[], Some(nodes));
        self.meter.borrow_mut().spend(fresh.nodes(), fresh.weight());
        Ok(checked)
    }

    /// What a solved check decides, remembered: a witness joins the pool, a
    /// proof is kept for larger premise sets; a stopped search decides
    /// nothing and drops the checker, so that later checks do not depend on
    /// how far this one got.
    fn record_check(
        &self,
        checker: &mut Option<ProbeChecker>,
        key: (String, Vec<String>),
        k: usize,
        removed: &[bool],
        checked: Checked,
    ) -> Option<bool> {
        let verdict = match checked {
            Checked::Witness(scene) => {
                self.remember(scene);
                Some(true)
            }
            Checked::Proven => {
                if self.opts.reuse {
                    let premises = (0..self.held.rules.len())
                        .filter(|&j| j != k && !removed.get(j).copied().unwrap_or(false))
                        .map(|j| self.text(j))
                        .collect();
                    self.proofs.borrow_mut().push((self.text(k), premises));
                }
                Some(false)
            }
            Checked::Stopped => {
                *checker = None;
                None
            }
        };
        if let Some(v) = verdict {
            self.checks.borrow_mut().insert(key, v);
        }
        verdict
    }

    /// Whether held rule `a` alone implies held rule `b` on this problem
    /// (syntactically, or proven by the checker; a limit counts as no).
    /// Memoised while the held rules stay the same (with `reuse`: decided
    /// answers for the whole session, keyed by statement text).
    pub(super) fn alone_implies(
        &self,
        checker: &mut Option<ProbeChecker>,
        a: usize,
        b: usize,
    ) -> Result<bool, AskError> {
        let key = (self.text(a), self.text(b));
        if let Some(&v) = self.alone.borrow().get(&key) {
            return Ok(v == Some(true));
        }
        let (ra, rb) = (&self.held.rules[a], &self.held.rules[b]);
        let v = if !related(ra, rb) {
            // No class in common: neither says anything about the other's
            // objects (a rule impossible or certain on its own would be the
            // exception; missing it only costs a question).
            Some(false)
        } else if rule_implies(
            (ra.scope, &ra.formula),
            (rb.scope, &rb.formula),
            self.opts.learn.contact,
        ) {
            Some(true)
        } else if self.opts.reuse && self.pool_holds().holds.iter().any(|h| h[a] && !h[b]) {
            // A layout keeping `a` and breaking `b`.
            Some(false)
        } else {
            let want = self.opts.probe.check_nodes.unwrap_or(u64::MAX);
            let deadline = self.meter.borrow().deadline();
            let c = self.checker(checker)?;
            let Some(grant) = self.meter.borrow().grant(want, c.weight()) else {
                // The question's budget is spent: "no", not remembered.
                return Ok(false);
            };
            c.set_deadline(deadline);
            let t = std::time::Instant::now();
            let before = c.nodes();
            let checked = c.implies_within(a, b, Some(grant));
            self.meter
                .borrow_mut()
                .spend(c.nodes() - before, c.weight());
            log::debug!(
                "ask: implies {} -> {}: {} in {:.1} ms",
                ra.name,
                rb.name,
                checked.name(),
                t.elapsed().as_secs_f64() * 1e3
            );
            match checked {
                Checked::Witness(scene) => {
                    self.remember(scene);
                    Some(false)
                }
                Checked::Proven => Some(true),
                Checked::Stopped => {
                    // A stopped search: a fresh engine for the next checks.
                    *checker = None;
                    None
                }
            }
        };
        self.alone.borrow_mut().insert(key, v);
        Ok(v == Some(true))
    }

    /// A probe for rule `k` that is a demonstration with a few objects
    /// moved, within the question's budget.
    pub(super) fn edit_probe(
        &self,
        k: usize,
        checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Option<Probe> {
        self.edit_probe_of(&[k], checkers)
    }

    /// A probe breaking every held rule of `targets` (and keeping the
    /// others) that is a demonstration with a few objects moved, within
    /// the question's budget.
    pub(super) fn edit_probe_of(
        &self,
        targets: &[usize],
        checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Option<Probe> {
        if !self.opts.edits {
            return None;
        }
        let search = EditSearch {
            demos: &self.demos,
            like: self.like.as_ref(),
            contact: self.opts.probe.contact,
            seed: self.opts.probe.seed,
            solve_time: self.opts.probe.solve_time,
            stop: self.opts.probe.stop.clone(),
            turnable: (self.problem.objects.iter())
                .filter(|o| o.turnable && o.is_oblong())
                .map(|o| (o.class.clone(), o.width, o.height))
                .collect(),
        };
        let t = std::time::Instant::now();
        let found = search.find_group(&self.held, targets, checkers, &mut self.meter.borrow_mut());
        log::debug!(
            "ask: edit search {}{}: {} in {:.1} ms",
            self.held.rules[targets[0]].name,
            if targets.len() > 1 {
                format!(" and {} more", targets.len() - 1)
            } else {
                String::new()
            },
            if found.is_some() { "probe" } else { "none" },
            t.elapsed().as_secs_f64() * 1e3
        );
        found
    }
}
