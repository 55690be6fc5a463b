//! The study's summaries per `(series, n, k)` and per peer, and their
//! fixed-width text tables.

use super::solve::{PeerRow, Row};
use super::Series;
use crate::peers::PeerStatus;
use rccpack::synth::Status;
use serde::Serialize;

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
