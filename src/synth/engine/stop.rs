//! When a solve stops: the counters of decisions and conflicts (kept by a
//! brancher wrapper) and the termination condition Pumpkin polls, which
//! stops on a deadline, a node limit or the cancel flag, only above the
//! root.

use super::brancher::Phased;
use crate::stop::Stop;
use pumpkin_core::branching::{Brancher, BrancherEvent, SelectionContext};
use pumpkin_core::predicates::Predicate;
use pumpkin_core::results::SolutionReference;
use pumpkin_core::statistics::StatisticLogger;
use pumpkin_core::termination::TerminationCondition;
use pumpkin_core::variables::DomainId;
use std::cell::Cell;
use std::rc::Rc;

/// The search's counters, shared by the engine, its [`Counting`] brancher
/// and its [`Termination`]: decisions, conflicts, and whether the search is above
/// the root (where stopping is safe).
#[derive(Debug, Clone, Default)]
pub(super) struct Counters {
    pub(super) nodes: Rc<Cell<u64>>,
    pub(super) conflicts: Rc<Cell<u64>>,
    pub(super) safe: Rc<Cell<bool>>,
}

/// Polled by Pumpkin; stops on deadline, node limit or cancel flag.
///
/// Only ever stops *above the root*: Pumpkin 0.5 restores its state after
/// a timeout only when the timeout struck at a decision level above 0 (at
/// the root it stays "timed out", and the next solve asserts). `safe` is
/// set by [`Counting`] after each decision and cleared by each conflict
/// (which may jump back to the root), so a limit waits at most for the
/// next decision; an engine can then be solved again after any limit,
/// keeping what it learned.
pub(super) struct Termination {
    pub(super) limits: Stop,
    pub(super) nodes: Rc<Cell<u64>>,
    pub(super) safe: Rc<Cell<bool>>,
    pub(super) fired: Rc<Cell<bool>>,
}

impl TerminationCondition for Termination {
    fn should_stop(&mut self) -> bool {
        if !self.safe.get() {
            return false;
        }
        let stop =
            self.limits.nodes().is_some_and(|n| self.nodes.get() >= n) || self.limits.expired();
        if stop {
            self.fired.set(true);
        }
        stop
    }
}

/// A brancher wrapper that counts decisions and conflicts.
#[derive(Debug)]
pub(super) struct Counting {
    pub(super) inner: Phased,
    pub(super) nodes: Rc<Cell<u64>>,
    pub(super) conflicts: Rc<Cell<u64>>,
    /// Whether the search is above the root (see [`Termination`]).
    pub(super) safe: Rc<Cell<bool>>,
}

impl Brancher for Counting {
    fn log_statistics(&self, l: StatisticLogger) {
        self.inner.log_statistics(l)
    }
    fn next_decision(&mut self, context: &mut SelectionContext) -> Option<Predicate> {
        let d = self.inner.next_decision(context);
        if d.is_some() {
            self.nodes.set(self.nodes.get() + 1);
            self.safe.set(true);
        }
        d
    }
    fn on_conflict(&mut self) {
        self.safe.set(false);
        self.conflicts.set(self.conflicts.get() + 1);
        self.inner.on_conflict()
    }
    fn on_backtrack(&mut self) {
        self.inner.on_backtrack()
    }
    fn on_solution(&mut self, solution: SolutionReference) {
        self.inner.on_solution(solution)
    }
    fn on_unassign_integer(&mut self, variable: DomainId, value: i32) {
        self.inner.on_unassign_integer(variable, value)
    }
    fn on_appearance_in_conflict_predicate(&mut self, predicate: Predicate) {
        self.inner.on_appearance_in_conflict_predicate(predicate)
    }
    fn on_restart(&mut self) {
        self.safe.set(false);
        self.inner.on_restart()
    }
    fn synchronise(&mut self, context: &mut SelectionContext) {
        self.inner.synchronise(context)
    }
    fn is_restart_pointless(&mut self) -> bool {
        self.inner.is_restart_pointless()
    }
    fn subscribe_to_events(&self) -> Vec<BrancherEvent> {
        let mut v = self.inner.subscribe_to_events();
        if !v.contains(&BrancherEvent::Conflict) {
            v.push(BrancherEvent::Conflict);
        }
        v
    }
}
