//! The Pumpkin engine: turns a [`Model`] into a Pumpkin `Solver` and runs
//! the optimisation loop, satisfiability checks and core extraction.
//!
//! Everything here runs on the calling thread (Pumpkin's `Solver` is not
//! `Send`). The brancher is created after every variable exists.
//!
//! # Encoding
//!
//! - grid variables: `new_bounded_integer(0, ub)`;
//! - `Ge` Booleans: `new_literal_for_predicate([v ≥ k])` (no propagator);
//! - `DiffGe` Booleans: a fresh literal reifying the linear `b − a ≤ −k`;
//! - `And` Booleans: the usual clauses `l → lᵢ` and `⋀lᵢ → l`;
//! - `AtLeast` Booleans: a fresh literal reifying the linear
//!   `Σ −mᵢ·[lᵢ] ≤ −k` over the distinct counted literals `lᵢ` (each a 0/1
//!   view, `1 − x` for a negated one) with multiplicities `mᵢ`; the reified
//!   linear propagator explains both directions, so it is sound under
//!   assumptions and in cores like every other reified constraint;
//! - objective: `obj = Σ cᵢ·[litᵢ]` (`boolean_equals`);
//! - symmetry: linear `≤`; redundant: `cumulative` on both axes in real units.
//!
//! # Search
//!
//! Two phases (see `Phased`): until the first solution, first-fail over the
//! grid variables with the smallest value (a greedy bottom-left packing, found
//! without backtracking in practice); then Pumpkin's default brancher (VSIDS
//! with solution-based phase saving, random backup) with 1UIP learning.
//! Without the greedy phase the first solve of a 48-object problem sometimes
//! found no layout at all within 10 s.
//!
//! # Optimisation
//!
//! None here: [`Engine`] is a [`Backend`]; the procedures that call it
//! (maximise the score, minimise the resemblance cost, shrink conflicts)
//! are in [`super::driver`]. Pumpkin's `LinearUnsatSat` is not used: its
//! final callback reports the first solution, and it steps the bound by one
//! unit, which is hopeless for scaled real weights.

use super::backend::{Assumption, Backend, Core, Fact, Verdict};
use super::like::LikeTerm;
use super::model::{BoolDef, Coord, Lit, Model};
use super::SynthError;
use like::PendingLike;
#[cfg(test)]
use like::{LikeEncoding, LIKE_ENCODING};

mod connected;
mod like;
mod like_group;
mod like_map;
mod no_overlap;
use pumpkin_conflict_resolvers::resolvers::ResolutionResolver;
use pumpkin_constraints::{boolean_equals, cumulative, less_than_or_equals};
use pumpkin_core::branching::branchers::independent_variable_value_brancher::IndependentVariableValueBrancher;
use pumpkin_core::branching::branchers::warm_start::WarmStart;
use pumpkin_core::branching::tie_breaking::InOrderTieBreaker;
use pumpkin_core::branching::value_selection::{InDomainMin, InDomainRandom};
use pumpkin_core::branching::variable_selection::{FirstFail, RandomSelector};
use pumpkin_core::branching::{Brancher, BrancherEvent, SelectionContext};
use pumpkin_core::options::SolverOptions;
use pumpkin_core::predicate;
use pumpkin_core::predicates::Predicate;
use pumpkin_core::proof::ConstraintTag;
use pumpkin_core::rand::rngs::SmallRng;
use pumpkin_core::rand::SeedableRng;
use pumpkin_core::results::{
    ProblemSolution, SatisfactionResult, SatisfactionResultUnderAssumptions, SolutionReference,
};
use pumpkin_core::statistics::StatisticLogger;
use pumpkin_core::termination::TerminationCondition;
use pumpkin_core::variables::{AffineView, DomainId, Literal, TransformableVariable};
use pumpkin_core::Solver;
use std::cell::Cell;
use std::rc::Rc;

/// `v` as an `i32`, or [`SynthError::TooLarge`] naming `what`.
fn i32_of(v: i64, what: impl FnOnce() -> String) -> Result<i32, SynthError> {
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
fn clamp_i32(v: i64) -> i32 {
    v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

pub use super::backend::Limits;

#[derive(Debug, Clone, Default)]
struct Counters {
    nodes: Rc<Cell<u64>>,
    conflicts: Rc<Cell<u64>>,
    safe: Rc<Cell<bool>>,
}

/// Polled by Pumpkin; stops on deadline, node limit or cancel flag.
///
/// Only ever stops *above the root*: Pumpkin 0.5 restores its state after
/// a timeout only when the timeout struck at a decision level above 0 (at
/// the root it stays "timed out", and the next solve asserts). `safe` is
/// set by [`Counting`] after each decision and cleared by each conflict
/// (which may jump back to the root), so a limit waits at most for the
/// next decision; an engine can then be solved again after any limit,
/// keeping what it learned.
struct Stop {
    limits: Limits,
    nodes: Rc<Cell<u64>>,
    safe: Rc<Cell<bool>>,
    fired: Rc<Cell<bool>>,
}

impl TerminationCondition for Stop {
    fn should_stop(&mut self) -> bool {
        if !self.safe.get() {
            return false;
        }
        let stop = self
            .limits
            .node_limit
            .is_some_and(|n| self.nodes.get() >= n)
            || self.limits.expired();
        if stop {
            self.fired.set(true);
        }
        stop
    }
}

/// A brancher wrapper that counts decisions and conflicts.
#[derive(Debug)]
struct Counting {
    inner: Phased,
    nodes: Rc<Cell<u64>>,
    conflicts: Rc<Cell<u64>>,
    /// Whether the search is above the root (see [`Stop`]).
    safe: Rc<Cell<bool>>,
}

impl Brancher for Counting {
    fn log_statistics(&self, l: StatisticLogger) {
        self.inner.log_statistics(l)
    }
    fn next_decision(&mut self, context: &mut SelectionContext) -> Option<Predicate> {
        let d = self.inner.next_decision(context);
        if d.is_some() {
            self.nodes.set(self.nodes.get() + 1);
            self.safe.set(true);
        }
        d
    }
    fn on_conflict(&mut self) {
        self.safe.set(false);
        self.conflicts.set(self.conflicts.get() + 1);
        self.inner.on_conflict()
    }
    fn on_backtrack(&mut self) {
        self.inner.on_backtrack()
    }
    fn on_solution(&mut self, solution: SolutionReference) {
        self.inner.on_solution(solution)
    }
    fn on_unassign_integer(&mut self, variable: DomainId, value: i32) {
        self.inner.on_unassign_integer(variable, value)
    }
    fn on_appearance_in_conflict_predicate(&mut self, predicate: Predicate) {
        self.inner.on_appearance_in_conflict_predicate(predicate)
    }
    fn on_restart(&mut self) {
        self.safe.set(false);
        self.inner.on_restart()
    }
    fn synchronise(&mut self, context: &mut SelectionContext) {
        self.inner.synchronise(context)
    }
    fn is_restart_pointless(&mut self) -> bool {
        self.inner.is_restart_pointless()
    }
    fn subscribe_to_events(&self) -> Vec<BrancherEvent> {
        let mut v = self.inner.subscribe_to_events();
        if !v.contains(&BrancherEvent::Conflict) {
            v.push(BrancherEvent::Conflict);
        }
        v
    }
}

type StaticBrancher = IndependentVariableValueBrancher<
    DomainId,
    FirstFail<DomainId, InOrderTieBreaker<DomainId, i32>>,
    InDomainMin,
>;

/// Two-phase search: until the first solution, place objects greedily
/// (first-fail over the grid variables, smallest value first), which finds a
/// packing at once; afterwards the main (learning) brancher. Every event
/// goes to both.
///
/// A *hint* ([`Engine::set_hint`]) comes before both: each hinted grid
/// variable is tried at its hinted value (Pumpkin's `WarmStart`), skipping
/// the ones that propagation already decided, until the next solution. The
/// hint is a value-ordering heuristic only: a hinted value that conflicts is
/// learned away like any decision, so it never changes what is provable.
#[derive(Debug)]
struct Phased {
    hint: Option<WarmStart<DomainId>>,
    first: StaticBrancher,
    main: Box<dyn Brancher>,
    use_first: Rc<Cell<bool>>,
    /// Conflicts met while the greedy phase was on.
    first_conflicts: u64,
    /// Leave the greedy phase after this many conflicts without a first
    /// solution ([`Engine::leave_greedy_after`]; `None`: only at a
    /// solution).
    first_cap: Option<u64>,
    /// Variables created after the engine (the second objective's), which
    /// the main brancher does not know: each takes its smallest value once
    /// `main` has nothing left to decide.
    late: Option<StaticBrancher>,
    late_vars: Vec<DomainId>,
}

impl Phased {
    /// Hand variables created after the engine to the brancher.
    fn add_late(&mut self, vars: &[DomainId]) {
        if vars.is_empty() {
            return;
        }
        self.late_vars.extend_from_slice(vars);
        self.late = Some(IndependentVariableValueBrancher::new(
            FirstFail::new(&self.late_vars),
            InDomainMin,
        ));
    }
}

impl Brancher for Phased {
    fn next_decision(&mut self, context: &mut SelectionContext) -> Option<Predicate> {
        if let Some(h) = &mut self.hint {
            if let Some(d) = h.next_decision(context) {
                return Some(d);
            }
        }
        if self.use_first.get() {
            if let Some(d) = self.first.next_decision(context) {
                return Some(d);
            }
        }
        if let Some(d) = self.main.next_decision(context) {
            return Some(d);
        }
        self.late.as_mut()?.next_decision(context)
    }
    fn on_conflict(&mut self) {
        // A greedy packing finds a first layout without backtracking in
        // practice; when it keeps failing, the problem is hard or
        // infeasible (an `ask` implication check, contradicting hard
        // rules), and the learning brancher — which also branches on the
        // rules' Booleans — proves it far sooner than coordinate
        // enumeration.
        if let (true, Some(cap)) = (self.use_first.get(), self.first_cap) {
            self.first_conflicts += 1;
            if self.first_conflicts >= cap {
                self.use_first.set(false);
            }
        }
        self.main.on_conflict()
    }
    fn on_backtrack(&mut self) {
        self.main.on_backtrack()
    }
    fn on_solution(&mut self, solution: SolutionReference) {
        // A hint lasts until the next solution.
        self.hint = None;
        self.main.on_solution(solution)
    }
    fn on_unassign_integer(&mut self, variable: DomainId, value: i32) {
        self.first.on_unassign_integer(variable, value);
        if let Some(l) = &mut self.late {
            l.on_unassign_integer(variable, value);
        }
        self.main.on_unassign_integer(variable, value)
    }
    fn on_appearance_in_conflict_predicate(&mut self, predicate: Predicate) {
        self.main.on_appearance_in_conflict_predicate(predicate)
    }
    fn on_restart(&mut self) {
        self.main.on_restart()
    }
    fn synchronise(&mut self, context: &mut SelectionContext) {
        if let Some(h) = &mut self.hint {
            h.synchronise(context);
        }
        self.first.synchronise(context);
        if let Some(l) = &mut self.late {
            l.synchronise(context);
        }
        self.main.synchronise(context)
    }
    fn is_restart_pointless(&mut self) -> bool {
        self.main.is_restart_pointless()
    }
    fn subscribe_to_events(&self) -> Vec<BrancherEvent> {
        let mut v = self.main.subscribe_to_events();
        // A hint may be set later: its events (solution, synchronise) are
        // always subscribed.
        for e in self
            .first
            .subscribe_to_events()
            .into_iter()
            .chain([BrancherEvent::Solution, BrancherEvent::Synchronise])
        {
            if !v.contains(&e) {
                v.push(e);
            }
        }
        v
    }
}

/// The result of one satisfiability call (the two-valued view of an
/// [`Verdict`] for callers that need no core).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Sat {
    /// A solution: grid values per model variable.
    Solution(Vec<i64>),
    /// Proved impossible (under the assumptions, when there are any).
    Unsat,
    /// A limit stopped the search.
    Unknown,
}

impl From<Verdict> for Sat {
    fn from(a: Verdict) -> Sat {
        match a {
            Verdict::Solution(v) => Sat::Solution(v),
            Verdict::Infeasible(_) => Sat::Unsat,
            Verdict::Unknown => Sat::Unknown,
        }
    }
}

/// A Pumpkin solver holding one model: the [`Backend`] the driver runs on.
pub struct Engine {
    solver: Solver,
    brancher: Counting,
    resolver: ResolutionResolver,
    vars: Vec<DomainId>,
    guards: Vec<Literal>,
    /// The objective variable and its coefficients (variable terms only).
    objective: Option<(DomainId, Vec<i64>)>,
    counters: Counters,
    tag: ConstraintTag,
    first_phase: Rc<Cell<bool>>,
    /// The resemblance total-cost variable (SPEC §12).
    like_total: Option<DomainId>,
    /// The second objective until the second phase starts ([`like`]).
    pending_like: Option<PendingLike>,
    /// Proved infeasible whatever the assumptions: Pumpkin's solver must not
    /// be called again (it asserts), and every later call is infeasible
    /// with an empty core.
    dead: bool,
}

impl std::fmt::Debug for Engine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Engine")
            .field("vars", &self.vars.len())
            .finish()
    }
}

/// Check every number of `model` (and of the resemblance terms) that will
/// be handed to Pumpkin before the solver exists.
fn check_ranges(model: &Model, like: &[LikeTerm]) -> Result<(), SynthError> {
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
    if !like_fits(like) {
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
struct Builder<'m> {
    model: &'m Model,
    solver: Solver,
    tag: ConstraintTag,
    vars: Vec<DomainId>,
    /// One Pumpkin literal per model Boolean.
    lits: Vec<Literal>,
    truth: Literal,
    /// Building stops (and the engine is not made) past this instant.
    /// The deadline and the cancel flag (the node limit is not used here).
    stop: Limits,
}

impl<'m> Builder<'m> {
    /// Whether the deadline has passed (checked between the steps and
    /// every few thousand definitions: posting a large model can take
    /// longer than the whole time limit).
    fn late(&self) -> bool {
        self.stop.expired()
    }

    /// The solver with one integer variable per grid variable.
    fn new(model: &'m Model, seed: u64) -> Result<Self, SynthError> {
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
            stop: Limits::default(),
        })
    }

    /// A model literal as a Pumpkin literal.
    fn lit(&self, l: Lit) -> Literal {
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
    fn create_literals(&mut self) -> Result<(), SynthError> {
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
    fn create_guards(&mut self, guarded: bool) -> Vec<Literal> {
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
    fn create_cumulative_starts(&mut self) -> Result<Vec<Vec<AffineView<DomainId>>>, SynthError> {
        let model = self.model;
        let grid = i32_of(model.grid, || "grid".into())?;
        let mut all = Vec::with_capacity(model.cumulative.len());
        for cu in &model.cumulative {
            let mut starts = Vec::with_capacity(cu.tasks.len());
            let shift = model.cumulative_shift(cu);
            for &(o, _, _) in &cu.tasks {
                let (cx, cy) = model.coords[o];
                let (c, origin) = match cu.axis {
                    super::model::Axis::X => (cx, model.origin.0),
                    super::model::Axis::Y => (cy, model.origin.1),
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
    fn create_objective(&mut self, coefs: Option<&[i64]>) -> Result<Option<DomainId>, SynthError> {
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
    fn post_definitions(&mut self) -> Result<(), SynthError> {
        let model = self.model;
        let tag = self.tag;
        for (i, def) in model.bools.iter().enumerate() {
            if i % 4096 == 4095 && self.late() {
                return Ok(());
            }
            let l = self.lits[i];
            match def {
                BoolDef::Ge { .. } => {}
                BoolDef::DiffGe { a, b, k } => {
                    // a − b ≥ k  ⇔  b − a ≤ −k
                    let rhs = i32_of(k.saturating_neg(), || "a distance bound".into())?;
                    let terms = vec![self.vars[*b].scaled(1), self.vars[*a].scaled(-1)];
                    self.solver
                        .add_constraint(less_than_or_equals(terms, rhs, tag))
                        .reify(l);
                }
                BoolDef::And(children) => {
                    let cs: Vec<Literal> = children.iter().map(|&c| self.lit(c)).collect();
                    for &c in &cs {
                        self.solver
                            .add_clause([(!l).get_true_predicate(), c.get_true_predicate()], tag);
                    }
                    let mut big: Vec<Predicate> = vec![l.get_true_predicate()];
                    big.extend(cs.iter().map(|c| (!*c).get_true_predicate()));
                    self.solver.add_clause(big, tag);
                }
                BoolDef::AtLeast { lits: counted, k } => {
                    // l ⇔ Σ counted ≥ k  ⇔  Σ −[counted] ≤ −k. A literal
                    // counted m times is one term with coefficient −m (the
                    // model keeps one polarity per Boolean), so no solver
                    // variable appears twice in the sum.
                    let terms: Vec<AffineView<DomainId>> = counted
                        .chunk_by(|a, b| a == b)
                        .map(|g| {
                            // (counts fit: at most one term per object)
                            let m = i32::try_from(g.len()).unwrap_or(i32::MAX);
                            self.lit(g[0]).get_integer_variable().scaled(-m)
                        })
                        .collect();
                    let rhs = i32_of(-i64::from(*k), || "a count bound".into())?;
                    self.solver
                        .add_constraint(less_than_or_equals(terms, rhs, tag))
                        .reify(l);
                }
                BoolDef::Connected { nodes, edges } => {
                    let args = connected::ConnectedArgs {
                        out: l,
                        nodes: *nodes as usize,
                        edges: edges
                            .iter()
                            .map(|&(a, b, e)| (a as usize, b as usize, self.lit(e)))
                            .collect(),
                        tag,
                    };
                    // A root failure surfaces as "infeasible" at the first
                    // solve, as for the other propagators.
                    let _ = self.solver.add_propagator(args);
                }
            }
        }
        Ok(())
    }

    /// Non-overlap of every pair with a variable object: one propagator
    /// (see `no_overlap`).
    fn post_no_overlap(&mut self) -> Result<(), SynthError> {
        let model = self.model;
        if model.pairwise_no_overlap || model.vars.is_empty() || model.coords.len() < 2 {
            return Ok(());
        }
        let pos = |c: Coord| match c {
            Coord::Var(v) => no_overlap::Pos::Var(self.vars[v]),
            Coord::Const(x) => no_overlap::Pos::Const(x),
        };
        let args = no_overlap::NoOverlapArgs {
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
    fn post_clauses(&mut self) {
        for c in &self.model.clauses {
            let c: Vec<Predicate> = c
                .iter()
                .map(|&l| self.lit(l).get_true_predicate())
                .collect();
            self.solver.add_clause(c, self.tag);
        }
    }

    /// Every hard literal, as a unit or under its rule's guard.
    fn post_hard(&mut self, guards: &[Literal]) {
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
    fn post_symmetry(&mut self) -> Result<(), SynthError> {
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
    fn post_cumulative(
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
    fn post_objective(
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
    fn finish(
        self,
        guards: Vec<Literal>,
        objective: Option<(DomainId, Vec<i64>)>,
        like_total: Option<DomainId>,
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
            like_total,
            pending_like: None,
            dead: false,
        }
    }
}

impl Engine {
    /// Post `model`. With `guarded`, every hard rule `r` is enforced only
    /// under its assumption literal (for core extraction); otherwise hard
    /// literals are posted as units. `coefs` are the objective coefficients
    /// of `model.soft` (none: no objective).
    ///
    /// Every number handed to Pumpkin goes through a checked conversion to
    /// `i32`; one that does not fit is a [`SynthError::TooLarge`] naming it
    /// (see [`super::MAX_COORD`] for why that cannot happen on a problem
    /// that passed the range check).
    pub fn new(
        model: &Model,
        seed: u64,
        guarded: bool,
        coefs: Option<&[i64]>,
    ) -> Result<Engine, SynthError> {
        Self::with_like(model, seed, guarded, coefs, &[])
    }

    /// [`Engine::new`] with the resemblance terms of the second objective
    /// (none: no second objective). Each term's cost is a variable bounded
    /// below by its distance map (see `post_like`); the total is one
    /// variable. Costs that do not fit `i32` ([`like_fits`]) are a
    /// [`SynthError::TooLarge`].
    pub fn with_like(
        model: &Model,
        seed: u64,
        guarded: bool,
        coefs: Option<&[i64]>,
        like: &[LikeTerm],
    ) -> Result<Engine, SynthError> {
        let e = Self::with_like_until(model, seed, guarded, coefs, like, None)?;
        Ok(e.expect("no deadline"))
    }

    /// [`Engine::with_like`], given up (`None`) once `deadline` passes:
    /// posting a large model can take longer than the solve's time limit.
    pub fn with_like_until(
        model: &Model,
        seed: u64,
        guarded: bool,
        coefs: Option<&[i64]>,
        like: &[LikeTerm],
        deadline: Option<std::time::Instant>,
    ) -> Result<Option<Engine>, SynthError> {
        let stop = Limits {
            deadline,
            ..Limits::default()
        };
        Self::with_like_stop(model, seed, guarded, coefs, like, &stop)
    }

    /// [`Engine::with_like_until`] that also gives up when `stop`'s cancel
    /// flag is set (Ctrl-C while a large model is posted).
    pub fn with_like_stop(
        model: &Model,
        seed: u64,
        guarded: bool,
        coefs: Option<&[i64]>,
        like: &[LikeTerm],
        stop: &Limits,
    ) -> Result<Option<Engine>, SynthError> {
        check_ranges(model, like)?;
        let mut b = Builder::new(model, seed)?;
        b.stop = Limits {
            deadline: stop.deadline,
            node_limit: None,
            cancel: stop.cancel.clone(),
        };
        // Every variable and literal first ...
        b.create_literals()?;
        let guards = b.create_guards(guarded);
        let starts = b.create_cumulative_starts()?;
        let obj = b.create_objective(coefs)?;
        if b.late() {
            return Ok(None);
        }
        // ... then every constraint.
        b.post_definitions()?;
        if b.late() {
            return Ok(None);
        }
        b.post_clauses();
        b.post_no_overlap()?;
        b.post_hard(&guards);
        b.post_symmetry()?;
        b.post_cumulative(starts)?;
        if b.late() {
            return Ok(None);
        }
        let objective = b.post_objective(coefs, obj)?;
        // The second objective waits for the second phase (see `like`).
        let pending = PendingLike::new(model, like);
        let mut engine = b.finish(guards, objective, None);
        engine.pending_like = pending;
        Ok(Some(engine))
    }

    /// The objective's coefficients, variable terms only, in
    /// [`Model::soft`] order (none: no objective).
    pub fn objective_coefs(&self) -> Option<&[i64]> {
        self.objective.as_ref().map(|(_, c)| c.as_slice())
    }

    /// Decisions so far.
    pub fn nodes(&self) -> u64 {
        self.counters.nodes.get()
    }

    /// Conflicts so far.
    pub fn conflicts(&self) -> u64 {
        self.counters.conflicts.get()
    }

    fn stop(&self, limits: &Limits) -> Stop {
        // Every call starts at the root.
        self.counters.safe.set(false);
        Stop {
            limits: limits.clone(),
            nodes: self.counters.nodes.clone(),
            safe: self.counters.safe.clone(),
            fired: Rc::new(Cell::new(false)),
        }
    }

    fn values(vars: &[DomainId], s: &impl ProblemSolution) -> Vec<i64> {
        vars.iter()
            .map(|&v| s.get_integer_value(v) as i64)
            .collect()
    }

    /// Find any solution.
    pub fn satisfy(&mut self, limits: &Limits) -> Sat {
        self.solve(&[], limits).into()
    }

    /// Solve with the guards of the hard rules in `rules` (indices into
    /// `Model::hard`) assumed true.
    pub fn satisfy_rules(&mut self, rules: &[usize], limits: &Limits) -> Sat {
        let a: Vec<Assumption> = rules.iter().map(|&r| Assumption::Rule(r)).collect();
        self.solve(&a, limits).into()
    }

    /// A Pumpkin call under `assumptions` (none: a plain `satisfy`).
    ///
    /// An infeasible call under assumptions carries no core: Pumpkin 0.5's
    /// `extract_core` can panic (`ConstraintTag::create_from_index`) or run
    /// for minutes without checking the termination condition on infeasible
    /// probe problems of the bundled example
    /// (`tests/fixtures/regressions/core-hang.rcc`), so the driver shrinks
    /// conflicts by deletion, where every solve obeys the limits.
    fn call(&mut self, assumptions: &[Predicate], limits: &Limits) -> Verdict {
        if self.dead {
            return Verdict::Infeasible(Core::Rules(Vec::new()));
        }
        let mut stop = self.stop(limits);
        let vars = self.vars.clone();
        let answer = if assumptions.is_empty() {
            match self
                .solver
                .satisfy(&mut self.brancher, &mut stop, &mut self.resolver)
            {
                SatisfactionResult::Satisfiable(s) => {
                    Verdict::Solution(Self::values(&vars, &s.solution()))
                }
                SatisfactionResult::Unsatisfiable(..) => {
                    self.dead = true;
                    Verdict::Infeasible(Core::Rules(Vec::new()))
                }
                SatisfactionResult::Unknown(..) => Verdict::Unknown,
            }
        } else {
            match self.solver.satisfy_under_assumptions(
                &mut self.brancher,
                &mut stop,
                &mut self.resolver,
                assumptions,
            ) {
                SatisfactionResultUnderAssumptions::Satisfiable(s) => {
                    Verdict::Solution(Self::values(&vars, &s.solution()))
                }
                SatisfactionResultUnderAssumptions::UnsatisfiableUnderAssumptions(_) => {
                    Verdict::Infeasible(Core::Unknown)
                }
                SatisfactionResultUnderAssumptions::Unsatisfiable(_) => {
                    self.dead = true;
                    Verdict::Infeasible(Core::Rules(Vec::new()))
                }
                SatisfactionResultUnderAssumptions::Unknown(_) => Verdict::Unknown,
            }
        };
        answer
    }
}

impl Engine {
    /// Exclude the assignment `values` (one per model variable) from every
    /// later call: the clause "some variable takes another value". Used by
    /// `crate::sample` to draw distinct layouts. With no variable, the model
    /// has one assignment, so every later call is infeasible.
    pub(crate) fn exclude(&mut self, values: &[i64]) {
        if self.dead {
            return;
        }
        if self.vars.is_empty() {
            self.dead = true;
            return;
        }
        let clause: Vec<Predicate> = self
            .vars
            .iter()
            .zip(values)
            .map(|(&v, &x)| predicate![v != clamp_i32(x)])
            .collect();
        self.solver.add_clause(clause, self.tag);
    }

    /// Leave the greedy first phase after `conflicts` conflicts without a
    /// solution, for the learning brancher (which branches on the rules'
    /// Booleans too). For engines that mostly prove infeasibility — `ask`'s
    /// implication checks —, where enumerating coordinates greedily can
    /// take thousands of times longer; synthesis keeps the greedy phase
    /// until its first layout (it finds one sooner on hard feasible
    /// problems).
    pub(crate) fn leave_greedy_after(&mut self, conflicts: u64) {
        self.brancher.inner.first_cap = Some(conflicts);
    }

    /// After the hint, search at random instead of by activity: a random
    /// unfixed grid variable, a random value of its domain (the solver's
    /// seeded generator); conflicts are learned as usual. Every Boolean of
    /// the model is defined by the grid variables, so branching on them
    /// alone is complete. Used by `crate::sample`.
    pub(crate) fn random_search(&mut self) {
        self.brancher.inner.main = Box::new(IndependentVariableValueBrancher::new(
            RandomSelector::new(self.vars.iter().copied()),
            InDomainRandom,
        ));
    }

    /// Try `hints` (pairs of a model variable and a value) first, in this
    /// order, until the next solution: [`Backend::hint`] with the order
    /// chosen by the caller (`crate::sample` draws it at random).
    pub(crate) fn hint_in_order(&mut self, hints: &[(usize, i64)]) {
        // `WarmStart` tries its list from the back.
        let (vars, vals): (Vec<DomainId>, Vec<i32>) = hints
            .iter()
            .rev()
            .filter_map(|&(v, x)| Some((*self.vars.get(v)?, i32::try_from(x).ok()?)))
            .unzip();
        self.brancher.inner.hint = (!vars.is_empty()).then(|| WarmStart::new(&vars, &vals));
    }
}

impl Backend for Engine {
    /// `Rule(r)` on an engine built without guards is a no-op (its rule is
    /// posted as units); `ObjectiveAtLeast(k)` without an objective holds
    /// iff `k ≤ 0`, `CostAtMost` without a second objective always holds.
    fn solve(&mut self, assumptions: &[Assumption], limits: &Limits) -> Verdict {
        if assumptions
            .iter()
            .any(|a| matches!(a, Assumption::CostAtMost(_)))
        {
            self.start_cost_phase();
        }
        let mut preds: Vec<Predicate> = Vec::with_capacity(assumptions.len());
        for a in assumptions {
            match *a {
                Assumption::ObjectiveAtLeast(k) => match &self.objective {
                    Some((obj, _)) => {
                        let obj = *obj;
                        preds.push(predicate![obj >= clamp_i32(k)]);
                    }
                    None if k <= 0 => {}
                    None => return Verdict::Infeasible(Core::Unknown),
                },
                Assumption::CostAtMost(k) => {
                    if let Some(total) = self.like_total {
                        let k = i32::try_from(k).unwrap_or(i32::MAX);
                        preds.push(predicate![total <= k]);
                    }
                }
                Assumption::Rule(r) => {
                    if let Some(g) = self.guards.get(r) {
                        preds.push(g.get_true_predicate());
                    }
                }
            }
        }
        self.call(&preds, limits)
    }

    fn add(&mut self, fact: Fact) {
        if self.dead {
            return;
        }
        if let Fact::CostAtLeast(_) = fact {
            self.start_cost_phase();
        }
        let p = match fact {
            Fact::ObjectiveAtMost(k) => self
                .objective
                .as_ref()
                .map(|&(obj, _)| predicate![obj <= clamp_i32(k)]),
            Fact::ObjectiveAtLeast(k) => self
                .objective
                .as_ref()
                .map(|&(obj, _)| predicate![obj >= clamp_i32(k)]),
            Fact::CostAtLeast(k) => self
                .like_total
                .map(|total| predicate![total >= i32::try_from(k).unwrap_or(i32::MAX)]),
        };
        if let Some(p) = p {
            self.solver.add_clause([p], self.tag);
        }
    }

    fn objective_bound(&self) -> Option<i64> {
        self.objective
            .as_ref()
            .map(|(obj, _)| i64::from(self.solver.upper_bound(obj)))
    }

    fn start_cost_phase(&mut self) {
        if self.dead {
            return;
        }
        if let Some(pending) = self.pending_like.take() {
            let posted = pending.post(&mut self.solver, &self.vars, self.tag);
            self.brancher.inner.add_late(&posted.created);
            self.like_total = Some(posted.total);
        }
    }

    fn cost_bound(&self) -> Option<u64> {
        match (&self.pending_like, self.like_total) {
            (Some(p), _) => Some(p.min_total()),
            (None, Some(t)) => Some(u64::try_from(self.solver.lower_bound(&t)).unwrap_or(0)),
            (None, None) => None,
        }
    }

    fn found_first(&mut self) {
        self.first_phase.set(false);
    }

    fn hint(&mut self, values: &[Option<i64>]) {
        let (vars, vals): (Vec<DomainId>, Vec<i32>) = self
            .vars
            .iter()
            .zip(values)
            .filter_map(|(&v, h)| Some((v, i32::try_from((*h)?).ok()?)))
            .unzip();
        self.brancher.inner.hint = (!vars.is_empty()).then(|| WarmStart::new(&vars, &vals));
    }

    fn nodes(&self) -> u64 {
        self.counters.nodes.get()
    }
}

/// Whether the resemblance terms' costs fit the engine's `i32` arithmetic
/// (every cost, every index and the total).
pub fn like_fits(terms: &[LikeTerm]) -> bool {
    let max = i32::MAX as u64;
    let mut total = 0u64;
    for t in terms {
        let hi = t.map.cost.iter().copied().max().unwrap_or(0);
        total = total.saturating_add(hi);
        if hi > max || t.map.cost.len() as u64 > max || t.map.nx > max {
            return false;
        }
    }
    total <= max
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The resemblance encodings — clauses, the bounds propagator, both —
    /// each reach brute force's lexicographic optimum (numerator, then
    /// cost) on small problems with random like-scenes, and prove it.
    #[test]
    fn like_encodings_agree_with_brute_force() {
        use crate::resemblance::Likeness;
        use crate::synth::{brute_force, synthesize, SynthOptions};
        let problem = Scene::from_json(
            r#"{"space":{"x":0,"y":0,"width":50,"height":40},"grid":10,"objects":[
              {"id":"a1","class":"A","width":10,"height":10},
              {"id":"a2","class":"A","width":10,"height":10},
              {"id":"b","class":"B","width":20,"height":10},
              {"id":"w","class":"W","x":0,"y":0,"width":10,"height":20,"fixed":true}]}"#,
        )
        .unwrap();
        let rules = crate::rules::parse_rules(
            "rule near: EC_E(A, B) | EC_W(A, B) | EC_N(A, B)\nrule wall: DR_E(B, W)\n",
        )
        .unwrap();
        let mut rng = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = |n: u64| {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng % n) as i64
        };
        let mut checked = 0;
        for case in 0..60 {
            let scenes: Vec<Scene> = (0..1 + next(2))
                .map(|_| {
                    let a = |i: u32, next: &mut dyn FnMut(u64) -> i64| {
                        format!(
                            r#"{{"id":"a{i}","class":"A","x":{},"y":{},"width":10,"height":10}}"#,
                            next(5) * 10 - next(3),
                            next(4) * 10
                        )
                    };
                    let objs = [
                        a(1, &mut next),
                        a(2, &mut next),
                        format!(
                            r#"{{"id":"b","class":"B","x":{},"y":{},"width":20,"height":10}}"#,
                            next(4) * 10,
                            next(4) * 10
                        ),
                    ];
                    Scene::from_json(&format!(
                        r#"{{"space":{{"x":0,"y":0,"width":50,"height":40}},"grid":10,"objects":[{}]}}"#,
                        objs.join(",")
                    ))
                })
                // Overlapping draws are not scenes: drawn again below.
                .filter_map(Result::ok)
                .collect();
            if scenes.is_empty() {
                continue;
            }
            checked += 1;
            let like = Likeness::new(&scenes);
            let bf = brute_force::solve_like(&problem, &rules, Contact::Point, &like, 10_000_000)
                .unwrap();
            for enc in [
                LikeEncoding::Clauses,
                LikeEncoding::Propagator,
                LikeEncoding::Both,
            ] {
                LIKE_ENCODING.with(|e| e.set(enc));
                let r = synthesize(
                    &problem,
                    &rules,
                    &SynthOptions {
                        like: Some(like.clone()),
                        ..SynthOptions::default()
                    },
                )
                .unwrap();
                LIKE_ENCODING.with(|e| e.set(LikeEncoding::Both));
                let res = r.resemblance.expect("a resemblance");
                let ev = r.evaluation.expect("an evaluation");
                assert!(res.proven, "case {case}, {enc:?}: cost not proven");
                assert_eq!(res.cost, bf.best_cost, "case {case}, {enc:?}");
                assert!(
                    (ev.satisfied_weight - bf.best_numerator).abs() < 1e-9,
                    "case {case}, {enc:?}"
                );
            }
        }
        assert!(checked >= 30, "only {checked} cases had like-scenes");
    }

    use crate::relations::{Contact, Dir, Kind, Quant, Relation};
    use crate::rules::{Atom, Formula, Rule, RuleSet, Scope, Target};
    use crate::scene::{Object, Scene, Space};
    use crate::synth::model::{BuildOptions, HardRule};

    /// Every literal of every soft term (reified counts among them), made
    /// hard under one guard in either polarity: the engine finds a solution
    /// iff some layout satisfies it (enumerated over the definitions), the
    /// solution does satisfy it, and a refutation's core is that guard. So
    /// the `AtLeast` encoding (and every other) is exact under assumptions.
    #[test]
    fn guarded_literals_match_the_definitions() {
        literals_match_the_definitions(true);
    }

    /// The same with non-overlap as the engine's propagator instead of one
    /// clause per pair (what models past `PAIRWISE_NO_OVERLAP_PAIRS` get):
    /// the same layouts are possible and impossible.
    #[test]
    fn the_no_overlap_propagator_matches_the_clauses() {
        literals_match_the_definitions(false);
    }

    fn literals_match_the_definitions(pairwise: bool) {
        let scene = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 30,
                height: 20,
            },
            grid: 10,
            objects: (0..4)
                .map(|i| Object {
                    id: format!("a{i}"),
                    class: "A".into(),
                    x: None,
                    y: None,
                    width: 10,
                    height: 10,
                    fixed: false,
                })
                .chain([Object::fixed_at("f", "F", 20, 10, 10, 10)])
                .collect(),
        };
        let q =
            |rel: Relation, quant, t: Target| Formula::Atom(Atom::quantified(rel, "A", quant, t));
        let al_s = Relation::new(Kind::AL, Dir::S);
        let ec_e = Relation::new(Kind::EC, Dir::E);
        let dr_n = Relation::new(Kind::DR, Dir::N);
        let rules = RuleSet::new(vec![
            Rule::new("r0", q(al_s, Quant::AtLeast(2), Target::Any)),
            Rule::new("r1", q(ec_e, Quant::AtMost(1), Target::Any)),
            Rule::new("r2", q(dr_n, Quant::Some, Target::Any))
                .with_scope(Scope::Scene(Quant::AtLeast(2))),
            Rule::new("r3", q(al_s, Quant::AtLeast(2), Target::Class("A".into())))
                .with_scope(Scope::Scene(Quant::AtMost(2))),
            // Impossible: the four A cannot all share their row with two
            // other objects (3 + 1 leaves one alone with `f`, 2 + 2 leaves
            // each of the bottom two with one).
            Rule::new("r4", q(al_s, Quant::AtLeast(2), Target::Any))
                .with_scope(Scope::Scene(Quant::AtLeast(4))),
            Rule::new("r5", q(al_s, Quant::AtLeast(2), Target::Any))
                .with_scope(Scope::Scene(Quant::AtLeast(3))),
        ]);
        let m = Model::build_encoded(
            &scene,
            &rules,
            BuildOptions {
                contact: Contact::Point,
                rules: true,
                symmetry_breaking: false,
                redundant: false,
            },
            &|| false,
            crate::synth::model::Encoding {
                pairwise: Some(pairwise),
                connectivity: crate::synth::model::Connectivity::Propagator,
            },
        )
        .expect("never stopped");
        assert_eq!(m.pairwise_no_overlap, pairwise);
        let counts = m
            .bools
            .iter()
            .filter(|b| matches!(b, BoolDef::AtLeast { .. }))
            .count();
        assert!(counts >= 4, "{counts} reified counts");
        // Every assignment: the clause values and the bools.
        let ub: Vec<i64> = m.vars.iter().map(|v| v.ub).collect();
        let mut all: Vec<(Vec<i64>, Vec<bool>)> = Vec::new();
        let mut vals = vec![0i64; ub.len()];
        'outer: loop {
            let bools = m.eval_bools(&vals);
            if m.clauses.iter().all(|c| c.iter().any(|l| l.value(&bools)))
                && m.non_overlapping(&vals)
            {
                all.push((vals.clone(), bools));
            }
            let mut i = 0;
            loop {
                if i == vals.len() {
                    break 'outer;
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
        let mut sat = 0;
        let mut unsat = 0;
        for t in &m.soft {
            for lit in [t.lit, !t.lit] {
                let mut mh = m.clone();
                mh.soft.clear();
                mh.hard = vec![HardRule {
                    rule: 0,
                    lits: vec![lit],
                }];
                let possible = all.iter().any(|(_, b)| lit.value(b));
                let mut e = Engine::new(&mh, 0, true, None).unwrap();
                match e.satisfy_rules(&[0], &Limits::default()) {
                    Sat::Solution(v) => {
                        assert!(possible, "engine found {v:?} for the impossible {lit:?}");
                        let b = m.eval_bools(&v);
                        assert!(lit.value(&b), "{lit:?} false in the engine's {v:?}");
                        assert!(m.clauses.iter().all(|c| c.iter().any(|l| l.value(&b))));
                        assert!(m.non_overlapping(&v), "{v:?} overlaps");
                        sat += 1;
                    }
                    Sat::Unsat => {
                        assert!(!possible, "engine refuted the possible {lit:?}");
                        unsat += 1;
                    }
                    Sat::Unknown => panic!("no limit, yet unknown"),
                }
            }
        }
        assert!(sat > 0 && unsat > 0, "{sat} sat, {unsat} unsat");
    }
}
