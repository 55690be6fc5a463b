//! When to stop a computation: one value for every long computation of
//! the library (in the spirit of Pumpkin's `termination`).
//!
//! A [`Stop`] is a deadline, a budget of search nodes and a cancel flag,
//! each optional. Learning ([`crate::infer::LearnOptions::stop`]),
//! synthesis ([`crate::synth::SynthOptions::stop`]), sampling
//! ([`crate::sample::SampleOptions::stop`]) and questions
//! ([`crate::ask::ProbeOptions::stop`]) take one. Learning checks the
//! deadline and the flag before every random scene of its null model; the
//! searches check them while they run, and count their decisions against
//! the node budget. A task's pipeline ([`crate::task::run`]) hands one
//! `Stop` to learning and then synthesis: what learning used of the time
//! is gone for synthesis.
//!
//! The deadline is absolute: a `Stop` made with [`Stop::after`] counts
//! from when it is made (the command line makes one when a command
//! starts), not from when a search starts. Where a budget counts from the
//! start of each search (a sampled layout, one probe solve), the options
//! say so and keep it beside the `Stop`. A `Stop` is cheap to clone:
//! clones share the cancel flag, so setting it stops every computation
//! that holds one.
//!
//! ```
//! use rccpack::stop::Stop;
//! use std::time::Duration;
//!
//! let stop = Stop::after(Duration::from_secs(5))
//!     .with_nodes(100_000)
//!     .cancellable();
//! assert!(stop.reason().is_none());
//! stop.cancel();
//! assert_eq!(stop.reason(), Some(rccpack::stop::Reason::Cancelled));
//! ```

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Why a computation stopped early.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Reason {
    /// The deadline passed.
    Deadline,
    /// The cancel flag was set.
    Cancelled,
}

/// When to stop (see the module documentation). The default never stops.
#[derive(Debug, Clone, Default)]
pub struct Stop {
    deadline: Option<Instant>,
    nodes: Option<u64>,
    cancel: Option<Arc<AtomicBool>>,
}

impl Stop {
    /// Never stop early.
    pub fn never() -> Stop {
        Stop::default()
    }

    /// Stop `limit` from now (a limit too large for the clock: never).
    pub fn after(limit: Duration) -> Stop {
        Stop {
            deadline: Instant::now().checked_add(limit),
            ..Stop::default()
        }
    }

    /// Stop at `deadline`.
    pub fn at(deadline: Instant) -> Stop {
        Stop {
            deadline: Some(deadline),
            ..Stop::default()
        }
    }

    /// [`Stop::after`] when `limit` is given, else [`Stop::never`].
    pub fn within(limit: Option<Duration>) -> Stop {
        limit.map_or_else(Stop::never, Stop::after)
    }

    /// This stop with a budget of `nodes` search nodes (for the searches
    /// that count them).
    #[must_use]
    pub fn with_nodes(mut self, nodes: u64) -> Stop {
        self.nodes = Some(nodes);
        self
    }

    /// This stop with `flag` as its cancel flag (shared with whoever sets
    /// it).
    #[must_use]
    pub fn with_cancel(mut self, flag: Arc<AtomicBool>) -> Stop {
        self.cancel = Some(flag);
        self
    }

    /// This stop with a cancel flag when it has none; clones share it.
    #[must_use]
    pub fn cancellable(mut self) -> Stop {
        if self.cancel.is_none() {
            self.cancel = Some(Arc::new(AtomicBool::new(false)));
        }
        self
    }

    /// Set the cancel flag (nothing when there is none: see
    /// [`Stop::cancellable`]).
    pub fn cancel(&self) {
        if let Some(c) = &self.cancel {
            c.store(true, Ordering::SeqCst);
        }
    }

    /// The deadline, if any.
    pub fn deadline(&self) -> Option<Instant> {
        self.deadline
    }

    /// The time left until the deadline (zero once it passed), if any.
    pub fn remaining(&self) -> Option<Duration> {
        self.deadline
            .map(|d| d.saturating_duration_since(Instant::now()))
    }

    /// The node budget, if any.
    pub fn nodes(&self) -> Option<u64> {
        self.nodes
    }

    /// The cancel flag, if any.
    pub fn cancel_flag(&self) -> Option<&Arc<AtomicBool>> {
        self.cancel.as_ref()
    }

    /// This stop with `nodes` as its node budget (`None`: no budget).
    #[must_use]
    pub(crate) fn nodes_at_most(mut self, nodes: Option<u64>) -> Stop {
        self.nodes = nodes;
        self
    }

    /// This stop with `flag` as its cancel flag (`None`: no flag).
    #[must_use]
    pub(crate) fn cancel_with(mut self, flag: Option<Arc<AtomicBool>>) -> Stop {
        self.cancel = flag;
        self
    }

    /// This stop, also stopping at `deadline` (the earlier deadline wins).
    #[must_use]
    pub(crate) fn by(mut self, deadline: Option<Instant>) -> Stop {
        if let Some(d) = deadline {
            self.deadline = Some(self.deadline.map_or(d, |own| own.min(d)));
        }
        self
    }

    /// Whether the deadline has passed or the flag is set (the node budget
    /// is the searches' to check).
    pub(crate) fn expired(&self) -> bool {
        self.reason().is_some()
    }

    /// Why to stop now, if so: the flag is checked first.
    pub fn reason(&self) -> Option<Reason> {
        if self
            .cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::Relaxed))
        {
            return Some(Reason::Cancelled);
        }
        if self.deadline.is_some_and(|d| Instant::now() >= d) {
            return Some(Reason::Deadline);
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn never_stops_and_a_passed_deadline_stops() {
        assert_eq!(Stop::never().reason(), None);
        assert_eq!(Stop::within(None).remaining(), None);
        let s = Stop::after(Duration::ZERO);
        assert_eq!(s.reason(), Some(Reason::Deadline));
        assert_eq!(s.remaining(), Some(Duration::ZERO));
        // A limit the clock cannot hold never stops.
        assert_eq!(Stop::after(Duration::MAX).reason(), None);
    }

    #[test]
    fn the_earlier_deadline_wins_and_budgets_are_replaced() {
        let now = Instant::now();
        let later = now + Duration::from_secs(60);
        let s = Stop::at(later).by(Some(now));
        assert_eq!(s.deadline(), Some(now));
        assert_eq!(s.reason(), Some(Reason::Deadline));
        // A later deadline, or none, leaves the earlier one.
        assert_eq!(Stop::at(now).by(Some(later)).deadline(), Some(now));
        assert_eq!(Stop::at(now).by(None).deadline(), Some(now));
        assert_eq!(Stop::never().by(Some(later)).deadline(), Some(later));
        let s = Stop::never().with_nodes(5).nodes_at_most(Some(3));
        assert_eq!(s.nodes(), Some(3));
        assert_eq!(s.nodes_at_most(None).nodes(), None);
        // The flag is replaced, not shared with the old one.
        let a = Stop::never().cancellable();
        let b = a.clone().cancel_with(None);
        a.cancel();
        assert!(b.reason().is_none() && !b.expired());
        assert!(a.expired());
        let flag = Arc::new(AtomicBool::new(false));
        let c = Stop::never().cancel_with(Some(flag.clone()));
        flag.store(true, Ordering::SeqCst);
        assert_eq!(c.reason(), Some(Reason::Cancelled));
    }

    #[test]
    fn clones_share_the_cancel_flag() {
        let a = Stop::never().cancellable();
        let b = a.clone();
        a.cancel();
        assert_eq!(b.reason(), Some(Reason::Cancelled));
        // Without a flag, cancel does nothing.
        let c = Stop::never();
        c.cancel();
        assert_eq!(c.reason(), None);
    }
}
