//! `rccpack learn`: learn rules from demonstrations (docs/guide.md#learning).

use super::io::{parse_rules_text, read_text};
use super::{out, read_scenes, write_file, LimitStruck, Reported};
use anyhow::Result;
use clap::Args;
use rccpack::infer::{learn_with_priors, InferError, LearnParams, Learned, Templates};
use rccpack::relations::Contact;
use rccpack::rules::{Diagnostic, DiagnosticKind, RulesError};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// `rccpack learn DEMOS.json [--statements T.rcc] [--samples N] ...`
#[derive(Args, Debug)]
pub struct LearnArgs {
    /// Demonstrations: a JSON array of complete scenes.
    demos: PathBuf,
    /// Statement set (`.rcc`); default: generated from the templates over
    /// the demonstrations' classes and fixed objects.
    #[arg(long)]
    statements: Option<PathBuf>,
    /// Which templates to generate without `--statements`: `third` (the
    /// second edition's and the group shapes: one row, column, block),
    /// `second` (flush contact, alignment, landmarks) or `first` (exactly
    /// the first edition's set).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().templates, value_name = "first|second|third")]
    templates: Templates,
    /// Random scenes in the null model (at least 1).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().samples)]
    samples: usize,
    /// Learn candidates whose posterior is below this, in (0, 1).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().cutoff)]
    cutoff: f64,
    /// Prior that a statement is not intended, in (0, 1).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().prior)]
    prior: f64,
    /// Floor of the chance rate, in (0, 1) [default: 0.5 / N_A per class].
    #[arg(long)]
    epsilon: Option<f64>,
    /// Seed of the null model; the same seed gives the same output.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().seed)]
    seed: u64,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().contact)]
    contact: Contact,
    /// Write the learned rules here (default: standard output).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Write a JSON report of every statement here.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Priors learned across tasks (`rccpack priors`): each generated
    /// statement gets its kind's prior; ruled-out kinds are left out.
    #[arg(long, value_name = "PRIORS.json")]
    priors: Option<PathBuf>,
}

pub fn run(a: LearnArgs) -> Result<ExitCode> {
    let mut inputs = vec![a.demos.as_path()];
    inputs.extend(a.statements.as_deref());
    inputs.extend(a.priors.as_deref());
    super::guard_outputs(
        &inputs,
        &[
            ("-o", a.output.as_deref()),
            ("--report", a.report.as_deref()),
        ],
        &[],
    )?;
    let params = LearnParams {
        samples: a.samples,
        cutoff: a.cutoff,
        prior: a.prior,
        epsilon: a.epsilon,
        seed: a.seed,
        contact: a.contact,
        templates: a.templates,
    };
    let progress = std::io::stderr().is_terminal();
    let priors = super::priors::read_priors_opt(a.priors.as_deref())?;
    let learned = learn_files(
        &a.demos,
        a.statements.as_deref(),
        &params,
        priors.as_ref(),
        progress,
        None,
    )?;
    let rcc = learned.to_rcc();
    match &a.output {
        Some(p) => {
            write_file(p, &rcc, "rules")?;
            if progress {
                ewriteln!("wrote {}", p.display());
            }
        }
        None => out(&rcc)?,
    }
    if let Some(p) = &a.report {
        write_file(p, learned.report_json(), "report")?;
        if progress {
            ewriteln!("wrote {}", p.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Read demonstrations (and optionally a statement file), learn, and turn
/// every error into a message naming the file (with a caret for statement
/// files). Shared by `learn` and `run`.
pub fn learn_files(
    demos_path: &Path,
    statements_path: Option<&Path>,
    params: &LearnParams,
    priors: Option<&rccpack::priors::Priors>,
    progress: bool,
    deadline: Option<Instant>,
) -> Result<Learned> {
    params
        .validate()
        .map_err(|e| Reported(format!("error: {}", super::learn_error_text(&e))))?;
    let (demos, _) = read_scenes(demos_path)?;
    let (statements, text) = read_statements(statements_path, &demos)?;
    if progress {
        ewriteln!(
            "learning from {} demonstrations with {} random scenes…",
            demos.len(),
            params.samples
        );
    }
    let start = Instant::now();
    let learned = learn_with_priors(&demos, statements.as_ref(), params, priors, deadline, None)
        .map_err(|e| learn_error(e, demos_path, statements_path, &text))?;
    if progress {
        let candidates = learned.statements.iter().filter(|s| s.candidate).count();
        ewriteln!(
            "{} statements, {} candidates, {} learned in {:.1} s",
            learned.statements.len(),
            candidates,
            learned.order.len(),
            start.elapsed().as_secs_f64()
        );
    }
    Ok(learned)
}

/// Read a statement file (when given) and check that every landmark it
/// names is a fixed object of every demonstration; its text is kept for
/// [`learn_error`]'s carets.
pub fn read_statements(
    statements_path: Option<&Path>,
    demos: &[rccpack::scene::Scene],
) -> Result<(Option<rccpack::rules::RuleSet>, String)> {
    Ok(match statements_path {
        Some(p) => {
            let text = read_text(p)?;
            let set = parse_rules_text(p, &text)?;
            for demo in demos {
                rccpack::rules::check_landmarks(&set, demo).map_err(|e| {
                    Reported(e.render(
                        &p.display().to_string(),
                        &text,
                        std::io::stderr().is_terminal(),
                    ))
                })?;
            }
            (Some(set), text)
        }
        None => (None, String::new()),
    })
}

/// A learning error in the command line's words: a time limit is exit 3
/// (`unknown: …`), a class or landmark of the statement file gets a caret
/// under it (`text` is the file's), anything else names the
/// demonstrations.
pub fn learn_error(
    e: InferError,
    demos_path: &Path,
    statements_path: Option<&Path>,
    text: &str,
) -> anyhow::Error {
    if let InferError::TimeLimit { .. } = e {
        return anyhow::Error::new(LimitStruck(format!("unknown: {e}")));
    }
    match (&e, statements_path) {
        (
            InferError::UnknownClass {
                span: Some(span), ..
            }
            | InferError::UnknownLandmark {
                span: Some(span), ..
            },
            Some(path),
        ) => {
            let kind = match e {
                InferError::UnknownClass { .. } => DiagnosticKind::UnknownClass,
                _ => DiagnosticKind::UnknownLandmark,
            };
            let diag = RulesError::new(vec![Diagnostic::new(kind, *span, e.to_string())]);
            Reported(diag.render(
                &path.display().to_string(),
                text,
                std::io::stderr().is_terminal(),
            ))
        }
        (InferError::UnknownClass { .. } | InferError::UnknownLandmark { .. }, Some(path)) => {
            Reported(format!("error: {}: {e}", path.display()))
        }
        _ => Reported(format!(
            "error: {}: {}",
            demos_path.display(),
            super::learn_error_text(&e)
        )),
    }
    .into()
}
