//! The picture's style: sizes, fonts, colours per class and the small
//! text helpers (escaping, number format, width estimate).

use crate::scene::Scene;
use std::collections::HashMap;

pub(super) const MARGIN: f64 = 24.0;
pub(super) const HEADER: f64 = 34.0;
pub(super) const GAP: f64 = 28.0;
pub(super) const FONT: &str = "DejaVu Sans, sans-serif";
/// Rough advance width of DejaVu Sans per font-size unit (a little generous).
pub(super) const CHAR_W: f64 = 0.62;

pub(super) const FIXED_FILL: &str = "#4a4a4a";
pub(super) const PALETTE: [&str; 8] = [
    "#f0ad4e", "#8e6cc0", "#1fa2a0", "#e07b39", "#c2577e", "#7f8c3a", "#5d7ea8", "#b08d57",
];

pub(super) fn class_colour(class: &str) -> Option<&'static str> {
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

pub(super) fn colours(scene: &Scene) -> HashMap<String, &'static str> {
    class_colours(scene)
}

pub(super) fn rgb(hex: &str) -> (f64, f64, f64) {
    let v = u32::from_str_radix(hex.trim_start_matches('#'), 16).unwrap_or(0);
    (
        ((v >> 16) & 0xff) as f64,
        ((v >> 8) & 0xff) as f64,
        (v & 0xff) as f64,
    )
}

pub(super) fn darker(hex: &str) -> String {
    let (r, g, b) = rgb(hex);
    format!(
        "#{:02x}{:02x}{:02x}",
        (r * 0.7) as u8,
        (g * 0.7) as u8,
        (b * 0.7) as u8
    )
}

/// White or near-black, whichever reads better on `hex`.
pub(super) fn text_on(hex: &str) -> &'static str {
    let (r, g, b) = rgb(hex);
    if 0.299 * r + 0.587 * g + 0.114 * b > 165.0 {
        "#222222"
    } else {
        "#ffffff"
    }
}

/// Escape text for XML content and attribute values.
pub(super) fn esc(s: &str) -> String {
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
pub(super) fn n(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

pub(super) fn text_width(s: &str, size: f64) -> f64 {
    s.chars().count() as f64 * size * CHAR_W
}

/// `s` cut to at most `max` characters, with an ellipsis when cut.
pub(super) fn truncate(s: &str, max: usize) -> String {
    if s.chars().count() <= max {
        s.to_string()
    } else {
        let mut t: String = s.chars().take(max.saturating_sub(1)).collect();
        t.push('…');
        t
    }
}

pub(super) fn effective_scale(s: f64) -> f64 {
    if s.is_finite() && s > 0.0 {
        s
    } else {
        1.0
    }
}
