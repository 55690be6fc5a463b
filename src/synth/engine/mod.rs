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
//! - `DiffGe` Booleans: a fresh literal; the literals of one pair of
//!   variables share one `difference` propagator (the reified linear
//!   `b − a ≤ −k` each with `RCCPACK_DIFFERENCE=off`);
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
use super::model::Model;
use super::resemblance_terms::ResemblanceTerm;
use super::SynthError;
use resemblance::PendingResemblance;
#[cfg(test)]
use resemblance::{ResemblanceEncoding, RESEMBLANCE_ENCODING};

mod brancher;
mod build;
mod connected;
mod difference;
mod no_overlap;
mod resemblance;
mod resemblance_group;
mod resemblance_map;
mod stop;
use build::{check_ranges, clamp_i32, Builder};
use pumpkin_conflict_resolvers::resolvers::ResolutionResolver;
use pumpkin_core::branching::branchers::independent_variable_value_brancher::IndependentVariableValueBrancher;
use pumpkin_core::branching::branchers::warm_start::WarmStart;
use pumpkin_core::branching::value_selection::InDomainRandom;
use pumpkin_core::branching::variable_selection::RandomSelector;
use pumpkin_core::predicate;
use pumpkin_core::predicates::Predicate;
use pumpkin_core::proof::ConstraintTag;
use pumpkin_core::results::{
    ProblemSolution, SatisfactionResult, SatisfactionResultUnderAssumptions,
};
use pumpkin_core::variables::{DomainId, Literal};
use pumpkin_core::Solver;
use std::cell::Cell;
use std::rc::Rc;
use stop::{Counters, Counting, Termination};

pub(crate) use crate::stop::Stop;

/// A Pumpkin solver holding one model: the [`Backend`] the driver runs on.
pub(crate) struct Engine {
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
    /// The resemblance total-cost variable (docs/guide.md#layouts-like-the-demonstrations).
    resemblance_total: Option<DomainId>,
    /// The second objective until the second phase starts ([`resemblance`]).
    pending_resemblance: Option<PendingResemblance>,
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

impl Engine {
    /// Post `model`. With `guarded`, every hard rule `r` is enforced only
    /// under its assumption literal (for core extraction); otherwise hard
    /// literals are posted as units. `coefs` are the objective coefficients
    /// of `model.soft` (none: no objective).
    ///
    /// Every number handed to Pumpkin goes through a checked conversion to
    /// `i32`; one that does not fit is a [`SynthError::TooLarge`] naming it
    /// (see [`super::MAX_SYNTH_COORD`] for why that cannot happen on a problem
    /// that passed the range check).
    pub(crate) fn new(
        model: &Model,
        seed: u64,
        guarded: bool,
        coefs: Option<&[i64]>,
    ) -> Result<Engine, SynthError> {
        Self::with_resemblance(model, seed, guarded, coefs, &[])
    }

    /// [`Engine::new`] with the resemblance terms of the second objective
    /// (none: no second objective). Each term's cost is a variable bounded
    /// below by its distance map (see `post_resemblance`); the total is one
    /// variable. Costs that do not fit `i32` ([`resemblance_fits`]) are a
    /// [`SynthError::TooLarge`].
    pub(crate) fn with_resemblance(
        model: &Model,
        seed: u64,
        guarded: bool,
        coefs: Option<&[i64]>,
        like: &[ResemblanceTerm],
    ) -> Result<Engine, SynthError> {
        let e = Self::with_resemblance_until(model, seed, guarded, coefs, like, None)?;
        Ok(e.expect("no deadline"))
    }

    /// [`Engine::with_resemblance`], given up (`None`) once `deadline` passes:
    /// posting a large model can take longer than the solve's time limit.
    pub(crate) fn with_resemblance_until(
        model: &Model,
        seed: u64,
        guarded: bool,
        coefs: Option<&[i64]>,
        like: &[ResemblanceTerm],
        deadline: Option<std::time::Instant>,
    ) -> Result<Option<Engine>, SynthError> {
        let stop = Stop::never().by(deadline);
        Self::with_resemblance_stop(model, seed, guarded, coefs, like, &stop)
    }

    /// [`Engine::with_resemblance_until`] that also gives up when `stop`'s cancel
    /// flag is set (Ctrl-C while a large model is posted).
    pub(crate) fn with_resemblance_stop(
        model: &Model,
        seed: u64,
        guarded: bool,
        coefs: Option<&[i64]>,
        like: &[ResemblanceTerm],
        stop: &Stop,
    ) -> Result<Option<Engine>, SynthError> {
        check_ranges(model, like)?;
        let mut b = Builder::new(model, seed)?;
        b.stop = stop.clone().nodes_at_most(None);
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
        // The second objective waits for the second phase (see `resemblance`).
        let pending = PendingResemblance::new(model, like);
        let mut engine = b.finish(guards, objective, None);
        engine.pending_resemblance = pending;
        Ok(Some(engine))
    }

    /// The objective's coefficients, variable terms only, in
    /// [`Model::soft`] order (none: no objective).
    pub(crate) fn objective_coefs(&self) -> Option<&[i64]> {
        self.objective.as_ref().map(|(_, c)| c.as_slice())
    }

    /// Decisions so far.
    pub(crate) fn nodes(&self) -> u64 {
        self.counters.nodes.get()
    }

    /// Conflicts so far.
    pub(crate) fn conflicts(&self) -> u64 {
        self.counters.conflicts.get()
    }

    fn stop(&self, limits: &Stop) -> Termination {
        // Every call starts at the root.
        self.counters.safe.set(false);
        Termination {
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
    pub(crate) fn satisfy(&mut self, limits: &Stop) -> Verdict {
        self.solve(&[], limits)
    }

    /// A Pumpkin call under `assumptions` (none: a plain `satisfy`).
    ///
    /// An infeasible call under assumptions carries no core: Pumpkin 0.5's
    /// `extract_core` can panic (`ConstraintTag::create_from_index`) or run
    /// for minutes without checking the termination condition on infeasible
    /// probe problems of the bundled example
    /// (`tests/fixtures/regressions/core-hang.rcc`), so the driver shrinks
    /// conflicts by deletion, where every solve obeys the limits.
    fn call(&mut self, assumptions: &[Predicate], limits: &Stop) -> Verdict {
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

impl Backend for Engine {
    /// `Rule(r)` on an engine built without guards is a no-op (its rule is
    /// posted as units); `ObjectiveAtLeast(k)` without an objective holds
    /// iff `k ≤ 0`, `CostAtMost` without a second objective always holds.
    fn solve(&mut self, assumptions: &[Assumption], limits: &Stop) -> Verdict {
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
                    if let Some(total) = self.resemblance_total {
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
                .resemblance_total
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
        if let Some(pending) = self.pending_resemblance.take() {
            let posted = pending.post(&mut self.solver, &self.vars, self.tag);
            self.brancher.inner.add_late(&posted.created);
            self.resemblance_total = Some(posted.total);
        }
    }

    fn cost_bound(&self) -> Option<u64> {
        match (&self.pending_resemblance, self.resemblance_total) {
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

    /// Exclude the assignment `values` (one per model variable) from every
    /// later call: the clause "some variable takes another value". Used by
    /// `crate::sample` to draw distinct layouts. With no variable, the model
    /// has one assignment, so every later call is infeasible.
    fn exclude(&mut self, values: &[i64]) {
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
    fn leave_greedy_after(&mut self, conflicts: u64) {
        self.brancher.inner.first_cap = Some(conflicts);
    }
    /// After the hint, search at random instead of by activity: a random
    /// unfixed grid variable, a random value of its domain (the solver's
    /// seeded generator); conflicts are learned as usual. Every Boolean of
    /// the model is defined by the grid variables, so branching on them
    /// alone is complete. Used by `crate::sample`.
    fn random_search(&mut self) {
        self.brancher.inner.main = Box::new(IndependentVariableValueBrancher::new(
            RandomSelector::new(self.vars.iter().copied()),
            InDomainRandom,
        ));
    }
    /// Try `hints` (pairs of a model variable and a value) first, in this
    /// order, until the next solution: [`Backend::hint`] with the order
    /// chosen by the caller (`crate::sample` draws it at random).
    fn hint_in_order(&mut self, hints: &[(usize, i64)]) {
        // `WarmStart` tries its list from the back.
        let (vars, vals): (Vec<DomainId>, Vec<i32>) = hints
            .iter()
            .rev()
            .filter_map(|&(v, x)| Some((*self.vars.get(v)?, i32::try_from(x).ok()?)))
            .unzip();
        self.brancher.inner.hint = (!vars.is_empty()).then(|| WarmStart::new(&vars, &vals));
    }
}

/// Whether the resemblance terms' costs fit the engine's `i32` arithmetic
/// (every cost, every index and the total).
pub(crate) fn resemblance_fits(terms: &[ResemblanceTerm]) -> bool {
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
    use crate::synth::model::BoolDef;

    /// The resemblance encodings — clauses, the bounds propagator, both —
    /// each reach brute force's lexicographic optimum (numerator, then
    /// cost) on small problems with random like-scenes, and prove it; so
    /// does the second phase when its probes run out of their node budget
    /// at once (budgets of 1 and 4 nodes: steps down, doubling).
    #[test]
    fn like_encodings_agree_with_brute_force() {
        use crate::resemblance::ResemblanceTarget;
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
            let like = ResemblanceTarget::new(&scenes);
            let bf = brute_force::solve_like(&problem, &rules, Contact::Point, &like, 10_000_000)
                .unwrap();
            for (enc, budget) in [
                (ResemblanceEncoding::Clauses, 2_000),
                (ResemblanceEncoding::Propagator, 2_000),
                (ResemblanceEncoding::Both, 2_000),
                (ResemblanceEncoding::Both, 1),
                (ResemblanceEncoding::Both, 4),
            ] {
                RESEMBLANCE_ENCODING.with(|e| e.set(enc));
                crate::synth::driver::COST_PROBE_NODES_HERE.with(|n| n.set(budget));
                let r = synthesize(
                    &problem,
                    &rules,
                    &SynthOptions {
                        like: Some(like.clone()),
                        ..SynthOptions::default()
                    },
                )
                .unwrap();
                RESEMBLANCE_ENCODING.with(|e| e.set(ResemblanceEncoding::Both));
                crate::synth::driver::COST_PROBE_NODES_HERE.with(|n| n.set(2_000));
                let res = r.resemblance.expect("a resemblance");
                let ev = r.evaluation.expect("an evaluation");
                assert!(res.proven, "case {case}, {enc:?}/{budget}: cost not proven");
                assert_eq!(res.cost, bf.best_cost, "case {case}, {enc:?}/{budget}");
                assert!(
                    (ev.satisfied_weight - bf.best_numerator).abs() < 1e-9,
                    "case {case}, {enc:?}/{budget}"
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
                    turnable: false,
                    turned: false,
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
                tuning: Default::default(),
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
                match e.solve(&[Assumption::Rule(0)], &Stop::never()) {
                    Verdict::Solution(v) => {
                        assert!(possible, "engine found {v:?} for the impossible {lit:?}");
                        let b = m.eval_bools(&v);
                        assert!(lit.value(&b), "{lit:?} false in the engine's {v:?}");
                        assert!(m.clauses.iter().all(|c| c.iter().any(|l| l.value(&b))));
                        assert!(m.non_overlapping(&v), "{v:?} overlaps");
                        sat += 1;
                    }
                    Verdict::Infeasible(_) => {
                        assert!(!possible, "engine refuted the possible {lit:?}");
                        unsat += 1;
                    }
                    Verdict::Unknown => panic!("no limit, yet unknown"),
                }
            }
        }
        assert!(sat > 0 && unsat > 0, "{sat} sat, {unsat} unsat");
    }
}
