//! Sampling many distinct layouts that keep the rules (docs/guide.md#sampling): for
//! property tests, fuzzing and data.
//!
//! # What is drawn
//!
//! [`sample`] returns a [`Sampler`], an iterator of complete scenes of one
//! problem. Every scene is valid in the docs/guide.md#synthesis sense (on the grid, inside
//! the space, no overlap, fixed and already-placed objects unmoved, every
//! hard rule kept) and meets the [`Quality`] asked for: the optimum score
//! (default), score 1 ([`Quality::AllRules`]) or at least a given score
//! ([`Quality::MinScore`]). No two scenes are the same layout, where two
//! layouts that differ only by swapping interchangeable objects (unplaced,
//! same class and size) count as one ([`canonical_key`]).
//!
//! # How
//!
//! One Pumpkin engine holds the synthesis model with symmetry breaking (so
//! every layout has exactly one assignment: interchangeable objects are
//! ordered by position) and the hard constraint "objective ≥ target". For
//! each layout the engine is given a random *hint*: every movable object a
//! grid position drawn uniformly (with `like` scenes, half of the time a
//! position such an object has in them), interchangeable objects' positions
//! sorted into the symmetry order, objects tried in a random order. The
//! engine tries the hinted values first and repairs the rest by its usual
//! conflict-driven search ([`Repair::Random`], the default: a random grid
//! variable and a random value of its domain at each decision;
//! [`Repair::Activity`]: the engine's activity-based branching); the layout
//! found is then excluded by a clause
//! ("some variable differs"). When the engine proves that no further layout
//! exists, the iterator ends: every layout of that quality has been
//! returned. A limit (per layout or overall) ends it with
//! [`SampleError::LimitReached`].
//!
//! # Objects that turn
//!
//! Unplaced `turnable` objects (docs/guide.md#objects-that-turn) are
//! grouped by class and size, as synthesis groups them; an *orientation
//! choice* says how many of each group lie turned (at most
//! [`MAX_SAMPLE_ORIENTATIONS`] choices). Each choice has its own engine,
//! built when first drawn from; each layout comes from a choice drawn
//! uniformly (from the seeded generator) among those not yet exhausted, so
//! turned and flat blocks both show up early. A choice whose engine proves
//! it has no further layout is exhausted; when every choice is, every
//! layout has been returned (layouts of different choices differ in some
//! footprint, so they are never the same layout). The optimum is the one
//! [`crate::synth::synthesize`] finds over every orientation.
//!
//! # Distribution
//!
//! The layouts are **not** drawn uniformly. Each one is "the layout the
//! conflict-driven search reaches first from a uniformly random hint,
//! among those not yet returned", so layouts in large open regions of the
//! solution space (far from the others) are likelier early on, and the
//! order depends on what the engine learned. Random repair is measurably
//! closer to uniform than activity-based repair, and 1.5 to 3 times slower.
//! Because found layouts are
//! excluded, the first `k` samples are `k` distinct layouts, and drawing
//! until the end enumerates every layout exactly once. docs/performance.md#sampling
//! reports a chi-square test against uniform on tiny problems enumerated by brute
//! force (`rccpack-bench sample`).
//!
//! # Determinism
//!
//! The engine is single-threaded and every random choice comes from a
//! ChaCha8 generator seeded with [`SampleOptions::seed`], so the same seed
//! and node limits give the same sequence of layouts whatever the number of
//! threads (time limits can cut a run short at a different point).

use crate::relations::Contact;
use crate::rules::RuleSet;
use crate::scene::Scene;
use crate::stop::Stop;
use crate::synth::{Conflict, Status, SynthError, SynthOptions};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::time::Duration;

#[cfg(feature = "arbitrary")]
pub mod arbitrary;
#[cfg(feature = "proptest")]
pub mod strategy;

mod draw;
mod orientations;

// The bench crate's CP-SAT baseline scores peer layouts with it.
#[doc(hidden)]
pub use draw::grid_values;
use draw::Totals;
pub(crate) use orientations::orientation_choices;
pub use orientations::MAX_SAMPLE_ORIENTATIONS;
use orientations::{orientation_branches, Branch};

/// Which layouts count as good enough.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Quality {
    /// The optimum score: the numerator that synthesis proves (or at
    /// least the best it found, when a limit stopped it; see
    /// [`Sampler::target_proven`]).
    #[default]
    Optimum,
    /// Score 1: every soft rule kept by every object.
    AllRules,
    /// A score of at least this (0 to 1).
    MinScore(f64),
}

/// Options of [`sample`].
#[derive(Debug, Clone)]
pub struct SampleOptions {
    /// Which layouts to draw.
    pub quality: Quality,
    /// Seed of every random choice (hints, the engine's own).
    pub seed: u64,
    /// How EC decides that two sides touch.
    pub contact: Contact,
    /// A per-layout time budget: stop looking for the next layout after
    /// this long, counted from when the search for it starts.
    pub layout_time_limit: Option<Duration>,
    /// A per-layout node budget: stop looking for the next layout after
    /// this many search decisions (deterministic); also the node budget of
    /// the optimum's solve.
    pub layout_node_limit: Option<u64>,
    /// When to stop the whole run (the optimum included): its deadline and
    /// cancel flag (e.g. set from a Ctrl-C handler). Its node budget is not
    /// used: the per-layout one is [`SampleOptions::layout_node_limit`].
    pub stop: Stop,
    /// Complete scenes (usually the demonstrations): half of the hints put
    /// an object where an object of its class and size is in one of them,
    /// so the layouts lean towards those positions. Also the warm start of
    /// the optimum. Empty: uniform hints only.
    pub like: Vec<Scene>,
    /// How the engine completes a random hint into a layout.
    pub repair: Repair,
    /// Engine tuning of every model (doc-hidden, see
    /// [`crate::synth::Tuning`]).
    #[doc(hidden)]
    pub tuning: crate::synth::Tuning,
}

/// How the engine completes a random hint into a layout (see the module
/// documentation; measured in docs/performance.md#sampling).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Repair {
    /// A random grid variable and a random value at each decision: closer
    /// to uniform.
    #[default]
    Random,
    /// The engine's activity-based branching: faster, further from uniform.
    Activity,
}

impl Default for SampleOptions {
    fn default() -> Self {
        SampleOptions {
            quality: Quality::Optimum,
            seed: 0,
            contact: Contact::Point,
            layout_time_limit: None,
            layout_node_limit: None,
            stop: Stop::never(),
            like: Vec::new(),
            repair: Repair::Random,
            tuning: crate::synth::Tuning::default(),
        }
    }
}

/// Why sampling stopped without a layout, or could not start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SampleError {
    /// The problem or the rules are not usable (as for synthesis).
    #[error(transparent)]
    Synth(#[from] SynthError),
    /// A minimum score outside 0..=1 (or not a number).
    #[error("minimum score {0} is not a number from 0 to 1")]
    BadMinScore(f64),
    /// No layout keeps the hard requirements (docs/guide.md#synthesis).
    #[error("infeasible: no layout keeps every hard requirement")]
    Infeasible(Conflict),
    /// Layouts exist, but none of the quality asked for.
    #[error("no layout {quality}; the best score is {best:.6}")]
    NoLayout {
        /// The quality asked for, in words.
        quality: String,
        /// The best score of any layout (from synthesis).
        best: f64,
    },
    /// A limit stopped the search for the next layout.
    #[error("a limit stopped the search after {found} layouts")]
    LimitReached {
        /// Layouts returned before the limit struck.
        found: usize,
    },
}

/// Draw distinct layouts of `problem` that keep `rules` (see the module
/// documentation). Errors here are bad input only; "no layout" and limits
/// are items of the iterator.
pub fn sample(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SampleOptions,
) -> Result<Sampler, SampleError> {
    if let Quality::MinScore(x) = opts.quality {
        if !(0.0..=1.0).contains(&x) {
            return Err(SampleError::BadMinScore(x));
        }
    }
    problem.validate().map_err(SynthError::from)?;
    let synth_opts = SynthOptions {
        contact: opts.contact,
        seed: opts.seed,
        stop: opts.stop.clone().nodes_at_most(opts.layout_node_limit),
        warm_start: opts.like.clone(),
        tuning: opts.tuning,
        ..SynthOptions::default()
    };
    let (turning, branches) = orientation_branches(problem)?;
    let mut sampler = Sampler {
        problem: problem.clone(),
        rules: rules.clone(),
        opts: SampleOptions {
            // Score at least 1 is score 1: the exact integer bound of
            // `AllRules` instead of the conservative one of `MinScore`.
            quality: match opts.quality {
                Quality::MinScore(x) if x >= 1.0 => Quality::AllRules,
                q => q,
            },
            ..opts.clone()
        },
        synth_opts,
        turning,
        branches,
        rng: ChaCha8Rng::seed_from_u64(opts.seed),
        like: BTreeMap::new(),
        target: None,
        min_score: None,
        found: 0,
        skipped: 0,
        pending: None,
        state: State::Running,
    };
    // The first choice (nothing turned) is built at once: bad rules and
    // weights are errors of `sample` itself.
    sampler.build_model(0)?;
    sampler.prepare()?;
    Ok(sampler)
}

/// How the iterator stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// More layouts may come.
    Running,
    /// The engine proved that no further layout exists: every layout of
    /// the quality asked for has been returned.
    Exhausted,
    /// A limit stopped it (or an error ended it).
    Stopped,
}

/// The iterator of [`sample`]: distinct complete scenes until every layout
/// has been returned ([`State::Exhausted`]) or a limit strikes. Stop it at
/// any time; it is fused.
pub struct Sampler {
    problem: Scene,
    rules: RuleSet,
    opts: SampleOptions,
    synth_opts: SynthOptions,
    /// The groups of interchangeable turnable objects (unplaced, oblong,
    /// one class and size), indices in problem order.
    turning: Vec<Vec<usize>>,
    /// The orientation choices of the turnable objects (one when nothing
    /// turns): each its own model and engine.
    branches: Vec<Branch>,
    rng: ChaCha8Rng,
    /// Per `(class, width, height)`: grid positions in the like scenes.
    like: BTreeMap<(String, i64, i64), Vec<(i64, i64)>>,
    /// The objective every layout reaches (the whole integer objective,
    /// constant terms included, the same in every orientation choice), and
    /// whether it is proven optimal (for [`Quality::Optimum`]).
    target: Option<(i64, bool)>,
    /// [`Quality::MinScore`]: layouts below it are excluded and skipped.
    min_score: Option<f64>,
    found: usize,
    skipped: usize,
    /// An outcome decided before the first call (infeasible, no layout).
    pending: Option<SampleError>,
    state: State,
}

impl std::fmt::Debug for Sampler {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Sampler")
            .field("found", &self.found)
            .field("state", &self.state)
            .finish()
    }
}

impl Sampler {
    /// How the iterator stands (after it ended: why).
    pub fn state(&self) -> State {
        self.state
    }

    /// Layouts returned so far.
    pub fn found(&self) -> usize {
        self.found
    }

    /// [`Quality::MinScore`]: layouts the engine found below the minimum
    /// (excluded, not returned).
    pub fn skipped(&self) -> usize {
        self.skipped
    }

    /// With [`Quality::Optimum`]: whether the target score is proven
    /// optimal (`false`: a limit stopped synthesis, and the layouts score
    /// at least as well as the best layout it found). `None` for the other
    /// qualities.
    pub fn target_proven(&self) -> Option<bool> {
        self.target.map(|(_, p)| p)
    }

    /// The docs/language.md#the-score integer numerator to reach, the hint
    /// tables, and the engine when nothing turns.
    fn prepare(&mut self) -> Result<(), SampleError> {
        self.tables();
        match self.opts.quality {
            Quality::Optimum => {
                let r = crate::synth::synthesize(&self.problem, &self.rules, &self.synth_opts)?;
                match r.status {
                    Status::Infeasible => {
                        self.fail(SampleError::Infeasible(r.conflict.unwrap_or_default()));
                        return Ok(());
                    }
                    Status::Unknown => {
                        self.fail(SampleError::LimitReached { found: 0 });
                        return Ok(());
                    }
                    Status::Optimal | Status::Feasible => {
                        let scene = r.scene.as_ref().expect("a solution has a scene");
                        let b = self.branch_of(scene);
                        self.build_model(b)?;
                        let scene = self.in_branch_order(scene);
                        let (model, coefs) = self.branches[b].model.as_ref().expect("built");
                        let v = model.objective_value(coefs, &grid_values(model, &scene));
                        let whole = v + Totals::of(model, coefs).constant;
                        self.target = Some((whole, r.status == Status::Optimal));
                    }
                }
            }
            Quality::MinScore(x) => self.min_score = Some(x),
            Quality::AllRules => {}
        }
        // Nothing turns: the engine at once, as the single choice.
        if self.branches.len() == 1 && !self.start_engine(0)? {
            self.fail(SampleError::LimitReached { found: 0 });
        }
        Ok(())
    }

    /// The orientation choice whose engine draws the next layout: uniform
    /// among those not exhausted (no draw when one is left); `None` when
    /// every choice is exhausted.
    fn pick(&mut self) -> Option<usize> {
        let alive: Vec<usize> = (0..self.branches.len())
            .filter(|&b| !self.branches[b].done)
            .collect();
        match alive.len() {
            0 => None,
            1 => Some(alive[0]),
            k => Some(alive[self.rng.random_range(0..k)]),
        }
    }

    fn fail(&mut self, e: SampleError) {
        self.pending = Some(e);
    }

    /// Nothing of the quality asked for: say why (infeasible, or the best
    /// score there is).
    fn no_layout(&mut self) -> Result<(), SampleError> {
        let r = crate::synth::synthesize(&self.problem, &self.rules, &self.synth_opts)?;
        let quality = match self.opts.quality {
            Quality::MinScore(x) => format!("scores at least {x}"),
            _ => "keeps every rule (score 1)".to_string(),
        };
        self.fail(match r.status {
            Status::Infeasible => SampleError::Infeasible(r.conflict.unwrap_or_default()),
            Status::Unknown => SampleError::LimitReached { found: 0 },
            Status::Optimal | Status::Feasible => SampleError::NoLayout {
                quality,
                best: r.evaluation.map_or(0.0, |e| e.score),
            },
        });
        Ok(())
    }
}

impl Iterator for Sampler {
    type Item = Result<Scene, SampleError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.state != State::Running {
            return None;
        }
        if let Some(e) = self.pending.take() {
            self.state = State::Stopped;
            return Some(Err(e));
        }
        loop {
            let Some(b) = self.pick() else {
                if self.found > 0 {
                    self.state = State::Exhausted;
                    return None;
                }
                // Nothing at all of this quality: say why.
                self.state = State::Stopped;
                if let Err(e) = self.no_layout() {
                    return Some(Err(e));
                }
                return self.pending.take().map(Err);
            };
            if self.branches[b].engine.is_none() {
                let started = match self.start_engine(b) {
                    Ok(s) => s,
                    Err(e) => {
                        self.state = State::Stopped;
                        return Some(Err(e.into()));
                    }
                };
                if !started {
                    self.state = State::Stopped;
                    return Some(Err(SampleError::LimitReached { found: self.found }));
                }
                if self.branches[b].done {
                    continue;
                }
            }
            match self.draw(b) {
                Ok(Some(scene)) => {
                    self.found += 1;
                    return Some(Ok(scene));
                }
                Ok(None) => self.branches[b].done = true,
                Err(e) => {
                    self.state = State::Stopped;
                    return Some(Err(e));
                }
            }
        }
    }
}

impl std::iter::FusedIterator for Sampler {}

/// A layout up to swapping interchangeable objects: per `(class, width,
/// height)` of unplaced objects, their positions, sorted.
pub type LayoutKey = Vec<(String, i64, i64, Vec<(i64, i64)>)>;

/// An object's class and footprint (how hints and layouts group objects).
fn like_key(o: &crate::scene::Object) -> (String, i64, i64) {
    let (w, h) = o.footprint();
    (o.class.clone(), w, h)
}

/// The layout of `scene` (a complete scene of `problem`) up to swapping
/// interchangeable objects: per group of unplaced objects of `problem` with
/// the same class and size, their positions, sorted. Two scenes are the
/// same layout (docs/guide.md#sampling) iff their keys are equal.
pub fn canonical_key(problem: &Scene, scene: &Scene) -> LayoutKey {
    let mut groups: BTreeMap<(String, i64, i64), Vec<(i64, i64)>> = BTreeMap::new();
    for (p, s) in problem.objects.iter().zip(&scene.objects) {
        if p.is_placed() {
            continue;
        }
        // By the layout's footprint: the same blocks at the same places,
        // one of them turned, are another layout.
        groups
            .entry(like_key(s))
            .or_default()
            .push((s.x.unwrap_or_default(), s.y.unwrap_or_default()));
    }
    groups
        .into_iter()
        .map(|((c, w, h), mut v)| {
            v.sort_unstable();
            (c, w, h, v)
        })
        .collect()
}
