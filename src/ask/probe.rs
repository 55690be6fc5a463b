//! Probes (docs/guide.md#questions): a layout that breaks one held rule and keeps the rest.
//!
//! # Background
//!
//! A learned rule is true in every demonstration and improbable by chance,
//! yet it may be a habit of these demonstrations rather than an intention.
//! Only the person can tell; the thesis (§5.2.2) proposes asking them with a
//! layout that breaks the rule on purpose.
//!
//! # Practical
//!
//! The probe for rule `r` is a synthesis problem built from the language
//! itself, so the model builder is not copied or special-cased:
//!
//! - every *other* held rule becomes `hard`;
//! - `r` is replaced by its [`negation`], also `hard`: for `rule r: φ` that
//!   is the scene-level rule `some A: !φ` ("at least one subject breaks
//!   it"); for a scene-level rule the complementary quantifier
//!   (`some` ↔ `no`, `at least K` ↔ `at most K−1`);
//! - the objective (soft, weight 1 per subject) is `!φ` for each subject, so
//!   the probe breaks `r` for as many objects as the other rules allow —
//!   the most visible break;
//! - the second objective (docs/guide.md#layouts-like-the-demonstrations) is resemblance to the demonstrations:
//!   everything the probe does not have to change sits where the person put
//!   it, so what stands out is the broken rule.
//!
//! An infeasible probe problem is a proof (the engine is exact) that on this
//! object mix the other held rules imply `r`: there is nothing to ask. The
//! conflict names the held rules that imply it.
//!
//! # How to extend
//!
//! A new rule form needs only a negation here when it adds a scope; new
//! atoms and quantifiers inside formulas are negated by `!` for free.

use crate::eval::evaluate;
use crate::relations::{Contact, Quant, MAX_COUNT};
use crate::resemblance::ResemblanceTarget;
use crate::rules::{Formula, Rule, RuleSet, Scope, Strength};
use crate::scene::Scene;
use crate::stop::Stop;
use crate::synth::{synthesize, Status, SynthError, SynthOptions};
use std::time::Duration;

/// The name given to the negated rule inside a probe problem.
pub(super) const NEGATION_PREFIX: &str = "not_";

/// A rule that holds exactly when `rule` is broken: `some A: !φ` for a
/// per-object rule, the complementary quantifier for a scene-level one.
/// `None` when `rule` cannot be broken at all (`at least 0`; `at most K`
/// with `K` = [`MAX_COUNT`], which no scene within the limits can break).
pub fn negation(rule: &Rule) -> Option<Rule> {
    let (scope, formula) = match rule.scope {
        Scope::Each => (
            Scope::Scene(Quant::Some),
            Formula::not(rule.formula.clone()),
        ),
        Scope::Scene(q) => {
            let nq = match q {
                // `every A: φ` is `Scope::Each`; kept total all the same.
                Quant::Every => {
                    return negation(&Rule {
                        scope: Scope::Each,
                        ..rule.clone()
                    })
                }
                Quant::Some => Quant::No,
                Quant::No => Quant::Some,
                Quant::AtLeast(0) => return None,
                Quant::AtLeast(1) => Quant::No,
                Quant::AtLeast(k) => Quant::AtMost(k - 1),
                Quant::AtMost(k) if k >= MAX_COUNT => return None,
                Quant::AtMost(0) => Quant::Some,
                Quant::AtMost(k) => Quant::AtLeast(k + 1),
            };
            (Scope::Scene(nq), rule.formula.clone())
        }
        // A group statement's negation is the negated shape: `!column(R)`.
        Scope::Group => match rule.formula.shape() {
            Some((shape, neg)) => {
                let f = Formula::Shape(shape.clone());
                (Scope::Group, if neg { f } else { Formula::not(f) })
            }
            None => return None,
        },
    };
    Some(Rule {
        name: format!("{NEGATION_PREFIX}{}", rule.name),
        strength: Strength::Hard,
        scope,
        formula,
        comments: Vec::new(),
        origin: None,
    })
}

/// Default node budget of [`ProbeOptions::stop`]: on the bundled example the largest
/// probe search takes 18,509 nodes (about 1.4 s in release), so this stops
/// only searches far outside what a question should cost.
pub const DEFAULT_PROBE_NODES: u64 = 100_000;

/// Default [`ProbeOptions::check_nodes`]: on the bundled example no check
/// takes more than 1,674 nodes (0.14 s).
pub const DEFAULT_CHECK_NODES: u64 = 20_000;

/// Settings of one probe solve.
#[derive(Debug, Clone)]
pub struct ProbeOptions {
    /// How EC decides that two sides touch.
    pub contact: Contact,
    /// Seed of the solve.
    pub seed: u64,
    /// A per-solve time budget: stop each solve (a probe search or a
    /// check) after this long from its start (`None`: no limit); a safety
    /// net for slow machines, what it stops depends on the clock.
    pub solve_time: Option<Duration>,
    /// When to stop every solve: the deadline and the cancel flag (e.g. a
    /// look-ahead for the answer not given), and the node budget of each
    /// probe search (deterministic: the best probe found so far is shown).
    pub stop: Stop,
    /// Stop a check of `ProbeChecker` (does a probe exist? does one rule
    /// imply another?) after this many search nodes (deterministic: the
    /// check then counts as undecided).
    pub check_nodes: Option<u64>,
    /// Positions the probe should resemble (the demonstrations).
    pub like: Option<ResemblanceTarget>,
    /// For a rule with no probe, name the held rules implying it (one more
    /// solve per held rule).
    pub explain: bool,
    /// Layouts to start the probe search from (a probe a check found):
    /// the search then only improves on it.
    pub warm_start: Vec<Scene>,
    /// Engine tuning of every solve and check (doc-hidden, see
    /// [`crate::synth::Tuning`]).
    #[doc(hidden)]
    pub tuning: crate::synth::Tuning,
}

impl ProbeOptions {
    /// The synthesis options of one probe solve starting now: a layout
    /// first and resemblance second, the engine's own search (from
    /// [`ProbeOptions::warm_start`] when there is one).
    pub(crate) fn synth_options(&self) -> SynthOptions {
        SynthOptions {
            contact: self.contact,
            stop: self.solve_stop(),
            seed: self.seed,
            like: self.like.clone(),
            explain: self.explain,
            lns: None,
            warm_start: self.warm_start.clone(),
            tuning: self.tuning,
            ..SynthOptions::default()
        }
    }

    /// The stop of one solve starting now: [`ProbeOptions::stop`] with
    /// the per-solve time budget.
    pub(crate) fn solve_stop(&self) -> Stop {
        let per = self
            .solve_time
            .and_then(|t| std::time::Instant::now().checked_add(t));
        self.stop.clone().by(per)
    }
}

impl Default for ProbeOptions {
    fn default() -> Self {
        ProbeOptions {
            contact: Contact::Point,
            seed: 0,
            solve_time: Some(Duration::from_secs(10)),
            stop: Stop::never().with_nodes(DEFAULT_PROBE_NODES),
            check_nodes: Some(DEFAULT_CHECK_NODES),
            like: None,
            explain: false,
            warm_start: Vec::new(),
            tuning: crate::synth::Tuning::default(),
        }
    }
}

/// What the probe search found for one rule.
#[derive(Debug, Clone, PartialEq)]
pub enum ProbeOutcome {
    /// A layout breaking the rule and keeping every other held rule.
    Probe(Probe),
    /// Proven: no layout of the problem breaks the rule while keeping the
    /// others. `by` names a minimal set of held rules implying it (empty
    /// when the rule cannot be broken on this problem at all, e.g. the
    /// problem has no object of its subject class).
    Implied {
        /// Held rules whose conjunction implies the rule on this problem.
        by: Vec<String>,
    },
    /// A limit stopped the search before either.
    Unknown,
}

/// A probe layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Probe {
    /// The probed rule's name.
    pub rule: String,
    /// The complete layout.
    pub scene: Scene,
    /// Ids of the objects that break the rule (for a scene-level rule: the
    /// evaluator's violators, possibly none).
    pub broken: Vec<String>,
    /// Its resemblance cost to the demonstrations (0 without `like`).
    pub cost: u64,
    /// Search time in milliseconds.
    pub time_ms: f64,
    /// When the probe is a demonstration with a few objects moved: which
    /// one, and what moved from where (`None`: a layout of the problem).
    pub edit: Option<super::edit::Edit>,
}

/// `rule` as a probe problem keeps it: hard, without its comments and
/// origin.
pub(crate) fn kept_hard(rule: &Rule) -> Rule {
    Rule {
        strength: Strength::Hard,
        comments: Vec::new(),
        origin: None,
        ..rule.clone()
    }
}

/// The probe problem for `held.rules[target]`: the other held rules hard,
/// its negation hard, "break it for as many subjects as possible" soft.
/// `None` when the rule cannot be broken at all ([`negation`]).
pub fn probe_rules(held: &RuleSet, target: usize) -> Option<RuleSet> {
    group_probe_rules(held, &[target])
}

/// The probe problem of a group question (docs/guide.md#questions): every
/// held rule of `targets` broken (its negation hard, "break it for as many
/// subjects as possible" soft), every other held rule hard. `None` when
/// one of them cannot be broken at all ([`negation`]).
pub fn group_probe_rules(held: &RuleSet, targets: &[usize]) -> Option<RuleSet> {
    let mut rules: Vec<Rule> = held
        .rules
        .iter()
        .enumerate()
        .filter(|&(k, _)| !targets.contains(&k))
        .map(|(_, h)| kept_hard(h))
        .collect();
    for &target in targets {
        let r = &held.rules[target];
        let neg = negation(r)?;
        if r.scope == Scope::Each {
            // The most visible break: as many subjects as possible.
            let mut visible =
                Rule::new(format!("break_{}", r.name), Formula::not(r.formula.clone()));
            visible.strength = Strength::Weight(1.0);
            rules.push(visible);
        }
        rules.push(neg);
    }
    // Names stay unique: the added names carry prefixes no learned name
    // needs, and if one clashes the solve still works (names are labels).
    Some(RuleSet::new(rules))
}

/// Search a probe for `held.rules[target]` on `problem`.
pub fn find_probe(
    problem: &Scene,
    held: &RuleSet,
    target: usize,
    opts: &ProbeOptions,
) -> Result<ProbeOutcome, SynthError> {
    search_probe(problem, held, target, opts).map(|(o, _)| o)
}

/// [`find_probe`], with the search nodes it spent.
pub(crate) fn search_probe(
    problem: &Scene,
    held: &RuleSet,
    target: usize,
    opts: &ProbeOptions,
) -> Result<(ProbeOutcome, u64), SynthError> {
    search_group_probe(problem, held, &[target], opts)
}

/// The probe of a group question: a layout breaking every held rule of
/// `targets` and keeping the others ([`group_probe_rules`]), with the
/// search nodes it spent. The probe is named after the first target; its
/// `broken` objects are those breaking any target.
pub(crate) fn search_group_probe(
    problem: &Scene,
    held: &RuleSet,
    targets: &[usize],
    opts: &ProbeOptions,
) -> Result<(ProbeOutcome, u64), SynthError> {
    let Some(rules) = group_probe_rules(held, targets) else {
        return Ok((ProbeOutcome::Implied { by: Vec::new() }, 0));
    };
    let r = synthesize(problem, &rules, &opts.synth_options())?;
    let name = &held.rules[targets[0]].name;
    let nodes = r.stats.nodes;
    let outcome = match r.status {
        Status::Optimal | Status::Feasible => {
            let scene = r.scene.expect("a layout with a solution status");
            let asked = RuleSet::new(targets.iter().map(|&k| held.rules[k].clone()).collect());
            let ev = evaluate(&scene, &asked, opts.contact);
            let mut broken: Vec<String> = Vec::new();
            for r in &ev.rules {
                for v in &r.violators {
                    if !broken.contains(v) {
                        broken.push(v.clone());
                    }
                }
            }
            ProbeOutcome::Probe(Probe {
                rule: name.clone(),
                scene,
                broken,
                cost: r.resemblance.map_or(0, |c| c.cost),
                time_ms: r.stats.time_ms,
                edit: None,
            })
        }
        Status::Infeasible => {
            let negs: Vec<String> = targets
                .iter()
                .map(|&k| format!("{NEGATION_PREFIX}{}", held.rules[k].name))
                .collect();
            let by = r
                .conflict
                .map(|c| {
                    c.hard_rules
                        .into_iter()
                        .filter(|n| !negs.contains(n))
                        .collect()
                })
                .unwrap_or_default();
            ProbeOutcome::Implied { by }
        }
        Status::Unknown => ProbeOutcome::Unknown,
    };
    Ok((outcome, nodes))
}
