//! HTTP handlers. Every error is JSON `{"error": "...", "path": "..."}` with a
//! message in the same words as the command-line tool.

use super::storage::{self, ANSWERS, DEMOS, LEARNED, LEARNED_BACKUP, STATEMENTS};
use super::AppState;
use crate::ask::{Answer, AnswersFile, AskError, AskOptions, Asker, ProbeOptions, Question};
use crate::infer::{learn_with_priors, statement_text, LearnParams, StatementSource};
use crate::limits::cut;
use crate::rules::{
    check_classes, check_landmarks, missing_classes, missing_classes_note, parse_rules, RuleSet,
};
use crate::scene::{scenes_from_json, scenes_to_json, Scene};
use crate::synth::{Progress, ProgressFn, SynthOptions, SynthResult};
use crate::task::Like;
use axum::body::Bytes;
use axum::extract::{Path, Query, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use serde_json::{json, Value};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

type St = State<Arc<AppState>>;

/// An error answer: status, message, optional field path and extra fields.
pub(crate) struct ApiError {
    status: StatusCode,
    message: String,
    path: Option<String>,
    extra: Option<(&'static str, Value)>,
}

impl ApiError {
    fn new(status: StatusCode, message: impl Into<String>) -> Self {
        ApiError {
            status,
            message: message.into(),
            path: None,
            extra: None,
        }
    }
    fn bad(message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, message)
    }
    fn at(mut self, path: impl Into<String>) -> Self {
        self.path = Some(path.into());
        self
    }
    fn with(mut self, key: &'static str, v: Value) -> Self {
        self.extra = Some((key, v));
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
        let mut body = json!({ "error": self.message });
        if let Some(p) = self.path {
            body["path"] = Value::String(p);
        }
        if let Some((k, v)) = self.extra {
            body[k] = v;
        }
        (self.status, Json(body)).into_response()
    }
}

type ApiResult = Result<Response, ApiError>;

fn ok(v: Value) -> ApiResult {
    Ok(Json(v).into_response())
}

// ---- page ------------------------------------------------------------------

const INDEX_HTML: &str = include_str!("assets/index.html");
const APP_JS: &str = include_str!("assets/app.js");
const BOARD_JS: &str = include_str!("assets/board.js");
const STYLE_CSS: &str = include_str!("assets/style.css");

pub(crate) async fn index() -> Response {
    (
        [
            (header::CONTENT_TYPE, "text/html; charset=utf-8"),
            (header::CACHE_CONTROL, "no-store"),
        ],
        INDEX_HTML,
    )
        .into_response()
}

pub(crate) async fn asset(Path(name): Path<String>) -> Response {
    let (body, ty) = match name.as_str() {
        "app.js" => (APP_JS, "text/javascript; charset=utf-8"),
        "board.js" => (BOARD_JS, "text/javascript; charset=utf-8"),
        "style.css" => (STYLE_CSS, "text/css; charset=utf-8"),
        _ => return not_found().await.into_response(),
    };
    (
        [
            (header::CONTENT_TYPE, ty),
            (header::CACHE_CONTROL, "no-store"),
        ],
        body,
    )
        .into_response()
}

pub(crate) async fn not_found() -> ApiError {
    ApiError::new(StatusCode::NOT_FOUND, "no such page or API endpoint")
}

/// Refuse requests whose `Host` names anything but this machine's loopback
/// (a page elsewhere reaching the studio through DNS rebinding).
pub(crate) async fn local_host_only(
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    if let Some(h) = req.headers().get(header::HOST) {
        let host = h.to_str().unwrap_or("");
        let name = match host.rsplit_once(':') {
            Some((n, port)) if port.bytes().all(|b| b.is_ascii_digit()) => n,
            _ => host,
        };
        if !matches!(name, "127.0.0.1" | "localhost" | "[::1]") {
            return ApiError::new(
                StatusCode::FORBIDDEN,
                format!(
                    "host `{}` refused: the studio answers only on 127.0.0.1",
                    cut(host)
                ),
            )
            .into_response();
        }
    }
    next.run(req).await
}

/// Refuse every request that changes a file or starts work (any method but
/// `GET`/`HEAD`) unless it comes from the studio's own page (SPEC §15
/// "Trust of the studio"): an `Origin` header, when sent, must be this
/// server's own (`http://` + the `Host` header; `null` and every other
/// origin are refused); a `Sec-Fetch-Site` header, when sent, must be
/// `same-origin` (or `none`, typed by the person); and the body must be
/// declared `application/json` — a type a page elsewhere cannot send
/// without a CORS preflight, which the studio never grants. Requests with
/// no `Origin` (curl, scripts on this machine) pass these checks.
pub(crate) async fn same_origin_only(
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    use axum::http::Method;
    if matches!(*req.method(), Method::GET | Method::HEAD) {
        return next.run(req).await;
    }
    let headers = req.headers();
    let text = |name: &str| {
        headers
            .get(name)
            .map(|v| String::from_utf8_lossy(v.as_bytes()).into_owned())
    };
    let refuse = |why: String| {
        ApiError::new(StatusCode::FORBIDDEN, why)
            .with("kind", json!("foreign_request"))
            .into_response()
    };
    if let Some(origin) = text("origin") {
        let host = text("host");
        let own = match &host {
            Some(h) => origin.eq_ignore_ascii_case(&format!("http://{h}")),
            // No Host (HTTP/1.0, tests): a loopback origin only.
            None => origin
                .strip_prefix("http://")
                .map(|o| match o.rsplit_once(':') {
                    Some((n, p)) if p.bytes().all(|b| b.is_ascii_digit()) => n,
                    _ => o,
                })
                .is_some_and(|n| matches!(n, "127.0.0.1" | "localhost" | "[::1]")),
        };
        if !own {
            return refuse(format!(
                "origin `{}` refused: only the studio's own page may change files or start work",
                cut(&origin)
            ));
        }
    }
    if let Some(site) = text("sec-fetch-site") {
        if !matches!(site.as_str(), "same-origin" | "none") {
            return refuse(format!(
                "a {} request refused (Sec-Fetch-Site: {}): only the studio's own page may change files or start work",
                req.method(),
                cut(&site)
            ));
        }
    }
    let json_body = text("content-type").is_some_and(|t| {
        t.split(';')
            .next()
            .is_some_and(|m| m.trim().eq_ignore_ascii_case("application/json"))
    });
    if !json_body {
        return refuse(format!(
            "content type `{}` refused; expected application/json (a {} request changes files or starts work)",
            cut(&text("content-type").unwrap_or_else(|| "(none)".into())),
            req.method()
        ));
    }
    next.run(req).await
}

/// Answer a body past [`super::BODY_LIMIT`] with the studio's JSON error
/// form (the body-limit layers answer 413 in plain text), and a method a
/// route does not take too (the router answers 405 with an empty body).
pub(crate) async fn json_413(
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    let res = next.run(req).await;
    let is_json = res
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|t| t.as_bytes().starts_with(b"application/json"));
    if res.status() == StatusCode::PAYLOAD_TOO_LARGE && !is_json {
        return ApiError::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!(
                "request body is too large; expected at most {} bytes (1 MiB)",
                super::BODY_LIMIT
            ),
        )
        .with("kind", json!("too_large"))
        .into_response();
    }
    if res.status() == StatusCode::METHOD_NOT_ALLOWED && !is_json {
        // The router's 405 has an empty body; every error is JSON.
        let allow = res.headers().get(header::ALLOW).cloned();
        let mut r = ApiError::new(
            StatusCode::METHOD_NOT_ALLOWED,
            format!(
                "method not allowed here; expected {}",
                allow
                    .as_ref()
                    .and_then(|a| a.to_str().ok())
                    .unwrap_or("another method (see docs/studio-api.md)")
            ),
        )
        .with("kind", json!("method_not_allowed"))
        .into_response();
        if let Some(a) = allow {
            r.headers_mut().insert(header::ALLOW, a);
        }
        return r;
    }
    res
}

// ---- task --------------------------------------------------------------------

/// Class colours exactly as `render` draws them.
fn class_colours(scene: &Scene) -> HashMap<String, &'static str> {
    crate::render::class_colours(scene)
}

pub(crate) async fn task(State(st): St) -> ApiResult {
    let p = &st.problem;
    let mut kinds: Vec<(String, i64, i64, usize)> = Vec::new();
    for o in p.objects.iter().filter(|o| !o.fixed) {
        match kinds
            .iter_mut()
            .find(|k| k.0 == o.class && k.1 == o.width && k.2 == o.height)
        {
            Some(k) => k.3 += 1,
            None => kinds.push((o.class.clone(), o.width, o.height, 1)),
        }
    }
    let colours = class_colours(p);
    let kinds: Vec<Value> = kinds
        .into_iter()
        .map(|(class, width, height, count)| {
            json!({"class": class, "width": width, "height": height, "count": count,
                   "colour": colours.get(&class).copied().unwrap_or("#888888")})
        })
        .collect();
    let name = st
        .dir
        .canonicalize()
        .ok()
        .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| "task".into());
    let statements = storage::read_optional(&st.dir, STATEMENTS)
        .map_err(|e| ApiError::io(STATEMENTS, e))?
        .is_some();
    ok(json!({
        "name": name,
        "problem": st.problem_json,
        "kinds": kinds,
        "colours": colours,
        "fixed_colour": "#4a4a4a",
        "statements": statements,
        "learning_jobs": st.learning_jobs.load(Ordering::SeqCst),
        "priors": st.priors.as_ref().map(|p| json!({"tasks": p.tasks, "hash": p.hash_text()})),
    }))
}

// ---- demonstrations ------------------------------------------------------------

/// Read demos.json; a file that does not parse is reported (409) and never
/// overwritten.
fn read_demos(st: &AppState) -> Result<Vec<Scene>, ApiError> {
    read_demos_versioned(st).map(|(d, _)| d)
}

/// The demonstrations and the version of the file they came from.
fn read_demos_versioned(st: &AppState) -> Result<(Vec<Scene>, String), ApiError> {
    let text = storage::read_optional(&st.dir, DEMOS)
        .map_err(|e| {
            // Not UTF-8: corrupt like any other bad content (409), not a
            // failure of the server.
            if e.kind() == std::io::ErrorKind::InvalidData {
                corrupt(&e.to_string())
            } else {
                ApiError::io(DEMOS, e)
            }
        })?
        .unwrap_or_else(|| "[]".into());
    if !text.trim_start().starts_with('[') {
        return Err(corrupt("expected a JSON array of scenes"));
    }
    let demos = scenes_from_json(&text).map_err(|e| corrupt(&e.to_string()))?;
    Ok((demos, storage::version(Some(&text))))
}

/// The task folder's lock (shared with `rccpack ask`), taken while
/// writing; a 409 naming it when an `ask` session holds it.
fn folder_lock(st: &AppState) -> Result<crate::fsutil::DirLock, ApiError> {
    match crate::fsutil::DirLock::try_lock(&st.dir) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err(ApiError::new(
            StatusCode::CONFLICT,
            format!(
                "the task folder is in use by `rccpack ask` (it holds {}); nothing was written — try again when it ends",
                crate::fsutil::LOCK_FILE
            ),
        )
        .with("kind", json!("folder_locked"))),
        Err(e) => Err(ApiError::io(crate::fsutil::LOCK_FILE, e)),
    }
}

fn corrupt(why: &str) -> ApiError {
    ApiError::new(
        StatusCode::CONFLICT,
        format!(
            "{DEMOS}: {why}; the studio will not overwrite it — fix or move the file, then reload"
        ),
    )
    .with("kind", json!("corrupt_demos"))
}

fn scene_value(s: &Scene) -> Value {
    serde_json::from_str(&s.to_json()).expect("scene JSON re-parses")
}

/// Parse a posted demonstration and check it as `check`/`score` would, plus
/// that it is a complete layout of this task.
fn parse_demo(st: &AppState, body: &[u8]) -> Result<Scene, ApiError> {
    let text = std::str::from_utf8(body).map_err(|_| ApiError::bad("request body is not UTF-8"))?;
    let scene = Scene::from_json(text).map_err(|e| {
        let path = e.path().to_string();
        ApiError::bad(format!("demonstration: {e}")).at(path)
    })?;
    let p = &st.problem;
    if scene.space != p.space {
        return Err(ApiError::bad(format!(
            "demonstration: space: {}x{} at ({}, {}) differs from {}'s {}x{} at ({}, {})",
            scene.space.width,
            scene.space.height,
            scene.space.x,
            scene.space.y,
            storage::PROBLEM,
            p.space.width,
            p.space.height,
            p.space.x,
            p.space.y
        ))
        .at("space"));
    }
    if scene.grid != p.grid {
        return Err(ApiError::bad(format!(
            "demonstration: grid: {} differs from {}'s {}",
            scene.grid,
            storage::PROBLEM,
            p.grid
        ))
        .at("grid"));
    }
    for (i, o) in scene.objects.iter().enumerate() {
        if !o.is_placed() {
            return Err(ApiError::bad(format!(
                "demonstration: objects[{i}]: object `{}` has no position; every object of a demonstration must be placed",
                o.id
            ))
            .at(format!("objects[{i}]")));
        }
        if o.fixed {
            if !p
                .objects
                .iter()
                .any(|f| f.fixed && f.id == o.id && f.rect() == o.rect() && f.class == o.class)
            {
                return Err(ApiError::bad(format!(
                    "demonstration: objects[{i}]: fixed object `{}` is not a fixed object of {} (fixed objects never move)",
                    o.id,
                    storage::PROBLEM
                ))
                .at(format!("objects[{i}]")));
            }
        } else if !p
            .objects
            .iter()
            .any(|k| !k.fixed && k.class == o.class && k.width == o.width && k.height == o.height)
        {
            return Err(ApiError::bad(format!(
                "demonstration: objects[{i}]: object `{}` ({} {}x{}) is not one of the kinds of objects of {}",
                o.id,
                o.class,
                o.width,
                o.height,
                storage::PROBLEM
            ))
            .at(format!("objects[{i}]")));
        }
    }
    for f in p.objects.iter().filter(|o| o.fixed) {
        if !scene.objects.iter().any(|o| o.fixed && o.id == f.id) {
            return Err(ApiError::bad(format!(
                "demonstration: objects: fixed object `{}` of {} is missing",
                f.id,
                storage::PROBLEM
            ))
            .at("objects"));
        }
    }
    if !scene.objects.iter().any(|o| !o.fixed) {
        return Err(ApiError::bad(
            "demonstration: objects: place at least one object before saving",
        )
        .at("objects"));
    }
    Ok(scene)
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

pub(crate) async fn list_demos(State(st): St) -> ApiResult {
    let st2 = st.clone();
    let v = off_async(move || {
        let (demos, version) = read_demos_versioned(&st2)?;
        Ok(json!({
            "count": demos.len(),
            "version": version,
            "demos": demos.iter().map(scene_value).collect::<Vec<_>>(),
        }))
    })
    .await?;
    ok(v)
}

pub(crate) async fn save_demo(State(st): St, body: Bytes) -> ApiResult {
    let st2 = st.clone();
    let scene = off_async(move || parse_demo(&st2, &body)).await?;
    let _guard = st.write_lock.lock().await;
    let _folder = folder_lock(&st)?;
    let mut demos = read_demos(&st)?;
    demos.push(scene);
    st.reset_ask();
    storage::atomic_write(&st.dir, DEMOS, &scenes_to_json(&demos))
        .map_err(|e| ApiError::io(DEMOS, e))?;
    Ok((
        StatusCode::CREATED,
        Json(json!({"index": demos.len() - 1, "count": demos.len()})),
    )
        .into_response())
}

fn demo_index(raw: &str, len: usize) -> Result<usize, ApiError> {
    match raw.parse::<usize>() {
        Ok(i) if i < len => Ok(i),
        _ => Err(ApiError::new(
            StatusCode::NOT_FOUND,
            format!("no demonstration [{raw}]; {DEMOS} holds {len}"),
        )),
    }
}

pub(crate) async fn get_demo(State(st): St, Path(index): Path<String>) -> ApiResult {
    let st2 = st.clone();
    let v = off_async(move || {
        let demos = read_demos(&st2)?;
        let i = demo_index(&index, demos.len())?;
        Ok(scene_value(&demos[i]))
    })
    .await?;
    ok(v)
}

#[derive(Deserialize)]
pub(crate) struct DeleteQuery {
    /// The `version` from `GET /api/demos`: refuse when the file changed
    /// since (another tab saved or deleted), so the index still means the
    /// demonstration the user saw.
    version: Option<String>,
}

pub(crate) async fn delete_demo(
    State(st): St,
    Path(index): Path<String>,
    Query(q): Query<DeleteQuery>,
) -> ApiResult {
    let _guard = st.write_lock.lock().await;
    let _folder = folder_lock(&st)?;
    let (mut demos, version) = read_demos_versioned(&st)?;
    if q.version.as_ref().is_some_and(|v| *v != version) {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("{DEMOS} changed since the page listed it (another tab?); nothing deleted — reload the list and try again"),
        )
        .with("kind", json!("stale_demos")));
    }
    let i = demo_index(&index, demos.len())?;
    demos.remove(i);
    st.reset_ask();
    storage::atomic_write(&st.dir, DEMOS, &scenes_to_json(&demos))
        .map_err(|e| ApiError::io(DEMOS, e))?;
    ok(json!({"count": demos.len()}))
}

// ---- learning ------------------------------------------------------------------

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct LearnBody {
    samples: Option<usize>,
    seed: Option<u64>,
    cutoff: Option<f64>,
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

/// statements.rcc, parsed, when present.
fn read_statements(st: &AppState) -> Result<Option<RuleSet>, ApiError> {
    match storage::read_optional(&st.dir, STATEMENTS).map_err(|e| ApiError::io(STATEMENTS, e))? {
        Some(text) => Ok(Some(
            parse_rules(&text).map_err(|e| rules_error(STATEMENTS, &text, e))?,
        )),
        None => Ok(None),
    }
}

fn rules_error(file: &str, src: &str, e: crate::rules::RulesError) -> ApiError {
    ApiError::bad(e.render(file, src, false)).with("file", json!(file))
}

/// Learning parameters from a learn (or ask) body, checked.
fn learn_params(b: &LearnBody) -> Result<LearnParams, ApiError> {
    let mut params = LearnParams::default();
    if let Some(n) = b.samples {
        params.samples = crate::limits::check_samples(n)
            .map_err(|e| ApiError::bad(format!("request body: samples: {e}")).at("samples"))?;
    }
    if let Some(s) = b.seed {
        params.seed = s;
    }
    if let Some(c) = b.cutoff {
        params.cutoff = c;
    }
    // Name the field of the body, not the command line's flag.
    if let Err(crate::infer::InferError::BadParameter {
        param,
        value,
        expected,
    }) = params.validate()
    {
        return Err(ApiError::bad(format!(
            "request body: {param}: {value} is invalid; expected {expected}"
        ))
        .at(param));
    }
    Ok(params)
}

/// Sets its flag when dropped: a request's learning run ends when the
/// request does, however it ends.
struct CancelOnDrop(Arc<AtomicBool>);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::SeqCst);
    }
}

/// Counts a running job down when dropped.
struct CountDown(Arc<std::sync::atomic::AtomicUsize>);

impl Drop for CountDown {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

pub(crate) async fn learn(State(st): St, body: Bytes) -> ApiResult {
    let b: LearnBody = parse_body(&body)?;
    let params = learn_params(&b)?;
    // Learning again starts the questions afresh (from the files).
    st.reset_ask();
    let demos = read_demos(&st)?;
    let statements = read_statements(&st)?;
    // One learning job per folder: a newer request cancels the one going
    // on, and so does this request's client leaving (the handler's future
    // is dropped, and with it `_leave`).
    let cancel = Arc::new(AtomicBool::new(false));
    if let Some(old) = st
        .learning
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .replace(cancel.clone())
    {
        old.store(true, Ordering::SeqCst);
    }
    let _leave = CancelOnDrop(cancel.clone());
    let jobs = st.learning_jobs.clone();
    jobs.fetch_add(1, Ordering::SeqCst);
    let priors = st.priors.clone();
    let learned = tokio::task::spawn_blocking(move || {
        let _done = CountDown(jobs);
        learn_with_priors(
            &demos,
            statements.as_ref(),
            &params,
            priors.as_deref(),
            None,
            Some(&cancel),
        )
    })
    .await
    .map_err(|e| {
        ApiError::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("learning failed: {e}"),
        )
    })?
    .map_err(|e| match e {
        crate::infer::InferError::Cancelled => ApiError::new(
            StatusCode::CONFLICT,
            "learning was cancelled: a newer learning request replaced this one",
        )
        .with("kind", json!("cancelled")),
        e => ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, format!("{DEMOS}: {e}")),
    })?;
    let rcc = learned.to_rcc();
    let header = rcc.split("\n\n").next().unwrap_or("").to_string() + "\n";
    let set = learned.rules();
    let rules: Vec<Value> = learned
        .order
        .iter()
        .zip(&set.rules)
        .map(|(&k, rule)| {
            let s = &learned.statements[k];
            let post = s.posterior.expect("learned rules have a posterior");
            json!({
                "name": s.name,
                "subject": s.subject,
                "formula": statement_text(s.scope, &s.formula),
                "english": s.english,
                "posterior": post.written(),
                "log10_posterior": post.log10_posterior,
                "q": s.q,
                "p": post.p,
                "n": s.n,
                "weight": rule.strength.weight(),
                "implied_by": s.implied_by,
                "rcc": crate::rules::print_rule(rule),
            })
        })
        .collect();
    ok(json!({
        "demonstrations": learned.demos,
        "source": match learned.source { StatementSource::Given => "given", StatementSource::Templates => "templates" },
        "statements": learned.statements.len(),
        "candidates": learned.statements.iter().filter(|s| s.candidate).count(),
        "samples": params.samples,
        "header": header,
        "rules": rules,
    }))
}

fn learned_value(st: &AppState, text: Option<&str>) -> Value {
    let mut v = json!({
        "exists": text.is_some(),
        "text": text.unwrap_or(""),
        "version": storage::version(text),
    });
    if let Some(t) = text {
        match parse_rules(t).and_then(|set| {
            check_landmarks(&set, &st.problem)?;
            Ok(set)
        }) {
            Ok(set) => {
                // SPEC §15: a class today's problem lacks is ordinary.
                if let Some(note) = missing_classes_note(&missing_classes(&set, &st.problem)) {
                    v["note"] = json!(note);
                }
                let confirmed = storage::confirmed_names(t);
                let mut rules = rule_summary(&set);
                for r in rules.as_array_mut().expect("an array") {
                    let name = r["name"].as_str().unwrap_or("");
                    r["confirmed"] = json!(confirmed.iter().any(|c| c == name));
                }
                v["rules"] = rules;
            }
            Err(e) => v["error"] = json!(e.render(LEARNED, t, false)),
        }
    }
    v
}

fn rule_summary(set: &RuleSet) -> Value {
    set.rules
        .iter()
        .map(|r| {
            json!({"name": r.name, "subject": r.subject(), "formula": statement_text(r.scope, &r.formula),
                   "weight": r.strength.weight(), "hard": r.strength.is_hard()})
        })
        .collect()
}

pub(crate) async fn get_learned(State(st): St) -> ApiResult {
    let text = storage::read_optional(&st.dir, LEARNED).map_err(|e| ApiError::io(LEARNED, e))?;
    ok(learned_value_async(&st, text).await)
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct PutLearned {
    text: String,
    /// The version the page loaded (`"absent"` when there was no file).
    base_version: String,
}

/// Parse and check `.rcc` text off the async threads (a large text must
/// not stall every other route).
async fn parse_checked(
    st: &Arc<AppState>,
    file: &'static str,
    text: String,
) -> Result<(RuleSet, String), ApiError> {
    let st = st.clone();
    tokio::task::spawn_blocking(move || {
        let set = parse_rules(&text).map_err(|e| rules_error(file, &text, e))?;
        check_landmarks(&set, &st.problem).map_err(|e| rules_error(file, &text, e))?;
        // A class of neither the problem nor the demonstrations is a typo;
        // one only the demonstrations have is ordinary (SPEC §15: noted).
        let mut known = st.problem.clone();
        for d in read_demos(&st).unwrap_or_default() {
            known.objects.extend(d.objects);
        }
        check_classes(&set, &known).map_err(|e| rules_error(file, &text, e))?;
        Ok((set, text))
    })
    .await
    .map_err(|_| internal("reading the rules"))?
}

/// [`learned_value`] off the async threads.
async fn learned_value_async(st: &Arc<AppState>, text: Option<String>) -> Value {
    let st = st.clone();
    tokio::task::spawn_blocking(move || learned_value(&st, text.as_deref()))
        .await
        .unwrap_or_else(
            |_| json!({"error": "reading the rules failed unexpectedly (internal error)"}),
        )
}

pub(crate) async fn put_learned(State(st): St, body: Bytes) -> ApiResult {
    let b: PutLearned = parse_body(&body)?;
    let (_, text) = parse_checked(&st, LEARNED, b.text).await?;
    let b = PutLearned {
        text,
        base_version: b.base_version,
    };
    let _guard = st.write_lock.lock().await;
    let _folder = folder_lock(&st)?;
    let current = storage::read_optional(&st.dir, LEARNED).map_err(|e| ApiError::io(LEARNED, e))?;
    if storage::version(current.as_deref()) != b.base_version {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("{LEARNED} changed on disk since the page loaded it; not overwritten — the page shows the file as it is now"),
        )
        .with("current", learned_value_async(&st, current).await));
    }
    storage::atomic_write(&st.dir, LEARNED, &b.text).map_err(|e| ApiError::io(LEARNED, e))?;
    ok(learned_value_async(&st, Some(b.text)).await)
}

// ---- questions ("Check rules", SPEC §13) ------------------------------------------

/// The open "Check rules" session: the question loop and the question the
/// page was shown.
pub(crate) struct AskSession {
    asker: Asker,
    question: Option<Question>,
    /// [`AppState::ask_generation`] when the session read the files.
    generation: u64,
    params: LearnParams,
    /// Versions of demos.json, learned.rcc and answers.json as the session
    /// last wrote them: a file changed outside the studio since (a hand
    /// edit) is never overwritten by an answer.
    versions: (String, String, String),
    /// The next question for both answers to the open one, being computed
    /// while the person looks.
    ahead: Option<crate::ask::Lookahead>,
    /// The next question, computed ahead (`Some(None)`: there is none).
    prepared: Option<Option<Question>>,
}

/// Versions ([`storage::version`]) of demos.json, learned.rcc and
/// answers.json on disk.
fn disk_versions(st: &AppState) -> Result<(String, String, String), ApiError> {
    let demos = storage::read_optional(&st.dir, DEMOS).map_err(|e| ApiError::io(DEMOS, e))?;
    let learned = storage::read_optional(&st.dir, LEARNED).map_err(|e| ApiError::io(LEARNED, e))?;
    let answers = storage::read_optional(&st.dir, ANSWERS).map_err(|e| ApiError::io(ANSWERS, e))?;
    Ok((
        storage::version(demos.as_deref()),
        storage::version(learned.as_deref()),
        storage::version(answers.as_deref()),
    ))
}

impl AppState {
    /// Drop the "Check rules" session: the next question reads the files
    /// again. Called (under `write_lock` when demos.json is written) by every
    /// endpoint that changes the demonstrations or learns.
    pub(crate) fn reset_ask(&self) {
        self.ask_generation.fetch_add(1, Ordering::SeqCst);
    }
}

/// Seconds each probe search may take (the rule is then left unsettled).
const PROBE_TIME_LIMIT_SECS: u64 = 10;

fn ask_error(e: AskError) -> ApiError {
    match e {
        AskError::Learn(e) => {
            ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, format!("{DEMOS}: {e}"))
        }
        AskError::Synth(e) => ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            format!("{}: {e}", storage::PROBLEM),
        ),
        e @ AskError::BadAnswer { .. } => ApiError::new(
            StatusCode::CONFLICT,
            format!("{ANSWERS}: {e}; fix or move the file, then ask again"),
        )
        .with("kind", json!("corrupt_answers")),
        e @ AskError::NotAsked(_) => {
            ApiError::new(StatusCode::CONFLICT, e.to_string()).with("kind", json!("not_asked"))
        }
    }
}

fn internal(what: &str) -> ApiError {
    ApiError::new(
        StatusCode::INTERNAL_SERVER_ERROR,
        format!("{what} failed unexpectedly (internal error); the question was dropped, ask again"),
    )
}

/// answers.json (empty when absent); one that does not parse is reported
/// (409) and never overwritten.
fn read_answers(st: &AppState) -> Result<Vec<Answer>, ApiError> {
    let Some(text) =
        storage::read_optional(&st.dir, ANSWERS).map_err(|e| ApiError::io(ANSWERS, e))?
    else {
        return Ok(Vec::new());
    };
    let file = AnswersFile::from_json(&text).map_err(|e| {
        ApiError::new(
            StatusCode::CONFLICT,
            format!(
                "{ANSWERS}: {e}; the studio will not overwrite it — fix or move the file, then ask again"
            ),
        )
        .with("kind", json!("corrupt_answers"))
    })?;
    Ok(file.answers)
}

/// Start (or resume) a session from the task folder's files, as `rccpack
/// ask` does: an accepted probe missing from demos.json is added again, and
/// learned.rcc is written (a different one of a first session is kept as
/// learned.rcc.bak). Returns the session and the backup's name, if any.
async fn start_session(
    st: &Arc<AppState>,
    params: LearnParams,
) -> Result<(AskSession, Option<&'static str>), ApiError> {
    let _guard = st.write_lock.lock().await;
    let _folder = folder_lock(st)?;
    let generation = st.ask_generation.load(Ordering::SeqCst);
    let demos = read_demos(st)?;
    let n_demos = demos.len();
    let statements = read_statements(st)?;
    let answers = read_answers(st)?;
    let resumed = answers.len();
    let opts = AskOptions {
        learn: params,
        probe: ProbeOptions {
            contact: params.contact,
            seed: params.seed,
            time_limit: Some(Duration::from_secs(PROBE_TIME_LIMIT_SECS)),
            ..ProbeOptions::default()
        },
        resemble: true,
        priors: st.priors.clone(),
        ..AskOptions::default()
    };
    let problem = st.problem.clone();
    let asker =
        tokio::task::spawn_blocking(move || Asker::new(problem, demos, statements, answers, opts))
            .await
            .map_err(|_| internal("learning"))?
            .map_err(ask_error)?;
    let backup = storage::write_session_start(&st.dir, &asker, n_demos, resumed)
        .map_err(|(file, e)| ApiError::io(file, e))?
        .then_some(LEARNED_BACKUP);
    Ok((
        AskSession {
            asker,
            question: None,
            generation,
            params,
            versions: disk_versions(st)?,
            ahead: None,
            prepared: None,
        },
        backup,
    ))
}

fn question_value(q: &Question, number: usize) -> Value {
    json!({
        "number": number,
        "rule": q.rule,
        "statement": q.statement,
        "english": q.english,
        "broken": q.probe.broken,
        "scene": scene_value(&q.probe.scene),
        "cost": q.probe.cost,
        "time_ms": q.probe.time_ms,
        "edit": q.probe.edit,
    })
}

fn current_learned(st: &AppState) -> Result<Value, ApiError> {
    let text = storage::read_optional(&st.dir, LEARNED).map_err(|e| ApiError::io(LEARNED, e))?;
    Ok(learned_value(st, text.as_deref()))
}

pub(crate) async fn ask_next(State(st): St, body: Bytes) -> ApiResult {
    let b: LearnBody = parse_body(&body)?;
    let params = learn_params(&b)?;
    let mut guard = st.ask.clone().lock_owned().await;
    let generation = st.ask_generation.load(Ordering::SeqCst);
    let on_disk = disk_versions(&st)?;
    let keep = guard.as_ref().is_some_and(|s| {
        // Parameters given in the body must match the session's; omitted
        // ones keep it. A file edited outside the studio starts afresh.
        s.generation == generation
            && s.versions == on_disk
            && b.samples.is_none_or(|n| n == s.params.samples)
            && b.seed.is_none_or(|x| x == s.params.seed)
            && b.cutoff.is_none_or(|c| c == s.params.cutoff)
    });
    let mut backup = None;
    if !keep {
        *guard = None;
        let (session, b) = start_session(&st, params).await?;
        *guard = Some(session);
        backup = b;
    }
    let open = guard
        .as_ref()
        .and_then(|s| s.question.clone())
        .map(|q| (q, guard.as_ref().map_or(0, |s| s.asker.answers().len())));
    let (guard, question) = match open {
        // The page asks again (a reload): the same question.
        Some((q, asked)) => (guard, Some(question_value(&q, asked + 1))),
        None => {
            let joined = tokio::task::spawn_blocking(move || {
                let mut guard = guard;
                let s = guard.as_mut().expect("a session was just started");
                let next = match s.prepared.take() {
                    Some(q) => Ok(q),
                    None => s.asker.next_question(),
                };
                if let Ok(q) = &next {
                    s.question = q.clone();
                    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
                    s.ahead = q.as_ref().map(|q| s.asker.look_ahead(q, threads));
                }
                (guard, next)
            })
            .await;
            let Ok((mut guard, next)) = joined else {
                *st.ask.lock().await = None;
                return Err(internal("the probe search"));
            };
            match next {
                Ok(q) => {
                    let asked = guard.as_ref().map_or(0, |s| s.asker.answers().len());
                    let v = q.as_ref().map(|q| question_value(q, asked + 1));
                    (guard, v)
                }
                Err(e) => {
                    *guard = None;
                    return Err(ask_error(e));
                }
            }
        }
    };
    let progress = guard.as_ref().map(|s| s.asker.progress());
    drop(guard);
    ok(json!({
        "question": question,
        "progress": progress,
        "learned": current_learned(&st)?,
        "backup": backup,
    }))
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct AnswerBody {
    rule: Option<String>,
    accepted: Option<bool>,
}

pub(crate) async fn ask_answer(State(st): St, body: Bytes) -> ApiResult {
    let b: AnswerBody = parse_body(&body)?;
    let rule = b.rule.ok_or_else(|| {
        ApiError::bad("request body: rule: missing; expected the name of the rule the open question asks about")
            .at("rule")
    })?;
    let accepted = b.accepted.ok_or_else(|| {
        ApiError::bad(
            "request body: accepted: missing; expected true (the layout looks right) or false (not like that)",
        )
        .at("accepted")
    })?;
    let mut guard = st.ask.clone().lock_owned().await;
    let generation = st.ask_generation.load(Ordering::SeqCst);
    if guard.as_ref().is_some_and(|s| s.generation != generation) {
        *guard = None;
    }
    let Some(open) = guard.as_ref().and_then(|s| s.question.as_ref()) else {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            "no question is open (none asked yet, or the demonstrations changed since); ask with POST /api/ask/next",
        )
        .with("kind", json!("no_question")));
    };
    if open.rule != rule {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!(
                "rule: no question about rule `{rule}` is open; the open question is about rule `{}`",
                open.rule
            ),
        )
        .at("rule")
        .with("kind", json!("not_asked")));
    }
    let joined = tokio::task::spawn_blocking(move || {
        let mut guard = guard;
        let s = guard.as_mut().expect("checked above");
        let q = s.question.take().expect("checked above");
        let r = match s.ahead.take() {
            // The branch computed ahead for this answer: the session after
            // it and its next question.
            Some(ahead) => ahead.answer(accepted).map(|(asker, next)| {
                s.asker = asker;
                s.prepared = Some(next);
            }),
            None => s.asker.answer(&q, accepted).map(|_| ()),
        };
        (guard, r)
    })
    .await;
    let Ok((mut guard, r)) = joined else {
        *st.ask.lock().await = None;
        return Err(internal("learning from the answer"));
    };
    if let Err(e) = r {
        *guard = None;
        return Err(ask_error(e));
    }
    let _write = st.write_lock.lock().await;
    let _folder = match folder_lock(&st) {
        Ok(l) => l,
        Err(e) => {
            *guard = None;
            return Err(e);
        }
    };
    let s = guard.as_ref().expect("answered above");
    if s.generation != st.ask_generation.load(Ordering::SeqCst) {
        *guard = None;
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("{DEMOS} changed while the answer was applied; the answer was not saved — ask again"),
        )
        .with("kind", json!("no_question")));
    }
    // The version check of the other routes: a demonstration or a rule
    // added by hand since the session read the files is never lost.
    let on_disk = match disk_versions(&st) {
        Ok(v) => v,
        Err(e) => {
            *guard = None;
            return Err(e);
        }
    };
    if on_disk != s.versions {
        *guard = None;
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("{DEMOS}, {LEARNED} or {ANSWERS} changed on disk since the question was asked; the answer was not saved and nothing was overwritten — ask again"),
        )
        .with("kind", json!("stale_files")));
    }
    // As `rccpack ask`: the journal first, then the demonstrations, then the
    // rules; each write atomic. A failed write drops the session, so the
    // next question starts again from what is on disk.
    let rcc = s.asker.learned_rcc();
    let written = storage::write_after_answer(&st.dir, &s.asker, accepted)
        .map_err(|(f, e)| ApiError::io(f, e))
        .and_then(|()| disk_versions(&st));
    match written {
        Ok(v) => {
            if let Some(s) = guard.as_mut() {
                s.versions = v;
            }
        }
        Err(e) => {
            *guard = None;
            return Err(e);
        }
    }
    let s = guard.as_ref().expect("answered above");
    let answer = s.asker.answers().last().expect("just answered");
    let v = json!({
        "answer": {"rule": answer.rule, "accepted": answer.accepted, "demo": answer.demo},
        "progress": s.asker.progress(),
        "learned": learned_value(&st, Some(&rcc)),
    });
    ok(v)
}

// ---- synthesis -------------------------------------------------------------------

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
    /// Prefer layouts like the saved demonstrations (SPEC §12; default
    /// true).
    like: Option<bool>,
}

const CHOSEN: &str = "chosen rules";

/// Largest `time_limit` of `POST /api/synth`, in seconds.
const STUDIO_MAX_TIME_LIMIT_SECS: u64 = 600;

pub(crate) async fn start_synth(State(st): St, body: Bytes) -> ApiResult {
    let b: SynthBody = parse_body(&body)?;
    let (set, _) = parse_checked(&st, CHOSEN, b.rules).await?;
    // SPEC §15: the chosen rules are learned ones; a class the problem
    // lacks is noted, not refused.
    let note = missing_classes_note(&missing_classes(&set, &st.problem));
    let secs = b.time_limit.unwrap_or(30.0);
    // The shared validated parser, then the studio's own tighter cap.
    let limit = crate::limits::time_limit(secs)
        .ok()
        .filter(|d| !d.is_zero() && *d <= Duration::from_secs(STUDIO_MAX_TIME_LIMIT_SECS))
        .ok_or_else(|| {
            ApiError::bad(format!(
                "request body: time_limit: {secs} is out of range; expected seconds in (0, {STUDIO_MAX_TIME_LIMIT_SECS}]"
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
        time_limit: Some(limit),
        seed: b.seed.unwrap_or(0),
        cancel: Some(cancel),
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
            Ok(Err(e)) => Err(format!("{}: {e}", storage::PROBLEM)),
            Err(_) => Err("synthesis failed unexpectedly (internal error)".to_string()),
        };
        if let Some(j) = st2.jobs.lock().expect("jobs lock").get_mut(&id) {
            j.outcome = Some(outcome);
        }
    });
    Ok((
        StatusCode::ACCEPTED,
        Json(json!({ "job": id, "note": note })),
    )
        .into_response())
}

fn synth_value(r: &SynthResult) -> Value {
    let e = r.evaluation.as_ref();
    json!({
        "status": r.status,
        "score": e.map(|e| e.score),
        "satisfied_weight": e.map(|e| e.satisfied_weight),
        "total_weight": e.map(|e| e.total_weight),
        "time_ms": r.stats.time_ms,
        "stats": r.stats,
        "scene": r.scene.as_ref().map(scene_value),
        "evaluation": e,
        "conflict": r.conflict,
        "resemblance": r.resemblance,
    })
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct SampleBody {
    /// The rules, as `.rcc` text (the rules of the layout shown).
    rules: String,
    /// The score the other layout must reach (the shown layout's).
    min_score: Option<f64>,
    /// Which draw: the page counts 1, 2, 3, …
    seed: Option<u64>,
}

/// How long `POST /api/sample` may look for a layout.
const SAMPLE_TIME_LIMIT: Duration = Duration::from_secs(10);

/// `POST /api/sample`: "another layout like this" — one layout drawn by
/// [`crate::sample()`] at least as good as the shown one (`min_score` 1:
/// every rule kept; below: the optimum score), leaning towards the saved
/// demonstrations; each `seed` gives another draw.
pub(crate) async fn sample_layout(State(st): St, body: Bytes) -> ApiResult {
    let b: SampleBody = parse_body(&body)?;
    let (set, _) = parse_checked(&st, CHOSEN, b.rules).await?;
    let min = b.min_score.unwrap_or(1.0);
    if !(0.0..=1.0).contains(&min) {
        return Err(ApiError::bad(format!(
            "request body: min_score: {min} is out of range; expected a number from 0 to 1"
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
        time_limit: Some(SAMPLE_TIME_LIMIT),
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
            Ok(Json(json!({
                "status": "feasible",
                "sampled": true,
                "score": evaluation.score,
                "satisfied_weight": evaluation.satisfied_weight,
                "total_weight": evaluation.total_weight,
                "scene": scene_value(&scene),
                "evaluation": evaluation,
                "conflict": null,
            }))
            .into_response())
        }
        Ok(None) => Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "no other layout of this score exists".to_string(),
        )),
        Err(e) => Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            format!("{}: {e}", storage::PROBLEM),
        )),
    }
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
    let mut v = json!({
        "job": id,
        "state": match &j.outcome { None => "running", Some(Ok(_)) => "done", Some(Err(_)) => "error" },
        "elapsed_ms": j.started.elapsed().as_secs_f64() * 1000.0,
        "best_score": *j.best.lock().expect("best lock"),
        "cancelled": j.cancel.load(Ordering::Relaxed),
    });
    match &j.outcome {
        Some(Ok(r)) => v["result"] = r.clone(),
        Some(Err(e)) => v["error"] = json!(e),
        None => {}
    }
    ok(v)
}

pub(crate) async fn cancel_synth(State(st): St, Path(job): Path<String>) -> ApiResult {
    let id = job_id(&job)?;
    let jobs = st.jobs.lock().expect("jobs lock");
    let j = jobs
        .get(&id)
        .ok_or_else(|| ApiError::new(StatusCode::NOT_FOUND, format!("no synthesis job {id}")))?;
    j.cancel.store(true, Ordering::Relaxed);
    ok(json!({ "job": id, "cancelled": true }))
}
