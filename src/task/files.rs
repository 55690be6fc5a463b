//! The files of a task folder (docs/cli.md): fixed names only, atomic writes,
//! content versions. Shared by `rccpack run`/`ask` and the studio, so a name
//! is written once.

use crate::scene::{scenes_to_json, Scene};
use std::fs;
use std::path::{Path, PathBuf};

/// The problem: space, fixed objects, objects to place (read only).
pub const PROBLEM: &str = "problem.json";
/// The demonstrations array (created when absent).
pub const DEMOS: &str = "demos.json";
/// Optional statement set for learning (read only).
pub const STATEMENTS: &str = "statements.rcc";
/// The chosen learned rules (written by the page).
pub const LEARNED: &str = "learned.rcc";

/// The learning report `rccpack run` writes beside `learned.rcc`.
pub const LEARN_REPORT: &str = "learn-report.json";
/// The layout `rccpack run` writes.
pub const SOLUTION: &str = "solution.json";
/// The picture of the layout `rccpack run` writes.
pub const SOLUTION_PNG: &str = "solution.png";
/// The probe pictures of a question session.
pub const PROBES: &str = "probes";

/// The answered questions of "Check rules" (docs/guide.md#questions), as `rccpack ask`
/// keeps them.
pub const ANSWERS: &str = "answers.json";
/// The previous `learned.rcc`, kept when a first question replaces it.
pub const LEARNED_BACKUP: &str = "learned.rcc.bak";

/// The path of one of the fixed file names inside `dir`.
pub fn file(dir: &Path, name: &'static str) -> PathBuf {
    dir.join(name)
}

/// Write `contents` to `dir/name` atomically: a temporary file in the same
/// folder, flushed to disk, then renamed over the target. A crash leaves
/// either the old file or the new one, never half of one.
pub fn atomic_write(dir: &Path, name: &'static str, contents: &str) -> std::io::Result<()> {
    atomic_write_path(&dir.join(name), contents)
}

/// [`atomic_write`] to any path: [`crate::fsutil::atomic_write`].
pub fn atomic_write_path(path: &Path, contents: &str) -> std::io::Result<()> {
    crate::fsutil::atomic_write(path, contents)
}

/// Read `dir/name`; `Ok(None)` when it does not exist.
pub fn read_optional(dir: &Path, name: &'static str) -> std::io::Result<Option<String>> {
    match fs::read(dir.join(name)) {
        Ok(b) => crate::fsutil::utf8_text(b)
            .map(Some)
            .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e)),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(e),
    }
}

/// A short version tag of a file's content (64-bit FNV-1a, hex), or
/// `"absent"` for a missing file. Used to refuse overwriting a file that
/// changed since the page loaded it.
pub fn version(content: Option<&str>) -> String {
    match content {
        None => "absent".to_string(),
        Some(s) => {
            let mut h: u64 = 0xcbf2_9ce4_8422_2325;
            for b in s.bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0000_0100_0000_01b3);
            }
            format!("{h:016x}")
        }
    }
}

/// A demonstrations file as read, as measured
/// ([`crate::scene::measured`]): the scenes on the grid, and — when reading
/// it moved an object (a camera's fractions, overlaps) — its recorded
/// entries, which every write keeps as they were: a question session or the
/// studio appends its new demonstrations after them, and never rewrites a
/// measured position with the snapped one.
#[derive(Debug, Clone, Default)]
pub struct DemosFile {
    /// The demonstrations on the grid.
    pub scenes: Vec<Scene>,
    /// The recorded entries, when reading moved an object.
    recorded: Option<Vec<serde_json::Value>>,
}

impl From<Vec<Scene>> for DemosFile {
    /// Demonstrations on the grid (written back as [`scenes_to_json`]
    /// writes them).
    fn from(scenes: Vec<Scene>) -> Self {
        DemosFile {
            scenes,
            recorded: None,
        }
    }
}

impl DemosFile {
    /// Read `text` as measured with the default tolerance; a file on the
    /// grid is read exactly and written back as [`scenes_to_json`] writes
    /// it, byte for byte.
    pub fn parse(text: &str) -> Result<DemosFile, crate::scene::SceneError> {
        let m = crate::scene::measured::measured_from_json(text, None)?;
        let recorded = if m.moves.is_empty() {
            None
        } else {
            // It parsed as scenes, so it is a JSON array (or one scene).
            match serde_json::from_str::<serde_json::Value>(text) {
                Ok(serde_json::Value::Array(v)) => Some(v),
                Ok(one) => Some(vec![one]),
                Err(_) => None,
            }
        };
        Ok(DemosFile {
            scenes: m.scenes,
            recorded,
        })
    }

    /// Whether reading moved an object to the grid.
    pub fn measured(&self) -> bool {
        self.recorded.is_some()
    }

    /// Drop demonstration `i` (its recorded entry too).
    pub fn remove(&mut self, i: usize) -> Scene {
        if let Some(r) = &mut self.recorded {
            if i < r.len() {
                r.remove(i);
            }
        }
        self.scenes.remove(i)
    }

    /// The file's text for `demos` — the scenes read, possibly with some
    /// appended or the last ones dropped: each demonstration that was read
    /// as recorded, the others as [`scenes_to_json`] writes them.
    pub fn to_json(&self, demos: &[Scene]) -> String {
        let Some(recorded) = &self.recorded else {
            return scenes_to_json(demos);
        };
        let values: Vec<serde_json::Value> = demos
            .iter()
            .enumerate()
            .map(|(i, d)| match recorded.get(i) {
                Some(v) => v.clone(),
                None => serde_json::from_str(&d.to_json()).expect("scene JSON re-parses"),
            })
            .collect();
        let mut s = serde_json::to_string_pretty(&values).expect("JSON values serialise");
        s.push('\n');
        s
    }
}

/// The writes that start (or resume) a question session (docs/guide.md#questions), shared
/// by `rccpack ask` and the studio: `demos.json` when `Asker::new` added an
/// accepted probe an abort had kept out of it (`demos_read` is how many
/// scenes the file held), then `learned.rcc`; a different `learned.rcc` of a
/// first session (`resumed` = 0 answers) is kept as `learned.rcc.bak` first.
/// Returns whether a backup was written; an error names the file.
pub fn write_session_start(
    dir: &Path,
    asker: &crate::ask::Asker,
    demos_read: &DemosFile,
    resumed: usize,
) -> Result<bool, (&'static str, std::io::Error)> {
    if asker.demos().len() != demos_read.scenes.len() {
        atomic_write(dir, DEMOS, &demos_read.to_json(asker.demos())).map_err(|e| (DEMOS, e))?;
    }
    let rcc = asker.learned_rcc();
    let old = read_optional(dir, LEARNED).map_err(|e| (LEARNED, e))?;
    let backup = resumed == 0 && old.as_ref().is_some_and(|o| *o != rcc);
    if backup {
        let old = old.unwrap_or_default();
        atomic_write(dir, LEARNED_BACKUP, &old).map_err(|e| (LEARNED_BACKUP, e))?;
    }
    atomic_write(dir, LEARNED, &rcc).map_err(|e| (LEARNED, e))?;
    Ok(backup)
}

/// The writes after an answer (docs/guide.md#questions), in journal order, each atomic:
/// `answers.json`, then `demos.json` (only when the probe was accepted),
/// then `learned.rcc`. An abort between two of them loses nothing:
/// `Asker::new` reconciles the demonstrations with the journal.
pub fn write_after_answer(
    dir: &Path,
    asker: &crate::ask::Asker,
    demos_read: &DemosFile,
    accepted: bool,
) -> Result<(), (&'static str, std::io::Error)> {
    let file = crate::ask::AnswersFile {
        answers: asker.answers().to_vec(),
    };
    atomic_write(dir, ANSWERS, &file.to_json()).map_err(|e| (ANSWERS, e))?;
    if accepted {
        atomic_write(dir, DEMOS, &demos_read.to_json(asker.demos())).map_err(|e| (DEMOS, e))?;
    }
    atomic_write(dir, LEARNED, &asker.learned_rcc()).map_err(|e| (LEARNED, e))
}

/// Names of the rules marked `# confirmed` (docs/guide.md#questions) in `.rcc` text: the
/// comment lines right above a `rule` line belong to it.
pub fn confirmed_names(text: &str) -> Vec<String> {
    let mark = format!("# {}", crate::ask::CONFIRMED);
    let mut out = Vec::new();
    let mut pending = false;
    for line in text.lines().map(str::trim) {
        if line == mark {
            pending = true;
        } else if let Some(rest) = line.strip_prefix("rule ") {
            if pending {
                let name = rest
                    .split(|c: char| c.is_whitespace() || c == ':')
                    .next()
                    .unwrap_or("");
                out.push(name.to_string());
            }
            pending = false;
        } else if !line.starts_with('#') {
            pending = false;
        }
    }
    out
}

/// The `learned.rcc` a fresh learning run writes over `old` (the file
/// there now, perhaps curated by `rccpack ask` or the studio): `new_rcc`
/// with the `# confirmed` mark carried over to every rule the old file
/// confirmed and the new one has unchanged (same name, strength and
/// formula). Returns the text and whether `old` must be kept as
/// [`LEARNED_BACKUP`] first (it differs and would be lost).
pub fn carry_confirmed(
    old: Option<&str>,
    header: &str,
    new_rules: &crate::rules::RuleSet,
) -> (String, bool) {
    let print = |set: &crate::rules::RuleSet| {
        let mut s = header.to_string();
        for r in &set.rules {
            s.push_str(&crate::rules::print_rule(r));
        }
        s
    };
    let Some(old) = old else {
        return (print(new_rules), false);
    };
    let confirmed = confirmed_names(old);
    let old_rules = crate::rules::parse_rules(old).unwrap_or_default();
    let mut set = new_rules.clone();
    for r in &mut set.rules {
        let kept = confirmed.contains(&r.name) && old_rules.rules.iter().any(|o| o.same_rule(r));
        if kept && !r.comments.iter().any(|c| c == crate::ask::CONFIRMED) {
            r.comments.push(crate::ask::CONFIRMED.into());
        }
    }
    let text = print(&set);
    let backup = text != old;
    (text, backup)
}
