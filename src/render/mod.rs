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
use crate::resemblance::ResemblanceTarget;
use crate::rules::RuleSet;
use crate::scene::{Object, Scene};
use std::path::Path;

mod draw;
mod legend;
#[cfg(feature = "png")]
mod png;
mod style;

#[cfg(feature = "png")]
pub use png::{render_png, render_png_to_fit, MAX_PNG_PIXELS, MAX_PNG_SIDE};
pub use style::class_colours;

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
    /// Positions shown in like-scenes (docs/guide.md#layouts-like-the-demonstrations), drawn faintly under the
    /// layout in each class's colour: a heat map of where each class was
    /// shown.
    pub like: Option<ResemblanceTarget>,
    /// Objects that moved, each with where it was `(id, x, y)` (a probe
    /// that is an edit of a demonstration): the old place is drawn dashed,
    /// with a line to the object, which is outlined.
    pub moved: Vec<(String, i64, i64)>,
    /// Objects outlined where they are (the blocks of a demonstration that
    /// look like a slip, docs/guide.md#slips).
    pub outlined: Vec<String>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            contact: Contact::default(),
            scale: 1.0,
            title: None,
            like: None,
            moved: Vec::new(),
            outlined: Vec::new(),
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
    #[error("picture of {width}x{height} pixels is too large for PNG ({limit}); lower the scale")]
    TooLarge {
        /// Width in pixels.
        width: u64,
        /// Height in pixels.
        height: u64,
        /// The limit the picture passes, in words (a side, or the pixels
        /// in all).
        limit: String,
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

/// Render `scene` as an SVG document (see the module docs for what is drawn).
///
/// With `rules`, the scene is evaluated under `opts.contact`; objects that
/// break any rule get an outline marked `class="violator"` and the legend
/// lists every rule with `satisfied/subjects`.
pub fn render_svg(scene: &Scene, rules: Option<&RuleSet>, opts: &RenderOptions) -> String {
    let s = style::effective_scale(opts.scale);
    let colours = style::colours(scene);
    let fill_of = |o: &Object| -> &'static str {
        if o.fixed {
            style::FIXED_FILL
        } else {
            colours.get(&o.class).copied().unwrap_or(style::PALETTE[0])
        }
    };
    let eval: Option<Evaluation> = rules.map(|r| evaluate(scene, r, opts.contact));
    // The legend is measured first: its width sets the picture's.
    let (lines, hard_of) = legend::lines(scene, eval.as_ref(), opts, &fill_of);
    let lw = legend::legend_width(&lines);
    let legend_h: f64 = lines.iter().map(|l| l.dy).sum();
    let (tray_items, tray_h) = draw::tray_layout(scene, s);
    let f = draw::Frame::new(scene.space, s, lw, legend_h, tray_h);

    let mut out = String::new();
    draw::write_header(&mut out, &f, opts);
    draw::write_table(&mut out, &f, scene.grid);
    if let Some(like) = &opts.like {
        draw::write_shown(&mut out, &f, like, &colours);
    }
    draw::write_objects(&mut out, &f, scene, &fill_of);
    draw::write_violations(&mut out, &f, scene, &hard_of);
    draw::write_moved(&mut out, &f, scene, &opts.moved);
    draw::write_outlined(&mut out, &f, scene, &opts.outlined);
    draw::write_tray(&mut out, &f, &tray_items, &fill_of);
    legend::write_legend(&mut out, &lines, f.lx, f.lw, f.ty);
    out.push_str("</svg>\n");
    out
}

/// Render to `path`, choosing the format by its extension (`.svg` or `.png`,
/// case-insensitive). Any other extension is an error naming it. A PNG
/// past the PNG limits is drawn scaled to fit ([`render_png_to_fit`]):
/// returns the scale the table was drawn at (`opts.scale` unless a PNG
/// had to shrink).
pub fn render_to_path(
    scene: &Scene,
    rules: Option<&RuleSet>,
    opts: &RenderOptions,
    path: &Path,
) -> Result<f64, RenderError> {
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
        Some("png") => {
            let (bytes, scale) = render_png_to_fit(scene, rules, opts)?;
            crate::fsutil::atomic_write(path, bytes)?;
            return Ok(scale);
        }
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
    Ok(opts.scale)
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
