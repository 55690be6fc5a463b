//! `/api/ask`: the "Check rules" questions (docs/guide.md#questions). One session per
//! folder, read from the files as `rccpack ask` reads them; each answer is
//! written as `rccpack ask` writes it (the journal first), and never over a
//! file changed outside the studio since the question was asked.

use super::super::AppState;
use super::demos::{folder_lock, read_demos_versioned};
use super::learn::{learn_params, read_statements, CancelOnDrop, LearnBody};
use super::learned::{current_learned, learned_value, LearnedView};
use super::{internal, ok, parse_body, scene_value, ApiError, ApiResult, St};
use crate::ask::{AskError, AskOptions, ProbeOptions, Question};
use crate::infer::LearnParams;
use crate::task::files::{self, ANSWERS, DEMOS, LEARNED, LEARNED_BACKUP};
use crate::task::session::{Locking, Session, SessionError, SessionInputs, SessionOptions};
use axum::body::Bytes;
use axum::extract::State;
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Duration;

/// The open "Check rules" session: the library's question session
/// ([`Session`], the only implementation of it) and what the studio needs
/// to know whether it still fits the folder.
pub(crate) struct AskSession {
    session: Session,
    /// [`AppState::ask_generation`] when the session read the files.
    generation: u64,
    params: LearnParams,
    /// Group questions on (docs/guide.md#questions).
    groups: bool,
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
            format!("{}: {e}", files::PROBLEM),
        ),
        e @ AskError::BadAnswer { .. } => ApiError::new(
            StatusCode::CONFLICT,
            format!("{ANSWERS}: {e}; fix or move the file, then ask again"),
        )
        .kind("corrupt_answers"),
        e @ AskError::NotAsked(_) => {
            ApiError::new(StatusCode::CONFLICT, e.to_string()).kind("not_asked")
        }
    }
}

/// A session's error as the page gets it.
fn session_error(e: SessionError) -> ApiError {
    match e {
        SessionError::Ask { source, .. } => ask_error(*source),
        SessionError::Answers { source, .. } => ApiError::new(
            StatusCode::CONFLICT,
            format!(
                "{ANSWERS}: {source}; the studio will not overwrite it — fix or move the file, then ask again"
            ),
        )
        .kind("corrupt_answers"),
        SessionError::Changed { .. } => ApiError::new(
            StatusCode::CONFLICT,
            format!("{DEMOS}, {LEARNED} or {ANSWERS} changed on disk since the question was asked; the answer was not saved and nothing was overwritten — ask again"),
        )
        .kind("stale_files"),
        e @ SessionError::NotOpen { .. } => {
            ApiError::new(StatusCode::CONFLICT, e.to_string()).at("rule").kind("not_asked")
        }
        SessionError::Write { path, source } => {
            let name = path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
            ApiError::io(&name, source)
        }
        e => ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, e.to_string()),
    }
}

/// Start (or resume) a session from the task folder's files, as `rccpack
/// ask` does: an accepted probe missing from demos.json is added again, and
/// learned.rcc is written (a different one of a first session is kept as
/// learned.rcc.bak). Returns the session and the backup's name, if any.
async fn start_session(
    st: &Arc<AppState>,
    params: LearnParams,
    groups: bool,
) -> Result<(AskSession, Option<&'static str>), ApiError> {
    let _guard = st.write_lock.lock().await;
    let folder = folder_lock(st)?;
    let generation = st.ask_generation.load(Ordering::SeqCst);
    let inputs = SessionInputs {
        problem: st.problem.clone(),
        demos: read_demos_versioned(st)?.0,
        statements: read_statements(st)?,
    };
    // Learning stops when the request's client leaves (the handler's
    // future is dropped, and with it `_leave`), as for POST /api/learn.
    let cancel = Arc::new(std::sync::atomic::AtomicBool::new(false));
    let _leave = CancelOnDrop(cancel.clone());
    let opts = SessionOptions {
        ask: AskOptions {
            learn: params,
            probe: ProbeOptions {
                seed: params.seed,
                solve_time: Some(Duration::from_secs(PROBE_TIME_LIMIT_SECS)),
                stop: ProbeOptions::default().stop.with_cancel(cancel),
                ..ProbeOptions::default()
            },
            resemble: true,
            priors: st.priors.clone(),
            groups,
            ..AskOptions::default()
        },
        locking: Locking::Caller,
        probe_files: false,
        lookahead_threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
        ..SessionOptions::default()
    };
    let dir = st.dir.clone();
    let session = tokio::task::spawn_blocking(move || {
        let s = Session::open_with(dir, inputs, opts).map(|mut s| {
            // Started: the request's flag no longer stops the session.
            s.set_cancel(None);
            s
        });
        drop(folder);
        s
    })
    .await
    .map_err(|_| internal("learning"))?
    .map_err(session_error)?;
    let backup = session.backup_written().then_some(LEARNED_BACKUP);
    Ok((
        AskSession {
            session,
            generation,
            params,
            groups,
        },
        backup,
    ))
}

/// A question as the page shows it.
#[derive(Serialize)]
struct QuestionBody {
    /// The objects breaking the rule in the probe.
    broken: Vec<String>,
    /// The probe's resemblance cost.
    cost: u64,
    /// When the probe is a demonstration with a few objects moved.
    edit: Option<crate::ask::Edit>,
    english: String,
    /// For a group question: every rule the probe breaks on purpose
    /// (`rule` first); absent for a question about one rule.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    group: Vec<crate::ask::Asked>,
    /// The question's number in the session, from 1.
    number: usize,
    rule: String,
    /// The probe layout.
    scene: Value,
    statement: String,
    /// When the question is whether a demonstration that looks like a slip
    /// is as the person meant it (`scene` is that demonstration).
    #[serde(skip_serializing_if = "Option::is_none")]
    suspect: Option<crate::ask::SuspectQuestion>,
    time_ms: f64,
}

/// The body of `POST /api/ask/next`.
#[derive(Serialize)]
struct NextBody {
    /// The backup of `learned.rcc` a first session made, if any.
    backup: Option<&'static str>,
    learned: LearnedView,
    progress: Option<crate::ask::Tally>,
    /// `None`: no more questions.
    question: Option<QuestionBody>,
}

/// The body of `POST /api/ask/answer`.
#[derive(Serialize)]
struct AnsweredBody {
    answer: AnswerSummary,
    /// `learned.rcc` as the answer left it.
    learned: LearnedView,
    progress: crate::ask::Tally,
}

/// The answer just saved.
#[derive(Serialize)]
struct AnswerSummary {
    accepted: bool,
    /// For an accepted probe: its index in `demos.json`.
    demo: Option<usize>,
    rule: String,
    /// For a question about a suspect: the demonstration (holding a slip
    /// when not accepted).
    #[serde(skip_serializing_if = "Option::is_none")]
    suspect: Option<usize>,
}

fn question_value(q: &Question, number: usize) -> QuestionBody {
    QuestionBody {
        broken: q.probe.broken.clone(),
        cost: q.probe.cost,
        edit: q.probe.edit.clone(),
        english: q.english.clone(),
        group: q.group.clone(),
        number,
        rule: q.rule.clone(),
        scene: scene_value(&q.probe.scene),
        statement: q.statement.clone(),
        suspect: q.suspect.clone(),
        time_ms: q.probe.time_ms,
    }
}

pub(crate) async fn ask_next(State(st): St, body: Bytes) -> ApiResult {
    let b: LearnBody = parse_body(&body)?;
    let params = learn_params(&b)?;
    let mut guard = st.ask.clone().lock_owned().await;
    let generation = st.ask_generation.load(Ordering::SeqCst);
    let keep = match guard.as_ref() {
        // Parameters given in the body must match the session's; omitted
        // ones keep it. A file edited outside the studio starts afresh.
        Some(s) => {
            s.generation == generation
                && !s.session.files_changed().map_err(session_error)?
                && b.samples.is_none_or(|n| n == s.params.samples)
                && b.seed.is_none_or(|x| x == s.params.seed)
                && b.cutoff.is_none_or(|c| c == s.params.cutoff)
                && b.slip_rate.is_none_or(|r| r == s.params.slip_rate)
                && b.groups.is_none_or(|g| g == s.groups)
        }
        None => false,
    };
    let mut backup = None;
    if !keep {
        *guard = None;
        let (session, b) = start_session(&st, params, b.groups.unwrap_or(true)).await?;
        *guard = Some(session);
        backup = b;
    }
    // A reload asks again: the session gives the open question again.
    let joined = tokio::task::spawn_blocking(move || {
        let mut guard = guard;
        let s = guard.as_mut().expect("a session was just started");
        let next = s.session.next_question();
        (guard, next)
    })
    .await;
    let Ok((mut guard, next)) = joined else {
        *st.ask.lock().await = None;
        return Err(internal("the probe search"));
    };
    let question = match next {
        Ok(shown) => shown.map(|s| question_value(&s.question, s.number)),
        Err(e) => {
            *guard = None;
            return Err(session_error(e));
        }
    };
    let progress = guard.as_ref().map(|s| s.session.asker().progress());
    drop(guard);
    ok(&NextBody {
        backup,
        learned: current_learned(&st)?,
        progress,
        question,
    })
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct AnswerBody {
    rule: Option<String>,
    accepted: Option<bool>,
}

/// The session lock, held across the blocking work of a request.
type SessionGuard = tokio::sync::OwnedMutexGuard<Option<AskSession>>;

pub(crate) async fn ask_answer(State(st): St, body: Bytes) -> ApiResult {
    let (rule, accepted) = parse_answer(&body)?;
    let mut guard = st.ask.clone().lock_owned().await;
    let generation = st.ask_generation.load(Ordering::SeqCst);
    if guard.as_ref().is_some_and(|s| s.generation != generation) {
        *guard = None;
    }
    check_open(&guard, &rule)?;
    // The other routes wait while the answer is applied and written; an
    // `rccpack ask` started meanwhile finds the folder locked.
    let write = st.write_lock.lock().await;
    let folder = folder_lock(&st)?;
    let joined = tokio::task::spawn_blocking(move || {
        let mut guard = guard;
        let s = guard.as_mut().expect("checked above");
        let r = s.session.answer(&rule, accepted).map(|_| ());
        drop(folder);
        (guard, r)
    })
    .await;
    drop(write);
    let Ok((mut guard, r)) = joined else {
        *st.ask.lock().await = None;
        return Err(internal("learning from the answer"));
    };
    if let Err(e) = r {
        // A failed or refused write drops the session, so the next
        // question starts again from what is on disk.
        *guard = None;
        return Err(session_error(e));
    }
    let s = &guard.as_ref().expect("answered above").session;
    let answer = s.asker().answers().last().expect("just answered");
    let rcc = s.asker().learned_rcc();
    ok(&AnsweredBody {
        answer: AnswerSummary {
            accepted: answer.accepted,
            demo: answer.demo,
            rule: answer.rule.clone(),
            suspect: answer.suspect.as_ref().map(|s| s.demonstration),
        },
        learned: learned_value(&st, Some(&rcc)),
        progress: s.asker().progress(),
    })
}

/// The rule and the answer of an answer body, both required.
fn parse_answer(body: &[u8]) -> Result<(String, bool), ApiError> {
    let b: AnswerBody = parse_body(body)?;
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
    Ok((rule, accepted))
}

/// Refuse an answer unless the open question is about `rule`.
fn check_open(guard: &SessionGuard, rule: &str) -> Result<(), ApiError> {
    let Some(open) = guard
        .as_ref()
        .and_then(|s| s.session.open_question())
        .map(|o| &o.question)
    else {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            "no question is open (none asked yet, or the demonstrations changed since); ask with POST /api/ask/next",
        )
        .kind("no_question"));
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
        .kind("not_asked"));
    }
    Ok(())
}
