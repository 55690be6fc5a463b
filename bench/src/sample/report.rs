//! The text report of `bench sample`: the uniformity table, then the
//! diversity table (the sampler and the CP-SAT baseline per problem).

use super::diversity::{Baseline, Spread};
use super::{BenchReport, ProblemRow, Uniformity};
use std::fmt::Write as _;

/// The report as two plain-text tables.
pub fn report_text(r: &BenchReport) -> String {
    let mut s = String::new();
    uniformity_table(&mut s, &r.uniformity);
    let _ = writeln!(s);
    diversity_table(&mut s, r);
    s
}

/// The uniformity table: one line per tiny problem.
fn uniformity_table(s: &mut String, rows: &[(String, Option<Uniformity>)]) {
    let _ = writeln!(
        s,
        "uniformity (first layout of each seed vs uniform over the brute-force optimum layouts)"
    );
    let _ = writeln!(
        s,
        "{:<24} {:>7} {:>6} {:>8} {:>9} {:>9} {:>10} {:>9} {:>10}",
        "problem", "layouts", "draws", "reached", "uniform", "chi2", "p", "min/max", "exhaustive"
    );
    for (name, u) in rows {
        match u {
            Some(u) => {
                let _ = writeln!(
                    s,
                    "{:<24} {:>7} {:>6} {:>8} {:>9.1} {:>9.1} {:>10.2e} {:>9} {:>10}",
                    name,
                    u.layouts,
                    u.draws,
                    u.reached,
                    u.uniform_reached,
                    u.chi_square,
                    u.p_value,
                    format!("{}/{}", u.min_count, u.max_count),
                    if u.exhaustive_ok { "all" } else { "MISSED" }
                );
            }
            None => {
                let _ = writeln!(s, "{name:<24} (not measured)");
            }
        }
    }
}

/// The diversity table: per problem, the sampler's line and the CP-SAT
/// baseline's (when it ran).
fn diversity_table(s: &mut String, r: &BenchReport) {
    let _ = writeln!(
        s,
        "diversity ({} layouts per problem; distance in grid steps, objects matched by id)",
        r.config.n
    );
    let _ = writeln!(
        s,
        "{:<30} {:>4} {:<8} {:>8} {:>7} {:>7} {:>10} {:>9}  positions per class",
        "problem", "objs", "who", "distinct", "mean d", "min d", "ms/layout", "total ms"
    );
    for p in &r.problems {
        sampler_line(s, p);
        if let Some(b) = &p.baseline {
            baseline_line(s, b);
        }
    }
}

/// The positions covered per class, e.g. `B:4 G:7 R:3`.
fn classes(sp: &Spread) -> String {
    sp.positions_per_class
        .iter()
        .map(|(c, n)| format!("{c}:{n}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The sampler's line of one problem (or why it was not measured).
fn sampler_line(s: &mut String, p: &ProblemRow) {
    match &p.sampler {
        Some(d) => {
            let _ = writeln!(
                s,
                "{:<30} {:>4} {:<8} {:>8} {:>7.1} {:>7.1} {:>10.2} {:>9.1}  {}{}",
                p.name,
                p.movable,
                "sample",
                d.spread.distinct,
                d.spread.mean_distance,
                d.spread.min_distance,
                d.ms_per_layout,
                d.total_ms,
                classes(&d.spread),
                if d.limit_struck { " (time limit)" } else { "" }
            );
        }
        None => {
            let _ = writeln!(
                s,
                "{:<30} {:>4} {:<8} {}",
                p.name,
                p.movable,
                "sample",
                p.error.as_deref().unwrap_or("-")
            );
        }
    }
}

/// The CP-SAT baseline's line of one problem (or why it did not run).
fn baseline_line(s: &mut String, b: &Result<Baseline, String>) {
    match b {
        Ok(b) => {
            let n = b.spread.layouts.max(1) as f64;
            let _ = writeln!(
                s,
                "{:<30} {:>4} {:<8} {:>8} {:>7.1} {:>7.1} {:>10.2} {:>9.1}  {}{}",
                "",
                "",
                "cp-sat",
                b.spread.distinct,
                b.spread.mean_distance,
                b.spread.min_distance,
                b.solve_ms / n,
                b.process_ms,
                classes(&b.spread),
                if b.invalid > 0 {
                    format!(" ({} invalid)", b.invalid)
                } else {
                    String::new()
                }
            );
        }
        Err(e) => {
            let _ = writeln!(s, "{:<30} {:>4} {:<8} not run: {e}", "", "", "cp-sat");
        }
    }
}
