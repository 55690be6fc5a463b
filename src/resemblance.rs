//! The resemblance cost of docs/guide.md#layouts-like-the-demonstrations: how far a layout's objects stand from
//! where the demonstrations put objects of the same class and size.
//!
//! # Background
//!
//! Rules say what must hold; they rarely pin down where things go. Among the
//! layouts with the best score, synthesis prefers the one *most like what
//! the person showed*: for every object that synthesis places, the distance
//! in grid steps, `⌈(|x − x'| + |y − y'|) / grid⌉`, to the nearest position
//! `(x', y')` of a movable, placed object of the same class and the same
//! `(width, height)` in any of the given scenes. An object whose class and
//! size appear in none of them adds nothing; objects already placed in the
//! problem add nothing. Each object takes its own nearest position (no
//! one-to-one matching). Positions are absolute: the scenes share the
//! problem's space and fixed objects.
//!
//! # Practical
//!
//! [`ResemblanceTarget::cost`] is *the* resemblance function: reports, the studio,
//! tests and the brute-force reference all call it, as every score comes
//! from `eval`. For the engine, `ResemblanceTarget::distance_map` precomputes, per
//! class and size, the cost of every grid position of the problem (a table,
//! not geometry): row-major over the object's grid-index domain
//! `gx ∈ 0..nx`, `gy ∈ 0..ny` with `x = space.x + grid·gx`. A test checks
//! the table against `ResemblanceTarget::object_cost` cell by cell.
//!
//! Arithmetic is done in `i128` and saturates at `u64::MAX`, so no
//! coordinate, however far out, can wrap.

use crate::scene::{Object, Scene};
use std::collections::BTreeMap;

/// The largest distance map `ResemblanceTarget::distance_map` builds (cells).
pub const MAX_MAP_CELLS: u64 = 4_000_000;

/// Why a distance map cannot be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ResemblanceError {
    /// The object's grid domain has more cells than [`MAX_MAP_CELLS`].
    #[error(
        "object `{id}` has {cells} grid positions, more than the {max} a resemblance map may have; \
         use a coarser grid or no resemblance target"
    )]
    TooManyPositions {
        /// The object.
        id: String,
        /// Its number of grid positions.
        cells: u128,
        /// The limit.
        max: u64,
    },
}

/// The positions shown in the like-scenes, per class and size.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ResemblanceTarget {
    /// `(class, width, height)` → positions `(x, y)`, sorted, one entry per
    /// shown object (a position shown twice is listed twice: the heat map
    /// draws it darker).
    positions: BTreeMap<(String, i64, i64), Vec<(i64, i64)>>,
}

/// A precomputed cost per grid position of one object (row-major: index
/// `gy·nx + gx`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DistanceMap {
    /// Grid positions along x.
    pub nx: u64,
    /// Grid positions along y.
    pub ny: u64,
    /// Cost per position, row-major.
    pub cost: Vec<u64>,
}

impl DistanceMap {
    /// The cost at grid position `(gx, gy)` (`None` outside the domain).
    pub fn at(&self, gx: u64, gy: u64) -> Option<u64> {
        if gx >= self.nx || gy >= self.ny {
            return None;
        }
        let i = usize::try_from(gy.checked_mul(self.nx)?.checked_add(gx)?).ok()?;
        self.cost.get(i).copied()
    }
    /// The smallest cost anywhere.
    pub fn min(&self) -> u64 {
        self.cost.iter().copied().min().unwrap_or(0)
    }
}

/// `⌈d / g⌉` for `d ≥ 0`, `g ≥ 1`, saturating into `u64`.
fn steps(d: i128, g: i128) -> u64 {
    let s = (d + g - 1) / g;
    u64::try_from(s).unwrap_or(u64::MAX)
}

/// The key positions are shown under: the class and the footprint (a
/// block standing on end is like the blocks shown standing on end).
fn key(o: &Object) -> (String, i64, i64) {
    let (w, h) = o.footprint();
    (o.class.clone(), w, h)
}

impl ResemblanceTarget {
    /// Collect the positions of every movable, placed object of `scenes`.
    pub fn new(scenes: &[Scene]) -> ResemblanceTarget {
        let mut positions: BTreeMap<(String, i64, i64), Vec<(i64, i64)>> = BTreeMap::new();
        for s in scenes {
            for o in &s.objects {
                if let (false, Some(x), Some(y)) = (o.fixed, o.x, o.y) {
                    positions.entry(key(o)).or_default().push((x, y));
                }
            }
        }
        for v in positions.values_mut() {
            v.sort_unstable();
        }
        ResemblanceTarget { positions }
    }

    /// Whether no scene showed any movable object.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// The positions shown for objects like `o` (same class and footprint).
    pub(crate) fn positions_of(&self, o: &Object) -> &[(i64, i64)] {
        self.positions.get(&key(o)).map_or(&[], Vec::as_slice)
    }

    /// Every `(class, width, height)` shown, with its positions.
    pub fn shown(&self) -> impl Iterator<Item = (&str, i64, i64, &[(i64, i64)])> {
        self.positions
            .iter()
            .map(|((c, w, h), p)| (c.as_str(), *w, *h, p.as_slice()))
    }

    /// The cost of object `o` at `(x, y)` on a grid of step `grid`: grid
    /// steps to the nearest shown position of its class and size, or 0 when
    /// none was shown.
    pub(crate) fn object_cost(&self, o: &Object, x: i64, y: i64, grid: i64) -> u64 {
        let g = i128::from(grid.max(1));
        self.positions_of(o)
            .iter()
            .map(|&(px, py)| {
                let d =
                    (i128::from(x) - i128::from(px)).abs() + (i128::from(y) - i128::from(py)).abs();
                steps(d, g)
            })
            .min()
            .unwrap_or(0)
    }

    /// The resemblance cost of `layout`, a complete placement of `problem`
    /// (same objects in the same order): the sum over the objects that are
    /// unplaced in `problem` (docs/guide.md#layouts-like-the-demonstrations). Objects still unplaced in `layout`
    /// add nothing.
    pub fn cost(&self, problem: &Scene, layout: &Scene) -> u64 {
        problem
            .objects
            .iter()
            .zip(&layout.objects)
            .filter(|(p, _)| !p.is_placed())
            .filter_map(|(_, o)| Some(self.object_cost(o, o.x?, o.y?, problem.grid)))
            .fold(0u64, u64::saturating_add)
    }

    /// The cost of every grid position of object `o` of `problem` (whose
    /// position is `x = space.x + grid·gx`, the whole object inside the
    /// space), or `None` when no scene showed its class and size (it adds
    /// nothing anywhere).
    pub(crate) fn distance_map(
        &self,
        problem: &Scene,
        o: &Object,
    ) -> Result<Option<DistanceMap>, ResemblanceError> {
        if self.positions_of(o).is_empty() {
            return Ok(None);
        }
        let g = problem.grid.max(1);
        let count = |room: i64| -> u64 {
            if room < 0 {
                0
            } else {
                u64::try_from(room / g).map_or(u64::MAX, |k| k.saturating_add(1))
            }
        };
        let (w, h) = o.footprint();
        let nx = count(problem.space.width.saturating_sub(w));
        let ny = count(problem.space.height.saturating_sub(h));
        let cells = u128::from(nx) * u128::from(ny);
        if cells > u128::from(MAX_MAP_CELLS) {
            return Err(ResemblanceError::TooManyPositions {
                id: o.id.clone(),
                cells,
                max: MAX_MAP_CELLS,
            });
        }
        let mut cost = Vec::with_capacity(cells as usize);
        for gy in 0..ny as i64 {
            let y = problem.space.y.saturating_add(g.saturating_mul(gy));
            for gx in 0..nx as i64 {
                let x = problem.space.x.saturating_add(g.saturating_mul(gx));
                cost.push(self.object_cost(o, x, y, g));
            }
        }
        Ok(Some(DistanceMap { nx, ny, cost }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(objects: &str) -> Scene {
        Scene::from_json(&format!(
            r#"{{"space":{{"x":5,"y":-3,"width":60,"height":50}},"grid":10,"objects":[{objects}]}}"#
        ))
        .unwrap()
    }

    #[test]
    fn cost_is_grid_steps_to_the_nearest_same_class_same_size_position_rounded_up() {
        let like = ResemblanceTarget::new(&[
            scene(r#"{"id":"a","class":"A","x":5,"y":-3,"width":10,"height":10}"#),
            scene(
                r#"{"id":"a","class":"A","x":45,"y":27,"width":10,"height":10},
                   {"id":"b","class":"A","x":25,"y":-3,"width":20,"height":10},
                   {"id":"w","class":"A","x":15,"y":17,"width":10,"height":10,"fixed":true}"#,
            ),
        ]);
        let problem = scene(
            r#"{"id":"p","class":"A","width":10,"height":10},
               {"id":"q","class":"A","width":20,"height":10},
               {"id":"z","class":"Z","width":10,"height":10},
               {"id":"k","class":"A","x":15,"y":7,"width":10,"height":10}"#,
        );
        let mut layout = problem.clone();
        for (i, (x, y)) in [(15, 7), (5, 17), (45, 37)].into_iter().enumerate() {
            layout.objects[i].x = Some(x);
            layout.objects[i].y = Some(y);
        }
        // p at (15, 7): nearest shown 10×10 A is (5, -3): 20 units = 2 steps
        // (the fixed A at (15, 17), one step away, does not count). q (20×10) at (5, 17):
        // (25, -3) is 40 units = 4 steps. z: class never shown, 0. k was
        // already placed: 0.
        assert_eq!(like.cost(&problem, &layout), 6);
        // Rounding up: 5 units is one step.
        let o = &problem.objects[0];
        assert_eq!(like.object_cost(o, 10, -3, 10), 1);
        assert_eq!(like.object_cost(o, 5, -3, 10), 0);
    }

    #[test]
    fn distance_map_equals_object_cost_everywhere() {
        let like = ResemblanceTarget::new(&[scene(
            r#"{"class":"A","x":8,"y":1,"width":10,"height":7},
               {"class":"A","x":42,"y":30,"width":10,"height":7}"#,
        )]);
        let problem = scene(r#"{"id":"p","class":"A","width":10,"height":7}"#);
        let o = &problem.objects[0];
        let map = like.distance_map(&problem, o).unwrap().unwrap();
        assert_eq!((map.nx, map.ny), (6, 5));
        for gy in 0..map.ny {
            for gx in 0..map.nx {
                let (x, y) = (5 + 10 * gx as i64, -3 + 10 * gy as i64);
                assert_eq!(map.at(gx, gy), Some(like.object_cost(o, x, y, 10)));
            }
        }
        assert_eq!(map.at(6, 0), None);
        let unseen = scene(r#"{"id":"u","class":"U","width":10,"height":7}"#);
        assert_eq!(like.distance_map(&unseen, &unseen.objects[0]), Ok(None));
    }

    #[test]
    fn far_coordinates_saturate_and_huge_maps_are_refused() {
        // Built in code: the scene loader refuses such coordinates, but
        // the library function must not wrap on them either.
        let far = Object {
            id: "f".into(),
            class: "A".into(),
            x: Some(-4_000_000_000_000_000_000),
            y: Some(0),
            width: 1,
            height: 1,
            fixed: false,
            turnable: false,
            turned: false,
        };
        let like = ResemblanceTarget::new(&[Scene {
            space: crate::scene::Space {
                x: i64::MIN / 2,
                y: 0,
                width: i64::MAX,
                height: 10,
            },
            grid: 1,
            objects: vec![far],
        }]);
        let o = Object {
            id: "a".into(),
            class: "A".into(),
            x: None,
            y: None,
            width: 1,
            height: 1,
            fixed: false,
            turnable: false,
            turned: false,
        };
        assert_eq!(like.object_cost(&o, i64::MAX, i64::MAX, 1), u64::MAX);
        let problem = Scene::from_json(
            r#"{"space":{"width":100000,"height":100000},"grid":1,"objects":[{"id":"a","class":"A","width":1,"height":1}]}"#,
        )
        .unwrap();
        assert!(matches!(
            like.distance_map(&problem, &problem.objects[0]),
            Err(ResemblanceError::TooManyPositions { .. })
        ));
    }
}
