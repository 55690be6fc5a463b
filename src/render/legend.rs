//! The legend beside the table: the score and one line per rule (with
//! its violators), the class key, and the notes on shading and moved
//! blocks; measured before the picture's width is known.

use super::draw::MOVED_STROKE;
use super::style::{darker, esc, n, text_width, truncate, FIXED_FILL};
use super::RenderOptions;
use crate::eval::Evaluation;
use crate::scene::{Object, Scene};
use std::collections::HashMap;
use std::fmt::Write as _;

/// Every legend line: the rules' lines (with, per violating object,
/// whether it breaks a hard rule), the class key and the notes on the
/// shading and the moved blocks.
pub(super) fn lines<'e>(
    scene: &Scene,
    eval: Option<&'e Evaluation>,
    opts: &RenderOptions,
    fill_of: &dyn Fn(&Object) -> &'static str,
) -> (Vec<Line>, HashMap<&'e str, bool>) {
    let mut lines: Vec<Line> = Vec::new();
    let mut hard_of: HashMap<&str, bool> = HashMap::new();
    if let Some(ev) = eval {
        (lines, hard_of) = rule_lines(ev);
    }
    lines.extend(class_lines(scene, fill_of));
    if opts.like.is_some() {
        lines.push(Line {
            dy: 20.0,
            parts: vec![text(
                0.0,
                11.0,
                false,
                "#666666",
                false,
                "shaded: where the demonstrations put each class".into(),
            )],
        });
    }
    if !opts.outlined.is_empty() {
        lines.push(Line {
            dy: 20.0,
            parts: vec![text(
                0.0,
                11.0,
                false,
                MOVED_STROKE,
                false,
                "outlined: the block that most looks like a slip".into(),
            )],
        });
    }
    if !opts.moved.is_empty() {
        lines.push(Line {
            dy: 20.0,
            parts: vec![text(
                0.0,
                11.0,
                false,
                MOVED_STROKE,
                false,
                "dashed: where a moved block was".into(),
            )],
        });
    }
    (lines, hard_of)
}

/// One legend line: `(x, y, size, bold, fill, anchor, text)` collected before
/// the column's width is known.
pub(super) struct Line {
    pub(super) dy: f64,
    pub(super) parts: Vec<Part>,
}

pub(super) enum Part {
    Text {
        dx: f64,
        size: f64,
        bold: bool,
        fill: &'static str,
        end: bool,
        text: String,
    },
    Swatch {
        fill: &'static str,
    },
}

/// One legend text part.
pub(super) fn text(
    dx: f64,
    size: f64,
    bold: bool,
    fill: &'static str,
    end: bool,
    t: String,
) -> Part {
    Part::Text {
        dx,
        size,
        bold,
        fill,
        end,
        text: t,
    }
}

/// The legend's score lines and one line per rule (with its violators);
/// per violating object, whether it breaks a hard rule.
pub(super) fn rule_lines(ev: &Evaluation) -> (Vec<Line>, HashMap<&str, bool>) {
    let mut lines = score_lines(ev);
    let mut hard_of: HashMap<&str, bool> = HashMap::new();
    for r in &ev.rules {
        for v in &r.violators {
            let hard = hard_of.entry(v.as_str()).or_insert(false);
            *hard |= r.hard;
        }
        push_rule_lines(r, &mut lines);
    }
    lines.push(Line {
        dy: 10.0,
        parts: vec![],
    });
    (lines, hard_of)
}

/// The score, the weights (and hard violations) and the "rules" heading.
fn score_lines(ev: &Evaluation) -> Vec<Line> {
    let any_soft = ev.rules.iter().any(|r| !r.hard);
    let mut sub = format!(
        "weight {} of {}",
        n(ev.satisfied_weight),
        n(ev.total_weight)
    );
    if ev.rules.iter().any(|r| r.hard) {
        let _ = write!(sub, " · hard violations {}", ev.hard_violations);
    }
    vec![
        Line {
            dy: 18.0,
            parts: vec![text(
                0.0,
                16.0,
                true,
                "#222222",
                false,
                if any_soft {
                    format!("score {:.3}", ev.score)
                } else {
                    "score 1 (no soft rules)".into()
                },
            )],
        },
        Line {
            dy: 17.0,
            parts: vec![text(0.0, 11.0, false, "#666666", false, sub)],
        },
        Line {
            dy: 26.0,
            parts: vec![text(0.0, 13.0, true, "#333333", false, "rules".into())],
        },
    ]
}

/// One rule's line (mark, name, count) and, when broken, its violators.
fn push_rule_lines(r: &crate::eval::RuleReport, lines: &mut Vec<Line>) {
    // A scene-level or group rule can fail with no object to blame
    // (`some R: …` with none, `not column(R)` with one column).
    let ok = r.violators.is_empty() && r.satisfied == r.subjects;
    let mut name = truncate(&r.name, 34);
    if r.hard {
        name.push_str("  [hard]");
    }
    lines.push(Line {
        dy: 18.0,
        parts: vec![
            text(
                0.0,
                12.0,
                true,
                if ok { "#3c8d40" } else { "#d35400" },
                false,
                if ok { "✓" } else { "✗" }.into(),
            ),
            text(
                16.0,
                12.0,
                false,
                if r.hard { "#7a4f00" } else { "#222222" },
                false,
                name,
            ),
            text(
                0.0,
                12.0,
                false,
                "#222222",
                true,
                format!("{}/{}", r.satisfied, r.subjects),
            ),
        ],
    });
    if !r.violators.is_empty() {
        let ids = truncate(&r.violators.join(", "), 40);
        let what = match &r.group {
            Some(g) => format!("off the main {}: {ids}", g.shape),
            None => format!("broken by {ids}"),
        };
        lines.push(Line {
            dy: 14.0,
            parts: vec![text(16.0, 10.5, false, "#8a8a8a", false, what)],
        });
    }
}

/// The legend's class key: one line per class (and colour), with counts.
pub(super) fn class_lines(scene: &Scene, fill_of: &dyn Fn(&Object) -> &'static str) -> Vec<Line> {
    let mut lines = Vec::new();
    let mut class_rows: Vec<(String, &'static str, usize, usize)> = Vec::new();
    for o in &scene.objects {
        let fill = fill_of(o);
        match class_rows
            .iter_mut()
            .find(|r| r.0 == o.class && r.1 == fill)
        {
            Some(r) => {
                if o.is_placed() {
                    r.2 += 1
                } else {
                    r.3 += 1
                }
            }
            None => class_rows.push((
                o.class.clone(),
                fill,
                o.is_placed() as usize,
                (!o.is_placed()) as usize,
            )),
        }
    }
    if !class_rows.is_empty() {
        lines.push(Line {
            dy: 18.0,
            parts: vec![text(0.0, 13.0, true, "#333333", false, "classes".into())],
        });
        for (class, fill, placed, unplaced) in &class_rows {
            let mut label = format!("{}  ×{}", truncate(class, 24), placed + unplaced);
            if *fill == FIXED_FILL {
                label.push_str(" (fixed)");
            } else if *unplaced > 0 {
                let _ = write!(label, " ({unplaced} unplaced)");
            }
            lines.push(Line {
                dy: 18.0,
                parts: vec![
                    Part::Swatch { fill },
                    text(18.0, 12.0, false, "#222222", false, label),
                ],
            });
        }
    }
    lines
}

/// The legend's width: its widest line (at least 120).
pub(super) fn legend_width(lines: &[Line]) -> f64 {
    let mut lw: f64 = 120.0;
    for l in lines {
        let mut w = 0.0;
        for p in &l.parts {
            if let Part::Text {
                dx,
                size,
                text,
                end,
                ..
            } = p
            {
                let tw = text_width(text, *size);
                w += if *end { tw + 18.0 } else { dx + tw };
            }
        }
        lw = lw.max(w);
    }
    lw
}

/// The legend column at `lx` (width `lw`), from the top of the table `ty`.
pub(super) fn write_legend(out: &mut String, lines: &[Line], lx: f64, lw: f64, ty: f64) {
    if lines.is_empty() {
        return;
    }
    out.push_str("<g class=\"legend\">\n");
    let mut y = ty;
    for l in lines {
        y += l.dy;
        for p in &l.parts {
            match p {
                Part::Text {
                    dx,
                    size,
                    bold,
                    fill,
                    end,
                    text,
                } => {
                    let (x, anchor) = if *end {
                        (lx + lw, " text-anchor=\"end\"")
                    } else {
                        (lx + dx, "")
                    };
                    let weight = if *bold { " font-weight=\"bold\"" } else { "" };
                    let _ = writeln!(
                        out,
                        "<text x=\"{}\" y=\"{}\" font-size=\"{}\"{weight}{anchor} fill=\"{fill}\">{}</text>",
                        n(x),
                        n(y),
                        n(*size),
                        esc(text)
                    );
                }
                Part::Swatch { fill } => {
                    let _ = writeln!(
                        out,
                        "<rect class=\"swatch\" x=\"{}\" y=\"{}\" width=\"12\" height=\"12\" fill=\"{fill}\" stroke=\"{}\"/>",
                        n(lx),
                        n(y - 10.5),
                        darker(fill)
                    );
                }
            }
        }
    }
    out.push_str("</g>\n");
}
