//! The JSON report of `rccpack learn --report`: the parameters, the class
//! counts and every statement with its numbers.

use super::{statement_text, ClassStats, Learned, Provenance, StatementSource, Templates};
use crate::rules::Scope;
use serde::Serialize;

impl Learned {
    /// The report: parameters, class counts and every statement.
    pub fn report(&self) -> Report {
        Report {
            parameters: ReportParams {
                samples: self.params.samples,
                cutoff: self.params.cutoff,
                prior: self.params.prior,
                epsilon: self.params.epsilon,
                seed: self.params.seed,
                contact: self.params.contact.to_string(),
                templates: match (self.source, self.params.templates) {
                    (StatementSource::Templates, Templates::Second) => Some("second".into()),
                    (StatementSource::Templates, Templates::Third) => Some("third".into()),
                    _ => None,
                },
            },
            demonstrations: self.demos,
            source: self.source,
            classes: self.classes.clone(),
            scene_epsilon: self
                .statements
                .iter()
                .any(|s| s.scope.is_scene())
                .then_some(self.scene_epsilon),
            priors: self.priors.clone(),
            statements: self
                .statements
                .iter()
                .map(|s| ReportStatement {
                    name: s.name.clone(),
                    formula: statement_text(s.scope, &s.formula),
                    scope: match s.scope {
                        Scope::Each => None,
                        Scope::Scene(q) => Some(q.to_string()),
                        Scope::Group => Some("group".to_string()),
                    },
                    subject: s.subject.clone(),
                    english: s.english.clone(),
                    candidate: s.candidate,
                    broken_by: s.broken_by.clone(),
                    n: s.n,
                    satisfied: s.satisfied,
                    q: s.q,
                    p: s.posterior.map(|p| p.p),
                    log10_likelihood: s.posterior.map(|p| p.log10_likelihood),
                    log10_posterior: s.posterior.map(|p| p.log10_posterior),
                    posterior: s.posterior.map(|p| p.written()),
                    learned: s.learned,
                    rank: self.order.iter().position(|&k| k == s.index),
                    implied_by: s.implied_by.clone(),
                    prior: s.prior.clone(),
                    exception: s.exception.clone(),
                })
                .collect(),
            suspects: self.suspects(),
        }
    }

    /// [`Learned::report`] as pretty JSON.
    pub fn report_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(&self.report()).expect("report serialises");
        s.push('\n');
        s
    }
}

/// The JSON report of `rccpack learn --report`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Parameters used.
    pub parameters: ReportParams,
    /// Number of demonstrations.
    pub demonstrations: usize,
    /// `given` or `templates`.
    pub source: StatementSource,
    /// Per subject class: `n_A`, `N_A`, `ε`.
    pub classes: Vec<ClassStats>,
    /// `ε_s` of the scene-level statements (docs/guide.md#learning); absent when there are
    /// none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene_epsilon: Option<f64>,
    /// With priors: the library's summary and the statements left out.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub priors: Option<crate::infer::priors::PriorsUsed>,
    /// Every statement, in statement order.
    pub statements: Vec<ReportStatement>,
    /// With a slip rate: the objects that break rules the other
    /// demonstrations keep (docs/guide.md#slips); absent when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub suspects: Vec<super::learned::Suspect>,
}

/// Parameters in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportParams {
    /// Random scenes.
    pub samples: usize,
    /// Cutoff.
    pub cutoff: f64,
    /// Prior.
    pub prior: f64,
    /// Fixed ε, or null for `0.5 / N_A` per class.
    pub epsilon: Option<f64>,
    /// Seed.
    pub seed: u64,
    /// `point` or `edge`.
    pub contact: String,
    /// `second` when the second-edition templates were used; absent for
    /// the first edition's templates and for given statements.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub templates: Option<String>,
}

/// One statement in the report. Chance numbers are null for non-candidates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportStatement {
    /// Name.
    pub name: String,
    /// The statement as `.rcc` text after `rule NAME:` (with `Q A: ` for a
    /// scene-level statement).
    pub formula: String,
    /// The subject quantifier of a scene-level statement (`some`, `no`,
    /// `at least 2`, …); absent for a per-object statement.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scope: Option<String>,
    /// Subject class.
    pub subject: String,
    /// English reading.
    pub english: String,
    /// Satisfied by every demonstration.
    pub candidate: bool,
    /// First demonstration and object breaking it (non-candidates).
    pub broken_by: Option<Provenance>,
    /// `n`: subject objects over the demonstrations (scene-level: the
    /// number of demonstrations).
    pub n: u64,
    /// Subject objects of the random scenes that satisfy it (scene-level:
    /// random scenes in which it holds).
    pub satisfied: Option<u64>,
    /// Chance rate `q`.
    pub q: Option<f64>,
    /// `p = max(ε, q)` (scene-level: `max(ε_s, q)`).
    pub p: Option<f64>,
    /// `log10 L`.
    pub log10_likelihood: Option<f64>,
    /// `log10 P`.
    pub log10_posterior: Option<f64>,
    /// `P` as written (floored at 1e-300).
    pub posterior: Option<f64>,
    /// Learned at the cutoff.
    pub learned: bool,
    /// Position among learned rules (0 = strongest).
    pub rank: Option<usize>,
    /// A stronger learned rule implying this one.
    pub implied_by: Option<String>,
    /// With priors: the statement's prior and its source.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prior: Option<crate::infer::priors::StatementPrior>,
    /// With a slip rate: broken in one demonstration only, that
    /// demonstration and the objects breaking it there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exception: Option<super::Exception>,
}
