//! `ask`: the questions of docs/guide.md#questions, answered by a Python function.

use crate::api::{contact, learn_error};
use crate::errors::{guard, AskError as PyAskError, Error, SynthError};
use crate::rules::PyRuleSet;
use crate::scene::PyScene;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rccpack_core::ask::{
    AnswersFile, AskError, AskOptions, ProbeOptions, QuestionBudget, DEFAULT_CHECK_NODES,
    DEFAULT_PROBE_NODES, DEFAULT_QUESTION_NODES,
};
use rccpack_core::infer::{LearnParams, Templates};
use rccpack_core::task::session::{Session, SessionError, SessionOptions, Shown};
use rccpack_core::Scene as CoreScene;
use std::path::PathBuf;
use std::sync::Mutex;
use std::time::Duration;

/// One question: the probe shown and (once answered) the answer.
#[pyclass(module = "rccpack", name = "Question", frozen, get_all)]
pub struct PyQuestion {
    /// Its number over every session of the folder (`probe-N`).
    number: usize,
    /// The rule asked about.
    rule: String,
    /// Its `.rcc` text after `rule NAME:`.
    statement: String,
    /// Its English reading.
    english: String,
    /// The probe layout shown.
    probe: Py<PyScene>,
    /// Objects of the probe that break the rule.
    broken: Vec<String>,
    /// Other held rules the probe breaks too.
    also_broken: Vec<String>,
    /// For a group question: every rule the probe breaks on purpose,
    /// `rule` first (acceptable: all dropped; not acceptable: at least one
    /// is meant, and the next questions find which); empty for one rule.
    group: Vec<String>,
    /// For a question about a demonstration that looks like a slip: its
    /// index in `demos.json` (the probe is that demonstration, `broken` its
    /// suspect blocks, `rule` and `also_broken` the rules it breaks);
    /// `None` for a probe.
    suspect: Option<usize>,
    /// The answer: acceptable (the rule is dropped) or not (confirmed);
    /// `None` while the question is open.
    accepted: Option<bool>,
    /// `probes/probe-N.json` (when the session saves).
    probe_file: Option<String>,
    /// `probes/probe-N.png` (when the session saves).
    picture_file: Option<String>,
}

#[pymethods]
impl PyQuestion {
    fn __repr__(&self) -> String {
        format!(
            "<Question {} {} -> {}>",
            self.number,
            self.rule,
            match self.accepted {
                Some(true) => "acceptable",
                Some(false) => "not acceptable",
                None => "open",
            }
        )
    }
}

impl PyQuestion {
    fn new(py: Python<'_>, shown: &Shown, accepted: Option<bool>) -> PyResult<Py<PyQuestion>> {
        let q = &shown.question;
        let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
        Py::new(
            py,
            PyQuestion {
                number: shown.number,
                rule: q.rule.clone(),
                statement: q.statement.clone(),
                english: q.english.clone(),
                probe: Py::new(py, PyScene::wrap(q.probe.scene.clone()))?,
                broken: q.probe.broken.clone(),
                also_broken: q.also_broken.clone(),
                group: q.group_names(),
                suspect: q.suspect.as_ref().map(|s| s.demonstration),
                accepted,
                probe_file: path(&shown.json),
                picture_file: path(&shown.png),
            },
        )
    }
}

/// What the questions changed.
#[pyclass(module = "rccpack", name = "AskResult", frozen)]
pub struct PyAskResult {
    questions: Vec<Py<PyQuestion>>,
    held: rccpack_core::RuleSet,
    learned_rcc: String,
    demos: Vec<CoreScene>,
    answers_json: String,
    progress: rccpack_core::ask::Tally,
    out_of_budget: bool,
}

#[pymethods]
impl PyAskResult {
    /// The questions of this run, in the order asked.
    #[getter]
    fn questions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, self.questions.iter().map(|q| q.clone_ref(py)))
    }
    /// The rules held now (confirmed ones carry a `confirmed` comment).
    #[getter]
    fn rules(&self) -> PyRuleSet {
        PyRuleSet::wrap(self.held.clone())
    }
    /// `learned.rcc` as `rccpack ask` leaves it.
    #[getter]
    fn learned_rcc(&self) -> &str {
        &self.learned_rcc
    }
    /// The demonstrations, accepted probes appended (`demos.json`).
    #[getter]
    fn demos(&self) -> Vec<PyScene> {
        self.demos.iter().cloned().map(PyScene::wrap).collect()
    }
    /// `answers.json` as `rccpack ask` writes it.
    #[getter]
    fn answers_json(&self) -> &str {
        &self.answers_json
    }
    /// Counts: asked, dropped, dropped_in_groups (dropped by accepted
    /// questions about a group), confirmed, implied, unknown, held,
    /// grouped (questions about a group), deduced (confirmed as the one
    /// left of a rejected group).
    #[getter]
    fn progress<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        tally(py, self.progress)
    }
    /// Whether `max_questions` stopped the loop before every rule was
    /// settled.
    #[getter]
    fn stopped_at_budget(&self) -> bool {
        self.out_of_budget
    }
    fn __repr__(&self) -> String {
        let p = self.progress;
        format!(
            "<AskResult {} questions: {} dropped, {} confirmed, {} held>",
            p.asked, p.dropped, p.confirmed, p.held
        )
    }
}

fn session_error(e: SessionError) -> PyErr {
    match e {
        SessionError::Task(e) => crate::task::task_error(*e),
        SessionError::Ask { source, path } => match *source {
            AskError::Learn(e) => learn_error(e),
            AskError::Synth(e) => {
                SynthError::new_err(format!("the problem cannot be used for probes: {e}"))
            }
            other => PyAskError::new_err(format!("{}: {other}", path.display())),
        },
        SessionError::Write { path, source } | SessionError::Lock { path, source } => {
            let errno = source.raw_os_error().unwrap_or(0);
            PyOSError::new_err((errno, source.to_string(), path.display().to_string()))
        }
        SessionError::Render { .. } => Error::new_err(e.to_string()),
        other => PyAskError::new_err(other.to_string()),
    }
}

struct State {
    session: Option<Session>,
    /// The question shown and not yet answered.
    open: Option<Shown>,
    /// The questions answered in this session, in order.
    questions: Vec<Py<PyQuestion>>,
}

/// A question session on a task folder, one question at a time, with the
/// files of `rccpack ask` (see docs/python.md).
#[pyclass(module = "rccpack", name = "AskSession", frozen)]
pub struct PyAskSession {
    state: Mutex<State>,
    dir: PathBuf,
}

fn tally<'py>(py: Python<'py>, p: rccpack_core::ask::Tally) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("asked", p.asked)?;
    d.set_item("dropped", p.dropped)?;
    d.set_item("dropped_in_groups", p.dropped_in_groups)?;
    d.set_item("confirmed", p.confirmed)?;
    d.set_item("implied", p.implied)?;
    d.set_item("unknown", p.unknown)?;
    d.set_item("held", p.held)?;
    d.set_item("grouped", p.grouped)?;
    d.set_item("deduced", p.deduced)?;
    Ok(d)
}

impl PyAskSession {
    fn with<T>(&self, f: impl FnOnce(&mut State) -> PyResult<T>) -> PyResult<T> {
        let mut state = self
            .state
            .try_lock()
            .map_err(|_| PyAskError::new_err("this AskSession is in use by another thread"))?;
        f(&mut state)
    }

    fn open_session(state: &mut State) -> PyResult<&mut Session> {
        state
            .session
            .as_mut()
            .ok_or_else(|| PyAskError::new_err("the session is closed"))
    }
}

/// Run `f` on the session with the GIL released, a panic becoming
/// `InternalError`.
fn detached<T: Send>(
    py: Python<'_>,
    session: &mut Session,
    f: impl FnOnce(&mut Session) -> Result<T, SessionError> + Send,
) -> PyResult<T> {
    py.detach(|| guard(|| f(session)))?.map_err(session_error)
}

#[pymethods]
impl PyAskSession {
    /// Start or resume the session of `task_dir` (see docs/python.md): with
    /// `save` (the default) the folder is locked, `answers.json` resumed
    /// and every file written as `rccpack ask` writes it.
    #[new]
    #[pyo3(signature = (task_dir, max_questions = None, save = true, samples = 1000,
                        cutoff = 0.01, seed = 0, time_limit = 10.0,
                        node_limit = DEFAULT_PROBE_NODES, check_nodes = DEFAULT_CHECK_NODES,
                        contact = "point", templates = "third",
                        question_nodes = DEFAULT_QUESTION_NODES, question_seconds = 3.0,
                        edits = true, priors = None, slip_rate = 0.0, groups = true))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        task_dir: PathBuf,
        max_questions: Option<usize>,
        save: bool,
        samples: usize,
        cutoff: f64,
        seed: u64,
        time_limit: Option<f64>,
        node_limit: u64,
        check_nodes: u64,
        contact: &str,
        templates: &str,
        question_nodes: u64,
        question_seconds: Option<f64>,
        edits: bool,
        priors: Option<PathBuf>,
        slip_rate: f64,
        groups: bool,
    ) -> PyResult<PyAskSession> {
        let priors = crate::priors::read_priors(py, priors)?;
        let contact = self::contact(contact)?;
        let templates: Templates = templates.parse().map_err(Error::new_err)?;
        let time_limit = crate::api::duration(time_limit)?;
        let opts = SessionOptions {
            ask: AskOptions {
                learn: LearnParams {
                    samples,
                    cutoff,
                    seed,
                    contact,
                    templates,
                    slip_rate,
                    ..LearnParams::default()
                },
                probe: ProbeOptions {
                    seed,
                    solve_time: time_limit.or(Some(Duration::from_secs(1_000_000))),
                    stop: rccpack_core::stop::Stop::never().with_nodes(node_limit.max(1)),
                    check_nodes: Some(check_nodes.max(1)),
                    ..ProbeOptions::default()
                },
                resemble: true,
                budget: QuestionBudget {
                    nodes: question_nodes.max(1),
                    wall: crate::api::duration(question_seconds)?,
                },
                edits,
                priors,
                groups,
                ..AskOptions::default()
            },
            max_questions,
            save,
            ..SessionOptions::default()
        };
        let dir = task_dir.clone();
        let session = py
            .detach(|| guard(|| Session::open(&dir, opts)))?
            .map_err(session_error)?;
        Ok(PyAskSession {
            state: Mutex::new(State {
                session: Some(session),
                open: None,
                questions: Vec::new(),
            }),
            dir: task_dir,
        })
    }

    /// The next question (its probe written to `probes/` when saving), or
    /// `None` when every held rule is settled or `max_questions` is spent.
    /// Asking again before answering returns the same question.
    fn next_question(&self, py: Python<'_>) -> PyResult<Option<Py<PyQuestion>>> {
        self.with(|state| {
            let session = Self::open_session(state)?;
            let shown = detached(py, session, |s| s.next_question())?;
            state.open = shown;
            match &state.open {
                Some(shown) => Ok(Some(PyQuestion::new(py, shown, None)?)),
                None => Ok(None),
            }
        })
    }

    /// Answer the open question: `accepted` (the layout is acceptable: the
    /// rule is dropped, the probe becomes a demonstration) or not (the rule
    /// is confirmed). Saved at once (`answers.json`, `demos.json`,
    /// `learned.rcc`). Returns the question with its answer.
    fn answer(
        &self,
        py: Python<'_>,
        question: &PyQuestion,
        accepted: bool,
    ) -> PyResult<Py<PyQuestion>> {
        self.with(|state| {
            let shown = match &state.open {
                Some(s) if s.number == question.number && s.question.rule == question.rule => {
                    s.clone()
                }
                _ => {
                    return Err(PyAskError::new_err(format!(
                        "question {} (rule `{}`) is not the open question; call next_question()",
                        question.number, question.rule
                    )))
                }
            };
            let session = Self::open_session(state)?;
            let rule = shown.question.rule.clone();
            detached(py, session, move |s| s.answer(&rule, accepted).map(|_| ()))?;
            state.open = None;
            let answered = PyQuestion::new(py, &shown, Some(accepted))?;
            state.questions.push(answered.clone_ref(py));
            Ok(answered)
        })
    }

    /// Take back the last answer (also one of an earlier session): the
    /// loop restarts from the answers before it and the files are
    /// rewritten. Returns the rule of the answer taken back, `None` when
    /// nothing was answered.
    fn undo(&self, py: Python<'_>) -> PyResult<Option<String>> {
        self.with(|state| {
            let session = Self::open_session(state)?;
            let undone = detached(py, session, |s| s.undo())?;
            state.open = None;
            if undone.is_some() {
                state.questions.pop();
            }
            Ok(undone.map(|a| a.rule))
        })
    }

    /// Counts: asked (over every session), dropped, confirmed, implied,
    /// unknown, held.
    #[getter]
    fn progress<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.with(|state| tally(py, Self::open_session(state)?.asker().progress()))
    }
    /// The questions answered in this session.
    #[getter]
    fn questions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        self.with(|state| PyTuple::new(py, state.questions.iter().map(|q| q.clone_ref(py))))
    }
    /// Answers read from `answers.json` when the session started.
    #[getter]
    fn resumed(&self) -> PyResult<usize> {
        self.with(|state| Ok(Self::open_session(state)?.resumed()))
    }
    /// Whether `max_questions` stopped the questions.
    #[getter]
    fn stopped_at_budget(&self) -> PyResult<bool> {
        self.with(|state| Ok(Self::open_session(state)?.out_of_budget()))
    }
    /// Whether the start kept a different `learned.rcc` as
    /// `learned.rcc.bak`.
    #[getter]
    fn backup_written(&self) -> PyResult<bool> {
        self.with(|state| Ok(Self::open_session(state)?.backup_written()))
    }
    /// The rules held now (confirmed ones carry a `confirmed` comment).
    #[getter]
    fn rules(&self) -> PyResult<PyRuleSet> {
        self.with(|state| {
            Ok(PyRuleSet::wrap(
                Self::open_session(state)?.asker().held().clone(),
            ))
        })
    }
    /// `learned.rcc` as `rccpack ask` leaves it.
    #[getter]
    fn learned_rcc(&self) -> PyResult<String> {
        self.with(|state| Ok(Self::open_session(state)?.asker().learned_rcc()))
    }
    /// The demonstrations, accepted probes appended (`demos.json`).
    #[getter]
    fn demos(&self) -> PyResult<Vec<PyScene>> {
        self.with(|state| {
            Ok(Self::open_session(state)?
                .asker()
                .demos()
                .iter()
                .cloned()
                .map(PyScene::wrap)
                .collect())
        })
    }
    /// `answers.json` as `rccpack ask` writes it.
    #[getter]
    fn answers_json(&self) -> PyResult<String> {
        self.with(|state| {
            Ok(AnswersFile {
                answers: Self::open_session(state)?.asker().answers().to_vec(),
            }
            .to_json())
        })
    }
    /// The task folder, as given.
    #[getter]
    fn dir(&self) -> String {
        self.dir.display().to_string()
    }
    /// Whether `close()` was called.
    #[getter]
    fn closed(&self) -> PyResult<bool> {
        self.with(|state| Ok(state.session.is_none()))
    }
    /// A snapshot: the questions of this session, the rules and files.
    fn result(&self, py: Python<'_>) -> PyResult<PyAskResult> {
        self.with(|state| {
            let questions = state.questions.iter().map(|q| q.clone_ref(py)).collect();
            let s = Self::open_session(state)?;
            let asker = s.asker();
            Ok(PyAskResult {
                questions,
                held: asker.held().clone(),
                learned_rcc: asker.learned_rcc(),
                demos: asker.demos().to_vec(),
                answers_json: AnswersFile {
                    answers: asker.answers().to_vec(),
                }
                .to_json(),
                progress: asker.progress(),
                out_of_budget: s.out_of_budget(),
            })
        })
    }
    /// End the session and release the folder lock (every answer is
    /// already saved). Idempotent.
    fn close(&self) -> PyResult<()> {
        self.with(|state| {
            state.session = None;
            state.open = None;
            Ok(())
        })
    }
    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }
    #[pyo3(signature = (*_args))]
    fn __exit__(&self, _args: &Bound<'_, PyTuple>) -> PyResult<bool> {
        self.close()?;
        Ok(false)
    }
    fn __repr__(&self) -> String {
        match self.state.try_lock() {
            Ok(state) => match &state.session {
                Some(s) => {
                    let p = s.asker().progress();
                    format!(
                        "<AskSession {}: {} asked, {} dropped, {} confirmed, {} held>",
                        self.dir.display(),
                        p.asked,
                        p.dropped,
                        p.confirmed,
                        p.held
                    )
                }
                None => format!("<AskSession {} (closed)>", self.dir.display()),
            },
            Err(_) => format!("<AskSession {} (busy)>", self.dir.display()),
        }
    }
}

/// Run the questions of docs/guide.md#questions on the task folder `task_dir` with
/// `oracle(probe) -> bool` answering "is this layout acceptable?": a loop
/// over `AskSession`. With `save=False` (the default) nothing is read but
/// the task and nothing is written; with `save=True` it resumes from
/// `answers.json` and writes every file as `rccpack ask` does.
#[pyfunction]
#[pyo3(signature = (task_dir, oracle, max_questions = None, save = false, samples = 1000,
                    cutoff = 0.01, seed = 0, time_limit = 10.0,
                    node_limit = DEFAULT_PROBE_NODES, check_nodes = DEFAULT_CHECK_NODES,
                    contact = "point", templates = "third",
                    question_nodes = DEFAULT_QUESTION_NODES, question_seconds = 3.0,
                    edits = true, priors = None, slip_rate = 0.0, groups = true))]
#[allow(clippy::too_many_arguments)]
pub fn ask(
    py: Python<'_>,
    task_dir: PathBuf,
    oracle: Bound<'_, PyAny>,
    max_questions: Option<usize>,
    save: bool,
    samples: usize,
    cutoff: f64,
    seed: u64,
    time_limit: Option<f64>,
    node_limit: u64,
    check_nodes: u64,
    contact: &str,
    templates: &str,
    question_nodes: u64,
    question_seconds: Option<f64>,
    edits: bool,
    priors: Option<PathBuf>,
    slip_rate: f64,
    groups: bool,
) -> PyResult<PyAskResult> {
    let session = PyAskSession::new(
        py,
        task_dir,
        max_questions,
        save,
        samples,
        cutoff,
        seed,
        time_limit,
        node_limit,
        check_nodes,
        contact,
        templates,
        question_nodes,
        question_seconds,
        edits,
        priors,
        slip_rate,
        groups,
    )?;
    let run = || -> PyResult<PyAskResult> {
        while let Some(q) = session.next_question(py)? {
            let accepted = oracle.call1((q.get().probe.clone_ref(py),))?.is_truthy()?;
            session.answer(py, q.get(), accepted)?;
        }
        session.result(py)
    };
    let out = run();
    session.close()?;
    out
}
