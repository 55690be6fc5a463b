//! What `bench tasks` reports: the tasks and rows of `tasks.json`, one line
//! per solved problem, the per-(series, size) summary and its text tables.

use super::solve::{SolveRow, TaskRow};
use super::style::ClassSpec;
use super::{TaskSeries, TasksConfig};
use crate::peers::PeerStatus;
use crate::thesis::{median, PeerRow};
use rccpack::synth::Status;
use serde::Serialize;
use std::fmt::Write;

/// A task as written to `tasks.json`.
#[derive(Debug, Clone, Serialize)]
pub struct TaskReport {
    /// Series.
    pub series: TaskSeries,
    /// Index.
    pub index: usize,
    /// The style in words.
    pub style: String,
    /// The classes and their habits.
    pub classes: Vec<ClassSpec>,
    /// Demonstrations.
    pub demos: usize,
    /// Learned rules.
    pub rules: usize,
}

/// Everything the benchmark measured.
#[derive(Debug, Clone, Serialize)]
pub struct TasksReport {
    /// The configuration.
    pub config: TasksConfig,
    /// The tasks.
    pub tasks: Vec<TaskReport>,
    /// One row per problem.
    pub rows: Vec<TaskRow>,
    /// One line per (series, size).
    pub summary: Vec<TasksSummary>,
}

/// One line about a solved problem, e.g. `task03-1.5x (31 objects, 42
/// rules): score-only optimal 1.000 0.2s; like optimal 1.000 cost 12 0.4s;
/// cp-sat optimal 1.000 3.1s`.
pub fn row_line(r: &TaskRow) -> String {
    let solve = |s: &SolveRow| {
        let status = s
            .status
            .map(|st| format!("{st:?}").to_lowercase())
            .unwrap_or_else(|| "ERROR".into());
        let score = s.score.map(|v| format!(" {v:.3}")).unwrap_or_default();
        let cost = s
            .cost
            .map(|c| {
                format!(
                    " cost {c}{}",
                    if s.cost_proven == Some(true) { "" } else { "?" }
                )
            })
            .unwrap_or_default();
        let bad = if s.verified == Some(false) || s.status.is_none() {
            " !!FAILED"
        } else {
            ""
        };
        format!("{status}{score}{cost} {}{bad}", ms(s.time_ms))
    };
    let mut line = format!(
        "{} ({} objects, {} rules): score-only {}",
        r.name,
        r.movable,
        r.rules,
        solve(&r.score_only)
    );
    if let Some(l) = &r.like {
        line.push_str(&format!("; like {}", solve(l)));
    }
    if r.turnable > 0 {
        line.push_str(&format!("; {} turnable", r.turnable));
    }
    let share = |v: Option<[usize; 2]>| v.map(|[k, n]| format!("{k}/{n}"));
    if let Some(l) = share(r.habits_learned) {
        let kept = |s: &SolveRow| share(s.habits_kept).unwrap_or_else(|| "-".into());
        line.push_str(&format!(
            ", orientation habits learned {l}, kept {}{}",
            kept(&r.score_only),
            r.like
                .as_ref()
                .map(|l| format!(" (like {})", kept(l)))
                .unwrap_or_default()
        ));
    }
    for p in &r.peers {
        if super::solve::peer_not_applicable(p) {
            line.push_str(&format!(
                "; {} {}",
                p.peer,
                super::solve::PEER_NOT_APPLICABLE
            ));
            continue;
        }
        let status = p
            .status
            .map(|st| format!("{st:?}").to_lowercase())
            .unwrap_or_else(|| "failed".into());
        let score = p.score.map(|v| format!(" {v:.3}")).unwrap_or_default();
        line.push_str(&format!("; {} {status}{score} {}", p.peer, ms(p.time_ms)));
    }
    line
}

/// One peer's aggregates in one (series, size) cell.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PeerCell {
    /// The peer.
    pub peer: String,
    /// Proved optimal by the peer.
    pub proven: usize,
    /// Median peer solve time, ms (time-outs at the limit).
    pub median_ms: f64,
    /// Problems where rccpack's score-only score is below the peer's.
    pub rccpack_below: usize,
    /// Problems where rccpack's score-only score is above the peer's.
    pub rccpack_above: usize,
    /// Peer failures or layouts the checker rejected.
    pub failures: usize,
    /// Problems the peer's emitted model cannot hold (turnable blocks).
    #[serde(skip_serializing_if = "is_zero")]
    pub not_applicable: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// Aggregates of one (series, size) cell.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TasksSummary {
    /// Series.
    pub series: TaskSeries,
    /// Size index.
    pub size_index: usize,
    /// Size label.
    pub size: String,
    /// Problems.
    pub problems: usize,
    /// Fewest movable objects.
    pub movable_min: usize,
    /// Most movable objects.
    pub movable_max: usize,
    /// Fewest learned rules.
    pub rules_min: usize,
    /// Most learned rules.
    pub rules_max: usize,
    /// Score-only solves proved optimal.
    pub proven: usize,
    /// Median score-only wall time, ms.
    pub median_ms: f64,
    /// Largest score-only wall time, ms.
    pub max_ms: f64,
    /// Median score-only score.
    pub median_score: Option<f64>,
    /// Lowest score-only score.
    pub min_score: Option<f64>,
    /// `like` solves whose score is proven optimal and cost proven minimal.
    pub like_proven: Option<usize>,
    /// Median `like` wall time, ms.
    pub like_median_ms: Option<f64>,
    /// `like` median over score-only median.
    pub like_ratio: Option<f64>,
    /// Solver errors (both modes).
    pub errors: usize,
    /// Layouts the checker rejected (both modes).
    pub check_failures: usize,
    /// Per peer.
    pub peers: Vec<PeerCell>,
    /// Group tasks: demonstrated shapes kept over shapes, score-only.
    pub shapes_kept: Option<[usize; 2]>,
    /// Group tasks: demonstrated shapes kept over shapes, with `like`.
    pub like_shapes_kept: Option<[usize; 2]>,
    /// `--turnable`: the most turnable blocks in a problem.
    #[serde(skip_serializing_if = "is_zero")]
    pub turnable_max: usize,
    /// `--turnable`: orientation habits learned over habits (one per
    /// class that turns, per problem).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub habits_learned: Option<[usize; 2]>,
    /// `--turnable`: orientation habits the score-only layouts keep.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub habits_kept: Option<[usize; 2]>,
    /// `--turnable`: orientation habits the `like` layouts keep.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub like_habits_kept: Option<[usize; 2]>,
}

/// One [`TasksSummary`] per (series, size), in series then size order.
pub fn summarize(rows: &[TaskRow]) -> Vec<TasksSummary> {
    let mut keys: Vec<(TaskSeries, usize)> =
        rows.iter().map(|r| (r.series, r.size_index)).collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .map(|(series, si)| {
            let cell: Vec<&TaskRow> = rows
                .iter()
                .filter(|r| r.series == series && r.size_index == si)
                .collect();
            summarize_cell(series, si, &cell)
        })
        .collect()
}

/// The problems of one (series, size).
fn summarize_cell(series: TaskSeries, si: usize, cell: &[&TaskRow]) -> TasksSummary {
    let times: Vec<f64> = cell.iter().map(|r| r.score_only.time_ms).collect();
    let scores: Vec<f64> = cell.iter().filter_map(|r| r.score_only.score).collect();
    let likes: Vec<&SolveRow> = cell.iter().filter_map(|r| r.like.as_ref()).collect();
    let like_times: Vec<f64> = likes.iter().map(|l| l.time_ms).collect();
    let solves = || {
        cell.iter()
            .flat_map(|r| std::iter::once(&r.score_only).chain(r.like.as_ref()))
    };
    let so_median = median(&times);
    let add = |a: [usize; 2], b: [usize; 2]| [a[0] + b[0], a[1] + b[1]];
    let sum_kept =
        |rows: &mut dyn Iterator<Item = &SolveRow>| rows.filter_map(|s| s.shapes_kept).reduce(add);
    let sum_habits =
        |rows: &mut dyn Iterator<Item = &SolveRow>| rows.filter_map(|s| s.habits_kept).reduce(add);
    let like_median = (!likes.is_empty()).then(|| median(&like_times));
    TasksSummary {
        series,
        size_index: si,
        size: cell[0].size.clone(),
        problems: cell.len(),
        movable_min: cell.iter().map(|r| r.movable).min().unwrap_or(0),
        movable_max: cell.iter().map(|r| r.movable).max().unwrap_or(0),
        rules_min: cell.iter().map(|r| r.rules).min().unwrap_or(0),
        rules_max: cell.iter().map(|r| r.rules).max().unwrap_or(0),
        proven: cell
            .iter()
            .filter(|r| r.score_only.status == Some(Status::Optimal))
            .count(),
        median_ms: so_median,
        max_ms: times.iter().copied().fold(0.0, f64::max),
        median_score: (!scores.is_empty()).then(|| median(&scores)),
        min_score: scores.iter().copied().reduce(f64::min),
        like_proven: (!likes.is_empty()).then(|| {
            likes
                .iter()
                .filter(|l| l.status == Some(Status::Optimal) && l.cost_proven == Some(true))
                .count()
        }),
        like_median_ms: like_median,
        like_ratio: like_median.map(|m| m / so_median),
        errors: solves().filter(|s| s.status.is_none()).count(),
        check_failures: solves().filter(|s| s.verified == Some(false)).count(),
        peers: peer_cells(cell),
        shapes_kept: sum_kept(&mut cell.iter().map(|r| &r.score_only)),
        like_shapes_kept: sum_kept(&mut likes.iter().copied()),
        turnable_max: cell.iter().map(|r| r.turnable).max().unwrap_or(0),
        habits_learned: cell.iter().filter_map(|r| r.habits_learned).reduce(add),
        habits_kept: sum_habits(&mut cell.iter().map(|r| &r.score_only)),
        like_habits_kept: sum_habits(&mut likes.iter().copied()),
    }
}

/// One [`PeerCell`] per peer that ran on the problems of `cell`, by name.
fn peer_cells(cell: &[&TaskRow]) -> Vec<PeerCell> {
    let mut peer_names: Vec<String> = cell
        .iter()
        .flat_map(|r| r.peers.iter().map(|p| p.peer.clone()))
        .collect();
    peer_names.sort();
    peer_names.dedup();
    let score = |s: Option<f64>| s.unwrap_or(f64::NEG_INFINITY);
    peer_names
        .into_iter()
        .map(|peer| {
            let all: Vec<(&TaskRow, &PeerRow)> = cell
                .iter()
                .filter_map(|r| r.peers.iter().find(|p| p.peer == peer).map(|p| (*r, p)))
                .collect();
            let not_applicable = all
                .iter()
                .filter(|(_, p)| super::solve::peer_not_applicable(p))
                .count();
            let pc: Vec<(&TaskRow, &PeerRow)> = all
                .into_iter()
                .filter(|(_, p)| !super::solve::peer_not_applicable(p))
                .collect();
            let pt: Vec<f64> = pc.iter().map(|(_, p)| p.time_ms).collect();
            PeerCell {
                proven: pc
                    .iter()
                    .filter(|(_, p)| p.status == Some(PeerStatus::Optimal))
                    .count(),
                median_ms: median(&pt),
                rccpack_below: pc
                    .iter()
                    .filter(|(r, p)| score(r.score_only.score) < score(p.score) - 1e-9)
                    .count(),
                rccpack_above: pc
                    .iter()
                    .filter(|(r, p)| score(p.score) < score(r.score_only.score) - 1e-9)
                    .count(),
                failures: pc
                    .iter()
                    .filter(|(_, p)| p.status.is_none() || p.verified == Some(false))
                    .count(),
                not_applicable,
                peer,
            }
        })
        .collect()
}

fn ms(v: f64) -> String {
    if v.is_nan() {
        "-".into()
    } else if v >= 1000.0 {
        format!("{:.1}s", v / 1000.0)
    } else {
        format!("{v:.0}ms")
    }
}

fn range(a: usize, b: usize) -> String {
    if a == b {
        a.to_string()
    } else {
        format!("{a}-{b}")
    }
}

/// The summary as fixed-width text tables: rccpack's, the demonstrated
/// shapes kept (group tasks), then the peers'.
pub fn table_text(summary: &[TasksSummary]) -> String {
    let mut s = String::new();
    engine_table(&mut s, summary);
    if summary.iter().any(|r| r.shapes_kept.is_some()) {
        shapes_table(&mut s, summary);
    }
    if summary.iter().any(|r| r.turnable_max > 0) {
        habits_table(&mut s, summary);
    }
    if summary.iter().any(|r| !r.peers.is_empty()) {
        peers_table(&mut s, summary);
    }
    s
}

/// `--turnable`: the most turnable blocks in a problem, and how many
/// orientation habits were learned and kept, score-only and with `like`.
fn habits_table(s: &mut String, summary: &[TasksSummary]) {
    let _ = writeln!(
        s,
        "\n{:<8} {:<8} {:>5} {:>8} {:>10} {:>10} {:>10}",
        "series", "size", "probs", "turnable", "learned", "kept_so", "kept_like"
    );
    let share = |v: Option<[usize; 2]>| match v {
        Some([k, n]) => format!("{k}/{n}"),
        None => "-".into(),
    };
    for r in summary.iter().filter(|r| r.turnable_max > 0) {
        let _ = writeln!(
            s,
            "{:<8} {:<8} {:>5} {:>8} {:>10} {:>10} {:>10}",
            r.series.name(),
            r.size,
            r.problems,
            r.turnable_max,
            share(r.habits_learned),
            share(r.habits_kept),
            share(r.like_habits_kept)
        );
    }
}

/// rccpack's table: one line per (series, size), score-only and `like`.
fn engine_table(s: &mut String, summary: &[TasksSummary]) {
    let _ = writeln!(
        s,
        "{:<8} {:<8} {:>5} {:>7} {:>7} {:>7} {:>8} {:>8} {:>6} {:>6} {:>8} {:>8} {:>6}",
        "series",
        "size",
        "probs",
        "objects",
        "rules",
        "proven",
        "median",
        "max",
        "med_sc",
        "min_sc",
        "like_pr",
        "like_med",
        "like/so"
    );
    for r in summary {
        let f3 = |v: Option<f64>| v.map(|v| format!("{v:.3}")).unwrap_or_else(|| "-".into());
        let _ = writeln!(
            s,
            "{:<8} {:<8} {:>5} {:>7} {:>7} {:>7} {:>8} {:>8} {:>6} {:>6} {:>8} {:>8} {:>6}{}",
            r.series.name(),
            r.size,
            r.problems,
            range(r.movable_min, r.movable_max),
            range(r.rules_min, r.rules_max),
            format!("{}/{}", r.proven, r.problems),
            ms(r.median_ms),
            ms(r.max_ms),
            f3(r.median_score),
            f3(r.min_score),
            r.like_proven
                .map(|p| format!("{p}/{}", r.problems))
                .unwrap_or_else(|| "-".into()),
            r.like_median_ms.map(ms).unwrap_or_else(|| "-".into()),
            r.like_ratio
                .map(|v| format!("{v:.2}"))
                .unwrap_or_else(|| "-".into()),
            if r.errors + r.check_failures > 0 {
                format!(
                    "  !! errors {} check failures {}",
                    r.errors, r.check_failures
                )
            } else {
                String::new()
            }
        );
    }
}

/// Group tasks: how many demonstrated shapes the layouts keep, score-only
/// and with `like`.
fn shapes_table(s: &mut String, summary: &[TasksSummary]) {
    let _ = writeln!(
        s,
        "\n{:<8} {:<8} {:>5} {:>14} {:>14}",
        "series", "size", "probs", "shapes_so", "shapes_like"
    );
    let share = |v: Option<[usize; 2]>| match v {
        Some([k, n]) if n > 0 => format!("{k}/{n} {:.0}%", 100.0 * k as f64 / n as f64),
        _ => "-".into(),
    };
    for r in summary.iter().filter(|r| r.shapes_kept.is_some()) {
        let _ = writeln!(
            s,
            "{:<8} {:<8} {:>5} {:>14} {:>14}",
            r.series.name(),
            r.size,
            r.problems,
            share(r.shapes_kept),
            share(r.like_shapes_kept)
        );
    }
}

/// The peers' table: one line per (series, size, peer), beside rccpack's
/// proven count and median.
fn peers_table(s: &mut String, summary: &[TasksSummary]) {
    let _ = writeln!(
        s,
        "\n{:<8} {:<8} {:<7} {:>7} {:>8} {:>7} {:>8} {:>9} {:>9}",
        "series", "size", "peer", "proven", "median", "rcc_pr", "rcc_med", "rcc_below", "rcc_above"
    );
    for r in summary {
        for p in &r.peers {
            let _ = writeln!(
                s,
                "{:<8} {:<8} {:<7} {:>7} {:>8} {:>7} {:>8} {:>9} {:>9}{}",
                r.series.name(),
                r.size,
                p.peer,
                format!("{}/{}", p.proven, r.problems),
                ms(p.median_ms),
                format!("{}/{}", r.proven, r.problems),
                ms(r.median_ms),
                p.rccpack_below,
                p.rccpack_above,
                match (p.failures, p.not_applicable) {
                    (0, 0) => String::new(),
                    (f, 0) => format!("  failures {f}"),
                    (f, n) => format!("  failures {f}, {} {n}", super::solve::PEER_NOT_APPLICABLE),
                }
            );
        }
    }
}
