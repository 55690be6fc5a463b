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
use crate::ask::{
    Answer, AnswersFile, AnswersFileError, AskError, AskOptions, Asker, Lookahead, Question,
};
use crate::fsutil::DirLock;
use crate::render::{render_to_path, RenderError, RenderOptions};
use crate::rules::RuleSet;
use crate::scene::Scene;
use std::path::{Path, PathBuf};

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

fn take_lock(dir: &Path) -> Result<DirLock, SessionError> {
    match DirLock::try_lock(dir) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err(SessionError::Locked {
            dir: dir.to_path_buf(),
        }),
        Err(source) => Err(SessionError::Lock {
            path: dir.join(crate::fsutil::LOCK_FILE),
            source,
        }),
    }
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
    /// Start or resume the session of the task folder `dir`: take the folder
    /// lock ([`Locking::Session`]), read `problem.json`, `demos.json`,
    /// `statements.rcc` (if any) and `answers.json` (if any), learn, and
    /// write `learned.rcc` (and `demos.json` when an abort had kept an
    /// accepted probe out of it) as `rccpack ask` does at its start
    /// ([`files::write_session_start`]).
    pub fn open(dir: impl AsRef<Path>, opts: SessionOptions) -> Result<Session, SessionError> {
        let dir = dir.as_ref();
        let lock = if opts.save && opts.locking == Locking::Session {
            Some(take_lock(dir)?)
        } else {
            None
        };
        let inputs = SessionInputs::read(dir)?;
        let mut s = Session::open_with(dir, inputs, opts)?;
        s._lock = lock;
        Ok(s)
    }

    /// [`Session::open`] with the task's inputs read by the caller (the
    /// studio reads them with its own errors); `answers.json` is read here.
    /// With [`Locking::Session`] the caller's lock is not taken: hold it, or
    /// use [`Session::open`].
    pub fn open_with(
        dir: impl AsRef<Path>,
        inputs: SessionInputs,
        opts: SessionOptions,
    ) -> Result<Session, SessionError> {
        let dir = dir.as_ref().to_path_buf();
        let answers_path = dir.join(files::ANSWERS);
        let answers = if opts.save && answers_path.exists() {
            AnswersFile::from_json(&read_text(&answers_path)?)
                .map_err(|source| SessionError::Answers {
                    path: answers_path.clone(),
                    source,
                })?
                .answers
        } else {
            Vec::new()
        };
        let resumed = answers.len();
        let SessionInputs {
            problem,
            demos,
            statements,
        } = inputs;
        let asker = Asker::new(
            problem.clone(),
            demos.scenes.clone(),
            statements.clone(),
            answers,
            opts.ask.clone(),
        )
        .map_err(|e| ask_err(ask_path(&dir, &e))(e))?;
        let backup = if opts.save {
            files::write_session_start(&dir, &asker, &demos, resumed).map_err(
                |(file, source)| SessionError::Write {
                    path: dir.join(file),
                    source,
                },
            )?
        } else {
            false
        };
        let versions = if opts.save {
            disk_versions(&dir)?
        } else {
            Default::default()
        };
        Ok(Session {
            dir,
            _lock: None,
            problem,
            statements,
            opts,
            asker,
            open: None,
            prepared: None,
            resumed,
            asked_now: 0,
            out_of_budget: false,
            backup,
            versions,
            demos_read: demos,
        })
    }

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
        self.opts.ask.probe.cancel = flag.clone();
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

    /// The next question, its probe written to `probes/probe-N.json` and
    /// drawn to `probes/probe-N.png` (when saving) as `rccpack ask` does;
    /// `None` when every held rule is settled, or when the question budget
    /// is spent ([`Session::out_of_budget`]; no probe file is written then).
    /// Asking again before answering returns the same question.
    pub fn next_question(&mut self) -> Result<Option<Shown>, SessionError> {
        if let Some(open) = &self.open {
            return Ok(Some(open.shown.clone()));
        }
        let next = match self.prepared.take() {
            Some(q) => q,
            None => self
                .asker
                .next_question()
                .map_err(ask_err(self.dir.join(files::PROBLEM)))?,
        };
        let Some(question) = next else {
            return Ok(None);
        };
        if self.opts.max_questions.is_some_and(|m| self.asked_now >= m) {
            self.out_of_budget = true;
            self.prepared = Some(Some(question));
            return Ok(None);
        }
        let number = self.asker.answers().len() + 1;
        let (json, png) = if self.opts.save && self.opts.probe_files {
            let (j, p) = write_probe_files(
                &self.dir,
                self.asker.held(),
                &question,
                number,
                self.opts.ask.probe.contact,
            )?;
            (Some(j), Some(p))
        } else {
            (None, None)
        };
        let ahead = self
            .asker
            .look_ahead(&question, self.opts.lookahead_threads);
        let shown = Shown {
            question,
            number,
            json,
            png,
        };
        self.open = Some(Open {
            shown: shown.clone(),
            ahead,
        });
        Ok(Some(shown))
    }

    /// Refuse to write when a file changed on disk since the session read
    /// or wrote it.
    fn check_unchanged(&self) -> Result<(), SessionError> {
        if self.files_changed()? {
            return Err(SessionError::Changed {
                dir: self.dir.clone(),
            });
        }
        Ok(())
    }

    /// Answer the open question, about `rule` (docs/guide.md#questions):
    /// accepted → the probe becomes a demonstration and learning is redone;
    /// rejected → the rule is confirmed. When saving, the answer is
    /// journaled in `answers.json` before it is applied, then `demos.json`
    /// (accepted only) and `learned.rcc` are written, each atomically.
    pub fn answer(&mut self, rule: &str, accepted: bool) -> Result<&Answer, SessionError> {
        let open_rule = self.open.as_ref().map(|o| o.shown.question.rule.clone());
        if open_rule.as_deref() != Some(rule) {
            return Err(SessionError::NotOpen {
                rule: rule.to_string(),
                open: open_rule,
            });
        }
        if self.opts.save {
            // Before the question is taken: refused, it stays open.
            self.check_unchanged()?;
        }
        let open = self.open.take().expect("checked above");
        if self.opts.save {
            let mut answers = self.asker.answers().to_vec();
            answers.push(self.asker.answer_record(&open.shown.question, accepted));
            files::atomic_write(
                &self.dir,
                files::ANSWERS,
                &AnswersFile { answers }.to_json(),
            )
            .map_err(write_err(self.dir.join(files::ANSWERS)))?;
            self.versions = disk_versions(&self.dir)?;
        }
        let (asker, next) = open
            .ahead
            .answer(accepted)
            .map_err(|e| ask_err(ask_path(&self.dir, &e))(e))?;
        self.asker = asker;
        self.prepared = Some(next);
        self.asked_now += 1;
        if self.opts.save {
            self.check_unchanged()?;
            files::write_after_answer(&self.dir, &self.asker, &self.demos_read, accepted).map_err(
                |(file, source)| SessionError::Write {
                    path: self.dir.join(file),
                    source,
                },
            )?;
            self.versions = disk_versions(&self.dir)?;
        }
        Ok(self.asker.answers().last().expect("just answered"))
    }

    /// Take back the last answer (of this session or an earlier one): the
    /// loop restarts from the answers before it, as a resumed session
    /// would (an accepted probe leaves the demonstrations again), and the
    /// files are rewritten. `None` when nothing was answered. What earlier
    /// checks found is not kept, so the next question is the one a resumed
    /// session asks (the same as before unless a check reaches its node
    /// budget).
    pub fn undo(&mut self) -> Result<Option<Answer>, SessionError> {
        let mut answers = self.asker.answers().to_vec();
        let Some(last) = answers.pop() else {
            return Ok(None);
        };
        if self.opts.save {
            self.check_unchanged()?;
        }
        let mut demos = self.asker.demos().to_vec();
        if last.accepted && last.demo == Some(demos.len().saturating_sub(1)) {
            demos.pop();
        }
        let asker = Asker::new(
            self.problem.clone(),
            demos,
            self.statements.clone(),
            answers,
            self.opts.ask.clone(),
        )
        .map_err(ask_err(self.dir.join(files::ANSWERS)))?;
        self.asker = asker;
        self.open = None;
        self.prepared = None;
        self.asked_now = self.asked_now.saturating_sub(1);
        self.out_of_budget = false;
        if self.opts.save {
            let file = AnswersFile {
                answers: self.asker.answers().to_vec(),
            };
            let dir = &self.dir;
            files::atomic_write(dir, files::ANSWERS, &file.to_json())
                .map_err(write_err(dir.join(files::ANSWERS)))?;
            if last.accepted {
                files::atomic_write(
                    dir,
                    files::DEMOS,
                    &self.demos_read.to_json(self.asker.demos()),
                )
                .map_err(write_err(dir.join(files::DEMOS)))?;
            }
            files::atomic_write(dir, files::LEARNED, &self.asker.learned_rcc())
                .map_err(write_err(dir.join(files::LEARNED)))?;
            self.versions = disk_versions(&self.dir)?;
        }
        Ok(Some(last))
    }
}

/// Write a question's probe as `rccpack ask` does: `probes/probe-N.json`
/// (the scene) and `probes/probe-N.png` (drawn with the question's rule,
/// titled `question N: is this acceptable? (breaks RULE)`). Returns the two
/// paths.
pub fn write_probe_files(
    dir: &Path,
    held: &RuleSet,
    q: &Question,
    number: usize,
    contact: crate::relations::Contact,
) -> Result<(PathBuf, PathBuf), SessionError> {
    let probes = dir.join(files::PROBES);
    std::fs::create_dir_all(&probes).map_err(write_err(probes.clone()))?;
    let json = probes.join(format!("probe-{number}.json"));
    let png = probes.join(format!("probe-{number}.png"));
    crate::fsutil::atomic_write(&json, q.probe.scene.to_json()).map_err(write_err(json.clone()))?;
    // The rules the question is about: the probed one, or every rule a
    // suspect demonstration breaks.
    let about: Vec<&str> = match &q.suspect {
        Some(s) => s.breaks.iter().map(String::as_str).collect(),
        None if !q.group.is_empty() => q.group.iter().map(|g| g.rule.as_str()).collect(),
        None => vec![q.rule.as_str()],
    };
    let rule: Vec<_> = held
        .rules
        .iter()
        .filter(|r| about.contains(&r.name.as_str()))
        .cloned()
        .collect();
    let title = match &q.suspect {
        Some(s) => format!(
            "question {number}: demonstration {} as you meant it? (breaks {} rule{} the others keep)",
            s.demonstration,
            s.breaks.len(),
            if s.breaks.len() == 1 { "" } else { "s" }
        ),
        // The legend lists them.
        None if !q.group.is_empty() => format!(
            "question {number}: is this acceptable? (breaks {} rules)",
            q.group.len()
        ),
        None => format!("question {number}: is this acceptable? (breaks {})", q.rule),
    };
    let ropts = RenderOptions {
        contact,
        scale: 1.0,
        title: Some(title),
        like: None,
        moved: q
            .probe
            .edit
            .iter()
            .flat_map(|e| &e.moved)
            .map(|m| (m.id.clone(), m.x, m.y))
            .collect(),
        outlined: q
            .suspect
            .as_ref()
            .and_then(|s| s.objects.first().cloned())
            .into_iter()
            .collect(),
    };
    render_to_path(&q.probe.scene, Some(&RuleSet::new(rule)), &ropts, &png).map_err(|source| {
        SessionError::Render {
            path: png.clone(),
            source,
        }
    })?;
    Ok((json, png))
}
