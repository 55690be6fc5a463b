//! The phases of one solve ([`super::synthesize`]) of a built model: the
//! engine posted under the limits, the score maximised (by the engine
//! alone, or alternating with large-neighbourhood search), the resemblance
//! cost minimised with the score held, and the layout checked and
//! reported.

use super::backend::{Backend, Stop};
use super::driver::{self, Objective, OptOutcome};
use super::engine::Engine;
use super::model::{BuildOptions, Lit, Model};
use super::resemblance_terms::{self, ResemblanceTerm};
use super::SynthResult;
use super::{lns, ms, verify, warm};
use super::{Conflict, Progress, Resemblance, SolveStats, Status, SynthError, SynthOptions};
use crate::resemblance::ResemblanceTarget;
use crate::rules::RuleSet;
use crate::scene::Scene;
use std::time::{Duration, Instant};

/// One solve of a built model: what every phase reads.
pub(super) struct Solve<'a> {
    /// The problem being solved.
    pub(super) problem: &'a Scene,
    /// Its rules.
    pub(super) rules: &'a RuleSet,
    /// The caller's options.
    pub(super) opts: &'a SynthOptions,
    /// The model of `problem` under `rules`.
    pub(super) model: &'a Model,
    /// Integer objective coefficients, one per soft term.
    pub(super) coefs: &'a [i64],
    /// The options `model` was built with.
    pub(super) build: BuildOptions,
    /// The solve's limits.
    pub(super) limits: &'a Stop,
    /// When the solve started.
    pub(super) start: Instant,
}

impl Solve<'_> {
    /// A result without a layout, its time stamped now.
    pub(super) fn without_layout(
        &self,
        status: Status,
        conflict: Option<Conflict>,
        mut stats: SolveStats,
    ) -> SynthResult {
        stats.time_ms = ms(self.start.elapsed());
        SynthResult::without_layout(status, conflict, stats)
    }

    /// Record an improving layout: the times of the first and the best,
    /// and the progress callback with its score.
    pub(super) fn found(
        &self,
        vals: &[i64],
        first: &mut Option<Duration>,
        best: &mut Option<Duration>,
    ) {
        let t = self.start.elapsed();
        first.get_or_insert(t);
        *best = Some(t);
        if let Some(p) = &self.opts.progress {
            let s = self.model.scene(self.problem, vals);
            let e = crate::eval::evaluate(&s, self.rules, self.opts.contact);
            (p.0)(&Progress {
                score: e.score,
                elapsed: t,
            });
        }
    }

    /// The engine holding the model and the resemblance terms (`None`: the
    /// limits struck while the model was posted).
    pub(super) fn post_engine(
        &self,
        terms: Option<&[ResemblanceTerm]>,
    ) -> Result<Option<Engine>, SynthError> {
        let t_model = self.start.elapsed();
        let Some(engine) = Engine::with_resemblance_stop(
            self.model,
            self.opts.seed,
            false,
            Some(self.coefs),
            terms.unwrap_or(&[]),
            self.limits,
        )?
        else {
            return Ok(None);
        };
        log::debug!(
            "model {:.1} ms ({} vars, {} bools, {} clauses), engine {:.1} ms",
            ms(t_model),
            self.model.vars.len(),
            self.model.bools.len(),
            self.model.clauses.len(),
            ms(self.start.elapsed() - t_model)
        );
        Ok(Some(engine))
    }

    /// The first phase: a first layout (from the warm start's hint when
    /// there is one), then the score maximised from it.
    pub(super) fn maximise_score(
        &self,
        engine: &mut Engine,
        objective: &Objective<'_>,
        stats: &mut SolveStats,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> Result<OptOutcome, SynthError> {
        let hint = warm::hint_values(self.model, self.problem, &self.opts.warm_start);
        if let Some(h) = &hint {
            engine.hint(h);
        }
        let first = match driver::first_solution(engine, self.limits) {
            Err(o) => return Ok(o),
            Ok(first) => first,
        };
        on_incumbent(&first);
        let movable = self.model.vars.iter().filter(|v| !v.turn).count() / 2;
        match self.opts.lns.filter(|l| movable >= l.min_objects) {
            Some(lopts) => {
                let search = lns::Lns {
                    problem: self.problem,
                    rules: self.rules,
                    model: self.model,
                    build: self.build,
                    coefs: self.coefs,
                    opts: lopts,
                    seed: self.opts.seed,
                    long_first_phase: hint.is_none() && movable >= 16,
                };
                self.alternate(engine, objective, &search, first, stats, on_incumbent)
            }
            None => Ok(driver::optimise_from(
                engine,
                Some(objective),
                first,
                self.limits,
                self.opts.strategy,
                on_incumbent,
            )),
        }
    }

    /// Large-neighbourhood search alternating with the engine's proof
    /// attempts; the sub-engines' work counts toward the statistics.
    fn alternate(
        &self,
        engine: &mut Engine,
        objective: &Objective<'_>,
        search: &lns::Lns<'_>,
        first: Vec<i64>,
        stats: &mut SolveStats,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> Result<OptOutcome, SynthError> {
        let (outcome, r) = search.alternate(
            engine,
            objective,
            first,
            self.limits,
            self.opts.strategy,
            on_incumbent,
        )?;
        stats.nodes += r.nodes;
        stats.conflicts += r.conflicts;
        log::debug!(
            "lns: {} rounds, {} improving, {} nodes; engine {} nodes; {:.1} ms",
            r.rounds,
            r.improved,
            r.nodes,
            engine.nodes(),
            ms(self.start.elapsed())
        );
        Ok(outcome)
    }

    /// The second phase: with the numerator held, the cheapest layout
    /// (the layout in `outcome` replaced by it). `None` without a layout.
    pub(super) fn minimise_resemblance(
        &self,
        engine: &mut Engine,
        objective: &Objective<'_>,
        like: &ResemblanceTarget,
        terms: &[ResemblanceTerm],
        outcome: &mut OptOutcome,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) -> Option<Resemblance> {
        let (OptOutcome::Optimal(v) | OptOutcome::Feasible(v)) = outcome else {
            return None;
        };
        let cost = |v: &[i64]| resemblance_terms::total_cost(terms, v);
        let r = driver::minimise_cost(
            engine,
            Some(objective),
            &cost,
            std::mem::take(v),
            self.limits,
            on_incumbent,
        );
        debug_assert_eq!(r.cost, resemblance_terms::total_cost(terms, &r.values));
        *v = r.values;
        let cost = like.cost(self.problem, &self.model.scene(self.problem, v));
        debug_assert_eq!(cost, r.cost);
        Some(Resemblance {
            cost,
            proven: r.proven,
            bound: r.bound,
        })
    }

    /// The score bound of the engine's proven objective bound `b`.
    pub(super) fn score_bound(&self, b: i64) -> f64 {
        let constant: i64 = self
            .model
            .soft
            .iter()
            .zip(self.coefs)
            .filter(|(t, _)| t.lit == Lit::TRUE)
            .map(|(_, &c)| c)
            .sum();
        let total: i64 = self.coefs.iter().sum();
        if total <= 0 {
            1.0
        } else {
            (b.saturating_add(constant) as f64 / total as f64).min(1.0)
        }
    }

    /// The result of the search's outcome: the layout evaluated and
    /// independently checked, or why there is none (with the conflict
    /// explained when asked for).
    pub(super) fn report(
        &self,
        outcome: OptOutcome,
        mut stats: SolveStats,
        resemblance: Option<Resemblance>,
        score_bound: Option<f64>,
    ) -> Result<SynthResult, SynthError> {
        let (status, vals) = match outcome {
            OptOutcome::Optimal(v) => (Status::Optimal, v),
            OptOutcome::Feasible(v) => (Status::Feasible, v),
            OptOutcome::Unknown => return Ok(self.without_layout(Status::Unknown, None, stats)),
            OptOutcome::Infeasible if !self.opts.explain => {
                return Ok(self.without_layout(Status::Infeasible, None, stats));
            }
            OptOutcome::Infeasible => {
                let conflict = super::explain::explain(
                    self.problem,
                    self.rules,
                    self.opts,
                    self.limits,
                    &mut stats,
                )?;
                return Ok(self.without_layout(Status::Infeasible, Some(conflict), stats));
            }
        };
        let scene = self.model.scene(self.problem, &vals);
        let evaluation = crate::eval::evaluate(&scene, self.rules, self.opts.contact);
        // Every layout is re-checked, in release builds too: a fault here is a
        // bug, reported as one instead of handed to the robot.
        verify::verify_solution(self.problem, &scene, self.rules, self.opts.contact)
            .map_err(SynthError::Unverified)?;
        stats.time_ms = ms(self.start.elapsed());
        let score_bound = match status {
            Status::Optimal => Some(evaluation.score),
            _ => score_bound.map(|b| b.max(evaluation.score)),
        };
        Ok(SynthResult {
            status,
            scene: Some(scene),
            evaluation: Some(evaluation),
            conflict: None,
            stats,
            resemblance,
            score_bound,
        })
    }
}
