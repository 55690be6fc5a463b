//! Benchmarks and studies: the thesis runtime study (`rccpack-bench
//! thesis`), its tables and its chart; realistic tasks (`rccpack-bench
//! tasks`).
//!
//! * [`pool`] — the pilot rules and the template statements
//!   (docs/guide.md#learning), built through the AST;
//! * [`thesis`] — the seeded study generator and runner (solver injected, so
//!   tests can run it on any engine);
//! * [`chart`] — the PNG chart (plotters, embedded font);
//! * [`peers`] — other solvers (OR-Tools CP-SAT, MiniZinc/Gecode) run on
//!   the emitted model, for side-by-side measurement;
//! * [`tasks`] — realistic tasks: demonstrations that follow a hidden
//!   style, rules learned from them, problems larger than the
//!   demonstrations, and the bundled example scaled;
//! * [`noisy`] — demonstrations as recorded (`rccpack-bench noisy`):
//!   jitter, a slipped block, both, rough positions, learned and compared
//!   with the exact demonstrations' rules;
//! * [`priors`] — priors learned across tasks on a seeded population of
//!   demonstrators (`rccpack-bench priors`): uniform, learned, shuffled and
//!   true-frequency priors on held-out tasks.

pub mod chart;
pub mod noisy;
pub mod peers;
pub mod pool;
pub mod priors;
pub mod sample;
pub mod tasks;
pub mod thesis;

use rccpack::relations::Contact;
use rccpack::rules::RuleSet;
use rccpack::scene::Scene;
use rccpack::synth::{SynthError, SynthOptions, SynthResult};

/// A solver: the engine's `synthesize` or a stand-in.
pub type SolveFn<'a> =
    &'a (dyn Fn(&Scene, &RuleSet, &SynthOptions) -> Result<SynthResult, SynthError> + Sync);
/// A solution checker `(problem, solution, rules, contact)`.
pub type VerifyFn<'a> =
    &'a (dyn Fn(&Scene, &Scene, &RuleSet, Contact) -> Result<(), String> + Sync);

/// The solver and checker a benchmark runs with (injectable: tests add
/// checks of their own).
#[derive(Clone, Copy)]
pub struct Solver<'a> {
    /// Solves one problem.
    pub solve: SolveFn<'a>,
    /// Checks one solution.
    pub verify: VerifyFn<'a>,
}

/// Why a peer solver or a chart failed; the message says what to install
/// or what went wrong.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum BenchError {
    /// A peer solver cannot run here (missing script, interpreter or
    /// package).
    #[error("{0}")]
    PeerUnavailable(String),
    /// A peer solver ran and failed, timed out or answered nonsense.
    #[error("{0}")]
    PeerFailed(String),
    /// A chart could not be drawn or written.
    #[error("{0}")]
    Chart(String),
}
