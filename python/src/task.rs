//! `Task`: a task folder and the pipeline of `rccpack run` on it
//! (`rccpack_core::task`, `rccpack_core::task::folder`).

use crate::api::{
    contact, duration, learn_error, learn_interruptible, run_interruptible, templates, PyLearned,
    PySynthResult,
};
use crate::errors::{rules_error, scene_error, Error, RulesError, SynthError};
use crate::rules::PyRuleSet;
use crate::scene::{scenes_arg, PyScene};
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError};
use pyo3::prelude::*;
use pyo3::types::PyString;
use rccpack_core::infer::LearnParams;
use rccpack_core::task::folder::{self, FolderError};
use rccpack_core::task::{Like, RunOptions, Task as CoreTask, TaskError};
use rccpack_core::SynthOptions;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

fn io_error(path: &std::path::Path, e: &std::io::Error) -> PyErr {
    // OSError(errno, strerror, filename) is FileNotFoundError,
    // PermissionError, … by its errno, as `open` raises.
    let errno = e.raw_os_error().unwrap_or(0);
    PyOSError::new_err((errno, e.to_string(), path.display().to_string()))
}

/// A pipeline error as the Python exception of the same kind.
pub(crate) fn task_error(e: TaskError) -> PyErr {
    match e {
        TaskError::Read { path, source } => io_error(&path, &source),
        TaskError::Scene { path, source } => scene_error(source, Some(&path.display().to_string())),
        TaskError::Rules { path, text, source } => {
            rules_error(&source, &text, &path.display().to_string())
        }
        TaskError::Learn(e) => learn_error(e),
        TaskError::Landmark(e) => RulesError::new_err(format!(
            "the learned rules name a landmark the problem lacks: {e}"
        )),
        TaskError::Synth(e) => SynthError::new_err(e.to_string()),
        other => Error::new_err(other.to_string()),
    }
}

fn folder_error(e: FolderError) -> PyErr {
    match e {
        FolderError::Task(e) => task_error(e),
        FolderError::Write { path, source }
        | FolderError::CreateDir { path, source }
        | FolderError::Lock { path, source } => io_error(&path, &source),
        other => Error::new_err(other.to_string()),
    }
}

/// `like=`: `"demos"` (the task's demonstrations, the default), `None`
/// (off) or scenes.
pub(crate) struct LikeArg(Like);

impl<'a, 'py> FromPyObject<'a, 'py> for LikeArg {
    type Error = PyErr;
    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if obj.is_none() {
            return Ok(LikeArg(Like::Off));
        }
        if obj.is_instance_of::<PyString>() {
            return match obj.extract::<String>()?.as_str() {
                "demos" => Ok(LikeArg(Like::Demos)),
                other => Err(Error::new_err(format!(
                    "invalid like {other:?}: expected \"demos\", None or scenes"
                ))),
            };
        }
        Ok(LikeArg(Like::Scenes(scenes_arg(&obj.to_owned(), "like")?)))
    }
}

const DEMOS: LikeArg = LikeArg(Like::Demos);

/// A task folder (docs/cli.md): `demos.json`, `problem.json` and, when
/// present, `statements.rcc`, read as `rccpack run` reads them.
#[pyclass(module = "rccpack", name = "Task", frozen)]
pub struct PyTask {
    dir: PathBuf,
    inner: CoreTask,
}

/// What `Task.run` produced: what `rccpack run` writes and prints.
#[pyclass(module = "rccpack", name = "RunOutcome", frozen)]
pub struct PyRunOutcome {
    learned: Py<PyLearned>,
    result: Py<PySynthResult>,
    missing_classes: Vec<String>,
    summary: String,
    message: Option<String>,
    exit_code: u8,
    files: Vec<String>,
}

#[pymethods]
impl PyRunOutcome {
    /// What learning found (`learned.rcc`, `learn-report.json`).
    #[getter]
    fn learned(&self, py: Python<'_>) -> Py<PyLearned> {
        self.learned.clone_ref(py)
    }
    /// The learned rules.
    #[getter]
    fn rules(&self, py: Python<'_>) -> PyRuleSet {
        let _ = py;
        PyRuleSet::wrap(self.learned.get().inner.rules())
    }
    /// The synthesis result (`solution.json` is `result.scene`).
    #[getter]
    fn result(&self, py: Python<'_>) -> Py<PySynthResult> {
        self.result.clone_ref(py)
    }
    /// The layout (`None` when infeasible or unknown).
    #[getter]
    fn scene(&self) -> Option<PyScene> {
        self.result.get().inner.scene.clone().map(PyScene::wrap)
    }
    /// Classes the rules name that the problem lacks (docs/language.md#classes-a-scene-lacks).
    #[getter]
    fn missing_classes(&self) -> Vec<String> {
        self.missing_classes.clone()
    }
    /// What `rccpack run` prints on standard output.
    #[getter]
    fn summary(&self) -> &str {
        &self.summary
    }
    /// What it prints on standard error (`infeasible: …`, `unknown: …`).
    #[getter]
    fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }
    /// Its exit code: 0 a layout, 2 infeasible, 3 a limit before any.
    #[getter]
    fn exit_code(&self) -> u8 {
        self.exit_code
    }
    /// The files written, in order.
    #[getter]
    fn files(&self) -> Vec<String> {
        self.files.clone()
    }
    fn __repr__(&self) -> String {
        format!(
            "<RunOutcome exit {}: {}>",
            self.exit_code,
            self.summary.lines().last().unwrap_or("")
        )
    }
}

#[pymethods]
impl PyTask {
    /// Read the task folder `dir` (`rccpack_core::task::Task::load`).
    #[staticmethod]
    fn load(py: Python<'_>, dir: PathBuf) -> PyResult<PyTask> {
        let d = dir.clone();
        let inner = py
            .detach(|| crate::errors::guard(|| CoreTask::load(&d)))?
            .map_err(task_error)?;
        Ok(PyTask { dir, inner })
    }
    /// The folder, as given.
    #[getter]
    fn dir(&self) -> String {
        self.dir.display().to_string()
    }
    /// The demonstrations (`demos.json`).
    #[getter]
    fn demos(&self) -> Vec<PyScene> {
        self.inner
            .demos
            .iter()
            .cloned()
            .map(PyScene::wrap)
            .collect()
    }
    /// The problem (`problem.json`).
    #[getter]
    fn problem(&self) -> PyScene {
        PyScene::wrap(self.inner.problem.clone())
    }
    /// The statements to learn (`statements.rcc`), `None` for the templates.
    #[getter]
    fn statements(&self) -> Option<PyRuleSet> {
        self.inner.statements.clone().map(PyRuleSet::wrap)
    }

    /// Learn from the demonstrations (and `statements.rcc`) as `rccpack
    /// run` does; nothing is written. `time_limit`: `LearnError` after it.
    /// Ctrl-C stops it (`KeyboardInterrupt`).
    #[pyo3(signature = (samples = 1000, cutoff = 0.01, seed = 0, templates = "third",
                        prior = 0.5, epsilon = None, contact = "point", time_limit = None,
                        priors = None))]
    #[allow(clippy::too_many_arguments)]
    fn learn(
        &self,
        py: Python<'_>,
        samples: usize,
        cutoff: f64,
        seed: u64,
        templates: &str,
        prior: f64,
        epsilon: Option<f64>,
        contact: &str,
        time_limit: Option<f64>,
        priors: Option<PathBuf>,
    ) -> PyResult<PyLearned> {
        let priors = crate::priors::read_priors(py, priors)?;
        let params = LearnParams {
            samples,
            cutoff,
            prior,
            epsilon,
            seed,
            contact: self::contact(contact)?,
            templates: self::templates(templates)?,
            ..LearnParams::default()
        };
        let deadline = duration(time_limit)?.and_then(|t| std::time::Instant::now().checked_add(t));
        learn_interruptible(
            py,
            &self.inner.demos,
            self.inner.statements.as_ref(),
            &params,
            priors.as_deref(),
            deadline,
        )
    }

    /// Place the problem under `rules` (`rccpack_core::task::place`): the
    /// landmarks checked, the demonstrations the warm start and, with
    /// `like="demos"` (the default), the resemblance target. Nothing is
    /// written. Ctrl-C returns the best layout found (`interrupted`).
    #[pyo3(signature = (rules, like = DEMOS, time_limit = None, node_limit = None, seed = 0,
                        contact = "point"))]
    #[allow(clippy::too_many_arguments)]
    fn place(
        &self,
        py: Python<'_>,
        rules: &PyRuleSet,
        like: LikeArg,
        time_limit: Option<f64>,
        node_limit: Option<u64>,
        seed: u64,
        contact: &str,
    ) -> PyResult<PySynthResult> {
        let like = like.0;
        let cancel = Arc::new(AtomicBool::new(false));
        let opts = SynthOptions {
            contact: self::contact(contact)?,
            stop: crate::api::stop(duration(time_limit)?, node_limit, &cancel),
            seed,
            ..SynthOptions::default()
        };
        let t = &self.inner;
        let rules = &rules.inner;
        let (placed, signal) = run_interruptible(py, &cancel, || {
            rccpack_core::task::place(&t.problem, rules, &t.demos, &like, &opts)
        })?;
        let (placement, interrupted) = settle(py, placed, signal, task_error)?;
        Ok(PySynthResult {
            inner: placement.result,
            interrupted,
        })
    }

    /// The whole of `rccpack run DIR --out OUT` (OUT defaults to the task
    /// folder): learn, write `learned.rcc` and `learn-report.json`, place,
    /// write `solution.json` and `solution.png`, under the folder lock,
    /// each file atomically and byte for byte as the command line writes
    /// it. `time_limit` covers learning and placing. Returns what was
    /// learned, the layout and what the command prints; an infeasible or
    /// unknown result is an outcome (`exit_code` 2 or 3), not an exception.
    #[pyo3(signature = (out = None, samples = 1000, cutoff = 0.01, seed = 0, time_limit = 60.0,
                        contact = "point", like = DEMOS, templates = "third", node_limit = None,
                        priors = None))]
    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        py: Python<'_>,
        out: Option<PathBuf>,
        samples: usize,
        cutoff: f64,
        seed: u64,
        time_limit: Option<f64>,
        contact: &str,
        like: LikeArg,
        templates: &str,
        node_limit: Option<u64>,
        priors: Option<PathBuf>,
    ) -> PyResult<PyRunOutcome> {
        let priors = crate::priors::read_priors(py, priors)?;
        let like = like.0;
        let contact = self::contact(contact)?;
        let cancel = Arc::new(AtomicBool::new(false));
        let opts = RunOptions {
            learn: LearnParams {
                samples,
                cutoff,
                seed,
                contact,
                templates: self::templates(templates)?,
                ..LearnParams::default()
            },
            synth: SynthOptions {
                contact,
                stop: crate::api::stop(duration(time_limit)?, node_limit, &cancel),
                seed,
                ..SynthOptions::default()
            },
            like,
            priors,
        };
        let out = out.unwrap_or_else(|| self.dir.clone());
        let (t, dir, o) = (&self.inner, &self.dir, &out);
        let (ran, signal) =
            run_interruptible(py, &cancel, || folder::run_folder(t, dir, o, &opts))?;
        let (ran, interrupted) = settle(py, ran, signal, folder_error)?;
        let said = folder::summary(&ran);
        let mut summary = String::new();
        for line in &said.stdout {
            summary.push_str(line);
            summary.push('\n');
        }
        // The exit codes of `rccpack run` (docs/cli.md).
        let exit_code = match ran.ending() {
            folder::Ending::Layout => 0,
            folder::Ending::Infeasible => 2,
            _ => 3,
        };
        Ok(PyRunOutcome {
            learned: Py::new(
                py,
                PyLearned {
                    inner: ran.outcome.learned,
                },
            )?,
            result: Py::new(
                py,
                PySynthResult {
                    inner: ran.outcome.placement.result,
                    interrupted,
                },
            )?,
            missing_classes: ran.outcome.placement.missing_classes,
            summary,
            message: said.stderr,
            exit_code,
            files: ran.files.iter().map(|p| p.display().to_string()).collect(),
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "<Task {}: {} demonstrations, {} objects to place>",
            self.dir.display(),
            self.inner.demos.len(),
            self.inner
                .problem
                .objects
                .iter()
                .filter(|o| !o.is_placed())
                .count()
        )
    }
}

/// The work's result and whether Ctrl-C interrupted it: a
/// `KeyboardInterrupt` after which the search returned its best is an
/// interruption (`interrupted`); one that stopped the work before any
/// result (learning) propagates, as does any other exception.
fn settle<T, E>(
    py: Python<'_>,
    r: Result<T, E>,
    signal: Option<PyErr>,
    convert: fn(E) -> PyErr,
) -> PyResult<(T, bool)> {
    match (r, signal) {
        (Err(_), Some(e)) => Err(e),
        (r, None) => Ok((r.map_err(convert)?, false)),
        (Ok(v), Some(e)) if e.is_instance_of::<PyKeyboardInterrupt>(py) => Ok((v, true)),
        (Ok(_), Some(e)) => Err(e),
    }
}
