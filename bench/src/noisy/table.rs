//! The report of `bench noisy` as markdown.

use super::{NoisyReport, NoisyRow, Variant, VariantRow};

fn pct(a: usize, b: usize) -> String {
    if b == 0 {
        "-".into()
    } else {
        format!("{:.0} %", 100.0 * a as f64 / b as f64)
    }
}

/// The report as a markdown table (one row per task, a cell per variant:
/// kept/exact, `+extra`, the slip's rank among the suspects), then the
/// totals against the targets.
pub fn table_markdown(r: &NoisyReport) -> String {
    let mut s = String::from("| task | reference | exact | jitter | slip | both | rough | slip named | run keeps |\n|---|---|---|---|---|---|---|---|---|\n");
    for row in &r.rows {
        let cell = |v: Variant| {
            row.variants
                .iter()
                .find(|x| x.variant == v)
                .map_or("-".to_string(), |x| match &x.error {
                    Some(_) => "refused".into(),
                    None => format!("{}/{} +{}", x.kept, row.exact, x.extra),
                })
        };
        let named = row
            .variants
            .iter()
            .find(|x| x.variant == Variant::Slip)
            .and_then(|x| x.slip_named.zip(x.slip_first))
            .map_or("-", |(n, f)| match (n, f) {
                (_, true) => "first",
                (true, false) => "named",
                _ => "no",
            });
        let run = row.run_kept.map_or("-".into(), |(b, n)| format!("{n}/{b}"));
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            row.name,
            row.exact,
            cell(Variant::Exact),
            cell(Variant::Jitter),
            cell(Variant::Slip),
            cell(Variant::Both),
            cell(Variant::Rough),
            named,
            run
        ));
    }
    s.push('\n');
    s.push_str(&totals_markdown(r));
    s
}

/// The totals of [`table_markdown`]: per variant, the exact rules kept and
/// the rules added; the slip named; suspects on the exact demonstrations.
fn totals_markdown(r: &NoisyReport) -> String {
    let mut s = String::new();
    for v in Variant::ALL {
        let rows: Vec<(&NoisyRow, &VariantRow)> = r
            .rows
            .iter()
            .filter_map(|row| {
                row.variants
                    .iter()
                    .find(|x| x.variant == v)
                    .map(|x| (row, x))
            })
            .collect();
        let exact: usize = rows.iter().map(|(row, _)| row.exact).sum();
        let kept: usize = rows.iter().map(|(_, x)| x.kept).sum();
        let extra: usize = rows.iter().map(|(_, x)| x.extra).sum();
        let whole = rows.iter().filter(|(row, x)| x.kept == row.exact).count();
        let refused = rows.iter().filter(|(_, x)| x.error.is_some()).count();
        s.push_str(&format!(
            "- {}: {kept}/{exact} exact rules kept ({}), {extra} extra ({} of the exact), {whole}/{} tasks whole, {refused} refused\n",
            v.name(),
            pct(kept, exact),
            pct(extra, exact),
            rows.len()
        ));
    }
    let slips: Vec<&VariantRow> = r
        .rows
        .iter()
        .filter_map(|row| row.variants.iter().find(|x| x.variant == Variant::Slip))
        .collect();
    let named = slips.iter().filter(|x| x.slip_named == Some(true)).count();
    let first = slips.iter().filter(|x| x.slip_first == Some(true)).count();
    let runs: Vec<(usize, usize)> = r.rows.iter().filter_map(|row| row.run_kept).collect();
    let run_whole = runs.iter().filter(|(b, n)| b == n).count();
    s.push_str(&format!(
        "- the slip named among the suspects on {named}/{} (first on {first}); the layout solved with the slipped rules keeps every exact rule the exact layout keeps on {run_whole}/{}\n",
        slips.len(),
        runs.len()
    ));
    let exact_suspects: usize = r.rows.iter().map(|row| row.exact_suspects).sum();
    s.push_str(&format!(
        "- suspects named on the exact demonstrations: {exact_suspects}\n"
    ));
    s
}
