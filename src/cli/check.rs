use super::{outln, read_rules, read_scenes};
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

/// `rccpack check RULES.rcc [--scene S]`
#[derive(Args, Debug)]
pub struct CheckArgs {
    /// The `.rcc` rule file.
    rules: PathBuf,
    /// A scene (or demonstrations array) whose classes every rule must use.
    #[arg(long)]
    scene: Option<PathBuf>,
}

pub fn run(a: CheckArgs) -> Result<ExitCode> {
    let scenes = match &a.scene {
        Some(p) => read_scenes(p)?.0,
        None => Vec::new(),
    };
    let set = read_rules(&a.rules, &scenes)?;
    let hard = set.rules.iter().filter(|r| r.strength.is_hard()).count();
    outln(format!(
        "{}: ok, {} rules ({} hard, {} soft)",
        a.rules.display(),
        set.rules.len(),
        hard,
        set.rules.len() - hard
    ))?;
    Ok(ExitCode::SUCCESS)
}
