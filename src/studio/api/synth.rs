//! `/api/synth`: synthesis jobs — started, polled and cancelled; the most
//! recent few are kept.

use super::demos::read_demos;
use super::learned::parse_checked;
use super::{ok, parse_body, reply, scene_value, ApiError, ApiResult, St};
use crate::limits::cut;
use crate::synth::{Progress, ProgressFn, SynthOptions, SynthResult};
use crate::task::files;
use crate::task::Like;
use axum::body::Bytes;
use axum::extract::{Path, State};
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// One synthesis run: started by `POST /api/synth`, polled, cancellable.
pub(crate) struct SynthJob {
    cancel: Arc<AtomicBool>,
    started: Instant,
    best: Arc<Mutex<Option<f64>>>,
    outcome: Option<Result<Value, String>>,
}

/// Jobs kept for polling; older ones are dropped.
const KEEP_JOBS: usize = 8;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct SynthBody {
    /// The rules, as `.rcc` text (the page sends the chosen rules).
    rules: String,
    /// Seconds (default 30, at most 600).
    time_limit: Option<f64>,
    seed: Option<u64>,
    /// Prefer layouts like the saved demonstrations (docs/guide.md#layouts-like-the-demonstrations; default
    /// true).
    like: Option<bool>,
}

pub(super) const CHOSEN: &str = "chosen rules";

/// Largest `time_limit` of `POST /api/synth`, in seconds.
const STUDIO_MAX_TIME_LIMIT_SECS: u64 = 600;

pub(crate) async fn start_synth(State(st): St, body: Bytes) -> ApiResult {
    let b: SynthBody = parse_body(&body)?;
    let (set, _) = parse_checked(&st, CHOSEN, b.rules).await?;
    // docs/language.md#classes-a-scene-lacks: the chosen rules are learned ones; a class the problem
    // lacks is noted, not refused.
    let note = crate::rules::absent_classes_note(&set, &st.problem);
    let secs = b.time_limit.unwrap_or(30.0);
    // The shared validated parser, then the studio's own tighter cap.
    let limit = crate::limits::time_limit(secs)
        .ok()
        .filter(|d| !d.is_zero() && *d <= Duration::from_secs(STUDIO_MAX_TIME_LIMIT_SECS))
        .ok_or_else(|| {
            ApiError::bad(format!(
                "request body: time_limit: {} is out of range; expected seconds in (0, {STUDIO_MAX_TIME_LIMIT_SECS}]",
                crate::limits::number(secs)
            ))
            .at("time_limit")
        })?;
    let demos = read_demos(&st)?;
    let like = if b.like.unwrap_or(true) {
        Like::Demos
    } else {
        Like::Off
    };
    let cancel = Arc::new(AtomicBool::new(false));
    let best = Arc::new(Mutex::new(None));
    let id = st.next_job.fetch_add(1, Ordering::Relaxed);
    {
        let mut jobs = st.jobs.lock().expect("jobs lock");
        while jobs.len() >= KEEP_JOBS {
            let oldest = *jobs.keys().next().expect("non-empty");
            if let Some(j) = jobs.remove(&oldest) {
                j.cancel.store(true, Ordering::Relaxed);
            }
        }
        jobs.insert(
            id,
            SynthJob {
                cancel: cancel.clone(),
                started: Instant::now(),
                best: best.clone(),
                outcome: None,
            },
        );
    }
    let progress_best = best.clone();
    let opts = SynthOptions {
        stop: crate::stop::Stop::after(limit).with_cancel(cancel),
        seed: b.seed.unwrap_or(0),
        progress: Some(ProgressFn(Arc::new(move |p: &Progress| {
            *progress_best.lock().expect("best lock") = Some(p.score);
        }))),
        ..SynthOptions::default()
    };
    let st2 = st.clone();
    tokio::task::spawn_blocking(move || {
        // The solver is not `Send`: it is created and run on this thread.
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            crate::task::place(&st2.problem, &set, &demos, &like, &opts)
        }));
        let outcome = match outcome {
            Ok(Ok(placed)) => Ok(synth_value(&placed.result)),
            Ok(Err(e)) => Err(format!("{}: {e}", files::PROBLEM)),
            Err(_) => Err("synthesis failed unexpectedly (internal error)".to_string()),
        };
        if let Some(j) = st2.jobs.lock().expect("jobs lock").get_mut(&id) {
            j.outcome = Some(outcome);
        }
    });
    Ok(reply(StatusCode::ACCEPTED, &Started { job: id, note }))
}

/// The body of `POST /api/synth` (`202 Accepted`).
#[derive(Serialize)]
struct Started {
    /// The job's id, for polling.
    job: u64,
    /// The classes of the rules that the problem lacks.
    note: Option<String>,
}

/// A finished job's result.
#[derive(Serialize)]
struct SynthDone<'a> {
    conflict: &'a Option<crate::synth::Conflict>,
    evaluation: Option<&'a crate::eval::Evaluation>,
    resemblance: &'a Option<crate::synth::Resemblance>,
    satisfied_weight: Option<f64>,
    scene: Option<Value>,
    score: Option<f64>,
    stats: &'a crate::synth::SolveStats,
    status: crate::synth::Status,
    time_ms: f64,
    total_weight: Option<f64>,
}

/// The body of `GET /api/synth/{job}`.
#[derive(Serialize)]
struct JobStatus<'a> {
    best_score: Option<f64>,
    cancelled: bool,
    elapsed_ms: f64,
    /// Why the job failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<&'a str>,
    job: u64,
    /// A finished job's [`SynthDone`].
    #[serde(skip_serializing_if = "Option::is_none")]
    result: Option<&'a Value>,
    /// `running`, `done` or `error`.
    state: &'static str,
}

/// The body of `POST /api/synth/{job}/cancel`.
#[derive(Serialize)]
struct Cancelled {
    cancelled: bool,
    job: u64,
}

/// A finished job's result, kept for polling.
fn synth_value(r: &SynthResult) -> Value {
    let e = r.evaluation.as_ref();
    let done = SynthDone {
        conflict: &r.conflict,
        evaluation: e,
        resemblance: &r.resemblance,
        satisfied_weight: e.map(|e| e.satisfied_weight),
        scene: r.scene.as_ref().map(scene_value),
        score: e.map(|e| e.score),
        stats: &r.stats,
        status: r.status,
        time_ms: r.stats.time_ms,
        total_weight: e.map(|e| e.total_weight),
    };
    serde_json::to_value(&done).expect("a synthesis result serialises")
}

fn job_id(raw: &str) -> Result<u64, ApiError> {
    raw.parse().map_err(|_| {
        ApiError::new(
            StatusCode::NOT_FOUND,
            format!("no synthesis job {}", cut(raw)),
        )
    })
}

pub(crate) async fn synth_status(State(st): St, Path(job): Path<String>) -> ApiResult {
    let id = job_id(&job)?;
    let jobs = st.jobs.lock().expect("jobs lock");
    let j = jobs
        .get(&id)
        .ok_or_else(|| ApiError::new(StatusCode::NOT_FOUND, format!("no synthesis job {id}")))?;
    let body = JobStatus {
        best_score: *j.best.lock().expect("best lock"),
        cancelled: j.cancel.load(Ordering::Relaxed),
        elapsed_ms: j.started.elapsed().as_secs_f64() * 1000.0,
        error: match &j.outcome {
            Some(Err(e)) => Some(e),
            _ => None,
        },
        job: id,
        result: match &j.outcome {
            Some(Ok(r)) => Some(r),
            _ => None,
        },
        state: match &j.outcome {
            None => "running",
            Some(Ok(_)) => "done",
            Some(Err(_)) => "error",
        },
    };
    ok(&body)
}

pub(crate) async fn cancel_synth(State(st): St, Path(job): Path<String>) -> ApiResult {
    let id = job_id(&job)?;
    let jobs = st.jobs.lock().expect("jobs lock");
    let j = jobs
        .get(&id)
        .ok_or_else(|| ApiError::new(StatusCode::NOT_FOUND, format!("no synthesis job {id}")))?;
    j.cancel.store(true, Ordering::Relaxed);
    ok(&Cancelled {
        cancelled: true,
        job: id,
    })
}
