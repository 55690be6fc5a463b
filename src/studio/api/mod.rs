//! HTTP handlers, one file per route group. Every error is JSON
//! `{"error": "...", "path": "..."}` with a message in the same words as
//! the command-line tool.
//!
//! Every body is a typed `#[derive(Serialize)]` struct, written through
//! [`serde_json::Value`]: the keys of every object come out sorted, at every
//! depth (the library's own types, such as evaluations and statistics,
//! included). The structs list their fields in that order, so a struct
//! reads as its body does.

mod ask;
mod demos;
mod guard;
mod learn;
mod learned;
mod page;
mod sample;
mod synth;
mod task;

pub(crate) use ask::{ask_answer, ask_next, AskSession};
pub(crate) use demos::{delete_demo, get_demo, list_demos, save_demo};
pub(crate) use guard::{json_413, local_host_only, same_origin_only};
pub(crate) use learn::learn;
pub(crate) use learned::{get_learned, put_learned};
pub(crate) use page::{asset, index, not_found};
pub(crate) use sample::sample_layout;
pub(crate) use synth::{cancel_synth, start_synth, synth_status, SynthJob};
pub(crate) use task::task;

use super::AppState;
use axum::extract::State;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

type St = State<Arc<AppState>>;

/// An error answer: status, message, optional field path and the optional
/// fields some errors carry.
pub(crate) struct ApiError {
    status: StatusCode,
    message: String,
    path: Option<String>,
    kind: Option<&'static str>,
    file: Option<String>,
    current: Option<Box<learned::LearnedView>>,
}

/// The body of an error answer.
#[derive(Serialize)]
struct ErrorBody {
    /// `learned.rcc` as it is on disk now (a refused write).
    #[serde(skip_serializing_if = "Option::is_none")]
    current: Option<Box<learned::LearnedView>>,
    error: String,
    /// The rules file a parse error is about.
    #[serde(skip_serializing_if = "Option::is_none")]
    file: Option<String>,
    /// A machine-readable reason (`folder_locked`, `stale_demos`, …).
    #[serde(skip_serializing_if = "Option::is_none")]
    kind: Option<&'static str>,
    /// The field path of the request body or scene at fault.
    #[serde(skip_serializing_if = "Option::is_none")]
    path: Option<String>,
}

impl ApiError {
    fn new(status: StatusCode, message: impl Into<String>) -> Self {
        ApiError {
            status,
            message: message.into(),
            path: None,
            kind: None,
            file: None,
            current: None,
        }
    }
    fn bad(message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, message)
    }
    fn at(mut self, path: impl Into<String>) -> Self {
        self.path = Some(path.into());
        self
    }
    fn kind(mut self, kind: &'static str) -> Self {
        self.kind = Some(kind);
        self
    }
    fn file(mut self, file: &str) -> Self {
        self.file = Some(file.to_string());
        self
    }
    fn current(mut self, current: learned::LearnedView) -> Self {
        self.current = Some(Box::new(current));
        self
    }
    fn io(name: &str, e: std::io::Error) -> Self {
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("{name}: cannot access file: {e}"),
        )
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = ErrorBody {
            current: self.current,
            error: self.message,
            file: self.file,
            kind: self.kind,
            path: self.path,
        };
        reply(self.status, &body)
    }
}

type ApiResult = Result<Response, ApiError>;

/// A JSON answer with `status`: `body` through [`serde_json::Value`], so
/// that every object's keys are sorted.
fn reply<T: Serialize>(status: StatusCode, body: &T) -> Response {
    let value = serde_json::to_value(body).expect("a response body serialises");
    (status, Json(value)).into_response()
}

/// `200 OK` with `body`.
fn ok<T: Serialize>(body: &T) -> ApiResult {
    Ok(reply(StatusCode::OK, body))
}

/// A failure of the server itself (a worker thread panicked).
fn internal(what: &str) -> ApiError {
    ApiError::new(
        StatusCode::INTERNAL_SERVER_ERROR,
        format!("{what} failed unexpectedly (internal error); the question was dropped, ask again"),
    )
}

/// Run `f` (parsing, validation: work that grows with the input) on a
/// blocking thread, so one large request never stalls the other routes.
async fn off_async<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    tokio::task::spawn_blocking(f)
        .await
        .map_err(|_| internal("reading the files"))?
}

/// Parse a JSON body (empty = default) with field-path errors.
fn parse_body<T: for<'de> Deserialize<'de> + Default>(body: &[u8]) -> Result<T, ApiError> {
    if body.iter().all(u8::is_ascii_whitespace) {
        return Ok(T::default());
    }
    let de = &mut serde_json::Deserializer::from_slice(body);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        ApiError::bad(format!("request body: {path}: {}", e.into_inner())).at(path)
    })
}

/// A scene as a JSON value (its keys sorted like every body's).
fn scene_value(s: &crate::scene::Scene) -> serde_json::Value {
    serde_json::from_str(&s.to_json()).expect("scene JSON re-parses")
}
