//! Why a proved-infeasible problem is infeasible: the objects that cannot
//! fit, or a minimal set of hard rules that conflict.

use super::backend::{Limits, Verdict};
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
    limits: &Limits,
    stats: &mut SolveStats,
) -> Result<Conflict, SynthError> {
    let base = BuildOptions {
        contact: opts.contact,
        rules: false,
        symmetry_breaking: opts.symmetry_breaking,
        redundant: opts.redundant,
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
    let m0 = Model::build(problem, rules, base);
    let mut e0 = Engine::new(&m0, opts.seed, false, None)?;
    let fit = e0.satisfy(limits);
    stats.nodes += e0.nodes();
    stats.conflicts += e0.conflicts();
    drop(e0);
    match fit {
        Verdict::Infeasible(_) => {
            return Ok(Conflict {
                objects_cannot_fit: true,
                ..Conflict::default()
            })
        }
        // Whether the objects fit is not known: blame nothing (every hard
        // rule may be harmless).
        Verdict::Unknown => {
            return Ok(Conflict {
                limit_struck: true,
                ..Conflict::default()
            })
        }
        Verdict::Solution(_) => {}
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
    let mg = Model::build(
        problem,
        rules,
        BuildOptions {
            rules: true,
            ..base
        },
    );
    let mut eg = Engine::new(&mg, opts.seed, true, None)?;
    // Deletion through the driver: every solve obeys the limits (a limit
    // keeps the rule, so the set stays conflicting, perhaps not minimal).
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
