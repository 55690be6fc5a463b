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
//! - LNS never proves anything: the main engine proves the optimum
//!   afterwards, from the improved incumbent (`driver::optimise_from`).
//! - It stops when the incumbent reaches the root bound, after `patience`
//!   fruitless rounds at the largest window, or when its node budget is
//!   spent.
//!
//! # How to extend
//!
//! Other neighbourhoods (a class, a band of rows, the objects of one broken
//! rule) go into `Lns::window`; the differential tests in `tests/synth.rs`
//! run synthesis with LNS on and off and compare with brute force.

use super::backend::{Backend, Limits};
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
    /// Smallest number of movable objects for which LNS runs (default 16):
    /// below it one search proves the optimum in milliseconds (the
    /// thesis-sized study, the bundled examples) and LNS would only add
    /// work.
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
    /// Search nodes for the whole phase.
    pub budget_nodes: u64,
}

impl Default for LnsOptions {
    fn default() -> Self {
        LnsOptions {
            min_objects: 16,
            window: 5,
            max_window: 24,
            patience: 12,
            round_nodes: 3_000,
            budget_nodes: 1_000_000,
        }
    }
}

/// What the phase did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LnsOutcome {
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
pub struct Lns<'a> {
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
}

impl Lns<'_> {
    /// Improve `start` (a solution of the full model) until the objective
    /// reaches `bound`, the phase stops paying off, or a limit fires.
    /// `on_incumbent` sees every improving layout.
    pub fn improve(
        &self,
        start: Vec<i64>,
        bound: i64,
        limits: &Limits,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> Result<LnsOutcome, SynthError> {
        let model = self.model;
        let opts = self.opts;
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(0x4c4e53); // "LNS"
        let movable: Vec<usize> = (0..model.coords.len())
            .filter(|&o| matches!(model.coords[o].0, Coord::Var(_)))
            .collect();
        let mut out = LnsOutcome {
            value: model.objective_value(self.coefs, &start),
            values: start,
            nodes: 0,
            conflicts: 0,
            rounds: 0,
            improved: 0,
        };
        let mut window = opts.window.min(movable.len());
        let mut fails = 0u32;
        while out.value < bound && window > 0 {
            let used = out.nodes;
            if used >= opts.budget_nodes
                || limits.node_limit.is_some_and(|n| used >= n)
                || limits.expired()
            {
                break;
            }
            let freed = self.window(&out.values, &movable, window, out.rounds, &mut rng);
            out.rounds += 1;
            let round_nodes = self
                .opts
                .round_nodes
                .min(opts.budget_nodes - used)
                .min(limits.node_limit.map_or(u64::MAX, |n| n - used));
            let sub_limits = Limits {
                deadline: limits.deadline,
                node_limit: Some(round_nodes),
                cancel: limits.cancel.clone(),
            };
            let seed = self.seed.wrapping_add(u64::from(out.rounds));
            let r = self.round(&out.values, &freed, bound, &sub_limits, seed)?;
            out.nodes += r.nodes;
            out.conflicts += r.conflicts;
            match r.values {
                Some(v) => {
                    let value = model.objective_value(self.coefs, &v);
                    if value > out.value {
                        out.value = value;
                        out.values = v;
                        out.improved += 1;
                        fails = 0;
                        on_incumbent(&out.values);
                        continue;
                    }
                    fails += 1;
                }
                None => fails += 1,
            }
            if fails >= opts.patience {
                if window >= opts.max_window.min(movable.len()) {
                    break;
                }
                window = (window + 2).min(opts.max_window).min(movable.len());
                fails = 0;
            }
        }
        Ok(out)
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
            let (w, h) = model.sizes[o];
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
        limits: &Limits,
        seed: u64,
    ) -> Result<Round, SynthError> {
        let model = self.model;
        let mut sub_scene = self.problem.clone();
        for (o, obj) in sub_scene.objects.iter_mut().enumerate() {
            if let (Coord::Var(vx), Coord::Var(vy)) = model.coords[o] {
                if freed.binary_search(&o).is_err() {
                    obj.x = Some(model.origin.0 + model.grid * vals[vx]);
                    obj.y = Some(model.origin.1 + model.grid * vals[vy]);
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
    use crate::synth::verify::verify_solution;
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
        };
        let model = Model::build(&problem, &rules, build);
        let weights: Vec<f64> = model.soft.iter().map(|s| s.weight).collect();
        let coefs = integer_weights(&weights).unwrap();
        let mut engine = Engine::new(&model, 0, false, Some(&coefs)).unwrap();
        let first = driver::first_solution(&mut engine, &Limits::default()).unwrap();
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
            },
            seed: 3,
        };
        let mut seen = Vec::new();
        let out = lns
            .improve(first, bound, &Limits::default(), &mut |v| {
                seen.push(v.to_vec())
            })
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
            &Limits::default(),
        )
        .unwrap();
        let again = lns
            .improve(first, bound, &Limits::default(), &mut |_| {})
            .unwrap();
        assert_eq!(again, out);
    }
}
