//! `/api/demos`: list, read, add and delete the demonstrations of
//! `demos.json`. A file that does not parse is reported (409) and never
//! overwritten; every write holds the folder's lock.

use super::super::AppState;
use super::{off_async, ok, reply, scene_value, ApiError, ApiResult, St};
use crate::scene::Scene;
use crate::task::files::DemosFile;
use crate::task::files::{self, DEMOS};
use axum::body::Bytes;
use axum::extract::{Path, Query, State};
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// Read demos.json; a file that does not parse is reported (409) and never
/// overwritten.
pub(super) fn read_demos(st: &AppState) -> Result<Vec<Scene>, ApiError> {
    read_demos_versioned(st).map(|(d, _)| d.scenes)
}

/// The demonstrations, read as measured (docs/scenes.md#demonstrations-as-measured:
/// on the grid, a measured file's recorded entries kept for writing), and
/// the version of the file they came from.
pub(super) fn read_demos_versioned(st: &AppState) -> Result<(DemosFile, String), ApiError> {
    let text = files::read_optional(&st.dir, DEMOS)
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
    let demos = DemosFile::parse(&text).map_err(|e| corrupt(&e.to_string()))?;
    Ok((demos, files::version(Some(&text))))
}

/// Refuse to delete demonstration `i` when answers.json refers to it or to
/// a later one (an accepted probe is demonstration `demo`, a suspect answer
/// names its demonstration): deleting would shift them and break the
/// journal "Check rules" resumes from.
fn refuse_if_answered(st: &AppState, i: usize) -> Result<(), ApiError> {
    let Some(text) = files::read_optional(&st.dir, files::ANSWERS)
        .map_err(|e| ApiError::io(files::ANSWERS, e))?
    else {
        return Ok(());
    };
    // A corrupt journal is reported by "Check rules"; nothing to protect.
    let Ok(journal) = crate::ask::AnswersFile::from_json(&text) else {
        return Ok(());
    };
    let refers = journal.answers.iter().enumerate().find_map(|(k, a)| {
        let d = a.demo.or(a.suspect.as_ref().map(|s| s.demonstration))?;
        (d >= i).then_some((k, d))
    });
    match refers {
        Some((k, d)) => Err(ApiError::new(
            StatusCode::CONFLICT,
            format!(
                "demonstration #{} was not deleted: answers.json refers to demonstration #{} (answer {} of Check rules), and deleting would renumber it; move answers.json away first (its answers are then forgotten)",
                i + 1,
                d + 1,
                k + 1
            ),
        )
        .kind("answered_demo")),
        None => Ok(()),
    }
}

/// The task folder's lock (shared with `rccpack ask`), taken while
/// writing; a 409 naming it when an `ask` session holds it.
pub(super) fn folder_lock(st: &AppState) -> Result<crate::fsutil::DirLock, ApiError> {
    match crate::fsutil::DirLock::try_lock(&st.dir) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err(ApiError::new(
            StatusCode::CONFLICT,
            format!(
                "the task folder is in use by `rccpack ask` (it holds {}); nothing was written — try again when it ends",
                crate::fsutil::LOCK_FILE
            ),
        )
        .kind("folder_locked")),
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
    .kind("corrupt_demos")
}

/// Parse a posted demonstration and check it as `check`/`score` would, plus
/// that it is a complete layout of this task.
fn parse_demo(st: &AppState, body: &[u8]) -> Result<Scene, ApiError> {
    let text = std::str::from_utf8(body).map_err(|_| ApiError::bad("request body is not UTF-8"))?;
    let scene = Scene::from_json(text).map_err(|e| {
        let path = e.path().to_string();
        ApiError::bad(format!("demonstration: {e}")).at(path)
    })?;
    same_space_and_grid(&scene, &st.problem)?;
    check_demo_objects(&scene, &st.problem)?;
    Ok(scene)
}

/// A demonstration lies in the problem's space, on its grid.
fn same_space_and_grid(scene: &Scene, p: &Scene) -> Result<(), ApiError> {
    if scene.space != p.space {
        return Err(ApiError::bad(format!(
            "demonstration: space: {}x{} at ({}, {}) differs from {}'s {}x{} at ({}, {})",
            scene.space.width,
            scene.space.height,
            scene.space.x,
            scene.space.y,
            files::PROBLEM,
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
            files::PROBLEM,
            p.grid
        ))
        .at("grid"));
    }
    Ok(())
}

/// Every object of a demonstration placed and one of the problem's kinds,
/// the problem's fixed objects where they are, at least one movable one.
fn check_demo_objects(scene: &Scene, p: &Scene) -> Result<(), ApiError> {
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
                    files::PROBLEM
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
                files::PROBLEM
            ))
            .at(format!("objects[{i}]")));
        }
    }
    for f in p.objects.iter().filter(|o| o.fixed) {
        if !scene.objects.iter().any(|o| o.fixed && o.id == f.id) {
            return Err(ApiError::bad(format!(
                "demonstration: objects: fixed object `{}` of {} is missing",
                f.id,
                files::PROBLEM
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
    Ok(())
}

/// The body of `GET /api/demos`.
#[derive(Serialize)]
struct DemoList {
    count: usize,
    demos: Vec<Value>,
    /// The file's version, for `DELETE /api/demos/{index}?version=`.
    version: String,
}

/// The body of `POST /api/demos` (`201 Created`).
#[derive(Serialize)]
struct Saved {
    count: usize,
    /// The new demonstration's index.
    index: usize,
}

/// The body of `DELETE /api/demos/{index}`.
#[derive(Serialize)]
struct Deleted {
    count: usize,
}

pub(crate) async fn list_demos(State(st): St) -> ApiResult {
    let st2 = st.clone();
    let list = off_async(move || {
        let (demos, version) = read_demos_versioned(&st2)?;
        Ok(DemoList {
            count: demos.scenes.len(),
            demos: demos.scenes.iter().map(scene_value).collect(),
            version,
        })
    })
    .await?;
    ok(&list)
}

pub(crate) async fn save_demo(State(st): St, body: Bytes) -> ApiResult {
    let st2 = st.clone();
    let scene = off_async(move || parse_demo(&st2, &body)).await?;
    let _guard = st.write_lock.lock().await;
    let _folder = folder_lock(&st)?;
    let (file, _) = read_demos_versioned(&st)?;
    let mut demos = file.scenes.clone();
    demos.push(scene);
    st.reset_ask();
    files::atomic_write(&st.dir, DEMOS, &file.to_json(&demos))
        .map_err(|e| ApiError::io(DEMOS, e))?;
    Ok(reply(
        StatusCode::CREATED,
        &Saved {
            count: demos.len(),
            index: demos.len() - 1,
        },
    ))
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
    ok(&v)
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
    q: Result<Query<DeleteQuery>, axum::extract::rejection::QueryRejection>,
) -> ApiResult {
    // A bad query string (a repeated `version`) answers JSON like every
    // other error, not axum's plain text.
    let Query(q) = q.map_err(|e| {
        ApiError::bad(format!(
            "query string: {}; expected at most one `version` parameter",
            crate::limits::cut(&e.body_text()).to_lowercase()
        ))
        .at("version")
    })?;
    let _guard = st.write_lock.lock().await;
    let _folder = folder_lock(&st)?;
    let (mut file, version) = read_demos_versioned(&st)?;
    if q.version.as_ref().is_some_and(|v| *v != version) {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("{DEMOS} changed since the page listed it (another tab?); nothing deleted — reload the list and try again"),
        )
        .kind("stale_demos"));
    }
    let i = demo_index(&index, file.scenes.len())?;
    refuse_if_answered(&st, i)?;
    file.remove(i);
    st.reset_ask();
    files::atomic_write(&st.dir, DEMOS, &file.to_json(&file.scenes))
        .map_err(|e| ApiError::io(DEMOS, e))?;
    ok(&Deleted {
        count: file.scenes.len(),
    })
}
