//! Large-neighbourhood search (LNS) for the anytime phase of synthesis.
//!
//! # Background
//!
//! On large problems (24–96 objects) one CP search over the whole layout
//! finds a first packing at once but improves it slowly: learning over
//! hundreds of objects rarely reaches the corner of the search space where
//! a handful of blocks must move together to satisfy one more rule. LNS
//! keeps the incumbent layout and repeatedly frees a *window* of a few
//! objects around an object that breaks a rule (it and its nearest
//! neighbours), fixes every other object where it is, and solves that small
//! problem to optimality with a node budget. An improvement replaces the
//! incumbent; the window grows when rounds stop paying off.
//!
//! A sub-problem is an ordinary problem — the same scene with the other
//! objects placed — so it is built by [`Model::build`] and solved by a fresh
//! engine through the same [`driver`]; its objective is the
//! full objective minus a constant (the terms no freed object can change).
//!
//! # Practical
//!
//! - Deterministic: the windows come from a seeded generator and every
//!   sub-solve has a node budget, so the same seed gives the same layout
//!   unless the deadline (or a stop flag) cuts the phase short.
//! - LNS never proves anything: the main engine proves the optimum from
//!   the improved incumbent (`driver::optimise_from`). [`Lns::alternate`]
//!   interleaves the two: a proof attempt with a node budget (300 at
//!   first, doubling; every other attempt asks for the incumbent plus one
//!   instead of the upper bound), then an LNS phase, and so on. The engine
//!   is stopped only above its search root, so it resumes each attempt
//!   with everything it learned.
//! - A phase stops when the incumbent reaches the root bound, after
//!   `patience` fruitless rounds at the largest window, or when as many
//!   nodes as the last proof attempt's budget pass without an improvement.
//! - Measured on `bench tasks` (docs/performance.md): on the tasks `learn`
//!   writes, LNS before the proof cost more than it brought at 16–40
//!   objects (the optimum was usually one the engine reaches directly from
//!   the warm start) and kept the scores up at 30–60; alternating keeps
//!   both.
//!
//! # How to extend
//!
//! Other neighbourhoods (a class, a band of rows, the objects of one broken
//! rule) go into `Lns::window`; the differential tests in
//! `tests/synth_differential.rs` run synthesis with LNS forced on (tiny
//! windows, proof attempts of a few nodes) and compare with brute force.

use super::backend::{Backend, Stop};
use super::driver::{self, Objective, OptOutcome, Strategy};
use super::engine::Engine;
use super::model::{BuildOptions, Coord, Lit, Model};
use super::SynthError;
use crate::rules::RuleSet;
use crate::scene::Scene;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// LNS parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LnsOptions {
    /// Smallest number of movable objects for which LNS runs (default 8):
    /// below it one search proves the optimum in milliseconds (the
    /// thesis-sized study, the bundled examples) and LNS would only add
    /// work. (Above it, a problem the first proof attempt settles never
    /// sees LNS either: see `Lns::alternate`.)
    pub min_objects: usize,
    /// Objects freed per round at first.
    pub window: usize,
    /// Largest window (default 24: on a 64-object problem of the scale
    /// series, windows up to 12 stopped at score 0.84 where 24 reached the
    /// optimum 1.0 in 3 s).
    pub max_window: usize,
    /// Fruitless rounds before the window grows (and, at the largest
    /// window, before LNS stops).
    pub patience: u32,
    /// Search nodes per round.
    pub round_nodes: u64,
    /// Search nodes without an improvement that end `Lns::improve` and
    /// the first LNS phase of `Lns::alternate` without a warm start
    /// (default 10 000: small enough that fruitless rounds hand the search
    /// back to the main engine, which proves realistic tasks without a warm
    /// start in a few thousand nodes).
    pub budget_nodes: u64,
    /// Search nodes of the main engine's first proof attempt in
    /// `Lns::alternate`; each later attempt gets twice as many (default
    /// 300: on the bundled example with 12 blocks per class, 200–500
    /// reached the proven optimum in 0.8–1.5 s, 2 000 in 2.3–4.7 s, 8 000
    /// in 3.4–5.9 s, seeds 0–2).
    pub proof_nodes: u64,
}

impl Default for LnsOptions {
    fn default() -> Self {
        LnsOptions {
            min_objects: 8,
            window: 5,
            max_window: 24,
            patience: 12,
            round_nodes: 3_000,
            budget_nodes: 10_000,
            proof_nodes: 300,
        }
    }
}

/// What the phase did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct LnsOutcome {
    /// The best layout (grid values of the full model).
    pub values: Vec<i64>,
    /// Its objective value.
    pub value: i64,
    /// Search nodes used.
    pub nodes: u64,
    /// Conflicts met.
    pub conflicts: u64,
    /// Rounds run.
    pub rounds: u32,
    /// Rounds that improved the incumbent.
    pub improved: u32,
}

/// One LNS run over one problem.
pub(super) struct Lns<'a> {
    /// The problem (movable objects unplaced).
    pub problem: &'a Scene,
    /// Its rules.
    pub rules: &'a RuleSet,
    /// The full model.
    pub model: &'a Model,
    /// How the full model was built (sub-models are built alike).
    pub build: BuildOptions,
    /// Objective coefficients in `model.soft` order.
    pub coefs: &'a [i64],
    /// Parameters.
    pub opts: LnsOptions,
    /// Seed of the window choice and the sub-engines.
    pub seed: u64,
    /// Whether [`Lns::alternate`]'s first LNS phase runs until it stops
    /// paying off (`budget_nodes` without an improvement), as LNS did before
    /// the alternation, instead of being as short as the proof attempt
    /// before it. `synthesize` sets it for problems of 16 or more objects
    /// without a warm start: their incumbent is a greedy packing far from
    /// the optimum (the thesis-style scale series: with short phases, 24
    /// of 36 proven and medians 2–10× slower; with a long first phase, 25
    /// of 36 and the earlier figures). With a warm start the incumbent is
    /// usually near the optimum and the proof matters more; below 16
    /// objects short phases found the case `scale_n12_k5_s5`'s optimum in
    /// 0.1 s where a long one took 13 s.
    pub long_first_phase: bool,
}

impl Lns<'_> {
    /// Improve `start` (a solution of the full model) until the objective
    /// reaches `bound`, the phase stops paying off, or a limit fires.
    /// `on_incumbent` sees every improving layout. (The solve alternates
    /// phases with [`Lns::alternate`]; this one phase is for the tests.)
    #[cfg(test)]
    pub(super) fn improve(
        &self,
        start: Vec<i64>,
        bound: i64,
        limits: &Stop,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> Result<LnsOutcome, SynthError> {
        let mut state = self.state(start);
        self.run(
            &mut state,
            bound,
            self.opts.budget_nodes,
            limits,
            on_incumbent,
        )?;
        Ok(state.out)
    }

    /// Alternate proof attempts of the main `engine` (the driver's
    /// optimisation from the incumbent, with a node budget that doubles
    /// each time) with LNS phases (each ends after as many nodes without an
    /// improvement, so it goes on while it pays off), until the engine
    /// proves the incumbent optimal or a limit of `limits` (over the whole
    /// solve: the engine's nodes plus the sub-engines') fires.
    ///
    /// Easy problems never see LNS: the first attempt proves them. On hard
    /// ones the engine keeps what it learned between attempts, and LNS
    /// hands it better incumbents. Every budget is in nodes, so a node limit
    /// keeps the whole solve deterministic.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn alternate(
        &self,
        engine: &mut dyn Backend,
        objective: &Objective<'_>,
        best: Vec<i64>,
        limits: &Stop,
        strategy: Strategy,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> Result<(OptOutcome, LnsOutcome), SynthError> {
        let mut state = self.state(best);
        let mut budget = self.opts.proof_nodes.max(1);
        let mut attempt = 0u32;
        loop {
            let lns_nodes = state.out.nodes;
            let used = engine.nodes().saturating_add(lns_nodes);
            if limits.expired() || limits.nodes().is_some_and(|n| used >= n) {
                let best = state.out.values.clone();
                return Ok((OptOutcome::Feasible(best), state.out));
            }
            // The engine's own limit counts its nodes only.
            let cap = engine.nodes().saturating_add(budget);
            let cap = limits
                .nodes()
                .map_or(cap, |n| cap.min(n.saturating_sub(lns_nodes)));
            let proof_limits = limits.clone().nodes_at_most(Some(cap));
            let best = state.out.values.clone();
            // Every other attempt asks for the incumbent plus one (the
            // proof a below-the-bound optimum needs); the others use the
            // caller's strategy (upper bound first: what reaches a score-1
            // layout at once).
            let this = if attempt % 2 == 1 {
                Strategy::ImproveFromFirst
            } else {
                strategy
            };
            attempt += 1;
            match driver::optimise_from(
                engine,
                Some(objective),
                best,
                &proof_limits,
                this,
                on_incumbent,
            ) {
                OptOutcome::Feasible(v) => {
                    let value = (objective.value)(&v);
                    if value > state.out.value {
                        state.out.value = value;
                        state.out.values = v;
                    }
                }
                done => return Ok((done, state.out)),
            }
            let bound = engine.objective_bound().unwrap_or(i64::MAX);
            let lns_limits = limits
                .clone()
                .nodes_at_most(limits.nodes().map(|n| n.saturating_sub(engine.nodes())));
            let phase_budget = if attempt == 1 && self.long_first_phase {
                self.opts.budget_nodes
            } else {
                budget
            };
            self.run(&mut state, bound, phase_budget, &lns_limits, on_incumbent)?;
            budget = budget.saturating_mul(2);
        }
    }

    fn state(&self, start: Vec<i64>) -> State {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(0x4c4e53); // "LNS"
        let movable: Vec<usize> = (0..self.model.coords.len())
            .filter(|&o| matches!(self.model.coords[o].0, Coord::Var(_)))
            .collect();
        let window = self.opts.window.min(movable.len());
        State {
            out: LnsOutcome {
                value: self.model.objective_value(self.coefs, &start),
                values: start,
                nodes: 0,
                conflicts: 0,
                rounds: 0,
                improved: 0,
            },
            rng,
            movable,
            window,
            fails: 0,
        }
    }

    /// One LNS phase: rounds until the incumbent reaches `bound`, `budget`
    /// nodes pass without an improvement, the rounds stop paying off at the
    /// largest window, or a limit fires (`limits.nodes()` counts the phase's nodes from
    /// the state's total).
    fn run(
        &self,
        st: &mut State,
        bound: i64,
        budget: u64,
        limits: &Stop,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> Result<(), SynthError> {
        let model = self.model;
        let opts = self.opts;
        // The budget counts the nodes since the last improvement: a phase
        // goes on while it pays off.
        let mut start_nodes = st.out.nodes;
        st.fails = 0;
        while st.out.value < bound && st.window > 0 {
            let phase = st.out.nodes - start_nodes;
            let used = st.out.nodes;
            if phase >= budget || limits.nodes().is_some_and(|n| used >= n) || limits.expired() {
                break;
            }
            let freed = self.window(
                &st.out.values,
                &st.movable,
                st.window,
                st.out.rounds,
                &mut st.rng,
            );
            st.out.rounds += 1;
            let round_nodes = opts
                .round_nodes
                .min(budget - phase)
                .min(limits.nodes().map_or(u64::MAX, |n| n - used));
            let sub_limits = limits.clone().nodes_at_most(Some(round_nodes));
            let seed = self.seed.wrapping_add(u64::from(st.out.rounds));
            let r = self.round(&st.out.values, &freed, bound, &sub_limits, seed)?;
            st.out.nodes += r.nodes;
            st.out.conflicts += r.conflicts;
            match r.values {
                Some(v) => {
                    let value = model.objective_value(self.coefs, &v);
                    if value > st.out.value {
                        st.out.value = value;
                        st.out.values = v;
                        st.out.improved += 1;
                        st.fails = 0;
                        start_nodes = st.out.nodes;
                        on_incumbent(&st.out.values);
                        continue;
                    }
                    st.fails += 1;
                }
                None => st.fails += 1,
            }
            if st.fails >= opts.patience {
                if st.window >= opts.max_window.min(st.movable.len()) {
                    break;
                }
                st.window = (st.window + 2).min(opts.max_window).min(st.movable.len());
                st.fails = 0;
            }
        }
        Ok(())
    }

    /// The objects to free: one that breaks a rule (any movable object when
    /// only scene-level terms are broken) and its nearest movable
    /// neighbours; every third round, half of them at random instead.
    fn window(
        &self,
        vals: &[i64],
        movable: &[usize],
        size: usize,
        round: u32,
        rng: &mut ChaCha8Rng,
    ) -> Vec<usize> {
        let model = self.model;
        let bools = model.eval_bools(vals);
        let mut broken: Vec<usize> = model
            .soft
            .iter()
            .filter(|s| matches!(s.lit, Lit::Var { .. }) && !s.lit.value(&bools))
            .filter_map(|s| s.object)
            .filter(|o| movable.contains(o))
            .collect();
        broken.sort_unstable();
        broken.dedup();
        let pool = if broken.is_empty() { movable } else { &broken };
        let seed_obj = pool[rng.random_range(0..pool.len())];
        let centre = |o: usize| -> (i64, i64) {
            let (w, h) = model.footprint_in(o, vals);
            let at = |c: Coord, origin: i64| match c {
                Coord::Const(v) => v,
                Coord::Var(i) => origin + model.grid * vals[i],
            };
            let (cx, cy) = model.coords[o];
            (
                2 * at(cx, model.origin.0) + w,
                2 * at(cy, model.origin.1) + h,
            )
        };
        let (sx, sy) = centre(seed_obj);
        let mut by_distance: Vec<(i64, usize)> = movable
            .iter()
            .map(|&o| {
                let (x, y) = centre(o);
                let (dx, dy) = ((x - sx).abs(), (y - sy).abs());
                (
                    dx.saturating_mul(dx).saturating_add(dy.saturating_mul(dy)),
                    o,
                )
            })
            .collect();
        by_distance.sort_unstable();
        let random_part = if round % 3 == 2 { size / 2 } else { 0 };
        let mut freed: Vec<usize> = by_distance
            .iter()
            .take(size - random_part)
            .map(|&(_, o)| o)
            .collect();
        while freed.len() < size {
            let o = movable[rng.random_range(0..movable.len())];
            if !freed.contains(&o) {
                freed.push(o);
            }
        }
        freed.sort_unstable();
        freed
    }

    /// Solve the sub-problem with `freed` movable and every other object
    /// where `vals` puts it; the best layout found, as full-model values.
    fn round(
        &self,
        vals: &[i64],
        freed: &[usize],
        bound: i64,
        limits: &Stop,
        seed: u64,
    ) -> Result<Round, SynthError> {
        let model = self.model;
        let mut sub_scene = self.problem.clone();
        for (o, obj) in sub_scene.objects.iter_mut().enumerate() {
            if let (Coord::Var(vx), Coord::Var(vy)) = model.coords[o] {
                if freed.binary_search(&o).is_err() {
                    obj.x = Some(model.origin.0 + model.grid * vals[vx]);
                    obj.y = Some(model.origin.1 + model.grid * vals[vy]);
                    obj.turned |= model.turned_in(o, vals);
                }
            }
        }
        let sub = Model::build(&sub_scene, self.rules, self.build);
        if sub.soft.len() != self.coefs.len() || !sub.too_large.is_empty() {
            return Ok(Round::none());
        }
        // The incumbent as sub-model values, and back.
        let to_sub: Vec<i64> = sub
            .vars
            .iter()
            .map(|v| match model.coord_of(v) {
                Coord::Var(i) => vals[i],
                Coord::Const(_) => 0,
            })
            .collect();
        let mut engine = Engine::new(&sub, seed, false, Some(self.coefs))?;
        let ws: Vec<i64> = engine.objective_coefs().unwrap_or(&[]).to_vec();
        let value = |v: &[i64]| sub.objective_value(self.coefs, v);
        let objective = Objective {
            coefs: &ws,
            value: &value,
        };
        // The sub-objective is the full one minus a constant.
        let offset = model.objective_value(self.coefs, vals) - value(&to_sub);
        engine.add(super::backend::Fact::ObjectiveAtMost(bound - offset));
        engine.found_first();
        let outcome = driver::optimise_from(
            &mut engine,
            Some(&objective),
            to_sub,
            limits,
            Strategy::UpperBoundFirst,
            &mut |_| {},
        );
        let (nodes, conflicts) = (engine.nodes(), engine.conflicts());
        let values = match outcome {
            OptOutcome::Optimal(v) | OptOutcome::Feasible(v) => {
                let mut full = vals.to_vec();
                for (sv, x) in sub.vars.iter().zip(&v) {
                    if let Coord::Var(i) = model.coord_of(sv) {
                        full[i] = *x;
                    }
                }
                Some(full)
            }
            OptOutcome::Infeasible | OptOutcome::Unknown => None,
        };
        Ok(Round {
            values,
            nodes,
            conflicts,
        })
    }
}

/// What persists between the phases of one LNS run.
struct State {
    out: LnsOutcome,
    rng: ChaCha8Rng,
    movable: Vec<usize>,
    window: usize,
    fails: u32,
}

struct Round {
    values: Option<Vec<i64>>,
    nodes: u64,
    conflicts: u64,
}

impl Round {
    fn none() -> Self {
        Round {
            values: None,
            nodes: 0,
            conflicts: 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::relations::Contact;
    use crate::rules::parse_rules;
    use crate::scene::{Object, Space};
    use crate::synth::verify_solution;
    use crate::synth::weights::integer_weights;

    /// Six blocks that should lie north of a fixed bar: the engine's first
    /// (greedy, bottom-left) packing puts them all south of it; LNS alone
    /// moves every one north, and each layout it reports is a valid
    /// solution.
    #[test]
    fn lns_improves_a_greedy_packing() {
        let mut objects: Vec<Object> = (0..6)
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
            .collect();
        objects.push(Object::fixed_at("bar", "F", 0, 40, 80, 10));
        let problem = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 80,
                height: 80,
            },
            grid: 10,
            objects,
        };
        let rules = parse_rules("rule north: DR_N(A, @bar)\n").unwrap();
        let build = BuildOptions {
            contact: Contact::Point,
            rules: true,
            symmetry_breaking: true,
            redundant: true,
            tuning: Default::default(),
        };
        let model = Model::build(&problem, &rules, build);
        let weights: Vec<f64> = model.soft.iter().map(|s| s.weight).collect();
        let coefs = integer_weights(&weights).unwrap();
        let mut engine = Engine::new(&model, 0, false, Some(&coefs)).unwrap();
        let first = driver::first_solution(&mut engine, &Stop::never()).unwrap();
        let start = model.objective_value(&coefs, &first);
        let bound = engine.objective_bound().unwrap();
        assert!(start < bound, "the greedy packing is already optimal");
        let lns = Lns {
            problem: &problem,
            rules: &rules,
            model: &model,
            build,
            coefs: &coefs,
            opts: LnsOptions {
                min_objects: 0,
                window: 1,
                max_window: 2,
                patience: 6,
                round_nodes: 500,
                budget_nodes: 50_000,
                proof_nodes: 1_000,
            },
            seed: 3,
            long_first_phase: false,
        };
        let mut seen = Vec::new();
        let out = lns
            .improve(first, bound, &Stop::never(), &mut |v| seen.push(v.to_vec()))
            .unwrap();
        assert_eq!(out.value, bound, "{out:?}");
        assert!(out.improved > 0 && out.rounds >= out.improved);
        assert_eq!(seen.last(), Some(&out.values));
        for v in &seen {
            let s = model.scene(&problem, v);
            verify_solution(&problem, &s, &rules, Contact::Point).unwrap();
        }
        // Deterministic: the same seed, the same layouts.
        let first = driver::first_solution(
            &mut Engine::new(&model, 0, false, Some(&coefs)).unwrap(),
            &Stop::never(),
        )
        .unwrap();
        let again = lns
            .improve(first, bound, &Stop::never(), &mut |_| {})
            .unwrap();
        assert_eq!(again, out);
    }

    /// Pumpkin 0.5 asserts when solving again after a timeout at the root;
    /// the engine only stops above it, so it can be stopped after every
    /// few decisions and solved again, keeping what it learned, and still
    /// reaches the optimum of an unlimited solve.
    #[test]
    fn engine_resumes_after_every_limit() {
        let mut objects: Vec<Object> = (0..7)
            .map(|i| Object {
                id: format!("a{i}"),
                class: if i % 2 == 0 { "A" } else { "B" }.into(),
                x: None,
                y: None,
                width: 10,
                height: 10 + 10 * (i % 2),
                fixed: false,
                turnable: false,
                turned: false,
            })
            .collect();
        objects.push(Object::fixed_at("bar", "F", 0, 30, 50, 10));
        let problem = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 60,
                height: 60,
            },
            grid: 10,
            objects,
        };
        let rules = parse_rules(
            "rule n: DR_N(A, @bar)\nrule t: EC_E(B, A) | EC_W(B, A)\nrule s: DR_S(B, A)\n",
        )
        .unwrap();
        let build = BuildOptions {
            contact: Contact::Point,
            rules: true,
            symmetry_breaking: true,
            redundant: true,
            tuning: Default::default(),
        };
        let model = Model::build(&problem, &rules, build);
        let weights: Vec<f64> = model.soft.iter().map(|s| s.weight).collect();
        let coefs = integer_weights(&weights).unwrap();
        let value = |v: &[i64]| model.objective_value(&coefs, v);
        let solve = |step: Option<u64>| -> (i64, u32) {
            let mut engine = Engine::new(&model, 0, false, Some(&coefs)).unwrap();
            let ws = engine.objective_coefs().unwrap().to_vec();
            let objective = Objective {
                coefs: &ws,
                value: &value,
            };
            let mut calls = 0u32;
            let mut best = loop {
                calls += 1;
                let limits = Stop::never().nodes_at_most(step.map(|s| engine.nodes() + s));
                if let Ok(v) = driver::first_solution(&mut engine, &limits) {
                    break v;
                }
            };
            loop {
                calls += 1;
                let limits = Stop::never().nodes_at_most(step.map(|s| engine.nodes() + s));
                match driver::optimise_from(
                    &mut engine,
                    Some(&objective),
                    best.clone(),
                    &limits,
                    Strategy::UpperBoundFirst,
                    &mut |_| {},
                ) {
                    OptOutcome::Optimal(v) => return (value(&v), calls),
                    OptOutcome::Feasible(v) => best = v,
                    o => panic!("{o:?}"),
                }
            }
        };
        let (optimum, _) = solve(None);
        // A budget of one decision more than there are variables: every
        // call ends in a solution, a conflict (learned, kept) or the limit.
        let (stepped, calls) = solve(Some(model.vars.len() as u64 + 1));
        assert_eq!(stepped, optimum);
        assert!(calls > 5, "only {calls} calls: the limit never struck");
    }
}
