//! The problems of the study: the box scene, rule sets drawn from the pool
//! and kept when viable, and per `(series, set, n, k)` the objects of
//! random classes from a stream of their own.

use super::solve::{study_options, StudyEvent};
use super::{Series, StudyConfig, BLOCK, CLASSES, MARGIN, WALL};
use crate::pool::pool_for;
use crate::Solver;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::relations::Kind;
use rccpack::rules::{Formula, Rule, RuleSet, Strength, Target};
use rccpack::scene::{Object, Scene, Space};

/// Interior side of the box for `n` objects: the pilot box (200) or
/// `20·⌈√(2n)⌉ + 40`, whichever is larger (room for twice the objects plus
/// a margin, so the box is never smaller than the pilot's).
pub fn interior_side(n: usize) -> i64 {
    let cells = ((2 * n) as f64).sqrt().ceil() as i64;
    (BLOCK * cells + 40).max(200)
}

/// The box-packing scene with an empty box of interior side `interior`:
/// four fixed walls of class `W`, [`MARGIN`] of free table around them, grid
/// 10. With `interior = 200` this is the thesis's 600×600 scene (south wall
/// at x=190, y=190, 220×10; north at y=400; west at x=190, 10×200; east at
/// x=400).
pub fn box_scene(interior: i64) -> Scene {
    let side = interior + 2 * (WALL + MARGIN);
    let lo = MARGIN; // outer edge of the walls
    let inner = MARGIN + WALL; // first interior coordinate
    let hi = inner + interior; // first coordinate past the interior
    let wall = |id: &str, x, y, w, h| Object::fixed_at(id, "W", x, y, w, h);
    Scene {
        space: Space {
            x: 0,
            y: 0,
            width: side,
            height: side,
        },
        grid: 10,
        objects: vec![
            wall("w_south", lo, lo, interior + 2 * WALL, WALL),
            wall("w_north", lo, hi, interior + 2 * WALL, WALL),
            wall("w_west", lo, inner, WALL, interior),
            wall("w_east", hi, inner, WALL, interior),
        ],
    }
}

/// `scene` plus unplaced 20×20 blocks of the given classes, with ids
/// `r1`, `g1`, `r2`, … (per-class counters).
pub fn with_blocks(mut scene: Scene, classes: &[&str]) -> Scene {
    let mut counters = [0usize; CLASSES.len()];
    for c in classes {
        let ci = CLASSES.iter().position(|x| x == c).unwrap_or(0);
        counters[ci] += 1;
        scene.objects.push(Object {
            id: format!("{}{}", c.to_lowercase(), counters[ci]),
            class: c.to_string(),
            x: None,
            y: None,
            width: BLOCK,
            height: BLOCK,
            fixed: false,
            turnable: false,
            turned: false,
        });
    }
    scene
}

/// One drawn set: per class (in [`CLASSES`] order), the rules in draw order.
#[derive(Debug, Clone)]
pub struct DrawnSet {
    /// 1-based draw number that produced this set.
    pub draw: usize,
    /// `rules[c]`: the rules about `CLASSES[c]`, in draw order.
    pub rules: Vec<Vec<Rule>>,
}

impl DrawnSet {
    /// The first `k` rules of every class, soft with weight 1.
    pub fn first(&self, k: usize) -> RuleSet {
        RuleSet::new(
            self.rules
                .iter()
                .flat_map(|rs| rs.iter().take(k).cloned())
                .map(|r| r.with_strength(Strength::Weight(1.0)))
                .collect(),
        )
    }
}

/// Draw `per_class` distinct rules per class from the pool.
pub fn draw_set(rng: &mut ChaCha8Rng, per_class: usize, draw: usize) -> DrawnSet {
    let rules = CLASSES
        .iter()
        .map(|c| {
            let mut pool = pool_for(c);
            let take = per_class.min(pool.len());
            // Partial Fisher–Yates: the first `take` entries are the draw.
            for i in 0..take {
                let j = rng.random_range(i..pool.len());
                pool.swap(i, j);
            }
            pool.truncate(take);
            pool
        })
        .collect();
    DrawnSet { draw, rules }
}

/// One generated problem.
#[derive(Debug, Clone)]
pub struct Problem {
    /// Pilot grid or scale series.
    pub series: Series,
    /// Index of the viable set.
    pub set: usize,
    /// Objects to place.
    pub n: usize,
    /// Rules per class.
    pub k: usize,
    /// The problem scene (walls fixed, blocks unplaced).
    pub scene: Scene,
    /// The rules (soft, weight 1).
    pub rules: RuleSet,
}

impl Problem {
    /// Classes of the blocks, e.g. `RGB`.
    pub fn classes(&self) -> String {
        self.scene
            .objects
            .iter()
            .filter(|o| !o.fixed)
            .map(|o| o.class.as_str())
            .collect()
    }
}

fn problem_rng(seed: u64, series: Series, set: usize, n: usize, k: usize) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream((series.code() << 48) | ((set as u64) << 32) | ((n as u64) << 16) | k as u64);
    rng
}

/// Build the problems of one series for the given sets, in
/// set-major, then `n`, then `k` order.
pub fn problems(
    cfg: &StudyConfig,
    sets: &[DrawnSet],
    series: Series,
    ns: &[usize],
    ks: &[usize],
) -> Vec<Problem> {
    let mut out = Vec::new();
    for (si, set) in sets.iter().enumerate() {
        for &n in ns {
            let interior = match series {
                Series::Pilot => 200,
                Series::Scale => interior_side(n),
            };
            for &k in ks {
                let mut rng = problem_rng(cfg.seed, series, si, n, k);
                let classes: Vec<&str> = (0..n)
                    .map(|_| CLASSES[rng.random_range(0..CLASSES.len())])
                    .collect();
                out.push(Problem {
                    series,
                    set: si,
                    n,
                    k,
                    scene: with_blocks(box_scene(interior), &classes),
                    rules: set.first(k),
                });
            }
        }
    }
    out
}

/// Whether no layout of two or more objects of the subject class can let
/// every one of them satisfy `f`: `f` is a single `DR_d(A, A)`, `EC_d(A, A)`
/// or `DR_d(A, *)` atom (two objects cannot each lie strictly north of — or
/// touch the north side of — the other). Draws containing such a rule are
/// rejected without a solve; this only saves time, the engine would reject
/// them too.
pub fn unsatisfiable_with_two(f: &Formula) -> bool {
    match f {
        Formula::Atom(a) => match &a.target {
            Target::Any => a.rel.kind == Kind::DR,
            Target::Class(c) => c == &a.subject,
            Target::Landmark(_) => false,
        },
        _ => false,
    }
}

/// Draw rule sets until `cfg.sets` are viable (or `cfg.max_draws` were
/// tried). Returns the sets and the number of draws.
pub fn find_viable_sets(
    engine: Solver<'_>,
    cfg: &StudyConfig,
    progress: &mut dyn FnMut(&StudyEvent),
) -> (Vec<DrawnSet>, usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    let classes: Vec<&str> = CLASSES
        .iter()
        .flat_map(|c| std::iter::repeat_n(*c, cfg.viability_objects_per_class))
        .collect();
    let scene = with_blocks(box_scene(200), &classes);
    let mut sets = Vec::new();
    let mut draws = 0;
    while sets.len() < cfg.sets && draws < cfg.max_draws {
        draws += 1;
        let set = draw_set(&mut rng, cfg.rules_per_class, draws);
        let rules = set.first(cfg.rules_per_class);
        let hopeless = cfg.viability_objects_per_class >= 2
            && rules
                .rules
                .iter()
                .any(|r| unsatisfiable_with_two(&r.formula));
        let viable = !hopeless
            && match (engine.solve)(&scene, &rules, &study_options(cfg)) {
                Ok(r) => r
                    .evaluation
                    .as_ref()
                    .is_some_and(|e| e.hard_ok() && e.score >= 1.0 - 1e-9),
                Err(_) => false,
            };
        if viable {
            sets.push(set);
        }
        progress(&StudyEvent::Drawing {
            draws,
            viable: sets.len(),
            wanted: cfg.sets,
        });
    }
    (sets, draws)
}

/// Every problem of the study for the drawn `sets`: the pilot grid, then
/// the scale series.
pub fn study_problems(cfg: &StudyConfig, sets: &[DrawnSet]) -> Vec<Problem> {
    let mut all = problems(cfg, sets, Series::Pilot, &cfg.ns, &cfg.ks);
    if !cfg.scale_ns.is_empty() {
        all.extend(problems(
            cfg,
            sets,
            Series::Scale,
            &cfg.scale_ns,
            &cfg.scale_ks,
        ));
    }
    all
}
