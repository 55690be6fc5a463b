//! What `rccpack synth --report` writes and the words of the command
//! line's summary lines, shared by the command line, [`crate::task`] and
//! the Python package (`SynthResult.report_json()`).

use super::{Conflict, Resemblance, Status, SynthResult};
use crate::eval::RuleReport;

#[derive(serde::Serialize)]
struct Report<'a> {
    status: Status,
    score: Option<f64>,
    satisfied_weight: Option<f64>,
    total_weight: Option<f64>,
    time_ms: f64,
    nodes: u64,
    conflicts: u64,
    time_to_first_ms: Option<f64>,
    time_to_best_ms: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    conflict: Option<&'a Conflict>,
    rules: &'a [RuleReport],
    #[serde(skip_serializing_if = "Option::is_none")]
    resemblance: Option<Resemblance>,
    /// With `feasible`: a proven upper bound on the score of any layout.
    #[serde(skip_serializing_if = "Option::is_none")]
    score_bound: Option<f64>,
}

/// The JSON report of `rccpack synth --report` (pretty, ending in a
/// newline): status, score, weights, times, search counts, conflict and
/// per-rule results.
pub fn report_json(result: &SynthResult) -> String {
    let ev = result.evaluation.as_ref();
    let report = Report {
        status: result.status,
        score: ev.map(|e| e.score),
        satisfied_weight: ev.map(|e| e.satisfied_weight),
        total_weight: ev.map(|e| e.total_weight),
        time_ms: result.stats.time_ms,
        nodes: result.stats.nodes,
        conflicts: result.stats.conflicts,
        time_to_first_ms: result.stats.time_to_first_ms,
        time_to_best_ms: result.stats.time_to_best_ms,
        conflict: result.conflict.as_ref(),
        rules: ev.map(|e| e.rules.as_slice()).unwrap_or(&[]),
        resemblance: result.resemblance,
        // Only for `feasible` (for `optimal` it is the score): the
        // first-edition report of an optimal solve is unchanged.
        score_bound: result
            .score_bound
            .filter(|_| result.status == Status::Feasible),
    };
    serde_json::to_string_pretty(&report).expect("a report serialises") + "\n"
}

/// `, no layout scores above B (proven)` for a `feasible` summary line:
/// how far the layout returned may be from the optimum.
pub fn bound_text(result: &SynthResult) -> String {
    match (result.status, result.score_bound) {
        (Status::Feasible, Some(b)) => {
            format!(", no layout scores above {b:.6} (proven)")
        }
        _ => String::new(),
    }
}

/// Why a problem is infeasible, in words (after `infeasible: `): only
/// what was proven is blamed.
pub fn conflict_text(c: &Conflict) -> String {
    let mut parts = Vec::new();
    if c.objects_cannot_fit {
        parts.push("the objects cannot all be placed in the space without overlap".to_string());
    }
    if !c.hard_rules.is_empty() {
        parts.push(format!(
            "the hard rules {} cannot all hold together{}",
            c.hard_rules
                .iter()
                .map(|r| format!("`{r}`"))
                .collect::<Vec<_>>()
                .join(", "),
            if c.limit_struck {
                " (a limit struck before the conflict was explained: not every one of them is proven needed)"
            } else {
                ""
            }
        ));
    } else if c.limit_struck {
        parts.push("a limit struck before the conflict was explained".to_string());
    }
    if parts.is_empty() {
        parts.push("no layout keeps every hard rule".to_string());
    }
    parts.join("; ")
}

/// `, resemblance cost N (proven minimal)` for the summary lines; when
/// not proven, with the proven lower bound: `(not proven minimal; none
/// scoring as high costs below B)`.
pub fn resemblance_text(r: Option<Resemblance>) -> String {
    match r {
        None => String::new(),
        Some(r) if r.proven => format!(", resemblance cost {} (proven minimal)", r.cost),
        Some(r) => format!(
            ", resemblance cost {} (not proven minimal; none scoring as high costs below {})",
            r.cost, r.bound
        ),
    }
}
