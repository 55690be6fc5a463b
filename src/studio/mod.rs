//! The studio: a small local web app to record demonstrations, learn rules
//! from them and synthesise layouts (`rccpack studio DIR`).
//!
//! [`router`] builds the HTTP API and the page over a task folder `DIR`
//! (`problem.json`, `demos.json`, optional `statements.rcc`, `learned.rcc`,
//! `answers.json` of the "Check rules" questions).
//! The server only ever touches those fixed file names inside `DIR`; no path
//! comes from the client. Writes are atomic (temporary file + rename) and
//! serialised by one mutex. The page's assets are embedded in the binary.
//! The API is described in `docs/studio-api.md`.

mod api;

use crate::scene::Scene;
use crate::task::files;
use axum::extract::DefaultBodyLimit;
use axum::routing::{get, post};
use axum::Router;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use tower_http::limit::RequestBodyLimitLayer;

/// Largest request body accepted, in bytes (1 MiB).
pub(crate) const BODY_LIMIT: usize = 1 << 20;

/// Why the studio cannot start on a folder.
#[derive(Debug, thiserror::Error)]
pub enum StudioError {
    /// A file cannot be read or written.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// `problem.json` is not a valid scene.
    #[error("{path}: {message}")]
    Problem {
        /// The file.
        path: PathBuf,
        /// The scene error, with its field path.
        message: String,
    },
}

/// How the studio learns (`rccpack studio --priors FILE`).
#[derive(Debug, Clone, Default)]
pub struct StudioOptions {
    /// Priors learned across tasks ([`crate::priors`]) for every learning
    /// run of the studio (`POST /api/learn` and the "Check rules"
    /// questions); `None`: the uniform prior.
    pub priors: Option<Arc<crate::priors::Priors>>,
}

/// Shared server state.
pub(crate) struct AppState {
    pub dir: PathBuf,
    /// Priors for every learning run.
    pub priors: Option<Arc<crate::priors::Priors>>,
    pub problem: Scene,
    pub problem_json: serde_json::Value,
    /// Serialises every read-modify-write of the folder's files.
    pub write_lock: tokio::sync::Mutex<()>,
    /// Synthesis jobs by id (the most recent few).
    pub jobs: std::sync::Mutex<std::collections::BTreeMap<u64, api::SynthJob>>,
    pub next_job: std::sync::atomic::AtomicU64,
    /// The open "Check rules" session (docs/guide.md#questions), if any. Held across the
    /// probe search, which runs on a blocking thread.
    pub ask: Arc<tokio::sync::Mutex<Option<api::AskSession>>>,
    /// Bumped (under `write_lock`) whenever demos.json changes or learning
    /// runs through the other endpoints: a session of an older generation
    /// is dropped and the files are read again.
    pub ask_generation: std::sync::atomic::AtomicU64,
    /// The cancel flag of the learning run of `POST /api/learn` going on
    /// now, if any: a newer request cancels it (one learning job per
    /// folder), and so does its client leaving.
    pub learning: std::sync::Mutex<Option<Arc<std::sync::atomic::AtomicBool>>>,
    /// Learning runs of `POST /api/learn` still computing (shown by `GET
    /// /api/task` as `learning_jobs`).
    pub learning_jobs: Arc<std::sync::atomic::AtomicUsize>,
}

/// Build the studio's router over the task folder `dir`: reads and checks
/// `problem.json` and creates an empty `demos.json` when there is none.
pub fn router(dir: &Path) -> Result<Router, StudioError> {
    router_with(dir, StudioOptions::default())
}

/// [`router`] with options (priors for learning).
pub fn router_with(dir: &Path, opts: StudioOptions) -> Result<Router, StudioError> {
    let io = |name: &'static str, e: std::io::Error| StudioError::Io {
        path: dir.join(name),
        message: e.to_string(),
    };
    let problem = read_problem(dir)?;
    if files::read_optional(dir, files::DEMOS)
        .map_err(|e| io(files::DEMOS, e))?
        .is_none()
    {
        files::atomic_write(dir, files::DEMOS, "[]\n").map_err(|e| io(files::DEMOS, e))?;
    }
    let problem_json = serde_json::from_str(&problem.to_json()).expect("scene JSON re-parses");
    let state = Arc::new(AppState {
        dir: dir.to_path_buf(),
        priors: opts.priors,
        problem,
        problem_json,
        write_lock: tokio::sync::Mutex::new(()),
        jobs: std::sync::Mutex::new(std::collections::BTreeMap::new()),
        next_job: std::sync::atomic::AtomicU64::new(1),
        ask: Arc::new(tokio::sync::Mutex::new(None)),
        ask_generation: std::sync::atomic::AtomicU64::new(0),
        learning: std::sync::Mutex::new(None),
        learning_jobs: Arc::new(std::sync::atomic::AtomicUsize::new(0)),
    });
    Ok(routes(state))
}

/// The task folder's `problem.json`, read and checked (a missing one is
/// an error that says a task folder needs it).
fn read_problem(dir: &Path) -> Result<Scene, StudioError> {
    let path = dir.join(files::PROBLEM);
    let text = match crate::task::read_scene_text(&path) {
        Ok(t) => t,
        Err(crate::task::TaskError::NotUtf8 { source, .. }) => {
            return Err(StudioError::Problem {
                path,
                message: source.to_string(),
            })
        }
        Err(e) => {
            let missing = matches!(&e, crate::task::TaskError::Read { source, .. } if source.kind() == std::io::ErrorKind::NotFound);
            let message = match e {
                crate::task::TaskError::Read { source, .. } => {
                    format!("cannot read file: {source}")
                }
                e => e.to_string(),
            };
            return Err(StudioError::Io {
                path,
                message: if missing {
                    format!("{message} (a task folder needs a problem.json)")
                } else {
                    message
                },
            });
        }
    };
    Scene::from_json(&text).map_err(|e| StudioError::Problem {
        path: dir.join(files::PROBLEM),
        message: e.to_string(),
    })
}

/// The studio's routes and layers (local, same-origin, body limits) over
/// `state`.
fn routes(state: Arc<AppState>) -> Router {
    Router::new()
        .route("/", get(api::index))
        .route("/assets/{name}", get(api::asset))
        .route("/api/task", get(api::task))
        .route("/api/demos", get(api::list_demos).post(api::save_demo))
        .route(
            "/api/demos/{index}",
            get(api::get_demo).delete(api::delete_demo),
        )
        .route("/api/learn", post(api::learn))
        .route("/api/learned", get(api::get_learned).put(api::put_learned))
        .route("/api/ask/next", post(api::ask_next))
        .route("/api/ask/answer", post(api::ask_answer))
        .route("/api/synth", post(api::start_synth))
        .route("/api/sample", post(api::sample_layout))
        .route("/api/synth/{job}", get(api::synth_status))
        .route("/api/synth/{job}/cancel", post(api::cancel_synth))
        .fallback(api::not_found)
        .layer(axum::middleware::from_fn(api::same_origin_only))
        .layer(axum::middleware::from_fn(api::local_host_only))
        .layer(DefaultBodyLimit::max(BODY_LIMIT))
        .layer(RequestBodyLimitLayer::new(BODY_LIMIT))
        .layer(axum::middleware::from_fn(api::json_413))
        .with_state(state)
}
