//! Learning rules from demonstrations (docs/guide.md#learning, thesis §3.2).
//!
//! # Background
//!
//! A statement that every demonstration satisfies (a *candidate*) may be one
//! of the demonstrator's rules or may hold by chance. The chance is measured
//! on random scenes made from the demonstrations (the null model): a rule
//! that random scenes rarely satisfy but every demonstrated object does is
//! unlikely to be an accident. Learned rules are the candidates whose
//! posterior probability of *not* being intended is below a cutoff.
//!
//! # Practical
//!
//! [`learn`] runs the whole pipeline: [`templates::generate`] (when no
//! statements are given), `candidates::find_candidates`,
//! [`null_model::NullModel::count`] (parallel, deterministic for a seed) and
//! [`posterior::Posterior`] (log space). Truth values come from
//! [`crate::relations::ClassAtoms`] and [`crate::eval::CompiledFormula`], the
//! evaluator's own code. [`Learned::to_rcc`] writes the learned rules,
//! [`Learned::report_json`] every statement with its numbers.
//!
//! ```
//! use rccpack::{infer::{learn, LearnParams}, scene::scenes_from_json};
//! let demos = scenes_from_json(r#"[{"space":{"width":100,"height":100},"objects":[
//!   {"class":"B","x":0,"y":50,"width":10,"height":10},
//!   {"class":"R","x":0,"y":0,"width":10,"height":10}]}]"#).unwrap();
//! let params = LearnParams { samples: 50, ..LearnParams::default() };
//! let learned = learn(&demos, None, &params).unwrap();
//! assert!(learned.statements.iter().any(|s| s.name == "B_dr_n_R" && s.candidate));
//! ```

mod candidates;
mod checks;
pub(crate) mod english;
mod error;
mod learn;
mod learned;
mod null_model;
mod params;
mod posterior;
pub(crate) mod priors;
mod report;
mod slips;
pub mod templates;

pub(crate) use candidates::{find_candidates, find_exceptions};
pub use candidates::{Exception, Provenance};
pub(crate) use checks::check_demos;
pub use english::{reading, statement_reading};
// The bench crate's priors study counts rules implied by others with it.
#[doc(hidden)]
pub use english::rule_implies;
pub use error::InferError;
pub use learn::{candidate_flags, learn, learn_with, LearnOptions};
pub use learned::{ClassStats, Learned, StatementResult, StatementSource, Suspect};
pub use null_model::NullModel;
pub use params::{LearnParams, DEFAULT_SLIP_RATE, SUGGESTED_SLIP_RATE};
pub use posterior::Posterior;
pub use report::{Report, ReportParams, ReportStatement};
pub use slips::Slip;
pub use templates::Templates;

use crate::rules::{print_formula, Formula, Scope};

/// `Q A: ` for a scene-level rule about `subject`, `""` for a per-object one.
pub(crate) fn scope_prefix(scope: Scope, subject: &str) -> String {
    match scope {
        Scope::Each | Scope::Group => String::new(),
        Scope::Scene(q) => format!("{q} {subject}: "),
    }
}

/// A statement as `.rcc` text after `rule NAME:`: the formula, preceded by
/// `Q A: ` for a scene-level statement.
pub fn statement_text(scope: Scope, formula: &Formula) -> String {
    format!(
        "{}{}",
        scope_prefix(scope, formula.subject()),
        print_formula(formula)
    )
}
