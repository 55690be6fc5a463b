//! The search order: a hint first, then a greedy first-fail packing until
//! the first solution, then Pumpkin's learning brancher, and last the
//! variables created after the engine.

use pumpkin_core::branching::branchers::independent_variable_value_brancher::IndependentVariableValueBrancher;
use pumpkin_core::branching::branchers::warm_start::WarmStart;
use pumpkin_core::branching::tie_breaking::InOrderTieBreaker;
use pumpkin_core::branching::value_selection::InDomainMin;
use pumpkin_core::branching::variable_selection::FirstFail;
use pumpkin_core::branching::{Brancher, BrancherEvent, SelectionContext};
use pumpkin_core::predicates::Predicate;
use pumpkin_core::results::SolutionReference;
use pumpkin_core::variables::DomainId;
use std::cell::Cell;
use std::rc::Rc;

pub(super) type StaticBrancher = IndependentVariableValueBrancher<
    DomainId,
    FirstFail<DomainId, InOrderTieBreaker<DomainId, i32>>,
    InDomainMin,
>;

/// Two-phase search: until the first solution, place objects greedily
/// (first-fail over the grid variables, smallest value first), which finds a
/// packing at once; afterwards the main (learning) brancher. Every event
/// goes to both.
///
/// A *hint* ([`Engine::set_hint`]) comes before both: each hinted grid
/// variable is tried at its hinted value (Pumpkin's `WarmStart`), skipping
/// the ones that propagation already decided, until the next solution. The
/// hint is a value-ordering heuristic only: a hinted value that conflicts is
/// learned away like any decision, so it never changes what is provable.
#[derive(Debug)]
pub(super) struct Phased {
    pub(super) hint: Option<WarmStart<DomainId>>,
    pub(super) first: StaticBrancher,
    pub(super) main: Box<dyn Brancher>,
    pub(super) use_first: Rc<Cell<bool>>,
    /// Conflicts met while the greedy phase was on.
    pub(super) first_conflicts: u64,
    /// Leave the greedy phase after this many conflicts without a first
    /// solution ([`Engine::leave_greedy_after`]; `None`: only at a
    /// solution).
    pub(super) first_cap: Option<u64>,
    /// Variables created after the engine (the second objective's), which
    /// the main brancher does not know: each takes its smallest value once
    /// `main` has nothing left to decide.
    pub(super) late: Option<StaticBrancher>,
    pub(super) late_vars: Vec<DomainId>,
}

impl Phased {
    /// Hand variables created after the engine to the brancher.
    pub(super) fn add_late(&mut self, vars: &[DomainId]) {
        if vars.is_empty() {
            return;
        }
        self.late_vars.extend_from_slice(vars);
        self.late = Some(IndependentVariableValueBrancher::new(
            FirstFail::new(&self.late_vars),
            InDomainMin,
        ));
    }
}

impl Brancher for Phased {
    fn next_decision(&mut self, context: &mut SelectionContext) -> Option<Predicate> {
        if let Some(h) = &mut self.hint {
            if let Some(d) = h.next_decision(context) {
                return Some(d);
            }
        }
        if self.use_first.get() {
            if let Some(d) = self.first.next_decision(context) {
                return Some(d);
            }
        }
        if let Some(d) = self.main.next_decision(context) {
            return Some(d);
        }
        self.late.as_mut()?.next_decision(context)
    }
    fn on_conflict(&mut self) {
        // A greedy packing finds a first layout without backtracking in
        // practice; when it keeps failing, the problem is hard or
        // infeasible (an `ask` implication check, contradicting hard
        // rules), and the learning brancher — which also branches on the
        // rules' Booleans — proves it far sooner than coordinate
        // enumeration.
        if let (true, Some(cap)) = (self.use_first.get(), self.first_cap) {
            self.first_conflicts += 1;
            if self.first_conflicts >= cap {
                self.use_first.set(false);
            }
        }
        self.main.on_conflict()
    }
    fn on_backtrack(&mut self) {
        self.main.on_backtrack()
    }
    fn on_solution(&mut self, solution: SolutionReference) {
        // A hint lasts until the next solution.
        self.hint = None;
        self.main.on_solution(solution)
    }
    fn on_unassign_integer(&mut self, variable: DomainId, value: i32) {
        self.first.on_unassign_integer(variable, value);
        if let Some(l) = &mut self.late {
            l.on_unassign_integer(variable, value);
        }
        self.main.on_unassign_integer(variable, value)
    }
    fn on_appearance_in_conflict_predicate(&mut self, predicate: Predicate) {
        self.main.on_appearance_in_conflict_predicate(predicate)
    }
    fn on_restart(&mut self) {
        self.main.on_restart()
    }
    fn synchronise(&mut self, context: &mut SelectionContext) {
        if let Some(h) = &mut self.hint {
            h.synchronise(context);
        }
        self.first.synchronise(context);
        if let Some(l) = &mut self.late {
            l.synchronise(context);
        }
        self.main.synchronise(context)
    }
    fn is_restart_pointless(&mut self) -> bool {
        self.main.is_restart_pointless()
    }
    fn subscribe_to_events(&self) -> Vec<BrancherEvent> {
        let mut v = self.main.subscribe_to_events();
        // A hint may be set later: its events (solution, synchronise) are
        // always subscribed.
        for e in self
            .first
            .subscribe_to_events()
            .into_iter()
            .chain([BrancherEvent::Solution, BrancherEvent::Synchronise])
        {
            if !v.contains(&e) {
                v.push(e);
            }
        }
        v
    }
}
