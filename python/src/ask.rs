//! `ask`: the questions of SPEC §13, answered by a Python function.

use crate::api::{contact, learn_error, read_text};
use crate::errors::{panic_error, scene_error, AskError as PyAskError, SynthError};
use crate::rules::PyRuleSet;
use crate::scene::PyScene;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rccpack_core::ask::{
    AnswersFile, AskError, AskOptions, Asker, ProbeOptions, DEFAULT_CHECK_NODES,
    DEFAULT_PROBE_NODES,
};
use rccpack_core::infer::{LearnParams, Templates};
use rccpack_core::task::files;
use rccpack_core::Scene as CoreScene;
use std::path::PathBuf;
use std::time::Duration;

/// One question asked and its answer.
#[pyclass(module = "rccpack", name = "Question", frozen, get_all)]
pub struct PyQuestion {
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
    /// The oracle's answer: acceptable (the rule is dropped) or not
    /// (confirmed).
    accepted: bool,
}

#[pymethods]
impl PyQuestion {
    fn __repr__(&self) -> String {
        format!(
            "<Question {} -> {}>",
            self.rule,
            if self.accepted {
                "acceptable"
            } else {
                "not acceptable"
            }
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
    /// Counts: asked, dropped, confirmed, implied, unknown, held.
    #[getter]
    fn progress<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let p = self.progress;
        let d = PyDict::new(py);
        d.set_item("asked", p.asked)?;
        d.set_item("dropped", p.dropped)?;
        d.set_item("confirmed", p.confirmed)?;
        d.set_item("implied", p.implied)?;
        d.set_item("unknown", p.unknown)?;
        d.set_item("held", p.held)?;
        Ok(d)
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

fn ask_error(e: AskError) -> PyErr {
    match e {
        AskError::Learn(e) => learn_error(e),
        AskError::Synth(e) => {
            SynthError::new_err(format!("the problem cannot be used for probes: {e}"))
        }
        other => PyAskError::new_err(other.to_string()),
    }
}

/// Run the questions of SPEC §13 on the task folder `task_dir`
/// (`problem.json`, `demos.json`, optional `statements.rcc`) with
/// `oracle(probe) -> bool` answering "is this layout acceptable?".
///
/// Nothing is written to the folder: the result holds what `rccpack ask`
/// would save (`learned_rcc`, `demos`, `answers_json`). An exception raised
/// by the oracle ends the loop and propagates.
#[pyfunction]
#[pyo3(signature = (task_dir, oracle, max_questions = None, samples = 1000, cutoff = 0.01, seed = 0,
                    time_limit = 10.0, node_limit = DEFAULT_PROBE_NODES,
                    check_nodes = DEFAULT_CHECK_NODES, contact = "point", templates = "second"))]
#[allow(clippy::too_many_arguments)]
pub fn ask(
    py: Python<'_>,
    task_dir: PathBuf,
    oracle: Bound<'_, PyAny>,
    max_questions: Option<usize>,
    samples: usize,
    cutoff: f64,
    seed: u64,
    time_limit: Option<f64>,
    node_limit: u64,
    check_nodes: u64,
    contact: &str,
    templates: &str,
) -> PyResult<PyAskResult> {
    let contact = self::contact(contact)?;
    let templates: Templates = templates.parse().map_err(crate::errors::Error::new_err)?;
    let time_limit = match time_limit {
        None => None,
        Some(s) => Some(
            rccpack_core::limits::parse_time_limit(&s.to_string()).map_err(|e| {
                crate::errors::Error::new_err(format!("invalid time_limit {s}: {e}"))
            })?,
        ),
    };
    let read_scene = |name: &str| -> PyResult<CoreScene> {
        let p = task_dir.join(name);
        let text = read_text(&p)?;
        CoreScene::from_json(&text).map_err(|e| scene_error(e, Some(&p.display().to_string())))
    };
    let problem = read_scene(files::PROBLEM)?;
    let demos_path = task_dir.join(files::DEMOS);
    let demos = rccpack_core::scene::scenes_from_json(&read_text(&demos_path)?)
        .map_err(|e| scene_error(e, Some(&demos_path.display().to_string())))?;
    let statements_path = task_dir.join(files::STATEMENTS);
    let statements = if statements_path.exists() {
        let text = read_text(&statements_path)?;
        Some(PyRuleSet::parse_named(&text, &statements_path.display().to_string())?.inner)
    } else {
        None
    };
    let opts = AskOptions {
        learn: LearnParams {
            samples,
            cutoff,
            seed,
            contact,
            templates,
            ..LearnParams::default()
        },
        probe: ProbeOptions {
            contact,
            seed,
            time_limit: time_limit.or(Some(Duration::from_secs(1_000_000))),
            node_limit: Some(node_limit.max(1)),
            check_nodes: Some(check_nodes.max(1)),
            ..ProbeOptions::default()
        },
        resemble: true,
        ..AskOptions::default()
    };
    let run = |f: &mut dyn FnMut() -> Result<(), AskError>| -> PyResult<()> {
        match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
            Ok(r) => r.map_err(ask_error),
            Err(p) => Err(panic_error(p)),
        }
    };
    let mut asker: Option<Asker> = None;
    let mut input = Some((problem, demos, statements));
    py.detach(|| {
        run(&mut || {
            let Some((problem, demos, statements)) = input.take() else {
                return Ok(());
            };
            asker = Some(Asker::new(
                problem,
                demos,
                statements,
                Vec::new(),
                opts.clone(),
            )?);
            Ok(())
        })
    })?;
    let Some(mut asker) = asker else {
        return Err(PyAskError::new_err("the question loop did not start"));
    };
    let mut questions = Vec::new();
    let mut out_of_budget = false;
    loop {
        let mut next = None;
        py.detach(|| {
            run(&mut || {
                next = asker.next_question()?;
                Ok(())
            })
        })?;
        let Some(q) = next else { break };
        if max_questions.is_some_and(|m| questions.len() >= m) {
            out_of_budget = true;
            break;
        }
        let probe = Py::new(py, PyScene::wrap(q.probe.scene.clone()))?;
        let accepted = oracle.call1((probe.clone_ref(py),))?.is_truthy()?;
        py.detach(|| {
            run(&mut || {
                asker.answer(&q, accepted)?;
                Ok(())
            })
        })?;
        questions.push(Py::new(
            py,
            PyQuestion {
                rule: q.rule,
                statement: q.statement,
                english: q.english,
                probe,
                broken: q.probe.broken,
                also_broken: q.also_broken,
                accepted,
            },
        )?);
    }
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
        out_of_budget,
    })
}
