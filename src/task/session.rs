//! A question session on a task folder (docs/guide.md#questions) with the files of
//! `rccpack ask`: the folder lock for the whole session, `answers.json`
//! read to resume, every probe written to `probes/probe-N.json` and `.png`
//! before it is shown, and after every answer `answers.json`, `demos.json`
//! (an accepted probe) and `learned.rcc`, each atomically
//! ([`files::write_after_answer`]).
//!
//! The loop itself is [`Asker`]; this module only adds the folder, so that
//! an embedder (the Python package's `AskSession`, a GUI) asks one question
//! at a time and leaves exactly the files `rccpack ask` leaves:
//!
//! ```no_run
//! use rccpack::task::session::{Session, SessionOptions};
//!
//! let mut s = Session::open("examples/box-packing", SessionOptions::default())?;
//! while let Some(shown) = s.next_question()? {
//!     // show `shown.question.probe.scene` (or the picture `shown.png`)
//!     let acceptable = false;
//!     s.answer(&shown.question, acceptable)?;
//! }
//! println!("{:?}", s.asker().progress());
//! # Ok::<(), rccpack::task::session::SessionError>(())
//! ```

use super::{files, read_scene, read_scenes, read_statements, read_text, TaskError};
use crate::ask::{Answer, AnswersFile, AnswersFileError, AskError, AskOptions, Asker, Question};
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
}

impl Default for SessionOptions {
    fn default() -> Self {
        SessionOptions {
            ask: AskOptions::default(),
            max_questions: None,
            save: true,
        }
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

/// A question session on a task folder (see the module documentation).
#[derive(Debug)]
pub struct Session {
    dir: PathBuf,
    _lock: Option<DirLock>,
    problem: Scene,
    statements: Option<RuleSet>,
    opts: SessionOptions,
    asker: Asker,
    resumed: usize,
    asked_now: usize,
    out_of_budget: bool,
    backup: bool,
}

fn write_err(path: PathBuf) -> impl FnOnce(std::io::Error) -> SessionError {
    move |source| SessionError::Write { path, source }
}

impl Session {
    /// Start or resume the session of the task folder `dir`: take the folder
    /// lock, read `problem.json`, `demos.json`, `statements.rcc` (if any)
    /// and `answers.json` (if any), learn, and write `learned.rcc` (and
    /// `demos.json` when an abort had kept an accepted probe out of it) as
    /// `rccpack ask` does at its start ([`files::write_session_start`]).
    pub fn open(dir: impl AsRef<Path>, opts: SessionOptions) -> Result<Session, SessionError> {
        let dir = dir.as_ref().to_path_buf();
        let lock = if opts.save {
            match DirLock::try_lock(&dir) {
                Ok(Some(l)) => Some(l),
                Ok(None) => return Err(SessionError::Locked { dir }),
                Err(source) => {
                    return Err(SessionError::Lock {
                        path: dir.join(crate::fsutil::LOCK_FILE),
                        source,
                    })
                }
            }
        } else {
            None
        };
        let problem_path = dir.join(files::PROBLEM);
        let demos_path = dir.join(files::DEMOS);
        let answers_path = dir.join(files::ANSWERS);
        let problem = read_scene(&problem_path)?;
        let demos = read_scenes(&demos_path)?;
        let statements_path = dir.join(files::STATEMENTS);
        let statements = if statements_path.exists() {
            Some(read_statements(&statements_path, &demos)?)
        } else {
            None
        };
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
        let n_demos = demos.len();
        let asker = Asker::new(
            problem.clone(),
            demos,
            statements.clone(),
            answers,
            opts.ask.clone(),
        )
        .map_err(|source| {
            let path = match source {
                AskError::BadAnswer { .. } => answers_path,
                AskError::Synth(_) => problem_path,
                _ => demos_path,
            };
            ask_err(path)(source)
        })?;
        let backup = if opts.save {
            files::write_session_start(&dir, &asker, n_demos, resumed).map_err(
                |(file, source)| SessionError::Write {
                    path: dir.join(file),
                    source,
                },
            )?
        } else {
            false
        };
        Ok(Session {
            dir,
            _lock: lock,
            problem,
            statements,
            opts,
            asker,
            resumed,
            asked_now: 0,
            out_of_budget: false,
            backup,
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

    /// The next question, its probe written to `probes/probe-N.json` and
    /// drawn to `probes/probe-N.png` (when saving) as `rccpack ask` does;
    /// `None` when every held rule is settled, or when the question budget
    /// is spent ([`Session::out_of_budget`]; no probe file is written then).
    pub fn next_question(&mut self) -> Result<Option<Shown>, SessionError> {
        let next = self
            .asker
            .next_question()
            .map_err(ask_err(self.dir.join(files::PROBLEM)))?;
        let Some(question) = next else {
            return Ok(None);
        };
        if self.opts.max_questions.is_some_and(|m| self.asked_now >= m) {
            self.out_of_budget = true;
            return Ok(None);
        }
        let number = self.asker.answers().len() + 1;
        let (json, png) = if self.opts.save {
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
        Ok(Some(Shown {
            question,
            number,
            json,
            png,
        }))
    }

    /// Answer the open question (docs/guide.md#questions): accepted → the probe becomes a
    /// demonstration and learning is redone; rejected → the rule is
    /// confirmed. Then (when saving) `answers.json`, `demos.json` (accepted
    /// only) and `learned.rcc` are written, in that order, each atomically.
    pub fn answer(&mut self, question: &Question, accepted: bool) -> Result<&Answer, SessionError> {
        self.asker
            .answer(question, accepted)
            .map_err(ask_err(self.dir.join(files::DEMOS)))?;
        self.asked_now += 1;
        if self.opts.save {
            files::write_after_answer(&self.dir, &self.asker, accepted).map_err(
                |(file, source)| SessionError::Write {
                    path: self.dir.join(file),
                    source,
                },
            )?;
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
                    &crate::scene::scenes_to_json(self.asker.demos()),
                )
                .map_err(write_err(dir.join(files::DEMOS)))?;
            }
            files::atomic_write(dir, files::LEARNED, &self.asker.learned_rcc())
                .map_err(write_err(dir.join(files::LEARNED)))?;
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
    let rule: Vec<_> = held
        .rules
        .iter()
        .filter(|r| r.name == q.rule)
        .take(1)
        .cloned()
        .collect();
    let ropts = RenderOptions {
        contact,
        scale: 1.0,
        title: Some(format!(
            "question {number}: is this acceptable? (breaks {})",
            q.rule
        )),
        like: None,
        moved: q
            .probe
            .edit
            .iter()
            .flat_map(|e| &e.moved)
            .map(|m| (m.id.clone(), m.x, m.y))
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
