//! Warm starts: a first layout assembled from the demonstrations.
//!
//! # Background
//!
//! Every demonstration keeps every rule the learner wrote (that is what a
//! candidate is), so the positions a demonstration gives its objects are,
//! most of the time, a score-1 layout of *its* objects. A problem usually
//! holds more objects than any demonstration, but the demonstrations'
//! positions are still the best guess of where objects of each class and
//! size belong.
//!
//! # Practical
//!
//! [`hint_values`] turns complete scenes into one preferred grid value per
//! model variable: the scenes are ranked by how typical they are (how often
//! the other scenes show their positions for the same class and exact
//! size; ties: how many of the problem's movable objects they host), and
//! their
//! positions are handed out in that order — the best scene's whole layout
//! first, then positions of the other scenes that overlap nothing chosen
//! so far (a *mosaic*). Positions off the problem's grid or outside an
//! object's domain are skipped; objects left without a position get none.
//!
//! The engine tries the hinted values first ([`super::backend::Backend::hint`])
//! and places the rest with its greedy first phase; propagation and
//! learning repair whatever the hint gets wrong (an overlap with a fixed
//! object, a broken hard rule), so a hint is never returned unchecked and
//! never changes what is optimal — only how soon a good layout is found.
//!
//! # How to extend
//!
//! Another source of hints (the previous probe of `ask`, a user's sketch)
//! is one more list of complete scenes; a smarter assignment of objects to
//! positions (e.g. matching by id) goes into [`hint_values`].

use super::model::{Coord, Model};
use crate::scene::Scene;
use std::collections::BTreeMap;

/// `(class, width, height)`.
type Key = (String, i64, i64);

/// Usable grid positions per key.
type Positions = BTreeMap<Key, Vec<(i64, i64)>>;

/// One preferred grid value per variable of `model` (`None`: no
/// preference), from the placements of the movable objects of `scenes`;
/// `None` when no scene gives any usable position.
pub fn hint_values(model: &Model, problem: &Scene, scenes: &[Scene]) -> Option<Vec<Option<i64>>> {
    if scenes.is_empty() {
        return None;
    }
    let wanted = wanted(model, problem);
    let per_scene: Vec<Positions> = scenes
        .iter()
        .map(|s| usable_positions(model, &wanted, s))
        .collect();
    let order = scene_order(&per_scene, &wanted);
    let chosen = mosaic(model, problem, &per_scene, &order, &wanted);
    assign(model, &wanted, chosen)
}

/// The problem's movable objects per key, in problem order.
fn wanted(model: &Model, problem: &Scene) -> BTreeMap<Key, Vec<usize>> {
    let mut wanted: BTreeMap<Key, Vec<usize>> = BTreeMap::new();
    for (o, obj) in problem.objects.iter().enumerate() {
        if let (Coord::Var(_), Coord::Var(_)) = model.coords[o] {
            wanted
                .entry((obj.class.clone(), obj.width, obj.height))
                .or_default()
                .push(o);
        }
    }
    wanted
}

/// The usable positions of scene `s` per key (grid values on the model's
/// grid and inside the objects' domains), in scene order.
fn usable_positions(model: &Model, wanted: &BTreeMap<Key, Vec<usize>>, s: &Scene) -> Positions {
    let mut m: Positions = BTreeMap::new();
    for obj in &s.objects {
        let (Some(x), Some(y)) = (obj.x, obj.y) else {
            continue;
        };
        let key = (obj.class.clone(), obj.width, obj.height);
        let Some(objs) = wanted.get(&key) else {
            continue;
        };
        if obj.fixed {
            continue;
        }
        // Every object of a key has the same domain (same size).
        let (Coord::Var(vx), Coord::Var(vy)) = model.coords[objs[0]] else {
            continue;
        };
        let (dx, dy) = (x - model.origin.0, y - model.origin.1);
        if dx.rem_euclid(model.grid) != 0 || dy.rem_euclid(model.grid) != 0 {
            continue;
        }
        let (gx, gy) = (dx.div_euclid(model.grid), dy.div_euclid(model.grid));
        if (0..=model.vars[vx].ub).contains(&gx) && (0..=model.vars[vy].ub).contains(&gy) {
            m.entry(key).or_default().push((gx, gy));
        }
    }
    m
}

/// The scenes in the order their positions are handed out: the most
/// typical first — the one whose positions the other scenes show most
/// often (a layout only one demonstration used comes late); ties: the one
/// that hosts the most objects, then file order.
fn scene_order(per_scene: &[Positions], wanted: &BTreeMap<Key, Vec<usize>>) -> Vec<usize> {
    let hosts = |m: &Positions| -> usize {
        m.iter()
            .map(|(k, ps)| ps.len().min(wanted.get(k).map_or(0, Vec::len)))
            .sum()
    };
    let typical = |i: usize| -> usize {
        per_scene[i]
            .iter()
            .flat_map(|(k, ps)| ps.iter().map(move |p| (k, p)))
            .map(|(k, p)| {
                per_scene
                    .iter()
                    .enumerate()
                    .filter(|&(j, m)| j != i && m.get(k).is_some_and(|q| q.contains(p)))
                    .count()
            })
            .sum()
    };
    let mut order: Vec<usize> = (0..per_scene.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse((typical(i), hosts(&per_scene[i]))));
    order
}

/// The mosaic: positions handed out per key, scene by scene in `order`,
/// each one that overlaps nothing taken so far (the problem's placed
/// objects and every position chosen before), until the key's objects
/// all have one.
fn mosaic(
    model: &Model,
    problem: &Scene,
    per_scene: &[Positions],
    order: &[usize],
    wanted: &BTreeMap<Key, Vec<usize>>,
) -> Positions {
    // Rectangles (real units) already taken.
    let mut taken: Vec<(i64, i64, i64, i64)> = problem
        .objects
        .iter()
        .filter_map(|o| Some((o.x?, o.y?, o.width, o.height)))
        .collect();
    let overlaps = |a: &(i64, i64, i64, i64), b: &(i64, i64, i64, i64)| {
        a.0 < b.0 + b.2 && b.0 < a.0 + a.2 && a.1 < b.1 + b.3 && b.1 < a.1 + a.3
    };
    let mut chosen: Positions = BTreeMap::new();
    for &si in order {
        for (key, positions) in &per_scene[si] {
            let room = wanted[key].len();
            for &(gx, gy) in positions {
                let got = chosen.entry(key.clone()).or_default();
                if got.len() >= room {
                    break;
                }
                let rect = (
                    model.origin.0 + model.grid * gx,
                    model.origin.1 + model.grid * gy,
                    key.1,
                    key.2,
                );
                if taken.iter().any(|t| overlaps(t, &rect)) {
                    continue;
                }
                taken.push(rect);
                got.push((gx, gy));
            }
        }
    }
    chosen
}

/// The chosen positions given to each key's objects in problem order,
/// sorted by (y, x): the order symmetry breaking imposes on
/// interchangeable objects, so a hint never fights it. `None` when no
/// object got a position.
fn assign(
    model: &Model,
    wanted: &BTreeMap<Key, Vec<usize>>,
    chosen: Positions,
) -> Option<Vec<Option<i64>>> {
    let mut hint: Vec<Option<i64>> = vec![None; model.vars.len()];
    let mut any = false;
    for (key, mut got) in chosen {
        got.sort_unstable_by_key(|&(gx, gy)| (gy, gx));
        for (&o, (gx, gy)) in wanted[&key].iter().zip(got) {
            if let (Coord::Var(vx), Coord::Var(vy)) = model.coords[o] {
                hint[vx] = Some(gx);
                hint[vy] = Some(gy);
                any = true;
            }
        }
    }
    any.then_some(hint)
}
