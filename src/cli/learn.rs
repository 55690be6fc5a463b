//! `rccpack learn`: learn rules from demonstrations (docs/guide.md#learning).

use super::io::{parse_rules_text, read_text};
use super::{out, write_file, LimitStruck, Reported};
use anyhow::Result;
use clap::Args;
use rccpack::infer::{learn_with, InferError, LearnOptions, LearnParams, Learned, Templates};
use rccpack::relations::Contact;
use rccpack::rules::{Diagnostic, DiagnosticKind, RulesError};
use rccpack::scene::measured::{Measured, Move};
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
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().samples, allow_hyphen_values = true)]
    samples: usize,
    /// Learn candidates whose posterior is below this, in (0, 1).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().cutoff, allow_hyphen_values = true)]
    cutoff: f64,
    /// Prior that a statement is not intended, in (0, 1).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().prior, allow_hyphen_values = true)]
    prior: f64,
    /// Floor of the chance rate, in (0, 1) [default: 0.5 / N_A per class].
    #[arg(long, allow_hyphen_values = true)]
    epsilon: Option<f64>,
    /// Seed of the null model; the same seed gives the same output.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().seed, allow_hyphen_values = true)]
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
    /// Demonstrations as measured: every position goes to the grid, moving
    /// at most about this many px (below half the grid step; default: four
    /// tenths of it; 0: exact, fractions and overlaps refused).
    #[arg(long, value_name = "PX", value_parser = tolerance_arg, allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// The chance that one object of a demonstration is a slip, in [0,
    /// 0.5): a statement broken in one demonstration only (of at least
    /// three) is weighed with it; 0 is the thesis's model.
    #[arg(long = "slip-rate", default_value_t = rccpack::infer::DEFAULT_SLIP_RATE, allow_hyphen_values = true)]
    slip_rate: f64,
}

/// Clap value parser for `--tolerance PX`: a finite number, at least 0
/// (checked against the grid once the demonstrations are read).
pub fn tolerance_arg(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!(
            "`{}` is not a number of pixels; expected a number from 0 to below half the grid step",
            rccpack::limits::cut(text)
        )),
    }
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
        slip_rate: a.slip_rate,
    };
    let progress = std::io::stderr().is_terminal();
    let priors = super::priors::read_priors_opt(a.priors.as_deref())?;
    let (learned, measured) = learn_files(
        &a.demos,
        a.tolerance,
        a.statements.as_deref(),
        &params,
        &LearnOptions {
            priors: priors.as_ref(),
            ..LearnOptions::default()
        },
        progress,
    )?;
    print_suspects(&learned, &measured.scenes);
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
        write_file(p, report_with_moves(&learned, &measured.moves), "report")?;
        if progress {
            ewriteln!("wrote {}", p.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// One line on standard error per suspect (docs/guide.md#slips): the
/// demonstration, the object and where it stands, the rules it breaks.
pub fn print_suspects(learned: &Learned, demos: &[rccpack::Scene]) {
    for s in learned.suspects() {
        let at = demos
            .get(s.demonstration)
            .and_then(|d| d.objects.iter().find(|o| o.id == s.object))
            .and_then(|o| o.x.zip(o.y))
            .map_or(String::new(), |(x, y)| format!(" at ({x}, {y})"));
        let who = if s.object.is_empty() {
            "it".to_string()
        } else {
            format!("`{}`{at}", s.object)
        };
        let mut names = s
            .breaks
            .iter()
            .take(3)
            .cloned()
            .collect::<Vec<_>>()
            .join(", ");
        if s.breaks.len() > 3 {
            names.push_str(", …");
        }
        ewriteln!(
            "demonstration {}: {who} breaks {} rule{} the other {} keep ({names}) — a slip?",
            s.demonstration,
            s.breaks.len(),
            if s.breaks.len() == 1 { "" } else { "s" },
            learned.demos.saturating_sub(1)
        );
    }
}

/// The learn report, with every move of demonstrations read as measured
/// (`"measured"`: the demonstration, object, measured and snapped position,
/// distance) when something moved; otherwise the report as the library
/// writes it.
pub fn report_with_moves(learned: &Learned, moves: &[Move]) -> String {
    let json = learned.report_json();
    if moves.is_empty() {
        return json;
    }
    let Ok(serde_json::Value::Object(mut map)) = serde_json::from_str(&json) else {
        return json;
    };
    let list: Vec<serde_json::Value> = moves
        .iter()
        .map(|m| {
            serde_json::json!({
                "demonstration": m.demonstration,
                "object": m.object,
                "from": [m.from.0, m.from.1],
                "to": [m.to.0, m.to.1],
                "distance": (m.distance * 1000.0).round() / 1000.0,
            })
        })
        .collect();
    map.insert("measured".into(), serde_json::json!({ "moves": list }));
    serde_json::to_string_pretty(&serde_json::Value::Object(map)).unwrap_or(json) + "\n"
}

/// Read demonstrations as measured (snapped to the grid with `tolerance`)
/// and optionally a statement file, learn, and turn every error into a
/// message naming the file (with a caret for statement files). Shared by
/// `learn` and `run`.
pub fn learn_files(
    demos_path: &Path,
    tolerance: Option<f64>,
    statements_path: Option<&Path>,
    params: &LearnParams,
    opts: &LearnOptions<'_>,
    progress: bool,
) -> Result<(Learned, Measured)> {
    params
        .validate()
        .map_err(|e| Reported(format!("error: {}", super::learn_error_text(&e))))?;
    let measured = super::io::read_demos(demos_path, tolerance)?;
    let demos = &measured.scenes;
    let (statements, text) = read_statements(statements_path, demos)?;
    if progress {
        ewriteln!(
            "learning from {} demonstrations with {} random scenes…",
            demos.len(),
            params.samples
        );
    }
    let start = Instant::now();
    let learned = learn_with(demos, statements.as_ref(), params, opts)
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
    Ok((learned, measured))
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
