//! Group questions (docs/guide.md#questions): one probe that breaks several
//! held rules that are likely habits, and the binary search that follows a
//! "not acceptable".
//!
//! # Background
//!
//! Most doubtful rules are habits, and a habit is dropped by one
//! "acceptable". Constraint acquisition (QuAcq) asks about an example that
//! breaks many candidate constraints at once, and only after a "no" looks
//! for the one that matters by halving the set (FindScope). A session
//! does the same with its held rules:
//!
//! - the rules most likely to be habits ([`Asker::p_meant`], lowest first)
//!   are put in one group while the chance that all of them are habits
//!   stays at least [`GROUP_CHANCE`]; a rule joins only if one layout
//!   breaks the whole group and keeps every other held rule (a check);
//! - "acceptable": the probe becomes a demonstration and learning drops
//!   the whole group;
//! - "not acceptable": at least one of the group is meant. The group is
//!   *pending*: the next question asks about its likelier-habit half. An
//!   accepted half leaves the rest pending; a rejected half becomes the
//!   pending group (the rest go back to the other held rules); a rejected
//!   single rule is confirmed; the last rule left of a pending group is
//!   confirmed without a question (*deduced*).
//!
//! What was pending and deduced is a function of the answers in order
//! ([`replay_groups`]), so a resumed session knows it too.

use super::belief::GROUP_CHANCE;
use super::{AskError, Asked, Asker, Known, Question};
use crate::ask::answers::Answer;
use crate::ask::checker::{Checked, ProbeChecker};
use crate::ask::probe::{search_group_probe, Probe, ProbeOutcome};
use std::collections::BTreeSet;

/// At most this many rules are tried for one group (each try is a check).
const MAX_GROUP_TRIES: usize = 12;

/// What an answer about the rules `asked` does to the pending group.
pub(super) fn narrow(pending: &mut Vec<String>, asked: &[&str], accepted: bool) {
    if accepted {
        pending.retain(|n| !asked.contains(&n.as_str()));
    } else if asked.len() == 1 {
        // The meant rule of the pending group is found; the others go back
        // to the held rules.
        if pending.iter().any(|n| n == asked[0]) {
            pending.clear();
        }
    } else {
        *pending = asked.iter().map(|s| s.to_string()).collect();
    }
}

/// The pending group and the deduced rules after `answers`, in order (a
/// session started from its answers without replaying them).
pub(super) fn replay_groups(answers: &[Answer]) -> (Vec<String>, BTreeSet<String>) {
    let mut pending = Vec::new();
    let mut deduced = BTreeSet::new();
    for a in answers.iter().filter(|a| a.suspect.is_none()) {
        narrow(&mut pending, &a.asked(), a.accepted);
        if pending.len() == 1 {
            deduced.insert(pending.remove(0));
        }
    }
    (pending, deduced)
}

impl Asker {
    /// Keep only held, unconfirmed rules in the pending group; confirm the
    /// last one left (deduced). Whether one was.
    pub(super) fn settle_pending(&mut self) -> bool {
        let held: BTreeSet<&str> = self.held.rules.iter().map(|r| r.name.as_str()).collect();
        let confirmed = &self.confirmed;
        self.pending
            .retain(|n| held.contains(n.as_str()) && !confirmed.contains(n));
        if self.pending.len() == 1 {
            let name = self.pending.remove(0);
            log::debug!("ask: {name} is the one left of a rejected group: confirmed");
            self.confirmed.insert(name.clone());
            self.deduced.insert(name);
            return true;
        }
        false
    }

    /// The chance that each held rule is meant, this scan.
    pub(super) fn meant_chances(&self) -> Vec<f64> {
        let families = self.families();
        (0..self.held.rules.len())
            .map(|k| self.p_meant(k, &families))
            .collect()
    }

    /// A group question starting from rule `k` (a likely habit that can
    /// break alone): `None` when no second rule can join it.
    pub(super) fn group_question(
        &self,
        k: usize,
        order: &[usize],
        p: &[f64],
        checker: &mut Option<ProbeChecker>,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Result<Option<Question>, AskError> {
        let none = vec![false; self.held.rules.len()];
        if self.check(checker, k, &none)? != Some(true) {
            return Ok(None);
        }
        let mut group = vec![k];
        let mut chance = 1.0 - p[k];
        let mut tried = 0;
        for &j in order {
            if tried >= MAX_GROUP_TRIES || self.meter.borrow().exhausted() {
                break;
            }
            let name = &self.held.rules[j].name;
            if group.contains(&j)
                || self.confirmed.contains(name)
                || matches!(self.known.get(name), Some(Known::Implied))
                || chance * (1.0 - p[j]) < GROUP_CHANCE
            {
                continue;
            }
            tried += 1;
            let mut with = group.clone();
            with.push(j);
            if self.group_check(checker, &with)? == Some(true) {
                group = with;
                chance *= 1.0 - p[j];
            }
        }
        if group.len() < 2 {
            return Ok(None);
        }
        Ok(self.ask_group(k, &group, edit_checkers))
    }

    /// The next question about the pending group: its likelier-habit half
    /// (then the other half, then single rules) that a probe can break.
    /// `None` (and the group is given up) when none can.
    pub(super) fn pending_question(
        &mut self,
        p: &[f64],
        checker: &mut Option<ProbeChecker>,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Result<Option<Question>, AskError> {
        let mut idx: Vec<usize> = self
            .pending
            .iter()
            .filter_map(|n| self.held.rules.iter().position(|r| r.name == *n))
            .collect();
        idx.sort_by(|&a, &b| p[a].total_cmp(&p[b]).then(b.cmp(&a)));
        let half = idx.len() / 2;
        let mut tries: Vec<Vec<usize>> = vec![idx[..half].to_vec(), idx[half..].to_vec()];
        tries.extend(idx.iter().map(|&k| vec![k]));
        for set in tries {
            match set.len() {
                0 => {}
                1 => {
                    let k = set[0];
                    let name = self.held.rules[k].name.clone();
                    if !self.known.contains_key(&name) {
                        let known = self.decide_on_problem(k, checker, edit_checkers)?;
                        self.known.insert(name.clone(), known);
                    }
                    if let Some(Known::Probe(pr)) = self.known.get(&name) {
                        return Ok(Some(self.question(k, pr.clone())));
                    }
                }
                _ => {
                    if self.group_check(checker, &set)? == Some(true) {
                        if let Some(q) = self.ask_group(set[0], &set, edit_checkers) {
                            return Ok(Some(q));
                        }
                    }
                }
            }
        }
        log::debug!("ask: no probe narrows the pending group: given up");
        self.pending.clear();
        Ok(None)
    }

    /// Held rule `j` as a member of a group question.
    fn asked(&self, j: usize) -> Asked {
        let rule = &self.held.rules[j];
        Asked {
            rule: rule.name.clone(),
            statement: crate::infer::statement_text(rule.scope, &rule.formula),
            english: self
                .learned
                .statements
                .iter()
                .find(|s| s.name == rule.name)
                .map(|s| s.english.clone())
                .unwrap_or_default(),
        }
    }

    /// The question about `group` (`k` first): a demonstration with an
    /// object or two moved when one breaks the group, else a layout of the
    /// problem searched.
    fn ask_group(
        &self,
        k: usize,
        group: &[usize],
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Option<Question> {
        let mut ordered = vec![k];
        ordered.extend(group.iter().copied().filter(|&j| j != k));
        let probe = match self.edit_probe_of(&ordered, edit_checkers) {
            Some(p) => p,
            None => match self.search_group(&ordered) {
                Ok(Some(p)) => p,
                _ => self.pool_group_probe(&ordered)?,
            },
        };
        Some(self.group_question_of(&ordered, probe))
    }

    /// The question about the held rules `set` (the first named first)
    /// with `probe`, which breaks them all.
    pub(super) fn group_question_of(&self, set: &[usize], probe: Probe) -> Question {
        let mut q = self.question(set[0], probe);
        q.group = set.iter().map(|&j| self.asked(j)).collect();
        q
    }

    /// The memo key of a check about the rule set `set` (`tag`: what kind
    /// of check), beside the single-rule checks.
    pub(super) fn set_key(&self, set: &[usize], tag: &str) -> (String, Vec<String>) {
        let names: Vec<&str> = set
            .iter()
            .map(|&j| self.held.rules[j].name.as_str())
            .collect();
        (names.join(" + "), vec![tag.to_string()])
    }

    /// Does one layout break every rule of `set` and keep every other held
    /// rule? A pool layout answers yes without a solve; a solve gets the
    /// check budget. `None`: a limit stopped it.
    pub(super) fn group_check(
        &self,
        checker: &mut Option<ProbeChecker>,
        set: &[usize],
    ) -> Result<Option<bool>, AskError> {
        let key = self.set_key(set, "(group)");
        if let Some(&v) = self.checks.borrow().get(&key) {
            return Ok(Some(v));
        }
        if self.pool_breaking_exactly(set).is_some() {
            self.checks.borrow_mut().insert(key, true);
            return Ok(Some(true));
        }
        let c = self.checker(checker)?;
        let Some((_, grant, deadline)) = self.check_grant(c) else {
            return Ok(None);
        };
        c.set_deadline(deadline);
        let t = std::time::Instant::now();
        let before = c.nodes();
        let checked = c.has_group_probe_within(set, Some(grant));
        let w = c.weight();
        self.meter.borrow_mut().spend(c.nodes() - before, w);
        log::debug!(
            "ask: group check {}: {} in {:.1} ms",
            key.0,
            checked.name(),
            t.elapsed().as_secs_f64() * 1e3
        );
        let v = match checked {
            Checked::Witness(scene) => {
                self.remember(scene);
                Some(true)
            }
            Checked::Proven => Some(false),
            Checked::Stopped => {
                *checker = None;
                None
            }
        };
        if let Some(v) = v {
            self.checks.borrow_mut().insert(key, v);
        }
        Ok(v)
    }

    /// The index of a pool layout that breaks every rule of `set` and keeps
    /// every other held rule.
    fn pool_breaking_exactly(&self, set: &[usize]) -> Option<usize> {
        if !self.opts.reuse {
            return None;
        }
        let pool = self.pool_holds();
        pool.holds.iter().position(|h| {
            h.iter()
                .enumerate()
                .all(|(j, &kept)| kept != set.contains(&j))
        })
    }

    /// The group's probe searched under the question's budget (`None`: the
    /// budget found none).
    fn search_group(&self, set: &[usize]) -> Result<Option<Probe>, AskError> {
        let Some(opts) = self.probe_search_options() else {
            return Ok(None);
        };
        let t = std::time::Instant::now();
        let (found, nodes) = search_group_probe(&self.problem, &self.held, set, &opts)?;
        self.meter.borrow_mut().spend(nodes, self.weight.get());
        log::debug!(
            "ask: group probe search ({} rules): {} in {:.1} ms",
            set.len(),
            matches!(found, ProbeOutcome::Probe(_)),
            t.elapsed().as_secs_f64() * 1e3
        );
        Ok(match found {
            ProbeOutcome::Probe(p) => {
                self.remember(p.scene.clone());
                Some(p)
            }
            _ => None,
        })
    }

    /// A pool layout breaking exactly `set` (`set[0]` first), as a probe.
    fn pool_group_probe(&self, set: &[usize]) -> Option<Probe> {
        let at = self.pool_breaking_exactly(set)?;
        let scene = self.pool.borrow().scenes[at].clone();
        Some(self.probe_of(set, scene))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    /// FindScope's bookkeeping: a rejected group is pending, an accepted
    /// half leaves the rest, the last one left is deduced, a rejected
    /// single rule ends the search.
    #[test]
    fn narrowing_a_rejected_group() {
        let mut pending = Vec::new();
        narrow(&mut pending, &["a", "b", "c", "d"], false);
        assert_eq!(pending, names(&["a", "b", "c", "d"]));
        narrow(&mut pending, &["a", "b"], true);
        assert_eq!(pending, names(&["c", "d"]));
        narrow(&mut pending, &["c"], false);
        assert!(pending.is_empty(), "c is the meant one; d goes back");
        narrow(&mut pending, &["x", "y", "z"], false);
        narrow(&mut pending, &["x", "y"], false);
        assert_eq!(pending, names(&["x", "y"]), "z goes back");
    }

    #[test]
    fn replaying_answers_deduces_the_last_rule_left() {
        let answer = |group: &[&str], accepted: bool| Answer {
            rule: group[0].to_string(),
            statement: String::new(),
            english: String::new(),
            accepted,
            demo: None,
            broken: Vec::new(),
            probe: crate::scene::Scene::from_json(
                r#"{"space":{"x":0,"y":0,"width":10,"height":10},"objects":[]}"#,
            )
            .unwrap(),
            edit: None,
            suspect: None,
            group: if group.len() > 1 {
                names(group)
            } else {
                Vec::new()
            },
        };
        let (pending, deduced) =
            replay_groups(&[answer(&["a", "b", "c"], false), answer(&["a", "b"], true)]);
        assert!(pending.is_empty());
        assert_eq!(deduced, ["c".to_string()].into_iter().collect());
        let (pending, deduced) =
            replay_groups(&[answer(&["a", "b", "c"], false), answer(&["a"], true)]);
        assert_eq!(pending, names(&["b", "c"]));
        assert!(deduced.is_empty());
    }
}
