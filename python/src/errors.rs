//! The exception classes and the conversions of the core's typed errors.
//!
//! Every entry point runs the core under [`guard`]: a panic (a bug) becomes
//! `rccpack.InternalError` instead of crossing the FFI boundary.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyList;
use rccpack_core::{RulesError as CoreRulesError, SceneError as CoreSceneError};

create_exception!(
    rccpack,
    Error,
    PyValueError,
    "Base class of every rccpack error (a ValueError: the input is at fault)."
);
create_exception!(
    rccpack,
    SceneError,
    Error,
    "A scene (or a demonstrations list) breaks docs/scenes.md; `path` names the field."
);
create_exception!(
    rccpack,
    RulesError,
    Error,
    "`.rcc` text is invalid; `line`, `column` and `report` (with a caret) locate it."
);
create_exception!(
    rccpack,
    SynthError,
    Error,
    "A problem cannot be used for synthesis (not infeasibility: see `Status`)."
);
create_exception!(
    rccpack,
    LearnError,
    Error,
    "Learning cannot run: bad parameters, demonstrations or statements."
);
create_exception!(
    rccpack,
    AskError,
    Error,
    "The question loop cannot go on (bad task folder or oracle answer)."
);
create_exception!(
    rccpack,
    SampleError,
    Error,
    "Sampling found no layout of the quality asked for (`kind`: `infeasible`, `no_layout`)."
);
create_exception!(
    rccpack,
    PriorsError,
    Error,
    "A priors file or task counts are damaged or do not fit; `field` names the field."
);
create_exception!(
    rccpack,
    InternalError,
    Error,
    "A bug in rccpack (a Rust panic caught at the boundary); please report it."
);

/// Run `f`, turning a panic into `InternalError`.
pub(crate) fn guard<T>(f: impl FnOnce() -> T) -> PyResult<T> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(panic_error)
}

pub(crate) fn panic_error(p: Box<dyn std::any::Any + Send>) -> PyErr {
    let what = p
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into());
    InternalError::new_err(format!("internal error (a bug, please report it): {what}"))
}

/// `SceneError` with `path`, `message` and `file` attributes.
pub(crate) fn scene_error(e: CoreSceneError, file: Option<&str>) -> PyErr {
    let path = e.path().to_string();
    let message = match &e {
        CoreSceneError::Json { message, .. } | CoreSceneError::Invalid { message, .. } => {
            message.clone()
        }
        other => other.to_string(),
    };
    let kind = snake(&format!("{:?}", e.kind()));
    let text = match file {
        Some(f) => format!("{f}: {e}"),
        None => e.to_string(),
    };
    let err = SceneError::new_err(text);
    Python::attach(|py| {
        let v = err.value(py);
        let _ = v.setattr("path", path);
        let _ = v.setattr("message", message);
        let _ = v.setattr("kind", kind);
        let _ = v.setattr("file", file);
    });
    err
}

/// `UnknownRelation` → `unknown_relation` (the `kind` attributes).
fn snake(name: &str) -> String {
    let mut out = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                out.push('_');
            }
            out.push(c.to_ascii_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

/// `RulesError` with `line`, `column` (1-based, of the first problem),
/// `message`, `report` (every problem with its source line and a caret),
/// `diagnostics` (`(line, column, message)` each) and `file`.
pub(crate) fn rules_error(e: &CoreRulesError, src: &str, file: &str) -> PyErr {
    let (line, column) = e.line_col(src);
    let message = e
        .diagnostics
        .first()
        .map(|d| d.message.clone())
        .unwrap_or_else(|| "invalid rules".into());
    let report = e.render(file, src, false);
    let err = RulesError::new_err(format!("{file}:{line}:{column}: {message}"));
    Python::attach(|py| {
        let v = err.value(py);
        let diags: Vec<(usize, usize, String)> = e
            .diagnostics
            .iter()
            .map(|d| {
                let (l, c) = d.line_col(src);
                (l, c, d.message.clone())
            })
            .collect();
        let kind = e
            .diagnostics
            .first()
            .map_or_else(|| "syntax".to_string(), |d| snake(&format!("{:?}", d.kind)));
        let _ = v.setattr("kind", kind);
        let _ = v.setattr("line", line);
        let _ = v.setattr("column", column);
        let _ = v.setattr("message", message);
        let _ = v.setattr("report", report);
        let _ = v.setattr("file", file);
        if let Ok(list) = PyList::new(py, diags) {
            let _ = v.setattr("diagnostics", list);
        }
    });
    err
}
