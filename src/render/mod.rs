//! Pictures of scenes: SVG, and PNG through resvg.
//!
//! [`render_svg`] writes the SVG by hand: the table (the space) with faint
//! grid lines, fixed objects in dark grey, movable objects coloured by class
//! (`R` red, `G` green, `B` blue, other classes from a fixed palette in order
//! of appearance), each labelled with its id. North is up: a scene's `y`
//! grows upwards, so the picture flips it. Unplaced objects are drawn in a
//! tray below the table, so a problem can be previewed. Given rules, the
//! scene is evaluated with [`crate::eval::evaluate`]: objects that break a
//! rule get a thick orange/black dashed outline and a legend beside the table
//! lists the score and each rule's `satisfied/subjects`.
//!
//! [`render_png`] (feature `png`) rasterises that SVG with resvg, using a DejaVu Sans font
//! embedded in the binary (no system fonts are consulted, so output is the
//! same on every machine). [`render_to_path`] picks the format from the
//! file extension.

use crate::eval::{evaluate, Evaluation};
use crate::relations::Contact;
use crate::resemblance::Likeness;
use crate::rules::RuleSet;
use crate::scene::{Object, Scene};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

#[cfg(feature = "png")]
mod png;
#[cfg(feature = "png")]
pub use png::render_png;

/// How to draw a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Contact mode used when evaluating rules for the overlay.
    pub contact: Contact,
    /// Pixels per length unit (default 1.0). Must be finite and positive;
    /// [`render_svg`] treats any other value as 1.0, the fallible functions
    /// report [`RenderError::Scale`].
    pub scale: f64,
    /// A title written above the table (e.g. the scene's file name).
    pub title: Option<String>,
    /// Positions shown in like-scenes (SPEC §12), drawn faintly under the
    /// layout in each class's colour: a heat map of where each class was
    /// shown.
    pub like: Option<Likeness>,
    /// Objects that moved, each with where it was `(id, x, y)` (a probe
    /// that is an edit of a demonstration): the old place is drawn dashed,
    /// with a line to the object, which is outlined.
    pub moved: Vec<(String, i64, i64)>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            contact: Contact::default(),
            scale: 1.0,
            title: None,
            like: None,
            moved: Vec::new(),
        }
    }
}

/// Why a picture could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The output file's extension names no supported format.
    #[error("unsupported picture format {found}; expected `.svg` or `.png`")]
    UnknownExtension {
        /// The extension found, quoted (e.g. "`.jpg`" or "no extension").
        found: String,
    },
    /// The scale is not a finite positive number.
    #[error("scale {0} is invalid; expected a finite number greater than 0")]
    Scale(f64),
    /// The picture would be too large to rasterise.
    #[error("picture of {width}x{height} pixels is too large for PNG (at most {max} pixels); lower the scale")]
    TooLarge {
        /// Width in pixels.
        width: u64,
        /// Height in pixels.
        height: u64,
        /// The largest pixel count accepted.
        max: u64,
    },
    /// resvg could not read the generated SVG (a bug).
    #[error("internal SVG error: {0}")]
    Svg(String),
    /// PNG encoding failed.
    #[error("PNG encoding failed: {0}")]
    Png(String),
    /// PNG was asked for in a build without the `png` feature.
    #[error("PNG output needs rccpack built with the `png` feature; use `.svg`")]
    PngUnavailable,
    /// Writing the file failed.
    #[error("cannot write picture: {0}")]
    Io(#[from] std::io::Error),
}

const MARGIN: f64 = 24.0;
const HEADER: f64 = 34.0;
const GAP: f64 = 28.0;
const FONT: &str = "DejaVu Sans, sans-serif";
/// Rough advance width of DejaVu Sans per font-size unit (a little generous).
const CHAR_W: f64 = 0.62;

const FIXED_FILL: &str = "#4a4a4a";
const PALETTE: [&str; 8] = [
    "#f0ad4e", "#8e6cc0", "#1fa2a0", "#e07b39", "#c2577e", "#7f8c3a", "#5d7ea8", "#b08d57",
];

fn class_colour(class: &str) -> Option<&'static str> {
    match class.to_ascii_lowercase().as_str() {
        "r" | "red" => Some("#d9534f"),
        "g" | "green" => Some("#5cb85c"),
        "b" | "blue" => Some("#428bca"),
        _ => None,
    }
}

/// Colours per class: the R/G/B names first, others from the palette by
/// order of first appearance among movable objects. A named colour goes to
/// the first class that names it only, so `R`, `r` and `red` (three
/// classes) are drawn in three colours. The studio uses the same colours.
pub fn class_colours(scene: &Scene) -> HashMap<String, &'static str> {
    let mut out: HashMap<String, &'static str> = HashMap::new();
    let mut next = 0;
    for o in scene.objects.iter().filter(|o| !o.fixed) {
        if out.contains_key(&o.class) {
            continue;
        }
        let c = class_colour(&o.class)
            .filter(|named| !out.values().any(|c| c == named))
            .unwrap_or_else(|| {
                let c = PALETTE[next % PALETTE.len()];
                next += 1;
                c
            });
        out.insert(o.class.clone(), c);
    }
    out
}

fn colours(scene: &Scene) -> HashMap<String, &'static str> {
    class_colours(scene)
}

fn rgb(hex: &str) -> (f64, f64, f64) {
    let v = u32::from_str_radix(hex.trim_start_matches('#'), 16).unwrap_or(0);
    (
        ((v >> 16) & 0xff) as f64,
        ((v >> 8) & 0xff) as f64,
        (v & 0xff) as f64,
    )
}

fn darker(hex: &str) -> String {
    let (r, g, b) = rgb(hex);
    format!(
        "#{:02x}{:02x}{:02x}",
        (r * 0.7) as u8,
        (g * 0.7) as u8,
        (b * 0.7) as u8
    )
}

/// White or near-black, whichever reads better on `hex`.
fn text_on(hex: &str) -> &'static str {
    let (r, g, b) = rgb(hex);
    if 0.299 * r + 0.587 * g + 0.114 * b > 165.0 {
        "#222222"
    } else {
        "#ffffff"
    }
}

/// Escape text for XML content and attribute values.
fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // What XML 1.0 does not allow at all (control characters, the
            // non-characters U+FFFE and U+FFFF) is shown as U+FFFD.
            c if (c as u32) < 0x20 && c != '\t' && c != '\n' => out.push('\u{fffd}'),
            '\u{fffe}' | '\u{ffff}' => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
    out
}

/// A number for SVG: at most two decimals, no trailing zeros.
fn n(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

fn text_width(s: &str, size: f64) -> f64 {
    s.chars().count() as f64 * size * CHAR_W
}

/// `s` cut to at most `max` characters, with an ellipsis when cut.
fn truncate(s: &str, max: usize) -> String {
    if s.chars().count() <= max {
        s.to_string()
    } else {
        let mut t: String = s.chars().take(max.saturating_sub(1)).collect();
        t.push('…');
        t
    }
}

fn effective_scale(s: f64) -> f64 {
    if s.is_finite() && s > 0.0 {
        s
    } else {
        1.0
    }
}

/// Draw one object as `<g>` with a `class="obj"` rect and, when it fits, a
/// centred label (rotated for tall thin objects).
fn draw_object(out: &mut String, o: &Object, rect: (f64, f64, f64, f64), fill: &str, ghost: bool) {
    let (x, y, w, h) = rect;
    let kind = if o.fixed { "fixed" } else { "movable" };
    let opacity = if ghost { " opacity=\"0.6\"" } else { "" };
    let _ = write!(
        out,
        "<g class=\"object {kind}\" data-id=\"{id}\"{opacity}><title>{id} ({class})</title>\
         <rect class=\"obj\" x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"{h}\" fill=\"{fill}\" \
         stroke=\"{stroke}\" stroke-width=\"1\"/>",
        id = esc(&o.id),
        class = esc(&o.class),
        x = n(x),
        y = n(y),
        w = n(w),
        h = n(h),
        stroke = darker(fill),
    );
    let len = o.id.chars().count().max(1) as f64;
    let flat = (h * 0.55).min(w * 0.88 / (CHAR_W * len));
    let upright = (w * 0.55).min(h * 0.88 / (CHAR_W * len));
    let (size, rotate) = if h > 1.5 * w && upright > flat * 1.2 {
        (upright.min(16.0), true)
    } else {
        (flat.min(16.0), false)
    };
    if size >= 6.0 {
        let (cx, cy) = (x + w / 2.0, y + h / 2.0);
        let transform = if rotate {
            format!(" transform=\"rotate(-90 {} {})\"", n(cx), n(cy))
        } else {
            String::new()
        };
        let _ = write!(
            out,
            "<text x=\"{}\" y=\"{}\" font-size=\"{}\" text-anchor=\"middle\" fill=\"{}\"{transform}>{}</text>",
            n(cx),
            n(cy + size * 0.36),
            n(size),
            text_on(fill),
            esc(&o.id)
        );
    }
    out.push_str("</g>\n");
}

/// One legend line: `(x, y, size, bold, fill, anchor, text)` collected before
/// the column's width is known.
struct Line {
    dy: f64,
    parts: Vec<Part>,
}

enum Part {
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
fn text(dx: f64, size: f64, bold: bool, fill: &'static str, end: bool, t: String) -> Part {
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
fn rule_lines(ev: &Evaluation) -> (Vec<Line>, HashMap<&str, bool>) {
    let mut lines = Vec::new();
    let mut hard_of: HashMap<&str, bool> = HashMap::new();
    let any_soft = ev.rules.iter().any(|r| !r.hard);
    lines.push(Line {
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
    });
    let mut sub = format!(
        "weight {} of {}",
        n(ev.satisfied_weight),
        n(ev.total_weight)
    );
    if ev.rules.iter().any(|r| r.hard) {
        let _ = write!(sub, " · hard violations {}", ev.hard_violations);
    }
    lines.push(Line {
        dy: 17.0,
        parts: vec![text(0.0, 11.0, false, "#666666", false, sub)],
    });
    lines.push(Line {
        dy: 26.0,
        parts: vec![text(0.0, 13.0, true, "#333333", false, "rules".into())],
    });
    for r in &ev.rules {
        for v in &r.violators {
            let hard = hard_of.entry(v.as_str()).or_insert(false);
            *hard |= r.hard;
        }
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
    lines.push(Line {
        dy: 10.0,
        parts: vec![],
    });
    (lines, hard_of)
}

/// The legend's class key: one line per class (and colour), with counts.
fn class_lines(scene: &Scene, fill_of: &dyn Fn(&Object) -> &'static str) -> Vec<Line> {
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
fn legend_width(lines: &[Line]) -> f64 {
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

/// The colour of moved-object marks.
const MOVED_STROKE: &str = "#1f5fbf";

/// Render `scene` as an SVG document (see the module docs for what is drawn).
///
/// With `rules`, the scene is evaluated under `opts.contact`; objects that
/// break any rule get an outline marked `class="violator"` and the legend
/// lists every rule with `satisfied/subjects`.
pub fn render_svg(scene: &Scene, rules: Option<&RuleSet>, opts: &RenderOptions) -> String {
    let s = effective_scale(opts.scale);
    let sp = scene.space;
    let tw = sp.width as f64 * s;
    let th = sp.height as f64 * s;
    let tx = MARGIN;
    let ty = HEADER;
    let colours = colours(scene);
    let fill_of = |o: &Object| -> &'static str {
        if o.fixed {
            FIXED_FILL
        } else {
            colours.get(&o.class).copied().unwrap_or(PALETTE[0])
        }
    };
    let eval: Option<Evaluation> = rules.map(|r| evaluate(scene, r, opts.contact));

    // ---- legend lines (measured first) -------------------------------------
    let mut lines: Vec<Line> = Vec::new();
    let mut hard_of: HashMap<&str, bool> = HashMap::new();
    if let Some(ev) = &eval {
        (lines, hard_of) = rule_lines(ev);
    }
    lines.extend(class_lines(scene, &fill_of));
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
    let lw = legend_width(&lines);
    let lx = tx + tw + GAP;
    let legend_h: f64 = lines.iter().map(|l| l.dy).sum();

    // ---- tray of unplaced objects ------------------------------------------
    let unplaced: Vec<&Object> = scene.objects.iter().filter(|o| !o.is_placed()).collect();
    let tray_w = tw.max(160.0);
    let mut tray_items = Vec::new();
    let mut tray_h = 0.0;
    if !unplaced.is_empty() {
        let pad = 10.0;
        let (mut cx, mut cy, mut row_h) = (pad, 26.0, 0.0f64);
        for o in &unplaced {
            let (w, h) = (o.width as f64 * s, o.height as f64 * s);
            if cx > pad && cx + w > tray_w - pad {
                cx = pad;
                cy += row_h + pad;
                row_h = 0.0;
            }
            tray_items.push((*o, cx, cy, w, h));
            cx += w + pad;
            row_h = row_h.max(h);
        }
        tray_h = cy + row_h + pad;
    }
    let tray_y = ty + th + 18.0;

    let width = (lx + lw + MARGIN).ceil();
    let mut bottom = ty + th;
    if tray_h > 0.0 {
        bottom = tray_y + tray_h;
    }
    let height = (bottom.max(ty + legend_h) + MARGIN).ceil();

    // ---- write -------------------------------------------------------------
    let mut out = String::new();
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"{FONT}\">",
        w = n(width),
        h = n(height)
    );
    if let Some(t) = &opts.title {
        let _ = writeln!(out, "<title>{}</title>", esc(t));
    }
    out.push_str("<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");
    // Header: title and north marker.
    let _ = writeln!(
        out,
        "<text class=\"north\" x=\"{}\" y=\"{}\" font-size=\"13\" font-weight=\"bold\" text-anchor=\"end\" fill=\"#555555\">N ↑</text>",
        n(tx + tw),
        n(ty - 10.0)
    );
    if let Some(t) = &opts.title {
        let room = ((tw + GAP + lw - 40.0) / (14.0 * 0.66)).max(4.0) as usize;
        let _ = writeln!(
            out,
            "<text class=\"title\" x=\"{}\" y=\"{}\" font-size=\"14\" font-weight=\"bold\" fill=\"#222222\">{}</text>",
            n(tx),
            n(ty - 10.0),
            esc(&truncate(t, room))
        );
    }
    // Table and grid.
    let _ = writeln!(
        out,
        "<rect class=\"table\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#f5f6f8\" stroke=\"#b9bfc8\" stroke-width=\"1\"/>",
        n(tx),
        n(ty),
        n(tw),
        n(th)
    );
    let g = scene.grid.max(1);
    let (nx, ny) = (sp.width / g, sp.height / g);
    if nx + ny <= 200 && g as f64 * s >= 3.0 {
        let mut d = String::new();
        for i in 1..=nx {
            let x = tx + (i * g) as f64 * s;
            if x < tx + tw - 0.01 {
                let _ = write!(d, "M{} {}V{}", n(x), n(ty), n(ty + th));
            }
        }
        for j in 1..=ny {
            let y = ty + th - (j * g) as f64 * s;
            if y > ty + 0.01 {
                let _ = write!(d, "M{} {}H{}", n(tx), n(y), n(tx + tw));
            }
        }
        if !d.is_empty() {
            let _ = writeln!(
                out,
                "<path class=\"grid\" d=\"{d}\" stroke=\"#e3e6eb\" stroke-width=\"0.6\" fill=\"none\"/>"
            );
        }
    }
    // Placed objects.
    let to_screen = |o: &Object| -> Option<(f64, f64, f64, f64)> {
        let r = o.rect()?;
        let x = tx + (r.x - sp.x) as f64 * s;
        let y = ty + (sp.y2_f() - r.y2() as f64) * s;
        Some((x, y, r.w as f64 * s, r.h as f64 * s))
    };
    // Where the like-scenes put each class: faint, stacked (more often
    // shown is darker), under everything else.
    if let Some(like) = &opts.like {
        out.push_str("<g class=\"like\">\n");
        for (class, w, h, positions) in like.shown() {
            let fill = colours
                .get(class)
                .copied()
                .or_else(|| class_colour(class))
                .unwrap_or(PALETTE[0]);
            for &(x, y) in positions {
                let probe = Object {
                    id: String::new(),
                    class: class.to_string(),
                    x: Some(x),
                    y: Some(y),
                    width: w,
                    height: h,
                    fixed: false,
                };
                if let Some((x, y, w, h)) = to_screen(&probe) {
                    let _ = writeln!(
                        out,
                        "<rect class=\"shown\" data-class=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{fill}\" fill-opacity=\"0.16\"/>",
                        esc(class),
                        n(x),
                        n(y),
                        n(w),
                        n(h)
                    );
                }
            }
        }
        out.push_str("</g>\n");
    }
    out.push_str("<g class=\"objects\">\n");
    for o in &scene.objects {
        if let Some((x, y, w, h)) = to_screen(o) {
            draw_object(&mut out, o, (x, y, w, h), fill_of(o), false);
        }
    }
    out.push_str("</g>\n");
    // Violator outlines, on top of every object.
    if !hard_of.is_empty() {
        out.push_str("<g class=\"violations\">\n");
        for o in &scene.objects {
            let (Some(&hard), Some((x, y, w, h))) = (hard_of.get(o.id.as_str()), to_screen(o))
            else {
                continue;
            };
            // Just outside the object, so its label stays readable.
            let (x, y, w, h) = (x - 2.0, y - 2.0, w + 4.0, h + 4.0);
            let colour = if hard { "#c0392b" } else { "#ff8c00" };
            let _ = writeln!(
                out,
                "<g class=\"violator\" data-id=\"{id}\"><rect x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"3\"/>\
                 <rect x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"#111111\" stroke-width=\"3\" stroke-dasharray=\"4 4\"/></g>",
                id = esc(&o.id),
                x = n(x),
                y = n(y),
                w = n(w),
                h = n(h)
            );
        }
        out.push_str("</g>\n");
    }
    // Moved objects: where each was (dashed), a line to where it is, and
    // an outline.
    if !opts.moved.is_empty() {
        out.push_str("<g class=\"moved\">\n");
        for (id, ox, oy) in &opts.moved {
            let Some(o) = scene.objects.iter().find(|o| &o.id == id) else {
                continue;
            };
            let was = Object {
                x: Some(*ox),
                y: Some(*oy),
                ..o.clone()
            };
            let (Some((x0, y0, w, h)), Some((x1, y1, _, _))) = (to_screen(&was), to_screen(o))
            else {
                continue;
            };
            let _ = writeln!(
                out,
                "<g class=\"move\" data-id=\"{id}\"><rect class=\"was\" x=\"{x0}\" y=\"{y0}\" width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"{MOVED_STROKE}\" stroke-width=\"2\" stroke-dasharray=\"5 3\"/>\
                 <line x1=\"{cx0}\" y1=\"{cy0}\" x2=\"{cx1}\" y2=\"{cy1}\" stroke=\"{MOVED_STROKE}\" stroke-width=\"1.5\" stroke-dasharray=\"2 3\"/>\
                 <rect class=\"now\" x=\"{x1o}\" y=\"{y1o}\" width=\"{wo}\" height=\"{ho}\" fill=\"none\" stroke=\"{MOVED_STROKE}\" stroke-width=\"2.5\"/></g>",
                id = esc(id),
                x0 = n(x0),
                y0 = n(y0),
                w = n(w),
                h = n(h),
                cx0 = n(x0 + w / 2.0),
                cy0 = n(y0 + h / 2.0),
                cx1 = n(x1 + w / 2.0),
                cy1 = n(y1 + h / 2.0),
                x1o = n(x1 - 4.0),
                y1o = n(y1 - 4.0),
                wo = n(w + 8.0),
                ho = n(h + 8.0),
            );
        }
        out.push_str("</g>\n");
    }
    // Tray.
    if !tray_items.is_empty() {
        let _ = writeln!(
            out,
            "<g class=\"tray\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"4\" fill=\"#fafafa\" stroke=\"#c5cad2\" stroke-dasharray=\"5 4\"/>\
             <text x=\"{}\" y=\"{}\" font-size=\"12\" fill=\"#666666\">unplaced ({})</text>",
            n(tx),
            n(tray_y),
            n(tray_w),
            n(tray_h),
            n(tx + 10.0),
            n(tray_y + 17.0),
            tray_items.len()
        );
        for (o, x, y, w, h) in &tray_items {
            draw_object(&mut out, o, (tx + x, tray_y + y, *w, *h), fill_of(o), true);
        }
        out.push_str("</g>\n");
    }
    // Legend.
    if !lines.is_empty() {
        out.push_str("<g class=\"legend\">\n");
        let mut y = ty;
        for l in &lines {
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
    out.push_str("</svg>\n");
    out
}

trait SpaceExt {
    fn y2_f(&self) -> f64;
}

impl SpaceExt for crate::scene::Space {
    fn y2_f(&self) -> f64 {
        (self.y + self.height) as f64
    }
}

/// Render to `path`, choosing the format by its extension (`.svg` or `.png`,
/// case-insensitive). Any other extension is an error naming it.
pub fn render_to_path(
    scene: &Scene,
    rules: Option<&RuleSet>,
    opts: &RenderOptions,
    path: &Path,
) -> Result<(), RenderError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("svg") => {
            if !(opts.scale.is_finite() && opts.scale > 0.0) {
                return Err(RenderError::Scale(opts.scale));
            }
            crate::fsutil::atomic_write(path, render_svg(scene, rules, opts))?;
        }
        #[cfg(feature = "png")]
        Some("png") => crate::fsutil::atomic_write(path, render_png(scene, rules, opts)?)?,
        #[cfg(not(feature = "png"))]
        Some("png") => return Err(RenderError::PngUnavailable),
        Some(other) => {
            return Err(RenderError::UnknownExtension {
                found: format!("`.{other}`"),
            })
        }
        None => {
            return Err(RenderError::UnknownExtension {
                found: "(no extension)".into(),
            })
        }
    }
    Ok(())
}

#[cfg(all(test, not(feature = "png")))]
mod core_tests {
    use super::*;

    /// Without the `png` feature a `.png` path is a clear error, not a panic.
    #[test]
    fn png_needs_the_feature() {
        let scene = Scene::from_json(r#"{"space": {"width": 10, "height": 10}, "objects": []}"#)
            .expect("scene");
        let path = std::env::temp_dir().join("rccpack-core-no-png.png");
        let e = render_to_path(&scene, None, &RenderOptions::default(), &path).unwrap_err();
        assert!(matches!(e, RenderError::PngUnavailable), "{e}");
        assert!(!path.exists());
    }
}
