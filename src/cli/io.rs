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

/// A limit stopped the command before any result (exit 3, SPEC §10); the
/// text is printed as it is.
#[derive(Debug)]
pub struct LimitStruck(pub String);

impl std::fmt::Display for LimitStruck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for LimitStruck {}

/// A learning error in the command line's words: the library names
/// parameters, the command line their flags.
pub fn learn_error_text(e: &rccpack::InferError) -> String {
    use rccpack::InferError;
    match e {
        InferError::BadParameter {
            param,
            value,
            expected,
        } => format!("invalid --{param} {value}: expected {expected}"),
        InferError::TooManyStatements { .. } => format!("{e} (`--statements`)"),
        _ => e.to_string(),
    }
}

/// A synthesis error in the command line's words (see [`learn_error_text`]).
pub fn synth_error_text(e: &rccpack::SynthError) -> String {
    use rccpack::resemblance::LikenessError;
    match e {
        rccpack::SynthError::Likeness(LikenessError::TooManyPositions {
            id, cells, max, ..
        }) => {
            format!(
                "object `{id}` has {cells} grid positions, more than the {max} a resemblance map may have; \
                 use a coarser grid or leave out --like"
            )
        }
        _ => e.to_string(),
    }
}

/// A pipeline error in the command line's words.
pub fn task_error_text(e: &rccpack::TaskError) -> String {
    match e {
        rccpack::TaskError::Synth(e) => synth_error_text(e),
        rccpack::TaskError::Learn(e) => learn_error_text(e),
        _ => e.to_string(),
    }
}

/// Read a whole text file, naming it in the error: UTF-8 (a leading
/// byte-order mark is dropped); invalid UTF-8 is reported with its byte
/// offset ([`rccpack::task::read_text`]).
pub fn read_text(path: &Path) -> Result<String> {
    rccpack::task::read_text(path).map_err(|e| Reported(format!("error: {e}")).into())
}

fn scene_error(path: &Path, e: scene::SceneError) -> anyhow::Error {
    Reported(format!("error: {}: {e}", path.display())).into()
}

/// Read one scene (a JSON object; [`rccpack::task::read_scene`]).
pub fn read_scene(path: &Path) -> Result<Scene> {
    rccpack::task::read_scene(path).map_err(|e| Reported(format!("error: {e}")).into())
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

/// Write a whole file atomically ([`rccpack::fsutil::atomic_write`]: a
/// temporary file beside it, then a rename; a failure keeps the previous
/// file). `what` names the contents in the error ("cannot write report").
pub fn write_file(path: &Path, contents: impl AsRef<[u8]>, what: &str) -> Result<()> {
    rccpack::fsutil::atomic_write(path, contents).map_err(|e| {
        Reported(format!(
            "error: {}: cannot write {what}: {e}",
            path.display()
        ))
        .into()
    })
}

/// Print to standard output, reporting a failed write (a full disk,
/// `> /dev/full`) as an error instead of panicking as `print!` does.
pub fn out(text: impl AsRef<str>) -> Result<()> {
    use std::io::Write as _;
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_ref().as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| Reported(format!("error: cannot write to standard output: {e}")).into())
}

/// [`out`] with a line end.
pub fn outln(text: impl AsRef<str>) -> Result<()> {
    out(format!("{}\n", text.as_ref()))
}
