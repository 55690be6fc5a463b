//! Reading input files at the edge, turning library errors into messages
//! that name the file, the line/column or the JSON field.

use anyhow::Result;
use rccpack::rules::{self, RuleSet};
use rccpack::scene::{self, Scene};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// An error whose full text is already formatted for the user.
#[derive(Debug)]
pub struct Reported(pub String);

impl std::fmt::Display for Reported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Reported {}

/// A limit stopped the command before any result (exit 3, docs/cli.md); the
/// text is printed as it is.
#[derive(Debug)]
pub struct LimitStruck(pub String);

impl std::fmt::Display for LimitStruck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for LimitStruck {}

/// The engine tuning the `RCCPACK_*` environment variables ask for
/// (docs/performance.md): only the command line reads them, never the
/// library.
pub fn tuning() -> Result<rccpack::synth::Tuning, Reported> {
    rccpack::synth::Tuning::from_env().map_err(|e| Reported(format!("error: {e}")))
}

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
    use rccpack::resemblance::ResemblanceError;
    match e {
        rccpack::SynthError::Resemblance(ResemblanceError::TooManyPositions {
            id,
            cells,
            max,
            ..
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

/// [`read_text`] of at most `max` bytes ([`rccpack::task::read_text_at_most`]).
pub fn read_text_at_most(path: &Path, max: usize) -> Result<String> {
    rccpack::task::read_text_at_most(path, max).map_err(|e| Reported(format!("error: {e}")).into())
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
    let text = read_text_at_most(path, rccpack::limits::MAX_SCENE_BYTES)?;
    let is_array = text.trim_start().starts_with('[');
    let scenes = scene::scenes_from_json(&text).map_err(|e| scene_error(path, e))?;
    Ok((scenes, is_array))
}

/// Read demonstrations as measured (docs/scenes.md#demonstrations-as-measured):
/// snapped to the grid with `tolerance` (`None`: four tenths of the grid
/// step), a note on standard error saying what moved. A given tolerance is
/// checked against every demonstration's grid (`--tolerance` named).
pub fn read_demos(path: &Path, tolerance: Option<f64>) -> Result<scene::measured::Measured> {
    let text = read_text_at_most(path, rccpack::limits::MAX_SCENE_BYTES)?;
    let m =
        scene::measured::measured_from_json(&text, tolerance).map_err(|e| scene_error(path, e))?;
    if let Some(t) = tolerance {
        scene::measured::check_tolerance(t, &m.scenes)
            .map_err(|e| Reported(format!("error: --tolerance: {e}")))?;
    }
    if !m.moves.is_empty() {
        let objects: std::collections::BTreeSet<(usize, usize)> = m
            .moves
            .iter()
            .map(|mv| (mv.demonstration, mv.index))
            .collect();
        ewriteln!(
            "{} demonstrations as measured: {} objects moved by at most {} px to the grid",
            m.scenes.len(),
            objects.len(),
            rccpack::limits::number((m.largest_move() * 10.0).round() / 10.0)
        );
        for mv in m.moves.iter().filter(|mv| {
            let t = tolerance.unwrap_or_else(|| {
                scene::measured::default_tolerance(m.scenes[mv.demonstration].grid)
            });
            mv.distance > t + 1e-9
        }) {
            ewriteln!(
                "note: demonstration {}: `{}` measured at ({}, {}) moved {} px to ({}, {}), more than the tolerance — a slip?",
                mv.demonstration,
                mv.object,
                rccpack::limits::number(mv.from.0),
                rccpack::limits::number(mv.from.1),
                rccpack::limits::number((mv.distance * 10.0).round() / 10.0),
                mv.to.0,
                mv.to.1
            );
        }
    }
    Ok(m)
}

/// Read and check a `.rcc` file against the scenes it applies to (see
/// [`read_rules_seen`]).
pub fn read_rules(path: &Path, scenes: &[Scene]) -> Result<RuleSet> {
    read_rules_seen(path, scenes, &[])
}

/// Whether `.rcc` text was written by `learn`/`ask`/`run` (its header says
/// so; docs/language.md#classes-a-scene-lacks).
fn is_learned(text: &str) -> bool {
    text.trim_start().starts_with("# learned by rccpack")
}

/// Read and check a `.rcc` file: every landmark `@ID` names a fixed object
/// of each of `scenes` (the scenes the rules apply to). A class a rule
/// names and one of `scenes` lacks is a note on standard error, and its
/// rules hold vacuously there, when the file was learned or when the class
/// is in some scene the command reads (`scenes` and `also`: `--like`,
/// warm starts); a hand-written file naming a class no such scene has is
/// refused, naming the closest class (docs/language.md#classes-a-scene-lacks).
pub fn read_rules_seen(path: &Path, scenes: &[Scene], also: &[Scene]) -> Result<RuleSet> {
    // The size limit while reading, not after (`check /dev/zero`).
    let text = rccpack::task::read_text_at_most(path, rccpack::limits::MAX_RULES_BYTES)
        .map_err(|e| Reported(format!("error: {e}")))?;
    let set = parse_rules_text(path, &text)?;
    let color = std::io::stderr().is_terminal();
    let name = path.display().to_string();
    if scenes.is_empty() {
        return Ok(set);
    }
    if !is_learned(&text) {
        let read: Vec<&Scene> = scenes.iter().chain(also).collect();
        rules::check_classes_across(&set, &read)
            .map_err(|e| Reported(e.render(&name, &text, color)))?;
    }
    for s in scenes {
        rules::check_landmarks(&set, s).map_err(|e| Reported(e.render(&name, &text, color)))?;
    }
    let mut missing: Vec<String> = Vec::new();
    for s in scenes {
        for c in rules::missing_classes(&set, s) {
            if !missing.contains(&c) {
                missing.push(c);
            }
        }
    }
    let missing: Vec<String> = missing.iter().map(|c| rccpack::limits::cut(c)).collect();
    let needing = rules::rules_needing(&set, &missing);
    if let Some(note) = rules::missing_classes_note(&missing, &needing) {
        let note = if scenes.len() > 1 {
            note.replacen("the problem has", "some scenes have", 1)
        } else {
            note
        };
        ewriteln!("{note}");
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

/// Whether two paths name the same file: the same device and inode when
/// both exist, else the same absolute path.
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
        use std::os::unix::fs::MetadataExt as _;
        return ma.dev() == mb.dev() && ma.ino() == mb.ino();
    }
    let abs = |p: &Path| {
        std::path::absolute(p)
            .map(|p| p.components().collect::<PathBuf>())
            .unwrap_or_else(|_| p.to_path_buf())
    };
    abs(a) == abs(b)
}

/// Whether a path is a device, a FIFO or a socket (`/dev/null`): two
/// outputs or an input and an output may share one.
fn is_special(p: &Path) -> bool {
    std::fs::metadata(p).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Refuse before anything is read or written (exit 1) when an output file
/// is one of the inputs or another output (`synth --rules r.rcc -o r.rcc`
/// would replace the rules with a scene; `learn -o x --report x` would keep
/// only the report). `outputs` and `more_inputs` pair each path with its
/// flag; devices such as `/dev/null` may be shared.
pub fn guard_outputs(
    inputs: &[&Path],
    outputs: &[(&str, Option<&Path>)],
    more_inputs: &[(&str, Option<&Path>)],
) -> Result<()> {
    let outs: Vec<(&str, &Path)> = outputs
        .iter()
        .filter_map(|(f, p)| p.map(|p| (*f, p)))
        .filter(|(_, p)| !is_special(p))
        .collect();
    let ins: Vec<(String, &Path)> = inputs
        .iter()
        .map(|p| (format!("input {}", p.display()), *p))
        .chain(
            more_inputs
                .iter()
                .filter_map(|(f, p)| p.map(|p| (format!("{f} {}", p.display()), p)))
                .filter(|(_, p)| *p != Path::new("none")),
        )
        .collect();
    for (i, (flag, out)) in outs.iter().enumerate() {
        let clash = ins
            .iter()
            .find(|(_, p)| same_file(p, out))
            .map(|(what, _)| what.clone())
            .or_else(|| {
                outs[..i]
                    .iter()
                    .find(|(_, p)| same_file(p, out))
                    .map(|(f, p)| format!("{f} {}", p.display()))
            });
        if let Some(what) = clash {
            return Err(Reported(format!(
                "error: {flag} {}: the same file as {what}; expected a different file for each output, none of them an input",
                out.display()
            ))
            .into());
        }
    }
    Ok(())
}

/// Take a task folder's lock (shared by `ask`, `run` and the studio)
/// without waiting; an error (exit 1) when another session holds it.
pub fn lock_folder(dir: &Path) -> Result<rccpack::fsutil::DirLock> {
    match rccpack::fsutil::DirLock::try_lock(dir) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err(Reported(format!(
            "error: {}: another `rccpack ask` or the studio is writing this task folder (it holds {}); wait until it ends, then run again",
            dir.display(),
            rccpack::fsutil::LOCK_FILE
        ))
        .into()),
        Err(e) => Err(Reported(format!(
            "error: {}: cannot lock the task folder: {e}",
            dir.join(rccpack::fsutil::LOCK_FILE).display()
        ))
        .into()),
    }
}
