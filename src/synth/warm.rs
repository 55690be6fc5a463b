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
//! so far (a *mosaic*). A class with more objects than the mosaic gives
//! positions then *grows* its pattern: flush against its positions, along
//! its column or row when they form one (`grow`). Positions off the
//! problem's grid or outside an object's domain are skipped; objects left
//! without a position get none.
//!
//! Measured (`bench tasks --sizes 2,3 --problems-out`, then `synth
//! --warm-start DEMOS --time-limit 10` on each, both engines in parallel
//! on the 2-core machine): growing raised the score on 12 of the 20
//! problems (at 3×: 0.805 → 0.929, 0.805 → 0.939, 0.861 → 0.998, 0.735
//! → 0.907, 0.746 → 0.866), lowered it on one by 10⁻⁴, and proved the
//! same 7; `RCCPACK_WARM_GROW=off` turns it off.
//!
//! An object that may turn takes the footprint its class and size show
//! most often in the scenes (flat on ties) and is hinted to lie that way:
//! a demonstrator who stands blocks on end hints standing blocks. Measured
//! (`bench tasks --sizes 2 --turnable --time-limit 30`, four tasks): proven
//! 1 → 3 of 4, orientation habits kept 2 → 6 of 6.
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
pub(super) fn hint_values(
    model: &Model,
    problem: &Scene,
    scenes: &[Scene],
) -> Option<Vec<Option<i64>>> {
    if scenes.is_empty() {
        return None;
    }
    let wanted = wanted(model, problem, scenes);
    let per_scene: Vec<Positions> = scenes
        .iter()
        .map(|s| usable_positions(model, &wanted, s))
        .collect();
    let order = scene_order(&per_scene, &wanted);
    let (mut chosen, mut taken) = mosaic(model, problem, &per_scene, &order, &wanted);
    if model.tuning.warm_grow {
        grow(model, &wanted, &mut chosen, &mut taken);
    }
    assign(model, problem, &wanted, chosen)
}

/// The problem's movable objects per key, in problem order. An object
/// that may turn takes the footprint the scenes show its class and size
/// in most often (flat on ties), so a demonstrator who stands blocks on
/// end gives positions for standing blocks.
fn wanted(model: &Model, problem: &Scene, scenes: &[Scene]) -> BTreeMap<Key, Vec<usize>> {
    let mut shown: BTreeMap<Key, usize> = BTreeMap::new();
    for obj in scenes.iter().flat_map(|s| &s.objects) {
        if obj.is_placed() && !obj.fixed {
            *shown.entry(key(obj)).or_default() += 1;
        }
    }
    let mut wanted: BTreeMap<Key, Vec<usize>> = BTreeMap::new();
    for (o, obj) in problem.objects.iter().enumerate() {
        if let (Coord::Var(_), Coord::Var(_)) = model.coords[o] {
            let flat = key(obj);
            let turned = (flat.0.clone(), flat.2, flat.1);
            let count = |k: &Key| shown.get(k).copied().unwrap_or(0);
            let k = if model.turn_vars[o].is_some() && count(&turned) > count(&flat) {
                turned
            } else {
                flat
            };
            wanted.entry(k).or_default().push(o);
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
        let key = key(obj);
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
    // How many scenes use each (key, position): counted once, so that
    // ordering many scenes stays linear in them (a warm start of thousands
    // of scenes once took a minute here).
    let mut scenes_with: std::collections::HashMap<(&Key, (i64, i64)), usize> =
        std::collections::HashMap::new();
    for m in per_scene {
        let mut seen = std::collections::HashSet::new();
        for (k, ps) in m {
            for &p in ps {
                if seen.insert((k, p)) {
                    *scenes_with.entry((k, p)).or_default() += 1;
                }
            }
        }
    }
    // Per position of scene `i`, the other scenes that use it too.
    let typical = |i: usize| -> usize {
        per_scene[i]
            .iter()
            .flat_map(|(k, ps)| ps.iter().map(move |&p| (k, p)))
            .map(|kp| scenes_with.get(&kp).map_or(0, |n| n.saturating_sub(1)))
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
) -> (Positions, Vec<Rect>) {
    // Rectangles (real units) already taken.
    let mut taken: Vec<Rect> = problem
        .objects
        .iter()
        .filter_map(|o| {
            let (w, h) = o.footprint();
            Some((o.x?, o.y?, w, h))
        })
        .collect();
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
    (chosen, taken)
}

/// `(x, y, width, height)` in real units.
type Rect = (i64, i64, i64, i64);

/// An object's key: its class and footprint.
fn key(o: &crate::scene::Object) -> Key {
    let (w, h) = o.footprint();
    (o.class.clone(), w, h)
}

fn overlaps(a: &Rect, b: &Rect) -> bool {
    a.0 < b.0 + b.2 && b.0 < a.0 + a.2 && a.1 < b.1 + b.3 && b.1 < a.1 + a.3
}

/// The demonstrations' patterns grown to more objects: while a key has
/// fewer positions than objects, add a free position flush against one
/// it has — along the column when all its positions share `x`, along the
/// row when they share `y`, else on any side — nearest the positions'
/// centre first. A box holding twice the demonstrations' blocks then
/// starts from the demonstrated column twice as long, not from half a
/// column and a greedy packing of the rest.
fn grow(
    model: &Model,
    wanted: &BTreeMap<Key, Vec<usize>>,
    chosen: &mut Positions,
    taken: &mut Vec<Rect>,
) {
    let g = model.grid.max(1);
    for (key, objs) in wanted {
        let Some(got) = chosen.get_mut(key) else {
            continue;
        };
        let (Coord::Var(vx), Coord::Var(vy)) = model.coords[objs[0]] else {
            continue;
        };
        let (ubx, uby) = (model.vars[vx].ub, model.vars[vy].ub);
        let (cw, ch) = ((key.1 + g - 1) / g, (key.2 + g - 1) / g);
        while !got.is_empty() && got.len() < objs.len() {
            let column = got.iter().all(|p| p.0 == got[0].0);
            let row = got.iter().all(|p| p.1 == got[0].1);
            let steps: &[(i64, i64)] = match (column, row) {
                (true, false) => &[(0, 1), (0, -1)],
                (false, true) => &[(1, 0), (-1, 0)],
                _ => &[(0, 1), (0, -1), (1, 0), (-1, 0)],
            };
            let n = i64::try_from(got.len()).unwrap_or(1);
            let (sx, sy) = got
                .iter()
                .fold((0i64, 0i64), |(a, b), p| (a + p.0, b + p.1));
            let mut best: Option<(i64, (i64, i64))> = None;
            for &(px, py) in got.iter() {
                for &(dx, dy) in steps {
                    let (gx, gy) = (px + dx * cw, py + dy * ch);
                    if !(0..=ubx).contains(&gx) || !(0..=uby).contains(&gy) {
                        continue;
                    }
                    let rect = (
                        model.origin.0 + g * gx,
                        model.origin.1 + g * gy,
                        key.1,
                        key.2,
                    );
                    if taken.iter().any(|t| overlaps(t, &rect)) {
                        continue;
                    }
                    let d = (gx * n - sx).abs() + (gy * n - sy).abs();
                    if best.is_none_or(|(bd, bp)| (d, (gx, gy)) < (bd, bp)) {
                        best = Some((d, (gx, gy)));
                    }
                }
            }
            let Some((_, (gx, gy))) = best else {
                break;
            };
            taken.push((
                model.origin.0 + g * gx,
                model.origin.1 + g * gy,
                key.1,
                key.2,
            ));
            got.push((gx, gy));
        }
    }
}

/// The chosen positions given to each key's objects in problem order,
/// sorted by (y, x): the order symmetry breaking imposes on
/// interchangeable objects, so a hint never fights it; an object that may
/// turn is hinted to lie as its key shows it. `None` when no object got a
/// position.
fn assign(
    model: &Model,
    problem: &Scene,
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
            if let Some(t) = model.turn_vars[o] {
                hint[t] = Some(i64::from(key != self::key(&problem.objects[o])));
            }
        }
    }
    any.then_some(hint)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::relations::Contact;
    use crate::rules::parse_rules;
    use crate::scene::{Object, Space};
    use crate::synth::model::BuildOptions;

    fn scene(objects: Vec<Object>) -> Scene {
        Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 100,
                height: 100,
            },
            grid: 10,
            objects,
        }
    }

    /// The hinted grid positions of `problem`'s objects, sorted.
    fn hinted(problem: &Scene, demo: Scene) -> Vec<(i64, i64)> {
        let rules = parse_rules("rule r: EC_E(R, *) | !EC_E(R, *)\n").unwrap();
        let opts = BuildOptions {
            contact: Contact::Point,
            rules: true,
            symmetry_breaking: true,
            redundant: true,
            tuning: Default::default(),
        };
        let model = Model::build(problem, &rules, opts);
        let hint = hint_values(&model, problem, &[demo]).unwrap();
        let mut at: Vec<(i64, i64)> = (0..problem.objects.len())
            .map(|o| match model.coords[o] {
                (Coord::Var(x), Coord::Var(y)) => (hint[x].unwrap(), hint[y].unwrap()),
                _ => panic!("object {o} is not movable"),
            })
            .collect();
        at.sort_unstable();
        at
    }

    /// A demonstrated column of two blocks, a problem with four: the hint
    /// is the column grown to four, flush, every position free.
    #[test]
    fn a_demonstrated_column_grows_to_more_objects() {
        let demo = scene(vec![
            Object::placed("a", "R", 80, 0, 20, 20),
            Object::placed("b", "R", 80, 20, 20, 20),
        ]);
        let problem = scene(
            (0..4)
                .map(|i| Object::movable(&format!("r{i}"), "R", 20, 20))
                .collect(),
        );
        assert_eq!(hinted(&problem, demo), vec![(8, 0), (8, 2), (8, 4), (8, 6)]);
    }

    /// A demonstrated row that meets the box's edge grows the other way.
    #[test]
    fn a_row_grows_away_from_the_edge() {
        let demo = scene(vec![
            Object::placed("a", "G", 60, 90, 20, 10),
            Object::placed("b", "G", 80, 90, 20, 10),
        ]);
        let problem = scene(
            (0..3)
                .map(|i| Object::movable(&format!("g{i}"), "G", 20, 10))
                .collect(),
        );
        assert_eq!(hinted(&problem, demo), vec![(4, 9), (6, 9), (8, 9)]);
    }

    /// Blocks the demonstration stands on end: turnable blocks of the
    /// problem are hinted to lie turned, at the standing blocks' places
    /// (the column grown); laid flat in the demonstration, hinted flat.
    #[test]
    fn a_demonstrated_orientation_is_hinted_to_blocks_that_turn() {
        let rules = parse_rules("rule r: EC_E(L, *) | !EC_E(L, *)\n").unwrap();
        let opts = BuildOptions {
            contact: Contact::Point,
            rules: true,
            symmetry_breaking: true,
            redundant: true,
            tuning: Default::default(),
        };
        let problem = scene(
            (0..3)
                .map(|i| Object::movable(&format!("l{i}"), "L", 20, 10).with_turnable())
                .collect(),
        );
        let model = Model::build(&problem, &rules, opts);
        let hints = |demo: Scene| {
            let hint = hint_values(&model, &problem, &[demo]).unwrap();
            let mut at: Vec<(i64, i64, i64)> = (0..problem.objects.len())
                .map(|o| match (model.coords[o], model.turn_vars[o]) {
                    ((Coord::Var(x), Coord::Var(y)), Some(t)) => {
                        (hint[x].unwrap(), hint[y].unwrap(), hint[t].unwrap())
                    }
                    _ => panic!("object {o} is not movable and turnable"),
                })
                .collect();
            at.sort_unstable();
            at
        };
        let standing = scene(vec![
            Object::placed("a", "L", 0, 0, 20, 10).with_turned(),
            Object::placed("b", "L", 10, 0, 20, 10).with_turned(),
        ]);
        assert_eq!(hints(standing), vec![(0, 0, 1), (1, 0, 1), (2, 0, 1)]);
        let flat = scene(vec![
            Object::placed("a", "L", 0, 0, 20, 10),
            Object::placed("b", "L", 0, 10, 20, 10),
        ]);
        assert_eq!(hints(flat), vec![(0, 0, 0), (0, 1, 0), (0, 2, 0)]);
    }
}
