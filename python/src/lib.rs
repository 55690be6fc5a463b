//! Python bindings of rccpack (PyO3, the abi3 stable ABI, built by
//! maturin): the native module `rccpack._rccpack`, re-exported by the pure
//! Python package `rccpack` (`python/rccpack/__init__.py`).
//!
//! Every entry point catches panics ([`errors::guard`]) so that no Rust
//! panic crosses into the interpreter; `learn` and `synthesize` release the
//! GIL.

use pyo3::prelude::*;

mod api;
mod ask;
mod errors;
mod priors;
mod rules;
mod sample;
mod scene;
mod task;

#[pymodule]
fn _rccpack(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<errors::Error>())?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("RulesError", py.get_type::<errors::RulesError>())?;
    m.add("SynthError", py.get_type::<errors::SynthError>())?;
    m.add("LearnError", py.get_type::<errors::LearnError>())?;
    m.add("AskError", py.get_type::<errors::AskError>())?;
    m.add("SampleError", py.get_type::<errors::SampleError>())?;
    m.add("PriorsError", py.get_type::<errors::PriorsError>())?;
    m.add("InternalError", py.get_type::<errors::InternalError>())?;
    m.add_class::<scene::PySpace>()?;
    m.add_class::<scene::PyObject>()?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<rules::PyRule>()?;
    m.add_class::<rules::PyRuleSet>()?;
    m.add_class::<api::PyEvaluation>()?;
    m.add_class::<api::PyRuleReport>()?;
    m.add_class::<api::PyLearned>()?;
    m.add_class::<api::PyStatement>()?;
    m.add_class::<api::PySynthResult>()?;
    m.add_class::<api::PyResemblance>()?;
    m.add_class::<api::PyConflict>()?;
    m.add_class::<api::PySolveStats>()?;
    m.add_class::<ask::PyQuestion>()?;
    m.add_class::<ask::PyAskResult>()?;
    m.add_function(wrap_pyfunction!(api::load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(api::load_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(api::load_measured, m)?)?;
    m.add_function(wrap_pyfunction!(api::measured, m)?)?;
    m.add_class::<api::PyMeasured>()?;
    m.add_function(wrap_pyfunction!(api::load_rules, m)?)?;
    m.add_function(wrap_pyfunction!(api::scenes_to_json, m)?)?;
    m.add_function(wrap_pyfunction!(api::evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(api::learn_py, m)?)?;
    m.add_function(wrap_pyfunction!(api::synthesize, m)?)?;
    m.add_function(wrap_pyfunction!(api::render, m)?)?;
    m.add_function(wrap_pyfunction!(api::render_png, m)?)?;
    m.add_function(wrap_pyfunction!(ask::ask, m)?)?;
    m.add_function(wrap_pyfunction!(priors::task_counts, m)?)?;
    m.add_function(wrap_pyfunction!(priors::combine_priors, m)?)?;
    m.add_class::<ask::PyAskSession>()?;
    m.add_class::<task::PyTask>()?;
    m.add_class::<task::PyRunOutcome>()?;
    sample::add(m)?;
    m.add_function(wrap_pyfunction!(sample::null_scene, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
