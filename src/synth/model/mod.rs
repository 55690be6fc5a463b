//! The solver-independent synthesis model (docs/language.md#relations, docs/language.md#class-rules, docs/language.md#the-score, docs/guide.md#synthesis).
//!
//! # Variables
//!
//! Every unplaced object gets two integer *grid-index* variables `gx`, `gy`
//! with `x = space.x + grid·gx`, `y = space.y + grid·gy` and domains
//! `0..=⌊(space.width − width)/grid⌋` (resp. height), so the whole object lies
//! inside the space. Fixed and already-placed objects are constants.
//!
//! # Objects that turn
//!
//! An unplaced, `turnable`, oblong object not already `turned` also gets
//! an *orientation variable* `t` (domain `0..=1`, 1 when it lies turned;
//! after every coordinate variable in [`Model::vars`], `IntVar::turn`
//! set, [`Model::turn_vars`]). Its grid domains are the union of both
//! orientations' (`0..=max(⌊(W−w)/g⌋, ⌊(W−h)/g⌋)`), with each
//! orientation's own bounds as clauses (`t → gx ≤ ⌊(W−h)/g⌋`, …). A
//! comparison that names its far edge becomes a case split over the
//! orientations of the (at most two) objects involved, e.g.
//! `x_a − x_b ≥ w_b` is `(¬t_b ∧ x_a − x_b ≥ w_b) ∨ (t_b ∧ x_a − x_b ≥ h_b)`,
//! built from the same `Ge`/`DiffGe`/`And` definitions (`t` itself is
//! `Ge { t, 1 }`), so every Boolean stays a function of the variables'
//! values and nothing downstream needs a new kind. A model without an
//! orientation variable is exactly the model it always was. Non-overlap
//! of a model with one is stated pairwise (the engine's non-overlap
//! propagator assumes constant sizes); the cumulatives give such an
//! object the square of its smaller side (sound either way); resemblance
//! terms leave it out (`synthesize` with `like` enumerates orientations).
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
//! # Relations (docs/language.md#relations)
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
//! # Rules (docs/language.md#class-rules, docs/language.md#the-score, docs/language.md)
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

pub(crate) use crate::relations::Axis;
use crate::relations::Contact;
use crate::scene::Scene;
use std::collections::HashMap;

mod bools;
mod build;
mod compile;
mod packing;
mod shapes;

pub(crate) use build::Encoding;
pub(crate) use compile::MAX_PAIR_LITERALS;

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

/// An integer grid-index variable with domain `0..=ub`, or an object's
/// orientation variable (`turn`: domain `0..=1`, 1 when it lies turned).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IntVar {
    /// The object it positions (or turns).
    pub object: usize,
    /// Which coordinate (`Axis::X` for an orientation variable).
    pub axis: Axis,
    /// Upper bound of the domain (the lower bound is 0).
    pub ub: i64,
    /// An orientation variable, not a coordinate.
    pub turn: bool,
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
    /// Engine tuning (see [`crate::synth::Tuning`]).
    pub tuning: crate::synth::Tuning,
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
    /// Per object: `(width, height)`: its footprint as given (flat for an
    /// object with an orientation variable, see [`Model::turn_vars`]).
    pub sizes: Vec<(i64, i64)>,
    /// Per object: its orientation variable (an index into
    /// [`Model::vars`], after every coordinate variable), for an unplaced,
    /// `turnable`, oblong object not already `turned`; `None` otherwise.
    pub turn_vars: Vec<Option<usize>>,
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
    /// posts it as one propagator ([`build::PAIRWISE_NO_OVERLAP_PAIRS`]).
    pub pairwise_no_overlap: bool,
    /// How group statements' connectivity is encoded.
    pub connectivity: Connectivity,
    /// The engine tuning the model was built with (the engine reads its
    /// choices from here).
    pub(crate) tuning: crate::synth::Tuning,
    interned: HashMap<BoolDef, u32>,
}

impl Model {
    /// The coordinate, in this model, of the object and axis that `v` (a
    /// variable of this or of another model of the same problem) positions.
    pub fn coord_of(&self, v: &IntVar) -> Coord {
        if v.turn {
            // An orientation variable: this model's, or none (`Const`).
            return self.turn_vars[v.object].map_or(Coord::Const(0), Coord::Var);
        }
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

    fn is_const(&self, o: usize) -> bool {
        matches!(self.coords[o].0, Coord::Const(_))
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

    /// Whether the model has an orientation variable.
    pub fn has_turns(&self) -> bool {
        self.turn_vars.iter().any(Option::is_some)
    }

    /// Whether object `o` lies turned under values `vals` (always false
    /// without an orientation variable: its footprint is `sizes[o]`).
    pub fn turned_in(&self, o: usize, vals: &[i64]) -> bool {
        self.turn_vars[o].is_some_and(|t| vals[t] == 1)
    }

    /// Object `o`'s footprint `(width, height)` under values `vals`.
    pub fn footprint_in(&self, o: usize, vals: &[i64]) -> (i64, i64) {
        let (w, h) = self.sizes[o];
        if self.turned_in(o, vals) {
            (h, w)
        } else {
            (w, h)
        }
    }

    fn axis_origin(&self, axis: Axis) -> i64 {
        match axis {
            Axis::X => self.origin.0,
            Axis::Y => self.origin.1,
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

    /// The complete scene for grid values `vals` (an object whose
    /// orientation variable is 1 lies `turned`).
    pub fn scene(&self, problem: &Scene, vals: &[i64]) -> Scene {
        let mut s = problem.clone();
        for (i, o) in s.objects.iter_mut().enumerate() {
            if let (Coord::Var(vx), Coord::Var(vy)) = self.coords[i] {
                o.x = Some(self.origin.0 + self.grid * vals[vx]);
                o.y = Some(self.origin.1 + self.grid * vals[vy]);
            }
            if self.turned_in(i, vals) {
                o.turned = true;
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::Evaluator;
    use crate::relations::{relation_bits, Dir, Kind, Quant, Relation};
    use crate::rules::{Atom, Formula, Rule, RuleSet, Scope, Strength, Target};
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
            turnable: false,
            turned: false,
        }
    }

    fn opts(contact: Contact, rules: bool) -> BuildOptions {
        BuildOptions {
            contact,
            rules,
            symmetry_breaking: false,
            redundant: false,
            tuning: Default::default(),
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

    /// With orientation variables: every pair literal is the geometry of
    /// the footprints the orientation values give, and the model's
    /// clauses hold exactly when every object lies inside the space and
    /// no two overlap.
    #[test]
    fn pair_literals_and_containment_follow_the_orientation_variables() {
        let mut scene = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 40,
                height: 30,
            },
            grid: 10,
            objects: vec![
                obj("a", "A", 20, 10, None).with_turnable(),
                // Flat it fits only at x ≤ 30; turned (30 × 10) at x ≤ 10.
                obj("b", "B", 10, 30, None).with_turnable(),
                obj("c", "C", 10, 10, None).with_turnable(),
                obj("f", "F", 10, 20, Some((30, 10))),
            ],
        };
        scene.objects[3].fixed = true;
        for contact in Contact::ALL {
            let m = Model::build(&scene, &RuleSet::default(), opts(contact, false));
            // a and b turn, the square c does not.
            assert_eq!(m.turn_vars, vec![Some(6), Some(7), None, None]);
            assert_eq!((m.vars[2].ub, m.vars[3].ub), (3, 2));
            let seen = check_pairs(&scene, contact);
            assert!(seen.iter().all(|e| *e == (true, true)), "{seen:?}");
            let mut inside = 0;
            each_assignment(&m, |vals| {
                let bools = m.eval_bools(vals);
                let clauses = m.clauses.iter().all(|c| c.iter().any(|l| l.value(&bools)));
                let s = m.scene(&scene, vals);
                let within = s.objects.iter().all(|o| {
                    let r = o.rect().expect("placed");
                    r.x2() <= 40 && r.y2() <= 30
                });
                // (A model with orientation variables states non-overlap
                // as clauses too.)
                assert_eq!(clauses, within && m.non_overlapping(vals), "{vals:?}");
                inside += usize::from(within);
            });
            // a: 3·3 flat + 4·2 turned; b: 4·1 + 2·3; c: 4·3.
            assert_eq!(inside, (9 + 8) * (4 + 6) * 12);
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
