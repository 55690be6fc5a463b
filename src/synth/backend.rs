//! The seam between the optimisation [`driver`](super::driver) and an
//! engine that can solve a [`Model`](super::model::Model).
//!
//! # Background
//!
//! Every procedure of synthesis — maximise the score, then minimise the
//! resemblance cost, shrink a conflict to a minimal set of hard rules, ask
//! whether the held rules imply another — is a sequence of satisfiability
//! calls *under assumptions* on one loaded model, plus facts learnt along the
//! way ("the objective is at most 41"). None of it depends on how the
//! engine propagates or branches. So the procedures live once, in the
//! driver, against the small [`Backend`] trait; the Pumpkin encoding lives
//! in [`engine`](super::engine) behind it.
//!
//! # Practical
//!
//! - [`Backend::solve`] answers one call. A limit that stops it gives
//!   [`Verdict::Unknown`]; a backend may refuse further calls afterwards (it
//!   answers `Unknown` again — Pumpkin 0.5 cannot resume after a stop), so
//!   the limits are over the backend's life.
//! - An infeasible call carries a [`Core`]: [`Core::Unknown`] when the
//!   backend does not say which assumptions are to blame, and
//!   [`Core::Rules`] with the guilty hard-rule assumptions otherwise. An
//!   *empty* `Core::Rules` is the strongest answer: the model is infeasible
//!   whatever is assumed. "No core" and "empty core" are different answers,
//!   and the driver treats them differently (no core: shrink by deletion;
//!   empty core: stop at once).
//! - Solutions are grid values, one per model variable
//!   ([`Model::vars`](super::model::Model::vars) order).
//!
//! # How to extend
//!
//! A new engine implements [`Backend`] for a loaded model; the driver's
//! tests (`driver::tests`, against a mock backend) state what each answer
//! must mean, and the synthesis differential tests run it against brute
//! force.

pub(crate) use crate::stop::Stop;

/// One assumption of a call: holds for this call only.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Assumption {
    /// The objective (the integer score numerator) is at least this.
    ObjectiveAtLeast(i64),
    /// The resemblance cost is at most this.
    CostAtMost(u64),
    /// Hard rule `i` (index into `Model::hard`) holds. Only a backend
    /// loaded with guarded hard rules accepts it.
    Rule(usize),
}

/// A fact added for good: every later call obeys it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Fact {
    /// The objective is at most this (after a refutation of more).
    ObjectiveAtMost(i64),
    /// The objective is at least this (the score is never traded away).
    ObjectiveAtLeast(i64),
    /// The resemblance cost is at least this (after a refutation of less).
    CostAtLeast(u64),
}

/// Which assumptions an infeasible call is to blame on.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Core {
    /// The backend does not say.
    Unknown,
    /// These `Rule` assumptions (hard-rule indices) are enough to make the
    /// call infeasible; empty: infeasible whatever is assumed.
    Rules(Vec<usize>),
}

/// The answer to one call.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Verdict {
    /// A solution: grid values per model variable.
    Solution(Vec<i64>),
    /// Proved impossible under the assumptions.
    Infeasible(Core),
    /// A limit stopped the search.
    Unknown,
}

/// An engine holding one model.
pub(crate) trait Backend {
    /// Solve under `assumptions` within `limits` (its node budget counts the
    /// decisions over the backend's life).
    fn solve(&mut self, assumptions: &[Assumption], limits: &Stop) -> Verdict;
    /// Add a fact for every later call.
    fn add(&mut self, fact: Fact);
    /// The largest objective value not yet excluded at the root (`None`:
    /// the backend has no objective).
    fn objective_bound(&self) -> Option<i64>;
    /// The smallest resemblance cost not yet excluded at the root (`None`:
    /// no second objective).
    fn cost_bound(&self) -> Option<u64>;
    /// Told once a first solution exists (a backend may change its search).
    fn found_first(&mut self) {}
    /// Told when the second phase (minimising the resemblance cost)
    /// starts: a backend may post reasoning that only the cost needs.
    fn start_cost_phase(&mut self) {}

    /// Try these values first (one per model variable, `None`: no
    /// preference) until the next solution: a warm start or the incumbent
    /// of a neighbourhood. A value-ordering hint only: it changes which
    /// solution is found first, never what is feasible or optimal.
    fn hint(&mut self, _values: &[Option<i64>]) {}
    /// Decisions so far.
    fn nodes(&self) -> u64;

    // What sampling and the question checks ask of an engine beyond the
    // driver's procedures (`crate::sample`, `crate::ask`'s checker).

    /// [`Backend::hint`] as `(variable, value)` pairs tried in this order
    /// (sampling draws the order at random).
    fn hint_in_order(&mut self, hints: &[(usize, i64)]);
    /// Forbid this solution (one value per model variable) in every later
    /// call: sampling's next layout differs from every one before.
    fn exclude(&mut self, values: &[i64]);
    /// After the hint, branch at random (a seeded choice of variable and
    /// value) instead of by the engine's own heuristic.
    fn random_search(&mut self);
    /// Leave a greedy first phase, if the backend has one, after this many
    /// conflicts without a solution (checks are mostly proofs).
    fn leave_greedy_after(&mut self, _conflicts: u64) {}
}

/// Load `model` into the engine (the one place outside the engine's
/// folder that names it): `guarded` hard rules take [`Assumption::Rule`],
/// `coefs` is the objective (`None`: satisfaction only), `like` the
/// resemblance terms of the second objective (empty: none). `Ok(None)`:
/// `stop` struck while it was built.
pub(crate) fn load(
    model: &super::model::Model,
    seed: u64,
    guarded: bool,
    coefs: Option<&[i64]>,
    like: &[super::resemblance_terms::ResemblanceTerm],
    stop: &Stop,
) -> Result<Option<Box<dyn Backend>>, super::SynthError> {
    let engine =
        super::engine::Engine::with_resemblance_stop(model, seed, guarded, coefs, like, stop)?;
    Ok(engine.map(|e| Box::new(e) as Box<dyn Backend>))
}
