//! What learning finds ([`Learned`]: every statement with its numbers, the
//! learned rules in order) and the `.rcc` text it writes.

use super::{LearnParams, Posterior, Provenance, Templates};
use crate::rules::{print_rule, Formula, Rule, RuleSet, Scope, Strength};
use serde::Serialize;
use std::fmt::Write as _;

/// Per subject class: object counts and the floor `ε`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClassStats {
    /// Class name.
    pub class: String,
    /// `n_A`: objects of the class over all demonstrations.
    pub demo_objects: u64,
    /// `N_A`: objects of the class over all random scenes.
    pub sample_objects: u64,
    /// `ε` for statements about this class.
    pub epsilon: f64,
}

/// Everything computed about one statement.
#[derive(Debug, Clone, PartialEq)]
pub struct StatementResult {
    /// Index in the statement set.
    pub index: usize,
    /// Name.
    pub name: String,
    /// Formula.
    pub formula: Formula,
    /// Per object, or about the whole scene (docs/language.md#scene-rules).
    pub scope: Scope,
    /// Subject class.
    pub subject: String,
    /// Whether every demonstration satisfies it.
    pub candidate: bool,
    /// For a non-candidate, the first demonstration (and object) breaking
    /// it.
    pub broken_by: Option<Provenance>,
    /// With a slip rate above 0: a statement broken in one demonstration
    /// only, that demonstration and the objects breaking it there; weighed
    /// like a candidate, with the slip rate per exception
    /// (docs/guide.md#slips).
    pub exception: Option<super::candidates::Exception>,
    /// `n`: subject objects over the demonstrations; for a scene-level
    /// statement the number of demonstrations `d` (docs/guide.md#learning).
    pub n: u64,
    /// Candidates only: subject objects of the random scenes satisfying it;
    /// for a scene-level statement the random scenes in which it holds.
    pub satisfied: Option<u64>,
    /// Candidates only: chance rate `q` (per object, or per scene for a
    /// scene-level statement).
    pub q: Option<f64>,
    /// Candidates only: `p`, `log10 L`, `log10 P`.
    pub posterior: Option<Posterior>,
    /// Whether it is learned.
    pub learned: bool,
    /// For a learned rule, a stronger learned rule that implies it.
    pub implied_by: Option<String>,
    /// One-line English reading.
    pub english: String,
    /// With priors ([`learn_with`](super::learn_with)): the statement's prior and
    /// where it came from; `None` without.
    pub prior: Option<crate::infer::priors::StatementPrior>,
}

/// Where the statements came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StatementSource {
    /// A statement file.
    Given,
    /// The template set (docs/guide.md#learning).
    Templates,
}

/// The result of [`learn`](super::learn).
#[derive(Debug, Clone, PartialEq)]
pub struct Learned {
    /// The parameters used.
    pub params: LearnParams,
    /// Number of demonstrations.
    pub demos: usize,
    /// Where the statements came from.
    pub source: StatementSource,
    /// Per class that is the subject of some statement, in class order.
    pub classes: Vec<ClassStats>,
    /// `ε_s` for scene-level statements: `0.5 / d_r`, or the fixed ε.
    pub scene_epsilon: f64,
    /// Every statement, in statement order.
    pub statements: Vec<StatementResult>,
    /// Indices into `statements` of the learned rules, strongest first
    /// (smallest posterior; ties by statement order).
    pub order: Vec<usize>,
    /// With priors: the library's summary and the statements left out.
    pub priors: Option<crate::infer::priors::PriorsUsed>,
    /// The demonstrations' blocks judged slips (docs/guide.md#slips), at
    /// most one per demonstration; none at slip rate 0.
    pub slips: Vec<super::Slip>,
}

/// Format a number for a comment: 4 significant digits.
fn short(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e4).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        let t = format!("{v:.digits$}");
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        }
    } else {
        format!("{v:.3e}")
    }
}

/// A demonstration's block that is likelier a slip than meant, breaking
/// rules the other demonstrations keep (docs/guide.md#slips).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Suspect {
    /// The demonstration (0-based, as in the demonstrations file).
    pub demonstration: usize,
    /// The block's id.
    pub object: String,
    /// The learned rules it breaks, strongest first.
    pub breaks: Vec<String>,
}

impl Learned {
    /// The suspects: each slip ([`Learned::slips`]) with the learned rules
    /// it breaks (strongest first), the likeliest slip first (then by
    /// demonstration); a slip that breaks no learned rule is left out.
    pub fn suspects(&self) -> Vec<Suspect> {
        let mut slips: Vec<&super::Slip> = self.slips.iter().collect();
        slips.sort_by(|a, b| {
            b.log10_odds
                .total_cmp(&a.log10_odds)
                .then(a.demonstration.cmp(&b.demonstration))
        });
        slips
            .into_iter()
            .map(|slip| Suspect {
                demonstration: slip.demonstration,
                object: slip.object.clone(),
                breaks: self
                    .order
                    .iter()
                    .map(|&k| &self.statements[k])
                    .filter(|st| {
                        st.exception.as_ref().is_some_and(|e| {
                            e.demo == slip.demonstration && e.objects.contains(&slip.object)
                        })
                    })
                    .map(|st| st.name.clone())
                    .collect(),
            })
            .filter(|s| !s.breaks.is_empty())
            .collect()
    }

    /// The learned rules, strongest first, each with `p P` and comments (the
    /// English reading, `q`, `n`, `log10 L`, and the stronger rule implying
    /// it, if any).
    pub fn rules(&self) -> RuleSet {
        RuleSet::new(
            self.order
                .iter()
                .map(|&k| {
                    let s = &self.statements[k];
                    let post = s.posterior.expect("learned rules are candidates");
                    let st = self
                        .classes
                        .iter()
                        .find(|c| c.class == s.subject)
                        .expect("subject stats");
                    let numbers = match s.scope {
                        Scope::Each => format!(
                            "q = {} ({} of {} {} objects in {} random scenes), n = {}, log10 L = {}",
                            short(s.q.unwrap_or(0.0)),
                            s.satisfied.unwrap_or(0),
                            st.sample_objects,
                            s.subject,
                            self.params.samples,
                            s.n,
                            short(post.log10_likelihood)
                        ),
                        Scope::Scene(_) | Scope::Group => format!(
                            "q = {} (holds in {} of {} random scenes), n = {} demonstrations, log10 L = {}",
                            short(s.q.unwrap_or(0.0)),
                            s.satisfied.unwrap_or(0),
                            self.params.samples,
                            s.n,
                            short(post.log10_likelihood)
                        ),
                    };
                    let mut comments = vec![s.english.clone(), numbers];
                    if let Some(e) = &s.exception {
                        comments.push(format!(
                            "kept by {} of {} demonstrations; demonstration {} breaks it ({})",
                            self.demos - 1,
                            self.demos,
                            e.demo,
                            e.objects.join(", ")
                        ));
                    }
                    if let Some(by) = &s.implied_by {
                        comments.push(format!("implied by {by}"));
                    }
                    Rule {
                        name: s.name.clone(),
                        strength: Strength::P(post.written()),
                        scope: s.scope,
                        formula: s.formula.clone(),
                        comments,
                        origin: None,
                    }
                })
                .collect(),
        )
    }

    /// The `.rcc` text: a header comment with the parameters, then
    /// [`Learned::rules`].
    pub fn to_rcc(&self) -> String {
        let mut s = self.rcc_header();
        for r in &self.rules().rules {
            s.push_str(&print_rule(r));
        }
        s
    }

    /// The header comment of [`Learned::to_rcc`] (parameters, ε), ending in
    /// a blank line.
    pub fn rcc_header(&self) -> String {
        let p = &self.params;
        let mut s = String::new();
        let candidates = self.statements.iter().filter(|s| s.candidate).count();
        let _ = writeln!(
            s,
            "# learned by rccpack from {} demonstrations: {} of {} candidates out of {} statements ({})",
            self.demos,
            self.order.len(),
            candidates,
            self.statements.len(),
            match (self.source, self.params.templates) {
                (StatementSource::Given, _) => "given",
                (StatementSource::Templates, Templates::First) => "templates",
                (StatementSource::Templates, Templates::Second) => "templates, second edition",
                (StatementSource::Templates, Templates::Third) => "templates, third edition",
            }
        );
        let _ = writeln!(
            s,
            "# samples {}, seed {}, cutoff {}, prior {}, contact {}",
            p.samples,
            p.seed,
            crate::limits::number(p.cutoff),
            crate::limits::number(p.prior),
            p.contact
        );
        let mut eps: Vec<String> = self
            .classes
            .iter()
            .map(|c| format!("{} {}", c.class, short(c.epsilon)))
            .collect();
        if self.statements.iter().any(|s| s.scope.is_scene()) {
            eps.push(format!("scene-level {}", short(self.scene_epsilon)));
        }
        let _ = writeln!(s, "# epsilon: {}", eps.join(", "));
        if let Some(line) = self.priors_header() {
            let _ = writeln!(s, "{line}");
        }
        s.push('\n');
        s
    }
}
