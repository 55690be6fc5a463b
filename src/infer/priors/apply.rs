//! Priors applied to one learning run ([`crate::infer::learn_with`]).

use super::kind::Kind;
use super::{Priors, StatementPrior};
use crate::infer::templates::{self, TemplateOrigin};
use crate::infer::Learned;
use crate::rules::RuleSet;
use crate::scene::Scene;
use serde::Serialize;

/// A statement left out because its kind is ruled out.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RuledOut {
    /// The statement's name.
    pub name: String,
    /// Its kind.
    pub kind: String,
    /// The node of the priors file that ruled it out.
    pub from: String,
}

/// What a learning run used: the library's size and hash, and the
/// statements left out.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PriorsUsed {
    /// Tasks in the library.
    pub tasks: u64,
    /// The priors file's content hash.
    pub hash: String,
    /// Statements left out (ruled-out kinds), in statement order.
    pub ruled_out: Vec<RuledOut>,
}

/// The generated statements minus the ruled-out ones, each remaining
/// statement's prior, and the ones left out.
pub(crate) fn generated(
    priors: &Priors,
    demos: &[Scene],
    set: RuleSet,
    origins: &[TemplateOrigin],
) -> (RuleSet, Vec<StatementPrior>, Vec<RuledOut>) {
    let classes = templates::demo_classes(demos);
    let movable = |c: &str| classes.iter().any(|(n, m)| n == c && *m);
    let mut rules = Vec::with_capacity(set.rules.len());
    let mut used = Vec::with_capacity(set.rules.len());
    let mut out = Vec::new();
    for (rule, origin) in set.rules.into_iter().zip(origins) {
        let kind = Kind::of(origin, movable);
        let entry = priors.lookup(&kind);
        if entry.ruled_out {
            out.push(RuledOut {
                name: rule.name,
                kind: kind.key(),
                from: entry.kind.clone(),
            });
            continue;
        }
        used.push(StatementPrior {
            prior: entry.prior,
            kind: Some(kind.key()),
            from: Some(entry.kind.clone()),
        });
        rules.push(rule);
    }
    (RuleSet::new(rules), used, out)
}

/// Given statements have no kind: the uniform prior `1 − pi`.
pub(crate) fn given(set: &RuleSet, pi: f64) -> Vec<StatementPrior> {
    set.rules
        .iter()
        .map(|_| StatementPrior {
            prior: 1.0 - pi,
            kind: None,
            from: None,
        })
        .collect()
}

pub(crate) fn summary(priors: &Priors, ruled_out: Vec<RuledOut>) -> PriorsUsed {
    PriorsUsed {
        tasks: priors.tasks,
        hash: priors.hash_text(),
        ruled_out,
    }
}

impl Learned {
    /// The `.rcc` header line naming the priors, when they changed
    /// anything (a statement left out, or a prior other than the uniform
    /// one); `None` otherwise, so a uniform priors file writes the same
    /// bytes as none.
    pub fn priors_header(&self) -> Option<String> {
        let used = self.priors.as_ref()?;
        let uniform = 1.0 - self.params.prior;
        let changed = self
            .statements
            .iter()
            .filter_map(|s| s.prior.as_ref())
            .filter(|p| p.prior != uniform)
            .count();
        if used.ruled_out.is_empty() && changed == 0 {
            return None;
        }
        Some(format!(
            "# priors {} from {} tasks: {} statements with a prior of their kind, {} left out (kind ruled out)",
            used.hash,
            used.tasks,
            changed,
            used.ruled_out.len()
        ))
    }
}
