//! The engine-facing half of [`Sampler`]: per orientation choice its model,
//! the objective target, the engine with "objective ≥ target", the random
//! hints and the draw of one layout.

use super::{like_key, Quality, Repair, SampleError, Sampler};
use crate::eval::evaluate;
use crate::scene::Scene;
use crate::synth::backend::{Fact, Stop, Verdict};
use crate::synth::model::{Coord, Lit, Model};
use crate::synth::SynthError;
use rand::seq::SliceRandom;
use rand::RngExt;
use std::collections::BTreeMap;
use std::time::Instant;

impl Sampler {
    /// The limits of the search for the next layout of choice `b`: the
    /// run's stop, tightened by the per-layout time and node budgets.
    pub(super) fn limits(&self, b: usize) -> Stop {
        let per = self
            .opts
            .layout_time_limit
            .and_then(|t| Instant::now().checked_add(t));
        let used = self.branches[b].engine.as_ref().map_or(0, |e| e.nodes());
        self.opts
            .stop
            .clone()
            .by(per)
            .nodes_at_most(self.opts.layout_node_limit.map(|n| used.saturating_add(n)))
    }

    /// The model of orientation choice `b` and its hint groups (built
    /// once).
    pub(super) fn build_model(&mut self, b: usize) -> Result<(), SynthError> {
        if self.branches[b].model.is_some() {
            return Ok(());
        }
        let br = &self.branches[b];
        let (model, coefs, _) =
            crate::synth::objective_model(&br.problem, &self.rules, &self.synth_opts)?;
        let groups = hint_groups(&model, &br.problem);
        let br = &mut self.branches[b];
        br.groups = groups;
        br.model = Some((model, coefs));
        Ok(())
    }

    /// The integer numerator choice `b`'s engine must reach (its own
    /// variable terms; the constant ones are the choice's); `None` when no
    /// layout of this choice reaches the quality asked for.
    pub(super) fn branch_target(&self, model: &Model, coefs: &[i64]) -> Option<i64> {
        let t = Totals::of(model, coefs);
        match self.opts.quality {
            Quality::Optimum => {
                let (whole, _) = self.target?;
                let k = whole - t.constant;
                (k <= t.variable).then_some(k)
            }
            // Some object can never keep some rule: look no further.
            Quality::AllRules => (!t.impossible).then_some(t.variable),
            Quality::MinScore(x) => {
                // Conservative: the integer weights are rounded (at most
                // half a unit each), so a layout with score ≥ x has at least
                // this integer numerator; the evaluator decides exactly.
                let total = (t.variable + t.constant) as f64;
                let n = model.soft.len() as f64;
                let k = (x * total - n).ceil() as i64 - t.constant;
                Some(k.max(0))
            }
        }
    }

    /// Build choice `b`'s engine with "objective ≥ target", or mark the
    /// choice done when none of its layouts can reach the target.
    /// `Ok(false)`: the time limit struck while it was built.
    pub(super) fn start_engine(&mut self, b: usize) -> Result<bool, SynthError> {
        self.build_model(b)?;
        let (model, coefs) = self.branches[b].model.as_ref().expect("built");
        let target = match self.branch_target(model, coefs) {
            Some(t) if model.too_large.is_empty() => t,
            _ => {
                self.branches[b].done = true;
                return Ok(true);
            }
        };
        let Some(mut engine) = crate::synth::backend::load(
            model,
            self.opts.seed,
            false,
            Some(coefs),
            &[],
            &Stop::never().by(self.opts.stop.deadline()),
        )?
        else {
            return Ok(false);
        };
        if target > 0 {
            engine.add(Fact::ObjectiveAtLeast(target));
        }
        // The greedy first phase would put every layout bottom-left.
        engine.found_first();
        if self.opts.repair == Repair::Random {
            engine.random_search();
        }
        self.branches[b].engine = Some(engine);
        Ok(true)
    }

    /// The like tables: positions per class and footprint.
    pub(super) fn tables(&mut self) {
        let Some((model, _)) = self.branches[0].model.as_ref() else {
            return;
        };
        let (ox, oy) = model.origin;
        let g = model.grid;
        for s in &self.opts.like {
            for o in s.objects.iter().filter(|o| !o.fixed) {
                let (Some(x), Some(y)) = (o.x, o.y) else {
                    continue;
                };
                if (x - ox) % g == 0 && (y - oy) % g == 0 {
                    self.like
                        .entry(like_key(o))
                        .or_default()
                        .push(((x - ox) / g, (y - oy) / g));
                }
            }
        }
    }

    /// A random hint for choice `b`: every movable object at a random grid
    /// position (interchangeable objects' positions sorted into the
    /// symmetry order), objects in a random order.
    pub(super) fn hint(&mut self, b: usize) -> Vec<(usize, i64)> {
        let br = &self.branches[b];
        let Some((model, _)) = br.model.as_ref() else {
            return Vec::new();
        };
        let mut per_object: Vec<[(usize, i64); 2]> = Vec::new();
        for group in &br.groups {
            let o = &br.problem.objects[model.vars[group[0]].object];
            let like = self.like.get(&like_key(o));
            // The y variable of an object follows its x variable.
            let (ux, uy) = (model.vars[group[0]].ub, model.vars[group[0] + 1].ub);
            let mut pos: Vec<(i64, i64)> = (0..group.len())
                .map(|_| match like {
                    Some(l) if !l.is_empty() && self.rng.random_bool(0.5) => {
                        l[self.rng.random_range(0..l.len())]
                    }
                    _ => (self.rng.random_range(0..=ux), self.rng.random_range(0..=uy)),
                })
                .collect();
            pos.sort_by_key(|&(x, y)| (y, x));
            for (&vx, (x, y)) in group.iter().zip(pos) {
                per_object.push([(vx, x), (vx + 1, y)]);
            }
        }
        per_object.shuffle(&mut self.rng);
        per_object.into_iter().flatten().collect()
    }

    /// The next layout of choice `b` (its engine started): `Ok(None)` when
    /// the choice has no further layout.
    pub(super) fn draw(&mut self, b: usize) -> Result<Option<Scene>, SampleError> {
        loop {
            let limits = self.limits(b);
            let hint = self.hint(b);
            let Some(engine) = self.branches[b].engine.as_mut() else {
                return Ok(None);
            };
            engine.hint_in_order(&hint);
            match engine.solve(&[], &limits) {
                Verdict::Solution(v) => {
                    engine.exclude(&v);
                    let scene = self.layout(b, &v);
                    if let Some(x) = self.min_score {
                        let e = evaluate(&scene, &self.rules, self.opts.contact);
                        // The engine's bound is conservative; the evaluator
                        // decides (with a rounding tolerance).
                        if e.score < x - 1e-9 {
                            self.skipped += 1;
                            continue;
                        }
                    }
                    return Ok(Some(scene));
                }
                Verdict::Infeasible(_) => return Ok(None),
                Verdict::Unknown => {
                    return Err(SampleError::LimitReached { found: self.found });
                }
            }
        }
    }
}

/// The integer objective's parts in one model.
pub(super) struct Totals {
    /// The coefficients of the terms the layout decides.
    pub(super) variable: i64,
    /// The coefficients of the terms true in every layout.
    pub(super) constant: i64,
    /// Some term is false in every layout.
    pub(super) impossible: bool,
}

impl Totals {
    pub(super) fn of(model: &Model, coefs: &[i64]) -> Totals {
        let sum = |keep: &dyn Fn(Lit) -> bool| -> i64 {
            (model.soft.iter().zip(coefs))
                .filter(|(t, _)| keep(t.lit))
                .map(|(_, &c)| c)
                .sum()
        };
        Totals {
            variable: sum(&|l| matches!(l, Lit::Var { .. })),
            constant: sum(&|l| l == Lit::TRUE),
            impossible: model.soft.iter().any(|t| t.lit == Lit::FALSE),
        }
    }
}

/// The hint groups of a model: interchangeable unplaced objects (one class
/// and footprint), their x variables in the symmetry order.
fn hint_groups(model: &Model, problem: &Scene) -> Vec<Vec<usize>> {
    let mut groups: BTreeMap<(String, i64, i64), Vec<usize>> = BTreeMap::new();
    for (i, o) in problem.objects.iter().enumerate() {
        if let (Coord::Var(vx), Coord::Var(_)) = model.coords[i] {
            groups.entry(like_key(o)).or_default().push(vx);
        }
    }
    groups.into_values().collect()
}

/// The grid value of every variable of `model` in `scene` (a complete
/// scene of the problem the model was built for).
pub fn grid_values(model: &Model, scene: &Scene) -> Vec<i64> {
    let (ox, oy) = model.origin;
    model
        .vars
        .iter()
        .map(|v| {
            let o = &scene.objects[v.object];
            match v.axis {
                crate::relations::Axis::X => (o.x.unwrap_or(ox) - ox) / model.grid,
                crate::relations::Axis::Y => (o.y.unwrap_or(oy) - oy) / model.grid,
            }
        })
        .collect()
}
