//! Running the study: every problem solved once by the engine (and by the
//! peers on the emitted model), every solution checked.

use super::problems::{find_viable_sets, study_problems, DrawnSet, Problem};
use super::report::{summarize, summarize_peers, PeerSummary, Summary};
use super::{Series, StudyConfig, CLASSES};
use crate::peers::{Peer, PeerStatus};
use crate::pool::formula_text;
use crate::{peers, Solver};
use rccpack::synth::{Status, SynthOptions};
use serde::Serialize;
use std::time::Instant;

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
    /// numerator of the solution.
    pub satisfied_weight: Option<f64>,
    /// denominator of the solution.
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
    let e = match rccpack::synth::emit::emitted(&p.scene, &p.rules, &study_options(cfg)) {
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
                    let ev = rccpack::eval::evaluate(&sol, &p.rules, cfg.contact);
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

/// The synthesis options of one solve of the study (its time limit
/// counts from now).
pub fn study_options(cfg: &StudyConfig) -> SynthOptions {
    let mut opts = SynthOptions {
        contact: cfg.contact,
        // Counted from now: one call per solve.
        stop: rccpack::stop::Stop::after(cfg.time_limit),
        seed: cfg.seed,
        tuning: cfg.tuning,
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
