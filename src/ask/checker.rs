//! The probe checker (docs/guide.md#questions): one engine holding every
//! held rule and every negation, so that "does this rule (or this group)
//! have a probe" and "does one rule alone imply another" are solves under
//! assumptions.

use super::probe::{negation, ProbeOptions};
use crate::rules::{Rule, RuleSet, Strength};
use crate::scene::Scene;
use crate::stop::Stop;
use crate::synth::backend::{Assumption, Backend};
use crate::synth::SynthError;

/// Whether each held rule has a probe, for many rules with one engine.
///
/// One model holds every held rule and every negation as a hard rule with
/// its own guard; "does rule `k` have a probe" is one solve under the
/// assumptions "every other held rule, and `k`'s negation". Pumpkin keeps
/// what it learned between solves, and the engine is built once (building
/// it is most of the time of one probe search on the bundled example).
/// A solution only says that a probe exists; [`find_probe`] then finds the
/// one to show (most visible, most like the demonstrations).
///
/// Objects that turn (docs/guide.md#objects-that-turn): the model places
/// every object in one orientation, so the checker holds one engine per
/// orientation (a *part*). On a problem, one per orientation choice of its
/// turnable objects (as `sample` draws them; at most
/// [`MAX_CHECK_ORIENTATIONS`], past that a check without a probe is
/// undecided); on a demonstration, the blocks as laid and then, for the
/// blocks a check frees, each set of them turned over. A check tries the
/// parts in order: a probe in any is a probe, "none" needs a proof in
/// every one.
///
/// Holds Pumpkin engines, so it is not `Send`: make one per scan.
pub(super) struct ProbeChecker {
    /// The engines, the first (nothing turned, or the demonstration as
    /// laid) built at once, the others when first needed.
    parts: Vec<Option<Part>>,
    /// Per part, the problem it places: an orientation choice of the
    /// problem, or the demonstration (pinned objects unplaced) with the
    /// blocks of [`ProbeChecker::flips`] turned over.
    oriented: Vec<Scene>,
    /// Pinned: per part, the blocks turned over (empty for the first).
    flips: Vec<Vec<usize>>,
    /// Every orientation has a part (false past [`MAX_CHECK_ORIENTATIONS`]).
    complete: bool,
    /// The problem or demonstration as given (its `turnable` flags are the
    /// witnesses').
    given: Scene,
    /// Every held rule and every negation, hard (the model's rules).
    rules: RuleSet,
    held: usize,
    negation_of: Vec<Option<usize>>,
    opts: ProbeOptions,
    /// A deadline besides the options' time limit (the question's
    /// wall-clock cap).
    deadline: Option<std::time::Instant>,
    /// Pinned: per object, where its pin holds it (`None`: not pinned).
    pin_at: Vec<Option<(i64, i64)>>,
    /// Pinned: per object, whether an edit may turn it over.
    turns: Vec<bool>,
}

/// One orientation's engine.
struct Part {
    engine: Option<Box<dyn crate::synth::backend::Backend>>,
    model: crate::synth::model::Model,
    /// Per object of the problem: the hard index of its pin (see
    /// [`ProbeChecker::pinned`]), `None` when it has none.
    pins: Vec<Option<usize>>,
}

/// Most orientation choices of a problem's turnable objects a checker
/// holds engines for.
pub(super) const MAX_CHECK_ORIENTATIONS: usize = 64;

impl ProbeChecker {
    /// Build the engine for `held` on `problem`.
    pub(super) fn new(
        problem: &Scene,
        held: &RuleSet,
        opts: &ProbeOptions,
    ) -> Result<ProbeChecker, SynthError> {
        crate::synth::check_problem(problem)?;
        let (oriented, complete) =
            match crate::sample::orientation_choices(problem, MAX_CHECK_ORIENTATIONS) {
                Some((_, choices)) => (choices.into_iter().map(|(_, p)| p).collect(), true),
                None => {
                    // Too many choices: the blocks as given (flat) only.
                    let mut flat = problem.clone();
                    for o in flat.objects.iter_mut().filter(|o| !o.is_placed()) {
                        o.turnable = false;
                    }
                    (vec![flat], false)
                }
            };
        Self::build(
            problem,
            oriented,
            complete,
            held,
            opts,
            Vec::new(),
            Vec::new(),
        )
    }

    /// A checker for edits of the complete scene `demo`: every movable
    /// object on the grid becomes unplaced with a *pin* (a guarded hard
    /// constraint holding it where it is), so that
    /// [`ProbeChecker::has_probe_moving`] can free any few of them under
    /// assumptions. Objects off the grid stay where they are. A freed
    /// oblong block may also turn over when it is `turnable` or `turned`,
    /// or its class and size are in `turnable` (the problem's turnable
    /// kinds).
    pub(super) fn pinned(
        demo: &Scene,
        held: &RuleSet,
        opts: &ProbeOptions,
        turnable: &[(String, i64, i64)],
    ) -> Result<ProbeChecker, SynthError> {
        let mut laid = demo.clone();
        let mut at: Vec<Option<(i64, i64)>> = vec![None; laid.objects.len()];
        let mut turns = vec![false; laid.objects.len()];
        let (sp, g) = (laid.space, laid.grid);
        for (i, o) in laid.objects.iter_mut().enumerate() {
            if let (false, Some(x), Some(y)) = (o.fixed, o.x, o.y) {
                if (x - sp.x) % g == 0 && (y - sp.y) % g == 0 {
                    at[i] = Some((x, y));
                    turns[i] = super::edit::may_turn(o, turnable);
                    o.x = None;
                    o.y = None;
                    // Its orientation is given: as laid.
                    o.turnable = o.turned;
                }
            }
        }
        crate::synth::check_problem(&laid)?;
        Self::build(demo, vec![laid], true, held, opts, at, turns)
    }

    fn build(
        given: &Scene,
        oriented: Vec<Scene>,
        complete: bool,
        held: &RuleSet,
        opts: &ProbeOptions,
        pin_at: Vec<Option<(i64, i64)>>,
        turns: Vec<bool>,
    ) -> Result<ProbeChecker, SynthError> {
        let n = held.rules.len();
        let mut rules: Vec<Rule> = held
            .rules
            .iter()
            .map(|h| Rule {
                strength: Strength::Hard,
                comments: Vec::new(),
                origin: None,
                ..h.clone()
            })
            .collect();
        let mut negation_of = Vec::with_capacity(n);
        for h in &held.rules {
            match negation(h) {
                Some(neg) => {
                    negation_of.push(Some(rules.len()));
                    rules.push(neg);
                }
                None => negation_of.push(None),
            }
        }
        let rules = RuleSet::new(rules);
        crate::synth::check_pairs(&oriented[0], &rules)?;
        let mut c = ProbeChecker {
            parts: Vec::new(),
            flips: vec![Vec::new()],
            oriented,
            complete,
            given: given.clone(),
            rules,
            held: n,
            negation_of,
            opts: opts.clone(),
            deadline: None,
            pin_at,
            turns,
        };
        c.parts.resize_with(c.oriented.len(), || None);
        let first = c.build_part(0)?;
        c.parts[0] = Some(first);
        Ok(c)
    }

    /// The engine of part `k` (its problem in `oriented[k]`).
    fn build_part(&self, k: usize) -> Result<Part, SynthError> {
        use crate::synth::model::{BuildOptions, Model};
        let problem = &self.oriented[k];
        crate::synth::check_problem(problem)?;
        let pin = !self.pin_at.is_empty();
        let mut model = Model::build(
            problem,
            &self.rules,
            BuildOptions {
                contact: self.opts.contact,
                rules: true,
                // Pins hold interchangeable objects in any order.
                symmetry_breaking: !pin,
                redundant: true,
                tuning: self.opts.tuning,
            },
        );
        let pins = (self.pin_at.iter().enumerate())
            .map(|(i, p)| p.and_then(|(x, y)| model.pin(i, x, y)))
            .collect();
        // Every rule is hard, so `model.hard[i]` is rule `i`.
        debug_assert!(model.hard.iter().enumerate().all(|(i, h)| h.rule == i));
        let engine = if model.too_large.is_empty() {
            let mut e = crate::synth::backend::load(
                &model,
                self.opts.seed,
                true,
                None,
                &[],
                &Stop::never(),
            )?
            .expect("never stopped");
            // Checks are mostly proofs that no layout breaks a rule.
            e.leave_greedy_after(CHECK_GREEDY_CONFLICTS);
            Some(e)
        } else {
            None
        };
        Ok(Part {
            engine,
            model,
            pins,
        })
    }

    /// The part of the demonstration with the blocks of `flip` turned over
    /// (made when first needed).
    fn flipped(&mut self, flip: &[usize]) -> usize {
        if let Some(k) = self.flips.iter().position(|f| f == flip) {
            return k;
        }
        let mut p = self.oriented[0].clone();
        for &i in flip {
            let o = &mut p.objects[i];
            o.turned = !o.turned;
            o.turnable = o.turned;
        }
        self.oriented.push(p);
        self.flips.push(flip.to_vec());
        self.parts.push(None);
        self.parts.len() - 1
    }

    /// Whether the rules `targets` have one probe that moves only the objects in `free`
    /// (indices into the scene of [`ProbeChecker::pinned`]; every other
    /// pinned object stays where it is), within `nodes` search nodes.
    pub(super) fn has_probe_moving(
        &mut self,
        targets: &[usize],
        free: &[usize],
        nodes: Option<u64>,
    ) -> Checked {
        let Some(assume) = self.breaking(targets) else {
            return Checked::Proven;
        };
        self.solve(&assume, Some(free), nodes)
    }

    /// Whether one layout breaks every held rule of `targets` and keeps
    /// every other held rule (a group question's probe exists), within
    /// `nodes` search nodes when that is below the check budget.
    pub(super) fn has_group_probe_within(
        &mut self,
        targets: &[usize],
        nodes: Option<u64>,
    ) -> Checked {
        match self.breaking(targets) {
            Some(assume) => self.solve(&assume, None, nodes),
            None => Checked::Proven,
        }
    }

    /// The assumptions "every held rule but `targets` holds, and each of
    /// `targets` breaks"; `None` when one of them cannot break at all.
    fn breaking(&self, targets: &[usize]) -> Option<Vec<usize>> {
        let mut assume: Vec<usize> = (0..self.held).filter(|j| !targets.contains(j)).collect();
        for &k in targets {
            assume.push(self.negation_of[k]?);
        }
        Some(assume)
    }

    /// Whether object `i` of the scene can move (it has a pin).
    pub(super) fn can_move(&self, i: usize) -> bool {
        (self.parts[0].as_ref()).is_some_and(|p| p.pins.get(i).is_some_and(Option::is_some))
    }

    /// The weight of one of its search nodes (see `super::budget`).
    pub(super) fn weight(&self) -> u64 {
        let bools = self.parts[0].as_ref().map_or(0, |p| p.model.bools.len());
        super::budget::weight(bools)
    }

    /// Search nodes spent by every solve so far.
    pub(super) fn nodes(&self) -> u64 {
        (self.parts.iter().flatten())
            .filter_map(|p| p.engine.as_ref())
            .map(|e| e.nodes())
            .sum()
    }

    /// Stop every later solve at `deadline` too (besides the options' time
    /// limit).
    pub(super) fn set_deadline(&mut self, deadline: Option<std::time::Instant>) {
        self.deadline = deadline;
    }

    /// [`Checked::Witness`]: rule `k` has a probe (the layout found, which
    /// breaks `k` and keeps the others); [`Checked::Proven`]: proven none
    /// (the others imply it on this problem); [`Checked::Stopped`]: a limit
    /// stopped the solve (the session then makes a new checker, so that
    /// later checks do not depend on how far the stopped search got).
    /// Rules with `removed[j]` (allowed to break with `k`) are left out of
    /// the assumptions.
    #[cfg(test)]
    pub(super) fn has_probe(&mut self, k: usize, removed: &[bool]) -> Checked {
        self.has_probe_within(k, removed, None)
    }

    /// [`ProbeChecker::has_probe`] with at most `nodes` search nodes when
    /// that is below the options' check budget.
    pub(super) fn has_probe_within(
        &mut self,
        k: usize,
        removed: &[bool],
        nodes: Option<u64>,
    ) -> Checked {
        let Some(neg) = self.negation_of[k] else {
            return Checked::Proven;
        };
        let mut assume: Vec<usize> = (0..self.held)
            .filter(|&j| j != k && !removed.get(j).copied().unwrap_or(false))
            .collect();
        assume.push(neg);
        self.solve(&assume, None, nodes)
    }

    /// Whether held rule `a` alone implies held rule `b` on this problem
    /// (no other rule assumed): [`Checked::Proven`] when it does,
    /// [`Checked::Witness`] with a layout keeping `a` and breaking `b`
    /// when it does not, [`Checked::Stopped`] when a limit stopped the
    /// solve.
    #[cfg(test)]
    pub(super) fn implies(&mut self, a: usize, b: usize) -> Checked {
        self.implies_within(a, b, None)
    }

    /// [`ProbeChecker::implies`] with at most `nodes` search nodes when
    /// that is below the options' check budget.
    pub(super) fn implies_within(&mut self, a: usize, b: usize, nodes: Option<u64>) -> Checked {
        let Some(neg) = self.negation_of[b] else {
            return Checked::Proven;
        };
        self.solve(&[a, neg], None, nodes)
    }

    /// One check under the assumptions "these rules hold" (and, with
    /// `free`, every pinned object but those stays where it is): each
    /// part in turn until one has a witness, within `nodes` search nodes
    /// in all.
    fn solve(&mut self, assume: &[usize], free: Option<&[usize]>, nodes: Option<u64>) -> Checked {
        let parts: Vec<usize> = match free {
            None => (0..self.parts.len()).collect(),
            Some(free) => {
                // The blocks as laid, then every set of the freed blocks
                // that may turn over, turned over.
                let turning: Vec<usize> = (free.iter().copied())
                    .filter(|&i| self.turns.get(i).copied().unwrap_or(false))
                    .collect();
                (0..1usize << turning.len())
                    .map(|m| {
                        let flip: Vec<usize> = (turning.iter().enumerate())
                            .filter(|(b, _)| m >> b & 1 == 1)
                            .map(|(_, &i)| i)
                            .collect();
                        self.flipped(&flip)
                    })
                    .collect()
            }
        };
        let mut stopped = !self.complete;
        let mut used: u64 = 0;
        for k in parts {
            let left = nodes.map(|n| n.saturating_sub(used));
            if left == Some(0) {
                stopped = true;
                break;
            }
            let before = self.nodes();
            let checked = self.solve_part(k, assume, free, left);
            used = used.saturating_add(self.nodes() - before);
            match checked {
                Checked::Witness(_) => return checked,
                Checked::Stopped => stopped = true,
                Checked::Proven => {}
            }
        }
        if stopped {
            Checked::Stopped
        } else {
            Checked::Proven
        }
    }

    /// One solve on part `k` (built first when needed).
    fn solve_part(
        &mut self,
        k: usize,
        rules: &[usize],
        free: Option<&[usize]>,
        nodes: Option<u64>,
    ) -> Checked {
        use crate::synth::backend::Verdict;
        if self.parts[k].is_none() {
            match self.build_part(k) {
                Ok(p) => self.parts[k] = Some(p),
                Err(e) => {
                    log::warn!("ask: a checker's orientation {k} could not be built: {e}");
                    return Checked::Stopped;
                }
            }
        }
        let Some(part) = self.parts[k].as_mut() else {
            return Checked::Stopped;
        };
        let mut assume = rules.to_vec();
        if let Some(free) = free {
            assume.extend(
                (part.pins.iter().enumerate())
                    .filter(|(i, _)| !free.contains(i))
                    .filter_map(|(_, p)| *p),
            );
        }
        // An object that cannot lie in the space: no layout at all.
        let Some(engine) = part.engine.as_mut() else {
            return Checked::Proven;
        };
        let mut limits = check_limits(&self.opts, &**engine).by(self.deadline);
        if let Some(n) = nodes {
            let cap = engine.nodes().saturating_add(n);
            let cap = limits.nodes().map_or(cap, |l| l.min(cap));
            limits = limits.nodes_at_most(Some(cap));
        }
        let before = engine.nodes();
        let t = std::time::Instant::now();
        let assume: Vec<Assumption> = assume.iter().map(|&r| Assumption::Rule(r)).collect();
        let sat = engine.solve(&assume, &limits);
        log::debug!(
            "ask: checker solve, {} nodes in {:.1} ms",
            engine.nodes() - before,
            t.elapsed().as_secs_f64() * 1e3
        );
        match sat {
            Verdict::Solution(v) => {
                let mut scene = part.model.scene(&self.oriented[k], &v);
                // The objects as given, in the orientation found.
                for (o, g) in scene.objects.iter_mut().zip(&self.given.objects) {
                    o.turnable = g.turnable;
                }
                Checked::Witness(scene)
            }
            Verdict::Infeasible(_) => Checked::Proven,
            Verdict::Unknown => Checked::Stopped,
        }
    }
}

/// What one check of a [`ProbeChecker`] found.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Checked {
    /// A layout of the problem that answers the check with "no": it keeps
    /// the assumed rules and breaks the rule checked.
    Witness(Scene),
    /// Proven: no such layout exists.
    Proven,
    /// A limit stopped the solve.
    Stopped,
}

impl Checked {
    /// A word for logs: `witness`, `proven` or `stopped`.
    pub(super) fn name(&self) -> &'static str {
        match self {
            Checked::Witness(_) => "witness",
            Checked::Proven => "proven",
            Checked::Stopped => "stopped",
        }
    }
}

/// The limits of one solve of a [`ProbeChecker`]: the probe options' stop
/// and per-solve time from now, their check budget past the nodes already
/// spent.
fn check_limits(opts: &ProbeOptions, engine: &dyn Backend) -> Stop {
    opts.solve_stop()
        .nodes_at_most(opts.check_nodes.map(|n| engine.nodes().saturating_add(n)))
}

/// A checker's engine leaves its greedy first phase after this many
/// conflicts without a layout (see `Backend::leave_greedy_after`): a proof
/// that a rule is implied needs the complete search, which the greedy
/// phase holds back (on the bundled example, "`group(B)` implies every B
/// touches something flush" is proven in under 0.1 s this way).
const CHECK_GREEDY_CONFLICTS: u64 = 1000;
