//! Priors learned across tasks (`rccpack_core::priors`, `docs/priors.md`):
//! `priors=` of the learning calls (a priors file), and the two steps of
//! `rccpack priors` as plain data for a cluster: `task_counts` (one task
//! folder → a dict) and `combine_priors` (the dicts → the file's text).

use crate::api::{contact, json_loads, read_text, templates};
use crate::errors::{guard, Error, LearnError, PriorsError};
use crate::task::task_error;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use rccpack_core::priors::{
    combine, counts_from_json_list, PriorParams, Priors, PriorsError as CorePriorsError,
};
use rccpack_core::task::library::{self, LibraryError};
use rccpack_core::task::TaskError;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// `PriorsError` with `field` (the field's path: `hash`, `kinds[3].prior`,
/// `counts[2].templates`, …) and `file` (the priors file, when one was
/// read) attributes.
fn priors_error(e: &CorePriorsError, file: Option<&Path>) -> PyErr {
    let field = match e {
        CorePriorsError::Field { field, .. }
        | CorePriorsError::Json { field, .. }
        | CorePriorsError::Counts { field, .. }
        | CorePriorsError::CountsJson { field, .. } => field.clone(),
        _ => String::new(),
    };
    let file = file.map(|f| f.display().to_string());
    let text = match &file {
        Some(f) => format!("{f}: {e}"),
        None => e.to_string(),
    };
    let err = PriorsError::new_err(text);
    Python::attach(|py| {
        let v = err.value(py);
        let _ = v.setattr("field", field);
        let _ = v.setattr("file", file);
    });
    err
}

/// A folder's error: reading its files as `Task.load` raises them
/// (`FileNotFoundError`, `SceneError`, `RulesError`); learning's with the
/// folder named.
fn folder_error(e: LibraryError) -> PyErr {
    match *e.source {
        TaskError::Learn(source) => learn_error_in(&e.dir, source),
        other => task_error(other),
    }
}

fn learn_error_in(dir: &Path, e: rccpack_core::infer::InferError) -> PyErr {
    LearnError::new_err(format!("{}: {e}", dir.display()))
}

/// Read the priors file of a `priors=` argument (`None`: no priors).
pub(crate) fn read_priors(py: Python<'_>, path: Option<PathBuf>) -> PyResult<Option<Arc<Priors>>> {
    let Some(path) = path else {
        return Ok(None);
    };
    let text = read_text(&path)?;
    let priors = py
        .detach(|| guard(|| Priors::from_json(&text)))?
        .map_err(|e| priors_error(&e, Some(&path)))?;
    Ok(Some(Arc::new(priors)))
}

fn params(
    strength: u32,
    rule_out_after: u64,
    templates_name: &str,
    contact_name: &str,
) -> PyResult<PriorParams> {
    if strength == 0 {
        return Err(Error::new_err(
            "invalid strength 0: expected a whole number of at least 1",
        ));
    }
    Ok(PriorParams {
        strength,
        rule_out_after,
        templates: templates(templates_name)?,
        contact: contact(contact_name)?,
    })
}

/// Count one finished task folder (`demos.json`, `learned.rcc`): the
/// per-task step of `rccpack priors`, as JSON-able plain data
/// (`rccpack-task-counts/1`: `version`, `templates`, `contact`, `hash`,
/// `kinds` → `{candidates, kept, confirmed}`). The GIL is released.
#[pyfunction]
#[pyo3(signature = (folder, templates = "third", contact = "point"))]
pub fn task_counts(
    py: Python<'_>,
    folder: PathBuf,
    templates: &str,
    contact: &str,
) -> PyResult<Py<PyAny>> {
    let p = params(4, 10, templates, contact)?;
    let counts = py
        .detach(|| guard(|| library::task_counts(&folder, &p)))?
        .map_err(folder_error)?;
    Ok(json_loads(py, &counts.to_json(&p))?.unbind())
}

/// Combine the counts of `task_counts` (any order) into the priors file's
/// text: exactly the bytes `rccpack priors` writes for the same folders
/// and parameters. Counts of another template set or contact mode, or
/// damaged ones, raise `PriorsError` naming the field.
#[pyfunction]
#[pyo3(signature = (counts, strength = 4, rule_out_after = 10, templates = "third",
                    contact = "point"))]
pub fn combine_priors(
    py: Python<'_>,
    counts: &Bound<'_, PyAny>,
    strength: u32,
    rule_out_after: u64,
    templates: &str,
    contact: &str,
) -> PyResult<String> {
    static DUMPS: PyOnceLock<Py<PyAny>> = PyOnceLock::new();
    let p = params(strength, rule_out_after, templates, contact)?;
    if counts.is_instance_of::<pyo3::types::PyDict>()
        || counts.is_instance_of::<pyo3::types::PyString>()
    {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "counts: expected a list of `task_counts` results, one per task folder",
        ));
    }
    let list = pyo3::types::PyList::new(py, counts.try_iter()?.collect::<PyResult<Vec<_>>>()?)?;
    let text: String = DUMPS
        .import(py, "json", "dumps")?
        .call1((list,))?
        .extract()?;
    py.detach(|| {
        guard(|| counts_from_json_list(&text, &p).map(|tasks| combine(&tasks, &p).to_json()))
    })?
    .map_err(|e| priors_error(&e, None))
}
