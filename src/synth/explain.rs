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
    let base = BuildOptions {
        contact: opts.contact,
        rules: false,
        symmetry_breaking: opts.symmetry_breaking,
        redundant: opts.redundant,
        tuning: opts.tuning,
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
    if let Some(conflict) = unless_objects_fit(problem, rules, base, opts, limits, stats)? {
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
    shrink_hard_rules(problem, rules, base, opts, limits, stats)
}

/// Solve without the rules: `None` when the objects fit, else the
/// explanation — they cannot fit, or a limit struck before it was known
/// (then nothing is blamed: every hard rule may be harmless).
fn unless_objects_fit(
    problem: &Scene,
    rules: &RuleSet,
    base: BuildOptions,
    opts: &SynthOptions,
    limits: &Stop,
    stats: &mut SolveStats,
) -> Result<Option<Conflict>, SynthError> {
    let m0 = Model::build(problem, rules, base);
    let mut e0 = Engine::new(&m0, opts.seed, false, None)?;
    let fit = e0.satisfy(limits);
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
fn shrink_hard_rules(
    problem: &Scene,
    rules: &RuleSet,
    base: BuildOptions,
    opts: &SynthOptions,
    limits: &Stop,
    stats: &mut SolveStats,
) -> Result<Conflict, SynthError> {
    let mg = Model::build(
        problem,
        rules,
        BuildOptions {
            rules: true,
            ..base
        },
    );
    let mut eg = Engine::new(&mg, opts.seed, true, None)?;
    let all: Vec<usize> = (0..mg.hard.len()).collect();
    let (core, minimal) = driver::shrink_conflict(&mut eg, &all, limits);
    stats.nodes += eg.nodes();
    stats.conflicts += eg.conflicts();
    Ok(Conflict {
        objects_cannot_fit: false,
        hard_rules: core
            .iter()
            .map(|&k| rules.rules[mg.hard[k].rule].name.clone())
            .collect(),
        limit_struck: !minimal || core.is_empty(),
    })
}
