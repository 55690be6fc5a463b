//! The second objective in the engine: per resemblance term a cost
//! variable bounded below by its distance map, their total, and the group
//! bounds of [`resemblance_group`](super::resemblance_group).
//!
//! # Background
//!
//! Synthesis with `like` scenes runs in two phases: the best score first,
//! then, with the score held, the smallest resemblance cost. Nothing of the
//! second objective is needed in the first phase, and posting it there is
//! not free: its clauses made the engine of a 20-object task ten times
//! slower to build (37 → 366 ms), and its variables and constraints steer
//! the first phase's learning search elsewhere — at twice the
//! demonstrations' blocks (`bench tasks --sizes 2`, 30 s), `--like` solves
//! ended with lower scores than the same problems solved without it
//! (0.858 against 0.991, 0.781 against 0.854).
//!
//! # Practical
//!
//! [`PendingResemblance`] holds the terms (and the group maps, which need the
//! model) until the engine is told the second phase starts
//! ([`Backend::start_cost_phase`](crate::synth::backend::Backend), or the
//! first call that names the cost); then everything is posted at the root
//! and the new variables are handed to the brancher. So the first phase of
//! a `like` solve is the score-only solve, node for node.
//!
//! # How to extend
//!
//! Another bound on the cost is one more constraint in [`PendingResemblance::post`].

use super::resemblance_group::{CostGroups, GroupMap, GroupVars};
use super::resemblance_map;
use crate::synth::model::{Coord, Model};
use crate::synth::resemblance_terms::ResemblanceTerm;
use pumpkin_constraints::equals;
use pumpkin_core::predicate;
use pumpkin_core::proof::ConstraintTag;
use pumpkin_core::variables::{AffineView, DomainId, TransformableVariable};
use pumpkin_core::Solver;
use std::rc::Rc;

/// The second objective, not yet posted.
#[derive(Debug, Clone)]
pub(super) struct PendingResemblance {
    terms: Vec<ResemblanceTerm>,
    /// Groups of two or more terms (indices into `terms`) with their map.
    groups: Vec<(Vec<usize>, Rc<GroupMap>)>,
}

/// What [`PendingResemblance::post`] made.
pub(super) struct PostedResemblance {
    /// The total cost.
    pub(super) total: DomainId,
    /// Every variable it created (for the brancher).
    pub(super) created: Vec<DomainId>,
}

fn clamp_i32(v: i64) -> i32 {
    i32::try_from(v.clamp(i64::from(i32::MIN), i64::from(i32::MAX))).unwrap_or(i32::MAX)
}

impl PendingResemblance {
    /// The terms of `model` (none: no second objective).
    pub(super) fn new(model: &Model, like: &[ResemblanceTerm]) -> Option<PendingResemblance> {
        if like.is_empty() {
            return None;
        }
        let groups = resemblance_groups(model, like)
            .into_iter()
            .filter(|g| g.len() >= 2)
            .map(|g| {
                let map = Rc::new(group_map(model, &like[g[0]]));
                (g, map)
            })
            .collect();
        Some(PendingResemblance {
            terms: like.to_vec(),
            groups,
        })
    }

    /// The smallest total cost before anything is posted.
    pub(super) fn min_total(&self) -> u64 {
        self.terms
            .iter()
            .map(|t| t.map.min())
            .fold(0, u64::saturating_add)
    }

    /// Post at the root (the ranges were checked by `resemblance_fits`): per term
    /// a cost variable with its clauses and bounds propagator
    /// ([`resemblance_encoding`]), the total their sum, and the group bounds.
    pub(super) fn post(
        self,
        solver: &mut Solver,
        vars: &[DomainId],
        tag: ConstraintTag,
    ) -> PostedResemblance {
        let hi_of = |t: &ResemblanceTerm| t.map.cost.iter().copied().max().unwrap_or(0);
        let costs: Vec<DomainId> = self
            .terms
            .iter()
            .map(|t| {
                solver
                    .new_bounded_integer(clamp_i32(t.map.min() as i64), clamp_i32(hi_of(t) as i64))
            })
            .collect();
        let lo: u64 = self.min_total();
        let hi: u64 = self.terms.iter().map(hi_of).fold(0, u64::saturating_add);
        let total = solver.new_bounded_integer(clamp_i32(lo as i64), clamp_i32(hi as i64));
        let mut created = costs.clone();
        created.push(total);
        let encoding = resemblance_encoding();
        let mut sum: Vec<AffineView<DomainId>> = Vec::with_capacity(costs.len() + 1);
        for (t, &c) in self.terms.iter().zip(&costs) {
            if encoding != ResemblanceEncoding::Propagator {
                post_clauses(solver, t, vars[t.x], vars[t.y], c, tag);
            }
            if encoding != ResemblanceEncoding::Clauses {
                let cells: Vec<i32> = t.map.cost.iter().map(|&v| clamp_i32(v as i64)).collect();
                let _ = solver.add_propagator(resemblance_map::ResemblanceMapArgs {
                    gx: vars[t.x],
                    gy: vars[t.y],
                    cost: c,
                    map: Rc::new(resemblance_map::MapIndex::new(
                        t.map.nx as usize,
                        t.map.ny as usize,
                        &cells,
                    )),
                    tag,
                });
            }
            sum.push(c.scaled(1));
        }
        sum.push(total.scaled(-1));
        solver.add_constraint(equals(sum, 0, tag)).post();
        let mut grouped = vec![false; self.terms.len()];
        let groups: Vec<GroupVars> = self
            .groups
            .iter()
            .map(|(members, map)| {
                for &i in members {
                    grouped[i] = true;
                }
                GroupVars {
                    xs: members.iter().map(|&i| vars[self.terms[i].x]).collect(),
                    ys: members.iter().map(|&i| vars[self.terms[i].y]).collect(),
                    costs: members.iter().map(|&i| costs[i]).collect(),
                    map: map.clone(),
                }
            })
            .collect();
        if !groups.is_empty() {
            let singles = costs
                .iter()
                .zip(&grouped)
                .filter(|(_, &g)| !g)
                .map(|(&c, _)| c)
                .collect();
            let groups = CostGroups {
                groups,
                singles,
                total,
            };
            created.extend(groups.post(solver, tag));
        }
        PostedResemblance { total, created }
    }
}

/// The resemblance terms in groups of one class and size (same size,
/// same map), in order of first appearance; every term alone when the
/// model's tuning says so (`like_groups` off).
fn resemblance_groups(model: &Model, like: &[ResemblanceTerm]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let off = !model.tuning.like_groups;
    for (i, t) in like.iter().enumerate() {
        let size = model.sizes[t.object];
        let same = |g: &Vec<usize>| {
            let u = &like[g[0]];
            model.sizes[u.object] == size && u.map == t.map
        };
        match groups.iter_mut().find(|g| !off && same(g)) {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    }
    groups
}

/// The group map of term `t`'s object: its distance map with the cells
/// where it would overlap a fixed (or already placed) object blocked.
fn group_map(m: &Model, t: &ResemblanceTerm) -> GroupMap {
    let (w, h) = m.sizes[t.object];
    let fixed: Vec<(i64, i64, i64, i64)> = m
        .coords
        .iter()
        .zip(&m.sizes)
        .filter_map(|(c, &(fw, fh))| match *c {
            (Coord::Const(x), Coord::Const(y)) => Some((x, y, fw, fh)),
            _ => None,
        })
        .collect();
    let (nx, ny) = (t.map.nx as usize, t.map.ny as usize);
    let mut cost = Vec::with_capacity(nx * ny);
    for gy in 0..ny {
        for gx in 0..nx {
            let x = m.origin.0 + m.grid * gx as i64;
            let y = m.origin.1 + m.grid * gy as i64;
            let blocked = fixed
                .iter()
                .any(|&(fx, fy, fw, fh)| x < fx + fw && fx < x + w && y < fy + fh && fy < y + h);
            cost.push((!blocked).then(|| clamp_i32(t.map.cost[gy * nx + gx] as i64)));
        }
    }
    let cells = |v: i64| {
        usize::try_from((v + m.grid - 1) / m.grid)
            .unwrap_or(1)
            .max(1)
    };
    GroupMap {
        nx,
        ny,
        tw: cells(w),
        th: cells(h),
        cost,
    }
}

/// How a resemblance term is posted: the clauses of [`post_clauses`] (exact
/// once a coordinate is fixed, value-level pruning under `c ≤ u`), the
/// bounds propagator of [`resemblance_map`](super::resemblance_map) (raises `c` from the bounds of both
/// coordinates), or both (the default: strictly stronger than either).
///
/// Measured on the realistic tasks' `--like` solves that both prove
/// (`bench tasks --problems-out`, `synth … --like`): both together needed
/// fewer nodes than the clauses alone on every one of five problems
/// (29 412 → 14 284, 15 153 → 11 644, 7 160 → 5 998, 1 853 → 1 675,
/// 470 → 460); the propagator alone builds faster (engine 383 → 84 ms on
/// a 20-object task) but found worse layouts when the limit struck on
/// 31-object tasks (cost 28 against 15), so the clauses stay.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ResemblanceEncoding {
    /// Clauses only.
    Clauses,
    /// The bounds propagator only.
    Propagator,
    /// Both.
    Both,
}

#[cfg(test)]
thread_local! {
    /// The encoding engines built on this thread use (tests compare them).
    pub(crate) static RESEMBLANCE_ENCODING: std::cell::Cell<ResemblanceEncoding> =
        const { std::cell::Cell::new(ResemblanceEncoding::Both) };
}

pub(super) fn resemblance_encoding() -> ResemblanceEncoding {
    #[cfg(test)]
    return RESEMBLANCE_ENCODING.with(|e| e.get());
    #[cfg(not(test))]
    ResemblanceEncoding::Both
}

/// Bound one object's resemblance cost `c` from below by its distance map:
/// `gx = a ∧ gy = b → c ≥ map(a, b)` for every cell above the map's
/// minimum, plus `gx = a → c ≥ min_b map(a, b)` and the same per row, so
/// that one fixed coordinate already raises the bound. Only the lower bound
/// is needed: the cost is minimised.
///
/// Measured on `examples/box-packing` (9 objects, 46 learned rules): an
/// `element` constraint over the map indexed by `nx·gy + gx` took 4.8 s for
/// the first `cost ≤ 9` call (463 nodes in all: the time is propagation);
/// these clauses take a few milliseconds.
fn post_clauses(
    solver: &mut Solver,
    t: &ResemblanceTerm,
    gx: DomainId,
    gy: DomainId,
    c: DomainId,
    tag: ConstraintTag,
) {
    let (nx, ny) = (t.map.nx as usize, t.map.ny as usize);
    let lo = t.map.min();
    let at = |a: usize, b: usize| t.map.cost[b * nx + a];
    let col: Vec<u64> = (0..nx)
        .map(|a| (0..ny).map(|b| at(a, b)).min().unwrap_or(lo))
        .collect();
    let row: Vec<u64> = (0..ny)
        .map(|b| (0..nx).map(|a| at(a, b)).min().unwrap_or(lo))
        .collect();
    for (a, &m) in col.iter().enumerate() {
        if m > lo {
            solver.add_clause([predicate![gx != a as i32], predicate![c >= m as i32]], tag);
        }
    }
    for (b, &m) in row.iter().enumerate() {
        if m > lo {
            solver.add_clause([predicate![gy != b as i32], predicate![c >= m as i32]], tag);
        }
    }
    for (b, &rb) in row.iter().enumerate() {
        for (a, &ca) in col.iter().enumerate() {
            let v = at(a, b);
            // Cells whose cost the column or row clause already gives need
            // no clause of their own.
            if v > ca.max(rb) {
                solver.add_clause(
                    [
                        predicate![gx != a as i32],
                        predicate![gy != b as i32],
                        predicate![c >= v as i32],
                    ],
                    tag,
                );
            }
        }
    }
}
