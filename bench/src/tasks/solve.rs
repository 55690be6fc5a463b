//! Solving the problems of the tasks: score only, with `like` = the
//! demonstrations, and the peers on the emitted score-only model; every
//! layout re-checked by the checker.

use super::report::{row_line, summarize, TaskReport, TasksReport};
use super::{groups, BenchTask, TaskSeries, TasksConfig};
use crate::peers::Peer;
use crate::thesis::PeerRow;
use crate::{peers, Solver};
use rccpack::relations::Contact;
use rccpack::resemblance::ResemblanceTarget;
use rccpack::rules::RuleSet;
use rccpack::scene::Scene;
use rccpack::synth::{Status, SynthOptions};
use serde::Serialize;
use std::time::Instant;

/// The options of a solve: score only (`like = None`) or with the
/// demonstrations as like-scenes; the time limit counts from now (see
/// `restarted`).
pub fn solve_options(cfg: &TasksConfig, demos: &[Scene], like: bool) -> SynthOptions {
    let mut opts = SynthOptions {
        contact: Contact::Point,
        stop: rccpack::stop::Stop::after(cfg.time_limit),
        seed: cfg.seed,
        like: like.then(|| ResemblanceTarget::new(demos)),
        tuning: cfg.tuning,
        ..SynthOptions::default()
    };
    if cfg.warm_start {
        opts.warm_start = demos.to_vec();
    }
    if !cfg.lns {
        opts.lns = None;
    }
    opts
}

/// One solve of one problem.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SolveRow {
    /// How it ended (`None`: the engine returned an error).
    pub status: Option<Status>,
    /// Wall time around the call, ms.
    pub time_ms: f64,
    /// Search nodes.
    pub nodes: u64,
    /// Evaluator score of the layout.
    pub score: Option<f64>,
    /// Resemblance cost (with `like`).
    pub cost: Option<u64>,
    /// Whether the cost is proven minimal (with `like`).
    pub cost_proven: Option<bool>,
    /// Whether the layout passed the checker (`None`: no layout).
    pub verified: Option<bool>,
    /// The checker's complaint or the engine's error.
    pub error: Option<String>,
    /// Group tasks: of the classes demonstrated with a group shape, how
    /// many keep it in the layout, `[kept, classes]`.
    pub shapes_kept: Option<[usize; 2]>,
    /// `--turnable`: of the classes that turn, how many the layout keeps
    /// the demonstrator's orientation habit for (every block on end, or
    /// every one flat), `[kept, classes]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub habits_kept: Option<[usize; 2]>,
    /// The layout (not written to `tasks.json`).
    #[serde(skip)]
    pub layout: Option<Scene>,
}

/// Solve `scene` once with `opts` and check the layout.
pub fn solve_once(
    engine: Solver<'_>,
    scene: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
) -> SolveRow {
    let t0 = Instant::now();
    let res = (engine.solve)(scene, rules, opts);
    let time_ms = t0.elapsed().as_secs_f64() * 1e3;
    let mut row = SolveRow {
        status: None,
        time_ms,
        nodes: 0,
        score: None,
        cost: None,
        cost_proven: None,
        verified: None,
        error: None,
        shapes_kept: None,
        habits_kept: None,
        layout: None,
    };
    match res {
        Err(e) => row.error = Some(e.to_string()),
        Ok(r) => {
            row.status = Some(r.status);
            row.nodes = r.stats.nodes;
            row.score = r.evaluation.as_ref().map(|e| e.score);
            if let Some(rs) = &r.resemblance {
                row.cost = Some(rs.cost);
                row.cost_proven = Some(rs.proven);
            }
            if let Some(sol) = &r.scene {
                match (engine.verify)(scene, sol, rules, opts.contact) {
                    Ok(()) => row.verified = Some(true),
                    Err(e) => {
                        row.verified = Some(false);
                        row.error = Some(e);
                    }
                }
            }
            row.layout = r.scene;
        }
    }
    row
}

/// What a peer's error starts with when its emitted model cannot hold the
/// problem's turnable blocks: the cell is "n/a (turnable)", not a failure.
pub const PEER_NOT_APPLICABLE: &str = "n/a (turnable)";

/// Whether a peer's row is [`PEER_NOT_APPLICABLE`].
pub fn peer_not_applicable(p: &PeerRow) -> bool {
    p.status.is_none()
        && p.error
            .as_deref()
            .is_some_and(|e| e.starts_with(PEER_NOT_APPLICABLE))
}

/// Run `peer` on the emitted (score-only) model of a problem; its layout
/// is scored by the evaluator and checked.
pub fn solve_peer(
    engine: Solver<'_>,
    cfg: &TasksConfig,
    scene: &Scene,
    rules: &RuleSet,
    peer: Peer,
) -> PeerRow {
    let mut row = PeerRow {
        peer: peer.name().into(),
        status: None,
        time_ms: 0.0,
        process_ms: 0.0,
        score: None,
        verified: None,
        error: None,
    };
    let opts = solve_options(cfg, &[], false);
    let e = match rccpack::synth::emit::emitted(scene, rules, &opts) {
        Ok(e) => e,
        // The emitted model cannot say that a block turns: no cell to fill.
        Err(e @ rccpack::synth::SynthError::Unsupported(_))
            if scene.objects.iter().any(|o| o.turnable) =>
        {
            row.error = Some(format!("{PEER_NOT_APPLICABLE}: {e}"));
            return row;
        }
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
                let sol = e.model.scene(scene, v);
                row.score = Some(rccpack::eval::evaluate(&sol, rules, opts.contact).score);
                match (engine.verify)(scene, &sol, rules, opts.contact) {
                    Ok(()) => row.verified = Some(true),
                    Err(msg) => {
                        row.verified = Some(false);
                        row.error = Some(msg);
                    }
                }
            }
        }
    }
    row
}

/// One problem, solved.
#[derive(Debug, Clone, Serialize)]
pub struct TaskRow {
    /// Generated tasks or the bundled example.
    pub series: TaskSeries,
    /// Task index.
    pub task: usize,
    /// Size index (for grouping).
    pub size_index: usize,
    /// `1.5x`, `8/class`.
    pub size: String,
    /// File name stem.
    pub name: String,
    /// Movable objects.
    pub movable: usize,
    /// Learned rules.
    pub rules: usize,
    /// The score-only solve.
    pub score_only: SolveRow,
    /// The solve with `like` = the demonstrations.
    pub like: Option<SolveRow>,
    /// The peers on the score-only model.
    pub peers: Vec<PeerRow>,
    /// `--turnable`: the problem's turnable blocks.
    #[serde(skip_serializing_if = "is_zero")]
    pub turnable: usize,
    /// `--turnable`: of the classes that turn, how many orientation habits
    /// learning kept as the meant statement (`turned(A)` or
    /// `!turned(A)`), `[learned, classes]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub habits_learned: Option<[usize; 2]>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// The classes of `t` that turn, with the statement their demonstrator
/// means.
fn habits(t: &BenchTask) -> Vec<(&str, rccpack::rules::Formula)> {
    (t.classes.iter())
        .filter_map(|c| Some((c.class.as_str(), c.orientation.meant(&c.class)?)))
        .collect()
}

/// Of the classes of `t` that turn, how many have their meant orientation
/// statement among the learned rules; `None` when no class turns.
pub(crate) fn habits_learned(t: &BenchTask) -> Option<[usize; 2]> {
    let h = habits(t);
    let learned = (h.iter())
        .filter(|(_, f)| {
            (t.rules.rules.iter())
                .any(|r| r.scope == rccpack::rules::Scope::Each && &r.formula == f)
        })
        .count();
    (!h.is_empty()).then_some([learned, h.len()])
}

/// Of the classes of `t` that turn, how many `layout` keeps the
/// demonstrator's habit for (the evaluator reads the meant statement);
/// `None` when no class turns.
pub(crate) fn habits_kept(t: &BenchTask, layout: &Scene, contact: Contact) -> Option<[usize; 2]> {
    let h = habits(t);
    let rules = RuleSet::new(
        (h.iter())
            .map(|(c, f)| rccpack::rules::Rule::new(format!("habit_{c}"), f.clone()))
            .collect(),
    );
    let e = rccpack::eval::evaluate(layout, &rules, contact);
    let kept = (e.rules.iter())
        .filter(|r| r.satisfied == r.subjects)
        .count();
    (!h.is_empty()).then_some([kept, h.len()])
}

/// What the benchmark is doing, for a progress bar.
#[derive(Debug, Clone)]
pub enum TasksEvent {
    /// A problem was solved: one line about it.
    Solved {
        /// Problems solved.
        done: usize,
        /// Problems in all.
        total: usize,
        /// e.g. `task03-1.5x (31 objects): score-only optimal 1.000 in 0.2 s; …`.
        line: String,
    },
    /// A problem is about to be solved (`done` solved before it).
    Solving {
        /// Problems solved.
        done: usize,
        /// Problems in all.
        total: usize,
        /// e.g. `task03-1.5x like`.
        label: String,
    },
}

/// How far [`run_tasks`] is.
#[derive(Clone, Copy)]
struct Progress {
    done: usize,
    total: usize,
}

/// `opts` with the time limit counted from now (one per solve).
fn restarted(cfg: &TasksConfig, opts: &SynthOptions) -> SynthOptions {
    SynthOptions {
        stop: rccpack::stop::Stop::after(cfg.time_limit),
        ..opts.clone()
    }
}

/// One problem of task `t`: score only, with `like` (`opts` in that
/// order), and by each peer.
fn solve_problem(
    engine: Solver<'_>,
    cfg: &TasksConfig,
    t: &BenchTask,
    p: &super::TaskProblem,
    [score_opts, like_opts]: [&SynthOptions; 2],
    at: Progress,
    progress: &mut dyn FnMut(&TasksEvent),
) -> TaskRow {
    let label = |what: &str| TasksEvent::Solving {
        done: at.done,
        total: at.total,
        label: format!("{} {what}", p.name),
    };
    let kept = |mut row: SolveRow, opts: &SynthOptions| {
        if let Some(l) = &row.layout {
            row.habits_kept = habits_kept(t, l, opts.contact);
        }
        if t.series == TaskSeries::Groups {
            row.shapes_kept = row.layout.as_ref().map(|l| {
                let (k, n) = groups::shapes_kept(t, l, opts.contact);
                [k, n]
            });
        }
        row.layout = None;
        row
    };
    progress(&label("score-only"));
    let score_opts = &restarted(cfg, score_opts);
    let score_only = kept(
        solve_once(engine, &p.scene, &t.rules, score_opts),
        score_opts,
    );
    let like = cfg.like.then(|| {
        progress(&label("like"));
        let like_opts = &restarted(cfg, like_opts);
        kept(solve_once(engine, &p.scene, &t.rules, like_opts), like_opts)
    });
    let peers = cfg
        .peers
        .iter()
        .map(|&peer| {
            progress(&label(peer.name()));
            solve_peer(engine, cfg, &p.scene, &t.rules, peer)
        })
        .collect();
    TaskRow {
        series: t.series,
        task: t.index,
        size_index: p.size_index,
        size: p.size.clone(),
        name: p.name.clone(),
        movable: p.movable,
        rules: t.rules.rules.len(),
        score_only,
        like,
        peers,
        turnable: p.scene.objects.iter().filter(|o| o.turnable).count(),
        habits_learned: habits_learned(t),
    }
}

/// Solve every problem of `tasks` (score only, with `like`, peers), one
/// solver at a time.
pub fn run_tasks(
    engine: Solver<'_>,
    cfg: &TasksConfig,
    tasks: &[BenchTask],
    progress: &mut dyn FnMut(&TasksEvent),
) -> TasksReport {
    let total: usize = tasks.iter().map(|t| t.problems.len()).sum();
    let mut rows = Vec::with_capacity(total);
    for t in tasks {
        let score_opts = solve_options(cfg, &t.demos, false);
        let like_opts = solve_options(cfg, &t.demos, true);
        for p in &t.problems {
            let at = Progress {
                done: rows.len(),
                total,
            };
            let row = solve_problem(engine, cfg, t, p, [&score_opts, &like_opts], at, progress);
            progress(&TasksEvent::Solved {
                done: at.done + 1,
                total,
                line: row_line(&row),
            });
            rows.push(row);
        }
    }
    progress(&TasksEvent::Solving {
        done: total,
        total,
        label: "done".into(),
    });
    TasksReport {
        config: cfg.clone(),
        tasks: tasks
            .iter()
            .map(|t| TaskReport {
                series: t.series,
                index: t.index,
                style: t.style.clone(),
                classes: t.classes.clone(),
                demos: t.demos.len(),
                rules: t.rules.rules.len(),
            })
            .collect(),
        summary: summarize(&rows),
        rows,
    }
}
