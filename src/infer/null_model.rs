//! The null model of docs/guide.md#learning: random complete scenes that keep each
//! demonstration's objects but forget where the movable ones were.
//!
//! # Background
//!
//! Random scene `i` copies demonstration `i mod d`. Fixed objects stay put;
//! movable objects are re-placed one by one, in a random order, at uniformly
//! random grid positions (`x = space.x + k·grid`, the whole object inside the
//! space) whose interior overlaps nothing placed so far. An object that finds
//! no free position in [`MAX_TRIES`] draws makes the whole scene start over;
//! after [`MAX_RESAMPLES`] restarts the objects are declared unplaceable.
//! An object that turns (not square, and `turned` or `turnable` in the
//! demonstration; docs/language.md#orientation) lies turned or not with
//! probability ½ each, drawn before its position (both orientations that
//! fit the space; one that does not fit is never drawn).
//!
//! # Practical
//!
//! * Occupancy: when every size, and every fixed object's offset from the
//!   space's corner, is a multiple of the grid step, each object covers whole
//!   grid cells and a try is a check of a few bits in a cell bitset
//!   (`Occupancy::Cells`). Otherwise every try scans the placed rectangles
//!   (`Occupancy::Scan`); both give the same answers.
//! * Determinism: sample `i` draws from `ChaCha8Rng::seed_from_u64(seed)` on
//!   stream `i`, so a sample does not depend on which thread makes it, and
//!   the per-statement counts are integers summed in any order.
//! * Counts: a per-object statement counts the subject objects that satisfy
//!   it, a scene-level statement the scenes in which it holds (docs/guide.md#learning).
//!   Landmarks are resolved by id in each scene's copy of its
//!   demonstration (fixed objects never move, so every random copy of a
//!   demonstration has the same landmarks).

use super::InferError;
use crate::eval::CompiledRule;
use crate::relations::{ClassAtoms, ClassIndex, Contact};
use crate::rules::Scope;
use crate::scene::{Rect, Scene};
use rand::seq::SliceRandom;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Draws per object before the scene is started over.
pub(super) const MAX_TRIES: usize = 1000;
/// Scene restarts before the objects are declared unplaceable.
pub(super) const MAX_RESAMPLES: usize = 100;

/// A cell bitset or a list of rectangles.
#[derive(Debug, Clone)]
enum Occupancy {
    /// Grid-aligned: one bit per grid cell, row-major, `words` u64 per row.
    Cells { words: usize, bits: Vec<u64> },
    /// Anything else: the placed rectangles.
    Scan(Vec<Rect>),
}

/// How to re-place the objects of one demonstration.
#[derive(Debug, Clone)]
struct Plan {
    grid: i64,
    space: Rect,
    /// Occupancy with only the fixed objects placed.
    fixed: Occupancy,
    /// Movable object indices and their number of grid positions along x
    /// and y (`kx ∈ 0..nx`), as demonstrated and, for an object that turns
    /// and fits turned too, turned.
    movable: Vec<(usize, Positions, Option<Positions>)>,
}

/// Grid positions along x and y, and the orientation (turned or not) they
/// are for.
#[derive(Debug, Clone, Copy)]
struct Positions {
    nx: i64,
    ny: i64,
    turned: bool,
}

/// The `(word, mask)` pieces of a bitset row that cover bits
/// `start..start + len`.
fn cell_masks(start: usize, len: usize) -> impl Iterator<Item = (usize, u64)> {
    let end = start + len;
    let mut i = start;
    std::iter::from_fn(move || {
        if i >= end {
            return None;
        }
        let (w, b) = (i / 64, i % 64);
        let n = (64 - b).min(end - i);
        let mask = if n == 64 {
            u64::MAX
        } else {
            ((1u64 << n) - 1) << b
        };
        i += n;
        Some((w, mask))
    })
}

fn cell_range_free(row: &[u64], start: usize, len: usize) -> bool {
    cell_masks(start, len).all(|(w, mask)| row[w] & mask == 0)
}

fn cell_range_set(row: &mut [u64], start: usize, len: usize) {
    for (w, mask) in cell_masks(start, len) {
        row[w] |= mask;
    }
}

impl Occupancy {
    /// Whether `r` (grid-aligned in cell mode) overlaps nothing placed.
    fn free(&self, r: &Rect, plan: &Plan) -> bool {
        match self {
            Occupancy::Cells { words, bits } => {
                let (cx, cy, kw, kh) = plan.cells(r);
                (cy..cy + kh).all(|y| cell_range_free(&bits[y * words..(y + 1) * words], cx, kw))
            }
            Occupancy::Scan(rects) => rects.iter().all(|p| !p.interiors_overlap(r)),
        }
    }
    fn mark(&mut self, r: Rect, plan: &Plan) {
        match self {
            Occupancy::Cells { words, bits } => {
                let (cx, cy, kw, kh) = plan.cells(&r);
                let words = *words;
                for y in cy..cy + kh {
                    cell_range_set(&mut bits[y * words..(y + 1) * words], cx, kw);
                }
            }
            Occupancy::Scan(rects) => rects.push(r),
        }
    }
}

impl Plan {
    fn new(demo_index: usize, scene: &Scene) -> Result<Plan, InferError> {
        let g = scene.grid;
        let space = scene.space.rect();
        let mut movable = Vec::new();
        for (i, o) in scene.objects.iter().enumerate() {
            if o.fixed {
                continue;
            }
            // Both orientations of an object that turns, the others as
            // demonstrated.
            let turns = o.is_oblong() && (o.turned || o.turnable);
            let fits = |(w, h): (i64, i64), turned: bool| {
                (w <= space.w && h <= space.h).then_some(Positions {
                    nx: (space.w - w) / g + 1,
                    ny: (space.h - h) / g + 1,
                    turned,
                })
            };
            let given = fits(o.footprint(), o.turned);
            let other = if turns {
                let (w, h) = o.footprint();
                fits((h, w), !o.turned)
            } else {
                None
            };
            let (ow, oh) = o.footprint();
            let Some(first) = given.or(other) else {
                return Err(InferError::CannotPlace {
                    demo: demo_index,
                    object: o.id.clone(),
                    reason: format!(
                        "it is {}x{}, larger than the {}x{} space",
                        ow, oh, space.w, space.h
                    ),
                });
            };
            movable.push((i, first, given.and(other)));
        }
        let aligned = scene.objects.iter().all(|o| {
            o.width % g == 0
                && o.height % g == 0
                && (!o.fixed
                    || ((o.x.unwrap_or(0) - space.x) % g == 0
                        && (o.y.unwrap_or(0) - space.y) % g == 0))
        });
        // Cells along each axis, rounded up (no overflow for huge spaces).
        let nx = (space.w / g + i64::from(space.w % g != 0)) as u64;
        let ny = (space.h / g + i64::from(space.h % g != 0)) as u64;
        let words = nx.div_ceil(64);
        // Cells only while the bitset stays small (≤ 512 KiB): it is copied
        // at every scene restart.
        let use_cells = aligned && words.checked_mul(ny).is_some_and(|c| c <= 1 << 16);
        let (words, ny) = (words as usize, ny as usize);
        let mut plan = Plan {
            grid: g,
            space,
            fixed: if use_cells {
                Occupancy::Cells {
                    words,
                    bits: vec![0; words * ny],
                }
            } else {
                Occupancy::Scan(Vec::new())
            },
            movable,
        };
        let mut fixed = plan.fixed.clone();
        for o in scene.objects.iter().filter(|o| o.fixed) {
            if let Some(r) = o.rect() {
                fixed.mark(r, &plan);
            }
        }
        plan.fixed = fixed;
        Ok(plan)
    }

    /// Cell coordinates and extent of a grid-aligned rectangle.
    fn cells(&self, r: &Rect) -> (usize, usize, usize, usize) {
        let g = self.grid;
        (
            ((r.x - self.space.x) / g) as usize,
            ((r.y - self.space.y) / g) as usize,
            (r.w / g) as usize,
            (r.h / g) as usize,
        )
    }

    /// Re-place the movable objects of `scene` (a copy of this plan's
    /// demonstration) with `rng`.
    fn place(
        &self,
        scene: &mut Scene,
        rng: &mut ChaCha8Rng,
        demo: usize,
    ) -> Result<(), InferError> {
        let mut order: Vec<usize> = (0..self.movable.len()).collect();
        let mut last_failed = 0;
        for _ in 0..MAX_RESAMPLES {
            let mut occ = self.fixed.clone();
            order.shuffle(rng);
            let mut ok = true;
            for &m in &order {
                let (i, given, other) = self.movable[m];
                let p = match other {
                    Some(other) if rng.random_bool(0.5) => other,
                    _ => given,
                };
                let Positions { nx, ny, turned } = p;
                scene.objects[i].turned = turned;
                let o = &scene.objects[i];
                let (w, h) = o.footprint();
                let mut placed = None;
                for _ in 0..MAX_TRIES {
                    let kx = rng.random_range(0..nx);
                    let ky = rng.random_range(0..ny);
                    let r = Rect::new(
                        self.space.x + kx * self.grid,
                        self.space.y + ky * self.grid,
                        w,
                        h,
                    );
                    if occ.free(&r, self) {
                        placed = Some(r);
                        break;
                    }
                }
                match placed {
                    Some(r) => {
                        occ.mark(r, self);
                        let o = &mut scene.objects[i];
                        o.x = Some(r.x);
                        o.y = Some(r.y);
                    }
                    None => {
                        last_failed = i;
                        ok = false;
                        break;
                    }
                }
            }
            if ok {
                return Ok(());
            }
        }
        Err(InferError::CannotPlace {
            demo,
            object: scene.objects[last_failed].id.clone(),
            reason: format!(
                "no free grid position found in {MAX_TRIES} tries, {MAX_RESAMPLES} times over"
            ),
        })
    }
}

/// The random scenes of the null model for a set of demonstrations.
#[derive(Debug, Clone)]
pub struct NullModel<'a> {
    demos: &'a [Scene],
    plans: Vec<Plan>,
    seed: u64,
}

impl<'a> NullModel<'a> {
    /// Prepare the null model. Fails when a movable object is larger than
    /// the space.
    pub fn new(demos: &'a [Scene], seed: u64) -> Result<Self, InferError> {
        let plans = demos
            .iter()
            .enumerate()
            .map(|(i, s)| Plan::new(i, s))
            .collect::<Result<_, _>>()?;
        Ok(NullModel { demos, plans, seed })
    }

    /// Random scene `index` (a copy of demonstration `index mod d`).
    pub fn scene(&self, index: usize) -> Result<Scene, InferError> {
        let d = index % self.demos.len();
        let mut s = self.demos[d].clone();
        self.place_into(index, &mut s)?;
        Ok(s)
    }

    fn rng(&self, index: usize) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(index as u64);
        rng
    }

    /// Re-place into `scene`, which must be a copy of demonstration
    /// `index mod d` (movable positions are overwritten).
    fn place_into(&self, index: usize, scene: &mut Scene) -> Result<(), InferError> {
        let d = index % self.demos.len();
        self.plans[d].place(scene, &mut self.rng(index), d)
    }

    /// Over `samples` random scenes, per statement: for a per-object
    /// statement, how many subject objects satisfy it; for a scene-level
    /// statement (docs/guide.md#learning), in how many scenes it holds. `classes` must cover
    /// every class of the demonstrations and every landmark of the
    /// statements (landmarks are resolved per scene, by id).
    ///
    /// Parallel over samples; the counts are integers, so the result does
    /// not depend on the number of threads. On failure the error is the one
    /// of the lowest failing sample.
    pub fn count(
        &self,
        samples: usize,
        classes: &ClassIndex,
        rules: &[CompiledRule],
        contact: Contact,
    ) -> Result<Vec<u64>, InferError> {
        self.count_until(
            samples,
            classes,
            rules,
            contact,
            &crate::stop::Stop::never(),
        )
    }

    /// [`NullModel::count`] that stops with [`InferError::TimeLimit`] once
    /// `stop`'s deadline passes, and with [`InferError::Cancelled`] once its
    /// flag is set (both checked before each random scene).
    pub fn count_until(
        &self,
        samples: usize,
        classes: &ClassIndex,
        rules: &[CompiledRule],
        contact: Contact,
        stop: &crate::stop::Stop,
    ) -> Result<Vec<u64>, InferError> {
        let by_class = self.objects_by_class(classes);
        let none: Vec<usize> = Vec::new();
        let subjects_of = |d: usize, r: &CompiledRule| -> &[usize] {
            by_class[d].get(r.subject).unwrap_or(&none)
        };
        let first_failure = AtomicUsize::new(usize::MAX);
        type Acc = (Vec<Scene>, Vec<u64>, Option<(usize, InferError)>);
        let merge_err = lowest_failure;
        let (counts, err) = (0..samples)
            .into_par_iter()
            .with_min_len(16)
            .fold(
                || -> Acc { (self.demos.to_vec(), vec![0u64; rules.len()], None) },
                |(mut scratch, mut counts, err), i| {
                    if i > first_failure.load(Ordering::Relaxed) {
                        return (scratch, counts, err);
                    }
                    if let Some(reason) = stop.reason() {
                        first_failure.fetch_min(i, Ordering::Relaxed);
                        let e = match reason {
                            crate::stop::Reason::Cancelled => InferError::Cancelled,
                            _ => InferError::TimeLimit { samples },
                        };
                        return (scratch, counts, merge_err(err, Some((i, e))));
                    }
                    let d = i % self.demos.len();
                    let scene = &mut scratch[d];
                    if let Err(e) = self.place_into(i, scene) {
                        first_failure.fetch_min(i, Ordering::Relaxed);
                        return (scratch, counts, merge_err(err, Some((i, e))));
                    }
                    let atoms = ClassAtoms::new(scene, classes, contact);
                    let n = scene.objects.len();
                    add_counts(&atoms, n, rules, |r| subjects_of(d, r), &mut counts);
                    (scratch, counts, err)
                },
            )
            .map(|(_, c, e)| (c, e))
            .reduce(
                || (vec![0u64; rules.len()], None),
                |(mut a, ea), (b, eb)| {
                    for (x, y) in a.iter_mut().zip(&b) {
                        *x += y;
                    }
                    (a, merge_err(ea, eb))
                },
            );
        match err {
            Some((_, e)) => Err(e),
            None => Ok(counts),
        }
    }

    /// Per demonstration, per class, the object indices.
    fn objects_by_class(&self, classes: &ClassIndex) -> Vec<Vec<Vec<usize>>> {
        self.demos
            .iter()
            .map(|s| {
                let mut v = vec![Vec::new(); classes.len()];
                for (i, o) in s.objects.iter().enumerate() {
                    if let Some(c) = classes.get(&o.class) {
                        v[c].push(i);
                    }
                }
                v
            })
            .collect()
    }
}

/// Of two failures (sample index, error), the one of the lower sample.
fn lowest_failure(
    a: Option<(usize, InferError)>,
    b: Option<(usize, InferError)>,
) -> Option<(usize, InferError)> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if x.0 <= y.0 { x } else { y }),
        (x, None) | (None, x) => x,
    }
}

/// Add one random scene's counts (its `n` objects' atoms) to `counts`: per
/// rule, the subject objects that satisfy it, or whether the scene-level
/// statement holds.
fn add_counts<'a>(
    atoms: &ClassAtoms,
    n: usize,
    rules: &[CompiledRule],
    subjects_of: impl Fn(&CompiledRule) -> &'a [usize],
    counts: &mut [u64],
) {
    for (k, r) in rules.iter().enumerate() {
        if r.scope == Scope::Group {
            counts[k] += u64::from(r.scene_holds(atoms, n));
            continue;
        }
        let objects = subjects_of(r);
        let c = objects
            .iter()
            .filter(|&&o| r.formula.eval(atoms, o))
            .count() as u64;
        counts[k] += match r.scope {
            Scope::Each => c,
            Scope::Scene(q) => u64::from(q.holds(c as u32, objects.len() as u32)),
            Scope::Group => 0,
        };
    }
}
