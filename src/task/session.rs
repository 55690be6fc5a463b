//! The question session on a task folder (docs/guide.md#questions): the
//! only implementation of it. `rccpack ask`, the studio's "Check rules"
//! and the Python package's `AskSession` are adapters: they read their
//! inputs, call this, and show the questions and errors in their own words.
//!
//! A session keeps the files of `rccpack ask`: the folder lock (for the
//! whole session, or held by the caller around each call, see
//! [`Locking`]), `answers.json` read to resume, every probe written to
//! `probes/probe-N.json` and `.png` before it is shown, and for every
//! answer the journal first (`answers.json`, before the answer is applied,
//! so an abort during the relearning loses nothing), then `demos.json` (an
//! accepted probe) and `learned.rcc`, each atomically
//! ([`files::write_after_answer`]). A file changed on disk since the
//! session read or wrote it (a hand edit) is never overwritten:
//! [`SessionError::Changed`].
//!
//! While a question waits for its answer, the session can compute the
//! next question for both answers ([`SessionOptions::lookahead_threads`],
//! [`crate::ask::Lookahead`]); the questions are the same either way.
//!
//! The loop itself is [`Asker`]; this module adds the folder, so that an
//! embedder asks one question at a time and leaves exactly the files
//! `rccpack ask` leaves:
//!
//! ```no_run
//! use rccpack::task::session::{Session, SessionOptions};
//!
//! let mut s = Session::open("examples/box-packing", SessionOptions::default())?;
//! while let Some(shown) = s.next_question()? {
//!     // show `shown.question.probe.scene` (or the picture `shown.png`)
//!     let acceptable = false;
//!     s.answer(&shown.question.rule, acceptable)?;
//! }
//! println!("{:?}", s.asker().progress());
//! # Ok::<(), rccpack::task::session::SessionError>(())
//! ```

use super::{files, read_scene, read_statements, read_text, TaskError};
use crate::ask::{AnswersFileError, AskError, AskOptions, Asker, Lookahead, Question};
use crate::fsutil::DirLock;
use crate::render::RenderError;
use crate::rules::RuleSet;
use crate::scene::Scene;
use std::path::{Path, PathBuf};

mod answer;
mod open;
mod probes;

pub use probes::write_probe_files;

/// Why a session cannot start or go on. Every variant names its file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SessionError {
    /// Another session (`rccpack ask`, the studio, another [`Session`])
    /// holds the folder lock.
    #[error("{}: another `rccpack ask` or the studio is writing this task folder (it holds {}); wait until it ends, then run again", dir.display(), crate::fsutil::LOCK_FILE)]
    Locked {
        /// The task folder.
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
    /// `problem.json`, `demos.json` or `statements.rcc` cannot be read.
    #[error(transparent)]
    Task(Box<TaskError>),
    /// `answers.json` is not an answers file.
    #[error("{}: {source}", path.display())]
    Answers {
        /// The file.
        path: PathBuf,
        /// The field and what is wrong.
        source: AnswersFileError,
    },
    /// The question loop refused: learning, the problem, or an answer that
    /// does not fit (`path` is the file at fault).
    #[error("{}: {source}", path.display())]
    Ask {
        /// The file at fault.
        path: PathBuf,
        /// The error.
        source: Box<AskError>,
    },
    /// An answer names a rule no open question asks about.
    #[error("rule: no question about rule `{rule}` is open; {}", match open {
        Some(o) => format!("the open question is about rule `{o}`"),
        None => "no question is open (ask for the next question first)".to_string(),
    })]
    NotOpen {
        /// The rule the answer names.
        rule: String,
        /// The rule of the open question, if any.
        open: Option<String>,
    },
    /// `demos.json`, `learned.rcc` or `answers.json` changed on disk since
    /// the session read or wrote it (a hand edit, another program):
    /// nothing was written.
    #[error("{}: {DEMOS_LEARNED_ANSWERS} changed on disk since the session read them; nothing was written and nothing was overwritten — start the session again", dir.display())]
    Changed {
        /// The task folder.
        dir: PathBuf,
    },
    /// A file or folder cannot be written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A probe picture cannot be drawn.
    #[error("{}: {source}", path.display())]
    Render {
        /// The picture.
        path: PathBuf,
        /// Why.
        source: RenderError,
    },
}

const DEMOS_LEARNED_ANSWERS: &str = "demos.json, learned.rcc or answers.json";

impl From<TaskError> for SessionError {
    fn from(e: TaskError) -> Self {
        SessionError::Task(Box::new(e))
    }
}

fn ask_err(path: PathBuf) -> impl FnOnce(AskError) -> SessionError {
    move |source| SessionError::Ask {
        path,
        source: Box::new(source),
    }
}

/// Who holds the task folder's lock (`.rccpack.lock`) while a session
/// writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Locking {
    /// The session takes it when it opens and keeps it until it is
    /// dropped (`rccpack ask`, Python).
    #[default]
    Session,
    /// The caller holds it around every call that writes ([`Session::open`],
    /// [`Session::answer`], [`Session::undo`]); the studio, which lets the
    /// folder go between requests.
    Caller,
}

/// Options of [`Session::open`].
#[derive(Debug, Clone)]
pub struct SessionOptions {
    /// The loop's settings (learning, probes).
    pub ask: AskOptions,
    /// Ask at most this many questions in this session (answers of earlier
    /// sessions do not count), as `rccpack ask --max-questions`.
    pub max_questions: Option<usize>,
    /// Lock the folder, resume from `answers.json` and write every file as
    /// `rccpack ask` does (the default). Off: nothing is read but the task
    /// and nothing is written; the session starts afresh and lives in
    /// memory.
    pub save: bool,
    /// Who holds the folder lock (when saving).
    pub locking: Locking,
    /// Write every question's probe to `probes/probe-N.json` and `.png`
    /// (when saving; the default). The studio draws its own.
    pub probe_files: bool,
    /// Threads for computing the next question for both answers while a
    /// question waits; below 2, nothing is computed ahead (the default).
    pub lookahead_threads: usize,
}

impl Default for SessionOptions {
    fn default() -> Self {
        SessionOptions {
            ask: AskOptions::default(),
            max_questions: None,
            save: true,
            locking: Locking::Session,
            probe_files: true,
            lookahead_threads: 1,
        }
    }
}

/// What a session reads from a task folder before it starts: the problem
/// the probes place, the demonstrations and the statements (`None`: the
/// templates of [`AskOptions::learn`]).
#[derive(Debug, Clone)]
pub struct SessionInputs {
    /// The problem (`problem.json`).
    pub problem: Scene,
    /// The demonstrations (`demos.json`, read as measured: a measured
    /// file's recorded entries are kept by every write).
    pub demos: files::DemosFile,
    /// The statements (`statements.rcc`), if any.
    pub statements: Option<RuleSet>,
}

impl SessionInputs {
    /// Read `problem.json`, `demos.json` and `statements.rcc` (if any) of
    /// the task folder `dir`.
    pub fn read(dir: &Path) -> Result<SessionInputs, SessionError> {
        let problem = read_scene(&dir.join(files::PROBLEM))?;
        let demos_path = dir.join(files::DEMOS);
        let demos = files::DemosFile::parse(&read_text(&demos_path)?).map_err(|source| {
            TaskError::Scene {
                path: demos_path,
                source,
            }
        })?;
        let statements_path = dir.join(files::STATEMENTS);
        let statements = if statements_path.exists() {
            Some(read_statements(&statements_path, &demos.scenes)?)
        } else {
            None
        };
        Ok(SessionInputs {
            problem,
            demos,
            statements,
        })
    }
}

/// A question, numbered as `rccpack ask` numbers it, with its files.
#[derive(Debug, Clone)]
pub struct Shown {
    /// The question (answer it with [`Session::answer`]).
    pub question: Question,
    /// Its number over every session of the folder (1 for the first).
    pub number: usize,
    /// `probes/probe-N.json` (when saving).
    pub json: Option<PathBuf>,
    /// `probes/probe-N.png` (when saving).
    pub png: Option<PathBuf>,
}

/// The question shown and not answered yet.
struct Open {
    shown: Shown,
    /// The session after each answer to it, being computed.
    ahead: Lookahead,
}

/// Versions ([`files::version`]) of demos.json, learned.rcc and
/// answers.json as the session last read or wrote them.
type Versions = [String; 3];

/// A question session on a task folder (see the module documentation).
pub struct Session {
    dir: PathBuf,
    _lock: Option<DirLock>,
    problem: Scene,
    statements: Option<RuleSet>,
    opts: SessionOptions,
    asker: Asker,
    open: Option<Open>,
    /// The next question, computed ahead with the last answer.
    prepared: Option<Option<Question>>,
    resumed: usize,
    asked_now: usize,
    out_of_budget: bool,
    backup: bool,
    versions: Versions,
    /// `demos.json` as read (its recorded entries kept by every write).
    demos_read: files::DemosFile,
}

impl std::fmt::Debug for Session {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Session")
            .field("dir", &self.dir)
            .field("asker", &self.asker)
            .field("open", &self.open.as_ref().map(|o| &o.shown))
            .field("resumed", &self.resumed)
            .field("asked_now", &self.asked_now)
            .finish_non_exhaustive()
    }
}

fn write_err(path: PathBuf) -> impl FnOnce(std::io::Error) -> SessionError {
    move |source| SessionError::Write { path, source }
}

/// The versions of demos.json, learned.rcc and answers.json on disk.
fn disk_versions(dir: &Path) -> Result<Versions, SessionError> {
    let one = |name: &'static str| {
        files::read_optional(dir, name)
            .map(|t| files::version(t.as_deref()))
            .map_err(|source| SessionError::Write {
                path: dir.join(name),
                source,
            })
    };
    Ok([
        one(files::DEMOS)?,
        one(files::LEARNED)?,
        one(files::ANSWERS)?,
    ])
}

/// Which file an error of the loop is about.
fn ask_path(dir: &Path, e: &AskError) -> PathBuf {
    dir.join(match e {
        AskError::BadAnswer { .. } => files::ANSWERS,
        AskError::Synth(_) => files::PROBLEM,
        _ => files::DEMOS,
    })
}

impl Session {
    /// The loop (held rules, demonstrations, answers, progress).
    pub fn asker(&self) -> &Asker {
        &self.asker
    }

    /// The task folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The problem the probes place.
    pub fn problem(&self) -> &Scene {
        &self.problem
    }

    /// The options the session was opened with.
    pub fn options(&self) -> &SessionOptions {
        &self.opts
    }

    /// Answers read from `answers.json` when the session started.
    pub fn resumed(&self) -> usize {
        self.resumed
    }

    /// Questions answered in this session.
    pub fn asked_now(&self) -> usize {
        self.asked_now
    }

    /// Whether [`SessionOptions::max_questions`] stopped the questions
    /// before every rule was settled.
    pub fn out_of_budget(&self) -> bool {
        self.out_of_budget
    }

    /// Whether the start kept a different `learned.rcc` as
    /// `learned.rcc.bak` (a first session, docs/guide.md#questions).
    pub fn backup_written(&self) -> bool {
        self.backup
    }

    /// Stop learning and every probe search when `flag` is set (`None`:
    /// never), for the session's options and its loop.
    #[cfg(feature = "studio")]
    pub(crate) fn set_cancel(
        &mut self,
        flag: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    ) {
        self.opts.ask.probe.stop = self.opts.ask.probe.stop.clone().cancel_with(flag.clone());
        self.asker.set_cancel(flag);
    }

    /// The question shown and not answered yet.
    pub fn open_question(&self) -> Option<&Shown> {
        self.open.as_ref().map(|o| &o.shown)
    }

    /// Whether `demos.json`, `learned.rcc` or `answers.json` changed on
    /// disk since the session last read or wrote them (always `false` when
    /// not saving).
    pub fn files_changed(&self) -> Result<bool, SessionError> {
        Ok(self.opts.save && disk_versions(&self.dir)? != self.versions)
    }
}
