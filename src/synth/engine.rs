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
//! [`Strategy::UpperBoundFirst`] (the default, chosen by measurement) finds a
//! first solution, then asks twice for `obj ≥ hi` with `hi` the largest
//! objective value the coefficients can reach below the proven bound (a
//! refutation adds `obj ≤ hi − 1` and steps `hi` down to the next reachable
//! subset sum); after that it bisects between the incumbent and the bound.
//! Pure stepping was slow on real-valued weights with many reachable sums
//! (max 800 ms on the study set); pure bisection was 10× slower on the
//! near-satisfiable 24-object problem. [`Strategy::ImproveFromFirst`] adds
//! `obj ≥ best + 1` after each solution until the solver refutes it.
//!
//! Pumpkin's `LinearUnsatSat` is not used: its final callback reports the
//! first solution, and it steps the bound by one unit, which is hopeless for
//! scaled real weights.

use super::like::{total_cost, LikeTerm};
use super::model::{BoolDef, Coord, Lit, Model};
use super::weights::SubsetSums;
use super::SynthError;
use pumpkin_conflict_resolvers::resolvers::ResolutionResolver;
use pumpkin_constraints::{boolean_equals, cumulative, equals, less_than_or_equals};
use pumpkin_core::branching::branchers::independent_variable_value_brancher::IndependentVariableValueBrancher;
use pumpkin_core::branching::tie_breaking::InOrderTieBreaker;
use pumpkin_core::branching::value_selection::InDomainMin;
use pumpkin_core::branching::variable_selection::FirstFail;
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
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

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

/// How many times [`Strategy::UpperBoundFirst`] asks for the proven upper
/// bound itself before it bisects between incumbent and bound.
const UPPER_BOUND_PROBES: u32 = 2;

/// How to optimise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Strategy {
    /// First solution, then `obj ≥ hi` stepping down from the upper bound.
    #[default]
    UpperBoundFirst,
    /// First solution, then `obj ≥ best + 1` until refuted.
    ImproveFromFirst,
}

/// When to stop.
#[derive(Debug, Clone, Default)]
pub struct Limits {
    /// Wall-clock deadline.
    pub deadline: Option<Instant>,
    /// Maximum number of decisions (over the whole engine's life).
    pub node_limit: Option<u64>,
    /// External stop flag.
    pub cancel: Option<Arc<AtomicBool>>,
}

#[derive(Debug, Clone, Default)]
struct Counters {
    nodes: Rc<Cell<u64>>,
    conflicts: Rc<Cell<u64>>,
}

/// Polled by Pumpkin; stops on deadline, node limit or cancel flag.
struct Stop {
    limits: Limits,
    nodes: Rc<Cell<u64>>,
    fired: Rc<Cell<bool>>,
}

impl TerminationCondition for Stop {
    fn should_stop(&mut self) -> bool {
        let stop = self
            .limits
            .node_limit
            .is_some_and(|n| self.nodes.get() >= n)
            || self
                .limits
                .cancel
                .as_ref()
                .is_some_and(|c| c.load(Ordering::Relaxed))
            || self.limits.deadline.is_some_and(|d| Instant::now() >= d);
        if stop {
            self.fired.set(true);
        }
        stop
    }
}

/// A brancher wrapper that counts decisions and conflicts.
#[derive(Debug)]
pub struct Counting {
    inner: Box<dyn Brancher>,
    nodes: Rc<Cell<u64>>,
    conflicts: Rc<Cell<u64>>,
}

impl Brancher for Counting {
    fn log_statistics(&self, l: StatisticLogger) {
        self.inner.log_statistics(l)
    }
    fn next_decision(&mut self, context: &mut SelectionContext) -> Option<Predicate> {
        let d = self.inner.next_decision(context);
        if d.is_some() {
            self.nodes.set(self.nodes.get() + 1);
        }
        d
    }
    fn on_conflict(&mut self) {
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
#[derive(Debug)]
struct Phased {
    first: StaticBrancher,
    main: Box<dyn Brancher>,
    use_first: Rc<Cell<bool>>,
}

impl Brancher for Phased {
    fn next_decision(&mut self, context: &mut SelectionContext) -> Option<Predicate> {
        if self.use_first.get() {
            if let Some(d) = self.first.next_decision(context) {
                return Some(d);
            }
        }
        self.main.next_decision(context)
    }
    fn on_conflict(&mut self) {
        self.main.on_conflict()
    }
    fn on_backtrack(&mut self) {
        self.main.on_backtrack()
    }
    fn on_solution(&mut self, solution: SolutionReference) {
        self.main.on_solution(solution)
    }
    fn on_unassign_integer(&mut self, variable: DomainId, value: i32) {
        self.first.on_unassign_integer(variable, value);
        self.main.on_unassign_integer(variable, value)
    }
    fn on_appearance_in_conflict_predicate(&mut self, predicate: Predicate) {
        self.main.on_appearance_in_conflict_predicate(predicate)
    }
    fn on_restart(&mut self) {
        self.main.on_restart()
    }
    fn synchronise(&mut self, context: &mut SelectionContext) {
        self.first.synchronise(context);
        self.main.synchronise(context)
    }
    fn is_restart_pointless(&mut self) -> bool {
        self.main.is_restart_pointless()
    }
    fn subscribe_to_events(&self) -> Vec<BrancherEvent> {
        let mut v = self.main.subscribe_to_events();
        for e in self.first.subscribe_to_events() {
            if !v.contains(&e) {
                v.push(e);
            }
        }
        v
    }
}

/// The result of one satisfiability call.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Sat {
    /// A solution: grid values per model variable.
    Solution(Vec<i64>),
    /// Proved impossible (under the assumptions, when there are any).
    Unsat,
    /// A limit stopped the search.
    Unknown,
}

/// How an optimisation ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum OptOutcome {
    /// Proved optimal.
    Optimal(Vec<i64>),
    /// Best found before a limit.
    Feasible(Vec<i64>),
    /// No solution exists.
    Infeasible,
    /// A limit stopped the search before any solution.
    Unknown,
}

/// A Pumpkin solver holding one model.
pub struct Engine {
    solver: Solver,
    brancher: Counting,
    resolver: ResolutionResolver,
    vars: Vec<DomainId>,
    guards: Vec<Literal>,
    objective: Option<(DomainId, Vec<i64>)>,
    counters: Counters,
    tag: ConstraintTag,
    first_phase: Rc<Cell<bool>>,
    /// The resemblance terms and the total-cost variable (SPEC §12).
    like: Option<(Vec<LikeTerm>, DomainId)>,
    /// Proved infeasible whatever the assumptions: Pumpkin's solver must not
    /// be called again (it asserts), and every later call is `Unsat`.
    dead: bool,
    /// A limit stopped a solve: Pumpkin 0.5 asserts when solving again after
    /// a timeout, so every later call is `Unknown` (the limits are over the
    /// engine's life anyway). Make a new engine to go on.
    spent: bool,
}

/// How the second phase ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CostOutcome {
    /// The layout to return: the numerator is at least the first phase's.
    pub values: Vec<i64>,
    /// Its resemblance cost.
    pub cost: u64,
    /// Whether the cost is proven minimal among layouts with at least its
    /// numerator.
    pub proven: bool,
}

impl std::fmt::Debug for Engine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Engine")
            .field("vars", &self.vars.len())
            .finish()
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
        Self::with_like(model, seed, guarded, coefs, Vec::new())
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
        like: Vec<LikeTerm>,
    ) -> Result<Engine, SynthError> {
        let obj_name = |o: usize| format!("objects[{o}]");
        // Range-check everything before the solver exists.
        for v in &model.vars {
            i32_of(v.ub, || {
                format!("the position range of {}", obj_name(v.object))
            })?;
        }
        for s in &model.symmetry {
            if !model.lin_fits_i32(s) {
                return Err(SynthError::TooLarge(
                    "a symmetry-breaking order is too large for the solver's 32-bit arithmetic"
                        .into(),
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
        if !like_fits(&like) {
            return Err(SynthError::TooLarge(
                "resemblance costs are too large for the solver's 32-bit arithmetic".into(),
            ));
        }
        let grid = i32_of(model.grid, || "grid".into())?;
        // The origin fits in 32 bits (every coordinate the engine sees is
        // one of its offsets).
        i32_of(model.origin.0, || "space.x".into())?;
        i32_of(model.origin.1, || "space.y".into())?;
        let mut solver = Solver::with_options(SolverOptions {
            random_generator: SmallRng::seed_from_u64(seed),
            memory_preallocated: 1,
            ..Default::default()
        });
        let tag = solver.new_constraint_tag();
        let vars: Vec<DomainId> = model
            .vars
            .iter()
            .map(|v| i32_of(v.ub, String::new).map(|ub| solver.new_bounded_integer(0, ub)))
            .collect::<Result<_, _>>()?;
        let t = solver.get_true_literal();
        let tb = Instant::now();
        let mut lits: Vec<Literal> = Vec::with_capacity(model.bools.len());
        let conv = |lits: &[Literal], l: Lit| -> Literal {
            match l {
                Lit::Const(true) => t,
                Lit::Const(false) => !t,
                Lit::Var { id, neg } => {
                    let x = lits[id as usize];
                    if neg {
                        !x
                    } else {
                        x
                    }
                }
            }
        };
        let mut tcat = [0f64; 3];
        // Pumpkin panics when a variable is created after a post made the
        // root inconsistent (e.g. objects that cannot fit at all). So create
        // every literal and variable first, and post constraints after.
        for def in &model.bools {
            lits.push(match def {
                BoolDef::Ge { var, k } => {
                    let x = vars[*var];
                    let k = i32_of(*k, || "a position bound".into())?;
                    solver.new_literal_for_predicate(predicate![x >= k], tag)
                }
                BoolDef::DiffGe { .. } | BoolDef::And(_) | BoolDef::AtLeast { .. } => {
                    solver.new_literal()
                }
            });
        }
        let guard_lits: Vec<Literal> = if guarded {
            model.hard.iter().map(|_| solver.new_literal()).collect()
        } else {
            Vec::new()
        };
        let mut cumulative_starts: Vec<Vec<AffineView<DomainId>>> = Vec::new();
        for cu in &model.cumulative {
            let mut starts = Vec::with_capacity(cu.tasks.len());
            // Every start at least 0 (see `Model::cumulative_shift`).
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
                            format!("the position of {}", obj_name(o))
                        })?;
                        solver.new_bounded_integer(v, v).scaled(1)
                    }
                    Coord::Var(v) => vars[v]
                        .scaled(grid)
                        .offset(i32_of(origin.saturating_add(shift), || {
                            "the space's origin".into()
                        })?),
                });
            }
            cumulative_starts.push(starts);
        }
        // Resemblance variables: per term a cost variable, bounded below by
        // clauses over the position (see `post_like`).
        let like_costs: Vec<DomainId> = like
            .iter()
            .map(|t| {
                let (lo, hi) = (t.map.min(), t.map.cost.iter().copied().max().unwrap_or(0));
                solver.new_bounded_integer(lo as i32, hi as i32)
            })
            .collect();
        let like_total = (!like.is_empty()).then(|| {
            let lo: u64 = like.iter().map(|t| t.map.min()).sum();
            let hi: u64 = like
                .iter()
                .map(|t| t.map.cost.iter().copied().max().unwrap_or(0))
                .sum();
            solver.new_bounded_integer(lo as i32, hi as i32)
        });
        let objective_var = match coefs {
            None => None,
            Some(coefs) => {
                let total: i128 = model
                    .soft
                    .iter()
                    .zip(coefs)
                    .filter(|(s, _)| matches!(s.lit, Lit::Var { .. }))
                    .map(|(_, &c)| i128::from(c))
                    .sum();
                let total = i64::try_from(total).unwrap_or(i64::MAX);
                let total = i32_of(total, || "the total of the rule weights".into())?;
                Some(solver.new_bounded_integer(0, total))
            }
        };
        for (i, def) in model.bools.iter().enumerate() {
            let tt = Instant::now();
            let cat = match def {
                BoolDef::Ge { .. } => 0,
                BoolDef::DiffGe { .. } => 1,
                BoolDef::And(_) | BoolDef::AtLeast { .. } => 2,
            };
            let l = lits[i];
            match def {
                BoolDef::Ge { .. } => {}
                BoolDef::DiffGe { a, b, k } => {
                    // a − b ≥ k  ⇔  b − a ≤ −k
                    let rhs = i32_of(k.saturating_neg(), || "a distance bound".into())?;
                    solver
                        .add_constraint(less_than_or_equals(
                            vec![vars[*b].scaled(1), vars[*a].scaled(-1)],
                            rhs,
                            tag,
                        ))
                        .reify(l);
                }
                BoolDef::And(children) => {
                    let cs: Vec<Literal> = children.iter().map(|&c| conv(&lits, c)).collect();
                    for &c in &cs {
                        solver.add_clause([(!l).get_true_predicate(), c.get_true_predicate()], tag);
                    }
                    let mut big: Vec<Predicate> = vec![l.get_true_predicate()];
                    big.extend(cs.iter().map(|c| (!*c).get_true_predicate()));
                    solver.add_clause(big, tag);
                }
                BoolDef::AtLeast { lits: counted, k } => {
                    // l ⇔ Σ counted ≥ k  ⇔  Σ −[counted] ≤ −k. A literal
                    // counted m times is one term with coefficient −m (the
                    // model keeps one polarity per Boolean), so no solver
                    // variable appears twice in the sum.
                    let terms: Vec<AffineView<DomainId>> = counted
                        .chunk_by(|a, b| a == b)
                        .map(|g| {
                            let m = i32::try_from(g.len()).unwrap_or(i32::MAX);
                            // (counts fit: at most one term per object)
                            conv(&lits, g[0]).get_integer_variable().scaled(-m)
                        })
                        .collect();
                    solver
                        .add_constraint(less_than_or_equals(
                            terms,
                            i32_of(-i64::from(*k), || "a count bound".into())?,
                            tag,
                        ))
                        .reify(l);
                }
            }
            tcat[cat] += tt.elapsed().as_secs_f64() * 1e3;
        }
        let dbg = std::env::var_os("RCCPACK_DEBUG").is_some();
        let t0 = Instant::now();
        if dbg {
            let n_ge = model
                .bools
                .iter()
                .filter(|b| matches!(b, BoolDef::Ge { .. }))
                .count();
            let n_diff = model
                .bools
                .iter()
                .filter(|b| matches!(b, BoolDef::DiffGe { .. }))
                .count();
            eprintln!(
                "  bools: {n_ge} ge, {n_diff} diff, {} and",
                model.bools.len() - n_ge - n_diff
            );
        }
        if dbg {
            eprintln!(
                "  bools posted in {:.1} ms {tcat:?}",
                tb.elapsed().as_secs_f64() * 1e3
            );
        }
        for c in &model.clauses {
            let c: Vec<Predicate> = c
                .iter()
                .map(|&l| conv(&lits, l).get_true_predicate())
                .collect();
            solver.add_clause(c, tag);
        }
        let mut guards = Vec::new();
        for (i, h) in model.hard.iter().enumerate() {
            let g = guard_lits.get(i).copied();
            for &l in &h.lits {
                let mut c = vec![conv(&lits, l).get_true_predicate()];
                if let Some(g) = g {
                    c.push((!g).get_true_predicate());
                }
                solver.add_clause(c, tag);
            }
            if let Some(g) = g {
                guards.push(g);
            }
        }
        for s in &model.symmetry {
            let mut terms: Vec<AffineView<DomainId>> = Vec::with_capacity(s.terms.len());
            for &(c, v) in &s.terms {
                terms.push(vars[v].scaled(i32_of(c, || "a symmetry coefficient".into())?));
            }
            let rhs = i32_of(s.rhs, || "a symmetry bound".into())?;
            solver
                .add_constraint(less_than_or_equals(terms, rhs, tag))
                .post();
        }
        for (cu, starts) in model.cumulative.iter().zip(cumulative_starts) {
            let mut durs: Vec<i32> = Vec::with_capacity(cu.tasks.len());
            let mut dems: Vec<i32> = Vec::with_capacity(cu.tasks.len());
            for &(o, dur, dem) in &cu.tasks {
                durs.push(i32_of(dur, || format!("the size of {}", obj_name(o)))?);
                dems.push(i32_of(dem, || format!("the size of {}", obj_name(o)))?);
            }
            let capacity = i32_of(cu.capacity, || "the space size".into())?;
            solver
                .add_constraint(cumulative(starts, durs, dems, capacity, tag))
                .post();
        }
        if dbg {
            eprintln!(
                "  clauses+hard+sym+cumulative {:.1} ms",
                t0.elapsed().as_secs_f64() * 1e3
            );
        }
        let mut objective = None;
        if let (Some(coefs), Some(obj)) = (coefs, objective_var) {
            let mut ws = Vec::new();
            let mut ls = Vec::new();
            for (s, &c) in model.soft.iter().zip(coefs) {
                if let Lit::Var { .. } = s.lit {
                    ws.push(c);
                    ls.push(conv(&lits, s.lit));
                }
            }
            let mut ws32: Vec<i32> = Vec::with_capacity(ws.len());
            for &w in &ws {
                ws32.push(i32_of(w, || "a rule weight".into())?);
            }
            solver
                .add_constraint(boolean_equals(ws32, ls, obj, tag))
                .post();
            objective = Some((obj, ws));
        }
        if let Some(total) = like_total {
            let mut sum: Vec<AffineView<DomainId>> = Vec::with_capacity(like.len() + 1);
            for (t, &c) in like.iter().zip(&like_costs) {
                post_like(&mut solver, t, vars[t.x], vars[t.y], c, tag);
                sum.push(c.scaled(1));
            }
            sum.push(total.scaled(-1));
            solver.add_constraint(equals(sum, 0, tag)).post();
        }
        let counters = Counters::default();
        // The brancher only after every variable exists.
        let main: Box<dyn Brancher> = Box::new(solver.default_brancher());
        let first_phase = Rc::new(Cell::new(true));
        let inner: Box<dyn Brancher> = Box::new(Phased {
            first: IndependentVariableValueBrancher::new(FirstFail::new(&vars), InDomainMin),
            main,
            use_first: first_phase.clone(),
        });
        let brancher = Counting {
            inner,
            nodes: counters.nodes.clone(),
            conflicts: counters.conflicts.clone(),
        };
        Ok(Engine {
            solver,
            brancher,
            resolver: ResolutionResolver::default(),
            vars,
            guards,
            objective,
            counters,
            tag,
            first_phase,
            like: like_total.map(|t| (like, t)),
            dead: false,
            spent: false,
        })
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
        Stop {
            limits: limits.clone(),
            nodes: self.counters.nodes.clone(),
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
        if self.dead {
            return Sat::Unsat;
        }
        if self.spent {
            return Sat::Unknown;
        }
        let mut stop = self.stop(limits);
        let vars = self.vars.clone();
        match self
            .solver
            .satisfy(&mut self.brancher, &mut stop, &mut self.resolver)
        {
            SatisfactionResult::Satisfiable(s) => Sat::Solution(Self::values(&vars, &s.solution())),
            SatisfactionResult::Unsatisfiable(..) => {
                self.dead = true;
                Sat::Unsat
            }
            SatisfactionResult::Unknown(..) => {
                self.spent = true;
                Sat::Unknown
            }
        }
    }

    /// Solve with the guards of the hard rules in `rules` (indices into
    /// `Model::hard`) assumed true.
    ///
    /// `Sat::Unsat` carries no core: Pumpkin 0.5's `extract_core` can panic
    /// (`ConstraintTag::create_from_index`) or run for minutes without
    /// checking the termination condition on infeasible probe problems of
    /// the bundled example (`tests/fixtures/regressions/core-hang.rcc`), so
    /// the caller shrinks conflicts by deletion, where every solve obeys the
    /// limits.
    pub fn satisfy_rules(&mut self, rules: &[usize], limits: &Limits) -> Sat {
        let assumptions: Vec<Predicate> = rules
            .iter()
            .map(|&r| self.guards[r].get_true_predicate())
            .collect();
        self.under(&assumptions, limits)
    }

    fn under(&mut self, assumptions: &[Predicate], limits: &Limits) -> Sat {
        if self.dead {
            return Sat::Unsat;
        }
        if self.spent {
            return Sat::Unknown;
        }
        let mut stop = self.stop(limits);
        let vars = self.vars.clone();
        match self.solver.satisfy_under_assumptions(
            &mut self.brancher,
            &mut stop,
            &mut self.resolver,
            assumptions,
        ) {
            SatisfactionResultUnderAssumptions::Satisfiable(s) => {
                Sat::Solution(Self::values(&vars, &s.solution()))
            }
            SatisfactionResultUnderAssumptions::UnsatisfiableUnderAssumptions(_) => Sat::Unsat,
            SatisfactionResultUnderAssumptions::Unsatisfiable(_) => {
                self.dead = true;
                Sat::Unsat
            }
            SatisfactionResultUnderAssumptions::Unknown(_) => {
                self.spent = true;
                Sat::Unknown
            }
        }
    }

    /// The objective value of grid values `vals` under the model's
    /// coefficients (the variable part only).
    fn objective_value(&self, model: &Model, vals: &[i64]) -> i64 {
        let Some((_, coefs)) = &self.objective else {
            return 0;
        };
        let bools = model.eval_bools(vals);
        model
            .soft
            .iter()
            .filter(|s| matches!(s.lit, Lit::Var { .. }))
            .zip(coefs)
            .filter(|(s, _)| s.lit.value(&bools))
            .map(|(_, &c)| c)
            .sum()
    }

    /// Maximise the objective. `on_incumbent` is called with every improving
    /// solution.
    pub fn optimise(
        &mut self,
        model: &Model,
        limits: &Limits,
        strategy: Strategy,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> OptOutcome {
        let mut best = match self.satisfy(limits) {
            Sat::Solution(v) => v,
            Sat::Unsat => return OptOutcome::Infeasible,
            Sat::Unknown => return OptOutcome::Unknown,
        };
        on_incumbent(&best);
        self.first_phase.set(false);
        let Some((obj, coefs)) = self.objective.clone() else {
            return OptOutcome::Optimal(best);
        };
        let mut best_val = self.objective_value(model, &best);
        if strategy == Strategy::ImproveFromFirst {
            // Improve from the incumbent.
            loop {
                let a = [predicate![obj >= clamp_i32(best_val + 1)]];
                match self.under(&a, limits) {
                    Sat::Solution(v) => {
                        best_val = self.objective_value(model, &v);
                        best = v;
                        on_incumbent(&best);
                    }
                    Sat::Unsat => return OptOutcome::Optimal(best),
                    Sat::Unknown => return OptOutcome::Feasible(best),
                }
            }
        }
        let sums = SubsetSums::new(&coefs).unwrap_or_else(SubsetSums::all);
        let total: i64 = coefs.iter().sum();
        let snap = |v: i64| -> i64 {
            if v < 0 || sums.contains(v) {
                v
            } else {
                sums.below(v).unwrap_or(-1)
            }
        };
        let probes = UPPER_BOUND_PROBES;
        let mut hi = snap(total);
        let mut step = 0u32;
        loop {
            let root_ub = self.solver.upper_bound(&obj) as i64;
            if root_ub < hi {
                hi = snap(root_ub);
            }
            if best_val >= hi {
                return OptOutcome::Optimal(best);
            }
            // Upper bound first; then bisect between the incumbent and the bound.
            let target = if step < probes {
                hi
            } else {
                best_val + (hi - best_val + 1) / 2
            };
            step += 1;
            let a = [predicate![obj >= clamp_i32(target)]];
            match self.under(&a, limits) {
                Sat::Solution(v) => {
                    best_val = self.objective_value(model, &v);
                    best = v;
                    on_incumbent(&best);
                }
                Sat::Unsat => {
                    self.solver
                        .add_clause([predicate![obj <= clamp_i32(target - 1)]], self.tag);
                    hi = snap(target - 1);
                }
                Sat::Unknown => return OptOutcome::Feasible(best),
            }
        }
    }

    /// The second phase (SPEC §12): keep the numerator at least that of
    /// `best` (the first phase's layout) and minimise the resemblance cost,
    /// by bisection between the proven lower bound and the incumbent. A
    /// layout with a larger numerator, should one turn up (only when a limit
    /// stopped the first phase), replaces the incumbent and raises the
    /// numerator floor: the score is never traded for resemblance.
    /// `on_incumbent` is called with every improving layout.
    pub fn minimise_cost(
        &mut self,
        model: &Model,
        best: Vec<i64>,
        limits: &Limits,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> CostOutcome {
        let Some((terms, total)) = self.like.clone() else {
            return CostOutcome {
                values: best,
                cost: 0,
                proven: true,
            };
        };
        self.first_phase.set(false);
        let mut best_num = self.objective_value(model, &best);
        if let Some((obj, _)) = &self.objective {
            let obj = *obj;
            self.solver
                .add_clause([predicate![obj >= clamp_i32(best_num)]], self.tag);
        }
        let mut best_cost = total_cost(&terms, &best);
        let mut best = best;
        let mut lo = self.solver.lower_bound(&total) as u64;
        while lo < best_cost {
            let mid = lo + (best_cost - lo - 1) / 2;
            let a = [predicate![total <= i32::try_from(mid).unwrap_or(i32::MAX)]];
            let t = Instant::now();
            let r = self.under(&a, limits);
            if std::env::var_os("RCCPACK_DEBUG").is_some() {
                eprintln!(
                    "  cost <= {mid} (lo {lo}, best {best_cost}): {} in {:.1} ms",
                    match &r {
                        Sat::Solution(_) => "sat",
                        Sat::Unsat => "unsat",
                        Sat::Unknown => "unknown",
                    },
                    t.elapsed().as_secs_f64() * 1e3
                );
            }
            match r {
                Sat::Solution(v) => {
                    let num = self.objective_value(model, &v);
                    best_cost = total_cost(&terms, &v);
                    best = v;
                    on_incumbent(&best);
                    if num > best_num {
                        best_num = num;
                        if let Some((obj, _)) = &self.objective {
                            let obj = *obj;
                            self.solver
                                .add_clause([predicate![obj >= clamp_i32(best_num)]], self.tag);
                        }
                        // The cost floor was proven for a lower numerator
                        // floor; it still holds (fewer layouts now).
                    }
                }
                Sat::Unsat => {
                    self.solver.add_clause(
                        [predicate![
                            total >= i32::try_from(mid + 1).unwrap_or(i32::MAX)
                        ]],
                        self.tag,
                    );
                    lo = mid + 1;
                }
                Sat::Unknown => {
                    return CostOutcome {
                        values: best,
                        cost: best_cost,
                        proven: false,
                    }
                }
            }
        }
        CostOutcome {
            values: best,
            cost: best_cost,
            proven: true,
        }
    }
}

/// Bound one object's resemblance cost `c` from below by its distance map:
/// `gx = a ∧ gy = b → c ≥ map(a, b)` for every cell above the map's
/// minimum, plus `gx = a → c ≥ min_b map(a, b)` and the same per row, so
/// that one fixed coordinate already raises the bound. Only the lower bound
/// is needed: the cost is minimised.
///
/// Measured on `examples/box-packing` (9 objects, 46 learned rules): an
/// `element` constraint over the map indexed by `nx·gy + gx` took 4.8 s for
/// the first `cost ≤ 9` call (463 nodes in all: the time is propagation);
/// these clauses take a few milliseconds.
fn post_like(
    solver: &mut Solver,
    t: &LikeTerm,
    gx: DomainId,
    gy: DomainId,
    c: DomainId,
    tag: ConstraintTag,
) {
    let (nx, ny) = (t.map.nx as usize, t.map.ny as usize);
    let lo = t.map.min();
    let at = |a: usize, b: usize| t.map.cost[b * nx + a];
    let col: Vec<u64> = (0..nx)
        .map(|a| (0..ny).map(|b| at(a, b)).min().unwrap_or(lo))
        .collect();
    let row: Vec<u64> = (0..ny)
        .map(|b| (0..nx).map(|a| at(a, b)).min().unwrap_or(lo))
        .collect();
    for (a, &m) in col.iter().enumerate() {
        if m > lo {
            solver.add_clause([predicate![gx != a as i32], predicate![c >= m as i32]], tag);
        }
    }
    for (b, &m) in row.iter().enumerate() {
        if m > lo {
            solver.add_clause([predicate![gy != b as i32], predicate![c >= m as i32]], tag);
        }
    }
    for (b, &rb) in row.iter().enumerate() {
        for (a, &ca) in col.iter().enumerate() {
            let v = at(a, b);
            // Cells whose cost the column or row clause already gives need
            // no clause of their own.
            if v > ca.max(rb) {
                solver.add_clause(
                    [
                        predicate![gx != a as i32],
                        predicate![gy != b as i32],
                        predicate![c >= v as i32],
                    ],
                    tag,
                );
            }
        }
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
        let m = Model::build(
            &scene,
            &rules,
            BuildOptions {
                contact: Contact::Point,
                rules: true,
                symmetry_breaking: false,
                redundant: false,
            },
        );
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
            if m.clauses.iter().all(|c| c.iter().any(|l| l.value(&bools))) {
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
