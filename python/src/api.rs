//! The functions: `evaluate`, `learn`, `synthesize`, `render`, `render_png`,
//! the file loaders, and their result classes.

use crate::errors::{guard, panic_error, scene_error, Error, LearnError, SynthError};
use crate::rules::PyRuleSet;
use crate::scene::{scenes_arg, PyScene};
use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyBytes, PyTuple};
use rccpack_core::infer::{learn_with, InferError, LearnOptions, LearnParams, Templates};
use rccpack_core::render::render_png as core_render_png;
use rccpack_core::resemblance::ResemblanceTarget;
use rccpack_core::stop::Stop;
use rccpack_core::synth::{Progress, ProgressFn};
use rccpack_core::{
    evaluate as core_evaluate, render_svg, synthesize as core_synthesize, Contact, Evaluation,
    RenderOptions, RuleReport, Scene as CoreScene, Status, SynthOptions,
};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

pub(crate) fn contact(s: &str) -> PyResult<Contact> {
    s.parse::<Contact>().map_err(Error::new_err)
}

pub(crate) fn templates(s: &str) -> PyResult<Templates> {
    s.parse::<Templates>().map_err(Error::new_err)
}

pub(crate) fn json_loads<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    static LOADS: PyOnceLock<Py<PyAny>> = PyOnceLock::new();
    LOADS.import(py, "json", "loads")?.call1((text,))
}

// ---- files ---------------------------------------------------------------

pub(crate) fn read_text(path: &Path) -> PyResult<String> {
    let bytes = std::fs::read(path)?;
    rccpack_core::fsutil::utf8_text(bytes)
        .map_err(|e| Error::new_err(format!("{}: {e}", path.display())))
}

/// Read one scene from a JSON file.
#[pyfunction]
pub fn load_scene(path: std::path::PathBuf) -> PyResult<PyScene> {
    let text = read_text(&path)?;
    let name = path.display().to_string();
    guard(|| CoreScene::from_json(&text))?
        .map(PyScene::wrap)
        .map_err(|e| scene_error(e, Some(&name)))
}

/// Read a demonstrations file (a JSON array of scenes; one scene is a list
/// of one).
#[pyfunction]
pub fn load_scenes(path: std::path::PathBuf) -> PyResult<Vec<PyScene>> {
    let text = read_text(&path)?;
    let name = path.display().to_string();
    guard(|| rccpack_core::scene::scenes_from_json(&text))?
        .map(|v| v.into_iter().map(PyScene::wrap).collect())
        .map_err(|e| scene_error(e, Some(&name)))
}

/// Demonstrations read as measured (docs/scenes.md#demonstrations-as-measured):
/// the scenes on the grid and every object moved to get there.
#[pyclass(module = "rccpack", name = "Measured", frozen)]
pub struct PyMeasured {
    scenes: Vec<CoreScene>,
    moves: Vec<rccpack_core::scene::measured::Move>,
}

#[pymethods]
impl PyMeasured {
    /// The demonstrations on the grid.
    #[getter]
    fn scenes(&self) -> Vec<PyScene> {
        self.scenes.iter().cloned().map(PyScene::wrap).collect()
    }

    /// Every object that moved, in order: dicts with `demonstration`,
    /// `object`, `from` (the measured `(x, y)`), `to` (on the grid) and
    /// `distance` (px).
    #[getter]
    fn moves<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, pyo3::types::PyDict>>> {
        self.moves
            .iter()
            .map(|m| {
                let d = pyo3::types::PyDict::new(py);
                d.set_item("demonstration", m.demonstration)?;
                d.set_item("object", &m.object)?;
                d.set_item("from", m.from)?;
                d.set_item("to", m.to)?;
                d.set_item("distance", m.distance)?;
                Ok(d)
            })
            .collect()
    }

    fn __repr__(&self) -> String {
        let most = self.moves.iter().map(|m| m.distance).fold(0.0, f64::max);
        format!(
            "<Measured {} demonstrations: {} objects moved by at most {most} px>",
            self.scenes.len(),
            self.moves.len()
        )
    }
}

fn measured_text(text: &str, tolerance: Option<f64>, name: Option<&str>) -> PyResult<PyMeasured> {
    let m = guard(|| rccpack_core::scene::measured::measured_from_json(text, tolerance))?
        .map_err(|e| scene_error(e, name))?;
    if let Some(t) = tolerance {
        rccpack_core::scene::measured::check_tolerance(t, &m.scenes)
            .map_err(|e| Error::new_err(format!("tolerance: {e}")))?;
    }
    Ok(PyMeasured {
        scenes: m.scenes,
        moves: m.moves,
    })
}

/// Read demonstrations as measured (fractions, small overlaps and gaps; as
/// `rccpack learn` reads them) from a JSON file; `tolerance` in px
/// (`None`: four tenths of the grid step; 0: exact).
#[pyfunction]
#[pyo3(signature = (path, tolerance = None))]
pub fn load_measured(path: std::path::PathBuf, tolerance: Option<f64>) -> PyResult<PyMeasured> {
    let text = read_text(&path)?;
    measured_text(&text, tolerance, Some(&path.display().to_string()))
}

/// [`load_measured`] from JSON text, or from a list of dicts (scenes whose
/// coordinates may be floats).
#[pyfunction]
#[pyo3(signature = (demos, tolerance = None))]
pub fn measured(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    tolerance: Option<f64>,
) -> PyResult<PyMeasured> {
    let text: String = if let Ok(s) = demos.extract::<String>() {
        s
    } else {
        py.import("json")?
            .call_method1("dumps", (demos,))?
            .extract()?
    };
    measured_text(&text, tolerance, None)
}

/// Read and parse a `.rcc` file.
#[pyfunction]
pub fn load_rules(path: std::path::PathBuf) -> PyResult<PyRuleSet> {
    let text = read_text(&path)?;
    PyRuleSet::parse_named(&text, &path.display().to_string())
}

/// Scenes as the pretty JSON array the command line writes.
#[pyfunction]
pub fn scenes_to_json(scenes: &Bound<'_, PyAny>) -> PyResult<String> {
    let v = scenes_arg(scenes, "scenes")?;
    Ok(rccpack_core::scene::scenes_to_json(&v))
}

// ---- evaluate --------------------------------------------------------------

/// Per rule: subjects, how many satisfy it, who breaks it.
#[pyclass(module = "rccpack", name = "RuleReport", frozen, get_all)]
pub struct PyRuleReport {
    name: String,
    weight: f64,
    hard: bool,
    subjects: usize,
    satisfied: usize,
    violators: Vec<String>,
    /// Scene-level rules: the subject quantifier (`some`, `at least 2`, …).
    quantifier: Option<String>,
}

#[pymethods]
impl PyRuleReport {
    fn __repr__(&self) -> String {
        format!(
            "<RuleReport {} {}/{}>",
            self.name, self.satisfied, self.subjects
        )
    }
}

impl From<&RuleReport> for PyRuleReport {
    fn from(r: &RuleReport) -> Self {
        PyRuleReport {
            name: r.name.clone(),
            weight: r.weight,
            hard: r.hard,
            subjects: r.subjects,
            satisfied: r.satisfied,
            violators: r.violators.clone(),
            quantifier: r.scene.as_ref().map(|s| s.quantifier.clone()),
        }
    }
}

/// The score of a scene and one report per rule.
#[pyclass(module = "rccpack", name = "Evaluation", frozen)]
pub struct PyEvaluation {
    inner: Evaluation,
}

#[pymethods]
impl PyEvaluation {
    #[getter]
    fn score(&self) -> f64 {
        self.inner.score
    }
    #[getter]
    fn satisfied_weight(&self) -> f64 {
        self.inner.satisfied_weight
    }
    #[getter]
    fn total_weight(&self) -> f64 {
        self.inner.total_weight
    }
    #[getter]
    fn hard_violations(&self) -> usize {
        self.inner.hard_violations
    }
    #[getter]
    fn off_grid(&self) -> Vec<String> {
        self.inner.off_grid.clone()
    }
    #[getter]
    fn rules<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let v: Vec<PyRuleReport> = self.inner.rules.iter().map(PyRuleReport::from).collect();
        PyTuple::new(py, v)
    }
    /// The JSON of `rccpack score --json`.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.inner).map_err(|e| Error::new_err(e.to_string()))
    }
    fn __repr__(&self) -> String {
        format!(
            "<Evaluation score {:.6} ({} / {})>",
            self.inner.score, self.inner.satisfied_weight, self.inner.total_weight
        )
    }
}

/// Score `scene` against `rules` (docs/language.md#the-score).
#[pyfunction]
#[pyo3(signature = (scene, rules, contact = "point"))]
pub fn evaluate(scene: &PyScene, rules: &PyRuleSet, contact: &str) -> PyResult<PyEvaluation> {
    let c = self::contact(contact)?;
    guard(|| rccpack_core::rules::check_landmarks(&rules.inner, &scene.inner))?
        .map_err(|e| rules.error(&e))?;
    let inner = guard(|| core_evaluate(&scene.inner, &rules.inner, c))?;
    Ok(PyEvaluation { inner })
}

// ---- learn -----------------------------------------------------------------

/// One statement weighed by learning (the `learn --report` entry).
#[pyclass(module = "rccpack", name = "Statement", frozen, get_all)]
pub struct PyStatement {
    name: String,
    formula: String,
    subject: String,
    english: String,
    candidate: bool,
    n: u64,
    satisfied: Option<u64>,
    q: Option<f64>,
    p: Option<f64>,
    log10_likelihood: Option<f64>,
    log10_posterior: Option<f64>,
    posterior: Option<f64>,
    learned: bool,
    rank: Option<usize>,
    implied_by: Option<String>,
}

#[pymethods]
impl PyStatement {
    fn __repr__(&self) -> String {
        format!(
            "<Statement {}: {}{}>",
            self.name,
            self.formula,
            if self.learned { " (learned)" } else { "" }
        )
    }
}

/// What `learn` found: the rules and the report.
#[pyclass(module = "rccpack", name = "Learned", frozen)]
pub struct PyLearned {
    pub(crate) inner: rccpack_core::Learned,
}

#[pymethods]
impl PyLearned {
    /// The learned rules, strongest first (each with `p P` and comments).
    #[getter]
    fn rules(&self) -> PyRuleSet {
        PyRuleSet::wrap(self.inner.rules())
    }
    /// The `.rcc` text `rccpack learn` writes (header, then the rules).
    fn to_rcc(&self) -> String {
        self.inner.to_rcc()
    }
    /// The JSON `rccpack learn --report` writes.
    fn report_json(&self) -> String {
        self.inner.report_json()
    }
    /// The report as a dict.
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_loads(py, &self.inner.report_json())
    }
    /// Every statement weighed, in statement order.
    #[getter]
    fn statements<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let report = self.inner.report();
        let v: Vec<PyStatement> = report
            .statements
            .into_iter()
            .map(|s| PyStatement {
                name: s.name,
                formula: s.formula,
                subject: s.subject,
                english: s.english,
                candidate: s.candidate,
                n: s.n,
                satisfied: s.satisfied,
                q: s.q,
                p: s.p,
                log10_likelihood: s.log10_likelihood,
                log10_posterior: s.log10_posterior,
                posterior: s.posterior,
                learned: s.learned,
                rank: s.rank,
                implied_by: s.implied_by,
            })
            .collect();
        PyTuple::new(py, v)
    }
    /// Number of demonstrations.
    #[getter]
    fn demonstrations(&self) -> usize {
        self.inner.demos
    }
    /// Number of candidates (statements every demonstration satisfies).
    #[getter]
    fn candidates(&self) -> usize {
        self.inner.statements.iter().filter(|s| s.candidate).count()
    }
    fn __len__(&self) -> usize {
        self.inner.order.len()
    }
    fn __repr__(&self) -> String {
        format!(
            "<Learned {} rules ({} candidates of {} statements) from {} demonstrations>",
            self.inner.order.len(),
            self.candidates(),
            self.inner.statements.len(),
            self.inner.demos
        )
    }
}

pub(crate) fn learn_error(e: InferError) -> PyErr {
    LearnError::new_err(e.to_string())
}

/// Learn rules from demonstrations (docs/guide.md#learning). The GIL is released while
/// learning; the same seed gives the same rules.
#[pyfunction]
#[pyo3(signature = (demos, samples = 1000, cutoff = 0.01, seed = 0, templates = "third",
                    statements = None, prior = 0.5, epsilon = None, contact = "point",
                    priors = None, slip_rate = 0.0))]
#[allow(clippy::too_many_arguments)]
#[pyo3(name = "learn")]
pub fn learn_py(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    samples: usize,
    cutoff: f64,
    seed: u64,
    templates: &str,
    statements: Option<&PyRuleSet>,
    prior: f64,
    epsilon: Option<f64>,
    contact: &str,
    priors: Option<std::path::PathBuf>,
    slip_rate: f64,
) -> PyResult<PyLearned> {
    let demos = scenes_arg(demos, "demos")?;
    let priors = crate::priors::read_priors(py, priors)?;
    let params = LearnParams {
        samples,
        cutoff,
        prior,
        epsilon,
        seed,
        contact: self::contact(contact)?,
        templates: self::templates(templates)?,
        slip_rate,
    };
    let set = statements.map(|s| s.inner.clone());
    learn_interruptible(py, &demos, set.as_ref(), &params, priors.as_deref(), None)
}

/// Learn on a worker thread with the GIL released; Ctrl-C stops the null
/// model's draws (the core's cancel flag) and raises `KeyboardInterrupt`.
pub(crate) fn learn_interruptible(
    py: Python<'_>,
    demos: &[CoreScene],
    statements: Option<&rccpack_core::RuleSet>,
    params: &LearnParams,
    priors: Option<&rccpack_core::priors::Priors>,
    deadline: Option<std::time::Instant>,
) -> PyResult<PyLearned> {
    let cancel = std::sync::Arc::new(AtomicBool::new(false));
    let stop = match deadline {
        Some(d) => rccpack_core::stop::Stop::at(d),
        None => rccpack_core::stop::Stop::never(),
    }
    .with_cancel(cancel.clone());
    let opts = LearnOptions {
        priors,
        stop,
        ..LearnOptions::default()
    };
    let (out, signal) =
        run_interruptible(py, &cancel, || learn_with(demos, statements, params, &opts))?;
    if let Some(e) = signal {
        return Err(e);
    }
    match out {
        Ok(inner) => Ok(PyLearned { inner }),
        Err(e) => Err(learn_error(e)),
    }
}

// ---- synthesize ------------------------------------------------------------

/// The second objective's result.
#[pyclass(module = "rccpack", name = "Resemblance", frozen, get_all)]
pub struct PyResemblance {
    cost: u64,
    proven: bool,
    bound: u64,
}

#[pymethods]
impl PyResemblance {
    fn __repr__(&self) -> String {
        format!(
            "Resemblance(cost={}, proven={}, bound={})",
            self.cost,
            py_bool(self.proven),
            self.bound
        )
    }
}

/// Why a problem is infeasible.
#[pyclass(module = "rccpack", name = "Conflict", frozen, get_all)]
pub struct PyConflict {
    objects_cannot_fit: bool,
    hard_rules: Vec<String>,
    limit_struck: bool,
}

#[pymethods]
impl PyConflict {
    fn __repr__(&self) -> String {
        format!(
            "Conflict(objects_cannot_fit={}, hard_rules={:?}, limit_struck={})",
            py_bool(self.objects_cannot_fit),
            self.hard_rules,
            py_bool(self.limit_struck)
        )
    }
}

fn py_bool(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

/// Search statistics.
#[pyclass(module = "rccpack", name = "SolveStats", frozen, get_all)]
pub struct PySolveStats {
    nodes: u64,
    conflicts: u64,
    time_ms: f64,
    time_to_first_ms: Option<f64>,
    time_to_best_ms: Option<f64>,
}

#[pymethods]
impl PySolveStats {
    fn __repr__(&self) -> String {
        format!(
            "SolveStats(nodes={}, conflicts={}, time_ms={:.1})",
            self.nodes, self.conflicts, self.time_ms
        )
    }
}

/// The result of `synthesize`.
#[pyclass(module = "rccpack", name = "SynthResult", frozen)]
pub struct PySynthResult {
    pub(crate) inner: rccpack_core::SynthResult,
    pub(crate) interrupted: bool,
}

fn status_name(s: Status) -> &'static str {
    match s {
        Status::Optimal => "optimal",
        Status::Feasible => "feasible",
        Status::Infeasible => "infeasible",
        Status::Unknown => "unknown",
    }
}

#[pymethods]
impl PySynthResult {
    /// `Status.OPTIMAL`, `FEASIBLE`, `INFEASIBLE` or `UNKNOWN` (docs/guide.md#synthesis).
    #[getter]
    fn status<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        static STATUS: PyOnceLock<Py<PyAny>> = PyOnceLock::new();
        STATUS
            .import(py, "rccpack", "Status")?
            .call1((status_name(self.inner.status),))
    }
    /// The complete layout (optimal and feasible only).
    #[getter]
    fn scene(&self) -> Option<PyScene> {
        self.inner.scene.clone().map(PyScene::wrap)
    }
    /// The evaluator's verdict on `scene`.
    #[getter]
    fn evaluation(&self) -> Option<PyEvaluation> {
        self.inner
            .evaluation
            .clone()
            .map(|inner| PyEvaluation { inner })
    }
    /// The score of `scene` (recomputed by the evaluator).
    #[getter]
    fn score(&self) -> Option<f64> {
        self.inner.evaluation.as_ref().map(|e| e.score)
    }
    /// A proven upper bound on the score of any layout.
    #[getter]
    fn score_bound(&self) -> Option<f64> {
        self.inner.score_bound
    }
    #[getter]
    fn resemblance(&self) -> Option<PyResemblance> {
        self.inner.resemblance.map(|r| PyResemblance {
            cost: r.cost,
            proven: r.proven,
            bound: r.bound,
        })
    }
    #[getter]
    fn conflict(&self) -> Option<PyConflict> {
        self.inner.conflict.as_ref().map(|c| PyConflict {
            objects_cannot_fit: c.objects_cannot_fit,
            hard_rules: c.hard_rules.clone(),
            limit_struck: c.limit_struck,
        })
    }
    #[getter]
    fn stats(&self) -> PySolveStats {
        let s = &self.inner.stats;
        PySolveStats {
            nodes: s.nodes,
            conflicts: s.conflicts,
            time_ms: s.time_ms,
            time_to_first_ms: s.time_to_first_ms,
            time_to_best_ms: s.time_to_best_ms,
        }
    }
    /// Whether Ctrl-C (KeyboardInterrupt) or the progress callback stopped
    /// the search; the layout is then the best found.
    #[getter]
    fn interrupted(&self) -> bool {
        self.interrupted
    }
    /// The JSON report `rccpack synth --report` writes (byte for byte).
    fn report_json(&self) -> String {
        rccpack_core::synth::report::report_json(&self.inner)
    }
    fn __repr__(&self) -> String {
        format!(
            "<SynthResult {}{}>",
            status_name(self.inner.status),
            self.inner
                .evaluation
                .as_ref()
                .map_or(String::new(), |e| format!(", score {:.6}", e.score))
        )
    }
}

pub(crate) fn duration(seconds: Option<f64>) -> PyResult<Option<Duration>> {
    match seconds {
        None => Ok(None),
        Some(s) => rccpack_core::limits::parse_time_limit(&s.to_string())
            .map(Some)
            .map_err(|e| Error::new_err(format!("invalid time_limit {s}: {e}"))),
    }
}

/// The stop of a solve: `time_limit` from now, the node budget and the
/// cancel flag (set by Ctrl-C or a progress callback).
pub(crate) fn stop(
    time_limit: Option<Duration>,
    node_limit: Option<u64>,
    cancel: &Arc<AtomicBool>,
) -> Stop {
    let stop = Stop::within(time_limit).with_cancel(cancel.clone());
    match node_limit {
        Some(n) => stop.with_nodes(n),
        None => stop,
    }
}

/// Place the unplaced objects of `problem` (docs/guide.md#synthesis, docs/guide.md#layouts-like-the-demonstrations).
///
/// The GIL is released while solving. Ctrl-C stops the search and returns
/// the best layout found (`interrupted` is then true); see docs/python.md.
#[pyfunction]
#[pyo3(signature = (problem, rules, like = None, time_limit = None, node_limit = None, seed = 0,
                    contact = "point", warm_start = None, progress = None))]
#[allow(clippy::too_many_arguments)]
pub fn synthesize(
    py: Python<'_>,
    problem: &PyScene,
    rules: &PyRuleSet,
    like: Option<&Bound<'_, PyAny>>,
    time_limit: Option<f64>,
    node_limit: Option<u64>,
    seed: u64,
    contact: &str,
    warm_start: Option<&Bound<'_, PyAny>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<PySynthResult> {
    let contact = self::contact(contact)?;
    let time_limit = duration(time_limit)?;
    let like_scenes = match like {
        Some(l) if !l.is_none() => Some(scenes_arg(l, "like")?),
        _ => None,
    };
    let warm = match warm_start {
        Some(w) if !w.is_none() => scenes_arg(w, "warm_start")?,
        _ => like_scenes.clone().unwrap_or_default(),
    };
    guard(|| rccpack_core::rules::check_landmarks(&rules.inner, &problem.inner))?
        .map_err(|e| rules.error(&e))?;
    let cancel = Arc::new(AtomicBool::new(false));
    let stopped = Arc::new(AtomicBool::new(false));
    let callback_error: Arc<Mutex<Option<PyErr>>> = Arc::new(Mutex::new(None));
    let progress = progress.map(|cb| {
        let (cancel, stopped, err) = (cancel.clone(), stopped.clone(), callback_error.clone());
        ProgressFn(Arc::new(move |p: &Progress| {
            Python::attach(
                |py| match cb.call1(py, (p.score, p.elapsed.as_secs_f64())) {
                    Ok(v) => {
                        if v.bind(py).is(PyBool::new(py, false)) {
                            stopped.store(true, Ordering::SeqCst);
                            cancel.store(true, Ordering::SeqCst);
                        }
                    }
                    Err(e) => {
                        if let Ok(mut slot) = err.lock() {
                            slot.get_or_insert(e);
                        }
                        cancel.store(true, Ordering::SeqCst);
                    }
                },
            )
        }))
    });
    let opts = SynthOptions {
        contact,
        stop: stop(time_limit, node_limit, &cancel),
        seed,
        progress,
        like: like_scenes.as_deref().map(ResemblanceTarget::new),
        warm_start: warm,
        ..SynthOptions::default()
    };
    let (problem, rules) = (&problem.inner, &rules.inner);
    let (result, signal_error) =
        run_interruptible(py, &cancel, || core_synthesize(problem, rules, &opts))?;
    let callback_error = callback_error.lock().ok().and_then(|mut e| e.take());
    let mut interrupted = stopped.load(Ordering::SeqCst);
    for e in [signal_error, callback_error].into_iter().flatten() {
        if e.is_instance_of::<PyKeyboardInterrupt>(py) {
            interrupted = true;
        } else {
            return Err(e);
        }
    }
    match result {
        Ok(inner) => Ok(PySynthResult { inner, interrupted }),
        Err(e) => Err(SynthError::new_err(e.to_string())),
    }
}

/// Run `work` on a worker thread (the engine is created, filled and run
/// there) while this thread waits with the GIL released and, every 50 ms,
/// takes it back to run Python's signal handlers, so Ctrl-C is seen even
/// when the work reports nothing for a long time. An exception a handler
/// raises (`KeyboardInterrupt`) sets `cancel` (the work stops soon) and is
/// returned beside the work's result; a panic becomes `InternalError`.
pub(crate) fn run_interruptible<T: Send>(
    py: Python<'_>,
    cancel: &AtomicBool,
    work: impl FnOnce() -> T + Send,
) -> PyResult<(T, Option<PyErr>)> {
    let done = (Mutex::new(false), Condvar::new());
    let done = &done;
    let mut signal_error: Option<PyErr> = None;
    let outcome = std::thread::scope(|s| {
        let worker = s.spawn(move || {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
            if let Ok(mut d) = done.0.lock() {
                *d = true;
            }
            done.1.notify_all();
            r
        });
        loop {
            let finished = py.detach(|| {
                let Ok(d) = done.0.lock() else { return true };
                if *d {
                    return true;
                }
                match done.1.wait_timeout(d, Duration::from_millis(50)) {
                    Ok((d, _)) => *d,
                    Err(_) => true,
                }
            });
            if finished {
                break;
            }
            if signal_error.is_none() {
                if let Err(e) = py.check_signals() {
                    signal_error = Some(e);
                    cancel.store(true, Ordering::SeqCst);
                }
            }
        }
        worker.join()
    });
    match outcome {
        Ok(Ok(r)) => Ok((r, signal_error)),
        Ok(Err(p)) | Err(p) => Err(panic_error(p)),
    }
}

// ---- render ----------------------------------------------------------------

fn render_options(
    like: Option<&Bound<'_, PyAny>>,
    contact: &str,
    scale: f64,
    title: Option<String>,
) -> PyResult<RenderOptions> {
    if !(scale.is_finite() && scale > 0.0) {
        return Err(Error::new_err(format!(
            "invalid scale {scale}: expected a finite number above 0"
        )));
    }
    let like = match like {
        Some(l) if !l.is_none() => Some(ResemblanceTarget::new(&scenes_arg(l, "like")?)),
        _ => None,
    };
    Ok(RenderOptions {
        contact: self::contact(contact)?,
        scale,
        title,
        like,
        ..RenderOptions::default()
    })
}

/// Draw `scene` as SVG text (rule violations outlined when `rules` given).
#[pyfunction]
#[pyo3(signature = (scene, rules = None, like = None, contact = "point", scale = 1.0, title = None))]
pub fn render(
    scene: &PyScene,
    rules: Option<&PyRuleSet>,
    like: Option<&Bound<'_, PyAny>>,
    contact: &str,
    scale: f64,
    title: Option<String>,
) -> PyResult<String> {
    let opts = render_options(like, contact, scale, title)?;
    if let Some(r) = rules {
        guard(|| rccpack_core::rules::check_landmarks(&r.inner, &scene.inner))?
            .map_err(|e| r.error(&e))?;
    }
    guard(|| render_svg(&scene.inner, rules.map(|r| &r.inner), &opts))
}

/// Draw `scene` as PNG bytes (the picture of `render`, rasterised).
#[pyfunction]
#[pyo3(signature = (scene, rules = None, like = None, contact = "point", scale = 1.0, title = None))]
pub fn render_png<'py>(
    py: Python<'py>,
    scene: &PyScene,
    rules: Option<&PyRuleSet>,
    like: Option<&Bound<'_, PyAny>>,
    contact: &str,
    scale: f64,
    title: Option<String>,
) -> PyResult<Bound<'py, PyBytes>> {
    let opts = render_options(like, contact, scale, title)?;
    if let Some(r) = rules {
        guard(|| rccpack_core::rules::check_landmarks(&r.inner, &scene.inner))?
            .map_err(|e| r.error(&e))?;
    }
    let (s, r) = (&scene.inner, rules.map(|r| &r.inner));
    let png = py.detach(|| {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            core_render_png(s, r, &opts)
        }))
    });
    match png {
        Ok(Ok(bytes)) => Ok(PyBytes::new(py, &bytes)),
        Ok(Err(e)) => Err(Error::new_err(e.to_string())),
        Err(p) => Err(panic_error(p)),
    }
}
