//! `POST /api/sample`: another layout as good as the one shown.

use super::demos::read_demos;
use super::learned::parse_checked;
use super::synth::CHOSEN;
use super::{ok, parse_body, scene_value, ApiError, ApiResult, St};
use crate::task::files;
use axum::body::Bytes;
use axum::extract::State;
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::time::Duration;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct SampleRequest {
    /// The rules, as `.rcc` text (the rules of the layout shown).
    rules: String,
    /// The score the other layout must reach (the shown layout's).
    min_score: Option<f64>,
    /// Which draw: the page counts 1, 2, 3, …
    seed: Option<u64>,
}

/// The body of `POST /api/sample`: a synthesis result's form, marked
/// `sampled`.
#[derive(Serialize)]
struct Sampled {
    /// Always null: a sampled layout has no conflict.
    conflict: Option<Value>,
    evaluation: crate::eval::Evaluation,
    sampled: bool,
    satisfied_weight: f64,
    scene: Value,
    score: f64,
    status: &'static str,
    total_weight: f64,
}

/// How long `POST /api/sample` may look for a layout.
const SAMPLE_TIME_LIMIT: Duration = Duration::from_secs(10);

/// `POST /api/sample`: "another layout like this" — one layout drawn by
/// [`crate::sample()`] at least as good as the shown one (`min_score` 1:
/// every rule kept; below: the optimum score), leaning towards the saved
/// demonstrations; each `seed` gives another draw.
pub(crate) async fn sample_layout(State(st): St, body: Bytes) -> ApiResult {
    let b: SampleRequest = parse_body(&body)?;
    let (set, _) = parse_checked(&st, CHOSEN, b.rules).await?;
    let min = b.min_score.unwrap_or(1.0);
    if !(0.0..=1.0).contains(&min) {
        return Err(ApiError::bad(format!(
            "request body: min_score: {} is out of range; expected a number from 0 to 1",
            crate::limits::number(min)
        ))
        .at("min_score"));
    }
    // Score 1: layouts that keep every rule; below: layouts of the optimum
    // score, which the synthesized layout's score never exceeds (the
    // conservative bound of `MinScore` below 1 can be slow).
    let quality = if min >= 1.0 {
        crate::sample::Quality::AllRules
    } else {
        crate::sample::Quality::Optimum
    };
    let opts = crate::sample::SampleOptions {
        quality,
        seed: b.seed.unwrap_or(0),
        stop: crate::stop::Stop::after(SAMPLE_TIME_LIMIT),
        like: read_demos(&st)?,
        ..crate::sample::SampleOptions::default()
    };
    let st2 = st.clone();
    let drawn = tokio::task::spawn_blocking(move || {
        // The engine is not `Send`: built and run on this thread.
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let mut sampler = crate::sample::sample(&st2.problem, &set, &opts)?;
            sampler.next().transpose().map(|s| s.map(|s| (s, set)))
        }))
    })
    .await
    .ok()
    .and_then(Result::ok)
    .ok_or_else(|| {
        ApiError::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "sampling failed unexpectedly (internal error)",
        )
    })?;
    match drawn {
        Ok(Some((scene, set))) => {
            let evaluation = crate::eval::evaluate(&scene, &set, crate::relations::Contact::Point);
            ok(&Sampled {
                conflict: None,
                sampled: true,
                satisfied_weight: evaluation.satisfied_weight,
                scene: scene_value(&scene),
                score: evaluation.score,
                total_weight: evaluation.total_weight,
                evaluation,
                status: "feasible",
            })
        }
        Ok(None) => Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "no other layout of this score exists".to_string(),
        )),
        Err(e) => Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            format!("{}: {e}", files::PROBLEM),
        )),
    }
}
