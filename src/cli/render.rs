use super::{read_rules_seen, read_scenes};
use anyhow::Result;
use clap::Args;
use rccpack::relations::Contact;
use rccpack::render::{render_to_path, RenderOptions};
use rccpack::resemblance::ResemblanceTarget;
use std::path::PathBuf;
use std::process::ExitCode;

/// `rccpack render SCENE [--rules R] -o out.svg|out.png`
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene JSON (or a demonstrations array, with `--index`).
    scene: PathBuf,
    /// Which scene of a demonstrations array to draw (0-based).
    #[arg(long, allow_hyphen_values = true)]
    index: Option<usize>,
    /// Rules: objects that break one are outlined, and a legend lists them.
    #[arg(long)]
    rules: Option<PathBuf>,
    /// Output picture; the extension picks the format (`.svg` or `.png`).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Pixels per length unit.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    scale: f64,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value = "point")]
    contact: Contact,
    /// Shade where these scenes (one scene or an array, usually the
    /// demonstrations) put each class, under the layout (docs/guide.md#layouts-like-the-demonstrations).
    #[arg(long, value_name = "SCENES.json")]
    like: Option<PathBuf>,
}

pub fn run(a: RenderArgs) -> Result<ExitCode> {
    let mut inputs = vec![a.scene.as_path()];
    inputs.extend(a.rules.as_deref());
    inputs.extend(a.like.as_deref());
    super::guard_outputs(&inputs, &[("-o", Some(a.output.as_path()))], &[])?;
    let (mut scenes, is_array) = read_scenes(&a.scene)?;
    let scene = match (is_array, a.index) {
        (false, None | Some(0)) => scenes.remove(0),
        (false, Some(i)) => anyhow::bail!(
            "--index {i}: {} holds one scene, not an array",
            a.scene.display()
        ),
        (true, _) if scenes.is_empty() => anyhow::bail!(
            "{} is an empty demonstrations array (`[]`); expected at least one scene to draw",
            a.scene.display()
        ),
        (true, None) => anyhow::bail!(
            "{} is a demonstrations array of {} scenes; pick one with --index 0..{}",
            a.scene.display(),
            scenes.len(),
            scenes.len().saturating_sub(1)
        ),
        (true, Some(i)) if i < scenes.len() => scenes.swap_remove(i),
        (true, Some(i)) => anyhow::bail!(
            "--index {i} is out of range: {} holds {} scenes",
            a.scene.display(),
            scenes.len()
        ),
    };
    let like = match &a.like {
        Some(p) => Some(read_scenes(p)?.0),
        None => None,
    };
    let rules = match &a.rules {
        Some(p) => Some(read_rules_seen(
            p,
            std::slice::from_ref(&scene),
            like.as_deref().unwrap_or_default(),
        )?),
        None => None,
    };
    if !(a.scale.is_finite() && a.scale > 0.0 && a.scale <= 20.0) {
        anyhow::bail!(
            "--scale {} is out of range; expected a number in (0, 20]",
            rccpack::limits::number(a.scale)
        );
    }
    let opts = RenderOptions {
        contact: a.contact,
        scale: a.scale,
        title: Some(a.scene.display().to_string()),
        like: like.as_deref().map(ResemblanceTarget::new),
        ..RenderOptions::default()
    };
    let drawn = render_to_path(&scene, rules.as_ref(), &opts, &a.output)
        .map_err(|e| anyhow::anyhow!("{}: {e}", a.output.display()))?;
    if drawn < a.scale {
        ewriteln!(
            "wrote {} at scale {} (scale {} would pass the PNG limits: {} pixels a side, {} in all)",
            a.output.display(),
            rccpack::limits::number(drawn),
            rccpack::limits::number(a.scale),
            rccpack::render::MAX_PNG_SIDE,
            rccpack::render::MAX_PNG_PIXELS
        );
    } else {
        ewriteln!("wrote {}", a.output.display());
    }
    Ok(ExitCode::SUCCESS)
}
