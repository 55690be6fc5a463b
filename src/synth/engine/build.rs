//! Posting a [`Model`] into a fresh Pumpkin solver: the range check of
//! every number handed to Pumpkin, then every `create_*` step before every
//! `post_*` step, then the engine with its brancher.

use super::brancher::Phased;
use super::stop::{Counters, Counting};
use super::{resemblance_fits, Engine, Stop};
use crate::synth::model::{BoolDef, Coord, Lit, Model};
use crate::synth::resemblance_terms::ResemblanceTerm;
use crate::synth::SynthError;
use pumpkin_conflict_resolvers::resolvers::ResolutionResolver;
use pumpkin_constraints::{boolean_equals, cumulative, less_than_or_equals};
use pumpkin_core::branching::branchers::independent_variable_value_brancher::IndependentVariableValueBrancher;
use pumpkin_core::branching::value_selection::InDomainMin;
use pumpkin_core::branching::variable_selection::FirstFail;
use pumpkin_core::branching::Brancher;
use pumpkin_core::options::SolverOptions;
use pumpkin_core::predicate;
use pumpkin_core::predicates::Predicate;
use pumpkin_core::proof::ConstraintTag;
use pumpkin_core::rand::rngs::SmallRng;
use pumpkin_core::rand::SeedableRng;
use pumpkin_core::variables::{AffineView, DomainId, Literal, TransformableVariable};
use pumpkin_core::Solver;
use std::cell::Cell;
use std::rc::Rc;

/// `v` as an `i32`, or [`SynthError::TooLarge`] naming `what`.
pub(super) fn i32_of(v: i64, what: impl FnOnce() -> String) -> Result<i32, SynthError> {
    i32::try_from(v).map_err(|_| {
        SynthError::TooLarge(format!(
            "{} ({v}) is too large for the solver's 32-bit arithmetic",
            what()
        ))
    })
}

/// `v` clamped into `i32`: for objective bounds, which lie in
/// `-1..=total` with `total` checked to fit; clamping keeps the meaning of
/// `obj ≥ v` / `obj ≤ v` for an `obj` whose domain is inside `i32`.
pub(super) fn clamp_i32(v: i64) -> i32 {
    v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// Check every number of `model` (and of the resemblance terms) that will
/// be handed to Pumpkin before the solver exists.
pub(super) fn check_ranges(model: &Model, like: &[ResemblanceTerm]) -> Result<(), SynthError> {
    for v in &model.vars {
        i32_of(v.ub, || {
            format!("the position range of objects[{}]", v.object)
        })?;
    }
    for s in &model.symmetry {
        if !model.lin_fits_i32(s) {
            return Err(SynthError::TooLarge(
                "a symmetry-breaking order is too large for the solver's 32-bit arithmetic".into(),
            ));
        }
    }
    for c in &model.cumulative {
        if !model.cumulative_fits_i32(c) {
            return Err(SynthError::TooLarge(
                "the area relaxation is too large for the solver's 32-bit arithmetic".into(),
            ));
        }
    }
    if !resemblance_fits(like) {
        return Err(SynthError::TooLarge(
            "resemblance costs are too large for the solver's 32-bit arithmetic".into(),
        ));
    }
    i32_of(model.grid, || "grid".into())?;
    // The origin fits in 32 bits (every coordinate the engine sees is one of
    // its offsets).
    i32_of(model.origin.0, || "space.x".into())?;
    i32_of(model.origin.1, || "space.y".into())?;
    Ok(())
}

/// The solver being filled with one model. Pumpkin panics when a variable
/// is created after a post made the root inconsistent (e.g. objects that
/// cannot fit at all), so every `create_*` step runs before every `post_*`
/// step.
pub(super) struct Builder<'m> {
    pub(super) model: &'m Model,
    pub(super) solver: Solver,
    pub(super) tag: ConstraintTag,
    pub(super) vars: Vec<DomainId>,
    /// One Pumpkin literal per model Boolean.
    pub(super) lits: Vec<Literal>,
    pub(super) truth: Literal,
    /// Building stops (and the engine is not made) past this instant.
    /// The deadline and the cancel flag (the node limit is not used here).
    pub(super) stop: Stop,
}

impl<'m> Builder<'m> {
    /// Whether the deadline has passed (checked between the steps and
    /// every few thousand definitions: posting a large model can take
    /// longer than the whole time limit).
    pub(super) fn late(&self) -> bool {
        self.stop.expired()
    }

    /// The solver with one integer variable per grid variable.
    pub(super) fn new(model: &'m Model, seed: u64) -> Result<Self, SynthError> {
        let mut solver = Solver::with_options(SolverOptions {
            random_generator: SmallRng::seed_from_u64(seed),
            memory_preallocated: 1,
            ..Default::default()
        });
        let tag = solver.new_constraint_tag();
        let vars = model
            .vars
            .iter()
            .map(|v| i32_of(v.ub, String::new).map(|ub| solver.new_bounded_integer(0, ub)))
            .collect::<Result<_, _>>()?;
        let truth = solver.get_true_literal();
        Ok(Builder {
            model,
            solver,
            tag,
            vars,
            lits: Vec::new(),
            truth,
            stop: Stop::never(),
        })
    }

    /// A model literal as a Pumpkin literal.
    pub(super) fn lit(&self, l: Lit) -> Literal {
        match l {
            Lit::Const(true) => self.truth,
            Lit::Const(false) => !self.truth,
            Lit::Var { id, neg } => {
                let x = self.lits[id as usize];
                if neg {
                    !x
                } else {
                    x
                }
            }
        }
    }

    /// One literal per model Boolean: a bound predicate for `Ge` (no
    /// propagator needed), a fresh literal for the others (defined by
    /// [`Builder::post_definitions`]).
    pub(super) fn create_literals(&mut self) -> Result<(), SynthError> {
        for def in &self.model.bools {
            let l = match def {
                BoolDef::Ge { var, k } => {
                    let x = self.vars[*var];
                    let k = i32_of(*k, || "a position bound".into())?;
                    self.solver
                        .new_literal_for_predicate(predicate![x >= k], self.tag)
                }
                BoolDef::DiffGe { .. }
                | BoolDef::And(_)
                | BoolDef::AtLeast { .. }
                | BoolDef::Connected { .. } => self.solver.new_literal(),
            };
            self.lits.push(l);
        }
        Ok(())
    }

    /// One assumption literal per hard rule (core extraction), or none.
    pub(super) fn create_guards(&mut self, guarded: bool) -> Vec<Literal> {
        if guarded {
            (0..self.model.hard.len())
                .map(|_| self.solver.new_literal())
                .collect()
        } else {
            Vec::new()
        }
    }

    /// The start views of every cumulative task (shifted to be ≥ 0, see
    /// `Model::cumulative_shift`); a fixed object's start is a constant
    /// variable.
    pub(super) fn create_cumulative_starts(
        &mut self,
    ) -> Result<Vec<Vec<AffineView<DomainId>>>, SynthError> {
        let model = self.model;
        let grid = i32_of(model.grid, || "grid".into())?;
        let mut all = Vec::with_capacity(model.cumulative.len());
        for cu in &model.cumulative {
            let mut starts = Vec::with_capacity(cu.tasks.len());
            let shift = model.cumulative_shift(cu);
            for &(o, _, _) in &cu.tasks {
                let (cx, cy) = model.coords[o];
                let (c, origin) = match cu.axis {
                    crate::synth::model::Axis::X => (cx, model.origin.0),
                    crate::synth::model::Axis::Y => (cy, model.origin.1),
                };
                starts.push(match c {
                    Coord::Const(v) => {
                        let v = i32_of(v.saturating_add(shift), || {
                            format!("the position of objects[{o}]")
                        })?;
                        self.solver.new_bounded_integer(v, v).scaled(1)
                    }
                    Coord::Var(v) => self.vars[v]
                        .scaled(grid)
                        .offset(i32_of(origin.saturating_add(shift), || {
                            "the space's origin".into()
                        })?),
                });
            }
            all.push(starts);
        }
        Ok(all)
    }

    /// The objective variable `0..=Σ coefs` over the variable soft terms.
    pub(super) fn create_objective(
        &mut self,
        coefs: Option<&[i64]>,
    ) -> Result<Option<DomainId>, SynthError> {
        let Some(coefs) = coefs else {
            return Ok(None);
        };
        let total: i128 = self
            .model
            .soft
            .iter()
            .zip(coefs)
            .filter(|(s, _)| matches!(s.lit, Lit::Var { .. }))
            .map(|(_, &c)| i128::from(c))
            .sum();
        let total = i64::try_from(total).unwrap_or(i64::MAX);
        let total = i32_of(total, || "the total of the rule weights".into())?;
        Ok(Some(self.solver.new_bounded_integer(0, total)))
    }

    /// The exact definition of every non-`Ge` Boolean.
    pub(super) fn post_definitions(&mut self) -> Result<(), SynthError> {
        let model = self.model;
        let tag = self.tag;
        let mut pairs: std::collections::BTreeMap<(usize, usize), Vec<(i32, Literal)>> =
            std::collections::BTreeMap::new();
        let by_pair = model.tuning.difference_propagator;
        for (i, def) in model.bools.iter().enumerate() {
            if i % 4096 == 4095 && self.late() {
                return Ok(());
            }
            let l = self.lits[i];
            match def {
                BoolDef::Ge { .. } => {}
                BoolDef::DiffGe { a, b, k } if by_pair => {
                    // One propagator per pair (see `difference`): the pair
                    // in order, a reversed literal as the negation of
                    // `a − b ≥ 1 − k`.
                    let (pair, k, l) = if a < b {
                        ((*a, *b), *k, l)
                    } else {
                        ((*b, *a), 1i64.saturating_sub(*k), !l)
                    };
                    let k = i32_of(k, || "a distance bound".into())?;
                    pairs.entry(pair).or_default().push((k, l));
                }
                BoolDef::DiffGe { a, b, k } => {
                    // a − b ≥ k  ⇔  b − a ≤ −k
                    let rhs = i32_of(k.saturating_neg(), || "a distance bound".into())?;
                    let terms = vec![self.vars[*b].scaled(1), self.vars[*a].scaled(-1)];
                    self.solver
                        .add_constraint(less_than_or_equals(terms, rhs, tag))
                        .reify(l);
                }
                BoolDef::And(children) => self.post_and(l, children),
                BoolDef::AtLeast { lits: counted, k } => self.post_at_least(l, counted, *k)?,
                BoolDef::Connected { nodes, edges } => self.post_connected(l, *nodes, edges),
            }
        }
        for ((a, b), lits) in pairs {
            let args = super::difference::DifferenceArgs {
                a: self.vars[a],
                b: self.vars[b],
                lits,
                tag,
            };
            // As above: a root failure surfaces at the first solve.
            let _ = self.solver.add_propagator(args);
        }
        Ok(())
    }

    /// `l ⇔ ∧ children`: one clause per child and one back.
    fn post_and(&mut self, l: Literal, children: &[Lit]) {
        let tag = self.tag;
        let cs: Vec<Literal> = children.iter().map(|&c| self.lit(c)).collect();
        for &c in &cs {
            self.solver
                .add_clause([(!l).get_true_predicate(), c.get_true_predicate()], tag);
        }
        let mut big: Vec<Predicate> = vec![l.get_true_predicate()];
        big.extend(cs.iter().map(|c| (!*c).get_true_predicate()));
        self.solver.add_clause(big, tag);
    }

    /// `l ⇔ Σ counted ≥ k`  ⇔  `Σ −[counted] ≤ −k`. A literal counted m
    /// times is one term with coefficient −m (the model keeps one polarity
    /// per Boolean), so no solver variable appears twice in the sum.
    fn post_at_least(&mut self, l: Literal, counted: &[Lit], k: u32) -> Result<(), SynthError> {
        let terms: Vec<AffineView<DomainId>> = counted
            .chunk_by(|a, b| a == b)
            .map(|g| {
                // (counts fit: at most one term per object)
                let m = i32::try_from(g.len()).unwrap_or(i32::MAX);
                self.lit(g[0]).get_integer_variable().scaled(-m)
            })
            .collect();
        let rhs = i32_of(-i64::from(k), || "a count bound".into())?;
        self.solver
            .add_constraint(less_than_or_equals(terms, rhs, self.tag))
            .reify(l);
        Ok(())
    }

    /// `l ⇔` the chosen edges connect the nodes (see `connected`).
    fn post_connected(&mut self, l: Literal, nodes: u32, edges: &[(u32, u32, Lit)]) {
        let args = super::connected::ConnectedArgs {
            out: l,
            nodes: nodes as usize,
            edges: edges
                .iter()
                .map(|&(a, b, e)| (a as usize, b as usize, self.lit(e)))
                .collect(),
            tag: self.tag,
        };
        // A root failure surfaces as "infeasible" at the first solve, as
        // for the other propagators.
        let _ = self.solver.add_propagator(args);
    }

    /// Non-overlap of every pair with a variable object: one propagator
    /// (see `no_overlap`).
    pub(super) fn post_no_overlap(&mut self) -> Result<(), SynthError> {
        let model = self.model;
        if model.pairwise_no_overlap || model.vars.is_empty() || model.coords.len() < 2 {
            return Ok(());
        }
        let pos = |c: Coord| match c {
            Coord::Var(v) => super::no_overlap::Pos::Var(self.vars[v]),
            Coord::Const(x) => super::no_overlap::Pos::Const(x),
        };
        let args = super::no_overlap::NoOverlapArgs {
            pos: model
                .coords
                .iter()
                .map(|&(x, y)| [pos(x), pos(y)])
                .collect(),
            size: model.sizes.iter().map(|&(w, h)| [w, h]).collect(),
            origin: [model.origin.0, model.origin.1],
            grid: model.grid,
            tag: self.tag,
        };
        // The root propagation may already fail (the objects cannot all
        // fit): the engine then reports "infeasible" at its first solve.
        let _ = self.solver.add_propagator(args);
        Ok(())
    }

    /// The model's clauses (the symmetry fallback; non-overlap when the
    /// model states it pairwise).
    pub(super) fn post_clauses(&mut self) {
        for c in &self.model.clauses {
            let c: Vec<Predicate> = c
                .iter()
                .map(|&l| self.lit(l).get_true_predicate())
                .collect();
            self.solver.add_clause(c, self.tag);
        }
    }

    /// Every hard literal, as a unit or under its rule's guard.
    pub(super) fn post_hard(&mut self, guards: &[Literal]) {
        for (i, h) in self.model.hard.iter().enumerate() {
            let g = guards.get(i).copied();
            for &l in &h.lits {
                let mut c = vec![self.lit(l).get_true_predicate()];
                if let Some(g) = g {
                    c.push((!g).get_true_predicate());
                }
                self.solver.add_clause(c, self.tag);
            }
        }
    }

    /// The symmetry-breaking orders (linear `≤`).
    pub(super) fn post_symmetry(&mut self) -> Result<(), SynthError> {
        for s in &self.model.symmetry {
            let mut terms: Vec<AffineView<DomainId>> = Vec::with_capacity(s.terms.len());
            for &(c, v) in &s.terms {
                terms.push(self.vars[v].scaled(i32_of(c, || "a symmetry coefficient".into())?));
            }
            let rhs = i32_of(s.rhs, || "a symmetry bound".into())?;
            self.solver
                .add_constraint(less_than_or_equals(terms, rhs, self.tag))
                .post();
        }
        Ok(())
    }

    /// The redundant cumulative relaxations, over the starts made by
    /// [`Builder::create_cumulative_starts`].
    pub(super) fn post_cumulative(
        &mut self,
        starts: Vec<Vec<AffineView<DomainId>>>,
    ) -> Result<(), SynthError> {
        for (cu, starts) in self.model.cumulative.iter().zip(starts) {
            let mut durs: Vec<i32> = Vec::with_capacity(cu.tasks.len());
            let mut dems: Vec<i32> = Vec::with_capacity(cu.tasks.len());
            for &(o, dur, dem) in &cu.tasks {
                durs.push(i32_of(dur, || format!("the size of objects[{o}]"))?);
                dems.push(i32_of(dem, || format!("the size of objects[{o}]"))?);
            }
            let capacity = i32_of(cu.capacity, || "the space size".into())?;
            self.solver
                .add_constraint(cumulative(starts, durs, dems, capacity, self.tag))
                .post();
        }
        Ok(())
    }

    /// `obj = Σ cᵢ·[litᵢ]` over the variable soft terms; returns the
    /// objective with its coefficients.
    pub(super) fn post_objective(
        &mut self,
        coefs: Option<&[i64]>,
        obj: Option<DomainId>,
    ) -> Result<Option<(DomainId, Vec<i64>)>, SynthError> {
        let (Some(coefs), Some(obj)) = (coefs, obj) else {
            return Ok(None);
        };
        let mut ws = Vec::new();
        for (s, &c) in self.model.soft.iter().zip(coefs) {
            if let Lit::Var { .. } = s.lit {
                ws.push(c);
            }
        }
        // One term per distinct literal (coefficients summed): many rules
        // or objects sharing a literal would otherwise register the same
        // literal once per term with the engine (quadratic).
        let mut index: std::collections::HashMap<Lit, usize> = std::collections::HashMap::new();
        let mut agg: Vec<(Lit, i64)> = Vec::new();
        for (s, &c) in self.model.soft.iter().zip(coefs) {
            if let Lit::Var { .. } = s.lit {
                match index.get(&s.lit) {
                    Some(&k) => agg[k].1 += c,
                    None => {
                        index.insert(s.lit, agg.len());
                        agg.push((s.lit, c));
                    }
                }
            }
        }
        let mut ws32 = Vec::with_capacity(agg.len());
        let mut ls = Vec::with_capacity(agg.len());
        for (l, c) in agg {
            ws32.push(i32_of(c, || "a rule weight".into())?);
            ls.push(self.lit(l));
        }
        self.solver
            .add_constraint(boolean_equals(ws32, ls, obj, self.tag))
            .post();
        Ok(Some((obj, ws)))
    }

    /// The engine, with its two-phase brancher (created only now that every
    /// variable exists).
    pub(super) fn finish(
        self,
        guards: Vec<Literal>,
        objective: Option<(DomainId, Vec<i64>)>,
        resemblance_total: Option<DomainId>,
    ) -> Engine {
        let counters = Counters::default();
        let main: Box<dyn Brancher> = Box::new(self.solver.default_brancher());
        let first_phase = Rc::new(Cell::new(true));
        let inner = Phased {
            hint: None,
            first: IndependentVariableValueBrancher::new(FirstFail::new(&self.vars), InDomainMin),
            main,
            use_first: first_phase.clone(),
            first_conflicts: 0,
            first_cap: None,
            late: None,
            late_vars: Vec::new(),
        };
        let brancher = Counting {
            inner,
            nodes: counters.nodes.clone(),
            conflicts: counters.conflicts.clone(),
            safe: counters.safe.clone(),
        };
        Engine {
            solver: self.solver,
            brancher,
            resolver: ResolutionResolver::default(),
            vars: self.vars,
            guards,
            objective,
            counters,
            tag: self.tag,
            first_phase,
            resemblance_total,
            pending_resemblance: None,
            dead: false,
        }
    }
}
