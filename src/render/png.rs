//! PNG through resvg (feature `png`): the SVG of [`super::render_svg`]
//! rasterised with a DejaVu Sans font embedded in the binary, so the pixels
//! are the same on every machine.

use super::{render_svg, RenderError, RenderOptions};
use crate::rules::RuleSet;
use crate::scene::Scene;
use std::sync::{Arc, OnceLock};

/// Largest PNG accepted, in pixels (≈ 256 MiB of RGBA).
const MAX_PIXELS: u64 = 64 * 1024 * 1024;
/// Largest side of a PNG, in pixels.
const MAX_SIDE: u64 = 32_000;

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
/// pixel per SVG unit, with the embedded DejaVu Sans font.
pub fn render_png(
    scene: &Scene,
    rules: Option<&RuleSet>,
    opts: &RenderOptions,
) -> Result<Vec<u8>, RenderError> {
    if !(opts.scale.is_finite() && opts.scale > 0.0) {
        return Err(RenderError::Scale(opts.scale));
    }
    let svg = render_svg(scene, rules, opts);
    svg_to_png(&svg)
}

fn svg_to_png(svg: &str) -> Result<Vec<u8>, RenderError> {
    use resvg::{tiny_skia, usvg};
    let mut opt = usvg::Options {
        font_family: "DejaVu Sans".into(),
        ..usvg::Options::default()
    };
    opt.fontdb = fontdb();
    let tree = usvg::Tree::from_str(svg, &opt).map_err(|e| RenderError::Svg(e.to_string()))?;
    let size = tree.size();
    let (w, h) = (size.width().ceil() as u64, size.height().ceil() as u64);
    if w > MAX_SIDE || h > MAX_SIDE || w * h > MAX_PIXELS {
        return Err(RenderError::TooLarge {
            width: w,
            height: h,
            max: MAX_PIXELS,
        });
    }
    let mut pixmap = tiny_skia::Pixmap::new(w as u32, h as u32).ok_or(RenderError::TooLarge {
        width: w,
        height: h,
        max: MAX_PIXELS,
    })?;
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    pixmap
        .encode_png()
        .map_err(|e| RenderError::Png(e.to_string()))
}
