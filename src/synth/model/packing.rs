//! The packing constraints of a model: non-overlap of every pair (as
//! clauses, or checked on grid values), symmetry breaking between
//! interchangeable objects and the redundant cumulative relaxations.

use super::{Coord, Cumulative, LinLe, Lit, Model};
use crate::relations::{Axis, Contact, Dir, Kind, Relation};
use crate::scene::Scene;

impl Model {
    /// State non-overlap explicitly, as the clause `DR_N ∨ DR_S ∨ DR_E ∨
    /// DR_W` per pair with at least one variable object (quadratic: for
    /// `--emit`'s peers, which have no propagator of their own).
    pub fn add_pairwise_no_overlap(&mut self, contact: Contact) {
        if !self.too_large.is_empty() || self.pairwise_no_overlap {
            return;
        }
        self.pairwise_no_overlap = true;
        let n = self.coords.len();
        let mut clauses = Vec::new();
        for a in 0..n {
            for b in a + 1..n {
                if self.is_const(a) && self.is_const(b) {
                    continue;
                }
                let c: Vec<Lit> = Dir::ALL
                    .iter()
                    .map(|&d| self.pair(Relation::new(Kind::DR, d), a, b, contact))
                    .collect();
                let l = self.or(c);
                if l != Lit::TRUE {
                    clauses.push(vec![l]);
                }
            }
        }
        // Non-overlap clauses come first.
        clauses.append(&mut self.clauses);
        self.clauses = clauses;
    }

    /// Whether grid values `vals` place no two objects with overlapping
    /// interiors (the non-overlap every model implies; see
    /// [`Model::add_pairwise_no_overlap`]).
    pub fn non_overlapping(&self, vals: &[i64]) -> bool {
        let at = |c: Coord, o: i64| match c {
            Coord::Const(v) => v,
            Coord::Var(v) => o + self.grid * vals[v],
        };
        let boxes: Vec<(i64, i64, i64, i64)> = (0..self.coords.len())
            .map(|i| {
                let (cx, cy) = self.coords[i];
                let (w, h) = self.footprint_in(i, vals);
                let (x, y) = (at(cx, self.origin.0), at(cy, self.origin.1));
                (x, y, x + w, y + h)
            })
            .collect();
        (0..boxes.len()).all(|a| {
            (a + 1..boxes.len()).all(|b| {
                (self.is_const(a) && self.is_const(b)) || {
                    let (p, q) = (boxes[a], boxes[b]);
                    p.2 <= q.0 || q.2 <= p.0 || p.3 <= q.1 || q.3 <= p.1
                }
            })
        })
    }

    /// Whether two constant objects' interiors overlap (false when either
    /// is a variable).
    pub(super) fn const_overlap(&self, a: usize, b: usize) -> bool {
        let ((Coord::Const(ax), Coord::Const(ay)), (Coord::Const(bx), Coord::Const(by))) =
            (self.coords[a], self.coords[b])
        else {
            return false;
        };
        let ((aw, ah), (bw, bh)) = (self.sizes[a], self.sizes[b]);
        ax < bx + bw && bx < ax + aw && ay < by + bh && by < ay + ah
    }

    pub(super) fn post_symmetry(&mut self, problem: &Scene) {
        // Groups of unplaced objects with the same class, size and
        // turnability (a turnable object is not interchangeable with one
        // that may not turn).
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for (i, o) in problem.objects.iter().enumerate() {
            if o.is_placed() {
                continue;
            }
            match groups.iter_mut().find(|g| {
                let p = &problem.objects[g[0]];
                p.class == o.class
                    && (p.width, p.height, p.turned) == (o.width, o.height, o.turned)
                    && p.turnable == o.turnable
            }) {
                Some(g) => g.push(i),
                None => groups.push(vec![i]),
            }
        }
        for g in groups {
            for w in g.windows(2) {
                let (Coord::Var(xa), Coord::Var(ya)) = self.coords[w[0]] else {
                    continue;
                };
                let (Coord::Var(xb), Coord::Var(yb)) = self.coords[w[1]] else {
                    continue;
                };
                if let (Some(ta), Some(tb)) = (self.turn_vars[w[0]], self.turn_vars[w[1]]) {
                    self.order_turning(ta, tb, (xa, ya), (xb, yb));
                    continue;
                }
                let nx = self.vars[xa].ub + 1;
                // (ya, xa) <lex (yb, xb): as the linear
                // nx·ya + xa < nx·yb + xb when its products fit the engine's
                // i32 arithmetic, else as clauses without products.
                let lin = LinLe {
                    terms: vec![(nx, ya), (1, xa), (-nx, yb), (-1, xb)],
                    rhs: -1,
                };
                if self.lin_fits_i32(&lin) {
                    self.symmetry.push(lin);
                } else {
                    // ya ≤ yb, and ya < yb ∨ xa < xb.
                    let le = self.vdiff_ge(yb, ya, 0);
                    let lt_y = self.vdiff_ge(yb, ya, 1);
                    let lt_x = self.vdiff_ge(xb, xa, 1);
                    self.clauses.push(vec![le]);
                    self.clauses.push(vec![lt_y, lt_x]);
                }
            }
        }
    }

    /// Symmetry breaking between two consecutive objects `a`, `b` of a
    /// group of interchangeable objects that may turn (orientation
    /// variables `ta`, `tb`): `ta ≥ tb` (the turned ones first), and when
    /// both lie the same way, `(ya, xa) <lex (yb, xb)`.
    ///
    /// Sound: take any layout and re-assign the group's placements
    /// (position and orientation) to its objects sorted by (not turned,
    /// y, x). The objects are interchangeable — one class, size and
    /// turnability, unplaced, so no rule, landmark or score tells them
    /// apart — so the new layout keeps every rule and the score; two
    /// objects of one orientation never share a position (they would
    /// overlap), so within an orientation the order is strict. Along the
    /// chain the orientations are non-increasing and, where consecutive
    /// objects agree, the positions increase: the layout satisfies these
    /// constraints. (Tested against brute force in the differential tests.)
    fn order_turning(
        &mut self,
        ta: usize,
        tb: usize,
        (xa, ya): (usize, usize),
        (xb, yb): (usize, usize),
    ) {
        // ta ≥ tb.
        let order = LinLe {
            terms: vec![(-1, ta), (1, tb)],
            rhs: 0,
        };
        self.symmetry.push(order);
        // nx·ya + xa < nx·yb + xb unless ta > tb: with ta − tb ∈ {0, 1},
        // nx·ya + xa − nx·yb − xb − big·(ta − tb) ≤ −1, where `big`
        // exceeds every value the left side's first terms take.
        let nx = self.vars[xa].ub.max(self.vars[xb].ub) + 1;
        let ny = self.vars[ya].ub.max(self.vars[yb].ub) + 1;
        let big = nx.saturating_mul(ny).saturating_add(1);
        let lin = LinLe {
            terms: vec![
                (nx, ya),
                (1, xa),
                (-nx, yb),
                (-1, xb),
                (-big, ta),
                (big, tb),
            ],
            rhs: -1,
        };
        if self.lin_fits_i32(&lin) {
            self.symmetry.push(lin);
        } else {
            // Unless a is turned and b is not: ya ≤ yb, and ya < yb ∨ xa < xb.
            let differ = {
                let (a, b) = (self.ge(ta, 1), self.ge(tb, 1));
                self.and(vec![a, !b])
            };
            let le = self.vdiff_ge(yb, ya, 0);
            let lt_y = self.vdiff_ge(yb, ya, 1);
            let lt_x = self.vdiff_ge(xb, xa, 1);
            self.clauses.push(vec![differ, le]);
            self.clauses.push(vec![differ, lt_y, lt_x]);
        }
    }

    /// Whether every partial sum of `Σ coef·var` (and the right-hand side)
    /// stays within `i32`: `Σ |coef|·ub + |rhs| ≤ i32::MAX`.
    pub fn lin_fits_i32(&self, l: &LinLe) -> bool {
        let sum: i128 = l
            .terms
            .iter()
            .map(|&(c, v)| i128::from(c).abs() * i128::from(self.vars[v].ub))
            .sum::<i128>()
            + i128::from(l.rhs).abs();
        sum <= i128::from(i32::MAX)
    }

    /// The shift added to every start of a cumulative in the engine, so
    /// that every start is at least 0: Pumpkin 0.5's time-table uses the
    /// time `-1` as "no profile yet" and panics ("negative resource usage")
    /// when a task really starts at `-1` (found by the `synth` fuzz target:
    /// `fuzz/regressions/synth/pumpkin-cumulative-negative-usage.bin`). The
    /// relaxation is invariant under a shift of the axis.
    pub fn cumulative_shift(&self, c: &Cumulative) -> i64 {
        let lowest = c
            .tasks
            .iter()
            .map(|&(o, _, _)| match self.coord(o, c.axis) {
                Coord::Const(v) => v,
                Coord::Var(_) => self.axis_origin(c.axis),
            })
            .min()
            .unwrap_or(0);
        -lowest
    }

    /// Whether a cumulative's numbers stay within `i32` in the engine:
    /// the sum of every demand plus the capacity, and every task's largest
    /// start (shifted by [`Model::cumulative_shift`]) plus its duration.
    pub fn cumulative_fits_i32(&self, c: &Cumulative) -> bool {
        let demands: i128 = c.tasks.iter().map(|t| i128::from(t.2).abs()).sum();
        let origin = i128::from(self.axis_origin(c.axis));
        let shift = i128::from(self.cumulative_shift(c));
        let ends_fit = c.tasks.iter().all(|&(o, dur, _)| {
            let start = match self.coord(o, c.axis) {
                Coord::Const(v) => i128::from(v) + shift,
                Coord::Var(v) => {
                    origin + shift + i128::from(self.grid) * i128::from(self.vars[v].ub)
                }
            };
            (0..=i128::from(i32::MAX)).contains(&start)
                && start + i128::from(dur).abs() <= i128::from(i32::MAX)
        });
        ends_fit && demands + i128::from(c.capacity).abs() <= i128::from(i32::MAX)
    }

    pub(super) fn post_cumulative(&mut self, problem: &Scene) {
        let sp = problem.space;
        for (axis, capacity) in [(Axis::X, sp.height), (Axis::Y, sp.width)] {
            let tasks: Vec<(usize, i64, i64)> = (0..problem.objects.len())
                .map(|i| {
                    // An object that may turn covers, either way, the
                    // square of its smaller side at its corner: that
                    // square is its task (the relaxation stays sound).
                    let (w, h) = match self.turn_vars[i] {
                        Some(_) => {
                            let m = self.sizes[i].0.min(self.sizes[i].1);
                            (m, m)
                        }
                        None => self.sizes[i],
                    };
                    match axis {
                        Axis::X => (i, w, h),
                        Axis::Y => (i, h, w),
                    }
                })
                .collect();
            if tasks.iter().filter(|t| !self.is_const(t.0)).count() >= 2 {
                let c = Cumulative {
                    axis,
                    tasks,
                    capacity,
                };
                // Redundant: left out when its sums could leave i32.
                if self.cumulative_fits_i32(&c) {
                    self.cumulative.push(c);
                }
            }
        }
    }
}
