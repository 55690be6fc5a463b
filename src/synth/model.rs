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
//! # Relations (SPEC §3)
//!
//! With `s_N(a,b) ⇔ a.y ≥ b.y2 + 1` ("strictly north, with a gap"):
//! `DR_N(a,b) ⇔ a.y − b.y ≥ b.h`;
//! `EC_N(a,b) ⇔ DR_N(a,b) ∧ ¬s_N(a,b) ∧ xmeet(a,b)` where point contact is
//! `xmeet ⇔ ¬s_E(a,b) ∧ ¬s_W(a,b)` and edge contact is
//! `xmeet ⇔ ¬DR_E(a,b) ∧ ¬DR_W(a,b)`. Non-overlap of a pair is the clause
//! `DR_N ∨ DR_S ∨ DR_E ∨ DR_W` over the same literals.
//!
//! # Rules (SPEC §4, §6)
//!
//! A class atom of object `o` is the AND (DR) / OR (EC) over every other
//! object of the target class, all objects counted (after synthesis every
//! object is placed). Each (object, rule) pair is one reified formula literal.
//! Hard rules give literals that must be true; soft rules give weighted
//! objective terms over all objects of the subject class (already-placed
//! ones included).

use crate::relations::{Contact, Dir, Kind, Relation};
use crate::rules::{Formula, RuleSet, Target};
use crate::scene::Scene;
use std::collections::HashMap;

/// An axis of the plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// East–west.
    X,
    /// North–south.
    Y,
}

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

/// One objective term: `weight · [lit]` (soft rule `rule` on `object`).
#[derive(Debug, Clone, PartialEq)]
pub struct SoftTerm {
    /// Index in the rule set.
    pub rule: usize,
    /// Subject object.
    pub object: usize,
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
    /// Clauses that must hold (non-overlap).
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
    interned: HashMap<BoolDef, u32>,
}

fn ceil_div(a: i64, b: i64) -> i64 {
    -((-a).div_euclid(b))
}

fn floor_div(a: i64, b: i64) -> i64 {
    a.div_euclid(b)
}

impl Model {
    /// Build the model of `problem` with `rules`.
    ///
    /// The problem must be a valid scene (see [`Scene::validate`]).
    pub fn build(problem: &Scene, rules: &RuleSet, opts: BuildOptions) -> Model {
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
            return m;
        }
        let n = problem.objects.len();
        // Non-overlap between every pair with at least one variable object.
        for a in 0..n {
            for b in a + 1..n {
                if m.is_const(a) && m.is_const(b) {
                    continue;
                }
                let c: Vec<Lit> = Dir::ALL
                    .iter()
                    .map(|&d| m.pair(Relation::new(Kind::DR, d), a, b, opts.contact))
                    .collect();
                let l = m.or(c);
                if l != Lit::TRUE {
                    m.clauses.push(vec![l]);
                }
            }
        }
        if opts.symmetry_breaking {
            m.post_symmetry(problem);
        }
        if opts.redundant {
            m.post_cumulative(problem);
        }
        if opts.rules {
            m.post_rules(problem, rules, opts.contact);
        }
        m
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

    /// The pairwise relation `rel(a, b)` between two distinct objects.
    pub fn pair(&mut self, rel: Relation, a: usize, b: usize, contact: Contact) -> Lit {
        let (axis, cross) = match rel.dir {
            Dir::N | Dir::S => (Axis::Y, Axis::X),
            Dir::E | Dir::W => (Axis::X, Axis::Y),
        };
        // "a after b on the axis" (N or E) vs "a before b" (S or W).
        let (p, q) = match rel.dir {
            Dir::N | Dir::E => (a, b),
            Dir::S | Dir::W => (b, a),
        };
        // DR: p − q ≥ size(q)
        let sq = self.size(q, axis);
        let dr = self.diff_ge(axis, p, q, sq);
        match rel.kind {
            Kind::DR => dr,
            Kind::EC => {
                let gap = self.diff_ge(axis, p, q, sq + 1);
                let meet = match contact {
                    Contact::Point => {
                        let (sa, sb) = (self.size(a, cross), self.size(b, cross));
                        let g1 = self.diff_ge(cross, a, b, sb + 1);
                        let g2 = self.diff_ge(cross, b, a, sa + 1);
                        vec![!g1, !g2]
                    }
                    Contact::Edge => {
                        let (sa, sb) = (self.size(a, cross), self.size(b, cross));
                        let d1 = self.diff_ge(cross, a, b, sb);
                        let d2 = self.diff_ge(cross, b, a, sa);
                        vec![!d1, !d2]
                    }
                };
                let mut all = vec![dr, !gap];
                all.extend(meet);
                self.and(all)
            }
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
                // nx·ya + xa < nx·yb + xb
                self.symmetry.push(LinLe {
                    terms: vec![(nx, ya), (1, xa), (-nx, yb), (-1, xb)],
                    rhs: -1,
                });
            }
        }
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
                self.cumulative.push(Cumulative {
                    axis,
                    tasks,
                    capacity,
                });
            }
        }
    }

    fn post_rules(&mut self, problem: &Scene, rules: &RuleSet, contact: Contact) {
        let mut cache: HashMap<(usize, Relation, Option<String>), Lit> = HashMap::new();
        for (ri, rule) in rules.rules.iter().enumerate() {
            let subject = rule.subject();
            let mut hard = Vec::new();
            for (o, obj) in problem.objects.iter().enumerate() {
                if obj.class != subject {
                    continue;
                }
                let lit = self.formula(&rule.formula, o, problem, contact, &mut cache);
                if rule.strength.is_hard() {
                    hard.push(lit);
                } else {
                    self.soft.push(SoftTerm {
                        rule: ri,
                        object: o,
                        lit,
                        weight: rule.strength.weight(),
                    });
                }
            }
            if rule.strength.is_hard() {
                self.hard.push(HardRule {
                    rule: ri,
                    lits: hard,
                });
            }
        }
    }

    fn formula(
        &mut self,
        f: &Formula,
        o: usize,
        problem: &Scene,
        contact: Contact,
        cache: &mut HashMap<(usize, Relation, Option<String>), Lit>,
    ) -> Lit {
        match f {
            Formula::Atom(a) => {
                let target = match &a.target {
                    Target::Any => None,
                    Target::Class(c) => Some(c.clone()),
                };
                let key = (o, a.rel, target);
                if let Some(&l) = cache.get(&key) {
                    return l;
                }
                let others: Vec<usize> = problem
                    .objects
                    .iter()
                    .enumerate()
                    .filter(|(b, ob)| *b != o && key.2.as_ref().is_none_or(|c| &ob.class == c))
                    .map(|(b, _)| b)
                    .collect();
                let lits: Vec<Lit> = others
                    .into_iter()
                    .map(|b| self.pair(a.rel, o, b, contact))
                    .collect();
                let l = if a.rel.is_universal() {
                    self.and(lits)
                } else {
                    self.or(lits)
                };
                cache.insert(key, l);
                l
            }
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
    use crate::relations::relation_bits;
    use crate::scene::{Object, Space};

    fn obj(class: &str, w: i64, h: i64, pos: Option<(i64, i64)>) -> Object {
        Object {
            id: String::new(),
            class: class.into(),
            x: pos.map(|p| p.0),
            y: pos.map(|p| p.1),
            width: w,
            height: h,
            fixed: false,
        }
    }

    /// Every pairwise literal agrees with `relation_bits` on every layout of a
    /// small problem with off-grid sizes, for both contact modes.
    #[test]
    fn pair_literals_match_geometry() {
        for contact in [Contact::Point, Contact::Edge] {
            let mut scene = Scene {
                space: Space {
                    x: 3,
                    y: -2,
                    width: 40,
                    height: 33,
                },
                grid: 5,
                objects: vec![
                    obj("A", 10, 7, None),
                    obj("B", 13, 5, None),
                    obj("C", 6, 9, Some((17, 8))),
                ],
            };
            for (i, o) in scene.objects.iter_mut().enumerate() {
                o.id = format!("o{i}");
            }
            let mut m = Model::build(
                &scene,
                &RuleSet::default(),
                BuildOptions {
                    contact,
                    rules: false,
                    symmetry_breaking: false,
                    redundant: false,
                },
            );
            let mut lits = Vec::new();
            for a in 0..3 {
                for b in 0..3 {
                    if a != b {
                        for rel in Relation::ALL {
                            lits.push((a, b, rel, m.pair(rel, a, b, contact)));
                        }
                    }
                }
            }
            let ub: Vec<i64> = m.vars.iter().map(|v| v.ub).collect();
            let mut vals = vec![0i64; 4];
            loop {
                let s = m.scene(&scene, &vals);
                let bools = m.eval_bools(&vals);
                for &(a, b, rel, l) in &lits {
                    let ra = s.objects[a].rect().unwrap();
                    let rb = s.objects[b].rect().unwrap();
                    let want = relation_bits(&ra, &rb, contact) & rel.bit() != 0;
                    assert_eq!(l.value(&bools), want, "{rel}({a},{b}) at {vals:?}");
                }
                // next assignment
                let mut i = 0;
                loop {
                    if i == vals.len() {
                        return_if_done(&mut vals);
                        break;
                    }
                    vals[i] += 1;
                    if vals[i] > ub[i] {
                        vals[i] = 0;
                        i += 1;
                    } else {
                        break;
                    }
                }
                if vals.is_empty() {
                    break;
                }
            }
        }
        fn return_if_done(v: &mut Vec<i64>) {
            v.clear();
        }
    }
}
