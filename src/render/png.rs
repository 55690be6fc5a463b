//! PNG through resvg (feature `png`): the SVG of [`super::render_svg`]
//! rasterised with a DejaVu Sans font embedded in the binary, so the pixels
//! are the same on every machine.

use super::{render_svg, RenderError, RenderOptions};
use crate::rules::RuleSet;
use crate::scene::Scene;
use std::sync::{Arc, OnceLock};

/// Largest PNG accepted, in pixels (≈ 256 MiB of RGBA).
pub const MAX_PNG_PIXELS: u64 = 64 * 1024 * 1024;
/// Largest side of a PNG, in pixels.
pub const MAX_PNG_SIDE: u64 = 32_000;

/// The font database shared by every PNG: DejaVu Sans (regular and bold),
/// embedded in the binary, mapped to every generic family.
fn fontdb() -> Arc<resvg::usvg::fontdb::Database> {
    static DB: OnceLock<Arc<resvg::usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        use resvg::usvg::fontdb::{Database, Source};
        let mut db = Database::new();
        db.load_font_source(Source::Binary(Arc::new(dejavu::sans::regular())));
        db.load_font_source(Source::Binary(Arc::new(dejavu::sans::bold())));
        db.set_sans_serif_family("DejaVu Sans");
        db.set_serif_family("DejaVu Sans");
        db.set_monospace_family("DejaVu Sans");
        db.set_cursive_family("DejaVu Sans");
        db.set_fantasy_family("DejaVu Sans");
        Arc::new(db)
    })
    .clone()
}

/// Render `scene` as PNG bytes: [`render_svg`] rasterised by resvg, one
/// pixel per SVG unit, with the embedded DejaVu Sans font. A picture past
/// the PNG limits (a side past 32 000 pixels, or more than 64 Mi pixels
/// in all) is [`RenderError::TooLarge`], naming the limit hit.
pub fn render_png(
    scene: &Scene,
    rules: Option<&RuleSet>,
    opts: &RenderOptions,
) -> Result<Vec<u8>, RenderError> {
    if !(opts.scale.is_finite() && opts.scale > 0.0) {
        return Err(RenderError::Scale(opts.scale));
    }
    let (tree, w, h) = tree(&render_svg(scene, rules, opts))?;
    if let Some(limit) = over_limit(w, h) {
        return Err(RenderError::TooLarge {
            width: w,
            height: h,
            limit,
        });
    }
    rasterise(&tree, w, h, 1.0)
}

/// [`render_png`], scaled down to fit the PNG limits when the picture at
/// `opts.scale` would pass them: drawn again at a smaller scale (the
/// legend and labels keep their size), and shrunk as a whole when that is
/// not enough. Returns the bytes and the scale the table was drawn at
/// (`opts.scale` when it fitted).
pub fn render_png_to_fit(
    scene: &Scene,
    rules: Option<&RuleSet>,
    opts: &RenderOptions,
) -> Result<(Vec<u8>, f64), RenderError> {
    if !(opts.scale.is_finite() && opts.scale > 0.0) {
        return Err(RenderError::Scale(opts.scale));
    }
    let mut o = opts.clone();
    let mut last = None;
    for _ in 0..6 {
        let (tree, w, h) = tree(&render_svg(scene, rules, &o))?;
        if over_limit(w, h).is_none() {
            return Ok((rasterise(&tree, w, h, 1.0)?, o.scale));
        }
        let f = fit_factor(w, h);
        last = Some((tree, w, h, f));
        o.scale *= f;
        if !(o.scale.is_finite() && o.scale > 0.0) {
            break;
        }
    }
    // Fixed-size parts (the legend, the tray) alone past a limit: shrink
    // the last picture as a whole.
    let (tree, w, h, f) = last.expect("the loop ran at least once");
    let (fw, fh) = ((w as f64 * f).floor() as u64, (h as f64 * f).floor() as u64);
    Ok((rasterise(&tree, fw.max(1), fh.max(1), f)?, o.scale))
}

/// The picture's tree and its size in pixels.
fn tree(svg: &str) -> Result<(resvg::usvg::Tree, u64, u64), RenderError> {
    use resvg::usvg;
    let mut opt = usvg::Options {
        font_family: "DejaVu Sans".into(),
        ..usvg::Options::default()
    };
    opt.fontdb = fontdb();
    let tree = usvg::Tree::from_str(svg, &opt).map_err(|e| RenderError::Svg(e.to_string()))?;
    let size = tree.size();
    let (w, h) = (size.width().ceil() as u64, size.height().ceil() as u64);
    Ok((tree, w, h))
}

/// The PNG limit a `w`×`h` picture passes, worded for an error; `None`
/// when it fits. A side is checked first: the message names the limit
/// actually hit.
fn over_limit(w: u64, h: u64) -> Option<String> {
    if w > MAX_PNG_SIDE || h > MAX_PNG_SIDE {
        Some(format!("at most {MAX_PNG_SIDE} pixels a side"))
    } else if w.saturating_mul(h) > MAX_PNG_PIXELS {
        Some(format!("at most {MAX_PNG_PIXELS} pixels in all"))
    } else {
        None
    }
}

/// The factor (below 1) that brings a `w`×`h` picture within both limits.
fn fit_factor(w: u64, h: u64) -> f64 {
    let side = MAX_PNG_SIDE as f64 / w.max(h) as f64;
    let all = (MAX_PNG_PIXELS as f64 / (w as f64 * h as f64)).sqrt();
    // A little under, so that rounding up a side cannot pass it again.
    side.min(all).min(1.0) * 0.995
}

/// `tree` drawn into a `w`×`h` pixmap, scaled by `f`.
fn rasterise(tree: &resvg::usvg::Tree, w: u64, h: u64, f: f64) -> Result<Vec<u8>, RenderError> {
    use resvg::tiny_skia;
    let too_large = || RenderError::TooLarge {
        width: w,
        height: h,
        limit: over_limit(w, h).unwrap_or_else(|| "a size the rasteriser accepts".into()),
    };
    let (pw, ph) = (
        u32::try_from(w).map_err(|_| too_large())?,
        u32::try_from(h).map_err(|_| too_large())?,
    );
    let mut pixmap = tiny_skia::Pixmap::new(pw, ph).ok_or_else(too_large)?;
    resvg::render(
        tree,
        tiny_skia::Transform::from_scale(f as f32, f as f32),
        &mut pixmap.as_mut(),
    );
    pixmap
        .encode_png()
        .map_err(|e| RenderError::Png(e.to_string()))
}
