//! Tiny packing problems that fit only when some blocks turn, found by
//! exhaustive search on the grid (docs/guide.md#objects-that-turn): the
//! `tests/fixtures/turns/packings.json` inputs of `tests/turns.rs` and of
//! `benches/turns.rs`.
//!
//! The search is its own (no solver): a space of `W × H` grid cells
//! (2 to 4 each way) and a multiset of blocks lying wide (`2×1`, `3×1`,
//! `3×2`, plus `1×1` squares), every block fitting the space flat on its
//! own, the blocks' area at least the space's area minus one cell. A
//! cell-by-cell search (the lowest free cell is covered by a block or, while
//! the slack lasts, left empty) decides whether they fit flat and whether
//! they fit with turns; the problems kept fit only with turns.

#![allow(dead_code)]

use rccpack::scene::{Object, Scene, Space};

/// The blocks' shapes in grid cells, wide side first (squares never turn).
const SHAPES: [(u32, u32); 4] = [(1, 1), (2, 1), (3, 1), (3, 2)];

/// Whether `pieces` (counts per [`SHAPES`] entry) fit a `w × h` board,
/// turning the oblong ones when `turns`.
pub fn fits(w: u32, h: u32, pieces: &[u32; 4], turns: bool) -> bool {
    let area: u32 = pieces
        .iter()
        .zip(SHAPES)
        .map(|(&n, (a, b))| n * a * b)
        .sum();
    if area > w * h {
        return false;
    }
    let mut board = vec![false; (w * h) as usize];
    let mut left = *pieces;
    fill(w, h, &mut board, &mut left, w * h - area, turns)
}

fn fill(w: u32, h: u32, board: &mut [bool], left: &mut [u32; 4], slack: u32, turns: bool) -> bool {
    let Some(cell) = board.iter().position(|&c| !c) else {
        return true;
    };
    if left.iter().all(|&n| n == 0) {
        return true;
    }
    let (cx, cy) = (cell as u32 % w, cell as u32 / w);
    for k in 0..SHAPES.len() {
        if left[k] == 0 {
            continue;
        }
        let (a, b) = SHAPES[k];
        let orientations: &[(u32, u32)] = if turns && a != b {
            &[(a, b), (b, a)]
        } else {
            &[(a, b)]
        };
        for &(pw, ph) in orientations {
            if cx + pw > w || cy + ph > h {
                continue;
            }
            let cells: Vec<usize> = (cy..cy + ph)
                .flat_map(|y| (cx..cx + pw).map(move |x| (y * w + x) as usize))
                .collect();
            if cells.iter().any(|&c| board[c]) {
                continue;
            }
            for &c in &cells {
                board[c] = true;
            }
            left[k] -= 1;
            let ok = fill(w, h, board, left, slack, turns);
            left[k] += 1;
            for &c in &cells {
                board[c] = false;
            }
            if ok {
                return true;
            }
        }
    }
    if slack > 0 {
        board[cell] = true;
        let ok = fill(w, h, board, left, slack - 1, turns);
        board[cell] = false;
        return ok;
    }
    false
}

/// The first `n` problems (in the search's order: spaces by area, then
/// by width; block multisets by count) whose blocks fit only with turns,
/// as problem scenes (grid 10, cells of 10 units; oblong blocks
/// `turnable`, ids `b0`, `b1`, … in shape order).
pub fn packings(n: usize) -> Vec<Scene> {
    let mut spaces: Vec<(u32, u32)> = (2..=4).flat_map(|w| (2..=4).map(move |h| (w, h))).collect();
    spaces.sort_by_key(|&(w, h)| (w * h, w));
    let mut out = Vec::new();
    for (w, h) in spaces {
        let mut multisets: Vec<[u32; 4]> = Vec::new();
        for s in 0..=2u32 {
            for d in 0..=6u32 {
                for t in 0..=4u32 {
                    for r in 0..=2u32 {
                        multisets.push([s, d, t, r]);
                    }
                }
            }
        }
        multisets.sort_by_key(|p| (p.iter().sum::<u32>(), std::cmp::Reverse(*p)));
        for p in multisets {
            let count: u32 = p.iter().sum();
            let area: u32 = p.iter().zip(SHAPES).map(|(&n, (a, b))| n * a * b).sum();
            let each_fits_flat = SHAPES
                .iter()
                .zip(&p)
                .all(|(&(a, b), &n)| n == 0 || (a <= w && b <= h));
            if !(2..=6).contains(&count)
                || area + 1 < w * h
                || area > w * h
                || !each_fits_flat
                || p[1] + p[2] + p[3] == 0
            {
                continue;
            }
            if !fits(w, h, &p, false) && fits(w, h, &p, true) {
                out.push(scene(w, h, &p));
                if out.len() == n {
                    return out;
                }
            }
        }
    }
    out
}

fn scene(w: u32, h: u32, pieces: &[u32; 4]) -> Scene {
    let mut objects = Vec::new();
    for (k, &n) in pieces.iter().enumerate() {
        let (a, b) = SHAPES[k];
        for _ in 0..n {
            let mut o = Object::movable(
                &format!("b{}", objects.len()),
                ["S", "D", "T", "R"][k],
                i64::from(a) * 10,
                i64::from(b) * 10,
            );
            o.turnable = a != b;
            objects.push(o);
        }
    }
    Scene::new(
        Space {
            x: 0,
            y: 0,
            width: i64::from(w) * 10,
            height: i64::from(h) * 10,
        },
        10,
        objects,
    )
    .expect("a valid problem")
}

/// The problem with no block allowed to turn.
pub fn flat(problem: &Scene) -> Scene {
    let mut p = problem.clone();
    for o in &mut p.objects {
        o.turnable = false;
    }
    p
}
