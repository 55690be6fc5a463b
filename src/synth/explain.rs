//! Why a proved-infeasible problem is infeasible: the objects that cannot
//! fit, or a minimal set of hard rules that conflict.

use super::backend::{Stop, Verdict};
use super::engine::Engine;
use super::model::{BuildOptions, Model};
use super::{capacity, driver, Conflict, SolveStats, SynthError, SynthOptions};
use crate::rules::RuleSet;
use crate::scene::Scene;

/// Why a proved-infeasible problem is infeasible: first whether the objects
/// fit at all, then a minimal set of hard rules (core under one assumption
/// per hard rule, shrunk by deletion). When a limit interrupts, the set is
/// conflicting but perhaps not minimal.
pub(super) fn explain(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
    limits: &Stop,
    stats: &mut SolveStats,
) -> Result<Conflict, SynthError> {
    let job = Explaining {
        problem,
        rules,
        opts,
        limits,
    };
    if capacity::cannot_fit(problem) {
        return Ok(Conflict {
            objects_cannot_fit: true,
            ..Conflict::default()
        });
    }
    // Building an engine does not look at the clock: past the deadline,
    // build none (the time limit would otherwise be overshot by up to two
    // engine builds) and blame nothing.
    if limits.expired() {
        return Ok(Conflict {
            limit_struck: true,
            ..Conflict::default()
        });
    }
    if let Some(conflict) = job.unless_objects_fit(stats)? {
        return Ok(conflict);
    }
    // The objects fit, so the hard rules together conflict (the main solve
    // proved it); past the deadline they are named together, unshrunk.
    if limits.expired() {
        return Ok(Conflict {
            hard_rules: rules
                .rules
                .iter()
                .filter(|r| r.strength.is_hard())
                .map(|r| r.name.clone())
                .collect(),
            limit_struck: true,
            ..Conflict::default()
        });
    }
    job.shrink_hard_rules(stats)
}

/// One explanation's inputs, shared by its two steps.
struct Explaining<'a> {
    problem: &'a Scene,
    rules: &'a RuleSet,
    opts: &'a SynthOptions,
    limits: &'a Stop,
}

impl Explaining<'_> {
    /// The model options: the solve's, with or without the rules.
    fn build(&self, rules: bool) -> BuildOptions {
        BuildOptions {
            contact: self.opts.contact,
            rules,
            symmetry_breaking: self.opts.symmetry_breaking,
            redundant: self.opts.redundant,
            tuning: self.opts.tuning,
        }
    }

    /// Solve without the rules: `None` when the objects fit, else the
    /// explanation — they cannot fit, or a limit struck before it was known
    /// (then nothing is blamed: every hard rule may be harmless).
    fn unless_objects_fit(&self, stats: &mut SolveStats) -> Result<Option<Conflict>, SynthError> {
        let m0 = Model::build(self.problem, self.rules, self.build(false));
        let mut e0 = Engine::new(&m0, self.opts.seed, false, None)?;
        let fit = e0.satisfy(self.limits);
        stats.nodes += e0.nodes();
        stats.conflicts += e0.conflicts();
        drop(e0);
        Ok(match fit {
            Verdict::Infeasible(_) => Some(Conflict {
                objects_cannot_fit: true,
                ..Conflict::default()
            }),
            Verdict::Unknown => Some(Conflict {
                limit_struck: true,
                ..Conflict::default()
            }),
            Verdict::Solution(_) => None,
        })
    }

    /// A minimal set of conflicting hard rules, by deletion through the driver
    /// on a model with the rules: every solve obeys the limits (a limit keeps
    /// the rule, so the set stays conflicting, perhaps not minimal).
    fn shrink_hard_rules(&self, stats: &mut SolveStats) -> Result<Conflict, SynthError> {
        let mg = Model::build(self.problem, self.rules, self.build(true));
        let mut eg = Engine::new(&mg, self.opts.seed, true, None)?;
        let all: Vec<usize> = (0..mg.hard.len()).collect();
        let (core, minimal) = driver::shrink_conflict(&mut eg, &all, self.limits);
        stats.nodes += eg.nodes();
        stats.conflicts += eg.conflicts();
        Ok(Conflict {
            objects_cannot_fit: false,
            hard_rules: core
                .iter()
                .map(|&k| self.rules.rules[mg.hard[k].rule].name.clone())
                .collect(),
            limit_struck: !minimal || core.is_empty(),
        })
    }
}
