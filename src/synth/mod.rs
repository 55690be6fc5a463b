//! Synthesis (SPEC §9): place every unplaced object on the grid so that hard
//! rules hold and the §6 numerator is as large as possible.
//!
//! This file fixes the public API; the model and engine live in submodules.

use crate::eval::Evaluation;
use crate::relations::Contact;
use crate::scene::Scene;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Duration;

pub mod brute_force;

/// Limits and switches for one solve.
#[derive(Debug, Clone)]
pub struct SynthOptions {
    /// How EC decides that two sides touch.
    pub contact: Contact,
    /// Stop after this long and return the best layout found.
    pub time_limit: Option<Duration>,
    /// Stop after this many search nodes (decisions).
    pub node_limit: Option<u64>,
    /// Seed for any randomised choice; same seed and limits → same layout.
    pub seed: u64,
    /// Break symmetry between interchangeable objects (same class and size).
    pub symmetry_breaking: bool,
    /// Post redundant area reasoning.
    pub redundant: bool,
    /// Set to true (e.g. from a Ctrl-C handler) to stop the search.
    pub cancel: Option<Arc<AtomicBool>>,
}

impl Default for SynthOptions {
    fn default() -> Self {
        SynthOptions {
            contact: Contact::Point,
            time_limit: None,
            node_limit: None,
            seed: 0,
            symmetry_breaking: true,
            redundant: true,
            cancel: None,
        }
    }
}

/// How a solve ended (SPEC §9).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Proved optimal.
    Optimal,
    /// A limit stopped the search; the layout is the best found.
    Feasible,
    /// No placement meets the hard requirements.
    Infeasible,
    /// A limit stopped the search before any solution.
    Unknown,
}

/// Why a problem is infeasible: a minimal conflicting set.
#[derive(Debug, Clone, PartialEq, Eq, Default, serde::Serialize)]
pub struct Conflict {
    /// The objects cannot all be placed in the space without overlap, even
    /// with no rule at all.
    pub objects_cannot_fit: bool,
    /// Names of hard rules whose conjunction (with the geometry) is
    /// impossible; minimal: dropping any one makes the rest satisfiable.
    pub hard_rules: Vec<String>,
}

/// Search statistics.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct SolveStats {
    /// Decisions taken.
    pub nodes: u64,
    /// Conflicts met.
    pub conflicts: u64,
    /// Wall time of the whole solve, in milliseconds.
    pub time_ms: f64,
    /// Time to the first solution, if any.
    pub time_to_first_ms: Option<f64>,
    /// Time to the best solution, if any.
    pub time_to_best_ms: Option<f64>,
}

/// The result of `synthesize`.
#[derive(Debug, Clone)]
pub struct SynthResult {
    /// How the search ended.
    pub status: Status,
    /// The complete scene (for `optimal` and `feasible`).
    pub scene: Option<Scene>,
    /// The evaluator's verdict on `scene` (the reported score comes from
    /// here, never from the solver).
    pub evaluation: Option<Evaluation>,
    /// For `infeasible`: what conflicts.
    pub conflict: Option<Conflict>,
    /// Statistics.
    pub stats: SolveStats,
}

/// Errors that are the input's fault (not infeasibility).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SynthError {
    /// The problem scene is not usable for synthesis.
    #[error("{0}")]
    BadProblem(String),
}
