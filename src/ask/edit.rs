//! Probes as small edits of the person's own demonstrations.
//!
//! # Background
//!
//! A probe may be a layout of the problem or of a demonstration's object
//! mix (the docs' *Checking rules with questions*). A demonstration with one
//! or two blocks moved is the cheapest probe to find — every other object
//! is a constant, so the search is over the positions of one or two
//! objects — and the easiest to judge: "your third demonstration with `b2`
//! moved here, acceptable?". The picture marks what moved and where it was.
//!
//! # Practical
//!
//! For a held rule `r` the neighbourhoods are tried in this order, each one
//! the probe problem of [`super::probe::probe_rules`] (every other held rule
//! hard, `r`'s negation hard) on the demonstration with the chosen objects
//! made movable:
//!
//! 1. one object moved, then two ([`MAX_MOVED`]);
//! 2. demonstrations with the fewest objects of `r`'s classes first (the
//!    smallest picture, the fewest ways to keep `r`), ties by index;
//! 3. within one, the objects of `r`'s subject class first, then those of
//!    its target classes (every movable object for `*`), in file order.
//!
//! At most [`MAX_SOLVES`] neighbourhoods per rule are searched, each with a
//! node budget; every search is charged to the question's budget
//! (`super::budget`). The first probe found is shown: it breaks `r` for at
//! least one object and keeps every other held rule (the evaluator checks
//! it again). A neighbourhood without a probe proves nothing about the
//! problem; the session then checks the problem as before.
//!
//! # How to extend
//!
//! Larger neighbourhoods (three objects, a whole class) are more searches
//! of the same kind: add them to [`neighbourhoods`], after the cheaper ones.

use super::budget::Meter;
use super::checker::{Checked, ProbeChecker};
use super::probe::{group_probe_rules, Probe, ProbeOptions};
use crate::eval::evaluate;
use crate::resemblance::ResemblanceTarget;
use crate::rules::{Rule, RuleSet, Target};
use crate::scene::Scene;
use crate::synth::{synthesize, SynthOptions};
use serde::{Deserialize, Serialize};
use std::time::Duration;

/// At most this many objects are moved in a demonstration.
pub(super) const MAX_MOVED: usize = 2;

/// At most this many neighbourhoods are searched per rule.
pub(super) const MAX_SOLVES: usize = 24;

/// Search nodes for one neighbourhood (one or two objects free: a complete
/// search is far below this on every bundled and generated task).
pub(super) const EDIT_NODES: u64 = 2_000;

/// A probe that is a demonstration with a few objects moved.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Edit {
    /// The demonstration's index (in the demonstrations the question was
    /// asked with, accepted probes included).
    pub demo: usize,
    /// The objects that moved, with where they were.
    pub moved: Vec<Moved>,
}

/// One moved object of an [`Edit`].
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Moved {
    /// The object's id.
    pub id: String,
    /// Its x in the demonstration.
    pub x: i64,
    /// Its y in the demonstration.
    pub y: i64,
    /// Whether it lay turned in the demonstration (an edit may turn a
    /// block over, in place or as it moves).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub turned: bool,
}

/// The classes whose objects may move to break `rule`: its subject classes
/// first, then its target classes; `None` for `*` targets (every class).
fn rule_classes(rule: &Rule) -> Option<Vec<String>> {
    let mut subjects = Vec::new();
    let mut targets = Vec::new();
    for a in rule.formula.atoms() {
        if !subjects.contains(&a.subject) {
            subjects.push(a.subject.clone());
        }
        match &a.target {
            Target::Class(c) => {
                if !targets.contains(c) {
                    targets.push(c.clone());
                }
            }
            Target::Any => return None,
            Target::Landmark(_) => {}
        }
    }
    for t in targets {
        if !subjects.contains(&t) {
            subjects.push(t);
        }
    }
    Some(subjects)
}

/// The sets of object indices to free in `demo`, cheapest first.
fn neighbourhoods(demo: &Scene, classes: Option<&[String]>) -> Vec<Vec<usize>> {
    let rank = |c: &str| match classes {
        Some(cs) => cs.iter().position(|x| x == c),
        None => Some(0),
    };
    let mut movable: Vec<(usize, usize)> = demo
        .objects
        .iter()
        .enumerate()
        .filter(|(_, o)| !o.fixed && o.is_placed())
        .filter_map(|(i, o)| rank(&o.class).map(|r| (r, i)))
        .collect();
    movable.sort();
    let idx: Vec<usize> = movable.into_iter().map(|(_, i)| i).collect();
    let mut out: Vec<Vec<usize>> = idx.iter().map(|&i| vec![i]).collect();
    if MAX_MOVED >= 2 {
        for (a, &i) in idx.iter().enumerate() {
            for &j in &idx[a + 1..] {
                out.push(vec![i, j]);
            }
        }
    }
    out
}

/// The number of objects of `classes` in `demo` (every movable one for
/// `None`).
fn weight(demo: &Scene, classes: Option<&[String]>) -> usize {
    demo.objects
        .iter()
        .filter(|o| !o.fixed && classes.is_none_or(|cs| cs.contains(&o.class)))
        .count()
}

/// Settings of the edit search.
pub(crate) struct EditSearch<'a> {
    /// The demonstrations (accepted probes included).
    pub demos: &'a [Scene],
    /// Resemblance of the moved objects to the demonstrations.
    pub like: Option<&'a ResemblanceTarget>,
    /// How EC decides that two sides touch.
    pub contact: crate::relations::Contact,
    /// Seed of every solve.
    pub seed: u64,
    /// The time budget of one solve (a safety net).
    pub solve_time: Option<Duration>,
    /// When to stop every solve (its deadline and cancel flag).
    pub stop: crate::stop::Stop,
    /// The class and size of the problem's turnable blocks: a moved block
    /// of one of them may also turn over (as may a block the demonstration
    /// marks `turnable` or `turned`).
    pub turnable: Vec<(String, i64, i64)>,
}

/// Whether an edit may turn `o` over: oblong, and `turnable`, `turned`,
/// or of a class and size in `kinds`.
pub(super) fn may_turn(o: &crate::scene::Object, kinds: &[(String, i64, i64)]) -> bool {
    o.is_oblong()
        && (o.turnable || o.turned || kinds.contains(&(o.class.clone(), o.width, o.height)))
}

impl EditSearch<'_> {
    /// A probe for the held rules `targets` (one rule, or a group
    /// question's) that is a demonstration with at most [`MAX_MOVED`]
    /// objects moved, breaking every one of them and keeping every other
    /// held rule (the objects of all their classes may move), within the
    /// meter's budget; `None` when no neighbourhood tried has one (or the
    /// budget ran out). `checkers` holds one pinned checker per
    /// demonstration, built when first needed (they stay valid while
    /// `held` does).
    pub(super) fn find_group(
        &self,
        held: &RuleSet,
        targets: &[usize],
        checkers: &mut Vec<Option<ProbeChecker>>,
        meter: &mut Meter,
    ) -> Option<Probe> {
        let rule = &held.rules[targets[0]];
        let rules = group_probe_rules(held, targets)?;
        let mut classes: Option<Vec<String>> = Some(Vec::new());
        for &t in targets {
            match (rule_classes(&held.rules[t]), classes.as_mut()) {
                (Some(cs), Some(all)) => {
                    for c in cs {
                        if !all.contains(&c) {
                            all.push(c);
                        }
                    }
                }
                _ => classes = None,
            }
        }
        let cs = classes.as_deref();
        let mut order: Vec<usize> = (0..self.demos.len()).collect();
        order.sort_by_key(|&d| (weight(&self.demos[d], cs), d));
        let mut tries: Vec<(usize, Vec<usize>)> = Vec::new();
        for moved in 1..=MAX_MOVED {
            for &d in &order {
                for s in neighbourhoods(&self.demos[d], cs) {
                    if s.len() == moved {
                        tries.push((d, s));
                    }
                }
            }
        }
        checkers.resize_with(self.demos.len(), || None);
        let popts = ProbeOptions {
            contact: self.contact,
            seed: self.seed,
            solve_time: self.solve_time,
            stop: self.stop.clone(),
            ..ProbeOptions::default()
        };
        for (n, (d, free)) in tries.into_iter().take(MAX_SOLVES).enumerate() {
            let demo = &self.demos[d];
            if checkers[d].is_none() {
                match ProbeChecker::pinned(demo, held, &popts, &self.turnable) {
                    Ok(c) => checkers[d] = Some(c),
                    Err(_) => continue,
                }
            }
            let c = checkers[d].as_mut().expect("built");
            if !free.iter().all(|&i| c.can_move(i)) {
                continue;
            }
            let nodes = meter.grant(EDIT_NODES, c.weight())?;
            c.set_deadline(meter.deadline());
            let before = c.nodes();
            let found = c.has_probe_moving(targets, &free, Some(nodes));
            meter.spend(c.nodes() - before, c.weight());
            let Checked::Witness(witness) = found else {
                continue;
            };
            // The neighbourhood has a probe: the one to show breaks the
            // rule for the most objects, most like the demonstrations.
            let (layout, cost) = self
                .refine(demo, &free, &rules, meter)
                .unwrap_or((witness, 0));
            if let Some(p) = self.probe(held, targets, d, layout, cost) {
                log::debug!(
                    "ask: edit probe of {} at try {n}: demonstration {d}, {} moved",
                    rule.name,
                    free.len()
                );
                return Some(p);
            }
        }
        None
    }

    /// The best probe of one neighbourhood (a synthesis of the probe
    /// problem with only `free` unplaced), within the meter's budget.
    fn refine(
        &self,
        demo: &Scene,
        free: &[usize],
        rules: &RuleSet,
        meter: &mut Meter,
    ) -> Option<(Scene, u64)> {
        // One or two objects free: a small model (weight 1).
        let nodes = meter.grant(EDIT_NODES, 1)?;
        let mut scene = demo.clone();
        for &i in free {
            let o = &mut scene.objects[i];
            // Unplaced, its orientation is synthesis' choice when it may
            // turn (a turned block always may).
            o.turnable = may_turn(o, &self.turnable);
            o.turned = false;
            o.x = None;
            o.y = None;
        }
        let opts = SynthOptions {
            contact: self.contact,
            stop: (self.stop.clone())
                .by(self
                    .solve_time
                    .and_then(|t| std::time::Instant::now().checked_add(t)))
                .nodes_at_most(Some(nodes)),
            seed: self.seed,
            like: self.like.cloned(),
            explain: false,
            lns: None,
            ..SynthOptions::default()
        };
        let r = synthesize(&scene, rules, &opts).ok()?;
        meter.spend(r.stats.nodes, 1);
        let cost = r.resemblance.map_or(0, |c| c.cost);
        r.scene.map(|s| (s, cost))
    }

    /// `layout` (an edit of demonstration `d`) as a probe of the held
    /// rules `targets`, after the evaluator confirms it breaks each of them
    /// and keeps every other held rule.
    fn probe(
        &self,
        held: &RuleSet,
        targets: &[usize],
        d: usize,
        layout: Scene,
        cost: u64,
    ) -> Option<Probe> {
        let rule = &held.rules[targets[0]];
        let ev = evaluate(&layout, held, self.contact);
        let breaks = targets
            .iter()
            .all(|&t| ev.rules[t].satisfied < ev.rules[t].subjects);
        let keeps = ev
            .rules
            .iter()
            .enumerate()
            .all(|(j, e)| targets.contains(&j) || e.satisfied == e.subjects);
        if !(breaks && keeps) {
            // The engine and the evaluator disagree: never shown.
            log::warn!("ask: an edit probe of {} failed the evaluator", rule.name);
            return None;
        }
        let demo = &self.demos[d];
        let moved: Vec<Moved> = demo
            .objects
            .iter()
            .zip(&layout.objects)
            .filter(|(a, b)| (a.x, a.y, a.turned) != (b.x, b.y, b.turned))
            .map(|(a, _)| Moved {
                id: a.id.clone(),
                x: a.x.unwrap_or(0),
                y: a.y.unwrap_or(0),
                turned: a.turned,
            })
            .collect();
        let mut broken: Vec<String> = Vec::new();
        for &t in targets {
            for v in &ev.rules[t].violators {
                if !broken.contains(v) {
                    broken.push(v.clone());
                }
            }
        }
        Some(Probe {
            rule: rule.name.clone(),
            scene: layout,
            broken,
            cost,
            time_ms: 0.0,
            edit: Some(Edit { demo: d, moved }),
        })
    }
}
