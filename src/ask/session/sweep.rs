//! Sweeps (docs/guide.md#how-a-session-chooses-its-questions): one probe
//! that breaks as many likely habits as the rules the person probably
//! means allow.
//!
//! A group question built rule by rule needs one layout that breaks
//! exactly the group and keeps every other held rule; habits interlock
//! (breaking one breaks another), so such groups stay small. A sweep
//! asks the engine instead: every held rule that is probably meant (or
//! confirmed) is kept hard, and every likely habit ([`SWEEP_P`]) is broken
//! softly, each weighted by the odds that it is a habit. The layout found
//! breaks some set of them; the question is about exactly that set (the
//! evaluator says which), so "acceptable" drops all of them at once and
//! "not acceptable" makes them the pending group that the next questions
//! narrow down ([`super::group`]).

use super::{AskError, Asker, Question};
use crate::ask::checker::ProbeChecker;
use crate::ask::probe::{kept_hard, negation};
use crate::rules::{Rule, RuleSet, Strength};
use crate::synth::{synthesize, Status};

/// A held rule is broken by a sweep when the chance that it is meant is
/// below this (a likely habit); the others are kept.
pub(super) const SWEEP_P: f64 = 0.5;

/// A sweep of `n` rules is asked when the chance that all of them are
/// habits is at least this over `n`. Measured (docs/performance.md#questions):
/// 1 (the break-even of the argument at [`worth_asking`]) asked 24
/// questions on the bundled box and 130 and 113 on the population with
/// habits (uniform, priors); 0.75 asked 23, 121 and 113 with as few
/// spurious rules left; 0.5 asked 22, 126 and 124 — the chances are
/// pessimistic about habits, so a little below break-even pays.
pub(super) const SWEEP_WORTH: f64 = 0.75;

/// At most this many solves look for one sweep (each with fewer rules
/// allowed to break than the one before).
const MAX_SWEEP_SOLVES: usize = 2;

/// How many of `set` (likeliest habit first) are worth one question: the
/// longest prefix of `n` rules whose chance of being all habits is at
/// least [`SWEEP_WORTH`]` / n`. A rejected sweep costs about one question
/// (its rules are then narrowed down as they would have been asked
/// anyway), an accepted one saves one question per rule but one, so a
/// sweep of `n` rules pays when the person accepts it about once in `n`
/// times.
fn worth_asking(set: &[usize], p: &[f64]) -> usize {
    let mut chance = 1.0;
    let mut worth = 0;
    for (i, &k) in set.iter().enumerate() {
        chance *= 1.0 - p[k];
        if chance * (i + 1) as f64 >= SWEEP_WORTH {
            worth = i + 1;
        }
    }
    worth
}

/// The odds weight of a rule meant with chance `p`: `ln((1 − p) / p)`,
/// bounded so that no rule is worth nothing or everything.
fn habit_weight(p: f64) -> f64 {
    let p = p.clamp(0.01, 0.99);
    ((1.0 - p) / p).ln().clamp(0.05, 5.0)
}

impl Asker {
    /// The sweep of this scan: a group question about every held rule one
    /// layout breaks, when it breaks at least two likely habits and keeps
    /// every other held rule. `None` when fewer than two rules are likely
    /// habits, the same sweep was tried before (the held rules and the
    /// chances unchanged), or the budget finds no such layout.
    pub(super) fn sweep_question(
        &self,
        p: &[f64],
        order: &[usize],
        checker: &mut Option<ProbeChecker>,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Result<Option<Question>, AskError> {
        let rejected = self.in_rejected_groups();
        let mut candidates: Vec<usize> = order
            .iter()
            .copied()
            .filter(|&k| {
                let r = &self.held.rules[k];
                p[k] < SWEEP_P
                    && !self.confirmed.contains(&r.name)
                    && !rejected.contains(r.name.as_str())
                    && negation(r).is_some()
            })
            .collect();
        for _ in 0..MAX_SWEEP_SOLVES {
            if candidates.len() < 2 {
                return Ok(None);
            }
            let key = self.set_key(&candidates, "(sweep)");
            if self.checks.borrow().contains_key(&key) {
                return Ok(None);
            }
            // The problem's checker sets the weight of a node (the rules'
            // checks need it next anyway).
            self.checker(checker)?;
            let broken = self.sweep_layout(&candidates, p)?;
            self.checks.borrow_mut().insert(key, broken.is_some());
            let Some((mut set, scene)) = broken else {
                return Ok(None);
            };
            set.sort_by(|&a, &b| p[a].total_cmp(&p[b]).then(b.cmp(&a)));
            let worth = worth_asking(&set, p);
            if worth == set.len() {
                return Ok(Some(self.sweep_of(&set, scene, edit_checkers)));
            }
            if worth < 2 {
                return Ok(None);
            }
            // Too likely rejected: keep the likelier meant rules of the
            // set (and every candidate as likely meant) and look again.
            let last = set[worth - 1];
            candidates.retain(|&k| p[k].total_cmp(&p[last]).then(last.cmp(&k)).is_le());
        }
        Ok(None)
    }

    /// The rules of every rejected group or sweep: at least one of each
    /// group is meant, so sweeping them again would likely be rejected
    /// again; they are settled by the narrowing or alone.
    fn in_rejected_groups(&self) -> std::collections::BTreeSet<&str> {
        self.answers
            .iter()
            .filter(|a| !a.accepted && a.suspect.is_none() && a.group.len() > 1)
            .flat_map(|a| a.group.iter().map(String::as_str))
            .collect()
    }

    /// The question about the rules `set` a sweep's `scene` breaks: a
    /// demonstration with a block or two moved that breaks the same rules
    /// when there is one (easier to judge than a new layout), else the
    /// layout.
    fn sweep_of(
        &self,
        set: &[usize],
        scene: crate::scene::Scene,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Question {
        let probe = match self.edit_probe_of(set, edit_checkers) {
            Some(pr) => pr,
            None => self.probe_of(set, scene),
        };
        self.group_question_of(set, probe)
    }

    /// Solve the sweep of `candidates` under the question's budget: the
    /// held rules it breaks (at least two, all candidates) and the layout.
    fn sweep_layout(
        &self,
        candidates: &[usize],
        p: &[f64],
    ) -> Result<Option<(Vec<usize>, crate::scene::Scene)>, AskError> {
        let Some(opts) = self.probe_search_options() else {
            return Ok(None);
        };
        let mut rules: Vec<Rule> = Vec::new();
        for (k, r) in self.held.rules.iter().enumerate() {
            if candidates.contains(&k) {
                let mut neg = negation(r).expect("candidates can break");
                neg.strength = Strength::Weight(habit_weight(p[k]));
                rules.push(neg);
            } else {
                rules.push(kept_hard(r));
            }
        }
        let t = std::time::Instant::now();
        let r = synthesize(&self.problem, &RuleSet::new(rules), &opts.synth_options())?;
        self.meter
            .borrow_mut()
            .spend(r.stats.nodes, self.weight.get());
        let found = match (r.status, r.scene) {
            (Status::Optimal | Status::Feasible, Some(scene)) => Some(scene),
            _ => None,
        };
        let Some(scene) = found else {
            log::debug!(
                "ask: sweep of {} rules: none in {:.1} ms",
                candidates.len(),
                t.elapsed().as_secs_f64() * 1e3
            );
            return Ok(None);
        };
        // Not kept in the session's pool of layouts: a layout breaking
        // many rules would answer later checks of rules that may break
        // with others, and become the probe of a single rule that breaks
        // many more (whose "no" confirms the wrong one).
        let ev = crate::eval::evaluate(&scene, &self.held, self.opts.probe.contact);
        let set: Vec<usize> = (0..self.held.rules.len())
            .filter(|&j| ev.rules[j].satisfied < ev.rules[j].subjects)
            .collect();
        log::debug!(
            "ask: sweep of {} rules: breaks {} in {:.1} ms",
            candidates.len(),
            set.len(),
            t.elapsed().as_secs_f64() * 1e3
        );
        // Every other held rule is hard, so only candidates can break.
        let only_candidates = set.iter().all(|j| candidates.contains(j));
        debug_assert!(only_candidates);
        Ok((set.len() >= 2 && only_candidates).then_some((set, scene)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ask::budget::{Meter, QuestionBudget};
    use crate::ask::AskOptions;
    use crate::scene::{scenes_from_json, Scene};
    use std::collections::BTreeSet;

    /// A rejected sweep's rules are not swept again: after "not
    /// acceptable" to the bundled example's first question (a sweep), no
    /// sweep of the next questions names a rule of it (each sweep looked
    /// for directly, before the session's own question). Without the
    /// exclusion, `R_not_dr_s_R` is swept again.
    #[test]
    fn a_rejected_sweeps_rules_are_not_swept_again() {
        let demos = scenes_from_json(include_str!("../../../examples/box-packing/demos.json"))
            .expect("demonstrations");
        let problem = Scene::from_json(include_str!("../../../examples/box-packing/problem.json"))
            .expect("problem");
        let opts = AskOptions {
            budget: QuestionBudget {
                wall: None,
                ..QuestionBudget::default()
            },
            ..AskOptions::default()
        };
        let mut asker = Asker::new(problem, demos, None, Vec::new(), opts).unwrap();
        let q = asker.next_question().unwrap().expect("a question");
        assert!(q.group.len() >= 2, "the first question is a sweep");
        let rejected: BTreeSet<String> = q.group_names().into_iter().collect();
        asker.answer(&q, false).unwrap();
        let mut swept = 0;
        for i in 0..8 {
            let p = asker.meant_chances();
            let order = asker.asking_order_with(&p);
            *asker.meter.get_mut() = Meter::start(&asker.opts.budget);
            let (mut checker, mut edits) = (None, Vec::new());
            if let Some(s) = asker
                .sweep_question(&p, &order, &mut checker, &mut edits)
                .unwrap()
            {
                swept += 1;
                for n in s.group_names() {
                    assert!(!rejected.contains(&n), "{n} swept again");
                }
            }
            let Some(q) = asker.next_question().unwrap() else {
                break;
            };
            asker.answer(&q, i % 2 == 0).unwrap();
        }
        assert!(swept > 0, "no sweep to look at");
    }

    /// A sweep of `n` rules is worth a question when all are habits with a
    /// chance of at least `0.75/n`; the longest such prefix counts.
    #[test]
    fn a_sweep_is_worth_asking_when_it_pays() {
        let p = [0.18, 0.24, 0.27, 0.35, 0.45, 0.49];
        // 0.82, 0.62, 0.46, 0.30, 0.16, 0.08 against 0.75 over 1 … 6.
        assert_eq!(worth_asking(&[0, 1, 2, 3, 4, 5], &p), 5);
        assert_eq!(worth_asking(&[0, 1, 2, 3], &p), 4);
        assert_eq!(worth_asking(&[4, 5], &p), 0, "0.55 × 0.51 < 0.75/2");
        assert_eq!(worth_asking(&[], &p), 0);
    }

    /// Likelier habits weigh more; no weight is zero or unbounded.
    #[test]
    fn habit_weights_follow_the_odds() {
        assert!(habit_weight(0.1) > habit_weight(0.3));
        assert!((habit_weight(0.2) - 4.0_f64.ln()).abs() < 1e-12);
        assert_eq!(habit_weight(0.5), 0.05);
        assert_eq!(habit_weight(0.0), 5.0f64.min((0.99_f64 / 0.01).ln()));
    }
}
