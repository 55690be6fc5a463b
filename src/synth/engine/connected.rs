//! A propagator for one group statement's connectivity: the literal `c`
//! holds exactly when the graph on `n` nodes (the objects of one class)
//! is connected over the edges whose adjacency literal holds.
//!
//! # Background
//!
//! Connectivity is a property of the whole contact graph. As clauses it
//! needs a circuit (a layered reachability, `O(n³)` And nodes: what
//! `--emit` writes for peers), which propagates little: a layer learns
//! nothing until the layer below it is decided. On the realistic tasks,
//! where group statements are learned for most classes, the circuit made
//! solving several times slower. This propagator reads the whole graph at
//! once:
//!
//! - the edges that **hold** connect every node: `c` holds, explained by a
//!   spanning tree of them;
//! - the edges that **may** hold (not false) leave the graph in two or more
//!   parts: `c` is false, explained by the false edges across the cut
//!   around node 0's part (with every edge across it false, no layout
//!   completing this one is connected);
//! - with `c` true, an edge that is a **bridge** of the graph of edges that
//!   may hold must hold, explained by `c` and the other (false) edges
//!   across the cut the bridge closes;
//! - with `c` false and the edges that hold forming exactly two parts, an
//!   undecided edge joining them must be false, explained by `¬c` and a
//!   spanning tree of each part.
//!
//! # Practical
//!
//! Each run is `O(n + e)` (union-find, and Tarjan's bridges over a depth
//! first search), for the 3–30 objects of a class. It runs from scratch on
//! every change of `c` or of an edge literal.
//!
//! # How to extend
//!
//! A shape that bounds the extent (a block's box) stays difference
//! literals beside this propagator. A stronger propagation would reason on
//! the objects' positions (two objects too far apart to ever touch make an
//! edge false before the engine decides it), which the pair literals'
//! own propagators already do.

use pumpkin_core::declare_inference_label;
use pumpkin_core::predicates::PropositionalConjunction;
use pumpkin_core::proof::{ConstraintTag, InferenceCode};
use pumpkin_core::propagation::{
    DomainEvents, EventsToRegister, LocalId, Priority, PropagationContext, Propagator,
    PropagatorConstructor, PropagatorConstructorContext, PropagatorSpec, ReadDomains,
    RuntimeCheckers,
};
use pumpkin_core::state::PropagationStatusCP;
use pumpkin_core::variables::Literal;

declare_inference_label!(Connected);

/// Posts [`ConnectedPropagator`].
#[derive(Debug, Clone)]
pub(super) struct ConnectedArgs {
    /// `c`: the graph is connected.
    pub(super) out: Literal,
    /// Number of nodes (at least 2).
    pub(super) nodes: usize,
    /// `(a, b, literal)` per edge.
    pub(super) edges: Vec<(usize, usize, Literal)>,
    pub(super) tag: ConstraintTag,
}

impl PropagatorConstructor for ConnectedArgs {
    type PropagatorImpl = ConnectedPropagator;

    fn create(self, _: PropagatorConstructorContext) -> PropagatorSpec<Self::PropagatorImpl> {
        let mut registration =
            EventsToRegister::builder().add(&self.out, DomainEvents::ASSIGN, LocalId::from(0));
        for (i, (_, _, l)) in self.edges.iter().enumerate() {
            let id = u32::try_from(i + 1).unwrap_or(u32::MAX);
            registration = registration.add(l, DomainEvents::ASSIGN, LocalId::from(id));
        }
        PropagatorSpec {
            registration: registration.build(),
            checkers: RuntimeCheckers::empty(),
            propagator: ConnectedPropagator {
                out: self.out,
                nodes: self.nodes,
                edges: self.edges,
                code: InferenceCode::new(self.tag, Connected),
            },
        }
    }
}

/// `out ⇔ connected(nodes, edges)`; see the module documentation.
#[derive(Debug, Clone)]
pub(super) struct ConnectedPropagator {
    out: Literal,
    nodes: usize,
    edges: Vec<(usize, usize, Literal)>,
    code: InferenceCode,
}

/// An edge's current value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Val {
    True,
    False,
    Open,
}

/// A union-find forest over the nodes, remembering the edges that joined
/// two parts (a spanning forest).
struct Forest {
    parent: Vec<usize>,
    parts: usize,
    tree: Vec<usize>,
}

impl Forest {
    fn new(n: usize) -> Forest {
        Forest {
            parent: (0..n).collect(),
            parts: n,
            tree: Vec::new(),
        }
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    /// Join `a` and `b` through edge `e`; whether they were apart.
    fn join(&mut self, a: usize, b: usize, e: usize) -> bool {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return false;
        }
        self.parent[ra] = rb;
        self.parts -= 1;
        self.tree.push(e);
        true
    }
}

impl ConnectedPropagator {
    fn val(&self, ctx: &PropagationContext, l: Literal) -> Val {
        match ctx.evaluate_literal(l) {
            Some(true) => Val::True,
            Some(false) => Val::False,
            None => Val::Open,
        }
    }

    /// The forest of the edges whose value passes `keep`.
    fn forest(&self, vals: &[Val], keep: impl Fn(Val) -> bool) -> Forest {
        let mut f = Forest::new(self.nodes);
        for (e, &(a, b, _)) in self.edges.iter().enumerate() {
            if keep(vals[e]) {
                f.join(a, b, e);
            }
        }
        f
    }

    /// `[edge is false]` for every edge across the cut around the nodes
    /// with `side[node]` (all of them false), except `skip`.
    fn cut_reason(&self, side: &[bool], skip: Option<usize>) -> PropositionalConjunction {
        let mut r = PropositionalConjunction::default();
        for (e, &(a, b, l)) in self.edges.iter().enumerate() {
            if side[a] != side[b] && Some(e) != skip {
                r.push(l.get_false_predicate());
            }
        }
        r
    }

    /// `[edge holds]` for every edge of `tree`.
    fn tree_reason(&self, tree: &[usize], r: &mut PropositionalConjunction) {
        for &e in tree {
            r.push(self.edges[e].2.get_true_predicate());
        }
    }

    /// Bridges of the graph of the edges that may hold (connected, checked
    /// by the caller): per bridge, the nodes on the side away from node 0.
    fn bridges(&self, vals: &[Val]) -> Vec<(usize, Vec<bool>)> {
        let n = self.nodes;
        let mut adj: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
        for (e, &(a, b, _)) in self.edges.iter().enumerate() {
            if vals[e] != Val::False {
                adj[a].push((b, e));
                adj[b].push((a, e));
            }
        }
        // Iterative DFS from node 0: entry order, low links, subtree spans.
        let mut order = vec![usize::MAX; n];
        let mut low = vec![0usize; n];
        let mut parent_edge = vec![usize::MAX; n];
        let mut preorder: Vec<usize> = Vec::with_capacity(n);
        let mut end = vec![0usize; n];
        let mut stack: Vec<(usize, usize)> = vec![(0, 0)];
        order[0] = 0;
        low[0] = 0;
        preorder.push(0);
        let mut found = Vec::new();
        while let Some(top) = stack.last_mut() {
            let (v, next) = *top;
            if let Some(&(w, e)) = adj[v].get(next) {
                top.1 += 1;
                if e == parent_edge[v] {
                    continue;
                }
                if order[w] == usize::MAX {
                    order[w] = preorder.len();
                    low[w] = order[w];
                    parent_edge[w] = e;
                    preorder.push(w);
                    stack.push((w, 0));
                } else {
                    low[v] = low[v].min(order[w]);
                }
            } else {
                stack.pop();
                end[v] = preorder.len();
                if let Some(&(u, _)) = stack.last() {
                    low[u] = low[u].min(low[v]);
                    if low[v] > order[u] {
                        // The subtree of v is cut off by parent_edge[v].
                        let mut side = vec![false; n];
                        for &x in &preorder[order[v]..end[v]] {
                            side[x] = true;
                        }
                        found.push((parent_edge[v], side));
                    }
                }
            }
        }
        found
    }
}

impl Propagator for ConnectedPropagator {
    fn name(&self) -> &str {
        "Connected"
    }

    fn priority(&self) -> Priority {
        Priority::Low
    }

    fn propagate_from_scratch(&self, mut ctx: PropagationContext) -> PropagationStatusCP {
        let vals: Vec<Val> = self
            .edges
            .iter()
            .map(|&(_, _, l)| self.val(&ctx, l))
            .collect();
        let out = self.val(&ctx, self.out);
        // The edges that hold connect everything: c.
        let holds = self.forest(&vals, |v| v == Val::True);
        if holds.parts == 1 {
            let mut r = PropositionalConjunction::default();
            self.tree_reason(&holds.tree, &mut r);
            ctx.post(self.out.get_true_predicate(), (r, &self.code))?;
            return Ok(());
        }
        // The edges that may hold leave two parts or more: ¬c.
        let mut may = self.forest(&vals, |v| v != Val::False);
        if may.parts > 1 {
            let root = may.find(0);
            let side: Vec<bool> = (0..self.nodes).map(|i| may.find(i) == root).collect();
            let r = self.cut_reason(&side, None);
            ctx.post(self.out.get_false_predicate(), (r, &self.code))?;
            return Ok(());
        }
        match out {
            Val::True => {
                for (e, side) in self.bridges(&vals) {
                    if vals[e] == Val::Open {
                        let mut r = self.cut_reason(&side, Some(e));
                        r.push(self.out.get_true_predicate());
                        ctx.post(self.edges[e].2.get_true_predicate(), (r, &self.code))?;
                    }
                }
            }
            Val::False if holds.parts == 2 => {
                let mut holds = holds;
                for (e, &(a, b, l)) in self.edges.iter().enumerate() {
                    if vals[e] == Val::Open && holds.find(a) != holds.find(b) {
                        let mut r = PropositionalConjunction::default();
                        self.tree_reason(&holds.tree, &mut r);
                        r.push(self.out.get_false_predicate());
                        ctx.post(l.get_false_predicate(), (r, &self.code))?;
                    }
                }
            }
            _ => {}
        }
        Ok(())
    }
}
