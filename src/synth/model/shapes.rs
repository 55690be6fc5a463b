//! Group statements in the model: one literal, defined exactly (both
//! directions) by And/Or over the pair literals of [`crate::shapes`]'s
//! adjacency and bounds on coordinate differences, so every model
//! Boolean stays a function of the grid values and the engine, the brute
//! force check, `eval_bools` and the emitted models need nothing new.
//!
//! # Background
//!
//! Connectivity is the hard part of a group statement for a CP engine: it
//! is a property of the whole contact graph. We build it as a layered
//! reachability circuit from the class's first object: `r⁰ᵢ` is true for
//! the root only, `rᵏᵢ = rᵏ⁻¹ᵢ ∨ ⋁ⱼ (rᵏ⁻¹ⱼ ∧ adjᵢⱼ)`, and the class is
//! connected when every `rᵐ⁻¹ᵢ` holds. Each layer is an exact definition,
//! so the literal is true exactly when the objects form one component,
//! and its negation exactly when they do not: a probe can ask for a
//! broken shape as easily as a layout can ask for a kept one.
//!
//! A row or a column needs no circuit: on one line, with interiors that
//! do not overlap, "the objects span exactly the sum of their sizes" is
//! one contiguous run, so it is a conjunction of difference literals
//! (`run_shape`), which the engine propagates on the coordinates' bounds.
//! The circuit is kept for `group` and `block` (and for a row or column
//! whose class has two fixed objects that overlap).
//!
//! # Practical
//!
//! The circuit has `O(m³)` And nodes for `m` objects of the class (a few
//! hundred for the 4–9 objects shapes are about; hash-consing folds the
//! constant parts of fixed objects). Redundant clauses, each implied by
//! the definitions or by non-overlap, give the engine shortcuts it would
//! otherwise have to learn:
//!
//! - a shape that holds gives every object an adjacent one;
//! - a row (column) that holds puts every south (west) edge on the first
//!   object's line, and its objects span exactly the sum of their widths
//!   (heights) — implied by non-overlap, so only stated when no two fixed
//!   objects of the class overlap;
//! - a block's box is a conjunction of bounds `x₂ᵢ − xⱼ ≤ a·cell` over the
//!   ordered pairs, one disjunct per box of [`crate::shapes::block_boxes`].
//!
//! # How to extend
//!
//! A new shape is its adjacency in [`crate::shapes::ShapeKind::adjacency`]
//! (read here as pair literals) and, when it bounds the extent, a
//! conjunction of difference bounds like the block's.

use super::{Axis, BoolDef, Connectivity, Lit, Model};
use crate::relations::{Contact, Edge};
use crate::shapes::{block_boxes, ShapeKind};

impl Model {
    /// The literal "the `objects` (indices into the problem's objects, all
    /// of one class) form `kind`", exactly as [`crate::shapes::check`]
    /// decides it.
    pub(super) fn shape(&mut self, kind: ShapeKind, objects: &[usize], contact: Contact) -> Lit {
        let m = objects.len();
        if m < 2 {
            return Lit::TRUE;
        }
        if let Some(run) = self.run_shape(kind, objects) {
            return run;
        }
        let (contacts, align) = kind.adjacency();
        // adj[i][j], symmetric.
        let mut adj = vec![vec![Lit::FALSE; m]; m];
        for i in 0..m {
            for j in i + 1..m {
                let (a, b) = (objects[i], objects[j]);
                let touch: Vec<Lit> = contacts
                    .iter()
                    .map(|&r| self.pair(r, a, b, contact))
                    .collect();
                let mut l = self.or(touch);
                if let Some(al) = align {
                    let al = self.pair(al, a, b, contact);
                    l = self.and(vec![l, al]);
                }
                adj[i][j] = l;
                adj[j][i] = l;
            }
        }
        let connected = self.connected(&adj);
        let mut parts = vec![connected];
        if kind == ShapeKind::Block {
            let b = self.block_box(objects);
            parts.push(b);
        }
        let shape = self.and(parts);
        self.shape_redundancy(kind, shape, objects, &adj);
        shape
    }

    /// A row (column) without a circuit: every object on the first one's
    /// south (west) line, and the objects spanning no more than the sum of
    /// their widths (heights) along it. With interiors that do not overlap
    /// (the model's non-overlap; not stated when two fixed objects of the
    /// class overlap, `None` then) that is exactly one contiguous run: on
    /// one line, a span equal to the sum of the sizes leaves no gap, and
    /// neighbours on the line share an edge of positive length. `O(m²)`
    /// difference literals, which the engine propagates on the bounds.
    fn run_shape(&mut self, kind: ShapeKind, objects: &[usize]) -> Option<Lit> {
        let (line, along) = match kind {
            ShapeKind::Row => (Axis::Y, Axis::X),
            ShapeKind::Column => (Axis::X, Axis::Y),
            _ => return None,
        };
        // A sum of sizes that depends on orientations: the circuit.
        if self.fixed_pair_overlaps(objects) || self.any_turns(objects) {
            return None;
        }
        let first = objects[0];
        let mut parts = Vec::new();
        for &o in &objects[1..] {
            parts.push(self.diff_ge(line, o, first, 0));
            parts.push(self.diff_ge(line, first, o, 0));
        }
        let total = objects
            .iter()
            .map(|&o| self.size(o, along))
            .fold(0i64, |s, v| s.saturating_add(v));
        parts.push(self.extent_at_most(along, objects, total));
        Some(self.and(parts))
    }

    /// Whether an object of `objects` has an orientation variable.
    fn any_turns(&self, objects: &[usize]) -> bool {
        objects.iter().any(|&o| self.turn_vars[o].is_some())
    }

    /// Whether two fixed (constant) objects of `objects` overlap.
    fn fixed_pair_overlaps(&self, objects: &[usize]) -> bool {
        objects.iter().enumerate().any(|(n, &a)| {
            objects[n + 1..]
                .iter()
                .any(|&b| self.is_const(a) && self.is_const(b) && self.const_overlap(a, b))
        })
    }

    /// True exactly when the graph over `adj` (symmetric) is connected, in
    /// the model's [`Connectivity`].
    fn connected(&mut self, adj: &[Vec<Lit>]) -> Lit {
        match self.connectivity {
            Connectivity::Circuit => self.connected_circuit(adj),
            Connectivity::Propagator => self.connected_def(adj),
        }
    }

    /// One [`BoolDef::Connected`]: nodes joined by a constant-true edge
    /// are merged first, constant-false edges dropped, so its edges are
    /// variable literals between distinct nodes. Folds to a constant when
    /// everything is merged (true) or a node has no edge left (false).
    fn connected_def(&mut self, adj: &[Vec<Lit>]) -> Lit {
        let m = adj.len();
        let mut parent: Vec<usize> = (0..m).collect();
        for (i, row) in adj.iter().enumerate() {
            for (j, &l) in row.iter().enumerate().skip(i + 1) {
                if l == Lit::TRUE {
                    let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                    parent[a] = b;
                }
            }
        }
        let mut label = vec![usize::MAX; m];
        let mut nodes = 0usize;
        for i in 0..m {
            let r = find(&mut parent, i);
            if label[r] == usize::MAX {
                label[r] = nodes;
                nodes += 1;
            }
        }
        if nodes == 1 {
            return Lit::TRUE;
        }
        let mut edges = Vec::new();
        let mut touched = vec![false; nodes];
        for (i, row) in adj.iter().enumerate() {
            for (j, &l) in row.iter().enumerate().skip(i + 1) {
                if let Lit::Var { .. } = l {
                    let a = label[find(&mut parent, i)];
                    let b = label[find(&mut parent, j)];
                    if a != b {
                        touched[a] = true;
                        touched[b] = true;
                        edges.push((a.min(b) as u32, a.max(b) as u32, l));
                    }
                }
            }
        }
        if touched.contains(&false) {
            return Lit::FALSE;
        }
        edges.sort_unstable();
        edges.dedup();
        self.intern(BoolDef::Connected {
            nodes: nodes as u32,
            edges,
        })
    }

    /// Layered reachability from object 0 over `adj`: true exactly when
    /// the graph is connected.
    fn connected_circuit(&mut self, adj: &[Vec<Lit>]) -> Lit {
        let m = adj.len();
        let mut reach: Vec<Lit> = (0..m).map(|i| Lit::Const(i == 0)).collect();
        for _ in 1..m {
            let mut next = Vec::with_capacity(m);
            for i in 0..m {
                let mut ways = vec![reach[i]];
                for j in 0..m {
                    if j != i {
                        let w = self.and(vec![reach[j], adj[i][j]]);
                        ways.push(w);
                    }
                }
                next.push(self.or(ways));
            }
            if next == reach {
                break;
            }
            reach = next;
        }
        self.and(reach)
    }

    /// The class's bounding box fits one of the block's boxes, whose cell
    /// is the largest footprint width × the largest footprint height
    /// ([`crate::shapes::block_cell`]). With orientation variables the
    /// cell depends on them: one case per possible cell, `cell = (cw, ch)
    /// ∧ fits(cw, ch)`, exactly one of which holds.
    fn block_box(&mut self, objects: &[usize]) -> Lit {
        if !self.any_turns(objects) {
            let cw = objects.iter().map(|&o| self.sizes[o].0).max().unwrap_or(0);
            let ch = objects.iter().map(|&o| self.sizes[o].1).max().unwrap_or(0);
            return self.block_box_of(objects, cw, ch);
        }
        // `max over objects of side = v`: some object has v, none more.
        let max_is = |m: &mut Self, axis: Axis, v: i64| -> Lit {
            let mut some = Vec::new();
            let mut none_more = Vec::new();
            for &o in objects {
                for (l, side) in m.sides(o, axis) {
                    if side == v {
                        some.push(l);
                    } else if side > v {
                        none_more.push(!l);
                    }
                }
            }
            let some = m.or(some);
            none_more.push(some);
            m.and(none_more)
        };
        let values = |m: &mut Self, axis: Axis| -> Vec<i64> {
            let mut v: Vec<i64> = objects
                .iter()
                .flat_map(|&o| m.sides(o, axis).into_iter().map(|c| c.1))
                .collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        let (ws, hs) = (values(self, Axis::X), values(self, Axis::Y));
        let mut cases = Vec::new();
        for &cw in &ws {
            for &ch in &hs {
                let cell = vec![max_is(self, Axis::X, cw), max_is(self, Axis::Y, ch)];
                let cell = self.and(cell);
                if cell == Lit::FALSE {
                    continue;
                }
                let fits = self.block_box_of(objects, cw, ch);
                cases.push(self.and(vec![cell, fits]));
            }
        }
        self.or(cases)
    }

    /// The class's bounding box fits one of the block's boxes of cell
    /// `cw × ch`.
    fn block_box_of(&mut self, objects: &[usize], cw: i64, ch: i64) -> Lit {
        let mut boxes = Vec::new();
        for (a, b) in block_boxes(objects.len()) {
            let (Some(kx), Some(ky)) = (
                i64::try_from(a).ok().and_then(|a| a.checked_mul(cw)),
                i64::try_from(b).ok().and_then(|b| b.checked_mul(ch)),
            ) else {
                // A box wider than any coordinate: it always fits.
                boxes.push(Lit::TRUE);
                continue;
            };
            let fit = vec![
                self.extent_at_most(Axis::X, objects, kx),
                self.extent_at_most(Axis::Y, objects, ky),
            ];
            boxes.push(self.and(fit));
        }
        self.or(boxes)
    }

    /// `max(c + size) − min(c) ≤ k` over `objects` on `axis`: for every
    /// ordered pair, `c_j − c_i ≥ size_i − k` (the far edge of `i` at most
    /// `k` past the near edge of `j`, over `i`'s orientations when it may
    /// turn).
    fn extent_at_most(&mut self, axis: Axis, objects: &[usize], k: i64) -> Lit {
        let (near, far) = match axis {
            Axis::X => (Edge::X, Edge::X2),
            Axis::Y => (Edge::Y, Edge::Y2),
        };
        let mut lits = Vec::new();
        for &i in objects {
            for &j in objects {
                if i != j {
                    lits.push(self.edge_ge(axis, (j, near), (i, far), k.saturating_neg()));
                }
            }
        }
        self.and(lits)
    }

    /// Clauses implied by the shape's definition (or by non-overlap),
    /// stated so the engine need not learn them.
    fn shape_redundancy(
        &mut self,
        kind: ShapeKind,
        shape: Lit,
        objects: &[usize],
        adj: &[Vec<Lit>],
    ) {
        if shape == Lit::FALSE || shape == Lit::TRUE {
            return;
        }
        let m = objects.len();
        for (i, row) in adj.iter().enumerate() {
            let mut c = vec![!shape];
            c.extend((0..m).filter(|&j| j != i).map(|j| row[j]));
            self.clauses.push(c);
        }
        let axis = match kind {
            ShapeKind::Row => Axis::Y,
            ShapeKind::Column => Axis::X,
            _ => return,
        };
        // Every object on the first one's line.
        let first = objects[0];
        for &o in &objects[1..] {
            let ge = self.diff_ge(axis, o, first, 0);
            let le = self.diff_ge(axis, first, o, 0);
            self.clauses.push(vec![!shape, ge]);
            self.clauses.push(vec![!shape, le]);
        }
        // The run spans the sum of the sizes along it (non-overlap; not
        // stated when the sizes depend on orientations).
        let along = match axis {
            Axis::Y => Axis::X,
            Axis::X => Axis::Y,
        };
        if self.fixed_pair_overlaps(objects) || self.any_turns(objects) {
            return;
        }
        let total = objects
            .iter()
            .map(|&o| self.size(o, along))
            .fold(0i64, |s, v| s.saturating_add(v));
        for &i in objects {
            let si = self.size(i, along);
            for &j in objects {
                if i != j {
                    let l = self.diff_ge(along, j, i, si.saturating_sub(total));
                    self.clauses.push(vec![!shape, l]);
                }
            }
        }
    }
}

/// The root of `i` in a union-find forest (path halving).
fn find(p: &mut [usize], mut i: usize) -> usize {
    while p[i] != i {
        p[i] = p[p[i]];
        i = p[i];
    }
    i
}

/// Whether the graph on `nodes` nodes is connected over the `edges` whose
/// literal `holds` (the meaning of [`BoolDef::Connected`]).
pub(crate) fn connected_under(
    nodes: usize,
    edges: &[(u32, u32, Lit)],
    holds: impl Fn(Lit) -> bool,
) -> bool {
    let mut parent: Vec<usize> = (0..nodes).collect();
    let mut parts = nodes;
    for &(a, b, l) in edges {
        if holds(l) {
            let (ra, rb) = (find(&mut parent, a as usize), find(&mut parent, b as usize));
            if ra != rb {
                parent[ra] = rb;
                parts -= 1;
            }
        }
    }
    parts <= 1
}
