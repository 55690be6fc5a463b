//! Pictures of scenes: SVG, and PNG through resvg.

// Placeholder API so the CLI compiles while the renderer is being written on
// its own branch; replaced wholesale by that branch.
use crate::relations::Contact;
use crate::rules::RuleSet;
use crate::scene::Scene;

/// Rendering options.
#[derive(Debug, Clone, Default)]
pub struct RenderOptions {
    /// Contact mode for rule evaluation.
    pub contact: Contact,
    /// Pixels per unit.
    pub scale: f64,
    /// Optional title.
    pub title: Option<String>,
}

/// Rendering errors.
#[derive(Debug, thiserror::Error)]
#[error("render error")]
pub struct RenderError;

/// Render to a file.
pub fn render_to_path(
    _scene: &Scene,
    _rules: Option<&RuleSet>,
    _opts: &RenderOptions,
    _path: &std::path::Path,
) -> Result<(), RenderError> {
    todo!("render branch")
}
