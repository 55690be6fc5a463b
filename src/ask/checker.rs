//! The probe checker (docs/guide.md#questions): one engine holding every
//! held rule and every negation, so that "does this rule (or this group)
//! have a probe" and "does one rule alone imply another" are solves under
//! assumptions.

use super::probe::{negation, ProbeOptions};
use crate::rules::{Rule, RuleSet, Strength};
use crate::scene::Scene;
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
/// Holds a Pumpkin engine, so it is not `Send`: make one per scan.
pub(super) struct ProbeChecker {
    engine: Option<crate::synth::engine::Engine>,
    model: crate::synth::model::Model,
    problem: Scene,
    held: usize,
    negation_of: Vec<Option<usize>>,
    opts: ProbeOptions,
    /// A deadline besides the options' time limit (the question's
    /// wall-clock cap).
    deadline: Option<std::time::Instant>,
    /// Per object of the problem: the hard index of its pin (see
    /// [`ProbeChecker::pinned`]), `None` when it has none.
    pins: Vec<Option<usize>>,
}

impl ProbeChecker {
    /// Build the engine for `held` on `problem`.
    pub(super) fn new(
        problem: &Scene,
        held: &RuleSet,
        opts: &ProbeOptions,
    ) -> Result<ProbeChecker, SynthError> {
        Self::build(problem, held, opts, false)
    }

    /// A checker for edits of the complete scene `demo`: every movable
    /// object on the grid becomes unplaced with a *pin* (a guarded hard
    /// constraint holding it where it is), so that
    /// [`ProbeChecker::has_probe_moving`] can free any few of them under
    /// assumptions. Objects off the grid stay where they are.
    pub(super) fn pinned(
        demo: &Scene,
        held: &RuleSet,
        opts: &ProbeOptions,
    ) -> Result<ProbeChecker, SynthError> {
        Self::build(demo, held, opts, true)
    }

    fn build(
        problem: &Scene,
        held: &RuleSet,
        opts: &ProbeOptions,
        pin: bool,
    ) -> Result<ProbeChecker, SynthError> {
        use crate::synth::engine::Engine;
        use crate::synth::model::{BuildOptions, Model};
        let mut problem = problem.clone();
        let mut at: Vec<Option<(i64, i64)>> = vec![None; problem.objects.len()];
        if pin {
            let (sp, g) = (problem.space, problem.grid);
            for (i, o) in problem.objects.iter_mut().enumerate() {
                if let (false, Some(x), Some(y)) = (o.fixed, o.x, o.y) {
                    if (x - sp.x) % g == 0 && (y - sp.y) % g == 0 {
                        at[i] = Some((x, y));
                        o.x = None;
                        o.y = None;
                    }
                }
            }
        }
        let problem = &problem;
        crate::synth::check_problem(problem)?;
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
        let set = RuleSet::new(rules);
        crate::synth::check_pairs(problem, &set)?;
        let model = Model::build(
            problem,
            &set,
            BuildOptions {
                contact: opts.contact,
                rules: true,
                // Pins hold interchangeable objects in any order.
                symmetry_breaking: !pin,
                redundant: true,
            },
        );
        let mut model = model;
        let pins = at
            .iter()
            .enumerate()
            .map(|(i, p)| p.and_then(|(x, y)| model.pin(i, x, y)))
            .collect();
        // Every rule is hard, so `model.hard[i]` is rule `i`.
        debug_assert!(model.hard.iter().enumerate().all(|(i, h)| h.rule == i));
        let engine = if model.too_large.is_empty() {
            let mut e = Engine::new(&model, opts.seed, true, None)?;
            // Checks are mostly proofs that no layout breaks a rule.
            e.leave_greedy_after(CHECK_GREEDY_CONFLICTS);
            Some(e)
        } else {
            None
        };
        Ok(ProbeChecker {
            engine,
            model,
            problem: problem.clone(),
            held: n,
            negation_of,
            opts: opts.clone(),
            deadline: None,
            pins,
        })
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
        let Some(mut assume) = self.breaking(targets) else {
            return Checked::Proven;
        };
        assume.extend(
            self.pins
                .iter()
                .enumerate()
                .filter(|(i, _)| !free.contains(i))
                .filter_map(|(_, p)| *p),
        );
        self.solve(&assume, nodes)
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
            Some(assume) => self.solve(&assume, nodes),
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
        self.pins.get(i).is_some_and(Option::is_some)
    }

    /// The weight of one of its search nodes (see `super::budget`).
    pub(super) fn weight(&self) -> u64 {
        super::budget::weight(self.model.bools.len())
    }

    /// Search nodes spent by every solve so far.
    pub(super) fn nodes(&self) -> u64 {
        self.engine.as_ref().map_or(0, |e| e.nodes())
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
        self.solve(&assume, nodes)
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
        self.solve(&[a, neg], nodes)
    }

    /// One solve under the assumptions "these rules hold".
    fn solve(&mut self, assume: &[usize], nodes: Option<u64>) -> Checked {
        use crate::synth::backend::Verdict;
        // An object that cannot lie in the space: no layout at all.
        let Some(engine) = self.engine.as_mut() else {
            return Checked::Proven;
        };
        let mut limits = check_limits(&self.opts, engine);
        if let Some(d) = self.deadline {
            limits.deadline = Some(limits.deadline.map_or(d, |l| l.min(d)));
        }
        if let Some(n) = nodes {
            let cap = engine.nodes().saturating_add(n);
            limits.node_limit = Some(limits.node_limit.map_or(cap, |l| l.min(cap)));
        }
        let before = engine.nodes();
        let t = std::time::Instant::now();
        let sat = engine.satisfy_rules(assume, &limits);
        log::debug!(
            "ask: checker solve, {} nodes in {:.1} ms",
            engine.nodes() - before,
            t.elapsed().as_secs_f64() * 1e3
        );
        match sat {
            Verdict::Solution(v) => Checked::Witness(self.model.scene(&self.problem, &v)),
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

/// The limits of one solve of a [`ProbeChecker`]: the probe options' time
/// limit from now, their check budget past the nodes already spent.
fn check_limits(
    opts: &ProbeOptions,
    engine: &crate::synth::engine::Engine,
) -> crate::synth::engine::Limits {
    crate::synth::engine::Limits {
        deadline: opts
            .time_limit
            .and_then(|t| std::time::Instant::now().checked_add(t)),
        node_limit: opts.check_nodes.map(|n| engine.nodes().saturating_add(n)),
        cancel: opts.cancel.clone(),
    }
}

/// A checker's engine leaves its greedy first phase after this many
/// conflicts without a layout (see `Engine::leave_greedy_after`): a proof
/// that a rule is implied needs the complete search, which the greedy
/// phase holds back (on the bundled example, "`group(B)` implies every B
/// touches something flush" is proven in under 0.1 s this way).
const CHECK_GREEDY_CONFLICTS: u64 = 1000;
