//! The solver-independent synthesis model (SPEC §3, §4, §6, §9).
//!
//! # Variables
//!
//! Every unplaced object gets two integer *grid-index* variables `gx`, `gy`
//! with `x = space.x + grid·gx`, `y = space.y + grid·gy` and domains
//! `0..=⌊(space.width − width)/grid⌋` (resp. height), so the whole object lies
//! inside the space. Fixed and already-placed objects are constants.
//!
//! # Booleans
//!
//! Every Boolean is defined *exactly* (both directions) by a [`BoolDef`]:
//!
//! - `Ge { var, k }`: `var ≥ k` (a bound predicate of one grid variable);
//! - `DiffGe { a, b, k }`: `a − b ≥ k` (two grid variables);
//! - `And(lits)`: the conjunction of other literals (disjunction is its De
//!   Morgan dual, so it needs no definition of its own).
//!
//! Definitions are hash-consed: asking twice for the same inequality or the
//! same conjunction returns the same literal, so a pairwise relation atom such
//! as `DR_N(a, b)` is created once and shared by non-overlap, every rule and
//! its converse `DR_S(b, a)`. Inequalities between two constants, and
//! inequalities outside a variable's domain, fold to constants.
//!
//! Inequalities in real units are turned into grid units exactly:
//! `x_a − x_b ≥ d` with both variable is `gx_a − gx_b ≥ ⌈d/grid⌉`; with `b`
//! constant it is `gx_a ≥ ⌈(d + x_b − space.x)/grid⌉`; with `a` constant it is
//! `gx_b ≤ ⌊(x_a − space.x − d)/grid⌋`. Sizes need not be multiples of the grid.
//!
//! - `AtLeast { lits, k }`: at least `k` of `lits` hold (a reified count).
//!
//! # Relations (SPEC §3, §11.1)
//!
//! A pairwise relation literal is read straight off the relation's entry in
//! [`crate::relations::TABLE`]: its condition is a disjunction of
//! conjunctions of comparisons `lhs OP rhs` between edges of the two
//! objects, and each comparison is a bound on a coordinate difference
//! (`a.y ≥ b.y2` is `y_a − y_b ≥ h_b`; `a.x2 < b.x2` is
//! `x_b − x_a ≥ w_a − w_b + 1`; `==` is both `≥` and `≤`). So the model's
//! literals are, by construction, exactly the geometry of the table.
//! Non-overlap of a pair is the clause `DR_N ∨ DR_S ∨ DR_E ∨ DR_W` over the
//! same literals.
//!
//! # Rules (SPEC §4, §6, §11)
//!
//! A class atom `REL(o, Q B)` of object `o` counts the pair literals
//! `REL(o, b)` over every other object `b` of the target (all objects
//! counted: after synthesis every object is placed; a landmark is the one
//! fixed object with that id): `every` is their AND, `some` their OR, `no`
//! the AND of their negations, `at least K` an `AtLeast` count (folded to
//! AND/OR/constants where it can be), `at most K` the negation of
//! `at least K+1`. Each (object, rule) pair is one reified formula literal.
//! A scene-level rule `Q A: φ` applies the same counting to the literals of
//! `φ` over every `A` object and gives one literal. Hard rules give literals
//! that must be true; soft rules give weighted objective terms over all
//! objects of the subject class (already-placed ones included), or one term
//! for a scene-level rule.

pub use crate::relations::Axis;
use crate::relations::{Cmp, Contact, Dir, Edge, Kind, Op, Quant, Relation, Side};
use crate::rules::{Formula, RuleSet, Scope, Target};
use crate::scene::Scene;
use std::collections::HashMap;

mod shapes;

/// A literal: a constant or a (possibly negated) model Boolean.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Lit {
    /// A constant truth value.
    Const(bool),
    /// Boolean `id` (index into [`Model::bools`]), negated when `neg`.
    Var {
        /// Index into [`Model::bools`].
        id: u32,
        /// Negated.
        neg: bool,
    },
}

impl Lit {
    /// The constant `true`.
    pub const TRUE: Lit = Lit::Const(true);
    /// The constant `false`.
    pub const FALSE: Lit = Lit::Const(false);

    /// The positive literal of Boolean `id`.
    pub const fn pos(id: u32) -> Lit {
        Lit::Var { id, neg: false }
    }

    /// Its truth value, under an assignment of the model Booleans.
    pub fn value(self, bools: &[bool]) -> bool {
        match self {
            Lit::Const(b) => b,
            Lit::Var { id, neg } => bools[id as usize] != neg,
        }
    }
}

impl std::ops::Not for Lit {
    type Output = Lit;
    fn not(self) -> Lit {
        match self {
            Lit::Const(b) => Lit::Const(!b),
            Lit::Var { id, neg } => Lit::Var { id, neg: !neg },
        }
    }
}

/// The exact definition of a model Boolean.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum BoolDef {
    /// `vars[var] ≥ k`, with `1 ≤ k ≤ ub` (never constant).
    Ge {
        /// Grid variable.
        var: usize,
        /// Bound.
        k: i64,
    },
    /// `vars[a] − vars[b] ≥ k`, with `a < b` and not constant.
    DiffGe {
        /// Left variable.
        a: usize,
        /// Right variable.
        b: usize,
        /// Bound.
        k: i64,
    },
    /// Conjunction of at least two non-constant, sorted, distinct literals
    /// of Booleans defined earlier.
    And(Vec<Lit>),
    /// At least `k` of `lits` hold, with `2 ≤ k < lits.len()`; `lits` are
    /// non-constant literals of Booleans defined earlier, sorted, repeats
    /// counted with their multiplicity.
    AtLeast {
        /// The counted literals.
        lits: Vec<Lit>,
        /// The threshold.
        k: u32,
    },
    /// The graph on `nodes` nodes whose edges are `edges` (two node
    /// indices and a literal each) is connected when only the edges whose
    /// literal holds count. `nodes ≥ 2`, every node on some edge; the
    /// literals are non-constant, of Booleans defined earlier. Built only
    /// with [`Connectivity::Propagator`]; the engine posts it as one
    /// propagator, the emitted models as a circuit (see `model/shapes.rs`).
    Connected {
        /// Number of nodes.
        nodes: u32,
        /// `(a, b, literal)`, `a < b < nodes`, sorted.
        edges: Vec<(u32, u32, Lit)>,
    },
}

/// How a group statement's connectivity enters the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Connectivity {
    /// One [`BoolDef::Connected`] per statement: the engine's connectivity
    /// propagator (the default).
    Propagator,
    /// A layered reachability circuit of `And` nodes: what `--emit` writes,
    /// so peers solve the same model without a propagator of their own.
    Circuit,
}

/// An integer grid-index variable with domain `0..=ub`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IntVar {
    /// The object it positions.
    pub object: usize,
    /// Which coordinate.
    pub axis: Axis,
    /// Upper bound of the domain (the lower bound is 0).
    pub ub: i64,
}

/// One coordinate of an object in the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coord {
    /// Fixed or already placed: the real coordinate.
    Const(i64),
    /// Unplaced: `origin + grid · vars[i]`.
    Var(usize),
}

/// `Σ coef·vars[v] ≤ rhs`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LinLe {
    /// `(coefficient, variable)` terms.
    pub terms: Vec<(i64, usize)>,
    /// Right-hand side.
    pub rhs: i64,
}

/// A redundant cumulative relaxation on one axis: at every coordinate `t`
/// along `axis`, the objects whose open interval contains `t` have disjoint
/// cross-sections, whose lengths sum to at most `capacity`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Cumulative {
    /// The "time" axis.
    pub axis: Axis,
    /// `(object, duration, demand)` per task (start = the object's coordinate).
    pub tasks: Vec<(usize, i64, i64)>,
    /// Space extent across the axis.
    pub capacity: i64,
}

/// The literals of one hard rule: every subject must satisfy it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HardRule {
    /// Index in the rule set.
    pub rule: usize,
    /// One literal per subject object.
    pub lits: Vec<Lit>,
}

/// One objective term: `weight · [lit]` (soft rule `rule` on `object`, or
/// on the whole scene for a scene-level rule).
#[derive(Debug, Clone, PartialEq)]
pub struct SoftTerm {
    /// Index in the rule set.
    pub rule: usize,
    /// Subject object; `None` for a scene-level rule.
    pub object: Option<usize>,
    /// Whether the object satisfies the rule.
    pub lit: Lit,
    /// The rule's real weight.
    pub weight: f64,
}

/// What to put into a model.
#[derive(Debug, Clone, Copy)]
pub struct BuildOptions {
    /// EC contact mode.
    pub contact: Contact,
    /// Include the rules (off: objects only, for the fit check).
    pub rules: bool,
    /// Order interchangeable objects.
    pub symmetry_breaking: bool,
    /// Cumulative relaxations.
    pub redundant: bool,
}

/// The whole model.
#[derive(Debug, Clone)]
pub struct Model {
    /// `space.x`, `space.y`.
    pub origin: (i64, i64),
    /// Grid step.
    pub grid: i64,
    /// Grid-index variables.
    pub vars: Vec<IntVar>,
    /// Per object: `(x, y)` coordinates.
    pub coords: Vec<(Coord, Coord)>,
    /// Per object: `(width, height)`.
    pub sizes: Vec<(i64, i64)>,
    /// Boolean definitions, children before parents.
    pub bools: Vec<BoolDef>,
    /// Clauses that must hold (the symmetry fallback; non-overlap only
    /// after [`Model::add_pairwise_no_overlap`] — every model implies it,
    /// the engine posts it as one propagator).
    pub clauses: Vec<Vec<Lit>>,
    /// Hard rules.
    pub hard: Vec<HardRule>,
    /// Objective terms (maximise the weighted sum).
    pub soft: Vec<SoftTerm>,
    /// Symmetry-breaking order constraints.
    pub symmetry: Vec<LinLe>,
    /// Redundant cumulative relaxations.
    pub cumulative: Vec<Cumulative>,
    /// Objects that cannot lie inside the space at all (too large), by index.
    pub too_large: Vec<usize>,
    /// Whether `clauses` state non-overlap pairwise; otherwise the engine
    /// posts it as one propagator ([`PAIRWISE_NO_OVERLAP_PAIRS`]).
    pub pairwise_no_overlap: bool,
    /// How group statements' connectivity is encoded.
    pub connectivity: Connectivity,
    interned: HashMap<BoolDef, u32>,
}

/// Most pairs of objects (at least one movable) whose non-overlap the model
/// states as one clause each (four reified pair literals, about 16 KB in
/// the engine per pair); past it the engine's non-overlap propagator holds
/// them all in linear memory. 2 000 pairs is about 64 objects.
pub const PAIRWISE_NO_OVERLAP_PAIRS: usize = 2_000;

/// `RCCPACK_NO_OVERLAP=clauses|propagator` forces one non-overlap encoding
/// for every model (to run the differential tests and fuzz corpora through
/// the propagator); unset, the number of pairs decides.
fn forced_encoding() -> Option<bool> {
    static FORCED: std::sync::OnceLock<Option<bool>> = std::sync::OnceLock::new();
    *FORCED.get_or_init(|| match std::env::var("RCCPACK_NO_OVERLAP").as_deref() {
        Ok("clauses") => Some(true),
        Ok("propagator") => Some(false),
        _ => None,
    })
}

/// `RCCPACK_CONNECTIVITY=circuit` builds every model's group statements
/// as circuits (to compare the encodings in `bench tasks` and to run the
/// differential tests through both); otherwise the propagator.
pub(crate) fn default_connectivity() -> Connectivity {
    static FORCED: std::sync::OnceLock<Connectivity> = std::sync::OnceLock::new();
    *FORCED.get_or_init(|| match std::env::var("RCCPACK_CONNECTIVITY").as_deref() {
        Ok("circuit") => Connectivity::Circuit,
        _ => Connectivity::Propagator,
    })
}

/// How a model is encoded, beyond [`BuildOptions`]: choices that change
/// the model's Booleans but never what it means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Encoding {
    /// Non-overlap: `Some(true)` pairwise clauses, `Some(false)` the
    /// engine's propagator, `None` by the number of pairs.
    pub(crate) pairwise: Option<bool>,
    /// Group statements' connectivity.
    pub(crate) connectivity: Connectivity,
}

impl Encoding {
    /// The encoding chosen by the environment (`RCCPACK_NO_OVERLAP`,
    /// `RCCPACK_CONNECTIVITY`), else the defaults.
    pub(crate) fn from_env() -> Encoding {
        Encoding {
            pairwise: forced_encoding(),
            connectivity: default_connectivity(),
        }
    }
}

/// Most pairwise relation literals the rules may ask for in one model
/// ([`Model::pair_literals`]): 120 000, about 1.5 GB at the engine's cost
/// of about 12.5 KB per literal (measured: `rule t: EC_N(R, *)` over 200
/// objects, 40 000 literals, 513 MB); past it synthesis is refused before
/// anything is built instead of running out of memory. A rule against a
/// landmark costs one literal per subject; `*` or a large target class,
/// one per pair.
pub const MAX_PAIR_LITERALS: u128 = 120_000;

/// Atom literals already built: `(object, relation, quantifier, target)`.
type AtomCache = HashMap<(usize, Relation, Quant, Target), Lit>;

fn ceil_div(a: i64, b: i64) -> i64 {
    -((-a).div_euclid(b))
}

fn floor_div(a: i64, b: i64) -> i64 {
    a.div_euclid(b)
}

impl Model {
    /// The coordinate, in this model, of the object and axis that `v` (a
    /// variable of this or of another model of the same problem) positions.
    pub fn coord_of(&self, v: &IntVar) -> Coord {
        let (cx, cy) = self.coords[v.object];
        match v.axis {
            Axis::X => cx,
            Axis::Y => cy,
        }
    }

    /// The objective value of grid values `vals`: `Σ coefs[i]` over the
    /// soft terms whose literal is a variable and holds (`coefs` in
    /// [`Model::soft`] order; constant terms are left out, as in the
    /// engine's objective).
    pub fn objective_value(&self, coefs: &[i64], vals: &[i64]) -> i64 {
        let bools = self.eval_bools(vals);
        self.soft
            .iter()
            .zip(coefs)
            .filter(|(s, _)| matches!(s.lit, Lit::Var { .. }) && s.lit.value(&bools))
            .map(|(_, &c)| c)
            .sum()
    }

    /// Build the model of `problem` with `rules`.
    ///
    /// The problem must be a valid scene (see [`Scene::validate`]).
    pub fn build(problem: &Scene, rules: &RuleSet, opts: BuildOptions) -> Model {
        Self::build_until(problem, rules, opts, &|| false).expect("never stopped")
    }

    /// [`Model::build_until`] with the encoding chosen by the caller (for
    /// non-overlap, `None` decides by the number of pairs, see
    /// [`PAIRWISE_NO_OVERLAP_PAIRS`]).
    pub(crate) fn build_encoded(
        problem: &Scene,
        rules: &RuleSet,
        opts: BuildOptions,
        stop: &dyn Fn() -> bool,
        encoding: Encoding,
    ) -> Option<Model> {
        let pairwise = encoding.pairwise;
        let movable = problem.objects.iter().filter(|o| !o.is_placed()).count();
        let n = problem.objects.len();
        // Pairs with at least one movable object.
        let pairs =
            n * (n.saturating_sub(1)) / 2 - (n - movable) * (n - movable).saturating_sub(1) / 2;
        let pairwise = pairwise.unwrap_or(pairs <= PAIRWISE_NO_OVERLAP_PAIRS);
        let mut m = Self::build_core(problem, rules, opts, stop, pairwise, encoding.connectivity)?;
        m.pairwise_no_overlap = pairwise || !m.too_large.is_empty();
        Some(m)
    }

    /// [`Model::build`], given up (`None`) as soon as `stop` says so
    /// (checked per rule and every 256 subject objects: a deadline or
    /// Ctrl-C while a large model is built).
    pub fn build_until(
        problem: &Scene,
        rules: &RuleSet,
        opts: BuildOptions,
        stop: &dyn Fn() -> bool,
    ) -> Option<Model> {
        Self::build_encoded(problem, rules, opts, stop, Encoding::from_env())
    }

    fn build_core(
        problem: &Scene,
        rules: &RuleSet,
        opts: BuildOptions,
        stop: &dyn Fn() -> bool,
        pairwise: bool,
        connectivity: Connectivity,
    ) -> Option<Model> {
        let sp = problem.space;
        let g = problem.grid;
        let mut m = Model {
            origin: (sp.x, sp.y),
            grid: g,
            vars: Vec::new(),
            coords: Vec::new(),
            sizes: Vec::new(),
            bools: Vec::new(),
            clauses: Vec::new(),
            hard: Vec::new(),
            soft: Vec::new(),
            symmetry: Vec::new(),
            cumulative: Vec::new(),
            too_large: Vec::new(),
            pairwise_no_overlap: false,
            connectivity,
            interned: HashMap::new(),
        };
        for (i, o) in problem.objects.iter().enumerate() {
            m.sizes.push((o.width, o.height));
            match (o.x, o.y) {
                (Some(x), Some(y)) => m.coords.push((Coord::Const(x), Coord::Const(y))),
                _ => {
                    let ux = floor_div(sp.width - o.width, g);
                    let uy = floor_div(sp.height - o.height, g);
                    if ux < 0 || uy < 0 {
                        m.too_large.push(i);
                    }
                    let vx = m.vars.len();
                    m.vars.push(IntVar {
                        object: i,
                        axis: Axis::X,
                        ub: ux.max(0),
                    });
                    m.vars.push(IntVar {
                        object: i,
                        axis: Axis::Y,
                        ub: uy.max(0),
                    });
                    m.coords.push((Coord::Var(vx), Coord::Var(vx + 1)));
                }
            }
        }
        if !m.too_large.is_empty() {
            return Some(m);
        }
        // Non-overlap between every pair with at least one variable object:
        // one clause per pair for a small model (the pair literals also
        // guide the search), else implicit — the engine posts one
        // propagator for all pairs (linear memory, issue 35 item 6) and
        // `add_pairwise_no_overlap` writes the clauses for the peers.
        if pairwise {
            m.add_pairwise_no_overlap(opts.contact);
        }
        if opts.symmetry_breaking {
            m.post_symmetry(problem);
        }
        if opts.redundant {
            m.post_cumulative(problem);
        }
        if opts.rules && !m.post_rules(problem, rules, opts.contact, stop) {
            return None;
        }
        Some(m)
    }

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
        // First, as `build` used to put them.
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
                let (w, h) = self.sizes[i];
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

    fn is_const(&self, o: usize) -> bool {
        matches!(self.coords[o].0, Coord::Const(_))
    }

    /// Whether two constant objects' interiors overlap (false when either
    /// is a variable).
    fn const_overlap(&self, a: usize, b: usize) -> bool {
        let ((Coord::Const(ax), Coord::Const(ay)), (Coord::Const(bx), Coord::Const(by))) =
            (self.coords[a], self.coords[b])
        else {
            return false;
        };
        let ((aw, ah), (bw, bh)) = (self.sizes[a], self.sizes[b]);
        ax < bx + bw && bx < ax + aw && ay < by + bh && by < ay + ah
    }

    fn coord(&self, o: usize, axis: Axis) -> Coord {
        match axis {
            Axis::X => self.coords[o].0,
            Axis::Y => self.coords[o].1,
        }
    }

    fn size(&self, o: usize, axis: Axis) -> i64 {
        match axis {
            Axis::X => self.sizes[o].0,
            Axis::Y => self.sizes[o].1,
        }
    }

    fn axis_origin(&self, axis: Axis) -> i64 {
        match axis {
            Axis::X => self.origin.0,
            Axis::Y => self.origin.1,
        }
    }

    fn intern(&mut self, def: BoolDef) -> Lit {
        if let Some(&id) = self.interned.get(&def) {
            return Lit::pos(id);
        }
        let id = self.bools.len() as u32;
        self.bools.push(def.clone());
        self.interned.insert(def, id);
        Lit::pos(id)
    }

    /// `vars[v] ≥ k`.
    /// A hard "rule" pinning unplaced object `object` at `(x, y)` (its
    /// index in [`Model::hard`]; `HardRule::rule` is that index too, past
    /// any rule set's). `None` when the position is not on the object's
    /// grid domain (or the object is a constant).
    pub(crate) fn pin(&mut self, object: usize, x: i64, y: i64) -> Option<usize> {
        let (Coord::Var(vx), Coord::Var(vy)) = self.coords[object] else {
            return None;
        };
        let mut lits = Vec::with_capacity(4);
        for (v, at, origin) in [(vx, x, self.origin.0), (vy, y, self.origin.1)] {
            let d = at - origin;
            if d % self.grid != 0 {
                return None;
            }
            let k = d / self.grid;
            if k < 0 || k > self.vars[v].ub {
                return None;
            }
            lits.push(self.ge(v, k));
            lits.push(!self.ge(v, k + 1));
        }
        let at = self.hard.len();
        self.hard.push(HardRule { rule: at, lits });
        Some(at)
    }

    fn ge(&mut self, v: usize, k: i64) -> Lit {
        if k <= 0 {
            Lit::TRUE
        } else if k > self.vars[v].ub {
            Lit::FALSE
        } else {
            self.intern(BoolDef::Ge { var: v, k })
        }
    }

    /// `vars[a] − vars[b] ≥ k`.
    fn vdiff_ge(&mut self, a: usize, b: usize, k: i64) -> Lit {
        if k <= -self.vars[b].ub {
            Lit::TRUE
        } else if k > self.vars[a].ub {
            Lit::FALSE
        } else if a > b {
            // a − b ≥ k  ⇔  ¬(b − a ≥ 1 − k)
            !self.vdiff_ge(b, a, 1 - k)
        } else {
            self.intern(BoolDef::DiffGe { a, b, k })
        }
    }

    /// `coord(a) − coord(b) ≥ d` in real units.
    fn diff_ge(&mut self, axis: Axis, a: usize, b: usize, d: i64) -> Lit {
        let o = self.axis_origin(axis);
        let g = self.grid;
        match (self.coord(a, axis), self.coord(b, axis)) {
            (Coord::Const(ca), Coord::Const(cb)) => Lit::Const(ca - cb >= d),
            (Coord::Var(va), Coord::Const(cb)) => self.ge(va, ceil_div(d + cb - o, g)),
            (Coord::Const(ca), Coord::Var(vb)) => !self.ge(vb, floor_div(ca - o - d, g) + 1),
            (Coord::Var(va), Coord::Var(vb)) => self.vdiff_ge(va, vb, ceil_div(d, g)),
        }
    }

    /// Conjunction with folding (constants, duplicates, complements).
    pub fn and(&mut self, lits: Vec<Lit>) -> Lit {
        let mut v = Vec::with_capacity(lits.len());
        for l in lits {
            match l {
                Lit::Const(true) => {}
                Lit::Const(false) => return Lit::FALSE,
                _ => v.push(l),
            }
        }
        v.sort_unstable();
        v.dedup();
        for w in v.windows(2) {
            if let (Lit::Var { id: i, .. }, Lit::Var { id: j, .. }) = (w[0], w[1]) {
                if i == j {
                    return Lit::FALSE;
                }
            }
        }
        match v.len() {
            0 => Lit::TRUE,
            1 => v[0],
            _ => self.intern(BoolDef::And(v)),
        }
    }

    /// Disjunction (the dual of [`Model::and`]).
    pub fn or(&mut self, lits: Vec<Lit>) -> Lit {
        let neg = lits.into_iter().map(|l| !l).collect();
        !self.and(neg)
    }

    /// The pairwise relation `rel(a, b)` between two distinct objects: the
    /// relation's condition in [`crate::relations::TABLE`], literally.
    pub fn pair(&mut self, rel: Relation, a: usize, b: usize, contact: Contact) -> Lit {
        let cond = rel.def().condition(contact);
        let mut disjuncts = Vec::with_capacity(cond.len());
        for conj in cond {
            let mut parts = Vec::with_capacity(conj.len() + 1);
            for c in conj.iter() {
                self.cmp(c, a, b, &mut parts);
            }
            disjuncts.push(self.and(parts));
        }
        self.or(disjuncts)
    }

    /// The literals whose conjunction is comparison `c` on the pair `(a, b)`.
    fn cmp(&mut self, c: &Cmp, a: usize, b: usize, out: &mut Vec<Lit>) {
        let obj = |s: Side| match s {
            Side::A => a,
            Side::B => b,
        };
        let axis = c.lhs.1.axis();
        let (p, q) = (obj(c.lhs.0), obj(c.rhs.0));
        let off = |m: &Self, o: usize, e: Edge| if e.is_far() { m.size(o, axis) } else { 0 };
        // lhs = coord(p) + op, rhs = coord(q) + oq.
        let (op, oq) = (off(self, p, c.lhs.1), off(self, q, c.rhs.1));
        match c.op {
            Op::Ge => out.push(self.diff_ge(axis, p, q, oq - op)),
            Op::Gt => out.push(self.diff_ge(axis, p, q, oq - op + 1)),
            Op::Le => out.push(self.diff_ge(axis, q, p, op - oq)),
            Op::Lt => out.push(self.diff_ge(axis, q, p, op - oq + 1)),
            Op::Eq => {
                out.push(self.diff_ge(axis, p, q, oq - op));
                out.push(self.diff_ge(axis, q, p, op - oq));
            }
        }
    }

    /// At least `k` of `lits` (a multiset) hold, folded where it can be.
    ///
    /// Constants are counted off; a literal and its complement together
    /// always count exactly one, so such pairs are counted off too. What is
    /// left holds at most one polarity of each Boolean (repeats kept with
    /// their multiplicity), so the engine never sees one solver variable
    /// twice in a count.
    pub fn at_least(&mut self, lits: Vec<Lit>, k: u32) -> Lit {
        let mut need = i64::from(k);
        let mut vars: Vec<(u32, bool)> = Vec::with_capacity(lits.len());
        for l in lits {
            match l {
                Lit::Const(true) => need -= 1,
                Lit::Const(false) => {}
                Lit::Var { id, neg } => vars.push((id, neg)),
            }
        }
        // Sorted, `l` and `¬l` are adjacent (same id, `neg` false first).
        vars.sort_unstable();
        let mut v = Vec::with_capacity(vars.len());
        for group in vars.chunk_by(|a, b| a.0 == b.0) {
            let id = group[0].0;
            let neg = group.iter().filter(|l| l.1).count();
            let pos = group.len() - neg;
            let pairs = pos.min(neg);
            need -= pairs as i64;
            let rest = Lit::Var { id, neg: neg > pos };
            v.extend(std::iter::repeat_n(rest, pos.max(neg) - pairs));
        }
        if need <= 0 {
            return Lit::TRUE;
        }
        let n = v.len() as i64;
        if need > n {
            Lit::FALSE
        } else if need == 1 {
            self.or(v)
        } else if need == n {
            self.and(v)
        } else {
            self.intern(BoolDef::AtLeast {
                lits: v,
                k: need as u32,
            })
        }
    }

    /// The literal of quantifier `q` over `lits` (§11.2's table).
    pub fn quantify(&mut self, q: Quant, lits: Vec<Lit>) -> Lit {
        match q {
            Quant::Every => self.and(lits),
            Quant::Some => self.or(lits),
            Quant::No => {
                let neg = lits.into_iter().map(|l| !l).collect();
                self.and(neg)
            }
            Quant::AtLeast(k) => self.at_least(lits, k),
            Quant::AtMost(k) => !self.at_least(lits, k.saturating_add(1)),
        }
    }

    fn post_symmetry(&mut self, problem: &Scene) {
        // Groups of unplaced objects with the same class and size.
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for (i, o) in problem.objects.iter().enumerate() {
            if o.is_placed() {
                continue;
            }
            match groups.iter_mut().find(|g| {
                let p = &problem.objects[g[0]];
                p.class == o.class && p.width == o.width && p.height == o.height
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

    fn post_cumulative(&mut self, problem: &Scene) {
        let sp = problem.space;
        for (axis, capacity) in [(Axis::X, sp.height), (Axis::Y, sp.width)] {
            let tasks: Vec<(usize, i64, i64)> = (0..problem.objects.len())
                .map(|i| {
                    let (w, h) = self.sizes[i];
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

    /// Post every rule; `false` when `stop` said so first.
    fn post_rules(
        &mut self,
        problem: &Scene,
        rules: &RuleSet,
        contact: Contact,
        stop: &dyn Fn() -> bool,
    ) -> bool {
        let mut cache: AtomCache = HashMap::new();
        for (ri, rule) in rules.rules.iter().enumerate() {
            if stop() {
                return false;
            }
            let subject = rule.subject();
            let hard = rule.strength.is_hard();
            if rule.scope == Scope::Group {
                let lit = match rule.formula.shape() {
                    Some((shape, neg)) => {
                        let objects: Vec<usize> = (0..problem.objects.len())
                            .filter(|&o| problem.objects[o].class == shape.class)
                            .collect();
                        let l = self.shape(shape.kind, &objects, contact);
                        if neg {
                            !l
                        } else {
                            l
                        }
                    }
                    // Not a shape formula: the evaluator reads it as false.
                    None => Lit::FALSE,
                };
                if hard {
                    self.hard.push(HardRule {
                        rule: ri,
                        lits: vec![lit],
                    });
                } else {
                    self.soft.push(SoftTerm {
                        rule: ri,
                        object: None,
                        lit,
                        weight: rule.strength.weight(),
                    });
                }
                continue;
            }
            let mut lits = Vec::new();
            let mut objects = Vec::new();
            for (o, obj) in problem.objects.iter().enumerate() {
                if obj.class != subject {
                    continue;
                }
                if objects.len() % 256 == 255 && stop() {
                    return false;
                }
                lits.push(self.formula(&rule.formula, o, problem, contact, &mut cache));
                objects.push(o);
            }
            let weight = rule.strength.weight();
            match rule.scope {
                Scope::Each if hard => self.hard.push(HardRule { rule: ri, lits }),
                Scope::Each => {
                    for (lit, o) in lits.into_iter().zip(objects) {
                        self.soft.push(SoftTerm {
                            rule: ri,
                            object: Some(o),
                            lit,
                            weight,
                        });
                    }
                }
                // Posted above.
                Scope::Group => {}
                Scope::Scene(q) => {
                    let lit = self.quantify(q, lits);
                    if hard {
                        self.hard.push(HardRule {
                            rule: ri,
                            lits: vec![lit],
                        });
                    } else {
                        self.soft.push(SoftTerm {
                            rule: ri,
                            object: None,
                            lit,
                            weight,
                        });
                    }
                }
            }
        }
        true
    }

    /// How many pairwise relation literals the rules ask for on `problem`
    /// at most: per rule and atom, subject objects × target objects. The
    /// model holds a few Booleans and the engine a few propagators per
    /// pair literal, so this bounds their memory ([`MAX_PAIR_LITERALS`]).
    pub fn pair_literals(problem: &Scene, rules: &RuleSet) -> u128 {
        let count =
            |class: &str| problem.objects.iter().filter(|o| o.class == class).count() as u128;
        let n = problem.objects.len() as u128;
        let mut total = 0u128;
        for rule in &rules.rules {
            let subjects = count(rule.subject());
            for atom in rule.formula.atoms() {
                let targets = match &atom.target {
                    Target::Any => n.saturating_sub(1),
                    Target::Class(c) if c == rule.subject() => subjects.saturating_sub(1),
                    Target::Class(c) => count(c),
                    Target::Landmark(_) => 1,
                };
                total += subjects * targets;
            }
        }
        total
    }

    fn formula(
        &mut self,
        f: &Formula,
        o: usize,
        problem: &Scene,
        contact: Contact,
        cache: &mut AtomCache,
    ) -> Lit {
        match f {
            Formula::Atom(a) => {
                let key = (o, a.rel, a.quant, a.target.clone());
                if let Some(&l) = cache.get(&key) {
                    return l;
                }
                let others: Vec<usize> = problem
                    .objects
                    .iter()
                    .enumerate()
                    .filter(|(b, ob)| {
                        *b != o
                            && match &a.target {
                                Target::Any => true,
                                Target::Class(c) => &ob.class == c,
                                Target::Landmark(id) => ob.fixed && &ob.id == id,
                            }
                    })
                    .map(|(b, _)| b)
                    .collect();
                let lits: Vec<Lit> = others
                    .into_iter()
                    .map(|b| self.pair(a.rel, o, b, contact))
                    .collect();
                let l = self.quantify(a.quant, lits);
                cache.insert(key, l);
                l
            }
            // Only a group rule's whole formula (posted by `post_rules`);
            // read per object it is false, as in the evaluator.
            Formula::Shape(_) => Lit::FALSE,
            Formula::Not(g) => !self.formula(g, o, problem, contact, cache),
            Formula::And(v) => {
                let ls = v
                    .iter()
                    .map(|g| self.formula(g, o, problem, contact, cache))
                    .collect();
                self.and(ls)
            }
            Formula::Or(v) => {
                let ls = v
                    .iter()
                    .map(|g| self.formula(g, o, problem, contact, cache))
                    .collect();
                self.or(ls)
            }
        }
    }

    /// Evaluate every model Boolean under grid values `vals` (one per
    /// variable). Used to cross-check the engine against the definitions.
    pub fn eval_bools(&self, vals: &[i64]) -> Vec<bool> {
        let mut out: Vec<bool> = Vec::with_capacity(self.bools.len());
        for d in &self.bools {
            let v = match d {
                BoolDef::Ge { var, k } => vals[*var] >= *k,
                BoolDef::DiffGe { a, b, k } => vals[*a] - vals[*b] >= *k,
                BoolDef::And(ls) => ls.iter().all(|l| l.value(&out)),
                BoolDef::AtLeast { lits, k } => {
                    lits.iter().filter(|l| l.value(&out)).count() >= *k as usize
                }
                BoolDef::Connected { nodes, edges } => {
                    shapes::connected_under(*nodes as usize, edges, |l| l.value(&out))
                }
            };
            out.push(v);
        }
        out
    }

    /// The complete scene for grid values `vals`.
    pub fn scene(&self, problem: &Scene, vals: &[i64]) -> Scene {
        let mut s = problem.clone();
        for (i, o) in s.objects.iter_mut().enumerate() {
            if let (Coord::Var(vx), Coord::Var(vy)) = self.coords[i] {
                o.x = Some(self.origin.0 + self.grid * vals[vx]);
                o.y = Some(self.origin.1 + self.grid * vals[vy]);
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::Evaluator;
    use crate::relations::relation_bits;
    use crate::rules::{Atom, Rule, Strength};
    use crate::scene::{Object, Space};

    fn obj(id: &str, class: &str, w: i64, h: i64, pos: Option<(i64, i64)>) -> Object {
        Object {
            id: id.into(),
            class: class.into(),
            x: pos.map(|p| p.0),
            y: pos.map(|p| p.1),
            width: w,
            height: h,
            fixed: false,
        }
    }

    fn opts(contact: Contact, rules: bool) -> BuildOptions {
        BuildOptions {
            contact,
            rules,
            symmetry_breaking: false,
            redundant: false,
        }
    }

    /// Call `f` with every assignment of the model's grid variables (the
    /// whole box of domains, overlapping layouts included: literals are
    /// definitions, not constraints).
    fn each_assignment(m: &Model, mut f: impl FnMut(&[i64])) {
        let ub: Vec<i64> = m.vars.iter().map(|v| v.ub).collect();
        let mut vals = vec![0i64; ub.len()];
        loop {
            f(&vals);
            let mut i = 0;
            loop {
                if i == vals.len() {
                    return;
                }
                vals[i] += 1;
                if vals[i] > ub[i] {
                    vals[i] = 0;
                    i += 1;
                } else {
                    break;
                }
            }
        }
    }

    /// Every pairwise literal of every relation between every ordered pair
    /// agrees with `relation_bits` on every layout; returns, per relation,
    /// whether it was seen true and seen false.
    fn check_pairs(scene: &Scene, contact: Contact) -> [(bool, bool); 16] {
        let mut m = Model::build(scene, &RuleSet::default(), opts(contact, false));
        let n = scene.objects.len();
        let mut lits = Vec::new();
        for a in 0..n {
            for b in 0..n {
                if a != b {
                    for rel in Relation::ALL {
                        lits.push((a, b, rel, m.pair(rel, a, b, contact)));
                    }
                }
            }
        }
        let mut seen = [(false, false); 16];
        each_assignment(&m, |vals| {
            let s = m.scene(scene, vals);
            let bools = m.eval_bools(vals);
            for &(a, b, rel, l) in &lits {
                let (Some(ra), Some(rb)) = (s.objects[a].rect(), s.objects[b].rect()) else {
                    panic!("every object is placed in the model's scene");
                };
                let want = relation_bits(&ra, &rb, contact) & rel.bit() != 0;
                assert_eq!(
                    l.value(&bools),
                    want,
                    "{rel}({a},{b}) {contact} at {vals:?}"
                );
                let e = &mut seen[rel.index()];
                if want {
                    e.0 = true;
                } else {
                    e.1 = true;
                }
            }
        });
        seen
    }

    /// The two encodings of a group statement's connectivity (the
    /// engine's [`BoolDef::Connected`] and the emitted circuit) give every
    /// group rule the same value on every assignment, overlapping layouts
    /// included, in both contact modes, and agree with the evaluator's
    /// `shapes::check` on the layouts without overlap: a fixed object of
    /// the class (merged by a constant edge) and three movable ones.
    #[test]
    fn connectivity_encodings_agree_on_every_assignment() {
        let mut scene = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 30,
                height: 30,
            },
            grid: 10,
            objects: vec![
                obj("a0", "A", 10, 10, None),
                obj("a1", "A", 10, 10, None),
                obj("a2", "A", 10, 10, None),
                obj("a3", "A", 10, 10, Some((0, 0))),
                obj("a4", "A", 10, 10, Some((10, 0))),
            ],
        };
        scene.objects[3].fixed = true;
        scene.objects[4].fixed = true;
        let rules = crate::rules::parse_rules(
            "rule g: group(A)\nrule b: block(A)\nrule n: not group(A)\nrule r: row(A)\n",
        )
        .expect("rules parse");
        for contact in [Contact::Point, Contact::Edge] {
            let enc = |connectivity| Encoding {
                pairwise: Some(true),
                connectivity,
            };
            let build = |connectivity| {
                Model::build_encoded(
                    &scene,
                    &rules,
                    opts(contact, true),
                    &|| false,
                    enc(connectivity),
                )
                .expect("never stopped")
            };
            let prop = build(Connectivity::Propagator);
            let circ = build(Connectivity::Circuit);
            assert!(prop
                .bools
                .iter()
                .any(|b| matches!(b, BoolDef::Connected { .. })));
            assert!(!circ
                .bools
                .iter()
                .any(|b| matches!(b, BoolDef::Connected { .. })));
            assert_eq!(prop.soft.len(), circ.soft.len());
            let (mut held, mut broken) = (0, 0);
            each_assignment(&prop, |vals| {
                let (bp, bc) = (prop.eval_bools(vals), circ.eval_bools(vals));
                let overlap_free = prop.non_overlapping(vals);
                let ev = crate::eval::evaluate(&prop.scene(&scene, vals), &rules, contact);
                for (i, (sp, sc)) in prop.soft.iter().zip(&circ.soft).enumerate() {
                    assert_eq!(sp.rule, sc.rule);
                    let v = sp.lit.value(&bp);
                    assert_eq!(v, sc.lit.value(&bc), "term {i} {contact} at {vals:?}");
                    if overlap_free {
                        let want = ev.rules[sp.rule].satisfied == 1;
                        assert_eq!(v, want, "term {i} vs the evaluator at {vals:?}");
                        if sp.rule == 0 {
                            if v {
                                held += 1;
                            } else {
                                broken += 1;
                            }
                        }
                    }
                }
            });
            assert!(held > 0 && broken > 0, "{held} {broken}");
        }
    }

    /// Every pairwise literal of all sixteen relations is exactly the
    /// geometry, in both contact modes, on a problem with off-grid sizes and
    /// offset origin, and on one with mixed sizes where every relation
    /// (the equalities of `FL` and `AL` included) is both true and false in
    /// some layout.
    #[test]
    fn pair_literals_match_geometry() {
        let mut off_grid = Scene {
            space: Space {
                x: 3,
                y: -2,
                width: 40,
                height: 33,
            },
            grid: 5,
            objects: vec![
                obj("o0", "A", 10, 7, None),
                obj("o1", "B", 13, 5, None),
                obj("o2", "C", 6, 9, Some((17, 8))),
            ],
        };
        off_grid.objects[2].fixed = true;
        let mixed = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 40,
                height: 30,
            },
            grid: 10,
            objects: vec![
                obj("a", "A", 10, 10, None),
                obj("b", "B", 20, 10, None),
                obj("c", "C", 10, 20, None),
                obj("f", "F", 30, 10, Some((10, 20))),
            ],
        };
        for contact in Contact::ALL {
            check_pairs(&off_grid, contact);
            let seen = check_pairs(&mixed, contact);
            for rel in Relation::ALL {
                assert_eq!(
                    seen[rel.index()],
                    (true, true),
                    "{rel} {contact}: (seen true, seen false)"
                );
            }
        }
    }

    fn at(rel: Relation, q: Quant, t: &Target) -> Formula {
        Formula::Atom(Atom::quantified(rel, "A", q, t.clone()))
    }

    const QUANTS: [Quant; 10] = [
        Quant::Every,
        Quant::Some,
        Quant::No,
        Quant::AtLeast(0),
        Quant::AtLeast(1),
        Quant::AtLeast(2),
        Quant::AtLeast(3),
        Quant::AtMost(0),
        Quant::AtMost(1),
        Quant::AtMost(2),
    ];

    /// Rules with subject `A` covering every relation × quantifier × target
    /// kind (class, `*`, a landmark on a fixed object, on a movable object,
    /// on no object), compound formulas, and scene-level rules with every
    /// subject quantifier, soft and hard.
    fn coverage_rules() -> RuleSet {
        let targets = [
            Target::Class("A".into()),
            Target::Class("B".into()),
            Target::Class("Z".into()), // no such class
            Target::Any,
            Target::Landmark("w".into()),
            Target::Landmark("b0".into()), // movable: empty target
            Target::Landmark("nope".into()),
        ];
        let mut rules = Vec::new();
        for rel in Relation::ALL {
            for q in QUANTS {
                for t in &targets {
                    rules.push(Rule::new(format!("r{}", rules.len()), at(rel, q, t)));
                }
            }
        }
        let ec = |d: Dir, q: Quant, t: &Target| at(Relation::new(Kind::EC, d), q, t);
        let fl = |d: Dir, q: Quant, t: &Target| at(Relation::new(Kind::FL, d), q, t);
        let al = |d: Dir, q: Quant, t: &Target| at(Relation::new(Kind::AL, d), q, t);
        let a = Target::Class("A".into());
        let any = Target::Any;
        let w = Target::Landmark("w".into());
        let compound = vec![
            // blue_row
            Formula::And(vec![
                al(Dir::S, Quant::Every, &a),
                Formula::Or(vec![
                    fl(Dir::E, Quant::Some, &a),
                    fl(Dir::W, Quant::Some, &a),
                ]),
            ]),
            // blue_flush
            Formula::And(
                Dir::ALL
                    .iter()
                    .map(|&d| {
                        Formula::Or(vec![
                            Formula::not(ec(d, Quant::Some, &any)),
                            fl(d, Quant::Some, &any),
                        ])
                    })
                    .collect(),
            ),
            // apart
            Formula::And(
                Dir::ALL
                    .iter()
                    .map(|&d| ec(d, Quant::No, &Target::Class("B".into())))
                    .collect(),
            ),
            // touches the landmark
            Formula::Or(Dir::ALL.iter().map(|&d| ec(d, Quant::Some, &w)).collect()),
            Formula::not(Formula::And(vec![
                al(Dir::N, Quant::AtLeast(1), &any),
                ec(Dir::W, Quant::AtMost(0), &any),
            ])),
        ];
        for f in &compound {
            rules.push(Rule::new(format!("r{}", rules.len()), f.clone()));
            rules.push(
                Rule::new(format!("r{}", rules.len()), f.clone()).with_strength(Strength::Hard),
            );
            for q in QUANTS
                .into_iter()
                .skip(1)
                .chain([Quant::AtLeast(4), Quant::AtMost(3)])
            {
                for strength in [Strength::Weight(1.5), Strength::Hard] {
                    rules.push(
                        Rule::new(format!("r{}", rules.len()), f.clone())
                            .with_scope(Scope::Scene(q))
                            .with_strength(strength),
                    );
                }
            }
        }
        RuleSet::new(rules)
    }

    /// Every rule literal of the model (soft terms and hard rules, per
    /// object and scene-level) has, under `eval_bools`, the evaluator's
    /// truth value on every layout of a tiny problem: quantified atoms with
    /// `at least`/`at most` around the object count, landmarks, empty
    /// targets, scene-level rules, both contact modes.
    #[test]
    fn rule_literals_match_evaluator() {
        let mut scene = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 30,
                height: 30,
            },
            grid: 10,
            objects: vec![
                obj("w", "W", 10, 10, Some((20, 0))),
                obj("a0", "A", 10, 10, None),
                obj("a1", "A", 10, 10, None),
                obj("b0", "B", 20, 10, None),
                obj("a2", "A", 10, 20, Some((0, 10))),
            ],
        };
        scene.objects[0].fixed = true;
        let rules = coverage_rules();
        let n_scene = rules.rules.iter().filter(|r| r.scope.is_scene()).count();
        for contact in Contact::ALL {
            let m = Model::build(&scene, &rules, opts(contact, true));
            assert!(m.bools.iter().any(|b| matches!(b, BoolDef::AtLeast { .. })));
            let objects: Vec<usize> = (0..scene.objects.len())
                .filter(|&o| scene.objects[o].class == "A")
                .collect();
            // Per rule: the literals by subject object, or the one
            // scene-level literal.
            let mut per_rule: Vec<Vec<(Option<usize>, Lit)>> = vec![Vec::new(); rules.rules.len()];
            for t in &m.soft {
                per_rule[t.rule].push((t.object, t.lit));
            }
            for h in &m.hard {
                let r = &rules.rules[h.rule];
                if r.scope.is_scene() {
                    assert_eq!(h.lits.len(), 1);
                    per_rule[h.rule].push((None, h.lits[0]));
                } else {
                    assert_eq!(h.lits.len(), objects.len());
                    for (&o, &l) in objects.iter().zip(&h.lits) {
                        per_rule[h.rule].push((Some(o), l));
                    }
                }
            }
            for (ri, r) in rules.rules.iter().enumerate() {
                let want = if r.scope.is_scene() { 1 } else { objects.len() };
                assert_eq!(per_rule[ri].len(), want, "rule {}", r.name);
            }
            let mut scene_truth = vec![(false, false); rules.rules.len()];
            let mut layouts = 0;
            each_assignment(&m, |vals| {
                layouts += 1;
                let s = m.scene(&scene, vals);
                let bools = m.eval_bools(vals);
                let ev = Evaluator::new(&s, &rules, contact).evaluate(&rules);
                for (ri, r) in rules.rules.iter().enumerate() {
                    let rep = &ev.rules[ri];
                    for &(o, l) in &per_rule[ri] {
                        let truth = match o {
                            Some(o) => !rep.violators.contains(&s.objects[o].id),
                            None => rep.satisfied == 1,
                        };
                        if o.is_none() {
                            let e = &mut scene_truth[ri];
                            if truth {
                                e.0 = true;
                            } else {
                                e.1 = true;
                            }
                        }
                        assert_eq!(
                            l.value(&bools),
                            truth,
                            "rule {} ({:?}, {}) on {o:?} {contact} at {vals:?}",
                            r.name,
                            r.scope,
                            crate::rules::print_formula(&r.formula)
                        );
                    }
                }
            });
            assert_eq!(layouts, 9 * 9 * 6);
            // The scene-level rules are not all constant on this problem.
            let varying = scene_truth.iter().filter(|e| **e == (true, true)).count();
            assert!(varying * 2 > n_scene, "{varying} of {n_scene} vary");
        }
    }

    /// `at_least` folds constants and complementary pairs and keeps
    /// multiplicities, and its value always equals the count.
    #[test]
    fn at_least_folds_exactly() {
        let scene = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 30,
                height: 10,
            },
            grid: 10,
            objects: vec![obj("a", "A", 10, 10, None)],
        };
        let mut m = Model::build(&scene, &RuleSet::default(), opts(Contact::Point, false));
        let x1 = m.ge(0, 1);
        let x2 = m.ge(0, 2);
        let pool = [x1, !x1, x2, !x2, Lit::TRUE, Lit::FALSE];
        // Every multiset of up to 4 literals from the pool, every k.
        let mut cases = Vec::new();
        for n in 0..=4u32 {
            let mut idx = vec![0usize; n as usize];
            loop {
                cases.push(idx.iter().map(|&i| pool[i]).collect::<Vec<Lit>>());
                let mut i = 0;
                while i < idx.len() {
                    idx[i] += 1;
                    if idx[i] < pool.len() {
                        break;
                    }
                    idx[i] = 0;
                    i += 1;
                }
                if i == idx.len() {
                    break;
                }
            }
        }
        let mut built = Vec::new();
        for lits in &cases {
            for k in 0..=5u32 {
                let l = m.at_least(lits.clone(), k);
                built.push((lits.clone(), k, l));
            }
        }
        for b in &m.bools {
            if let BoolDef::AtLeast { lits, k } = b {
                assert!(*k >= 2 && (*k as usize) < lits.len(), "{b:?}");
                for w in lits.windows(2) {
                    assert!(w[0] <= w[1]);
                    if let (Lit::Var { id: i, neg: p }, Lit::Var { id: j, neg: q }) = (w[0], w[1]) {
                        assert!(i != j || p == q, "complements left in {b:?}");
                    }
                }
            }
        }
        for v in 0..=2 {
            let bools = m.eval_bools(&[v, 0]);
            for (lits, k, l) in &built {
                let c = lits.iter().filter(|x| x.value(&bools)).count();
                assert_eq!(l.value(&bools), c >= *k as usize, "{lits:?} k={k} x={v}");
            }
        }
    }
}
