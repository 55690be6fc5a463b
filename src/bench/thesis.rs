//! The thesis runtime study (§4.1, Figure 4-1), reproduced with a seeded
//! generator.
//!
//! 1. **Viable sets.** Draw 5 rules per class (R, G, B) at random from
//!    [`pool_for`]; keep the draw when 2 objects per class can reach score 1
//!    in the box (solved by the engine within the time limit). Repeat until
//!    `sets` viable sets are found (or `max_draws` draws were tried).
//! 2. **Pilot grid.** For every set, every `n` in `ns` (objects) and every `k`
//!    in `ks` (rules per class): the first `k` rules per class of the set, and
//!    `n` objects of uniformly random classes, in the 600×600 box scene.
//! 3. **Scale series.** The same with `n` in `scale_ns` and `k` in
//!    `scale_ks`, in a box enlarged to hold the objects ([`interior_side`]).
//!
//! Every rule is soft with weight 1. Each problem is solved once; the row
//! records status, wall time and search nodes, and the solution is checked
//! by the engine's solution checker.
//!
//! Determinism: the draws use `ChaCha8Rng::seed_from_u64(seed)` on stream 0;
//! the classes of problem `(series, set, n, k)` come from their own stream,
//! so a quick run's problems are the first problems of a full run with the
//! same seed (as long as the engine decides viability the same way).

use super::peers::{self, Peer, PeerStatus};
use super::pool::{formula_text, pool_for};
use crate::relations::Contact;
use crate::relations::Kind;
use crate::rules::{Formula, Rule, RuleSet, Strength, Target};
use crate::scene::{Object, Scene, Space};
use crate::synth::{Status, SynthOptions};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use std::time::{Duration, Instant};

/// The movable classes of the box-packing task.
pub const CLASSES: [&str; 3] = ["R", "G", "B"];
/// Side of every movable block.
pub const BLOCK: i64 = 20;
/// Thickness of the walls.
pub const WALL: i64 = 10;
/// Free table between the walls and the edge of the space.
pub const MARGIN: i64 = 190;

pub use super::{SolveFn, Solver, VerifyFn};

/// Which part of the study a problem belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, PartialOrd, Ord, Hash)]
#[serde(rename_all = "lowercase")]
pub enum Series {
    /// n = 2..6, k = 1..5 in the 600×600 box (the thesis grid).
    Pilot,
    /// Larger n in an enlarged box.
    Scale,
}

impl Series {
    fn code(self) -> u64 {
        match self {
            Series::Pilot => 1,
            Series::Scale => 2,
        }
    }
}

/// Study parameters.
#[derive(Debug, Clone, Serialize)]
pub struct StudyConfig {
    /// Seed of every random choice.
    pub seed: u64,
    /// Per-problem time limit (also for the viability solves).
    #[serde(serialize_with = "ser_secs")]
    pub time_limit: Duration,
    /// Viable rule sets to collect.
    pub sets: usize,
    /// Rules drawn per class.
    pub rules_per_class: usize,
    /// Objects per class in the viability check.
    pub viability_objects_per_class: usize,
    /// Give up drawing after this many draws.
    pub max_draws: usize,
    /// Object counts of the pilot grid.
    pub ns: Vec<usize>,
    /// Rules per class of the pilot grid.
    pub ks: Vec<usize>,
    /// Object counts of the scale series (empty: no scale series).
    pub scale_ns: Vec<usize>,
    /// Rules per class of the scale series.
    pub scale_ks: Vec<usize>,
    /// Contact mode.
    #[serde(serialize_with = "ser_display")]
    pub contact: Contact,
    /// Large-neighbourhood search on large problems (`SynthOptions::lns`).
    pub lns: bool,
    /// Peer solvers run beside rccpack on every problem (same model, same
    /// time limit).
    #[serde(serialize_with = "ser_peers")]
    pub peers: Vec<Peer>,
}

pub(crate) fn ser_peers<S: serde::Serializer>(p: &[Peer], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(p.iter().map(|p| p.name()))
}

pub(crate) fn ser_secs<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(d.as_secs_f64())
}

fn ser_display<S: serde::Serializer>(c: &Contact, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&c.to_string())
}

impl StudyConfig {
    /// The full study: 10 sets, n = 2..6 × k = 1..5, and the scale series
    /// n ∈ {8, 12, 16, 24, 32, 48, 64, 96} × k ∈ {3, 5}.
    pub fn full(seed: u64, time_limit: Duration) -> Self {
        StudyConfig {
            seed,
            time_limit,
            sets: 10,
            rules_per_class: 5,
            viability_objects_per_class: 2,
            max_draws: 50_000,
            ns: (2..=6).collect(),
            ks: (1..=5).collect(),
            scale_ns: vec![8, 12, 16, 24, 32, 48, 64, 96],
            scale_ks: vec![3, 5],
            contact: Contact::Point,
            lns: true,
            peers: Vec::new(),
        }
    }

    /// A smoke run: 3 sets, the pilot grid only.
    pub fn quick(seed: u64, time_limit: Duration) -> Self {
        StudyConfig {
            sets: 3,
            scale_ns: Vec::new(),
            ..Self::full(seed, time_limit)
        }
    }
}

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

/// One solved problem.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// Pilot grid or scale series.
    pub series: Series,
    /// Index of the viable set.
    pub set: usize,
    /// Objects.
    pub n: usize,
    /// Rules per class.
    pub k: usize,
    /// Classes of the blocks, e.g. `RGB`.
    pub classes: String,
    /// How the solve ended (`None` when the engine returned an error).
    pub status: Option<Status>,
    /// Wall time around the solver call, milliseconds.
    pub time_ms: f64,
    /// Search nodes reported by the engine.
    pub nodes: u64,
    /// Conflicts reported by the engine.
    pub conflicts: u64,
    /// Evaluator score of the solution.
    pub score: Option<f64>,
    /// §6 numerator of the solution.
    pub satisfied_weight: Option<f64>,
    /// §6 denominator of the solution.
    pub total_weight: Option<f64>,
    /// Whether the solution passed the checker (`None`: no solution).
    pub verified: Option<bool>,
    /// The checker's complaint, or the engine's error.
    pub error: Option<String>,
    /// The peers' answers on the same problem.
    pub peers: Vec<PeerRow>,
}

/// One peer's answer on one problem, scored by rccpack's evaluator.
#[derive(Debug, Clone, Serialize)]
pub struct PeerRow {
    /// `cp-sat` or `gecode`.
    pub peer: String,
    /// How its solve ended (`None`: it failed to run; see `error`).
    pub status: Option<PeerStatus>,
    /// Its solve time as it reports it, ms.
    pub time_ms: f64,
    /// Wall time around its process, ms.
    pub process_ms: f64,
    /// rccpack's evaluator score of its layout.
    pub score: Option<f64>,
    /// Whether its layout passed the checker.
    pub verified: Option<bool>,
    /// What went wrong.
    pub error: Option<String>,
}

/// Run `peer` on problem `p` (the model rccpack solves, emitted) and score
/// its layout with the evaluator and the checker.
pub fn solve_peer(engine: Solver<'_>, cfg: &StudyConfig, p: &Problem, peer: Peer) -> PeerRow {
    let mut row = PeerRow {
        peer: peer.name().into(),
        status: None,
        time_ms: 0.0,
        process_ms: 0.0,
        score: None,
        verified: None,
        error: None,
    };
    let e = match crate::synth::emit::emitted(&p.scene, &p.rules, &study_options(cfg)) {
        Ok(e) => e,
        Err(e) => {
            row.error = Some(e.to_string());
            return row;
        }
    };
    match peers::solve(peer, &e, cfg.time_limit) {
        Err(e) => row.error = Some(e.to_string()),
        Ok(r) => {
            row.status = Some(r.status);
            row.time_ms = r.time_ms;
            row.process_ms = r.process_ms;
            if let Some(v) = &r.values {
                if v.len() == e.model.vars.len() {
                    let sol = e.model.scene(&p.scene, v);
                    let ev = crate::eval::evaluate(&sol, &p.rules, cfg.contact);
                    row.score = Some(ev.score);
                    match (engine.verify)(&p.scene, &sol, &p.rules, cfg.contact) {
                        Ok(()) => row.verified = Some(true),
                        Err(msg) => {
                            row.verified = Some(false);
                            row.error = Some(msg);
                        }
                    }
                } else {
                    row.error = Some(format!(
                        "{} values for {} variables",
                        v.len(),
                        e.model.vars.len()
                    ));
                }
            }
        }
    }
    row
}

/// The synthesis options of every solve of the study.
pub fn study_options(cfg: &StudyConfig) -> SynthOptions {
    let mut opts = SynthOptions {
        contact: cfg.contact,
        time_limit: Some(cfg.time_limit),
        seed: cfg.seed,
        ..SynthOptions::default()
    };
    if !cfg.lns {
        opts.lns = None;
    }
    opts
}

/// Solve one problem and check its solution.
pub fn solve_problem(engine: Solver<'_>, cfg: &StudyConfig, p: &Problem) -> Row {
    let opts = study_options(cfg);
    let t0 = Instant::now();
    let res = (engine.solve)(&p.scene, &p.rules, &opts);
    let time_ms = t0.elapsed().as_secs_f64() * 1e3;
    let mut row = Row {
        series: p.series,
        set: p.set,
        n: p.n,
        k: p.k,
        classes: p.classes(),
        status: None,
        time_ms,
        nodes: 0,
        conflicts: 0,
        score: None,
        satisfied_weight: None,
        total_weight: None,
        verified: None,
        error: None,
        peers: Vec::new(),
    };
    match res {
        Err(e) => row.error = Some(e.to_string()),
        Ok(r) => {
            row.status = Some(r.status);
            row.nodes = r.stats.nodes;
            row.conflicts = r.stats.conflicts;
            if let Some(ev) = &r.evaluation {
                row.score = Some(ev.score);
                row.satisfied_weight = Some(ev.satisfied_weight);
                row.total_weight = Some(ev.total_weight);
            }
            if let Some(sol) = &r.scene {
                match (engine.verify)(&p.scene, sol, &p.rules, cfg.contact) {
                    Ok(()) => row.verified = Some(true),
                    Err(e) => {
                        row.verified = Some(false);
                        row.error = Some(e);
                    }
                }
            }
        }
    }
    row
}

/// What the study is doing, for a progress bar.
#[derive(Debug, Clone)]
pub enum StudyEvent {
    /// Drawing rule sets: draws tried so far, viable sets found, wanted.
    Drawing {
        /// Draws tried.
        draws: usize,
        /// Viable sets found.
        viable: usize,
        /// Viable sets wanted.
        wanted: usize,
    },
    /// Solving: problems done of total; the last one's label.
    Solving {
        /// Problems done.
        done: usize,
        /// Problems in all.
        total: usize,
        /// e.g. `pilot set 3 n=4 k=2`.
        label: String,
    },
}

/// A viable set as written to `thesis.json`.
#[derive(Debug, Clone, Serialize)]
pub struct SetReport {
    /// Index of the set.
    pub index: usize,
    /// Draw number that produced it.
    pub draw: usize,
    /// Per class, `name: formula` in draw order.
    pub rules: std::collections::BTreeMap<String, Vec<String>>,
}

/// Everything the study measured.
#[derive(Debug, Clone, Serialize)]
pub struct StudyReport {
    /// The configuration.
    pub config: StudyConfig,
    /// Draws tried to collect the sets.
    pub draws: usize,
    /// The viable sets.
    pub sets: Vec<SetReport>,
    /// One row per problem.
    pub rows: Vec<Row>,
    /// One line per (series, n, k).
    pub summary: Vec<Summary>,
    /// One line per (series, n, k, peer), when peers ran.
    pub peer_summary: Vec<PeerSummary>,
    /// The drawn sets themselves (to rebuild the problems).
    #[serde(skip)]
    pub drawn: Vec<DrawnSet>,
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
    let opts = study_options(cfg);
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
            && match (engine.solve)(&scene, &rules, &opts) {
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

/// Run the whole study.
pub fn run_study(
    engine: Solver<'_>,
    cfg: &StudyConfig,
    progress: &mut dyn FnMut(&StudyEvent),
) -> StudyReport {
    let (sets, draws) = find_viable_sets(engine, cfg, progress);
    let all = study_problems(cfg, &sets);
    let total = all.len();
    let mut rows = Vec::with_capacity(total);
    for (i, p) in all.iter().enumerate() {
        let mut row = solve_problem(engine, cfg, p);
        for &peer in &cfg.peers {
            row.peers.push(solve_peer(engine, cfg, p, peer));
        }
        rows.push(row);
        progress(&StudyEvent::Solving {
            done: i + 1,
            total,
            label: format!("{:?} set {} n={} k={}", p.series, p.set, p.n, p.k).to_lowercase(),
        });
    }
    let summary = summarize(&rows);
    let sets_drawn = sets.clone();
    let reports = sets
        .iter()
        .enumerate()
        .map(|(index, s)| SetReport {
            index,
            draw: s.draw,
            rules: CLASSES
                .iter()
                .zip(&s.rules)
                .map(|(c, rs)| {
                    (
                        c.to_string(),
                        rs.iter()
                            .map(|r| format!("{}: {}", r.name, formula_text(&r.formula)))
                            .collect(),
                    )
                })
                .collect(),
        })
        .collect();
    StudyReport {
        config: cfg.clone(),
        draws,
        sets: reports,
        peer_summary: summarize_peers(&rows),
        rows,
        summary,
        drawn: sets_drawn,
    }
}

/// Aggregates of one (series, n, k) cell.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Summary {
    /// Series.
    pub series: Series,
    /// Objects.
    pub n: usize,
    /// Rules per class.
    pub k: usize,
    /// Problems in the cell.
    pub total: usize,
    /// Proved optimal.
    pub optimal: usize,
    /// Stopped by the limit with a solution.
    pub feasible: usize,
    /// Proved infeasible.
    pub infeasible: usize,
    /// Stopped by the limit without a solution.
    pub unknown: usize,
    /// Solver errors.
    pub errors: usize,
    /// Solutions that failed the checker.
    pub check_failures: usize,
    /// Median wall time, ms (every problem, time-outs included).
    pub median_ms: f64,
    /// Largest wall time, ms.
    pub max_ms: f64,
    /// Median search nodes.
    pub median_nodes: f64,
    /// Median score of the solutions found.
    pub median_score: Option<f64>,
}

/// The median of `v` (mean of the middle two for an even count); NaN when
/// empty.
pub fn median(v: &[f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let m = s.len() / 2;
    if s.len() % 2 == 1 {
        s[m]
    } else {
        (s[m - 1] + s[m]) / 2.0
    }
}

/// One [`Summary`] per (series, n, k), sorted.
pub fn summarize(rows: &[Row]) -> Vec<Summary> {
    let mut keys: Vec<(Series, usize, usize)> = rows.iter().map(|r| (r.series, r.n, r.k)).collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .map(|(series, n, k)| {
            let cell: Vec<&Row> = rows
                .iter()
                .filter(|r| r.series == series && r.n == n && r.k == k)
                .collect();
            let count = |s: Status| cell.iter().filter(|r| r.status == Some(s)).count();
            let times: Vec<f64> = cell.iter().map(|r| r.time_ms).collect();
            let nodes: Vec<f64> = cell.iter().map(|r| r.nodes as f64).collect();
            let scores: Vec<f64> = cell.iter().filter_map(|r| r.score).collect();
            Summary {
                series,
                n,
                k,
                total: cell.len(),
                optimal: count(Status::Optimal),
                feasible: count(Status::Feasible),
                infeasible: count(Status::Infeasible),
                unknown: count(Status::Unknown),
                errors: cell.iter().filter(|r| r.status.is_none()).count(),
                check_failures: cell.iter().filter(|r| r.verified == Some(false)).count(),
                median_ms: median(&times),
                max_ms: times.iter().copied().fold(0.0, f64::max),
                median_nodes: median(&nodes),
                median_score: (!scores.is_empty()).then(|| median(&scores)),
            }
        })
        .collect()
}

/// One peer's aggregates in one (series, n, k) cell, beside rccpack's.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PeerSummary {
    /// Series.
    pub series: Series,
    /// Objects.
    pub n: usize,
    /// Rules per class.
    pub k: usize,
    /// The peer.
    pub peer: String,
    /// Problems in the cell.
    pub total: usize,
    /// Proved optimal by the peer.
    pub optimal: usize,
    /// Proved optimal by rccpack.
    pub rccpack_optimal: usize,
    /// Median peer solve time, ms (time-outs at the limit).
    pub median_ms: f64,
    /// Largest peer solve time, ms.
    pub max_ms: f64,
    /// Median rccpack time, ms.
    pub rccpack_median_ms: f64,
    /// Peer median over rccpack median (above 1: rccpack is faster).
    pub ratio: f64,
    /// Problems where rccpack's score is below the peer's.
    pub rccpack_worse: usize,
    /// Problems where the peer's score is below rccpack's.
    pub peer_worse: usize,
    /// Peer layouts the checker rejected, or peer failures.
    pub failures: usize,
}

/// One [`PeerSummary`] per (series, n, k, peer), sorted.
pub fn summarize_peers(rows: &[Row]) -> Vec<PeerSummary> {
    let mut keys: Vec<(Series, usize, usize, String)> = rows
        .iter()
        .flat_map(|r| r.peers.iter().map(|p| (r.series, r.n, r.k, p.peer.clone())))
        .collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .map(|(series, n, k, peer)| {
            let cell: Vec<(&Row, &PeerRow)> = rows
                .iter()
                .filter(|r| r.series == series && r.n == n && r.k == k)
                .filter_map(|r| r.peers.iter().find(|p| p.peer == peer).map(|p| (r, p)))
                .collect();
            let ptimes: Vec<f64> = cell.iter().map(|(_, p)| p.time_ms).collect();
            let rtimes: Vec<f64> = cell.iter().map(|(r, _)| r.time_ms).collect();
            let (pm, rm) = (median(&ptimes), median(&rtimes));
            let score = |s: Option<f64>| s.unwrap_or(f64::NEG_INFINITY);
            PeerSummary {
                series,
                n,
                k,
                peer,
                total: cell.len(),
                optimal: cell
                    .iter()
                    .filter(|(_, p)| p.status == Some(PeerStatus::Optimal))
                    .count(),
                rccpack_optimal: cell
                    .iter()
                    .filter(|(r, _)| r.status == Some(Status::Optimal))
                    .count(),
                median_ms: pm,
                max_ms: ptimes.iter().copied().fold(0.0, f64::max),
                rccpack_median_ms: rm,
                ratio: pm / rm,
                rccpack_worse: cell
                    .iter()
                    .filter(|(r, p)| score(r.score) < score(p.score) - 1e-9)
                    .count(),
                peer_worse: cell
                    .iter()
                    .filter(|(r, p)| score(p.score) < score(r.score) - 1e-9)
                    .count(),
                failures: cell
                    .iter()
                    .filter(|(_, p)| p.status.is_none() || p.verified == Some(false))
                    .count(),
            }
        })
        .collect()
}

/// The peer summary as a fixed-width text table.
pub fn peer_table_text(summary: &[PeerSummary]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<6} {:>3} {:>2} {:<7} {:>8} {:>8} {:>10} {:>10} {:>10} {:>7} {:>8} {:>8}",
        "series",
        "n",
        "k",
        "peer",
        "optimal",
        "rcc_opt",
        "median_ms",
        "max_ms",
        "rcc_med",
        "ratio",
        "rcc_wrs",
        "peer_wrs"
    );
    for r in summary {
        let series = match r.series {
            Series::Pilot => "pilot",
            Series::Scale => "scale",
        };
        let _ = writeln!(
            s,
            "{:<6} {:>3} {:>2} {:<7} {:>8} {:>8} {:>10.1} {:>10.1} {:>10.1} {:>7.2} {:>8} {:>8}{}",
            series,
            r.n,
            r.k,
            r.peer,
            format!("{}/{}", r.optimal, r.total),
            format!("{}/{}", r.rccpack_optimal, r.total),
            r.median_ms,
            r.max_ms,
            r.rccpack_median_ms,
            r.ratio,
            r.rccpack_worse,
            r.peer_worse,
            if r.failures > 0 {
                format!("  failures {}", r.failures)
            } else {
                String::new()
            }
        );
    }
    s
}

/// The summary as a fixed-width text table.
pub fn table_text(summary: &[Summary]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<6} {:>3} {:>2} {:>8} {:>5} {:>5} {:>5} {:>10} {:>10} {:>10} {:>7}",
        "series",
        "n",
        "k",
        "optimal",
        "feas",
        "inf",
        "unk",
        "median_ms",
        "max_ms",
        "med_nodes",
        "med_sc"
    );
    for r in summary {
        let series = match r.series {
            Series::Pilot => "pilot",
            Series::Scale => "scale",
        };
        let _ = writeln!(
            s,
            "{:<6} {:>3} {:>2} {:>8} {:>5} {:>5} {:>5} {:>10.1} {:>10.1} {:>10.0} {:>7}{}",
            series,
            r.n,
            r.k,
            format!("{}/{}", r.optimal, r.total),
            r.feasible,
            r.infeasible,
            r.unknown,
            r.median_ms,
            r.max_ms,
            r.median_nodes,
            r.median_score
                .map(|v| format!("{v:.3}"))
                .unwrap_or_else(|| "-".into()),
            if r.errors + r.check_failures > 0 {
                format!("  errors {} check failures {}", r.errors, r.check_failures)
            } else {
                String::new()
            }
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pilot_box_matches_the_thesis_scene() {
        let s = box_scene(200);
        assert_eq!((s.space.width, s.space.height), (600, 600));
        let r: Vec<_> = s.objects.iter().map(|o| o.rect().unwrap()).collect();
        use crate::scene::Rect;
        assert_eq!(r[0], Rect::new(190, 190, 220, 10));
        assert_eq!(r[1], Rect::new(190, 400, 220, 10));
        assert_eq!(r[2], Rect::new(190, 200, 10, 200));
        assert_eq!(r[3], Rect::new(400, 200, 10, 200));
        s.validate().unwrap();
        box_scene(interior_side(48)).validate().unwrap();
    }

    #[test]
    fn interior_grows_with_n() {
        assert_eq!(interior_side(2), 200);
        assert_eq!(interior_side(32), 200);
        assert_eq!(interior_side(48), 240);
        assert_eq!(interior_side(200), 440);
    }

    #[test]
    fn problems_are_deterministic_and_shaped() {
        let cfg = StudyConfig::quick(7, Duration::from_secs(1));
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let sets: Vec<DrawnSet> = (1..=2).map(|d| draw_set(&mut rng, 5, d)).collect();
        for s in &sets {
            for (c, rs) in CLASSES.iter().zip(&s.rules) {
                assert_eq!(rs.len(), 5);
                assert!(rs.iter().all(|r| r.subject() == *c));
                let mut names: Vec<_> = rs.iter().map(|r| &r.name).collect();
                names.dedup();
                assert_eq!(names.len(), 5);
            }
            assert_eq!(s.first(2).rules.len(), 6);
        }
        let a = problems(&cfg, &sets, Series::Pilot, &cfg.ns, &cfg.ks);
        let b = problems(&cfg, &sets, Series::Pilot, &cfg.ns, &cfg.ks);
        assert_eq!(a.len(), 2 * 5 * 5);
        for (p, q) in a.iter().zip(&b) {
            assert_eq!(p.scene, q.scene);
            assert_eq!(p.classes().len(), p.n);
            assert_eq!(p.rules.rules.len(), 3 * p.k);
            p.scene.validate().unwrap();
        }
        let classes: std::collections::HashSet<String> = a.iter().map(|p| p.classes()).collect();
        assert!(classes.len() > 10, "classes vary: {classes:?}");
    }

    #[test]
    fn self_referential_atoms_are_hopeless_for_two() {
        use crate::bench::pool::{atom, touches};
        use crate::relations::Dir;
        let c = |s: &str| Target::Class(s.into());
        assert!(unsatisfiable_with_two(&atom(
            Kind::DR,
            Dir::N,
            "R",
            &c("R")
        )));
        assert!(unsatisfiable_with_two(&atom(
            Kind::EC,
            Dir::W,
            "R",
            &c("R")
        )));
        assert!(unsatisfiable_with_two(&atom(
            Kind::DR,
            Dir::E,
            "R",
            &Target::Any
        )));
        assert!(!unsatisfiable_with_two(&atom(
            Kind::EC,
            Dir::E,
            "R",
            &Target::Any
        )));
        assert!(!unsatisfiable_with_two(&atom(
            Kind::DR,
            Dir::N,
            "R",
            &c("G")
        )));
        assert!(!unsatisfiable_with_two(&touches("R", &c("R"))));
        assert!(!unsatisfiable_with_two(&Formula::not(atom(
            Kind::DR,
            Dir::N,
            "R",
            &c("R")
        ))));
    }

    #[test]
    fn median_and_summary() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(&[]).is_nan());
    }
}
