//! Slips (docs/guide.md#slips): a block of one demonstration that is not
//! where the person meant it.
//!
//! # The model
//!
//! Each movable object of a demonstration is a *slip* with probability `η`
//! (the slip rate): it was put down at random, so what it keeps or breaks
//! says nothing about the person's rules. Every other object keeps every
//! meant rule, as in the thesis's model. A statement broken in exactly one
//! demonstration `d` (of at least three) can then still be meant, if one
//! object `o` of `d` is a slip and the statement holds in `d` once `o` is
//! left out (`o` *repairs* it: `o` broke it as a subject, or as the object
//! another subject relates to).
//!
//! Whether `o` is a slip is weighed against the statements, each as a
//! single piece of evidence (its posterior `P'` of not being meant,
//! computed as if `o` were left out):
//!
//! - a statement `o` repairs: if `o` is no slip, the statement is broken by
//!   a placed object, so it is not meant (chance `P'`); if `o` is a slip it
//!   may be meant. Likelihood ratio `1 / P'`.
//! - a candidate about `o`'s class (which `o` keeps, like every subject):
//!   a slip keeps it by chance (`p`), a placed object keeps it if it is
//!   meant (`1 − P`) or by chance. Likelihood ratio `p / (1 − P + P·p)`.
//!
//! `log10 odds(o is a slip) = log10 (η / (1 − η)) + Σ log10 ratios`. A
//! deliberately placed object keeps its class's rare rules, which costs
//! the slip hypothesis `log10 p` each; a slipped block keeps only what is
//! common, and the rules it breaks are strong. Per demonstration the object
//! with the highest odds is its slip when the odds are above 1 (a slip is
//! likelier than not). A statement it repairs is then weighed by mixing
//! both hypotheses with the slip's chance `s`:
//! `P = s·P' + (1 − s)·1` — never below `P'`, and 1 (not meant, the
//! thesis's verdict) at `η = 0`.

use super::candidates::holds_in;
use crate::eval::CompiledRule;
use crate::relations::{ClassAtoms, ClassIndex, Contact};
use crate::rules::Scope;
use crate::scene::Scene;

/// A block judged a slip: likelier misplaced than meant.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Slip {
    /// The demonstration (0-based, as in the demonstrations file).
    pub demonstration: usize,
    /// The object's id.
    pub object: String,
    /// The object's class.
    pub class: String,
    /// `log10` of the odds that it is a slip (> 0).
    pub log10_odds: f64,
    /// Indices of the statements it repairs.
    #[serde(skip)]
    pub repairs: Vec<usize>,
}

impl Slip {
    /// The chance `s` that it is a slip.
    pub fn chance(&self) -> f64 {
        1.0 / (1.0 + 10f64.powf(-self.log10_odds))
    }
}

/// How many of a demonstration's likeliest slips are also tried at every
/// free place.
const PLACES_TRIED_FOR: usize = 2;

/// `log10 P` below which a candidate counts as held when a place for a
/// slip is weighed (`P < 0.01`, the default cutoff).
const HELD: f64 = -2.0;

/// At most this many free places are weighed per block: past it, only
/// places touching another object or the space's edge, evenly spread.
const MAX_PLACES: usize = 1000;

/// The odds of a slip the person confirmed (`s = 1` to double precision).
pub(crate) const SURE: f64 = 1000.0;

/// What [`find`] needs to know of one statement's numbers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Weighed {
    /// `p = max(ε, q)`.
    pub p: f64,
    /// `log10 P` of not being meant, every subject keeping it.
    pub log10_posterior: f64,
}

/// The statements and their numbers, as [`find`] weighs slips against them.
pub(crate) struct Evidence<'a> {
    /// The demonstrations' classes (and landmarks).
    pub classes: &'a ClassIndex,
    /// Every statement, compiled.
    pub rules: &'a [CompiledRule],
    /// The contact mode of `EC`.
    pub contact: Contact,
    /// Per statement, the one demonstration breaking it (`None`: broken in
    /// several, or in none).
    pub exceptions: &'a [Option<usize>],
    /// Per statement, whether every demonstration keeps it.
    pub candidate: &'a [bool],
    /// Per statement, its numbers (`None` when not weighed).
    pub weighed: &'a [Option<Weighed>],
}

/// Which demonstrations the person answered about.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Answered<'a> {
    /// Answered as meant, exceptions and all: no slip is looked for.
    pub meant: &'a [usize],
    /// Answered as holding a slip: its likeliest block is a slip for sure.
    pub slipped: &'a [usize],
}

/// The slips of `demos` at slip rate `eta` (at most one per
/// demonstration, in demonstration order); none at rate 0.
pub(crate) fn find(
    demos: &[Scene],
    ev: &Evidence<'_>,
    eta: f64,
    answered: Answered<'_>,
) -> Vec<Slip> {
    if eta <= 0.0 {
        return Vec::new();
    }
    let judge = Judge::new(ev, eta);
    let mut out = Vec::new();
    for (d, scene) in demos.iter().enumerate() {
        if answered.meant.contains(&d) {
            continue;
        }
        let broken_here: Vec<usize> = (0..ev.rules.len())
            .filter(|&k| ev.exceptions[k] == Some(d) && ev.weighed[k].is_some())
            .collect();
        if broken_here.is_empty() {
            continue;
        }
        let mut scored = judge.left_out(d, scene, &broken_here);
        // The likeliest first (ties: file order); the best few are also
        // tried at every free place where the person may have meant them.
        scored.sort_by(|a, b| b.log10_odds.total_cmp(&a.log10_odds));
        for slip in scored.iter_mut().take(PLACES_TRIED_FOR) {
            judge.placed(scene, &broken_here, slip);
        }
        let best = scored
            .into_iter()
            .reduce(|a, b| if b.log10_odds > a.log10_odds { b } else { a });
        let sure = answered.slipped.contains(&d);
        out.extend(best.filter(|s| sure || s.log10_odds > 0.0).map(|mut s| {
            if sure {
                s.log10_odds = SURE;
            }
            s
        }));
    }
    out
}

/// The numbers every block of every demonstration is judged with.
struct Judge<'a> {
    ev: &'a Evidence<'a>,
    /// `log10 (η / (1 − η))`.
    prior_odds: f64,
    /// Per class, what keeping its class's candidates costs a slip.
    kept_cost: Vec<f64>,
    /// The candidates held with some confidence: a place that breaks one
    /// of them is unlikely to be where the person meant the block.
    held: Vec<usize>,
}

impl<'a> Judge<'a> {
    fn new(ev: &'a Evidence<'a>, eta: f64) -> Self {
        let mut kept_cost = vec![0.0f64; ev.classes.len()];
        let mut held = Vec::new();
        for (k, r) in ev.rules.iter().enumerate() {
            let (true, Some(w)) = (ev.candidate[k], ev.weighed[k]) else {
                continue;
            };
            if w.log10_posterior < HELD {
                held.push(k);
            }
            if r.scope == Scope::Each {
                let not_meant = 10f64.powf(w.log10_posterior);
                kept_cost[r.subject] += (w.p / (1.0 - not_meant + not_meant * w.p)).log10();
            }
        }
        Judge {
            ev,
            prior_odds: eta.log10() - (1.0 - eta).log10(),
            kept_cost,
            held,
        }
    }

    /// The evidence a repaired statement gives: `−log10 P'`.
    fn evidence(&self, k: usize) -> f64 {
        -self.ev.weighed[k].map_or(0.0, |w| w.log10_posterior)
    }

    /// Every movable block of demonstration `d` whose leaving out repairs
    /// some of `broken_here`, with its odds of being a slip.
    fn left_out(&self, d: usize, scene: &Scene, broken_here: &[usize]) -> Vec<Slip> {
        let ev = self.ev;
        let mut scored = Vec::new();
        for (i, o) in scene.objects.iter().enumerate() {
            if o.fixed || !o.is_placed() {
                continue;
            }
            let Some(class) = ev.classes.get(&o.class) else {
                continue;
            };
            let mut without = scene.clone();
            without.objects.remove(i);
            let atoms = ClassAtoms::new(&without, ev.classes, ev.contact);
            let repairs: Vec<usize> = broken_here
                .iter()
                .copied()
                .filter(|&k| holds_in(&ev.rules[k], &without, &atoms))
                .collect();
            if repairs.is_empty() {
                continue;
            }
            let gain: f64 = repairs.iter().map(|&k| self.evidence(k)).sum();
            scored.push(Slip {
                demonstration: d,
                object: o.id.clone(),
                class: o.class.clone(),
                log10_odds: self.prior_odds + gain + self.kept_cost[class],
                repairs,
            });
        }
        scored
    }

    /// Add to `slip` what the best free place for its block repairs beyond
    /// leaving it out (see [`best_place`]).
    fn placed(&self, scene: &Scene, broken_here: &[usize], slip: &mut Slip) {
        let Some(i) = scene.objects.iter().position(|o| o.id == slip.object) else {
            return;
        };
        let open: Vec<usize> = broken_here
            .iter()
            .copied()
            .filter(|k| !slip.repairs.contains(k))
            .collect();
        if let Some((more, net)) = self.best_place(scene, i, &open) {
            slip.repairs.extend(more);
            slip.repairs.sort_unstable();
            slip.log10_odds += net;
        }
    }

    /// The free grid place for object `i` of `scene` where the person most
    /// likely meant it: the statements of `open` that hold there, each
    /// worth its evidence, less the evidence of every held candidate the
    /// place breaks. `None` when no place gains.
    fn best_place(&self, scene: &Scene, i: usize, open: &[usize]) -> Option<(Vec<usize>, f64)> {
        if open.is_empty() {
            return None;
        }
        let ev = self.ev;
        let mut best: Option<(Vec<usize>, f64)> = None;
        let mut moved = scene.clone();
        for (x, y) in free_places(scene, i) {
            moved.objects[i].x = Some(x);
            moved.objects[i].y = Some(y);
            let atoms = ClassAtoms::new(&moved, ev.classes, ev.contact);
            let more: Vec<usize> = open
                .iter()
                .copied()
                .filter(|&k| holds_in(&ev.rules[k], &moved, &atoms))
                .collect();
            if more.is_empty() {
                continue;
            }
            let gain: f64 = more.iter().map(|&k| self.evidence(k)).sum();
            let loss: f64 = self
                .held
                .iter()
                .filter(|&&k| !holds_in(&ev.rules[k], &moved, &atoms))
                .map(|&k| self.evidence(k))
                .sum();
            let net = gain - loss;
            if net > 0.0 && best.as_ref().is_none_or(|b| net > b.1) {
                best = Some((more, net));
            }
        }
        best
    }
}

/// The grid places where object `i` of `scene` fits (inside the space,
/// overlapping nothing), other than where it is; past [`MAX_PLACES`], only
/// those touching another object or the space's edge, in order.
fn free_places(scene: &Scene, i: usize) -> Vec<(i64, i64)> {
    let o = &scene.objects[i];
    let (w, h) = o.footprint();
    let sp = scene.space.rect();
    let g = scene.grid.max(1);
    let others: Vec<crate::scene::Rect> = scene
        .objects
        .iter()
        .enumerate()
        .filter(|&(j, _)| j != i)
        .filter_map(|(_, p)| p.rect())
        .collect();
    let mut all = Vec::new();
    let mut touching = Vec::new();
    let mut x = sp.x;
    while x.saturating_add(w) <= sp.x2() {
        let mut y = sp.y;
        while y.saturating_add(h) <= sp.y2() {
            let r = crate::scene::Rect::new(x, y, w, h);
            if (Some(x), Some(y)) != (o.x, o.y) && !others.iter().any(|p| p.interiors_overlap(&r)) {
                all.push((x, y));
                let edge = x == sp.x || y == sp.y || r.x2() == sp.x2() || r.y2() == sp.y2();
                if edge
                    || others
                        .iter()
                        .any(|p| r.x <= p.x2() && p.x <= r.x2() && r.y <= p.y2() && p.y <= r.y2())
                {
                    touching.push((x, y));
                }
            }
            y = y.saturating_add(g);
        }
        x = x.saturating_add(g);
    }
    let pick = if all.len() <= MAX_PLACES {
        all
    } else {
        touching
    };
    if pick.len() <= MAX_PLACES {
        return pick;
    }
    // Evenly over the space (the places are in scan order).
    let step = pick.len().div_ceil(MAX_PLACES);
    pick.into_iter().step_by(step).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slip_chance_follows_its_odds() {
        let s = |lo: f64| Slip {
            demonstration: 0,
            object: String::new(),
            class: String::new(),
            log10_odds: lo,
            repairs: Vec::new(),
        };
        assert!((s(0.0).chance() - 0.5).abs() < 1e-15);
        assert!((s(2.0).chance() - 100.0 / 101.0).abs() < 1e-15);
        assert!(s(400.0).chance() == 1.0);
    }
}
