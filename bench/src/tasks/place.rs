//! The box of a task and the procedural placement of its demonstrations:
//! every class placed by its habit with random offsets, on the grid, inside
//! the box and overlap-free.

use super::style::{ClassSpec, Corner, Habit, WallSide};
use super::{groups, scaled, GRID, WALL};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use rccpack::scene::{Object, Rect, Scene, Space};

/// The box of a task: interior `width × height`, `margin` of free table
/// around the walls, grid 10.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BoxGeom {
    /// Interior width.
    pub width: i64,
    /// Interior height.
    pub height: i64,
    /// Free table between the walls and the edge of the space.
    pub margin: i64,
}

impl BoxGeom {
    /// The interior as a rectangle.
    pub fn interior(&self) -> Rect {
        let lo = self.margin + WALL;
        Rect::new(lo, lo, self.width, self.height)
    }

    /// The empty box: four fixed walls `w_south`, `w_north`, `w_west`,
    /// `w_east` of class `W`.
    pub fn scene(&self) -> Scene {
        let lo = self.margin;
        let inner = self.margin + WALL;
        let wall = |id: &str, x, y, w, h| Object::fixed_at(id, "W", x, y, w, h);
        Scene {
            space: Space {
                x: 0,
                y: 0,
                width: self.width + 2 * (WALL + self.margin),
                height: self.height + 2 * (WALL + self.margin),
            },
            grid: GRID,
            objects: vec![
                wall("w_south", lo, lo, self.width + 2 * WALL, WALL),
                wall(
                    "w_north",
                    lo,
                    inner + self.height,
                    self.width + 2 * WALL,
                    WALL,
                ),
                wall("w_west", lo, inner, WALL, self.height),
                wall("w_east", inner + self.width, inner, WALL, self.height),
            ],
        }
    }
}

fn round_up(v: f64) -> i64 {
    ((v / GRID as f64).ceil() as i64) * GRID
}

/// The box for `classes` (see the module doc, step 3).
pub(crate) fn box_for(classes: &[ClassSpec], largest: f64, rng: &mut ChaCha8Rng) -> BoxGeom {
    let area: i64 = classes
        .iter()
        .map(|c| scaled(c.max_count, largest) as i64 * c.width * c.height)
        .sum();
    let target = 2.25 * area as f64;
    let aspect = [1.0, 1.25, 1.5][rng.random_range(0..3usize)];
    let wide = rng.random_bool(0.5);
    let long = round_up((target * aspect).sqrt());
    let short = round_up(target / long as f64);
    let (mut w, mut h) = if wide { (long, short) } else { (short, long) };
    // Room for the longest band or stack of a demonstration, and more.
    let need = classes
        .iter()
        .map(|c| c.max_count as i64 * c.width.max(c.height) + 2 * GRID)
        .max()
        .unwrap_or(0)
        .max(100);
    w = w.max(need);
    h = h.max(need);
    BoxGeom {
        width: w,
        height: h,
        margin: w.max(h) - GRID,
    }
}

/// A demonstration being built: the occupied rectangles and the interior.
pub(super) struct Placer {
    /// The box's interior.
    pub(super) interior: Rect,
    /// The blocks placed so far.
    pub(super) taken: Vec<Rect>,
}

impl Placer {
    /// `r` inside the interior and clear of every block placed.
    pub(super) fn free(&self, r: Rect) -> bool {
        let i = self.interior;
        r.x >= i.x
            && r.y >= i.y
            && r.x + r.w <= i.x + i.w
            && r.y + r.h <= i.y + i.h
            && self.taken.iter().all(|t| !overlaps(*t, r))
    }

    /// All of `rs` free and pairwise apart.
    pub(super) fn all_free(&self, rs: &[Rect]) -> bool {
        rs.iter()
            .enumerate()
            .all(|(k, r)| self.free(*r) && rs[..k].iter().all(|q| !overlaps(*q, *r)))
    }
}

fn overlaps(a: Rect, b: Rect) -> bool {
    a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h
}

/// Grid positions `lo, lo+10, …, ≤ hi`, rotated to start at a random one.
pub(super) fn rotated(lo: i64, hi: i64, rng: &mut ChaCha8Rng) -> Vec<i64> {
    if hi < lo {
        return Vec::new();
    }
    let n = ((hi - lo) / GRID + 1) as usize;
    let start = rng.random_range(0..n);
    (0..n)
        .map(|k| lo + ((start + k) % n) as i64 * GRID)
        .collect()
}

/// Place `n` blocks of `spec` by its habit; `placed` holds the blocks of
/// the earlier classes (for `NorthOf`). `None` when no room was found.
fn place_class(
    p: &Placer,
    spec: &ClassSpec,
    n: usize,
    placed: &[Vec<Rect>],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Rect>> {
    let size = (spec.width, spec.height);
    match spec.habit {
        Habit::Band { wall } => place_band(p, size, n, wall, rng),
        Habit::Corner { corner } => place_corner(p, size, n, corner, rng),
        Habit::Stack => place_stack(p, size, n, rng),
        Habit::Cluster => place_cluster(p, size, n, rng),
        Habit::Row | Habit::Column { .. } | Habit::Block => groups::place_group(p, spec, n, rng),
        Habit::NorthOf { class } => place_north_of(p, size, n, placed.get(class)?, rng),
    }
}

/// The interior's edges `(x0, y0, x1, y1)`.
fn edges(p: &Placer) -> (i64, i64, i64, i64) {
    let i = p.interior;
    (i.x, i.y, i.x + i.w, i.y + i.h)
}

/// A band: one contiguous row (or column) of `n` blocks against `wall`, at
/// the first free offset from a random start.
fn place_band(
    p: &Placer,
    (w, h): (i64, i64),
    n: usize,
    wall: WallSide,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Rect>> {
    let (x0, y0, x1, y1) = edges(p);
    let horizontal = matches!(wall, WallSide::N | WallSide::S);
    let (lo, hi) = if horizontal {
        (x0, x1 - n as i64 * w)
    } else {
        (y0, y1 - n as i64 * h)
    };
    for off in rotated(lo, hi, rng) {
        let rs: Vec<Rect> = (0..n as i64)
            .map(|k| match wall {
                WallSide::S => Rect::new(off + k * w, y0, w, h),
                WallSide::N => Rect::new(off + k * w, y1 - h, w, h),
                WallSide::W => Rect::new(x0, off + k * h, w, h),
                WallSide::E => Rect::new(x1 - w, off + k * h, w, h),
            })
            .collect();
        if p.all_free(&rs) {
            return Some(rs);
        }
    }
    None
}

/// A corner cluster: `n` blocks filling `corner` row by row (or column by
/// column), the most compact shapes first.
fn place_corner(
    p: &Placer,
    (w, h): (i64, i64),
    n: usize,
    corner: Corner,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Rect>> {
    let (x0, y0, x1, y1) = edges(p);
    let lo_cols = (n as f64).sqrt().ceil() as usize;
    let mut options: Vec<usize> = (lo_cols.max(1)..=n).collect();
    // Prefer compact shapes; shuffle within the first few.
    let keep = options.len().min(3);
    options.truncate(keep);
    let first = rng.random_range(0..options.len());
    options.rotate_left(first);
    let column_major = rng.random_bool(0.5);
    for cols in options {
        let rs: Vec<Rect> = (0..n)
            .map(|k| {
                let (a, b) = ((k % cols) as i64, (k / cols) as i64);
                let (cx, cy) = if column_major { (b, a) } else { (a, b) };
                let x = if corner.east() {
                    x1 - (cx + 1) * w
                } else {
                    x0 + cx * w
                };
                let y = if corner.north() {
                    y1 - (cy + 1) * h
                } else {
                    y0 + cy * h
                };
                Rect::new(x, y, w, h)
            })
            .collect();
        if p.all_free(&rs) {
            return Some(rs);
        }
    }
    None
}

/// A stack: columns of `n` blocks standing on the floor, spilling into a
/// neighbouring column when the box is not high enough.
fn place_stack(
    p: &Placer,
    (w, h): (i64, i64),
    n: usize,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Rect>> {
    let (x0, y0, x1, y1) = edges(p);
    let per_col = (((y1 - y0) / h) as usize).clamp(1, n);
    let cols = n.div_ceil(per_col) as i64;
    for off in rotated(x0, x1 - cols * w, rng) {
        let rs: Vec<Rect> = (0..n)
            .map(|k| {
                let (c, r) = ((k / per_col) as i64, (k % per_col) as i64);
                Rect::new(off + c * w, y0 + r * h, w, h)
            })
            .collect();
        if p.all_free(&rs) {
            return Some(rs);
        }
    }
    None
}

/// A connected cluster of `n` blocks grown from a random start (50 starts).
fn place_cluster(
    p: &Placer,
    (w, h): (i64, i64),
    n: usize,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Rect>> {
    let (x0, y0, x1, y1) = edges(p);
    for _ in 0..50 {
        let x = *rotated(x0, x1 - w, rng).first()?;
        let y = *rotated(y0, y1 - h, rng).first()?;
        if let Some(rs) = grow(p, Rect::new(x, y, w, h), n, y0, rng) {
            return Some(rs);
        }
    }
    None
}

/// A connected cluster of `n` blocks north of every block of `other`,
/// resting on one of its topmost blocks if it can.
fn place_north_of(
    p: &Placer,
    (w, h): (i64, i64),
    n: usize,
    other: &[Rect],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Rect>> {
    let (x0, _, x1, _) = edges(p);
    let top = other.iter().map(|r| r.y + r.h).max()?;
    // Rest on a topmost block of the other class, else anywhere
    // along that height.
    let mut starts: Vec<Rect> = other
        .iter()
        .filter(|r| r.y + r.h == top)
        .map(|r| Rect::new(r.x, top, w, h))
        .collect();
    let k = starts.len();
    if k > 0 {
        let first = rng.random_range(0..k);
        starts.rotate_left(first);
    }
    starts.extend(
        rotated(x0, x1 - w, rng)
            .into_iter()
            .map(|x| Rect::new(x, top, w, h)),
    );
    for s in starts.into_iter().take(60) {
        if let Some(rs) = grow(p, s, n, top, rng) {
            return Some(rs);
        }
    }
    None
}

/// A connected cluster of `n` blocks (each flush against an earlier one)
/// from `start`, every block at `y ≥ floor`.
fn grow(p: &Placer, start: Rect, n: usize, floor: i64, rng: &mut ChaCha8Rng) -> Option<Vec<Rect>> {
    let ok =
        |rs: &[Rect], r: Rect| r.y >= floor && p.free(r) && rs.iter().all(|q| !overlaps(*q, r));
    if !ok(&[], start) {
        return None;
    }
    let mut rs = vec![start];
    while rs.len() < n {
        let mut cands = Vec::new();
        for q in &rs {
            for (dx, dy) in [(q.w, 0), (-q.w, 0), (0, q.h), (0, -q.h)] {
                let c = Rect::new(q.x + dx, q.y + dy, q.w, q.h);
                if ok(&rs, c) && !cands.contains(&c) {
                    cands.push(c);
                }
            }
        }
        if cands.is_empty() {
            return None;
        }
        // Favour compact growth a little: pick among the candidates
        // touching the most blocks, half of the time.
        let pick = if rng.random_bool(0.5) {
            let touching = |c: &Rect| {
                rs.iter()
                    .filter(|q| {
                        (q.x == c.x && (q.y + q.h == c.y || c.y + c.h == q.y))
                            || (q.y == c.y && (q.x + q.w == c.x || c.x + c.w == q.x))
                    })
                    .count()
            };
            let best = cands.iter().map(touching).max().unwrap_or(0);
            let top: Vec<Rect> = cands
                .iter()
                .copied()
                .filter(|c| touching(c) == best)
                .collect();
            top[rng.random_range(0..top.len())]
        } else {
            cands[rng.random_range(0..cands.len())]
        };
        rs.push(pick);
    }
    Some(rs)
}

pub(crate) fn block(class: &str, k: usize, w: i64, h: i64, at: Option<Rect>) -> Object {
    Object {
        id: format!("{}{}", class.to_ascii_lowercase(), k + 1),
        class: class.to_string(),
        x: at.map(|r| r.x),
        y: at.map(|r| r.y),
        width: w,
        height: h,
        fixed: false,
        turnable: false,
        turned: false,
    }
}

/// The demonstrations of a task, or `None` when a placement failed.
pub(super) fn make_demos(
    geom: &BoxGeom,
    classes: &[ClassSpec],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Scene>> {
    let d = rng.random_range(3..=5usize);
    make_demos_n(geom, classes, d, rng)
}

/// `d` demonstrations of `classes` in `geom`'s box, each class placed by
/// its habit (one demonstration per class shows its largest count), or
/// `None` when a placement failed.
pub(crate) fn make_demos_n(
    geom: &BoxGeom,
    classes: &[ClassSpec],
    d: usize,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Scene>> {
    if d == 0 {
        return None;
    }
    // Per demonstration and class, the count; one demonstration per class
    // shows the largest.
    let mut counts: Vec<Vec<usize>> = (0..d)
        .map(|_| {
            classes
                .iter()
                .map(|c| rng.random_range(2..=c.max_count))
                .collect()
        })
        .collect();
    for (ci, c) in classes.iter().enumerate() {
        let at = rng.random_range(0..d);
        counts[at][ci] = c.max_count;
    }
    let mut demos = Vec::with_capacity(d);
    for row in &counts {
        let mut done = None;
        for _attempt in 0..20 {
            let mut p = Placer {
                interior: geom.interior(),
                taken: Vec::new(),
            };
            let mut placed: Vec<Vec<Rect>> = Vec::new();
            let mut ok = true;
            for (ci, c) in classes.iter().enumerate() {
                match place_class(&p, c, row[ci], &placed, rng) {
                    Some(rs) => {
                        p.taken.extend(rs.iter().copied());
                        placed.push(rs);
                    }
                    None => {
                        ok = false;
                        break;
                    }
                }
            }
            if ok {
                done = Some(placed);
                break;
            }
        }
        let placed = done?;
        demos.push(demo_scene(geom, classes, &placed));
    }
    Some(demos)
}

/// A demonstration: the box with the blocks of every class at `placed`
/// (per class, in class order).
pub(super) fn demo_scene(geom: &BoxGeom, classes: &[ClassSpec], placed: &[Vec<Rect>]) -> Scene {
    let mut scene = geom.scene();
    for (c, rs) in classes.iter().zip(placed) {
        scene.objects.extend(
            rs.iter()
                .enumerate()
                .map(|(k, r)| block(&c.class, k, c.width, c.height, Some(*r))),
        );
    }
    scene
}
