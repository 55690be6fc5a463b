//! Reading input files at the edge, turning library errors into messages
//! that name the file, the line/column or the JSON field.

use anyhow::Result;
use rccpack::rules::{self, RuleSet};
use rccpack::scene::{self, Scene};
use std::io::IsTerminal;
use std::path::Path;

/// An error whose full text is already formatted for the user.
#[derive(Debug)]
pub struct Reported(pub String);

impl std::fmt::Display for Reported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Reported {}

/// Read a whole text file, naming it in the error.
pub fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path)
        .map_err(|e| Reported(format!("error: {}: cannot read file: {e}", path.display())).into())
}

fn scene_error(path: &Path, e: scene::SceneError) -> anyhow::Error {
    Reported(format!("error: {}: {e}", path.display())).into()
}

/// Read one scene (a JSON object).
pub fn read_scene(path: &Path) -> Result<Scene> {
    let text = read_text(path)?;
    Scene::from_json(&text).map_err(|e| scene_error(path, e))
}

/// Read a scene file or a demonstrations array; `true` when it was an array.
pub fn read_scenes(path: &Path) -> Result<(Vec<Scene>, bool)> {
    let text = read_text(path)?;
    let is_array = text.trim_start().starts_with('[');
    let scenes = scene::scenes_from_json(&text).map_err(|e| scene_error(path, e))?;
    Ok((scenes, is_array))
}

/// Read and check a `.rcc` file; with scenes, also check that every class it
/// names exists in each of them and that every landmark `@ID` names a fixed
/// object of each of them.
pub fn read_rules(path: &Path, scenes: &[Scene]) -> Result<RuleSet> {
    let text = read_text(path)?;
    let set = parse_rules_text(path, &text)?;
    let color = std::io::stderr().is_terminal();
    let name = path.display().to_string();
    for s in scenes {
        rules::check_classes(&set, s).map_err(|e| Reported(e.render(&name, &text, color)))?;
        rules::check_landmarks(&set, s).map_err(|e| Reported(e.render(&name, &text, color)))?;
    }
    Ok(set)
}

/// Parse `.rcc` text read from `path`, rendering errors with carets.
pub fn parse_rules_text(path: &Path, text: &str) -> Result<RuleSet> {
    let color = std::io::stderr().is_terminal();
    rules::parse_rules(text)
        .map_err(|e| Reported(e.render(&path.display().to_string(), text, color)).into())
}
