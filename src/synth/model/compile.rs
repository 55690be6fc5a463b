//! Rules into literals: a pairwise relation read off its entry in
//! [`crate::relations::TABLE`], class atoms counted by their quantifier,
//! one literal per (object, rule) or per scene-level rule.

use super::{HardRule, Lit, Model, SoftTerm};
use crate::relations::{Axis, Cmp, Contact, Edge, Op, Quant, Relation, Side};
use crate::rules::{Formula, Rule, RuleSet, Scope, Target};
use crate::scene::Scene;
use std::collections::HashMap;

/// Most pairwise relation literals the rules may ask for in one model
/// ([`Model::pair_literals`]): 120 000, about 1.5 GB at the engine's cost
/// of about 12.5 KB per literal (measured: `rule t: EC_N(R, *)` over 200
/// objects, 40 000 literals, 513 MB); past it synthesis is refused before
/// anything is built instead of running out of memory. A rule against a
/// landmark costs one literal per subject; `*` or a large target class,
/// one per pair.
pub(crate) const MAX_PAIR_LITERALS: u128 = 120_000;

/// Atom literals already built: `(object, relation, quantifier, target)`.
type AtomCache = HashMap<(usize, Relation, Quant, Target), Lit>;

impl Model {
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
    pub(super) fn cmp(&mut self, c: &Cmp, a: usize, b: usize, out: &mut Vec<Lit>) {
        let obj = |s: Side| match s {
            Side::A => a,
            Side::B => b,
        };
        let axis = c.lhs.1.axis();
        let (p, q) = (obj(c.lhs.0), obj(c.rhs.0));
        // lhs = coord(p) + op, rhs = coord(q) + oq.
        let (ep, eq) = (c.lhs.1, c.rhs.1);
        match c.op {
            Op::Ge => out.push(self.edge_ge(axis, (p, ep), (q, eq), 0)),
            Op::Gt => out.push(self.edge_ge(axis, (p, ep), (q, eq), 1)),
            Op::Le => out.push(self.edge_ge(axis, (q, eq), (p, ep), 0)),
            Op::Lt => out.push(self.edge_ge(axis, (q, eq), (p, ep), 1)),
            Op::Eq => {
                out.push(self.edge_ge(axis, (p, ep), (q, eq), 0));
                out.push(self.edge_ge(axis, (q, eq), (p, ep), 0));
            }
        }
    }

    /// Edge `ea` of object `a` ≥ edge `eb` of object `b` plus `plus`, along
    /// `axis`: `coord(a) − coord(b) ≥ off(b) − off(a) + plus`, where a far
    /// edge's offset is the object's size along the axis. The size of an
    /// object with an orientation variable `t` depends on it, so the
    /// comparison is split over the orientations of the (at most two)
    /// objects whose far edge it names: `∨ (orientation ∧ a − b ≥ k)` —
    /// exact, since exactly one case's orientation holds. Without an
    /// orientation variable involved it is the one literal it always was.
    pub(super) fn edge_ge(
        &mut self,
        axis: Axis,
        (a, ea): (usize, Edge),
        (b, eb): (usize, Edge),
        plus: i64,
    ) -> Lit {
        let ca = self.offsets(a, ea, axis);
        let cb = self.offsets(b, eb, axis);
        if ca.len() == 1 && cb.len() == 1 {
            return self.diff_ge(axis, a, b, (cb[0].1 - ca[0].1).saturating_add(plus));
        }
        let mut cases = Vec::with_capacity(ca.len() * cb.len());
        for &(la, oa) in &ca {
            for &(lb, ob) in &cb {
                cases.push((
                    [la, lb],
                    self.diff_ge(axis, a, b, (ob - oa).saturating_add(plus)),
                ));
            }
        }
        // The same bound in every case: no split needed.
        if cases.iter().all(|c| c.1 == cases[0].1) {
            return cases[0].1;
        }
        let mut disjuncts = Vec::with_capacity(cases.len());
        for ([la, lb], l) in cases {
            disjuncts.push(self.and(vec![la, lb, l]));
        }
        self.or(disjuncts)
    }

    /// The offsets of edge `e` of object `o` along `axis`, each under the
    /// orientation literal that gives it: one case `(true, offset)`
    /// unless `e` is a far edge of an object with an orientation variable.
    fn offsets(&mut self, o: usize, e: Edge, axis: Axis) -> Vec<(Lit, i64)> {
        if e.is_far() {
            self.sides(o, axis)
        } else {
            vec![(Lit::TRUE, 0)]
        }
    }

    /// Object `o`'s footprint side along `axis`, under the orientation
    /// literal that gives it: one case `(true, side)` without an
    /// orientation variable, else `(¬t, flat side)` and `(t, other side)`.
    pub(super) fn sides(&mut self, o: usize, axis: Axis) -> Vec<(Lit, i64)> {
        let flat = self.size(o, axis);
        match self.turn_vars[o] {
            None => vec![(Lit::TRUE, flat)],
            Some(t) => {
                let across = match axis {
                    Axis::X => self.sizes[o].1,
                    Axis::Y => self.sizes[o].0,
                };
                let turned = self.ge(t, 1);
                vec![(!turned, flat), (turned, across)]
            }
        }
    }

    /// Post every rule; `false` when `stop` said so first.
    pub(super) fn post_rules(
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
            if rule.scope == Scope::Group {
                let lit = self.group_literal(problem, rule, contact);
                self.post_scene_wide(ri, rule, lit);
                continue;
            }
            let Some((lits, objects)) =
                self.subject_literals(problem, rule, contact, &mut cache, stop)
            else {
                return false;
            };
            match rule.scope {
                Scope::Each if rule.strength.is_hard() => {
                    self.hard.push(HardRule { rule: ri, lits })
                }
                Scope::Each => {
                    let weight = rule.strength.weight();
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
                    self.post_scene_wide(ri, rule, lit);
                }
            }
        }
        true
    }

    /// The literal of a group statement: its shape over the objects of the
    /// shape's class, negated when the formula is.
    fn group_literal(&mut self, problem: &Scene, rule: &Rule, contact: Contact) -> Lit {
        match rule.formula.shape() {
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
        }
    }

    /// Post the one literal of rule `ri` about the whole scene: a hard rule
    /// or one soft term with the rule's weight.
    fn post_scene_wide(&mut self, ri: usize, rule: &Rule, lit: Lit) {
        if rule.strength.is_hard() {
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
    }

    /// The rule's formula for each object of its subject class, with those
    /// objects; `None` when `stop` said so first (asked every 256 objects).
    fn subject_literals(
        &mut self,
        problem: &Scene,
        rule: &Rule,
        contact: Contact,
        cache: &mut AtomCache,
        stop: &dyn Fn() -> bool,
    ) -> Option<(Vec<Lit>, Vec<usize>)> {
        let subject = rule.subject();
        let mut lits = Vec::new();
        let mut objects = Vec::new();
        for (o, obj) in problem.objects.iter().enumerate() {
            if obj.class != subject {
                continue;
            }
            if objects.len() % 256 == 255 && stop() {
                return None;
            }
            lits.push(self.formula(&rule.formula, o, problem, contact, cache));
            objects.push(o);
        }
        Some((lits, objects))
    }

    /// How many pairwise relation literals the rules ask for on `problem`
    /// at most: per rule and atom, subject objects × target objects; per
    /// group statement, the unordered pairs of its class's objects × the
    /// relations of the shape's adjacency (four for `group`). The
    /// model holds a few Booleans and the engine a few propagators per
    /// pair literal, so this bounds their memory ([`MAX_PAIR_LITERALS`]).
    pub fn pair_literals(problem: &Scene, rules: &RuleSet) -> u128 {
        let count =
            |class: &str| problem.objects.iter().filter(|o| o.class == class).count() as u128;
        let n = problem.objects.len() as u128;
        let mut total = 0u128;
        for rule in &rules.rules {
            let subjects = count(rule.subject());
            // A group statement relates every pair of its class's objects,
            // once per relation of the shape's adjacency (`Model::shape`).
            if let (Scope::Group, Some((shape, _))) = (rule.scope, rule.formula.shape()) {
                let m = count(&shape.class);
                let (contacts, align) = shape.kind.adjacency();
                let per_pair = contacts.len() as u128 + u128::from(align.is_some());
                total += m * m.saturating_sub(1) / 2 * per_pair;
                continue;
            }
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

    pub(super) fn formula(
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
            // The orientation variable, or the orientation given.
            Formula::Turned(_) => match self.turn_vars[o] {
                Some(t) => self.ge(t, 1),
                None => {
                    let ob = &problem.objects[o];
                    Lit::Const(ob.turned && ob.is_oblong())
                }
            },
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
}
