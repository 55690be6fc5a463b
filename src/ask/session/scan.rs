//! One scan of the held rules for the next question, in passes (see
//! [`Asker::next_question`]).

use super::checks::related;
use super::{AskError, Asker, Known, Question};
use crate::ask::budget::{Meter, QuestionBudget};
use crate::ask::checker::ProbeChecker;
use crate::ask::probe::Probe;
use std::ops::ControlFlow;

/// How a scan for the next question ended.
pub(super) enum Scan {
    Question(Box<Question>),
    /// The question's budget ran out before any rule had a probe; the rule
    /// that used it up is decided or deferred, so the next scan goes on.
    OutOfBudget,
    Done,
}

/// What the last pass found for one rule.
enum EditPass {
    /// A demonstration with an object or two moved breaks the rule.
    Probe(Probe),
    /// The question's budget ran out before the rule was looked at.
    OutOfBudget,
    /// Nothing to ask.
    Skip,
}

impl Asker {
    /// One scan of the held rules for the next question, under a fresh
    /// question budget (see [`Asker::next_question`]): pass 0 decides each
    /// rule on the problem, passes 1 and 2 ask about groups of rules that
    /// follow from one another, pass 3 looks for edits of the
    /// demonstrations that break a rule implied on the problem.
    pub(super) fn scan(
        &mut self,
        checker: &mut Option<ProbeChecker>,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Result<Scan, AskError> {
        *self.meter.get_mut() = Meter::start(&self.opts.budget);
        let mut decided = 0usize;
        // Decided checks so far: a group pass that runs out of budget after
        // deciding new ones goes on in the next scan (the decided ones are
        // kept), so every scan makes progress and the loop ends.
        let settled = |a: &Asker| a.checks.borrow().len() + a.alone.borrow().len();
        let settled_before = settled(self);
        let p = self.meant_chances();
        let order = self.asking_order_with(&p);
        if self.opts.groups && !self.pending.is_empty() {
            if let Some(q) = self.pending_question(&p, checker, edit_checkers)? {
                return Ok(Scan::Question(Box::new(q)));
            }
        }
        if self.opts.groups && self.pending.is_empty() {
            // A sweep has a budget of its own (a quarter of a question's),
            // so that a sweep that finds nothing defers no rule.
            let share = QuestionBudget {
                nodes: (self.opts.budget.nodes / 4).max(1),
                ..self.opts.budget
            };
            *self.meter.get_mut() = Meter::start(&share);
            let sweep = self.sweep_question(&p, &order, checker, edit_checkers)?;
            *self.meter.get_mut() = Meter::start(&self.opts.budget);
            if let Some(q) = sweep {
                return Ok(Scan::Question(Box::new(q)));
            }
        }
        for pass in 0..4 {
            if pass > 0 {
                // The group passes and the last one get budgets of their
                // own.
                *self.meter.get_mut() = Meter::start(&self.opts.budget);
            }
            let mut tried = 0usize;
            for &k in &order {
                let name = self.held.rules[k].name.clone();
                if self.confirmed.contains(&name) {
                    continue;
                }
                let probe = match pass {
                    0 => match self.problem_pass(
                        k,
                        &order,
                        &p,
                        &mut decided,
                        checker,
                        edit_checkers,
                    )? {
                        ControlFlow::Break(scan) => return Ok(scan),
                        ControlFlow::Continue(probe) => probe,
                    },
                    1 | 2 => {
                        if self.meter.borrow().exhausted() && settled(self) > settled_before {
                            return Ok(Scan::OutOfBudget);
                        }
                        if matches!(self.known.get(&name), Some(Known::Implied)) {
                            self.group_probe(k, pass == 2, &order, checker)?
                        } else {
                            None
                        }
                    }
                    _ => match self.edit_pass(k, &name, &mut tried, edit_checkers) {
                        EditPass::Probe(p) => Some(p),
                        EditPass::OutOfBudget => return Ok(Scan::OutOfBudget),
                        EditPass::Skip => None,
                    },
                };
                if let Some(p) = probe {
                    return Ok(Scan::Question(Box::new(self.question(k, p))));
                }
            }
        }
        Ok(Scan::Done)
    }

    /// Pass 0 for rule `k`: a group question when the rule is an unlikely
    /// habit, else the rule decided on the problem (once); its probe, if
    /// any. `Break`: the scan ends here (a question, or out of budget).
    fn problem_pass(
        &mut self,
        k: usize,
        order: &[usize],
        p: &[f64],
        decided: &mut usize,
        checker: &mut Option<ProbeChecker>,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Result<ControlFlow<Scan, Option<Probe>>, AskError> {
        let name = self.held.rules[k].name.clone();
        if self.opts.groups
            && p[k] < 0.5
            && !self.known.contains_key(&name)
            && !self.syntactically_implied(k)
        {
            if let Some(q) = self.group_question(k, order, p, checker, edit_checkers)? {
                return Ok(ControlFlow::Break(Scan::Question(Box::new(q))));
            }
        }
        if !self.known.contains_key(&name) {
            if *decided > 0 && self.meter.borrow().exhausted() {
                // Every rule so far is decided or deferred: the next scan
                // goes on from here with a fresh budget.
                return Ok(ControlFlow::Break(Scan::OutOfBudget));
            }
            let known = self.decide_on_problem(k, checker, edit_checkers)?;
            *decided += 1;
            self.known.insert(name.clone(), known);
        }
        Ok(ControlFlow::Continue(match self.known.get(&name) {
            Some(Known::Probe(p)) => Some(p.clone()),
            _ => None,
        }))
    }

    /// Pass 0: the problem first. A rule the others imply there is not
    /// asked about now (the last pass looks at other mixes); one that can
    /// break is shown as an edit of a demonstration when one breaks it,
    /// else as a layout of the problem.
    pub(super) fn decide_on_problem(
        &self,
        k: usize,
        checker: &mut Option<ProbeChecker>,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Result<Known, AskError> {
        if self.syntactically_implied(k) {
            return Ok(Known::Implied);
        }
        let none = vec![false; self.held.rules.len()];
        Ok(match self.check(checker, k, &none)? {
            Some(false) => Known::Implied,
            _ => match self.edit_probe(k, edit_checkers) {
                Some(p) => Known::Probe(p),
                None => self.search(k, &none)?,
            },
        })
    }

    /// Pass 3, other mixes: a rule the others imply on the problem may
    /// still break in a demonstration with an object or two moved. Each
    /// rule is tried once while the held rules stay the same.
    fn edit_pass(
        &self,
        k: usize,
        name: &str,
        tried: &mut usize,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> EditPass {
        if !matches!(self.known.get(name), Some(Known::Implied))
            || !self.opts.edits
            || !self.edit_tried.borrow_mut().insert(name.to_string())
        {
            return EditPass::Skip;
        }
        if *tried > 0 && self.meter.borrow().exhausted() {
            self.edit_tried.borrow_mut().remove(name);
            return EditPass::OutOfBudget;
        }
        *tried += 1;
        if self.syntactically_implied(k) {
            return EditPass::Skip;
        }
        match self.edit_probe(k, edit_checkers) {
            Some(p) => EditPass::Probe(p),
            None => EditPass::Skip,
        }
    }

    /// Passes 1 and 2, for a rule `k` the others imply on the problem: the
    /// probe of its group, if one exists. `k` is skipped when another
    /// implied rule alone implies it and not the other way round (the
    /// stronger rule is asked about, and once settled, settles `k`); it is
    /// grouped with those that say the same on this problem (each alone
    /// implies the other), then with its parts until a probe exists; in the
    /// `last` pass every open rule about the same classes may break too.
    fn group_probe(
        &self,
        k: usize,
        last: bool,
        order: &[usize],
        checker: &mut Option<ProbeChecker>,
    ) -> Result<Option<Probe>, AskError> {
        let n = self.held.rules.len();
        let open: Vec<usize> = (0..n)
            .filter(|&j| {
                let other = &self.held.rules[j].name;
                j != k
                    && !self.confirmed.contains(other)
                    && matches!(self.known.get(other), Some(Known::Implied))
            })
            .collect();
        let mut with = vec![false; n];
        let mut parts = vec![false; n];
        for &j in &open {
            let j_k = self.alone_implies(checker, j, k)?;
            let k_j = self.alone_implies(checker, k, j)?;
            if j_k && !k_j {
                return Ok(None);
            }
            with[j] = j_k && k_j;
            parts[j] = k_j && !j_k;
        }
        // Grow the group with the rule's parts (the rules it alone
        // implies), weakest evidence first, until the firm rules no longer
        // imply `k`.
        let mut probe_able =
            with.iter().any(|&w| w) && self.check(checker, k, &with)? == Some(true);
        for &j in order.iter().filter(|&&j| parts[j]) {
            if probe_able {
                break;
            }
            with[j] = true;
            probe_able = self.check(checker, k, &with)? == Some(true);
        }
        if !probe_able && last {
            // Last pass, one solve: every open rule about the same classes
            // may break (e.g. a habit of the same objects that the probe
            // must break too).
            let mut all = with.clone();
            for &j in &open {
                all[j] |= related(&self.held.rules[k], &self.held.rules[j]);
            }
            if all != with && self.check(checker, k, &all)? == Some(true) {
                with = all;
                probe_able = true;
            }
        }
        if !probe_able {
            // The firm rules imply it (or a limit): settled.
            return Ok(None);
        }
        self.keep_hard(checker, k, &mut with)?;
        // Not cached: it depends on which rules are confirmed.
        Ok(match self.search(k, &with)? {
            Known::Probe(p) => Some(p),
            _ => None,
        })
    }

    /// Keep hard again every rule of `with` that a probe of `k` can keep
    /// (strongest first), so the probe breaks the fewest others.
    fn keep_hard(
        &self,
        checker: &mut Option<ProbeChecker>,
        k: usize,
        with: &mut [bool],
    ) -> Result<(), AskError> {
        for j in 0..with.len() {
            if with[j] {
                with[j] = false;
                if self.check(checker, k, with)? != Some(true) {
                    with[j] = true;
                }
            }
        }
        Ok(())
    }

    /// The question about held rule `k` with probe `p`, naming the other
    /// held rules the probe breaks.
    pub(super) fn question(&self, k: usize, p: Probe) -> Question {
        let rule = &self.held.rules[k];
        let name = &rule.name;
        let stmt = self
            .learned
            .statements
            .iter()
            .find(|s| s.name == *name)
            .expect("a held rule is a statement");
        let ev = crate::eval::evaluate(&p.scene, &self.held, self.opts.learn.contact);
        let also_broken = ev
            .rules
            .iter()
            .filter(|r| r.name != *name && r.satisfied < r.subjects)
            .map(|r| r.name.clone())
            .collect();
        Question {
            also_broken,
            rule: name.clone(),
            statement: crate::infer::statement_text(rule.scope, &rule.formula),
            english: stmt.english.clone(),
            probe: p,
            group: Vec::new(),
            suspect: None,
        }
    }
}
