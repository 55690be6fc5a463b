//! A propagator for one resemblance term: `c ≥ map(gx, gy)` over the
//! object's distance map (docs/guide.md#layouts-like-the-demonstrations), on the bounds of all three variables.
//!
//! # Background
//!
//! The second phase minimises `Σ cᵢ`, each `cᵢ` bounded below by a table
//! over the object's grid position. The clauses of `post_resemblance` raise `cᵢ`
//! only once a coordinate is *fixed* (a column, a row, a cell); the
//! default brancher mostly narrows bounds (`[gx ≥ k]`), so most of the
//! search ran with `cᵢ` at its root minimum and the sum could not fail
//! early. This propagator reads the box `[lx, ux] × [ly, uy]` of the
//! current bounds:
//!
//! - `c ≥ min over the box of map` (explained by the four bounds, each
//!   dropped when the minimum over the box widened to the root bound on
//!   that side stays as large: a shorter, more general nogood);
//! - with `c ≤ u`, the first and last column (row) of the box holding a
//!   cell of cost `≤ u` are the new bounds of `gx` (`gy`), explained by
//!   `[c ≤ u]` and the other axis's bounds.
//!
//! # Practical
//!
//! Range minima come from one sparse table per row (over `gx`) and one per
//! column (over `gy`): a box minimum costs `O(rows)`, a column scan
//! `O(1)` per column. A map of 40 × 30 cells takes about 20 000 integers.
//!
//! # How to extend
//!
//! Holes in the domains are ignored (bounds only); `post_resemblance`'s clauses
//! remain for value-level pruning. A propagator over the *sum* (objects of
//! one class competing for the same shown positions) would be the next
//! strengthening.

use pumpkin_core::declare_inference_label;
use pumpkin_core::predicate;
use pumpkin_core::predicates::PropositionalConjunction;
use pumpkin_core::proof::{ConstraintTag, InferenceCode};
use pumpkin_core::propagation::{
    DomainEvents, EventsToRegister, LocalId, Priority, PropagationContext, Propagator,
    PropagatorConstructor, PropagatorConstructorContext, PropagatorSpec, ReadDomains,
    RuntimeCheckers,
};
use pumpkin_core::state::{EmptyDomainConflict, PropagationStatusCP};
use pumpkin_core::variables::DomainId;
use std::rc::Rc;

declare_inference_label!(ResemblanceMap);

/// Range minima over one axis of a table: `level[k][i] = min(v[i..i+2^k])`.
#[derive(Debug, Clone)]
struct SparseTable {
    levels: Vec<Vec<i32>>,
}

impl SparseTable {
    fn new(v: Vec<i32>) -> Self {
        let mut levels = vec![v];
        let mut k = 1usize;
        while (1usize << k) <= levels[0].len() {
            let prev = &levels[k - 1];
            let half = 1usize << (k - 1);
            let next: Vec<i32> = (0..prev.len() - half)
                .map(|i| prev[i].min(prev[i + half]))
                .collect();
            levels.push(next);
            k += 1;
        }
        SparseTable { levels }
    }

    /// `min(v[lo..=hi])`, `lo ≤ hi` in range.
    fn min(&self, lo: usize, hi: usize) -> i32 {
        let len = hi - lo + 1;
        let k = usize::BITS as usize - 1 - len.leading_zeros() as usize;
        let l = &self.levels[k];
        l[lo].min(l[hi + 1 - (1 << k)])
    }
}

/// A distance map with its range-minimum tables (shared by clones of the
/// propagator).
#[derive(Debug)]
pub(super) struct MapIndex {
    nx: usize,
    ny: usize,
    /// Per row `gy`, minima over `gx` ranges.
    rows: Vec<SparseTable>,
    /// Per column `gx`, minima over `gy` ranges.
    cols: Vec<SparseTable>,
}

impl MapIndex {
    /// `cost` row-major over `(gy, gx)`, `nx · ny` cells, each fitting `i32`.
    pub(super) fn new(nx: usize, ny: usize, cost: &[i32]) -> Self {
        debug_assert_eq!(cost.len(), nx * ny);
        let rows = (0..ny)
            .map(|b| SparseTable::new(cost[b * nx..(b + 1) * nx].to_vec()))
            .collect();
        let cols = (0..nx)
            .map(|a| SparseTable::new((0..ny).map(|b| cost[b * nx + a]).collect()))
            .collect();
        MapIndex { nx, ny, rows, cols }
    }

    /// The minimum over the box `[lx, ux] × [ly, uy]` (non-empty, in range).
    fn box_min(&self, lx: usize, ux: usize, ly: usize, uy: usize) -> i32 {
        (ly..=uy)
            .map(|b| self.rows[b].min(lx, ux))
            .min()
            .unwrap_or(i32::MAX)
    }

    /// The minimum of column `a` over rows `[ly, uy]`.
    fn col_min(&self, a: usize, ly: usize, uy: usize) -> i32 {
        self.cols[a].min(ly, uy)
    }

    /// The minimum of row `b` over columns `[lx, ux]`.
    fn row_min(&self, b: usize, lx: usize, ux: usize) -> i32 {
        self.rows[b].min(lx, ux)
    }
}

/// Posts [`ResemblanceMapPropagator`].
#[derive(Debug, Clone)]
pub(super) struct ResemblanceMapArgs {
    pub(super) gx: DomainId,
    pub(super) gy: DomainId,
    pub(super) cost: DomainId,
    pub(super) map: Rc<MapIndex>,
    pub(super) tag: ConstraintTag,
}

impl PropagatorConstructor for ResemblanceMapArgs {
    type PropagatorImpl = ResemblanceMapPropagator;

    fn create(self, _: PropagatorConstructorContext) -> PropagatorSpec<Self::PropagatorImpl> {
        let registration = EventsToRegister::builder()
            .add(&self.gx, DomainEvents::BOUNDS, LocalId::from(0))
            .add(&self.gy, DomainEvents::BOUNDS, LocalId::from(1))
            .add(&self.cost, DomainEvents::UPPER_BOUND, LocalId::from(2))
            .build();
        PropagatorSpec {
            registration,
            checkers: RuntimeCheckers::empty(),
            propagator: ResemblanceMapPropagator {
                gx: self.gx,
                gy: self.gy,
                cost: self.cost,
                map: self.map,
                code: InferenceCode::new(self.tag, ResemblanceMap),
            },
        }
    }
}

/// `cost ≥ map(gx, gy)` on bounds; see the module documentation.
#[derive(Debug, Clone)]
pub(super) struct ResemblanceMapPropagator {
    gx: DomainId,
    gy: DomainId,
    cost: DomainId,
    map: Rc<MapIndex>,
    code: InferenceCode,
}

/// A box of grid positions, bounds inclusive.
#[derive(Debug, Clone, Copy)]
struct Box2 {
    lx: usize,
    ux: usize,
    ly: usize,
    uy: usize,
}

impl ResemblanceMapPropagator {
    fn bounds(&self, ctx: &PropagationContext) -> Option<Box2> {
        let clamp = |v: i32, n: usize| (v.max(0) as usize).min(n.saturating_sub(1));
        let (lx, ux) = (ctx.lower_bound(&self.gx), ctx.upper_bound(&self.gx));
        let (ly, uy) = (ctx.lower_bound(&self.gy), ctx.upper_bound(&self.gy));
        if lx > ux || ly > uy || ux < 0 || uy < 0 {
            return None;
        }
        Some(Box2 {
            lx: clamp(lx, self.map.nx),
            ux: clamp(ux, self.map.nx),
            ly: clamp(ly, self.map.ny),
            uy: clamp(uy, self.map.ny),
        })
    }

    /// The bounds of `b` as a reason, each side left out when the box
    /// widened to the root on that side still has every cell `≥ m`.
    fn box_reason(&self, b: Box2, m: i32) -> PropositionalConjunction {
        let map = &self.map;
        let mut w = b;
        let mut reason = PropositionalConjunction::default();
        let (gx, gy) = (self.gx, self.gy);
        if w.lx > 0 && map.box_min(0, w.ux, w.ly, w.uy) >= m {
            w.lx = 0;
        } else if w.lx > 0 {
            reason.push(predicate![gx >= w.lx as i32]);
        }
        if w.ux + 1 < map.nx && map.box_min(w.lx, map.nx - 1, w.ly, w.uy) >= m {
            w.ux = map.nx - 1;
        } else if w.ux + 1 < map.nx {
            reason.push(predicate![gx <= w.ux as i32]);
        }
        if w.ly > 0 && map.box_min(w.lx, w.ux, 0, w.uy) >= m {
            w.ly = 0;
        } else if w.ly > 0 {
            reason.push(predicate![gy >= w.ly as i32]);
        }
        if w.uy + 1 < map.ny && map.box_min(w.lx, w.ux, w.ly, map.ny - 1) < m {
            reason.push(predicate![gy <= w.uy as i32]);
        }
        reason
    }
}

impl Propagator for ResemblanceMapPropagator {
    fn name(&self) -> &str {
        "ResemblanceMap"
    }

    fn priority(&self) -> Priority {
        Priority::Low
    }

    fn propagate_from_scratch(&self, mut ctx: PropagationContext) -> PropagationStatusCP {
        // Narrowing one axis may narrow the other's scan; two rounds reach
        // the fixpoint in practice (and any round is sound), the lower
        // bound is posted last.
        for _ in 0..2 {
            let x = self.narrow(&mut ctx, Axis::X)?;
            let y = self.narrow(&mut ctx, Axis::Y)?;
            if !(x || y) {
                break;
            }
        }
        // The lower bound of the cost over the (final) box; when no cell is
        // ≤ u this posts past the upper bound: a conflict.
        let Some(b) = self.bounds(&ctx) else {
            return Ok(());
        };
        let m = self.map.box_min(b.lx, b.ux, b.ly, b.uy);
        let cost = self.cost;
        if m > ctx.lower_bound(&cost) {
            let r = self.box_reason(b, m);
            ctx.post(predicate![cost >= m], (r, &self.code))?;
        }
        Ok(())
    }
}

/// One of the two grid axes.
#[derive(Debug, Clone, Copy)]
enum Axis {
    X,
    Y,
}

impl ResemblanceMapPropagator {
    /// Under `cost ≤ u`, move the bounds of `axis`'s variable in to the
    /// first and last line (column for x, row for y) of the box holding a
    /// cell of cost `≤ u`; whether a bound moved.
    fn narrow(
        &self,
        ctx: &mut PropagationContext,
        axis: Axis,
    ) -> Result<bool, EmptyDomainConflict> {
        let Some(b) = self.bounds(ctx) else {
            return Ok(false);
        };
        let map = &*self.map;
        let cost = self.cost;
        let u = ctx.upper_bound(&cost);
        // (this axis's variable, its bounds and size, the other's)
        let (var, lo, hi, n, other, olo, ohi, on) = match axis {
            Axis::X => (self.gx, b.lx, b.ux, map.nx, self.gy, b.ly, b.uy, map.ny),
            Axis::Y => (self.gy, b.ly, b.uy, map.ny, self.gx, b.lx, b.ux, map.nx),
        };
        let fits = |line: usize| match axis {
            Axis::X => map.col_min(line, olo, ohi) <= u,
            Axis::Y => map.row_min(line, olo, ohi) <= u,
        };
        // The reason shared by both ends: the cost's bound and the other
        // axis's bounds (those not at the root).
        let mut base = PropositionalConjunction::default();
        base.push(predicate![cost <= u]);
        if olo > 0 {
            base.push(predicate![other >= olo as i32]);
        }
        if ohi + 1 < on {
            base.push(predicate![other <= ohi as i32]);
        }
        let Some(first) = (lo..=hi).find(|&l| fits(l)) else {
            // No line fits: the lower bound posted after this conflicts.
            return Ok(false);
        };
        let last = (first..=hi).rev().find(|&l| fits(l)).unwrap_or(first);
        let mut moved = false;
        if first > lo {
            let mut r = base.clone();
            if lo > 0 {
                r.push(predicate![var >= lo as i32]);
            }
            ctx.post(predicate![var >= first as i32], (r, &self.code))?;
            moved = true;
        }
        if last < hi {
            let mut r = base;
            if hi + 1 < n {
                r.push(predicate![var <= hi as i32]);
            }
            ctx.post(predicate![var <= last as i32], (r, &self.code))?;
            moved = true;
        }
        Ok(moved)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sparse_table_minima_match_a_scan() {
        let v: Vec<i32> = (0..37).map(|i: i32| (i * 7919) % 23).collect();
        let t = SparseTable::new(v.clone());
        for lo in 0..v.len() {
            for hi in lo..v.len() {
                assert_eq!(t.min(lo, hi), *v[lo..=hi].iter().min().unwrap());
            }
        }
    }

    #[test]
    fn box_minima_match_a_scan() {
        let (nx, ny) = (9, 6);
        let cost: Vec<i32> = (0..nx * ny).map(|i| ((i * 31) % 17) as i32).collect();
        let m = MapIndex::new(nx, ny, &cost);
        for lx in 0..nx {
            for ux in lx..nx {
                for ly in 0..ny {
                    for uy in ly..ny {
                        let want = (ly..=uy)
                            .flat_map(|b| (lx..=ux).map(move |a| (a, b)))
                            .map(|(a, b)| cost[b * nx + a])
                            .min()
                            .unwrap();
                        assert_eq!(m.box_min(lx, ux, ly, uy), want);
                    }
                }
            }
        }
    }
}
