//! Synthesis (docs/guide.md#synthesis): place every unplaced object on the grid so that hard
//! rules hold and the numerator is as large as possible.
//!
//! This file fixes the public API ([`synthesize`], its options and result,
//! [`verify_solution`], the [`emit`]ted model); the rest lives in private
//! submodules:
//!
//! - `model` — the solver-free model (variables, exact Boolean
//!   definitions, clauses, hard literals, objective terms);
//! - `backend` — the seam: what an engine must answer (solve under
//!   assumptions with limits, facts, root bounds);
//! - `driver` — every procedure as calls to a backend: maximise the
//!   score, minimise the resemblance cost, shrink a conflict;
//! - `engine` — the Pumpkin backend (the only module naming solver types);
//! - `lns` — large-neighbourhood search for the anytime phase on large
//!   problems;
//! - [`emit`] — the model written out for other solvers (MiniZinc, JSON);
//! - `verify` ([`verify_solution`]), `brute_force` — the independent
//!   checker (run on every output) and the exhaustive reference of the
//!   tests;
//! - `weights`, `resemblance_terms`, `warm`, `capacity` — integer objective weights, the second
//!   objective's terms, the warm start, the area test before any engine.
//!
//! # Second-edition rules (docs/language.md)
//!
//! Quantified atoms, landmarks and scene-level rules are compiled by
//! `model` into the same kind of literals as first-edition rules, so
//! everything downstream treats them alike:
//!
//! - a soft scene-level rule (`some A: φ`, `no A: φ`, `at least K A: φ`,
//!   `at most K A: φ`) is **one** objective term `w·[holds]`
//!   (`SoftTerm::object` is `None`), exactly the docs/language.md#scene-rules score;
//! - a hard scene-level rule is one hard literal; under core extraction it
//!   has one assumption like every hard rule;
//! - an infeasibility [`Conflict`] names hard **rules**, never objects. A
//!   scene-level rule in a core is named like any other (its name only: the
//!   rule is about the scene, so there is no object to blame, and listing
//!   every subject would say nothing more than the rule's subject class);
//! - the reported [`Evaluation`](crate::eval::Evaluation) is the evaluator's, so a scene-level rule's
//!   entry has `subjects = 1` and `satisfied` 0 or 1, plus its `scene`
//!   counts; first-edition rule sets report exactly as before;
//! - a landmark `@ID` that names no fixed object of the problem (a movable
//!   object, or none) is an empty target, as in the evaluator: the default
//!   quantifier decides (`DR` true; `EC`, `FL`, `AL` false). The command
//!   line rejects such rules before synthesis (docs/language.md#landmarks).

use crate::relations::Contact;
use crate::resemblance::ResemblanceTarget;
use crate::rules::RuleSet;
use crate::scene::Scene;
use crate::stop::Stop;
use std::sync::Arc;
use std::time::Duration;

pub(crate) mod backend;
// The exhaustive reference solver: a test oracle (and the uniformity
// reference of `rccpack-bench sample`, in the bench crate), not an API.
#[doc(hidden)]
pub mod brute_force;
mod capacity;
mod driver;
pub mod emit;
mod engine;
mod explain;
mod lns;
// The solver-free model: internal, visible to the crate's own differential
// and emit tests (feature `fuzzing`).
#[cfg(feature = "fuzzing")]
#[doc(hidden)]
pub mod model;
#[cfg(not(feature = "fuzzing"))]
pub(crate) mod model;
pub mod report;
mod resemblance_terms;
mod result;
mod solve;
mod tuning;
mod turns;
mod verify;
mod warm;
mod weights;

pub use driver::Strategy;
pub use lns::LnsOptions;
pub use result::{Conflict, Resemblance, SolveStats, Status, SynthResult};
#[doc(hidden)]
pub use tuning::{NoOverlap, Tuning, TuningError};
pub use turns::MAX_ORIENTATION_CHOICES;
pub use verify::{verify_solution, VerifyError};

/// Limits and switches for one solve.
#[derive(Debug, Clone)]
pub struct SynthOptions {
    /// How EC decides that two sides touch.
    pub contact: Contact,
    /// When to stop and return the best layout found: the deadline, the
    /// cancel flag (e.g. set from a Ctrl-C handler) and the budget of
    /// search nodes (decisions) of this solve. A deadline is a moment, not
    /// a duration: options kept for a later solve need a fresh
    /// [`Stop::after`].
    pub stop: Stop,
    /// Seed for any randomised choice; same seed and limits → same layout.
    pub seed: u64,
    /// Break symmetry between interchangeable objects (same class and size).
    pub symmetry_breaking: bool,
    /// Post redundant area reasoning.
    pub redundant: bool,
    /// The optimisation procedure (see [`Strategy`]).
    pub strategy: Strategy,
    /// Called with every improving layout (e.g. to print progress).
    pub progress: Option<ProgressFn>,
    /// The second objective (docs/guide.md#layouts-like-the-demonstrations): among the layouts with the best
    /// score, one most like these positions (`synth --like`).
    pub like: Option<ResemblanceTarget>,
    /// On an infeasible problem, name a minimal conflicting set of hard
    /// rules ([`SynthResult::conflict`]); off, the result says only
    /// `infeasible` (a probe needs no more, and the shrinking costs one solve
    /// per hard rule).
    pub explain: bool,
    /// Large-neighbourhood search before the proof (see `lns`), on
    /// problems with at least [`lns::LnsOptions::min_objects`] movable
    /// objects; `None`: the engine's own search only.
    pub lns: Option<lns::LnsOptions>,
    /// Complete scenes whose placements hint at a good first layout (usually
    /// the demonstrations): objects of the problem are matched to their
    /// objects by class and size, and the layout assembled from them (then
    /// repaired) is the search's first incumbent when it is valid. A hint
    /// never changes the optimum, only the time to reach it; an unusable
    /// hint is ignored. Empty: no warm start.
    pub warm_start: Vec<Scene>,
    /// Engine tuning: never changes the answer (doc-hidden, see
    /// [`Tuning`]); the library never fills it from the environment.
    #[doc(hidden)]
    pub tuning: Tuning,
}

/// An improving layout found during the search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Its score (from the evaluator).
    pub score: f64,
    /// Time since the solve started.
    pub elapsed: Duration,
}

/// A progress callback.
#[derive(Clone)]
pub struct ProgressFn(pub Arc<dyn Fn(&Progress) + Send + Sync>);

impl std::fmt::Debug for ProgressFn {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ProgressFn")
    }
}

impl Default for SynthOptions {
    fn default() -> Self {
        SynthOptions {
            contact: Contact::Point,
            stop: Stop::never(),
            seed: 0,
            symmetry_breaking: true,
            redundant: true,
            strategy: Strategy::default(),
            progress: None,
            like: None,
            explain: true,
            lns: Some(lns::LnsOptions::default()),
            warm_start: Vec::new(),
            tuning: Tuning::default(),
        }
    }
}

/// Why synthesis refused to start (infeasibility is a [`Status`], not an
/// error).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SynthError {
    /// The problem is not a valid scene (docs/scenes.md#geometry); the error names the field.
    #[error(transparent)]
    Scene(#[from] crate::scene::SceneError),
    /// A rule built in code has a weight that is not a finite positive
    /// number (the parser never makes one).
    #[error("rule `{rule}` has weight {weight}; expected a finite number greater than 0")]
    BadWeight {
        /// The rule's name.
        rule: String,
        /// Its weight, as written by `{}` on `f64`.
        weight: String,
    },
    /// The resemblance target cannot be built for this problem.
    #[error(transparent)]
    Resemblance(#[from] crate::resemblance::ResemblanceError),
    /// A number of the problem (or derived from it) is too large for the
    /// solver's 32-bit arithmetic; the message names it.
    #[error("{0}")]
    TooLarge(String),
    /// The rules' weights, divided by their common factor, still total
    /// more than the solver's objective can hold (a fault of the rule
    /// file, not of the problem).
    #[error("the rule weights are too large for the solver: divided by their common factor, the weights of all (object, rule) terms total more than 2^30; expected smaller weights")]
    WeightsTooLarge,
    /// What was asked is not built yet for this problem; the message says
    /// what.
    #[error("{0}")]
    Unsupported(String),
    /// The layout the engine found fails the independent check
    /// ([`verify_solution`]): a bug in rccpack, never the input's fault.
    #[error("internal error: the layout found fails the independent check: {0}")]
    Unverified(VerifyError),
}

/// Largest absolute coordinate or size accepted for synthesis (2^28); the
/// space's far edges `space.x + width`, `space.y + height` too.
///
/// # Why every number handed to Pumpkin fits in `i32`
///
/// Pumpkin works in `i32` (2^31 − 1). With every coordinate, size and grid
/// step within ±2^28 and both edges of the space within ±2^28 (so every
/// edge of a placed object too, as it lies inside the space):
///
/// - grid variables have domains `0..=ub` with `ub ≤ space.width ≤ 2^28`;
///   `Ge` bounds `k` lie in `1..=ub`;
/// - a `DiffGe` literal `b − a ≤ −k` has two unit terms and a bound folded
///   into `(−ub_b, ub_a]`: `|b| + |a| + |k| ≤ 3·2^28`;
/// - the cumulative views `grid·v + origin` stay inside the space (±2^28),
///   `start + duration ≤ space.x + width ≤ 2^28`; the sum of all demands is
///   checked when the model is built, and the (redundant) constraint is
///   left out when it could exceed `i32`;
/// - the symmetry order `nx·gy_a + gx_a < nx·gy_b + gx_b` is posted as a
///   linear only when `Σ |coef|·ub + |rhs|` fits, else as the equivalent
///   lexicographic clauses over `DiffGe` literals (no products);
/// - objective coefficients sum to at most 2^30 (`weights`), and `AtLeast`
///   bounds are at most the number of objects.
///
/// The engine still converts every value with a checked conversion
/// ([`SynthError::TooLarge`] if one ever failed), so a mistake in this
/// argument is an error, never a panic or a wrapped number.
pub const MAX_SYNTH_COORD: i64 = 1 << 28;

/// Most grid positions an unplaced object may have along one axis,
/// `(space size − object size) / grid + 1` (2^18 = 262 144).
///
/// Bound propagation over differences of grid variables can converge one
/// step at a time across a whole domain (e.g. `a ≥ b + 5` and `b ≥ a − 3`
/// learned as a conflict only after `ub/2` rounds), and Pumpkin does not
/// stop inside propagation, so this is what bounds the time and memory of
/// one propagation (a fuzzed 54×2^28 space with grid 5 took gigabytes).
pub const MAX_POSITIONS: i64 = 1 << 18;

/// Whether `problem` is usable for synthesis: a valid scene (docs/scenes.md#geometry) whose
/// numbers are within the solver's bounds ([`MAX_SYNTH_COORD`],
/// [`MAX_POSITIONS`]). [`synthesize`] checks this first; callers that build
/// `model::Model`s themselves must too.
pub(crate) fn check_problem(problem: &Scene) -> Result<(), SynthError> {
    problem.validate_oriented()?;
    check_ranges(problem)
}

/// Whether the rules relate few enough pairs of `problem`'s objects for a
/// model to fit in memory ([`model::MAX_PAIR_LITERALS`]), counting every
/// form of rule (per object, scene-level, group statements). Checked
/// before anything is built, by [`synthesize`] and by every caller that
/// builds a `model::Model` from user rules.
pub(crate) fn check_pairs(problem: &Scene, rules: &RuleSet) -> Result<(), SynthError> {
    let pairs = model::Model::pair_literals(problem, rules);
    if pairs > model::MAX_PAIR_LITERALS {
        return Err(SynthError::TooLarge(format!(
            "the rules relate {pairs} pairs of objects (subject objects × target objects, summed over the rules' relations; \
             a group statement: pairs of its class's objects × its shape's relations), \
             more than the {} the solver can hold in memory; expected fewer objects, or rules about a landmark or a smaller class",
            model::MAX_PAIR_LITERALS
        )));
    }
    Ok(())
}

fn check_ranges(problem: &Scene) -> Result<(), SynthError> {
    let sp = problem.space;
    let mut vals: Vec<(String, i64)> = vec![
        ("space.x".into(), sp.x),
        ("space.y".into(), sp.y),
        ("space.width".into(), sp.width),
        ("space.height".into(), sp.height),
        ("grid".into(), problem.grid),
    ];
    for (i, o) in problem.objects.iter().enumerate() {
        vals.push((format!("objects[{i}].width"), o.width));
        vals.push((format!("objects[{i}].height"), o.height));
        if let Some(x) = o.x {
            vals.push((format!("objects[{i}].x"), x));
        }
        if let Some(y) = o.y {
            vals.push((format!("objects[{i}].y"), y));
        }
    }
    let max = MAX_SYNTH_COORD.unsigned_abs();
    for (what, v) in vals {
        // `unsigned_abs`: `i64::MIN.abs()` would wrap and pass.
        if v.unsigned_abs() > max {
            return Err(SynthError::TooLarge(format!(
                "{what} = {v} is too large for synthesis; expected at most {MAX_SYNTH_COORD} in absolute value"
            )));
        }
    }
    for (axis, corner, size) in [("x", sp.x, sp.width), ("y", sp.y, sp.height)] {
        let far = corner.saturating_add(size);
        if far.unsigned_abs() > max {
            return Err(SynthError::TooLarge(format!(
                "the space reaches {axis} = {far} (space.{axis} + size), too far for synthesis; expected at most {MAX_SYNTH_COORD} in absolute value"
            )));
        }
    }
    for (i, o) in problem.objects.iter().enumerate() {
        if o.is_placed() {
            continue;
        }
        // A turnable object may lie either way: its smaller side along an
        // axis gives the most positions.
        let (w, h) = if o.turnable {
            let m = o.width.min(o.height);
            (m, m)
        } else {
            o.footprint()
        };
        for (axis, space, size) in [("x", sp.width, w), ("y", sp.height, h)] {
            // Within ±2^28 (checked above): no overflow.
            let n = if space < size {
                0
            } else {
                (space - size) / problem.grid + 1
            };
            if n > MAX_POSITIONS {
                return Err(SynthError::TooLarge(format!(
                    "objects[{i}] `{}` has {n} grid positions along {axis}, too many for synthesis; expected at most {MAX_POSITIONS} (use a coarser grid or a smaller space)",
                    o.id
                )));
            }
        }
    }
    Ok(())
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

/// The model [`synthesize`] solves for `problem` under `rules` and `opts`
/// (checked first), its integer objective coefficients (one per soft term)
/// and the options it was built with. Shared with [`emit`], so that the
/// emitted model is the solved one. (An object too large for the space
/// gives a model with `too_large` set and no rules.)
pub(crate) fn objective_model(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
) -> Result<(model::Model, Vec<i64>, model::BuildOptions), SynthError> {
    Ok(objective_model_until(problem, rules, opts, &|| false)?.expect("never stopped"))
}

/// [`objective_model`], given up (`Ok(None)`) once `stop` says so while
/// the model is built.
pub(crate) fn objective_model_until(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
    stop: &dyn Fn() -> bool,
) -> Result<Option<(model::Model, Vec<i64>, model::BuildOptions)>, SynthError> {
    objective_model_encoded(
        problem,
        rules,
        opts,
        stop,
        model::Encoding::of(&opts.tuning),
    )
}

/// [`objective_model_until`] with the encoding chosen by the caller.
pub(crate) fn objective_model_encoded(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
    stop: &dyn Fn() -> bool,
    encoding: model::Encoding,
) -> Result<Option<(model::Model, Vec<i64>, model::BuildOptions)>, SynthError> {
    check_problem(problem)?;
    check_pairs(problem, rules)?;
    let build = model::BuildOptions {
        contact: opts.contact,
        rules: true,
        symmetry_breaking: opts.symmetry_breaking,
        redundant: opts.redundant,
        tuning: opts.tuning,
    };
    let Some(model) = model::Model::build_encoded(problem, rules, build, stop, encoding) else {
        return Ok(None);
    };
    // Weights from the parser are finite and positive; a rule built in code
    // may carry anything, and NaN would silently become a coefficient of 1.
    if let Some(s) = model
        .soft
        .iter()
        .find(|s| !(s.weight.is_finite() && s.weight > 0.0))
    {
        let name = rules.rules.get(s.rule).map_or("?", |r| r.name.as_str());
        return Err(SynthError::BadWeight {
            rule: name.to_string(),
            weight: crate::limits::number(s.weight),
        });
    }
    let weights: Vec<f64> = model.soft.iter().map(|s| s.weight).collect();
    let coefs = weights::integer_weights(&weights).ok_or(SynthError::WeightsTooLarge)?;
    Ok(Some((model, coefs, build)))
}
/// Synthesise a layout (docs/guide.md#synthesis): place every unplaced object on the grid,
/// inside the space, without overlap, so that every hard rule holds and the
/// numerator over all objects is maximal.
///
/// The returned score is the evaluator's, recomputed from the output scene.
/// Errors are reserved for unusable input; infeasibility is a [`Status`].
///
/// Unplaced objects marked `turnable` may lie turned in the layout
/// (docs/guide.md#objects-that-turn): the model has an orientation
/// variable per such object, so `optimal` and `infeasible` hold over every
/// orientation. With a second objective (`like`), whose costs assume each
/// object's footprint, every orientation choice is solved in turn instead
/// (at most [`MAX_ORIENTATION_CHOICES`]).
pub fn synthesize(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
) -> Result<SynthResult, SynthError> {
    // The problem as given: an unplaced object may not lie turned yet.
    problem.validate()?;
    let groups = turns::turn_groups(problem);
    if groups.is_empty() {
        synthesize_fixed(problem, rules, opts)
    } else if turns::enumerate(opts) {
        turns::synthesize_turning(problem, rules, opts, &groups)
    } else {
        turns::synthesize_model(problem, rules, opts, &groups)
    }
}

/// [`synthesize`] on the one model of `problem`: an unplaced object lies
/// turned when `turned` is set, and may turn (an orientation variable)
/// when it is `turnable`, oblong and not `turned`.
fn synthesize_fixed(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
) -> Result<SynthResult, SynthError> {
    let start = std::time::Instant::now();
    let limits = opts.stop.clone();
    let mut stats = SolveStats::default();
    // The deadline and Ctrl-C are checked while the model is built.
    let Some((model, coefs, build)) =
        objective_model_until(problem, rules, opts, &|| limits.expired())?
    else {
        stats.time_ms = ms(start.elapsed());
        return Ok(SynthResult::without_layout(Status::Unknown, None, stats));
    };
    if let Some(r) = capacity::infeasible_at_once(problem, opts) {
        return Ok(r);
    }
    let s = solve::Solve {
        problem,
        rules,
        opts,
        model: &model,
        coefs: &coefs,
        build,
        limits: &limits,
        start,
    };
    if !model.too_large.is_empty() {
        let conflict = Conflict {
            objects_cannot_fit: true,
            ..Conflict::default()
        };
        return Ok(s.without_layout(Status::Infeasible, Some(conflict), stats));
    }
    // The engine refuses costs past its 32-bit arithmetic.
    let resemblance_terms = (opts.like.as_ref())
        .map(|like| resemblance_terms::resemblance_terms(&model, problem, like))
        .transpose()?;
    let Some(mut engine) = s.post_engine(resemblance_terms.as_deref())? else {
        // The time limit struck while the model was being posted.
        return Ok(s.without_layout(Status::Unknown, None, stats));
    };
    let ws: Vec<i64> = engine.objective_coefs().unwrap_or(&[]).to_vec();
    let value = |v: &[i64]| model.objective_value(&coefs, v);
    let objective = driver::Objective {
        coefs: &ws,
        value: &value,
    };
    let (mut first, mut best) = (None, None);
    let mut on_incumbent = |vals: &[i64]| s.found(vals, &mut first, &mut best);
    let mut outcome = s.maximise_score(&mut engine, &objective, &mut stats, &mut on_incumbent)?;
    let resemblance = match (&opts.like, &resemblance_terms) {
        (Some(like), Some(terms)) => s.minimise_resemblance(
            &mut engine,
            &objective,
            like,
            terms,
            &mut outcome,
            &mut on_incumbent,
        ),
        _ => None,
    };
    stats.nodes += engine.nodes();
    stats.conflicts += engine.conflicts();
    stats.time_to_first_ms = first.map(ms);
    stats.time_to_best_ms = best.map(ms);
    let score_bound = backend::Backend::objective_bound(&engine).map(|b| s.score_bound(b));
    drop(engine);
    s.report(outcome, stats, resemblance, score_bound)
}
