//! A propagator for the resemblance cost of a *group*: the objects of one
//! class and size, which share one distance map and cannot overlap.
//!
//! # Background
//!
//! Each object's cost is bounded below by the minimum of its map over its
//! current box ([`resemblance_map`](super::resemblance_map)). When a problem has more
//! objects of a class than the demonstrations show positions, every object
//! can still sit on a shown position *alone*, so the sum of those minima
//! stays at 0 while every layout costs more: the objects compete for the
//! same cells. Clause learning rediscovers that competition one placement
//! at a time.
//!
//! The counting argument: partition the grid into tiles of `tw × th`
//! cells, `tw = ⌈w / grid⌉`, `th = ⌈h / grid⌉`. Two objects of size
//! `w × h` whose anchors lie in one tile overlap, so the `n` objects of a
//! group use `n` distinct tiles, and each pays at least the minimum of the
//! map over the cells of its tile it may still take. Hence
//!
//! ```text
//! Σᵢ cᵢ ≥ sum of the n smallest tile minima
//! ```
//!
//! over the cells inside the union of the objects' boxes that no fixed
//! object blocks; every offset of the tiling gives a bound, and the largest
//! is posted. Fewer tiles than objects is a conflict (the group cannot be
//! packed there).
//!
//! # Practical
//!
//! The bound is monotone in the boxes (smaller boxes: fewer cells, larger
//! tile minima, fewer tiles), so its reason is the bounds of every object
//! of the group that differ from the root. One propagation costs
//! `O(tw · th · cells of the union's bounding box)`; it runs at low
//! priority, after the cheap propagators.
//!
//! # How to extend
//!
//! A matching between objects and tiles (each object confined to the tiles
//! its own box reaches) is the exact relaxation of this argument and would
//! be stronger when the boxes are far apart.

use pumpkin_constraints::equals;
use pumpkin_core::declare_inference_label;
use pumpkin_core::predicate;
use pumpkin_core::predicates::PropositionalConjunction;
use pumpkin_core::proof::{ConstraintTag, InferenceCode};
use pumpkin_core::propagation::{
    DomainEvents, EventsToRegister, LocalId, Priority, PropagationContext, Propagator,
    PropagatorConstructor, PropagatorConstructorContext, PropagatorSpec, ReadDomains,
    RuntimeCheckers,
};
use pumpkin_core::state::PropagationStatusCP;
use pumpkin_core::variables::{AffineView, DomainId, TransformableVariable};
use pumpkin_core::Solver;
use std::cell::RefCell;
use std::rc::Rc;

declare_inference_label!(ResemblanceGroup);

/// The static data of a group: its map with blocked cells, and its tile.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct GroupMap {
    /// Grid positions along x (the variables' root domain is `0..nx`).
    pub(crate) nx: usize,
    /// Grid positions along y.
    pub(crate) ny: usize,
    /// Tile width in cells, `⌈w / grid⌉ ≥ 1`.
    pub(crate) tw: usize,
    /// Tile height in cells.
    pub(crate) th: usize,
    /// Cost per cell, row-major; `None` where a fixed object blocks it.
    pub(crate) cost: Vec<Option<i32>>,
}

impl GroupMap {
    /// The bound for `n` objects whose anchors lie in the union of `boxes`
    /// (`(lx, ux, ly, uy)`, inclusive, clamped to the grid): `None` when
    /// fewer than `n` tiles are left, i.e. the group cannot be packed.
    pub(crate) fn bound(&self, n: usize, boxes: &[(usize, usize, usize, usize)]) -> Option<i64> {
        if n == 0 {
            return Some(0);
        }
        let (nx, ny) = (self.nx, self.ny);
        let mut mark = vec![false; nx * ny];
        let (mut bx0, mut bx1, mut by0, mut by1) = (usize::MAX, 0, usize::MAX, 0);
        for &(lx, ux, ly, uy) in boxes {
            bx0 = bx0.min(lx);
            bx1 = bx1.max(ux);
            by0 = by0.min(ly);
            by1 = by1.max(uy);
            for gy in ly..=uy {
                mark[gy * nx + lx..=gy * nx + ux].fill(true);
            }
        }
        if bx0 > bx1 || by0 > by1 {
            return None;
        }
        let mut best: Option<i64> = None;
        let mut tiles: Vec<i32> = Vec::new();
        for ox in 0..self.tw {
            for oy in 0..self.th {
                let cols = (bx1 + ox) / self.tw - (bx0 + ox) / self.tw + 1;
                let rows = (by1 + oy) / self.th - (by0 + oy) / self.th + 1;
                tiles.clear();
                tiles.resize(cols * rows, i32::MAX);
                for gy in by0..=by1 {
                    let ty = (gy + oy) / self.th - (by0 + oy) / self.th;
                    for gx in bx0..=bx1 {
                        let i = gy * nx + gx;
                        let (true, Some(c)) = (mark[i], self.cost[i]) else {
                            continue;
                        };
                        let tx = (gx + ox) / self.tw - (bx0 + ox) / self.tw;
                        let t = &mut tiles[ty * cols + tx];
                        *t = (*t).min(c);
                    }
                }
                tiles.retain(|&c| c != i32::MAX);
                if tiles.len() < n {
                    return None;
                }
                tiles.select_nth_unstable(n - 1);
                let sum: i64 = tiles[..n].iter().map(|&c| i64::from(c)).sum();
                best = Some(best.map_or(sum, |b: i64| b.max(sum)));
            }
        }
        best
    }
}

/// One group's variables and map.
#[derive(Debug, Clone)]
pub(super) struct GroupVars {
    pub(super) xs: Vec<DomainId>,
    pub(super) ys: Vec<DomainId>,
    /// The members' cost variables.
    pub(super) costs: Vec<DomainId>,
    pub(super) map: Rc<GroupMap>,
}

/// The groups of a model's resemblance terms, posted with the rest of the
/// second objective ([`super::resemblance`]).
#[derive(Debug, Clone)]
pub(super) struct CostGroups {
    /// The groups of two or more objects.
    pub(super) groups: Vec<GroupVars>,
    /// The cost variables of every other term.
    pub(super) singles: Vec<DomainId>,
    /// The total resemblance cost (already the sum of every term).
    pub(super) total: DomainId,
}

impl CostGroups {
    /// Post, at the root: per group a variable `s = Σ cᵢ` with the
    /// propagator, and the redundant `total = Σ s + Σ singles` (a root
    /// conflict shows in the next solve, as for any added fact). Returns
    /// the variables it created.
    pub(super) fn post(self, solver: &mut Solver, tag: ConstraintTag) -> Vec<DomainId> {
        let mut parts: Vec<AffineView<DomainId>> = Vec::new();
        let mut created = Vec::new();
        for g in self.groups {
            let lo: i32 = g.costs.iter().map(|c| solver.lower_bound(c)).sum();
            let hi: i32 = g
                .costs
                .iter()
                .map(|c| solver.upper_bound(c))
                .fold(0, i32::saturating_add);
            let sum = solver.new_bounded_integer(lo, hi);
            created.push(sum);
            let mut terms: Vec<AffineView<DomainId>> =
                g.costs.iter().map(|c| c.scaled(1)).collect();
            terms.push(sum.scaled(-1));
            solver.add_constraint(equals(terms, 0, tag)).post();
            let _ = solver.add_propagator(ResemblanceGroupArgs {
                xs: g.xs,
                ys: g.ys,
                sum,
                map: g.map,
                tag,
            });
            parts.push(sum.scaled(1));
        }
        parts.extend(self.singles.iter().map(|c| c.scaled(1)));
        parts.push(self.total.scaled(-1));
        solver.add_constraint(equals(parts, 0, tag)).post();
        created
    }
}

/// Posts [`ResemblanceGroupPropagator`].
#[derive(Debug, Clone)]
pub(super) struct ResemblanceGroupArgs {
    xs: Vec<DomainId>,
    ys: Vec<DomainId>,
    /// The group's cost, `Σ cᵢ`.
    sum: DomainId,
    map: Rc<GroupMap>,
    tag: ConstraintTag,
}

impl PropagatorConstructor for ResemblanceGroupArgs {
    type PropagatorImpl = ResemblanceGroupPropagator;

    fn create(self, ctx: PropagatorConstructorContext) -> PropagatorSpec<Self::PropagatorImpl> {
        let free_above = ctx.upper_bound(&self.sum);
        let n = self.xs.len() as u32;
        let mut registration = EventsToRegister::builder().add(
            &self.sum,
            DomainEvents::UPPER_BOUND,
            LocalId::from(2 * n),
        );
        for (i, (x, y)) in self.xs.iter().zip(&self.ys).enumerate() {
            registration = registration
                .add(x, DomainEvents::BOUNDS, LocalId::from(2 * i as u32))
                .add(y, DomainEvents::BOUNDS, LocalId::from(2 * i as u32 + 1));
        }
        PropagatorSpec {
            registration: registration.build(),
            checkers: RuntimeCheckers::empty(),
            propagator: ResemblanceGroupPropagator {
                xs: self.xs,
                ys: self.ys,
                sum: self.sum,
                map: self.map,
                boxes: RefCell::new(Vec::new()),
                free_above,
                code: InferenceCode::new(self.tag, ResemblanceGroup),
            },
        }
    }
}

/// `Σ cᵢ ≥` the tile bound; see the module documentation.
#[derive(Debug, Clone)]
pub(super) struct ResemblanceGroupPropagator {
    xs: Vec<DomainId>,
    ys: Vec<DomainId>,
    sum: DomainId,
    map: Rc<GroupMap>,
    boxes: RefCell<Vec<(usize, usize, usize, usize)>>,
    /// The sum's root upper bound: at or above it, nothing is propagated.
    free_above: i32,
    code: InferenceCode,
}

impl ResemblanceGroupPropagator {
    /// The bounds of every object that are not at the root.
    fn reason(&self, ctx: &PropagationContext) -> PropositionalConjunction {
        let mut r = PropositionalConjunction::default();
        let (nx, ny) = (self.map.nx as i32, self.map.ny as i32);
        for (&x, &y) in self.xs.iter().zip(&self.ys) {
            for (v, n) in [(x, nx), (y, ny)] {
                let (lo, hi) = (ctx.lower_bound(&v), ctx.upper_bound(&v));
                if lo > 0 {
                    r.push(predicate![v >= lo]);
                }
                if hi < n - 1 {
                    r.push(predicate![v <= hi]);
                }
            }
        }
        r
    }
}

impl Propagator for ResemblanceGroupPropagator {
    fn name(&self) -> &str {
        "ResemblanceGroup"
    }

    fn priority(&self) -> Priority {
        Priority::Low
    }

    fn propagate_from_scratch(&self, mut ctx: PropagationContext) -> PropagationStatusCP {
        // Only a bounded cost can be pruned by the bound; while it is free
        // the group costs the search nothing.
        let sum = self.sum;
        if ctx.upper_bound(&sum) >= self.free_above {
            return Ok(());
        }
        let clamp = |v: i32, n: usize| (v.max(0) as usize).min(n.saturating_sub(1));
        let mut boxes = self.boxes.borrow_mut();
        boxes.clear();
        for (&x, &y) in self.xs.iter().zip(&self.ys) {
            let (lx, ux) = (ctx.lower_bound(&x), ctx.upper_bound(&x));
            let (ly, uy) = (ctx.lower_bound(&y), ctx.upper_bound(&y));
            boxes.push((
                clamp(lx, self.map.nx),
                clamp(ux, self.map.nx),
                clamp(ly, self.map.ny),
                clamp(uy, self.map.ny),
            ));
        }
        // No room for the group: a bound past the sum's domain (a conflict).
        let bound = match self.map.bound(self.xs.len(), &boxes) {
            Some(b) => i32::try_from(b).unwrap_or(i32::MAX),
            None => ctx.upper_bound(&sum).saturating_add(1),
        };
        drop(boxes);
        if bound > ctx.lower_bound(&sum) {
            let r = self.reason(&ctx);
            ctx.post(predicate![sum >= bound], (r, &self.code))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every way to put `n` pairwise non-overlapping `tw × th` objects on
    /// the free cells: the cheapest total (brute force).
    fn cheapest(m: &GroupMap, n: usize) -> Option<i64> {
        fn go(m: &GroupMap, n: usize, from: usize, taken: &mut Vec<(usize, usize)>) -> Option<i64> {
            if n == 0 {
                return Some(0);
            }
            let mut best: Option<i64> = None;
            for i in from..m.nx * m.ny {
                let (gx, gy) = (i % m.nx, i / m.nx);
                let Some(c) = m.cost[i] else { continue };
                let clash = taken
                    .iter()
                    .any(|&(a, b)| gx.abs_diff(a) < m.tw && gy.abs_diff(b) < m.th);
                if clash {
                    continue;
                }
                taken.push((gx, gy));
                if let Some(rest) = go(m, n - 1, i + 1, taken) {
                    let t = rest + i64::from(c);
                    best = Some(best.map_or(t, |b| b.min(t)));
                }
                taken.pop();
            }
            best
        }
        go(m, n, 0, &mut Vec::new())
    }

    /// The bound never exceeds the cheapest packing, and says "no room"
    /// only when there is none, on random maps with blocked cells.
    #[test]
    fn the_bound_is_a_lower_bound_of_the_cheapest_packing() {
        let mut seed = 7u64;
        let mut next = |k: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % k
        };
        let mut tight = 0;
        for case in 0..300 {
            let (nx, ny) = (2 + next(4) as usize, 2 + next(4) as usize);
            let (tw, th) = (1 + next(2) as usize, 1 + next(2) as usize);
            let cost = (0..nx * ny)
                .map(|_| (next(5) != 0).then(|| next(4) as i32))
                .collect();
            let m = GroupMap {
                nx,
                ny,
                tw,
                th,
                cost,
            };
            let n = 1 + next(3) as usize;
            let all = [(0, nx - 1, 0, ny - 1)];
            let want = cheapest(&m, n);
            let got = m.bound(n, &all);
            match (want, got) {
                (Some(w), Some(g)) => {
                    assert!(g <= w, "case {case}: bound {g} above the cheapest {w}");
                    tight += usize::from(g == w);
                }
                (Some(w), None) => panic!("case {case}: no room claimed, but {w} packs"),
                (None, _) => {}
            }
        }
        // Not vacuous: the bound is often exact on small maps.
        assert!(tight > 100, "only {tight} tight bounds");
    }

    /// Anchors 0, 1, 2 on a strip: two objects two cells wide fit (at 0
    /// and 2), three do not; and a blocked cell leaves room for one.
    #[test]
    fn too_few_tiles_is_no_room() {
        let mut m = GroupMap {
            nx: 3,
            ny: 1,
            tw: 2,
            th: 1,
            cost: vec![Some(0), Some(5), Some(1)],
        };
        assert_eq!(m.bound(2, &[(0, 2, 0, 0)]), Some(1));
        assert_eq!(m.bound(3, &[(0, 2, 0, 0)]), None);
        m.cost[2] = None;
        assert_eq!(m.bound(2, &[(0, 2, 0, 0)]), None);
        assert_eq!(m.bound(1, &[(1, 2, 0, 0)]), Some(5));
    }
}
