//! `POST /api/learn`: learn rules from the saved demonstrations (one run per
//! folder: a newer request, or the client leaving, cancels the one going
//! on). The request bodies' learning parameters, shared with the questions.

use super::super::AppState;
use super::demos::read_demos;
use super::{ok, parse_body, ApiError, ApiResult, St};
use crate::infer::{learn_with, statement_text, LearnOptions, LearnParams, StatementSource};
use crate::rules::{parse_rules, RuleSet};
use crate::task::files::{self, DEMOS, STATEMENTS};
use axum::body::Bytes;
use axum::extract::State;
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct LearnBody {
    pub(super) samples: Option<usize>,
    pub(super) seed: Option<u64>,
    pub(super) cutoff: Option<f64>,
    /// The chance that one object of a demonstration is a slip
    /// (docs/guide.md#slips); omitted: the library's default.
    pub(super) slip_rate: Option<f64>,
    /// "Check rules" only: ask about groups of likely habits with one
    /// probe (docs/guide.md#questions); omitted: on.
    pub(super) groups: Option<bool>,
}

/// statements.rcc, parsed, when present.
pub(super) fn read_statements(st: &AppState) -> Result<Option<RuleSet>, ApiError> {
    match files::read_optional(&st.dir, STATEMENTS).map_err(|e| ApiError::io(STATEMENTS, e))? {
        Some(text) => Ok(Some(
            parse_rules(&text).map_err(|e| rules_error(STATEMENTS, &text, e))?,
        )),
        None => Ok(None),
    }
}

pub(super) fn rules_error(file: &str, src: &str, e: crate::rules::RulesError) -> ApiError {
    ApiError::bad(e.render(file, src, false)).file(file)
}

/// Learning parameters from a learn (or ask) body, checked.
pub(super) fn learn_params(b: &LearnBody) -> Result<LearnParams, ApiError> {
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
    if let Some(r) = b.slip_rate {
        params.slip_rate = r;
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
pub(super) struct CancelOnDrop(pub(super) Arc<AtomicBool>);

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
        let opts = LearnOptions {
            priors: priors.as_deref(),
            stop: crate::stop::Stop::never().with_cancel(cancel),
            ..LearnOptions::default()
        };
        learn_with(&demos, statements.as_ref(), &params, &opts)
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
        .kind("cancelled"),
        e => ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, format!("{DEMOS}: {e}")),
    })?;
    ok(&learn_body(&learned, params.samples))
}

/// The body of `POST /api/learn`.
#[derive(Serialize)]
struct LearnResponse {
    /// Statements every demonstration satisfies.
    candidates: usize,
    demonstrations: usize,
    /// The header comment of `learned.rcc`, ending in a newline.
    header: String,
    /// The learned rules, strongest first.
    rules: Vec<LearnedRule>,
    samples: usize,
    /// `given` or `templates`.
    source: &'static str,
    /// Statements weighed.
    statements: usize,
    /// With a slip rate: the blocks likelier slips than not, with the
    /// learned rules they break, the likeliest first (docs/guide.md#slips).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    suspects: Vec<crate::infer::Suspect>,
}

/// One learned rule with its numbers.
#[derive(Serialize)]
struct LearnedRule {
    english: String,
    formula: String,
    implied_by: Option<String>,
    log10_posterior: f64,
    n: u64,
    name: String,
    p: f64,
    posterior: f64,
    q: Option<f64>,
    /// The rule as `.rcc` text.
    rcc: String,
    subject: String,
    weight: f64,
}

/// What a learning run answers: its header and every learned rule.
fn learn_body(learned: &crate::infer::Learned, samples: usize) -> LearnResponse {
    let rcc = learned.to_rcc();
    let header = rcc.split("\n\n").next().unwrap_or("").to_string() + "\n";
    let set = learned.rules();
    let rules = learned
        .order
        .iter()
        .zip(&set.rules)
        .map(|(&k, rule)| {
            let s = &learned.statements[k];
            let post = s.posterior.expect("learned rules have a posterior");
            LearnedRule {
                english: s.english.clone(),
                formula: statement_text(s.scope, &s.formula),
                implied_by: s.implied_by.clone(),
                log10_posterior: post.log10_posterior,
                n: s.n,
                name: s.name.clone(),
                p: post.p,
                posterior: post.written(),
                q: s.q,
                rcc: crate::rules::print_rule(rule),
                subject: s.subject.clone(),
                weight: rule.strength.weight(),
            }
        })
        .collect();
    LearnResponse {
        candidates: learned.statements.iter().filter(|s| s.candidate).count(),
        demonstrations: learned.demos,
        header,
        rules,
        samples,
        source: match learned.source {
            StatementSource::Given => "given",
            StatementSource::Templates => "templates",
        },
        statements: learned.statements.len(),
        suspects: learned.suspects(),
    }
}
