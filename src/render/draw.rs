//! Drawing the picture: its frame (where the table, the tray and the
//! legend go), the header, the table with its grid, the shaded positions
//! of the resemblance target, the objects, the violators' outlines, the
//! moved blocks and the tray of unplaced objects.

use super::style::{
    class_colour, darker, esc, n, text_on, truncate, CHAR_W, FONT, GAP, HEADER, MARGIN, PALETTE,
};
use super::RenderOptions;
use crate::resemblance::ResemblanceTarget;
use crate::scene::{Object, Scene, Space};
use std::collections::HashMap;
use std::fmt::Write as _;

/// An unplaced object in the tray: the object and its box `(x, y, w, h)`
/// relative to the tray's corner.
pub(super) type TrayItem<'s> = (&'s Object, f64, f64, f64, f64);

/// Where everything goes, in pixels: the table's box, the legend's column,
/// the tray below the table and the picture's size.
pub(super) struct Frame {
    /// Pixels per length unit.
    pub(super) s: f64,
    /// The scene's space.
    pub(super) space: Space,
    /// The table's left and top edges, width and height.
    pub(super) tx: f64,
    pub(super) ty: f64,
    pub(super) tw: f64,
    pub(super) th: f64,
    /// The legend's left edge and width.
    pub(super) lx: f64,
    pub(super) lw: f64,
    /// The tray's top edge, width and height (0: no tray).
    pub(super) tray_y: f64,
    pub(super) tray_w: f64,
    pub(super) tray_h: f64,
    /// The picture's width and height.
    pub(super) width: f64,
    pub(super) height: f64,
}

impl Frame {
    /// The frame of a `space` drawn at scale `s` beside a legend of width
    /// `lw` and height `legend_h`, with a tray of height `tray_h`.
    pub(super) fn new(space: Space, s: f64, lw: f64, legend_h: f64, tray_h: f64) -> Frame {
        let tw = space.width as f64 * s;
        let th = space.height as f64 * s;
        let tx = MARGIN;
        let ty = HEADER;
        let lx = tx + tw + GAP;
        let tray_y = ty + th + 18.0;
        let width = (lx + lw + MARGIN).ceil();
        let mut bottom = ty + th;
        if tray_h > 0.0 {
            bottom = tray_y + tray_h;
        }
        let height = (bottom.max(ty + legend_h) + MARGIN).ceil();
        Frame {
            s,
            space,
            tx,
            ty,
            tw,
            th,
            lx,
            lw,
            tray_y,
            tray_w: tray_width(space, s),
            tray_h,
            width,
            height,
        }
    }

    /// A placed object's box on the picture (north up).
    pub(super) fn to_screen(&self, o: &Object) -> Option<(f64, f64, f64, f64)> {
        let (sp, s) = (self.space, self.s);
        let r = o.rect()?;
        let x = self.tx + (r.x - sp.x) as f64 * s;
        let y = self.ty + (sp.y2_f() - r.y2() as f64) * s;
        Some((x, y, r.w as f64 * s, r.h as f64 * s))
    }
}

/// The tray's width for a space drawn at scale `s`.
fn tray_width(space: Space, s: f64) -> f64 {
    (space.width as f64 * s).max(160.0)
}

/// The unplaced objects laid out in rows across the tray, and the tray's
/// height (0 when every object is placed).
pub(super) fn tray_layout(scene: &Scene, s: f64) -> (Vec<TrayItem<'_>>, f64) {
    let unplaced: Vec<&Object> = scene.objects.iter().filter(|o| !o.is_placed()).collect();
    let tray_w = tray_width(scene.space, s);
    let mut tray_items = Vec::new();
    let mut tray_h = 0.0;
    if !unplaced.is_empty() {
        let pad = 10.0;
        let (mut cx, mut cy, mut row_h) = (pad, 26.0, 0.0f64);
        for o in &unplaced {
            let (fw, fh) = o.footprint();
            let (w, h) = (fw as f64 * s, fh as f64 * s);
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
    (tray_items, tray_h)
}

/// The `<svg>` element, the background, the title and the north marker.
pub(super) fn write_header(out: &mut String, f: &Frame, opts: &RenderOptions) {
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"{FONT}\">",
        w = n(f.width),
        h = n(f.height)
    );
    if let Some(t) = &opts.title {
        let _ = writeln!(out, "<title>{}</title>", esc(t));
    }
    out.push_str("<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");
    // Header: title and north marker.
    let _ = writeln!(
        out,
        "<text class=\"north\" x=\"{}\" y=\"{}\" font-size=\"13\" font-weight=\"bold\" text-anchor=\"end\" fill=\"#555555\">N ↑</text>",
        n(f.tx + f.tw),
        n(f.ty - 10.0)
    );
    if let Some(t) = &opts.title {
        let room = ((f.tw + GAP + f.lw - 40.0) / (14.0 * 0.66)).max(4.0) as usize;
        let _ = writeln!(
            out,
            "<text class=\"title\" x=\"{}\" y=\"{}\" font-size=\"14\" font-weight=\"bold\" fill=\"#222222\">{}</text>",
            n(f.tx),
            n(f.ty - 10.0),
            esc(&truncate(t, room))
        );
    }
}

/// The table and, when they are not too dense, its grid lines.
pub(super) fn write_table(out: &mut String, f: &Frame, grid: i64) {
    let (sp, s) = (f.space, f.s);
    let (tx, ty, tw, th) = (f.tx, f.ty, f.tw, f.th);
    let _ = writeln!(
        out,
        "<rect class=\"table\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#f5f6f8\" stroke=\"#b9bfc8\" stroke-width=\"1\"/>",
        n(tx),
        n(ty),
        n(tw),
        n(th)
    );
    let g = grid.max(1);
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
}

/// Where the resemblance target puts each class: faint, stacked (more
/// often shown is darker), under everything else.
pub(super) fn write_shown(
    out: &mut String,
    f: &Frame,
    like: &ResemblanceTarget,
    colours: &HashMap<String, &'static str>,
) {
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
                turnable: false,
                turned: false,
            };
            if let Some((x, y, w, h)) = f.to_screen(&probe) {
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

/// Every placed object.
pub(super) fn write_objects(
    out: &mut String,
    f: &Frame,
    scene: &Scene,
    fill_of: &dyn Fn(&Object) -> &'static str,
) {
    out.push_str("<g class=\"objects\">\n");
    for o in &scene.objects {
        if let Some((x, y, w, h)) = f.to_screen(o) {
            draw_object(out, o, (x, y, w, h), fill_of(o), false);
        }
    }
    out.push_str("</g>\n");
}

/// Violator outlines, on top of every object (red for a hard rule
/// broken, orange for a soft one).
pub(super) fn write_violations(
    out: &mut String,
    f: &Frame,
    scene: &Scene,
    hard_of: &HashMap<&str, bool>,
) {
    if hard_of.is_empty() {
        return;
    }
    out.push_str("<g class=\"violations\">\n");
    for o in &scene.objects {
        let (Some(&hard), Some((x, y, w, h))) = (hard_of.get(o.id.as_str()), f.to_screen(o)) else {
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

/// Outlined objects (a suspect's blocks): a thick outline where each is.
pub(super) fn write_outlined(out: &mut String, f: &Frame, scene: &Scene, ids: &[String]) {
    if ids.is_empty() {
        return;
    }
    out.push_str("<g class=\"outlined\">\n");
    for id in ids {
        let Some(o) = scene.objects.iter().find(|o| &o.id == id) else {
            continue;
        };
        let Some((x, y, w, h)) = f.to_screen(o) else {
            continue;
        };
        let _ = writeln!(
            out,
            "<rect class=\"suspect\" data-id=\"{id}\" x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"{MOVED_STROKE}\" stroke-width=\"3\"/>",
            id = esc(id),
            x = n(x - 5.0),
            y = n(y - 5.0),
            w = n(w + 10.0),
            h = n(h + 10.0),
        );
    }
    out.push_str("</g>\n");
}

/// Moved objects: where each was (dashed), a line to where it is, and an
/// outline.
pub(super) fn write_moved(
    out: &mut String,
    f: &Frame,
    scene: &Scene,
    moved: &[(String, i64, i64)],
) {
    if moved.is_empty() {
        return;
    }
    out.push_str("<g class=\"moved\">\n");
    for (id, ox, oy) in moved {
        let Some(o) = scene.objects.iter().find(|o| &o.id == id) else {
            continue;
        };
        let was = Object {
            x: Some(*ox),
            y: Some(*oy),
            ..o.clone()
        };
        let (Some((x0, y0, w, h)), Some((x1, y1, _, _))) = (f.to_screen(&was), f.to_screen(o))
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

/// The tray of unplaced objects below the table.
pub(super) fn write_tray(
    out: &mut String,
    f: &Frame,
    tray_items: &[TrayItem<'_>],
    fill_of: &dyn Fn(&Object) -> &'static str,
) {
    if tray_items.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "<g class=\"tray\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"4\" fill=\"#fafafa\" stroke=\"#c5cad2\" stroke-dasharray=\"5 4\"/>\
         <text x=\"{}\" y=\"{}\" font-size=\"12\" fill=\"#666666\">unplaced ({})</text>",
        n(f.tx),
        n(f.tray_y),
        n(f.tray_w),
        n(f.tray_h),
        n(f.tx + 10.0),
        n(f.tray_y + 17.0),
        tray_items.len()
    );
    for (o, x, y, w, h) in tray_items {
        draw_object(out, o, (f.tx + x, f.tray_y + y, *w, *h), fill_of(o), true);
    }
    out.push_str("</g>\n");
}

/// Draw one object as `<g>` with a `class="obj"` rect and, when it fits, a
/// centred label (rotated for tall thin objects).
fn draw_object(out: &mut String, o: &Object, rect: (f64, f64, f64, f64), fill: &str, ghost: bool) {
    let (x, y, w, h) = rect;
    let kind = if o.fixed { "fixed" } else { "movable" };
    let opacity = if ghost { " opacity=\"0.6\"" } else { "" };
    let _ = write!(
        out,
        "<g class=\"object {kind}{turned}\" data-id=\"{id}\"{opacity}><title>{id} ({class}{turned_title})</title>\
         <rect class=\"obj\" x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"{h}\" fill=\"{fill}\" \
         stroke=\"{stroke}\" stroke-width=\"1\"/>",
        id = esc(&o.id),
        class = esc(&o.class),
        x = n(x),
        y = n(y),
        w = n(w),
        h = n(h),
        stroke = darker(fill),
        turned = if o.turned { " turned" } else { "" },
        turned_title = if o.turned { ", turned" } else { "" },
    );
    if o.turned {
        // A turned object's mark: a small quarter-turn arrow in its
        // north-east corner (a curve and its head), in the outline's colour.
        let r = (w.min(h) * 0.3).clamp(2.0, 9.0);
        let (ax, ay) = (x + w - r - 1.5, y + 1.5);
        let _ = write!(
            out,
            "<path class=\"turn-mark\" d=\"M {x0} {y0} A {r} {r} 0 0 1 {x1} {y1} l {hx} 0 l 0 {hy}\" \
             fill=\"none\" stroke=\"{stroke}\" stroke-width=\"1.6\"/>",
            x0 = n(ax),
            y0 = n(ay),
            r = n(r),
            x1 = n(ax + r),
            y1 = n(ay + r),
            hx = n(-r * 0.5),
            hy = n(-r * 0.5),
            stroke = darker(fill),
        );
    }
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

/// The colour of moved-object marks.
pub(super) const MOVED_STROKE: &str = "#1f5fbf";

trait SpaceExt {
    fn y2_f(&self) -> f64;
}

impl SpaceExt for crate::scene::Space {
    fn y2_f(&self) -> f64 {
        (self.y + self.height) as f64
    }
}
