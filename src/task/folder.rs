//! Running a task folder (`rccpack run`, Python's `Task.run`): the one
//! implementation, [`run_locked`] ([`run_folder`] takes the lock first).
//!
//! Under the folder lock of the output folder ([`lock`]), on a task whose
//! inputs were all read and checked first ([`super::Task::load`]): learn,
//! place ([`super::run`]), then [`write_outcome`] writes, each atomically,
//! `learned.rcc` (confirmed marks carried over, a curated file kept as
//! `learned.rcc.bak`: [`files::carry_confirmed`]), `learn-report.json`,
//! `solution.json` and `solution.png`. The result is data ([`FolderRun`]);
//! [`summary`] words it as the command prints it, and the front ends
//! choose their exit codes from [`FolderRun::ending`].

use super::{files, Outcome, Placement, RunOptions, Task, TaskError};
use crate::fsutil::DirLock;
use crate::infer::Learned;
use crate::render::{render_to_path, RenderError, RenderOptions};
use crate::rules::{missing_classes_note, RuleSet};
use crate::synth::report::{bound_text, conflict_text, resemblance_text};
use crate::synth::Status;
use std::path::{Path, PathBuf};

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
    /// Where the `learned.rcc` found in the output folder was kept, when
    /// it was not what this run learned ([`files::LEARNED_BACKUP`]).
    pub backup: Option<PathBuf>,
    /// The files written, in order.
    pub files: Vec<PathBuf>,
}

/// What [`run_folder`] produced: the data; [`summary`] words it as
/// `rccpack run` prints it.
#[derive(Debug, Clone)]
pub struct FolderRun {
    /// Learned rules, layout (as [`super::run`] returns them).
    pub outcome: Outcome,
    /// The output folder, as given.
    pub out: PathBuf,
    /// How many objects the problem had to place.
    pub to_place: usize,
    /// Where the `learned.rcc` found in the output folder was kept, when
    /// it was not what this run learned.
    pub backup: Option<PathBuf>,
    /// Every file written, in order.
    pub files: Vec<PathBuf>,
}

/// How a folder run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Ending {
    /// A layout was found and written.
    Layout,
    /// No layout can keep the hard rules.
    Infeasible,
    /// A limit stopped the search before any layout.
    Unknown,
}

impl FolderRun {
    /// How the run ended.
    pub fn ending(&self) -> Ending {
        let result = &self.outcome.placement.result;
        match (&result.scene, &result.evaluation) {
            (Some(_), Some(_)) => Ending::Layout,
            _ if result.status == Status::Infeasible => Ending::Infeasible,
            _ => Ending::Unknown,
        }
    }
}

/// What `rccpack run` (and Python's `Task.run`) says about a folder run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Summary {
    /// The lines for standard output, in order.
    pub stdout: Vec<String>,
    /// The line for standard error (infeasible, unknown).
    pub stderr: Option<String>,
}

/// The words of a folder run: the note on a kept `learned.rcc`, the note
/// on classes the problem lacks, what was learned, then how good the
/// layout is and which rules it does not keep (or why there is none).
pub fn summary(run: &FolderRun) -> Summary {
    let Outcome {
        learned,
        rules,
        placement,
    } = &run.outcome;
    let result = &placement.result;
    let mut stdout = Vec::new();
    if let Some(bak) = &run.backup {
        stdout.push(format!(
            "note: {} was not what this run learned; kept as {}",
            run.out.join(files::LEARNED).display(),
            bak.display()
        ));
    }
    // Learned rules about a class today's problem lacks hold as docs/language.md#class-rules
    // says (docs/language.md#classes-a-scene-lacks): a note, then a layout.
    let needing = crate::rules::rules_needing(rules, &placement.missing_classes);
    if let Some(note) = missing_classes_note(&placement.missing_classes, &needing) {
        stdout.push(note);
    }
    let candidates = learned.statements.iter().filter(|s| s.candidate).count();
    stdout.push(format!(
        "learned {} rules ({} candidates of {} statements) from {} demonstrations -> {}",
        rules.rules.len(),
        candidates,
        learned.statements.len(),
        learned.demos,
        run.out.join(files::LEARNED).display()
    ));
    let stderr = match (&result.scene, &result.evaluation) {
        (Some(_), Some(ev)) => {
            layout_lines(run, ev, &mut stdout);
            None
        }
        _ if result.status == Status::Infeasible => {
            let c = result.conflict.clone().unwrap_or_default();
            Some(format!("infeasible: {}", conflict_text(&c)))
        }
        _ => Some("unknown: the time limit stopped the search before any layout was found".into()),
    };
    Summary { stdout, stderr }
}

/// The lines that say how good a layout is and which rules it does not
/// keep.
fn layout_lines(run: &FolderRun, ev: &crate::eval::Evaluation, stdout: &mut Vec<String>) {
    let result = &run.outcome.placement.result;
    let broken: Vec<String> = ev
        .rules
        .iter()
        .filter(|r| r.satisfied < r.subjects)
        .map(|r| format!("{} {}/{}", r.name, r.satisfied, r.subjects))
        .collect();
    stdout.push(format!(
        "placed {} objects: {} score {:.6} (weight {:.3} / {:.3}){}{} in {:.1} ms -> {}, {}",
        run.to_place,
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
        run.out.join(files::SOLUTION).display(),
        run.out.join(files::SOLUTION_PNG).display()
    ));
    if broken.is_empty() {
        stdout.push("every placed object keeps every learned rule".into());
    } else {
        stdout.push(format!(
            "rules not kept by every object: {}",
            broken.join(", ")
        ));
    }
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

/// Write what a run produced into `out`: `learned.rcc` (the confirmed
/// marks of the file there carried over; a file that would change
/// otherwise kept as `learned.rcc.bak` first), `learn-report.json`, then
/// with a layout `solution.json` and `solution.png` (titled `DIR —
/// synthesised`, `dir` as given).
pub fn write_outcome(
    dir: &Path,
    out: &Path,
    learned: &Learned,
    rules: &RuleSet,
    placement: Placement,
    contact: crate::relations::Contact,
) -> Result<Written, FolderError> {
    let mut written = Vec::new();
    let backup = write_learned(out, learned, rules, &mut written)?;
    if let Some(scene) = &placement.result.scene {
        if placement.result.evaluation.is_some() {
            written.push(write(out.join(files::SOLUTION), scene.to_json())?);
            let png = out.join(files::SOLUTION_PNG);
            let ropts = RenderOptions {
                contact,
                scale: 1.0,
                title: Some(format!("{} — synthesised", dir.display())),
                like: placement.like.clone(),
                ..RenderOptions::default()
            };
            render_to_path(scene, Some(rules), &ropts, &png).map_err(|source| {
                FolderError::Render {
                    path: png.clone(),
                    source,
                }
            })?;
            written.push(png);
        }
    }
    Ok(Written {
        placement,
        backup,
        files: written,
    })
}

/// `learned.rcc` with the confirmed marks of the file in `out` carried over
/// (a file that would change otherwise kept as `learned.rcc.bak` first:
/// its path returned), then `learn-report.json`.
fn write_learned(
    out: &Path,
    learned: &Learned,
    rules: &RuleSet,
    written: &mut Vec<PathBuf>,
) -> Result<Option<PathBuf>, FolderError> {
    let learned_path = out.join(files::LEARNED);
    let old = files::read_optional(out, files::LEARNED).map_err(|source| FolderError::Read {
        path: learned_path.clone(),
        source,
    })?;
    let (rcc, backup) = files::carry_confirmed(old.as_deref(), &learned.rcc_header(), rules);
    let backup = if backup {
        let bak = out.join(files::LEARNED_BACKUP);
        written.push(write(bak.clone(), old.unwrap_or_default())?);
        Some(bak)
    } else {
        None
    };
    written.push(write(learned_path, rcc)?);
    written.push(write(out.join(files::LEARN_REPORT), learned.report_json())?);
    Ok(backup)
}

/// `rccpack run DIR --out OUT` on a task already read from `dir`: lock
/// `out`, then [`run_locked`].
pub fn run_folder(
    task: &Task,
    dir: &Path,
    out: &Path,
    opts: &RunOptions,
) -> Result<FolderRun, FolderError> {
    let lock = lock(out)?;
    run_locked(&lock, task, dir, out, opts)
}

/// The one implementation of running a task folder, under the lock of
/// `out` already taken ([`lock`]; the command line takes it before it
/// reads the inputs): learn ([`super::run`]: `opts.synth.stop` covers the
/// whole run),
/// place, write the files ([`write_outcome`]).
pub fn run_locked(
    _held: &DirLock,
    task: &Task,
    dir: &Path,
    out: &Path,
    opts: &RunOptions,
) -> Result<FolderRun, FolderError> {
    let Outcome {
        learned,
        rules,
        placement,
    } = super::run(task, opts)?;
    let w = write_outcome(dir, out, &learned, &rules, placement, opts.learn.contact)?;
    Ok(FolderRun {
        outcome: Outcome {
            learned,
            rules,
            placement: w.placement,
        },
        out: out.to_path_buf(),
        to_place: task
            .problem
            .objects
            .iter()
            .filter(|o| !o.is_placed())
            .count(),
        backup: w.backup,
        files: w.files,
    })
}
