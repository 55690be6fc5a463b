//! `/api/learned`: `learned.rcc` as text with its rules summarised, and
//! writing it back (checked, and refused when the file changed on disk
//! since the page loaded it).

use super::super::AppState;
use super::demos::{folder_lock, read_demos};
use super::learn::rules_error;
use super::{internal, ok, parse_body, ApiError, ApiResult, St};
use crate::infer::statement_text;
use crate::rules::{check_classes, check_landmarks, parse_rules, RuleSet};
use crate::task::files::{self, LEARNED};
use axum::body::Bytes;
use axum::extract::State;
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// `learned.rcc` as the page shows it.
#[derive(Serialize)]
#[serde(untagged)]
pub(crate) enum LearnedView {
    /// The file (or its absence), read and checked.
    File(LearnedFile),
    /// Reading it failed unexpectedly.
    Failed {
        /// What failed.
        error: &'static str,
    },
}

/// `learned.rcc`: its text and version, and its rules when it parses (or
/// the error when it does not).
#[derive(Serialize)]
pub(crate) struct LearnedFile {
    /// Why the text does not parse or names a landmark the problem lacks.
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
    exists: bool,
    /// The classes of the rules that today's problem lacks.
    #[serde(skip_serializing_if = "Option::is_none")]
    note: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rules: Option<Vec<RuleSummary>>,
    /// The text (`""` when there is no file).
    text: String,
    version: String,
}

/// One rule of `learned.rcc`.
#[derive(Serialize)]
struct RuleSummary {
    /// Marked `# confirmed` in the file.
    confirmed: bool,
    formula: String,
    hard: bool,
    name: String,
    subject: String,
    weight: f64,
}

/// `learned.rcc` with content `text` (`None`: no file) as the page shows it.
pub(super) fn learned_value(st: &AppState, text: Option<&str>) -> LearnedView {
    let mut v = LearnedFile {
        error: None,
        exists: text.is_some(),
        note: None,
        rules: None,
        text: text.unwrap_or("").to_string(),
        version: files::version(text),
    };
    if let Some(t) = text {
        match parse_rules(t).and_then(|set| {
            check_landmarks(&set, &st.problem)?;
            Ok(set)
        }) {
            Ok(set) => {
                // docs/language.md#classes-a-scene-lacks: a class today's problem lacks is ordinary.
                v.note = crate::rules::absent_classes_note(&set, &st.problem);
                v.rules = Some(rule_summary(&set, &files::confirmed_names(t)));
            }
            Err(e) => v.error = Some(e.render(LEARNED, t, false)),
        }
    }
    LearnedView::File(v)
}

/// The rules of `set`, each marked confirmed when `confirmed` names it.
fn rule_summary(set: &RuleSet, confirmed: &[String]) -> Vec<RuleSummary> {
    set.rules
        .iter()
        .map(|r| RuleSummary {
            confirmed: confirmed.contains(&r.name),
            formula: statement_text(r.scope, &r.formula),
            hard: r.strength.is_hard(),
            name: r.name.clone(),
            subject: r.subject().to_string(),
            weight: r.strength.weight(),
        })
        .collect()
}

/// `learned.rcc` as it is on disk now.
pub(super) fn current_learned(st: &AppState) -> Result<LearnedView, ApiError> {
    let text = files::read_optional(&st.dir, LEARNED).map_err(|e| ApiError::io(LEARNED, e))?;
    Ok(learned_value(st, text.as_deref()))
}

pub(crate) async fn get_learned(State(st): St) -> ApiResult {
    let text = files::read_optional(&st.dir, LEARNED).map_err(|e| ApiError::io(LEARNED, e))?;
    ok(&learned_value_async(&st, text).await)
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
pub(super) async fn parse_checked(
    st: &Arc<AppState>,
    file: &'static str,
    text: String,
) -> Result<(RuleSet, String), ApiError> {
    let st = st.clone();
    tokio::task::spawn_blocking(move || {
        let set = parse_rules(&text).map_err(|e| rules_error(file, &text, e))?;
        check_landmarks(&set, &st.problem).map_err(|e| rules_error(file, &text, e))?;
        // A class of neither the problem nor the demonstrations is a typo;
        // one only the demonstrations have is ordinary (docs/language.md#classes-a-scene-lacks: noted).
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
async fn learned_value_async(st: &Arc<AppState>, text: Option<String>) -> LearnedView {
    let st = st.clone();
    tokio::task::spawn_blocking(move || learned_value(&st, text.as_deref()))
        .await
        .unwrap_or(LearnedView::Failed {
            error: "reading the rules failed unexpectedly (internal error)",
        })
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
    let current = files::read_optional(&st.dir, LEARNED).map_err(|e| ApiError::io(LEARNED, e))?;
    if files::version(current.as_deref()) != b.base_version {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("{LEARNED} changed on disk since the page loaded it; not overwritten — the page shows the file as it is now"),
        )
        .current(learned_value_async(&st, current).await));
    }
    files::atomic_write(&st.dir, LEARNED, &b.text).map_err(|e| ApiError::io(LEARNED, e))?;
    ok(&learned_value_async(&st, Some(b.text)).await)
}
