//! `/api/ask`: the "Check rules" questions (docs/guide.md#questions). One session per
//! folder, read from the files as `rccpack ask` reads them; each answer is
//! written as `rccpack ask` writes it (the journal first), and never over a
//! file changed outside the studio since the question was asked.

use super::super::AppState;
use super::demos::{folder_lock, read_demos};
use super::learn::{learn_params, read_statements, LearnBody};
use super::learned::{current_learned, learned_value, LearnedView};
use super::{internal, ok, parse_body, scene_value, ApiError, ApiResult, St};
use crate::ask::{Answer, AnswersFile, AskError, AskOptions, Asker, ProbeOptions, Question};
use crate::infer::LearnParams;
use crate::task::files::{self, ANSWERS, DEMOS, LEARNED, LEARNED_BACKUP};
use axum::body::Bytes;
use axum::extract::State;
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Duration;

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

/// Versions ([`files::version`]) of demos.json, learned.rcc and
/// answers.json on disk.
fn disk_versions(st: &AppState) -> Result<(String, String, String), ApiError> {
    let demos = files::read_optional(&st.dir, DEMOS).map_err(|e| ApiError::io(DEMOS, e))?;
    let learned = files::read_optional(&st.dir, LEARNED).map_err(|e| ApiError::io(LEARNED, e))?;
    let answers = files::read_optional(&st.dir, ANSWERS).map_err(|e| ApiError::io(ANSWERS, e))?;
    Ok((
        files::version(demos.as_deref()),
        files::version(learned.as_deref()),
        files::version(answers.as_deref()),
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

/// answers.json (empty when absent); one that does not parse is reported
/// (409) and never overwritten.
fn read_answers(st: &AppState) -> Result<Vec<Answer>, ApiError> {
    let Some(text) =
        files::read_optional(&st.dir, ANSWERS).map_err(|e| ApiError::io(ANSWERS, e))?
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
        .kind("corrupt_answers")
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
    let backup = files::write_session_start(&st.dir, &asker, n_demos, resumed)
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
    /// The question's number in the session, from 1.
    number: usize,
    rule: String,
    /// The probe layout.
    scene: Value,
    statement: String,
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
}

fn question_value(q: &Question, number: usize) -> QuestionBody {
    QuestionBody {
        broken: q.probe.broken.clone(),
        cost: q.probe.cost,
        edit: q.probe.edit.clone(),
        english: q.english.clone(),
        number,
        rule: q.rule.clone(),
        scene: scene_value(&q.probe.scene),
        statement: q.statement.clone(),
        time_ms: q.probe.time_ms,
    }
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
    let mut guard = apply_answer(&st, guard, accepted).await?;
    let _write = st.write_lock.lock().await;
    let saved = folder_lock(&st)
        .and_then(|_folder| save_answer(&st, guard.as_ref().expect("answered above"), accepted));
    let rcc = match saved {
        Ok((rcc, versions)) => {
            if let Some(s) = guard.as_mut() {
                s.versions = versions;
            }
            rcc
        }
        Err(e) => {
            // A failed or refused write drops the session, so the next
            // question starts again from what is on disk.
            *guard = None;
            return Err(e);
        }
    };
    let s = guard.as_ref().expect("answered above");
    let answer = s.asker.answers().last().expect("just answered");
    ok(&AnsweredBody {
        answer: AnswerSummary {
            accepted: answer.accepted,
            demo: answer.demo,
            rule: answer.rule.clone(),
        },
        learned: learned_value(&st, Some(&rcc)),
        progress: s.asker.progress(),
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
    let Some(open) = guard.as_ref().and_then(|s| s.question.as_ref()) else {
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

/// Apply the answer to the open question on a blocking thread (learning
/// again after an accepted probe); a failure drops the session.
async fn apply_answer(
    st: &Arc<AppState>,
    guard: SessionGuard,
    accepted: bool,
) -> Result<SessionGuard, ApiError> {
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
    Ok(guard)
}

/// Write the answered session as `rccpack ask` does — the journal first,
/// then the demonstrations, then the rules; each write atomic — unless the
/// demonstrations changed through another route or a file changed on disk
/// since the question was asked. Called with the folder's locks held.
/// Returns `learned.rcc`'s new text and the files' versions after the
/// writes.
fn save_answer(
    st: &AppState,
    s: &AskSession,
    accepted: bool,
) -> Result<(String, (String, String, String)), ApiError> {
    if s.generation != st.ask_generation.load(Ordering::SeqCst) {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("{DEMOS} changed while the answer was applied; the answer was not saved — ask again"),
        )
        .kind("no_question"));
    }
    // The version check of the other routes: a demonstration or a rule
    // added by hand since the session read the files is never lost.
    if disk_versions(st)? != s.versions {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("{DEMOS}, {LEARNED} or {ANSWERS} changed on disk since the question was asked; the answer was not saved and nothing was overwritten — ask again"),
        )
        .kind("stale_files"));
    }
    let rcc = s.asker.learned_rcc();
    files::write_after_answer(&st.dir, &s.asker, accepted).map_err(|(f, e)| ApiError::io(f, e))?;
    Ok((rcc, disk_versions(st)?))
}
