//! What a solve returns: how it ended ([`Status`]), the layout with the
//! evaluator's verdict, the conflict of an infeasible problem, the second
//! objective's result and the search statistics.

use crate::eval::Evaluation;
use crate::scene::Scene;

/// How a solve ended (docs/guide.md#synthesis).
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
    /// Scene-level rules (docs/language.md#scene-rules) appear by name like the others.
    pub hard_rules: Vec<String>,
    /// A limit struck before the conflict was explained: nothing is blamed
    /// that was not proven. With `hard_rules` empty (and not
    /// `objects_cannot_fit`) no reason is known; otherwise those rules
    /// conflict together but were not all proven needed. Absent from JSON
    /// when false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub limit_struck: bool,
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
    /// With [`SynthOptions::like`](super::SynthOptions::like) and a layout: its resemblance cost.
    pub resemblance: Option<Resemblance>,
    /// An upper bound on the score of any layout, proven by the search
    /// (the score itself when `optimal`; for `feasible`, how far the layout
    /// returned may be from the optimum). Computed from the integer
    /// objective, so exact up to the weights' scaling (`weights`).
    pub score_bound: Option<f64>,
}

impl SynthResult {
    /// A result without a layout (`unknown`, `infeasible`).
    pub(super) fn without_layout(
        status: Status,
        conflict: Option<Conflict>,
        stats: SolveStats,
    ) -> Self {
        SynthResult {
            status,
            scene: None,
            evaluation: None,
            conflict,
            stats,
            resemblance: None,
            score_bound: None,
        }
    }
}

/// The second objective's result (the report's `resemblance`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Resemblance {
    /// The layout's resemblance cost ([`ResemblanceTarget::cost`](crate::resemblance::ResemblanceTarget::cost)).
    pub cost: u64,
    /// Whether the cost is proven minimal among the layouts whose docs/language.md#the-score
    /// numerator equals the returned layout's.
    pub proven: bool,
    /// A proven lower bound on the resemblance cost of every layout whose
    /// numerator is at least the returned layout's: `cost` when `proven`;
    /// otherwise how far the layout returned may be from the cheapest
    /// (the gap is `cost − bound`).
    pub bound: u64,
}
