//! PNG charts of the runtime study, in the style of the thesis's Figure 4-1:
//! median search nodes (left) and median time (right) against the number of
//! objects, one line per number of rules per class, log y axes.
//!
//! Drawn with plotters' bitmap backend and DejaVu Sans embedded through the
//! `dejavu` crate (the same font the renderer embeds), so no system font or
//! library is needed at build or run time.

use super::thesis::{Series, Summary};
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::path::Path;
use std::sync::Once;

/// Line colours: distinct on white, in the order of the lines.
const COLORS: [RGBColor; 6] = [
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(23, 190, 207),
];

fn ensure_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // Registration only fails on a malformed font; the embedded one is
        // fine, and drawing would report FontUnavailable anyway.
        let _ = register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular());
    });
}

/// One line: a label and `(objects, median nodes, median ms)` points.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Legend text, e.g. `k = 3`.
    pub label: String,
    /// Points sorted by objects.
    pub points: Vec<(f64, f64, f64)>,
}

/// The lines of one chart: over the summaries whose series is in `series`,
/// one line per `k`.
pub fn lines(summary: &[Summary], series: &[Series]) -> Vec<Line> {
    let mut ks: Vec<usize> = summary
        .iter()
        .filter(|s| series.contains(&s.series))
        .map(|s| s.k)
        .collect();
    ks.sort();
    ks.dedup();
    ks.into_iter()
        .map(|k| {
            let mut points: Vec<(f64, f64, f64)> = summary
                .iter()
                .filter(|s| s.k == k && series.contains(&s.series))
                .map(|s| (s.n as f64, s.median_nodes, s.median_ms))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            Line {
                label: format!("k = {k} rules/class"),
                points,
            }
        })
        .collect()
}

fn log_range(values: impl Iterator<Item = f64>, floor: f64) -> std::ops::Range<f64> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        let v = v.max(floor);
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !lo.is_finite() {
        return floor..floor * 10.0;
    }
    (lo / 2.0).max(floor / 2.0)..(hi * 2.0).max(lo * 10.0)
}

/// Draw a two-panel PNG (nodes | time) of `lines` to `path`.
pub fn draw(path: &Path, title: &str, lines: &[Line]) -> Result<(), super::BenchError> {
    draw_png(path, title, lines).map_err(super::BenchError::Chart)
}

fn draw_png(path: &Path, title: &str, lines: &[Line]) -> Result<(), String> {
    ensure_font();
    let e = |e: &dyn std::fmt::Display| format!("{}: cannot draw chart: {e}", path.display());
    let root = BitMapBackend::new(path, (1300, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let root = root.titled(title, ("sans-serif", 24)).map_err(|x| e(&x))?;
    let panels = root.split_evenly((1, 2));
    let xs = lines.iter().flat_map(|l| l.points.iter().map(|p| p.0));
    let (xmin, xmax) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    let (xmin, xmax) = if xmin.is_finite() {
        (xmin - 0.5, xmax + 0.5)
    } else {
        (0.0, 1.0)
    };
    for (pi, panel) in panels.iter().enumerate() {
        draw_panel(panel, pi == 0, lines, (xmin, xmax)).map_err(|x| e(&x))?;
    }
    root.present().map_err(|x| e(&x))?;
    Ok(())
}

/// One panel of [`draw_png`]: median nodes (`nodes`) or median time.
fn draw_panel(
    panel: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    nodes: bool,
    lines: &[Line],
    (xmin, xmax): (f64, f64),
) -> Result<(), String> {
    const NODE_FLOOR: f64 = 1.0;
    const MS_FLOOR: f64 = 0.01;
    let e = |x: &dyn std::fmt::Display| x.to_string();
    let (caption, ydesc, floor) = if nodes {
        ("Median search nodes", "nodes (log)", NODE_FLOOR)
    } else {
        ("Median wall time", "milliseconds (log)", MS_FLOOR)
    };
    let pick = |p: &(f64, f64, f64)| if nodes { p.1 } else { p.2 };
    let yr = log_range(lines.iter().flat_map(|l| l.points.iter().map(pick)), floor);
    let mut chart = ChartBuilder::on(panel)
        .caption(caption, ("sans-serif", 20))
        .margin(18)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(xmin..xmax, yr.log_scale())
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_desc("objects to place")
        .y_desc(ydesc)
        .x_labels(((xmax - xmin).round() as usize + 1).min(30))
        .x_label_formatter(&|x| {
            if (x - x.round()).abs() < 1e-6 {
                format!("{x:.0}")
            } else {
                String::new()
            }
        })
        .y_label_formatter(&|y| {
            if *y >= 1.0 {
                format!("{y:.0}")
            } else {
                format!("{y}")
            }
        })
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .draw()
        .map_err(|x| e(&x))?;
    for (i, l) in lines.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        let pts: Vec<(f64, f64)> = l
            .points
            .iter()
            .map(|p| (p.0, pick(p).max(floor)))
            .filter(|p| p.1.is_finite())
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
            .map_err(|x| e(&x))?
            .label(l.label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .draw_series(pts.iter().map(|p| Circle::new(*p, 4, color.filled())))
            .map_err(|x| e(&x))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(|x| e(&x))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_a_png_with_the_embedded_font() {
        let dir = std::env::temp_dir().join(format!("rccpack-chart-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("c.png");
        let lines = vec![
            Line {
                label: "k = 1".into(),
                points: vec![(2.0, 3.0, 0.5), (3.0, 10.0, 2.0), (4.0, 0.0, 0.0)],
            },
            Line {
                label: "k = 2".into(),
                points: vec![(2.0, 30.0, 5.0), (3.0, 100.0, 20.0)],
            },
        ];
        draw(&path, "test chart", &lines).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        // Empty input still draws.
        draw(&path, "empty", &[]).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
