//! Objects that turn (docs/guide.md#objects-that-turn). Without `like`
//! ([`synthesize_model`]): a short probe with nothing turned, then the one
//! model with an orientation variable per turnable object
//! (`model/mod.rs`, "Objects that turn"). With `like` (whose resemblance
//! costs assume each object's footprint), or `RCCPACK_TURNS=enumerate`
//! ([`synthesize_turning`]): a problem whose unplaced objects may lie
//! turned by 90° is solved as one exact solve per *orientation choice*,
//! and the best layout over the choices is the answer, as follows.
//!
//! Objects of one class and size that may turn are interchangeable (rules
//! name classes, resemblance and warm starts match class and footprint),
//! so a choice is how many of each such group lie turned — the first `t`
//! of the group in problem order — not which: `Π (nᵍ + 1)` choices, at most
//! [`MAX_ORIENTATION_CHOICES`] (past that, only the flat choice is solved,
//! and the problem is refused unless its layout keeps every rule). A square object never turns (its footprint
//! is the same). Each choice is the same problem with `turned` set on the
//! chosen objects, solved (and verified) like any other problem, so:
//!
//! - `optimal` means every choice was solved to optimality or proven
//!   infeasible: the layout is optimal over every orientation;
//! - `infeasible` means every choice was proven infeasible: no layout in
//!   any orientation (the conflict is the union of the choices' conflicts);
//! - a limit (time, nodes, Ctrl-C) is shared by the choices in turn; what
//!   is left unsolved makes the result `feasible` or `unknown`;
//! - without a second objective (`like`), a layout that satisfies every
//!   rule (the numerator is the total weight) ends the search: no choice
//!   can score more, so the choices left are not solved.

use super::{
    synthesize_fixed, verify_solution, Conflict, Progress, ProgressFn, Resemblance, SolveStats,
    Status, SynthError, SynthOptions, SynthResult,
};
use crate::rules::RuleSet;
use crate::scene::Scene;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Whether orientations are enumerated (one solve per choice) rather than
/// chosen by the model's orientation variables: with a second objective
/// (`like`: the resemblance costs assume each object's footprint), or
/// when the tuning asks for it (`enumerate_turns`, to compare the two).
pub(crate) fn enumerate(opts: &SynthOptions) -> bool {
    opts.like.is_some() || opts.tuning.enumerate_turns
}

/// Most nodes the flat probe of [`synthesize_model`] may use before the
/// model with orientation variables takes over.
pub(crate) const FLAT_PROBE_NODES: u64 = 10_000;

/// [`super::synthesize`] without `like` for a problem with orientation
/// choices (`groups` from [`turn_groups`], not empty): first a short probe
/// with nothing turned (at most [`FLAT_PROBE_NODES`] nodes) — a layout
/// that keeps every rule is optimal over every orientation, since no
/// layout scores more — then, unless it found one, the one model with an
/// orientation variable per turnable object, under what is left of the
/// limits. (Measured: where the flat optimum keeps every rule the probe
/// costs what the flat solve costs, the bigger model up to 2.5× more;
/// where it breaks one the probe costs a fraction of the model's solve.)
pub(super) fn synthesize_model(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
    groups: &[Vec<usize>],
) -> Result<SynthResult, SynthError> {
    let start = Instant::now();
    let mut probe = opts.clone();
    probe.stop = opts.stop.clone().nodes_at_most(Some(
        opts.stop
            .nodes()
            .map_or(FLAT_PROBE_NODES, |n| n.min(FLAT_PROBE_NODES)),
    ));
    let flat = oriented(problem, groups, &vec![0; groups.len()]);
    let mut first = synthesize_fixed(&flat, rules, &probe)?;
    turnable_as_in(&mut first, problem);
    let elapsed = start.elapsed();
    let nodes_left = opts
        .stop
        .nodes()
        .map(|n| n.saturating_sub(first.stats.nodes));
    if at_maximum(&first) || opts.stop.expired() || nodes_left == Some(0) {
        if at_maximum(&first) {
            first.status = Status::Optimal;
            first.score_bound = first.evaluation.as_ref().map(|e| e.score);
        } else if first.scene.is_some() {
            // Stopped: the flat layout, nothing proven over the turns.
            first.status = Status::Feasible;
            first.score_bound = None;
        } else {
            first.status = Status::Unknown;
            first.conflict = None;
        }
        first.stats.time_ms = start.elapsed().as_secs_f64() * 1000.0;
        if let Some(scene) = &first.scene {
            verify_solution(problem, scene, rules, opts.contact).map_err(SynthError::Unverified)?;
        }
        return Ok(first);
    }
    let mut sub = opts.clone();
    sub.stop = opts.stop.clone().nodes_at_most(nodes_left);
    let offset = elapsed.as_secs_f64() * 1000.0;
    let mut out = synthesize_fixed(problem, rules, &sub)?;
    // The model found nothing before a limit, the probe did: its layout.
    if out.scene.is_none() && out.status == Status::Unknown && first.scene.is_some() {
        first.status = Status::Feasible;
        first.score_bound = None;
        out = SynthResult {
            stats: out.stats.clone(),
            ..first.clone()
        };
        out.stats.time_to_first_ms = first.stats.time_to_first_ms;
        out.stats.time_to_best_ms = first.stats.time_to_best_ms;
    } else {
        out.stats.time_to_first_ms = out.stats.time_to_first_ms.map(|t| t + offset);
        out.stats.time_to_best_ms = out.stats.time_to_best_ms.map(|t| t + offset);
    }
    out.stats.nodes = out.stats.nodes.saturating_add(first.stats.nodes);
    out.stats.conflicts = out.stats.conflicts.saturating_add(first.stats.conflicts);
    out.stats.time_ms = start.elapsed().as_secs_f64() * 1000.0;
    Ok(out)
}

/// Most orientation choices (`Π (nᵍ + 1)` over the groups of
/// interchangeable turnable objects) one synthesis with `like` tries.
pub const MAX_ORIENTATION_CHOICES: u128 = 256;

/// The groups of interchangeable objects that may turn: unplaced,
/// `turnable`, not square, of one class and size; indices in problem
/// order. Empty: the problem has no orientation to choose.
pub(crate) fn turn_groups(problem: &Scene) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for (i, o) in problem.objects.iter().enumerate() {
        if o.is_placed() || !o.turnable || !o.is_oblong() {
            continue;
        }
        match groups.iter_mut().find(|g| {
            let p = &problem.objects[g[0]];
            p.class == o.class && (p.width, p.height) == (o.width, o.height)
        }) {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    }
    groups
}

/// How many orientation choices `groups` give (saturating).
pub(crate) fn choice_count(groups: &[Vec<usize>]) -> u128 {
    groups
        .iter()
        .fold(1u128, |acc, g| acc.saturating_mul(g.len() as u128 + 1))
}

/// Every orientation choice, as turned counts per group, the choice with
/// nothing turned first (then the first group's count varying fastest).
fn choices(groups: &[Vec<usize>]) -> Vec<Vec<usize>> {
    let mut out = vec![vec![0; groups.len()]];
    loop {
        let mut next = out[out.len() - 1].clone();
        let mut g = 0;
        loop {
            if g == groups.len() {
                return out;
            }
            if next[g] < groups[g].len() {
                next[g] += 1;
                break;
            }
            next[g] = 0;
            g += 1;
        }
        out.push(next);
    }
}

/// The problem with the first `turned[g]` objects of every group turned
/// and the others flat: every orientation given, so the model has no
/// orientation variable (a turned object keeps `turnable`, as an oriented
/// problem must; a flat one loses it).
fn oriented(problem: &Scene, groups: &[Vec<usize>], turned: &[usize]) -> Scene {
    let mut p = problem.clone();
    for (g, &t) in groups.iter().zip(turned) {
        for (k, &i) in g.iter().enumerate() {
            p.objects[i].turned = k < t;
            p.objects[i].turnable = k < t;
        }
    }
    p
}

/// The layout of an oriented problem's result names the objects as
/// `problem` does: `turnable` as given there.
fn turnable_as_in(result: &mut SynthResult, problem: &Scene) {
    if let Some(scene) = &mut result.scene {
        for (o, p) in scene.objects.iter_mut().zip(&problem.objects) {
            o.turnable = p.turnable;
        }
    }
}

/// One choice's outcome, kept for the combination.
struct Solved {
    result: SynthResult,
    /// When its solve started, since the whole solve's start.
    offset: Duration,
}

/// [`super::synthesize`] for a problem with orientation choices (`groups`
/// from [`turn_groups`], not empty).
pub(super) fn synthesize_turning(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
    groups: &[Vec<usize>],
) -> Result<SynthResult, SynthError> {
    let count = choice_count(groups);
    // Past the limit only the flat choice is tried: enough when its layout
    // keeps every rule, else the problem is refused.
    let too_many = count > MAX_ORIENTATION_CHOICES;
    let all = if too_many {
        vec![vec![0; groups.len()]]
    } else {
        choices(groups)
    };
    let start = Instant::now();
    // The best score reported so far: progress reports only improvements
    // over every choice, timed from the whole solve's start.
    let reported = Arc::new(Mutex::new(f64::NEG_INFINITY));
    let mut nodes_used: u64 = 0;
    let mut solved: Vec<Solved> = Vec::new();
    let (mut stopped, mut maximum) = (false, false);
    for turned in all {
        let now = Instant::now();
        let nodes_left = opts.stop.nodes().map(|n| n.saturating_sub(nodes_used));
        if opts.stop.expired() || nodes_left == Some(0) {
            stopped = true;
            break;
        }
        let offset = now.duration_since(start);
        let mut sub = opts.clone();
        sub.stop = opts.stop.clone().nodes_at_most(nodes_left);
        sub.progress = opts.progress.as_ref().map(|f| {
            let (f, reported) = (f.clone(), Arc::clone(&reported));
            ProgressFn(Arc::new(move |p: &Progress| {
                let mut best = reported.lock().unwrap_or_else(|e| e.into_inner());
                if p.score > *best {
                    *best = p.score;
                    (f.0)(&Progress {
                        score: p.score,
                        elapsed: offset + p.elapsed,
                    });
                }
            }))
        });
        let choice = oriented(problem, groups, &turned);
        let mut result = synthesize_fixed(&choice, rules, &sub)?;
        turnable_as_in(&mut result, problem);
        nodes_used = nodes_used.saturating_add(result.stats.nodes);
        let top = opts.like.is_none() && at_maximum(&result);
        solved.push(Solved { result, offset });
        if top {
            maximum = true;
            break;
        }
    }
    if too_many && !maximum {
        let objects: usize = groups.iter().map(Vec::len).sum();
        return Err(SynthError::TooLarge(format!(
            "{objects} turnable objects in {} groups of one class and size give {count} orientation choices, \
             more than the {MAX_ORIENTATION_CHOICES} synthesis tries (and the layout with none turned breaks a rule); \
             expected fewer turnable objects (drop \"turnable\" from some, or make interchangeable ones the same class and size)",
            groups.len()
        )));
    }
    let mut out = combine(solved, stopped, opts.like.is_some(), maximum);
    out.stats.time_ms = start.elapsed().as_secs_f64() * 1000.0;
    if let Some(scene) = &out.scene {
        verify_solution(problem, scene, rules, opts.contact).map_err(SynthError::Unverified)?;
    }
    Ok(out)
}

/// Whether a result's layout satisfies every rule (its numerator is the
/// total weight): no layout scores more.
fn at_maximum(r: &SynthResult) -> bool {
    r.evaluation
        .as_ref()
        .is_some_and(|e| e.hard_ok() && e.satisfied_weight >= e.total_weight)
}

/// The numerator of a result's layout (`None` without one).
fn numerator(r: &SynthResult) -> Option<f64> {
    r.evaluation.as_ref().map(|e| e.satisfied_weight)
}

/// The best layout over the choices, its status and bounds (see the
/// module's documentation). `stopped`: a limit struck before every choice
/// was tried; `maximum`: the last choice solved found a layout that
/// satisfies every rule, so the choices left cannot score more.
fn combine(mut solved: Vec<Solved>, stopped: bool, like: bool, maximum: bool) -> SynthResult {
    let mut stats = summed_stats(&solved);
    let all_proven = maximum
        || !stopped
            && solved
                .iter()
                .all(|s| matches!(s.result.status, Status::Optimal | Status::Infeasible));
    let Some(b) = best_choice(&solved) else {
        let infeasible = all_proven && !solved.is_empty();
        let conflict = infeasible.then(|| union_conflict(&solved));
        return SynthResult::without_layout(
            if infeasible {
                Status::Infeasible
            } else {
                Status::Unknown
            },
            conflict,
            stats,
        );
    };
    let score_bound = score_bound_over(&solved, b, stopped, maximum);
    let best_num = numerator(&solved[b].result);
    let resemblance = like
        .then(|| resemblance_over(&solved, b, best_num, all_proven))
        .flatten();
    let offset = solved[b].offset;
    let mut result = solved.swap_remove(b).result;
    stats.time_to_best_ms = result.stats.time_to_best_ms.map(|t| ms(offset) + t);
    result.status = if all_proven {
        Status::Optimal
    } else {
        Status::Feasible
    };
    result.stats = stats;
    result.score_bound = score_bound;
    result.resemblance = resemblance;
    result.conflict = None;
    result
}

/// A duration in milliseconds.
fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

/// The choices' nodes and conflicts summed, and the earliest first layout
/// (counted from the start of the first choice).
fn summed_stats(solved: &[Solved]) -> SolveStats {
    let mut stats = SolveStats::default();
    for s in solved {
        stats.nodes += s.result.stats.nodes;
        stats.conflicts += s.result.stats.conflicts;
    }
    stats.time_to_first_ms = solved
        .iter()
        .filter_map(|s| Some(ms(s.offset) + s.result.stats.time_to_first_ms?))
        .reduce(f64::min);
    stats
}

/// The index of the best choice with a layout: the largest numerator, then
/// the smallest resemblance cost, then the earliest choice.
fn best_choice(solved: &[Solved]) -> Option<usize> {
    let cost = |r: &SynthResult| r.resemblance.map_or(0, |x| x.cost);
    let mut best: Option<usize> = None;
    for (i, s) in solved.iter().enumerate() {
        let Some(n) = numerator(&s.result) else {
            continue;
        };
        let better = match best {
            None => true,
            Some(b) => {
                let bn = numerator(&solved[b].result).unwrap_or(f64::NEG_INFINITY);
                n > bn || (n == bn && cost(&s.result) < cost(&solved[b].result))
            }
        };
        if better {
            best = Some(i);
        }
    }
    best
}

/// A bound on every choice's score, `b` the best: its own score when it is
/// the `maximum`, else the largest of their bounds (an infeasible choice
/// has none to add); a choice left unsolved, or stopped without a bound,
/// leaves the score unbounded.
fn score_bound_over(solved: &[Solved], b: usize, stopped: bool, maximum: bool) -> Option<f64> {
    let bounded = !stopped
        && solved
            .iter()
            .all(|s| s.result.status == Status::Infeasible || s.result.score_bound.is_some());
    if maximum {
        solved[b].result.evaluation.as_ref().map(|e| e.score)
    } else {
        bounded.then(|| {
            solved
                .iter()
                .filter_map(|s| s.result.score_bound)
                .fold(f64::NEG_INFINITY, f64::max)
        })
    }
}

/// The second objective over the choices: the best layout's cost, proven
/// when every choice was proven and every choice with the same numerator
/// proved its cost; the bound is the least over the choices that may hold
/// a layout with that numerator.
fn resemblance_over(
    solved: &[Solved],
    b: usize,
    best_num: Option<f64>,
    all_proven: bool,
) -> Option<Resemblance> {
    let own = solved[b].result.resemblance?;
    let rivals = solved.iter().filter(|s| {
        s.result.status != Status::Infeasible
            && (s.result.status != Status::Optimal || numerator(&s.result) == best_num)
    });
    let mut bound = own.bound;
    let mut proven = own.proven && all_proven;
    for s in rivals {
        match s.result.resemblance {
            Some(r) => {
                bound = bound.min(r.bound);
                proven &= r.proven;
            }
            None => {
                bound = 0;
                proven = false;
            }
        }
    }
    Some(Resemblance {
        cost: own.cost,
        proven: proven && bound == own.cost,
        bound: bound.min(own.cost),
    })
}

/// Every choice infeasible: the objects cannot fit when they cannot in
/// any choice; the hard rules are those named by any choice (together
/// with the geometry they rule out every orientation; minimal per choice,
/// not necessarily over all).
fn union_conflict(solved: &[Solved]) -> Conflict {
    let mut c = Conflict {
        objects_cannot_fit: true,
        ..Conflict::default()
    };
    for s in solved {
        let Some(k) = &s.result.conflict else {
            c.objects_cannot_fit = false;
            continue;
        };
        c.objects_cannot_fit &= k.objects_cannot_fit;
        c.limit_struck |= k.limit_struck;
        for r in &k.hard_rules {
            if !c.hard_rules.contains(r) {
                c.hard_rules.push(r.clone());
            }
        }
    }
    if c.objects_cannot_fit {
        c.hard_rules.clear();
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Object, Space};

    fn problem(objects: Vec<Object>) -> Scene {
        Scene::new(
            Space {
                x: 0,
                y: 0,
                width: 40,
                height: 20,
            },
            10,
            objects,
        )
        .expect("valid")
    }

    #[test]
    fn groups_are_turnable_oblong_unplaced_objects_of_one_class_and_size() {
        let p = problem(vec![
            Object::movable("a", "A", 20, 10).with_turnable(),
            Object::movable("b", "A", 20, 10),
            Object::movable("c", "A", 10, 10).with_turnable(),
            Object::movable("d", "A", 20, 10).with_turnable(),
            Object::movable("e", "B", 20, 10).with_turnable(),
            Object::placed("f", "A", 0, 0, 10, 20).with_turnable(),
        ]);
        assert_eq!(turn_groups(&p), vec![vec![0, 3], vec![4]]);
        assert_eq!(choice_count(&turn_groups(&p)), 3 * 2);
    }

    #[test]
    fn choices_count_the_turned_objects_of_every_group_once() {
        let groups = vec![vec![0, 1], vec![2]];
        let c = choices(&groups);
        assert_eq!(c.len(), 6);
        assert_eq!(c[0], vec![0, 0]);
        let mut sorted = c.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), 6, "{c:?}");
        assert!(c.iter().all(|t| t[0] <= 2 && t[1] <= 1));
    }
}
