//! Area first: bounds that prove at once, without the engine, that the
//! objects to place cannot all fit in the space. Every
//! bound is sound — it only ever says "cannot fit" when no layout exists —
//! and takes time linear in the objects (quadratic only in up to
//! [`MAX_UNION_OBJECTS`] placed objects).
//!
//! 1. **Area.** The movable objects' areas sum to more than the free area of
//!    the space: its area minus the union of the already placed objects
//!    (clipped to the space), which no movable object may overlap.
//! 2. **Grid footprints.** On grid step `g` an object of width `w` sits at
//!    `x = space.x + g·k` and two objects apart in `x` differ by at least
//!    `⌈w/g⌉` grid steps, so each object owns the half-open index box
//!    `[k, k + ⌈w/g⌉) × [l, l + ⌈h/g⌉)`, disjoint from every other's, all
//!    inside `⌈W/g⌉ × ⌈H/g⌉` cells: their sum bounds the count.
//! 3. **One size.** `n` objects of one footprint `w × h` that may not turn need
//!    `n ≤ ⌊(p_x − 1 + c)/c⌋ · ⌊(p_y − 1 + d)/d⌋` with `p` the positions per
//!    axis and `c = ⌈w/g⌉`, `d = ⌈h/g⌉` (each index box holds exactly one
//!    point of the lattice `(c·i, d·j)`, `i, j ≥ 1`).

use super::{Conflict, SolveStats, Status, SynthOptions, SynthResult};
use crate::scene::Scene;

/// Most placed objects whose union area is computed exactly (quadratic);
/// with more, they are not subtracted (the bound stays sound, only weaker).
pub(super) const MAX_UNION_OBJECTS: usize = 2_000;

/// Whether the bounds above prove that the unplaced objects of `problem`
/// cannot all be placed (whatever the rules).
pub(super) fn cannot_fit(problem: &Scene) -> bool {
    let s = &problem.space;
    let g = i128::from(problem.grid.max(1));
    let (sw, sh) = (i128::from(s.width), i128::from(s.height));
    let movable: Vec<_> = problem.objects.iter().filter(|o| !o.is_placed()).collect();
    if movable.is_empty() || sw <= 0 || sh <= 0 {
        return false;
    }
    // 1. Area against the free area.
    let need: i128 = movable
        .iter()
        .map(|o| i128::from(o.width) * i128::from(o.height))
        .sum();
    let placed: Vec<[i128; 4]> = problem
        .objects
        .iter()
        .filter_map(|o| o.rect())
        .filter_map(|r| {
            let x1 = i128::from(r.x).max(i128::from(s.x));
            let y1 = i128::from(r.y).max(i128::from(s.y));
            let x2 = (i128::from(r.x) + i128::from(r.w)).min(i128::from(s.x) + sw);
            let y2 = (i128::from(r.y) + i128::from(r.h)).min(i128::from(s.y) + sh);
            (x1 < x2 && y1 < y2).then_some([x1, y1, x2, y2])
        })
        .collect();
    let taken = if placed.len() <= MAX_UNION_OBJECTS {
        union_area(&placed)
    } else {
        0
    };
    if need > sw * sh - taken {
        return true;
    }
    // 2. Grid footprints (placed objects ignored).
    let cells = |v: i128| (v + g - 1) / g;
    let footprints: i128 = movable
        .iter()
        .map(|o| cells(i128::from(o.width)) * cells(i128::from(o.height)))
        .sum();
    if footprints > cells(sw) * cells(sh) {
        return true;
    }
    // 3. Per footprint, over the objects that may not turn (a turnable
    // group may split between two footprints; areas and grid footprints
    // above are the same either way).
    let mut sizes: Vec<(i64, i64, i128)> = Vec::new();
    for o in movable.iter().filter(|o| !o.turnable) {
        let (w, h) = o.footprint();
        match sizes.iter_mut().find(|k| k.0 == w && k.1 == h) {
            Some(k) => k.2 += 1,
            None => sizes.push((w, h, 1)),
        }
    }
    sizes.iter().any(|&(w, h, n)| {
        let (w, h) = (i128::from(w), i128::from(h));
        if w > sw || h > sh {
            return false; // too large: the model reports it
        }
        let per_axis = |len: i128, size: i128| {
            let positions = (len - size) / g + 1;
            let c = cells(size);
            (positions - 1 + c) / c
        };
        n > per_axis(sw, w) * per_axis(sh, h)
    })
}

/// The union area of axis-aligned boxes `[x1, y1, x2, y2]` (sweep over the
/// distinct x edges, merging y intervals in each slab).
fn union_area(boxes: &[[i128; 4]]) -> i128 {
    let mut xs: Vec<i128> = boxes.iter().flat_map(|b| [b[0], b[2]]).collect();
    xs.sort_unstable();
    xs.dedup();
    let mut area = 0;
    let mut spans: Vec<(i128, i128)> = Vec::new();
    for w in xs.windows(2) {
        let (a, b) = (w[0], w[1]);
        spans.clear();
        spans.extend(
            boxes
                .iter()
                .filter(|r| r[0] <= a && b <= r[2])
                .map(|r| (r[1], r[3])),
        );
        spans.sort_unstable();
        let mut covered = 0;
        let mut cur: Option<(i128, i128)> = None;
        for &(lo, hi) in &spans {
            match cur {
                Some((cl, ch)) if lo <= ch => cur = Some((cl, ch.max(hi))),
                Some((cl, ch)) => {
                    covered += ch - cl;
                    cur = Some((lo, hi));
                }
                None => cur = Some((lo, hi)),
            }
        }
        if let Some((cl, ch)) = cur {
            covered += ch - cl;
        }
        area += covered * (b - a);
    }
    area
}

/// The result of a problem whose objects cannot fit (see [`cannot_fit`]),
/// or `None`: what [`super::synthesize`] returns at once.
pub(super) fn infeasible_at_once(problem: &Scene, opts: &SynthOptions) -> Option<SynthResult> {
    let start = std::time::Instant::now();
    if !cannot_fit(problem) {
        return None;
    }
    Some(SynthResult {
        status: Status::Infeasible,
        scene: None,
        evaluation: None,
        conflict: opts.explain.then(|| Conflict {
            objects_cannot_fit: true,
            ..Conflict::default()
        }),
        stats: SolveStats {
            time_ms: start.elapsed().as_secs_f64() * 1000.0,
            ..SolveStats::default()
        },
        resemblance: None,
        score_bound: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn problem(space: (i64, i64), grid: i64, blocks: &[(i64, i64)], walls: &[[i64; 4]]) -> Scene {
        let mut objects = Vec::new();
        for (i, w) in walls.iter().enumerate() {
            objects.push(
                serde_json::json!({"id": format!("w{i}"), "class": "W", "fixed": true,
                "x": w[0], "y": w[1], "width": w[2], "height": w[3]}),
            );
        }
        for (i, &(w, h)) in blocks.iter().enumerate() {
            objects.push(
                serde_json::json!({"id": format!("b{i}"), "class": "R", "width": w, "height": h}),
            );
        }
        let v = serde_json::json!({"space": {"width": space.0, "height": space.1}, "grid": grid, "objects": objects});
        Scene::from_json(&v.to_string()).unwrap()
    }

    #[test]
    fn area_decides_at_once() {
        assert!(!cannot_fit(&problem((100, 100), 10, &[(10, 10); 100], &[])));
        assert!(cannot_fit(&problem((100, 100), 10, &[(10, 10); 101], &[])));
        assert!(cannot_fit(&problem((120, 120), 10, &[(10, 10); 145], &[])));
        // Walls take area.
        let walls = [[0, 0, 100, 10], [0, 10, 10, 90]];
        assert!(!cannot_fit(&problem(
            (100, 100),
            10,
            &[(10, 10); 81],
            &walls
        )));
        assert!(cannot_fit(&problem(
            (100, 100),
            10,
            &[(10, 10); 82],
            &walls
        )));
    }

    #[test]
    fn union_area_counts_overlaps_once() {
        let boxes = [[0, 0, 100, 10], [0, 0, 10, 100], [0, 0, 10, 10]];
        assert_eq!(union_area(&boxes), 1000 + 900);
        assert_eq!(union_area(&[]), 0);
    }

    #[test]
    fn grid_and_size_bounds() {
        // 6×6 blocks in 11×11: area allows 3, only one fits.
        assert!(!cannot_fit(&problem((11, 11), 1, &[(6, 6)], &[])));
        assert!(cannot_fit(&problem((11, 11), 1, &[(6, 6); 2], &[])));
        // 5×5 blocks on grid 10 in 100×100: each owns a 10×10 cell.
        assert!(!cannot_fit(&problem((100, 100), 10, &[(5, 5); 100], &[])));
        assert!(cannot_fit(&problem((100, 100), 10, &[(5, 5); 101], &[])));
        // Off-grid sizes: 15 wide on grid 10 needs two steps; 95 wide fits
        // positions 0..=8, so 5 in a row (0, 2, 4, 6, 8).
        assert!(!cannot_fit(&problem((95, 15), 10, &[(15, 15); 5], &[])));
        assert!(cannot_fit(&problem((95, 15), 10, &[(15, 15); 6], &[])));
    }
}
