//! `GET /api/task`: what the page needs to draw the task — the problem, the
//! kinds of objects to place with their colours, and what the folder holds.

use super::{ok, ApiError, ApiResult, St};
use crate::task::files::{self, STATEMENTS};
use axum::extract::State;
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeMap;
use std::sync::atomic::Ordering;

/// The body of `GET /api/task`.
#[derive(Serialize)]
struct TaskBody<'a> {
    /// Colour per class, exactly as `render` draws them.
    colours: BTreeMap<String, &'static str>,
    fixed_colour: &'static str,
    /// The movable objects grouped by class and size, in problem order.
    kinds: Vec<Kind>,
    /// Learning runs of `POST /api/learn` still computing.
    learning_jobs: usize,
    /// The folder's name.
    name: String,
    /// The priors every learning run uses, if any.
    priors: Option<PriorsSummary>,
    problem: &'a Value,
    /// Whether the folder has a `statements.rcc`.
    statements: bool,
}

/// Movable objects of one class and size.
#[derive(Serialize)]
struct Kind {
    class: String,
    colour: &'static str,
    count: usize,
    height: i64,
    width: i64,
}

/// The priors file in use.
#[derive(Serialize)]
struct PriorsSummary {
    hash: String,
    tasks: u64,
}

/// The movable objects of `problem` grouped by class and size, in the order
/// they first occur, with their colours.
fn kinds(problem: &crate::scene::Scene, colours: &BTreeMap<String, &'static str>) -> Vec<Kind> {
    let mut kinds: Vec<Kind> = Vec::new();
    for o in problem.objects.iter().filter(|o| !o.fixed) {
        match kinds
            .iter_mut()
            .find(|k| k.class == o.class && k.width == o.width && k.height == o.height)
        {
            Some(k) => k.count += 1,
            None => kinds.push(Kind {
                class: o.class.clone(),
                colour: colours.get(&o.class).copied().unwrap_or("#888888"),
                count: 1,
                height: o.height,
                width: o.width,
            }),
        }
    }
    kinds
}

pub(crate) async fn task(State(st): St) -> ApiResult {
    let colours: BTreeMap<String, &'static str> = crate::render::class_colours(&st.problem)
        .into_iter()
        .collect();
    let name = st
        .dir
        .canonicalize()
        .ok()
        .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| "task".into());
    let statements = files::read_optional(&st.dir, STATEMENTS)
        .map_err(|e| ApiError::io(STATEMENTS, e))?
        .is_some();
    ok(&TaskBody {
        kinds: kinds(&st.problem, &colours),
        colours,
        fixed_colour: "#4a4a4a",
        learning_jobs: st.learning_jobs.load(Ordering::SeqCst),
        name,
        priors: st.priors.as_ref().map(|p| PriorsSummary {
            hash: p.hash_text(),
            tasks: p.tasks,
        }),
        problem: &st.problem_json,
        statements,
    })
}
