//! Orientation choices of the turnable objects: how many of each group of
//! interchangeable ones lie turned, one engine per choice ([`Branch`]).

use super::{like_key, SampleError, Sampler};
use crate::scene::Scene;
use crate::synth::backend::Backend;
use crate::synth::model::Model;
use crate::synth::SynthError;
use std::collections::BTreeMap;

impl Sampler {
    /// The orientation choice a layout of the problem lies in: how many of
    /// each group of turnable objects it turns.
    pub(super) fn branch_of(&self, scene: &Scene) -> usize {
        let turned: Vec<usize> = (self.turning.iter())
            .map(|g| g.iter().filter(|&&i| scene.objects[i].turned).count())
            .collect();
        (self.branches.iter())
            .position(|br| br.turned == turned)
            .unwrap_or(0)
    }

    /// `scene` with the turned objects of every group of turnable objects
    /// first (they are interchangeable), as its orientation choice has them.
    pub(super) fn in_branch_order(&self, scene: &Scene) -> Scene {
        let mut s = scene.clone();
        for g in &self.turning {
            let mut at: Vec<(bool, Option<i64>, Option<i64>)> = (g.iter())
                .map(|&i| (!s.objects[i].turned, s.objects[i].x, s.objects[i].y))
                .collect();
            at.sort_by_key(|a| a.0);
            for (&i, (flat, x, y)) in g.iter().zip(at) {
                let o = &mut s.objects[i];
                (o.turned, o.x, o.y) = (!flat, x, y);
            }
        }
        s
    }

    /// The layout of choice `b`'s solution `v`: the problem's objects
    /// placed, turned as the choice turns them.
    pub(super) fn layout(&self, b: usize, v: &[i64]) -> Scene {
        let (model, _) = self.branches[b].model.as_ref().expect("built");
        let mut s = model.scene(&self.branches[b].problem, v);
        for (o, p) in s.objects.iter_mut().zip(&self.problem.objects) {
            o.turnable = p.turnable;
        }
        s
    }
}

/// Most orientation choices (`Π (nᵍ + 1)` over the groups of
/// interchangeable turnable objects) a sampler draws from.
pub const MAX_SAMPLE_ORIENTATIONS: usize = 256;

/// One orientation choice of a problem's turnable objects: the first
/// `turned[g]` objects of group `g` lie turned, the others flat.
pub(super) struct Branch {
    /// Turned objects per group of turnable objects.
    pub(super) turned: Vec<usize>,
    /// The problem with every orientation given.
    pub(super) problem: Scene,
    /// Its model and integer objective coefficients (built when first
    /// drawn from).
    pub(super) model: Option<(Model, Vec<i64>)>,
    pub(super) engine: Option<Box<dyn Backend>>,
    /// Groups of interchangeable unplaced objects: their x variables, in
    /// the symmetry order.
    pub(super) groups: Vec<Vec<usize>>,
    /// Every layout of this choice has been returned (or none reaches the
    /// target).
    pub(super) done: bool,
}

/// The groups of interchangeable turnable objects of `problem` and one
/// [`Branch`] per orientation choice (the choice with nothing turned
/// first); one branch, the problem as given, when nothing turns.
pub(super) fn orientation_branches(
    problem: &Scene,
) -> Result<(Vec<Vec<usize>>, Vec<Branch>), SampleError> {
    let Some((turning, choices)) = orientation_choices(problem, MAX_SAMPLE_ORIENTATIONS) else {
        let objects = (problem.objects.iter())
            .filter(|o| !o.is_placed() && o.turnable && o.is_oblong())
            .count();
        return Err(SampleError::Synth(SynthError::TooLarge(format!(
            "{objects} turnable objects give more than the {MAX_SAMPLE_ORIENTATIONS} orientation \
             choices sampling draws from; expected fewer turnable objects (drop \"turnable\" from \
             some, or make interchangeable ones the same class and size)"
        ))));
    };
    let branches = (choices.into_iter())
        .map(|(turned, problem)| Branch {
            turned,
            problem,
            model: None,
            engine: None,
            groups: Vec::new(),
            done: false,
        })
        .collect();
    Ok((turning, branches))
}

/// The orientation choices of `problem`'s turnable objects: the groups of
/// interchangeable ones (unplaced, `turnable`, oblong, one class and size;
/// indices in problem order) and per choice how many of each group lie
/// turned — the first ones of the group — with the problem oriented that
/// way (those objects `turned`, the rest of the groups no longer
/// `turnable`), the choice with nothing turned first. One choice, the
/// problem as given, when nothing turns; `None` past `max` choices.
pub(crate) type OrientationChoices = (Vec<Vec<usize>>, Vec<(Vec<usize>, Scene)>);

/// See [`OrientationChoices`].
pub(crate) fn orientation_choices(problem: &Scene, max: usize) -> Option<OrientationChoices> {
    let mut by_kind: BTreeMap<(String, i64, i64), Vec<usize>> = BTreeMap::new();
    for (i, o) in problem.objects.iter().enumerate() {
        if !o.is_placed() && o.turnable && o.is_oblong() {
            by_kind.entry(like_key(o)).or_default().push(i);
        }
    }
    let turning: Vec<Vec<usize>> = by_kind.into_values().collect();
    let count = (turning.iter()).try_fold(1usize, |acc, g| acc.checked_mul(g.len() + 1))?;
    if count > max {
        return None;
    }
    if turning.is_empty() {
        return Some((turning, vec![(Vec::new(), problem.clone())]));
    }
    let mut out = Vec::with_capacity(count);
    for c in 0..count {
        // Choice `c` in mixed radix: the first group's count fastest.
        let mut rest = c;
        let mut p = problem.clone();
        let mut turned = Vec::with_capacity(turning.len());
        for g in &turning {
            let t = rest % (g.len() + 1);
            rest /= g.len() + 1;
            for (k, &i) in g.iter().enumerate() {
                // The orientation is given: turned (and marked turnable, as
                // an oriented problem has it) or flat.
                p.objects[i].turned = k < t;
                p.objects[i].turnable = k < t;
            }
            turned.push(t);
        }
        out.push((turned, p));
    }
    Some((turning, out))
}
