//! The question budget: how much search one question may cost.
//!
//! Every question is produced under a budget of search work
//! ([`QuestionBudget::nodes`], summed over every check and probe search the
//! question needs), so the same folder, answers and budget give the same
//! questions on any machine and thread count. A search node on a large
//! model costs more than one on a small model, so each node is charged the
//! model's *weight*: its Booleans in units of [`WEIGHT_UNIT`] (at least 1).
//! On the bundled example a question's budget is then a few thousand nodes;
//! on a 20-object task with 69 held rules, a few hundred. The wall-clock cap
//! ([`QuestionBudget::wall`]) only guards the machine: when it strikes
//! first, what was not decided depends on the machine's speed.
//!
//! A check the budget does not decide is never waited on: the rule is
//! *deferred* for the held rules of the moment (asked about again after
//! learning is redone), and the session says so in its summary.

use crate::stop::Stop;
use std::time::{Duration, Instant};

/// Default [`QuestionBudget::nodes`]: about a second of search on a
/// 2-core machine of the kind this project is measured on (see the docs'
/// performance page).
pub const DEFAULT_QUESTION_NODES: u64 = 20_000;

/// Model Booleans per unit of weight (see the module docs).
pub(super) const WEIGHT_UNIT: usize = 1024;

/// The weight of a node on a model with `bools` Booleans.
pub(crate) fn weight(bools: usize) -> u64 {
    u64::try_from(bools / WEIGHT_UNIT)
        .unwrap_or(u64::MAX)
        .max(1)
}

/// Default [`QuestionBudget::wall`].
pub const DEFAULT_QUESTION_WALL: Duration = Duration::from_secs(10);

/// How much one question may cost.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QuestionBudget {
    /// Search work per question: nodes, each weighted by its model's size
    /// (see the module docs), over every check and probe search
    /// (deterministic).
    pub nodes: u64,
    /// Wall-clock cap per question, counted from when the question is
    /// started (a safety net; `None`: none). Each question gets a
    /// [`Stop`] at this much from its start.
    pub wall: Option<Duration>,
}

impl Default for QuestionBudget {
    fn default() -> Self {
        QuestionBudget {
            nodes: DEFAULT_QUESTION_NODES,
            wall: Some(DEFAULT_QUESTION_WALL),
        }
    }
}

/// What is left of one question's budget: its weighted nodes, and its
/// stop (the wall-clock cap as a deadline).
#[derive(Debug, Clone)]
pub(crate) struct Meter {
    left: u64,
    stop: Stop,
}

impl Meter {
    /// A full budget from now.
    pub(super) fn start(b: &QuestionBudget) -> Meter {
        Meter {
            left: b.nodes,
            stop: Stop::within(b.wall),
        }
    }

    /// A meter that never runs out (for one-off checks outside a question).
    pub(super) fn unlimited() -> Meter {
        Meter {
            left: u64::MAX,
            stop: Stop::never(),
        }
    }

    /// Whether nothing is left (nodes or time).
    pub(super) fn exhausted(&self) -> bool {
        self.left == 0 || self.stop.expired()
    }

    /// Nodes for a solve on a model of weight `weight` that wants `want`:
    /// at most what is left; `None` when nothing is.
    pub(super) fn grant(&self, want: u64, weight: u64) -> Option<u64> {
        let can = self.left / weight.max(1);
        if self.exhausted() || can == 0 {
            None
        } else {
            Some(want.min(can))
        }
    }

    /// Half of what is left, in nodes of weight `weight` (at least 1).
    pub(super) fn half_nodes(&self, weight: u64) -> u64 {
        (self.left / 2 / weight.max(1)).max(1)
    }

    /// Charge `nodes` spent on a model of weight `weight`.
    pub(super) fn spend(&mut self, nodes: u64, weight: u64) {
        self.left = self
            .left
            .saturating_sub(nodes.saturating_mul(weight.max(1)));
    }

    /// The deadline (the wall-clock cap), if any.
    pub(super) fn deadline(&self) -> Option<Instant> {
        self.stop.deadline()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wall_counts_from_the_question_start_and_nodes_are_weighted() {
        let spent = Meter::start(&QuestionBudget {
            nodes: 10,
            wall: Some(Duration::ZERO),
        });
        assert!(spent.exhausted());
        assert_eq!(spent.grant(5, 1), None);
        let mut m = Meter::start(&QuestionBudget {
            nodes: 10,
            wall: Some(Duration::from_secs(3600)),
        });
        assert!(!m.exhausted());
        assert!(m.deadline().is_some());
        assert_eq!(m.grant(50, 2), Some(5));
        m.spend(4, 2);
        assert_eq!(m.grant(50, 1), Some(2));
        m.spend(1, 2);
        assert!(m.exhausted());
        assert_eq!(Meter::unlimited().deadline(), None);
    }
}
