//! `sample`: distinct layouts that keep the rules (docs/guide.md#sampling,
//! `rccpack_core::sample`), as a Python iterator.
//!
//! The core's sampler owns a solver engine that stays on the thread that
//! made it, so each Python `Sampler` has one worker thread: it makes the
//! sampler (the optimum's solve included) and draws one layout per request.
//! The calling thread waits with the GIL released and every 50 ms runs
//! Python's signal handlers: Ctrl-C sets the core's cancel flag, the draw
//! stops, the iterator ends and the `KeyboardInterrupt` propagates.

use crate::errors::{Error, InternalError, SampleError as PySampleError};
use crate::rules::PyRuleSet;
use crate::scene::{scenes_arg, PyScene};
use pyo3::exceptions::PyStopIteration;
use pyo3::prelude::*;
use rccpack_core::sample::{sample as core_sample, Quality, Repair, SampleError, SampleOptions};
use rccpack_core::Scene as CoreScene;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The sampler's counters after a draw.
#[derive(Clone, Copy, Default)]
struct Counts {
    state: &'static str,
    skipped: usize,
    target_proven: Option<bool>,
}

enum Msg {
    Started(Result<Counts, String>),
    Item(Result<Option<CoreScene>, SampleError>, Counts),
    Panicked(String),
}

struct Inner {
    requests: Option<Sender<()>>,
    replies: Mutex<Receiver<Msg>>,
    counts: Counts,
    done: bool,
    limit_reached: bool,
    returned: usize,
}

/// The iterator of `rccpack.sample`: distinct complete layouts.
#[pyclass(module = "rccpack", name = "Sampler")]
pub struct PySampler {
    inner: Mutex<Inner>,
    cancel: Arc<AtomicBool>,
    n: Option<usize>,
}

fn panic_text(p: Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

fn counts(s: &rccpack_core::Sampler) -> Counts {
    Counts {
        state: match s.state() {
            rccpack_core::sample::State::Running => "running",
            rccpack_core::sample::State::Exhausted => "exhausted",
            rccpack_core::sample::State::Stopped => "stopped",
        },
        skipped: s.skipped(),
        target_proven: s.target_proven(),
    }
}

fn sample_error(e: SampleError) -> PyErr {
    let kind = match &e {
        SampleError::Infeasible(_) => "infeasible",
        SampleError::NoLayout { .. } => "no_layout",
        SampleError::LimitReached { .. } => "limit",
        SampleError::BadMinScore(_) => "bad_min_score",
        SampleError::Synth(_) => "synth",
        _ => "other",
    };
    let text = match &e {
        SampleError::Infeasible(c) => {
            format!(
                "infeasible: {}",
                rccpack_core::synth::report::conflict_text(c)
            )
        }
        other => other.to_string(),
    };
    let err = PySampleError::new_err(text);
    Python::attach(|py| {
        let _ = err.value(py).setattr("kind", kind);
    });
    err
}

/// Wait for the worker's next message with the GIL released, running the
/// signal handlers every 50 ms; a handler's exception sets `cancel` and is
/// returned with the message that follows it.
fn wait(
    py: Python<'_>,
    rx: &Mutex<Receiver<Msg>>,
    cancel: &AtomicBool,
) -> (Option<Msg>, Option<PyErr>) {
    let mut signal = None;
    loop {
        let got = py.detach(|| match rx.lock() {
            Ok(rx) => rx.recv_timeout(Duration::from_millis(50)),
            Err(_) => Err(RecvTimeoutError::Disconnected),
        });
        match got {
            Ok(m) => return (Some(m), signal),
            Err(RecvTimeoutError::Disconnected) => return (None, signal),
            Err(RecvTimeoutError::Timeout) => {
                if signal.is_none() {
                    if let Err(e) = py.check_signals() {
                        signal = Some(e);
                        cancel.store(true, Ordering::SeqCst);
                    }
                }
            }
        }
    }
}

impl PySampler {
    fn busy() -> PyErr {
        Error::new_err("this Sampler is in use by another thread")
    }
}

#[pymethods]
impl PySampler {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&self, py: Python<'_>) -> PyResult<PyScene> {
        let mut inner = self.inner.try_lock().map_err(|_| Self::busy())?;
        if inner.done || self.n.is_some_and(|n| inner.returned >= n) {
            inner.done = true;
            inner.requests = None;
            return Err(PyStopIteration::new_err(()));
        }
        let sent = inner.requests.as_ref().is_some_and(|r| r.send(()).is_ok());
        if !sent {
            inner.done = true;
            return Err(PyStopIteration::new_err(()));
        }
        let (msg, signal) = wait(py, &inner.replies, &self.cancel);
        let item = match msg {
            Some(Msg::Item(item, c)) => {
                inner.counts = c;
                item
            }
            Some(Msg::Panicked(p)) => {
                inner.done = true;
                return Err(InternalError::new_err(format!(
                    "internal error (a bug, please report it): {p}"
                )));
            }
            _ => Ok(None),
        };
        if let Some(e) = signal {
            inner.done = true;
            inner.requests = None;
            return Err(e);
        }
        match item {
            Ok(Some(scene)) => {
                inner.returned += 1;
                Ok(PyScene::wrap(scene))
            }
            Ok(None) => {
                inner.done = true;
                inner.requests = None;
                Err(PyStopIteration::new_err(()))
            }
            Err(SampleError::LimitReached { .. }) => {
                inner.done = true;
                inner.limit_reached = true;
                inner.requests = None;
                Err(PyStopIteration::new_err(()))
            }
            Err(e) => {
                inner.done = true;
                inner.requests = None;
                Err(sample_error(e))
            }
        }
    }

    /// Stop drawing: the worker thread ends and the iterator is over.
    fn close(&self) -> PyResult<()> {
        self.cancel.store(true, Ordering::SeqCst);
        let mut inner = self.inner.try_lock().map_err(|_| Self::busy())?;
        inner.done = true;
        inner.requests = None;
        Ok(())
    }

    /// `"running"`, `"exhausted"` (the solver proved there is no other
    /// layout of this quality: all were returned) or `"stopped"`.
    #[getter]
    fn state(&self) -> PyResult<&'static str> {
        Ok(self
            .inner
            .try_lock()
            .map_err(|_| Self::busy())?
            .counts
            .state)
    }
    /// Layouts returned so far.
    #[getter]
    fn found(&self) -> PyResult<usize> {
        Ok(self.inner.try_lock().map_err(|_| Self::busy())?.returned)
    }
    /// Layouts drawn and skipped for scoring below `min_score`.
    #[getter]
    fn skipped(&self) -> PyResult<usize> {
        Ok(self
            .inner
            .try_lock()
            .map_err(|_| Self::busy())?
            .counts
            .skipped)
    }
    /// Whether a limit (`time_limit`, `layout_node_limit`, …) ended the
    /// iterator.
    #[getter]
    fn limit_reached(&self) -> PyResult<bool> {
        Ok(self
            .inner
            .try_lock()
            .map_err(|_| Self::busy())?
            .limit_reached)
    }
    /// With the default quality (the optimum): whether the target score is
    /// proven optimal (`False`: a limit stopped synthesis, the best found
    /// is the target); `None` for `all_rules` and `min_score`.
    #[getter]
    fn target_proven(&self) -> PyResult<Option<bool>> {
        Ok(self
            .inner
            .try_lock()
            .map_err(|_| Self::busy())?
            .counts
            .target_proven)
    }
    fn __repr__(&self) -> String {
        match self.inner.try_lock() {
            Ok(i) => format!("<Sampler {} layouts, {}>", i.returned, i.counts.state),
            Err(_) => "<Sampler (busy)>".into(),
        }
    }
}

impl Drop for PySampler {
    fn drop(&mut self) {
        // The worker stops its draw and ends when the request channel
        // closes.
        self.cancel.store(true, Ordering::SeqCst);
        if let Ok(i) = self.inner.get_mut() {
            i.requests = None;
        }
    }
}

/// Draw distinct layouts of `problem` that keep `rules`, as `rccpack
/// sample` does (the same seed gives the same layouts).
#[pyfunction]
#[pyo3(signature = (problem, rules, n = None, seed = 0, all_rules = false, min_score = None,
                    like = None, repair = "random", time_limit = None, layout_node_limit = None,
                    layout_time_limit = None, contact = "point"))]
#[allow(clippy::too_many_arguments)]
pub fn sample(
    py: Python<'_>,
    problem: &PyScene,
    rules: &PyRuleSet,
    n: Option<usize>,
    seed: u64,
    all_rules: bool,
    min_score: Option<f64>,
    like: Option<&Bound<'_, PyAny>>,
    repair: &str,
    time_limit: Option<f64>,
    layout_node_limit: Option<u64>,
    layout_time_limit: Option<f64>,
    contact: &str,
) -> PyResult<PySampler> {
    let quality = match (all_rules, min_score) {
        (true, Some(_)) => {
            return Err(Error::new_err(
                "all_rules and min_score cannot be given together",
            ))
        }
        (true, None) => Quality::AllRules,
        (false, Some(x)) => {
            if !(0.0..=1.0).contains(&x) {
                return Err(Error::new_err(format!(
                    "invalid min_score {x}: expected a number from 0 to 1"
                )));
            }
            Quality::MinScore(x)
        }
        (false, None) => Quality::Optimum,
    };
    let repair = match repair {
        "random" => Repair::Random,
        "activity" => Repair::Activity,
        other => {
            return Err(Error::new_err(format!(
                "invalid repair {other:?}: expected \"random\" or \"activity\""
            )))
        }
    };
    let like = match like {
        Some(l) if !l.is_none() => scenes_arg(l, "like")?,
        _ => Vec::new(),
    };
    crate::errors::guard(|| rccpack_core::rules::check_landmarks(&rules.inner, &problem.inner))?
        .map_err(|e| rules.error(&e))?;
    let cancel = Arc::new(AtomicBool::new(false));
    let opts = SampleOptions {
        quality,
        seed,
        contact: crate::api::contact(contact)?,
        stop: crate::api::stop(crate::api::duration(time_limit)?, None, &cancel),
        layout_time_limit: crate::api::duration(layout_time_limit)?,
        layout_node_limit,
        like,
        repair,
        ..SampleOptions::default()
    };
    let (problem, rules) = (problem.inner.clone(), rules.inner.clone());
    let (req_tx, req_rx) = channel::<()>();
    let (tx, rx) = channel::<Msg>();
    std::thread::Builder::new()
        .name("rccpack-sample".into())
        .spawn(move || {
            let made = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                core_sample(&problem, &rules, &opts)
            }));
            let mut sampler = match made {
                Ok(Ok(s)) => {
                    if tx.send(Msg::Started(Ok(counts(&s)))).is_err() {
                        return;
                    }
                    s
                }
                Ok(Err(e)) => {
                    let _ = tx.send(Msg::Item(Err(e), Counts::default()));
                    return;
                }
                Err(p) => {
                    let _ = tx.send(Msg::Panicked(panic_text(p)));
                    return;
                }
            };
            while req_rx.recv().is_ok() {
                let next =
                    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| sampler.next()));
                let msg = match next {
                    Ok(item) => Msg::Item(item.transpose(), counts(&sampler)),
                    Err(p) => Msg::Panicked(panic_text(p)),
                };
                if tx.send(msg).is_err() {
                    return;
                }
            }
        })
        .map_err(|e| Error::new_err(format!("cannot start the sampler's thread: {e}")))?;
    let rx = Mutex::new(rx);
    let (msg, signal) = wait(py, &rx, &cancel);
    if let Some(e) = signal {
        return Err(e);
    }
    let counts = match msg {
        Some(Msg::Started(Ok(c))) => c,
        Some(Msg::Item(Err(e), _)) => return Err(sample_error(e)),
        Some(Msg::Panicked(p)) | Some(Msg::Started(Err(p))) => {
            return Err(InternalError::new_err(format!(
                "internal error (a bug, please report it): {p}"
            )))
        }
        _ => return Err(InternalError::new_err("the sampler's thread ended")),
    };
    Ok(PySampler {
        inner: Mutex::new(Inner {
            requests: Some(req_tx),
            replies: rx,
            counts,
            done: false,
            limit_reached: false,
            returned: 0,
        }),
        cancel,
        n,
    })
}

pub(crate) fn add(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySampler>()?;
    m.add_function(wrap_pyfunction!(sample, m)?)?;
    Ok(())
}

/// Random scene `index` of the learner's null model (docs/guide.md#learning) with
/// `seed`: a copy of demonstration `index mod len(demos)` with its movable
/// objects re-placed at random (what `rccpack.strategies.scenes` draws).
#[pyfunction]
#[pyo3(name = "_null_scene")]
pub fn null_scene(demos: &Bound<'_, PyAny>, seed: u64, index: usize) -> PyResult<PyScene> {
    let demos = scenes_arg(demos, "demos")?;
    if demos.is_empty() {
        return Err(Error::new_err("no demonstrations"));
    }
    crate::errors::guard(|| {
        rccpack_core::infer::NullModel::new(&demos, seed).and_then(|m| m.scene(index))
    })?
    .map(PyScene::wrap)
    .map_err(crate::api::learn_error)
}
