//! `rccpack run` on a task folder, the files and the summary: shared by the
//! command line and the Python package (`Task.run`), so both write the
//! same bytes.
//!
//! Under the folder lock of the output folder ([`lock`]), every input read
//! and checked first: learn, place ([`super::place`]), then
//! [`write_outcome`] writes, each atomically, `learned.rcc` (confirmed
//! marks carried over, a curated file kept as `learned.rcc.bak`:
//! [`files::carry_confirmed`]), `learn-report.json`, `solution.json` and
//! `solution.png`, and says what the command prints. [`run_folder`] is
//! the whole of it on a folder already read ([`super::Task::load`]).

use super::{files, learn_with_priors, place, Outcome, Placement, RunOptions, Task, TaskError};
use crate::fsutil::DirLock;
use crate::infer::Learned;
use crate::render::{render_to_path, RenderError, RenderOptions};
use crate::rules::{missing_classes_note, RuleSet};
use crate::scene::Scene;
use crate::synth::report::{bound_text, conflict_text, resemblance_text};
use crate::synth::{Status, SynthOptions};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Why the folder pipeline stopped.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FolderError {
    /// The output folder cannot be made.
    #[error("{}: cannot create folder: {source}", path.display())]
    CreateDir {
        /// The folder.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Another process (`rccpack ask`, the studio) holds the folder lock.
    #[error("{}: another `rccpack ask` or the studio is writing this task folder (it holds {}); wait until it ends, then run again", dir.display(), crate::fsutil::LOCK_FILE)]
    Locked {
        /// The folder.
        dir: PathBuf,
    },
    /// The lock file cannot be made.
    #[error("{}: cannot lock the task folder: {source}", path.display())]
    Lock {
        /// The lock file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file cannot be read.
    #[error("{}: cannot read file: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file cannot be written.
    #[error("{}: cannot write file: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The picture cannot be drawn.
    #[error("{}: {source}", path.display())]
    Render {
        /// The picture.
        path: PathBuf,
        /// Why.
        source: RenderError,
    },
    /// Learning or placing failed.
    #[error(transparent)]
    Task(#[from] TaskError),
}

/// What [`write_outcome`] wrote.
#[derive(Debug, Clone)]
pub struct Written {
    /// The placed problem.
    pub placement: Placement,
    /// The lines `rccpack run` prints on standard output, in order.
    pub stdout: Vec<String>,
    /// The line it prints on standard error (infeasible, unknown).
    pub stderr: Option<String>,
    /// Its exit code: 0 a layout, 2 infeasible, 3 a limit before any
    /// layout (docs/cli.md).
    pub exit_code: u8,
    /// The files written, in order.
    pub files: Vec<PathBuf>,
}

/// What [`run_folder`] produced.
#[derive(Debug, Clone)]
pub struct FolderRun {
    /// Learned rules, layout (as [`super::run`] returns them).
    pub outcome: Outcome,
    /// The lines `rccpack run` prints on standard output.
    pub stdout: Vec<String>,
    /// The line it prints on standard error.
    pub stderr: Option<String>,
    /// Its exit code.
    pub exit_code: u8,
    /// Every file written, in order.
    pub files: Vec<PathBuf>,
}

/// Create the output folder and take its lock (the lock file of `rccpack
/// ask` and the studio), held until the returned value is dropped.
pub fn lock(out: &Path) -> Result<DirLock, FolderError> {
    std::fs::create_dir_all(out).map_err(|source| FolderError::CreateDir {
        path: out.to_path_buf(),
        source,
    })?;
    match DirLock::try_lock(out) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err(FolderError::Locked {
            dir: out.to_path_buf(),
        }),
        Err(source) => Err(FolderError::Lock {
            path: out.join(crate::fsutil::LOCK_FILE),
            source,
        }),
    }
}

fn write(path: PathBuf, contents: impl AsRef<[u8]>) -> Result<PathBuf, FolderError> {
    match crate::fsutil::atomic_write(&path, contents) {
        Ok(()) => Ok(path),
        Err(source) => Err(FolderError::Write { path, source }),
    }
}

/// Write what a run produced into `out` and say what `rccpack run` says:
/// `learned.rcc` (the confirmed marks of the file there carried over; a
/// file that would change otherwise kept as `learned.rcc.bak` first, with
/// a note), `learn-report.json`, then with a layout `solution.json` and
/// `solution.png` (titled `DIR — synthesised`, `dir` as given).
pub fn write_outcome(
    dir: &Path,
    out: &Path,
    problem: &Scene,
    learned: &Learned,
    rules: &RuleSet,
    placement: Placement,
    contact: crate::relations::Contact,
) -> Result<Written, FolderError> {
    let mut stdout = Vec::new();
    let mut written = Vec::new();
    write_learned(out, learned, rules, &mut stdout, &mut written)?;
    let result = &placement.result;
    // Learned rules about a class today's problem lacks hold as docs/language.md#class-rules
    // says (docs/language.md#classes-a-scene-lacks): a note, then a layout.
    if let Some(note) = missing_classes_note(&placement.missing_classes) {
        stdout.push(note);
    }
    let candidates = learned.statements.iter().filter(|s| s.candidate).count();
    stdout.push(format!(
        "learned {} rules ({} candidates of {} statements) from {} demonstrations -> {}",
        rules.rules.len(),
        candidates,
        learned.statements.len(),
        learned.demos,
        out.join(files::LEARNED).display()
    ));
    let (stderr, exit_code) = match (&result.scene, &result.evaluation) {
        (Some(scene), Some(ev)) => {
            let shown = Shown {
                dir,
                out,
                problem,
                rules,
                placement: &placement,
                contact,
            };
            write_layout(&shown, scene, ev, &mut stdout, &mut written)?;
            (None, 0)
        }
        _ if result.status == Status::Infeasible => {
            let c = result.conflict.clone().unwrap_or_default();
            (Some(format!("infeasible: {}", conflict_text(&c))), 2)
        }
        _ => (
            Some("unknown: the time limit stopped the search before any layout was found".into()),
            3,
        ),
    };
    Ok(Written {
        placement,
        stdout,
        stderr,
        exit_code,
        files: written,
    })
}

/// `learned.rcc` with the confirmed marks of the file in `out` carried over
/// (a file that would change otherwise kept as `learned.rcc.bak` first,
/// with a note), then `learn-report.json`.
fn write_learned(
    out: &Path,
    learned: &Learned,
    rules: &RuleSet,
    stdout: &mut Vec<String>,
    written: &mut Vec<PathBuf>,
) -> Result<(), FolderError> {
    let learned_path = out.join(files::LEARNED);
    let old = files::read_optional(out, files::LEARNED).map_err(|source| FolderError::Read {
        path: learned_path.clone(),
        source,
    })?;
    let (rcc, backup) = files::carry_confirmed(old.as_deref(), &learned.rcc_header(), rules);
    if backup {
        let bak = out.join(files::LEARNED_BACKUP);
        written.push(write(bak.clone(), old.unwrap_or_default())?);
        stdout.push(format!(
            "note: {} was not what this run learned; kept as {}",
            learned_path.display(),
            bak.display()
        ));
    }
    written.push(write(learned_path, rcc)?);
    written.push(write(out.join(files::LEARN_REPORT), learned.report_json())?);
    Ok(())
}

/// What [`write_layout`] shows a layout against.
struct Shown<'a> {
    dir: &'a Path,
    out: &'a Path,
    problem: &'a Scene,
    rules: &'a RuleSet,
    placement: &'a Placement,
    contact: crate::relations::Contact,
}

/// `solution.json` and `solution.png` of a layout, and the lines that say
/// how good it is and which rules it does not keep.
fn write_layout(
    x: &Shown,
    scene: &Scene,
    ev: &crate::eval::Evaluation,
    stdout: &mut Vec<String>,
    written: &mut Vec<PathBuf>,
) -> Result<(), FolderError> {
    let result = &x.placement.result;
    written.push(write(x.out.join(files::SOLUTION), scene.to_json())?);
    let png = x.out.join(files::SOLUTION_PNG);
    let ropts = RenderOptions {
        contact: x.contact,
        scale: 1.0,
        title: Some(format!("{} — synthesised", x.dir.display())),
        like: x.placement.like.clone(),
        ..RenderOptions::default()
    };
    render_to_path(scene, Some(x.rules), &ropts, &png).map_err(|source| FolderError::Render {
        path: png.clone(),
        source,
    })?;
    written.push(png.clone());
    let broken: Vec<String> = ev
        .rules
        .iter()
        .filter(|r| r.satisfied < r.subjects)
        .map(|r| format!("{} {}/{}", r.name, r.satisfied, r.subjects))
        .collect();
    stdout.push(format!(
        "placed {} objects: {} score {:.6} (weight {:.3} / {:.3}){}{} in {:.1} ms -> {}, {}",
        x.problem.objects.iter().filter(|o| !o.is_placed()).count(),
        match result.status {
            Status::Optimal => "optimal,",
            _ => "feasible (time limit),",
        },
        ev.score,
        ev.satisfied_weight,
        ev.total_weight,
        bound_text(result),
        resemblance_text(result.resemblance),
        result.stats.time_ms,
        x.out.join(files::SOLUTION).display(),
        png.display()
    ));
    if broken.is_empty() {
        stdout.push("every placed object keeps every learned rule".into());
    } else {
        stdout.push(format!(
            "rules not kept by every object: {}",
            broken.join(", ")
        ));
    }
    Ok(())
}

/// `rccpack run DIR --out OUT` on a task already read from `dir`: lock
/// `out`, learn (the time limit `opts.synth.time_limit` covers the whole
/// run), place, write the files. `opts.synth.contact` is taken from
/// `opts.learn.contact`, as [`super::run`] does.
pub fn run_folder(
    task: &Task,
    dir: &Path,
    out: &Path,
    opts: &RunOptions,
) -> Result<FolderRun, FolderError> {
    let start = Instant::now();
    let _lock = lock(out)?;
    let deadline = opts
        .synth
        .time_limit
        .and_then(|limit| start.checked_add(limit));
    let learned = learn_with_priors(
        task,
        &opts.learn,
        opts.priors.as_deref(),
        deadline,
        opts.synth.cancel.as_deref(),
    )?;
    let rules = learned.rules();
    let synth = SynthOptions {
        contact: opts.learn.contact,
        time_limit: opts
            .synth
            .time_limit
            .map(|limit| limit.saturating_sub(start.elapsed())),
        ..opts.synth.clone()
    };
    let placement = place(&task.problem, &rules, &task.demos, &opts.like, &synth)?;
    let w = write_outcome(
        dir,
        out,
        &task.problem,
        &learned,
        &rules,
        placement,
        opts.learn.contact,
    )?;
    let files = w.files;
    Ok(FolderRun {
        outcome: Outcome {
            learned,
            rules,
            placement: w.placement,
        },
        stdout: w.stdout,
        stderr: w.stderr,
        exit_code: w.exit_code,
        files,
    })
}
