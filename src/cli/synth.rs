use super::{read_rules_seen, read_scene, read_scenes, Reported};
use anyhow::Result;
use clap::Args;
use rccpack::relations::Contact;
use rccpack::resemblance::ResemblanceTarget;
use rccpack::rules::RuleSet;
use rccpack::scene::Scene;
use rccpack::stop::Stop;
use rccpack::synth::{
    emit, synthesize, Progress, ProgressFn, Status, SynthError, SynthOptions, SynthResult,
};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// `rccpack synth PROBLEM --rules R [-o OUT] [--report REPORT] [limits]`
///
/// Exit codes: 0 optimal or feasible (solution written), 1 bad input,
/// 2 infeasible (the conflict is printed), 3 a limit stopped the search
/// before any solution.
#[derive(Args, Debug)]
pub struct SynthArgs {
    /// Problem scene JSON (objects without `x`/`y` are to be placed).
    problem: PathBuf,
    /// The `.rcc` rule file.
    #[arg(long)]
    rules: PathBuf,
    /// Write the solution scene here (default: stdout).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Write a JSON report: status, score, weights, times, search counts,
    /// conflict and per-rule results.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Stop after this many seconds and keep the best layout found.
    #[arg(long, value_name = "SECONDS", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Option<Duration>,
    /// Stop after this many search decisions (deterministic).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    node_limit: Option<u64>,
    /// Seed of the solver's randomised choices.
    #[arg(long, default_value_t = 0, allow_hyphen_values = true)]
    seed: u64,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value = "point")]
    contact: Contact,
    /// No progress output.
    #[arg(long)]
    quiet: bool,
    /// Do not order interchangeable objects.
    #[arg(long)]
    no_symmetry_breaking: bool,
    /// Do not post the redundant cumulative relaxations.
    #[arg(long)]
    no_redundant: bool,
    /// Among the best-scoring layouts, return one most like these scenes
    /// (one scene or an array, usually the demonstrations; docs/guide.md#layouts-like-the-demonstrations).
    #[arg(long, value_name = "SCENES.json")]
    like: Option<PathBuf>,
    /// Start from a layout assembled from these complete scenes (one scene
    /// or an array, usually the demonstrations): objects are matched by
    /// class and size, the positions tried first, the rest placed by the
    /// search. Changes only how fast a good layout is found, never the
    /// optimum. Default: the `--like` scenes; `none` turns it off.
    #[arg(long = "warm-start", value_name = "SCENES.json")]
    warm_start: Option<PathBuf>,
    /// Also write the solver-free model for other solvers: MiniZinc when FILE
    /// ends in `.mzn`, `rccpack-model/1` JSON when it ends in `.json` (see
    /// `benches/peers/`). Only the score objective is written, not `--like`.
    /// The model is written before the solve, which then runs as usual.
    #[arg(long, value_name = "FILE")]
    emit: Option<PathBuf>,
}

/// The model formats `--emit` writes.
#[derive(Clone, Copy)]
enum EmitFormat {
    MiniZinc,
    Json,
}

/// The format named by `path`'s extension (`.mzn`, `.json`), or an error
/// naming the file.
fn emit_format(path: &Path) -> Result<EmitFormat> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("mzn") => Ok(EmitFormat::MiniZinc),
        Some("json") => Ok(EmitFormat::Json),
        _ => Err(Reported(format!(
            "error: {}: cannot tell the model format from the file name; expected a name ending in `.mzn` (MiniZinc) or `.json` (rccpack-model/1 JSON)",
            path.display()
        ))
        .into()),
    }
}

/// `--emit`: build the model `synthesize` solves and write it atomically.
fn write_emitted(
    path: &Path,
    format: EmitFormat,
    problem: &rccpack::scene::Scene,
    rules: &rccpack::rules::RuleSet,
    opts: &SynthOptions,
) -> Result<(), Emitted> {
    let text = match format {
        EmitFormat::MiniZinc => emit::to_minizinc(
            &emit::emitted_for_minizinc(problem, rules, opts).map_err(Emitted::Refused)?,
        ),
        EmitFormat::Json => {
            emit::to_json(&emit::emitted(problem, rules, opts).map_err(Emitted::Refused)?)
        }
    };
    super::write_file(path, &text, "the model").map_err(Emitted::Write)
}

/// Why `--emit` wrote nothing.
enum Emitted {
    /// The checks of `synthesize` refused the problem or the rules.
    Refused(SynthError),
    /// The file could not be written.
    Write(anyhow::Error),
}

/// A synthesis error naming its file: a fault of the rules (their weights)
/// the rule file, any other the problem.
fn failure(a: &SynthArgs, e: &SynthError) -> Reported {
    let file = match e {
        SynthError::WeightsTooLarge | SynthError::BadWeight { .. } => &a.rules,
        _ => &a.problem,
    };
    Reported(format!(
        "error: {}: {}",
        file.display(),
        super::synth_error_text(e)
    ))
}

/// Solve the problem, write the layout (and the report, the emitted
/// model); exit 0 with a layout, 2 infeasible, 3 unknown.
pub fn run(a: SynthArgs) -> Result<ExitCode> {
    let emit_to = match &a.emit {
        Some(p) => Some((p.clone(), emit_format(p)?)),
        None => None,
    };
    super::guard_outputs(
        &[&a.problem, &a.rules],
        &[
            ("-o", a.output.as_deref()),
            ("--report", a.report.as_deref()),
            ("--emit", a.emit.as_deref()),
        ],
        &[
            ("--like", a.like.as_deref()),
            ("--warm-start", a.warm_start.as_deref()),
        ],
    )?;
    let Inputs {
        problem,
        like_scenes,
        warm_start,
        rules,
    } = read_inputs(&a)?;
    let opts = synth_options(&a, like_scenes.as_deref(), warm_start, super::io::tuning()?);
    if let Some((path, format)) = &emit_to {
        write_emitted(path, *format, &problem, &rules, &opts).map_err(|e| match e {
            Emitted::Refused(e) => failure(&a, &e).into(),
            Emitted::Write(e) => e,
        })?;
        if opts.like.is_some() && !a.quiet {
            ewriteln!(
                "note: {}: the model holds the score objective only, not --like's resemblance",
                path.display()
            );
        }
    }
    let result = synthesize(&problem, &rules, &opts).map_err(|e| failure(&a, &e))?;
    if let Some(path) = &a.report {
        super::write_file(path, rccpack::synth::report::report_json(&result), "report")?;
    }
    write_result(&a, &result)
}

/// What a solve reads: the problem, the like-scenes, the warm start and
/// the rules.
struct Inputs {
    problem: Scene,
    like_scenes: Option<Vec<Scene>>,
    warm_start: Vec<Scene>,
    rules: RuleSet,
}

/// Read the problem, `--like`, `--warm-start` (default: the like-scenes;
/// `none`: none) and the rules (checked against every scene read).
fn read_inputs(a: &SynthArgs) -> Result<Inputs> {
    let problem = read_scene(&a.problem)?;
    let like_scenes = match &a.like {
        Some(p) => Some(read_scenes(p)?.0),
        None => None,
    };
    let warm_start = match a.warm_start.as_deref() {
        Some(p) if p == std::path::Path::new("none") => Vec::new(),
        Some(p) => read_scenes(p)?.0,
        None => like_scenes.clone().unwrap_or_default(),
    };
    let rules = read_rules_seen(
        &a.rules,
        std::slice::from_ref(&problem),
        &[like_scenes.as_deref().unwrap_or_default(), &warm_start[..]].concat(),
    )?;
    Ok(Inputs {
        problem,
        like_scenes,
        warm_start,
        rules,
    })
}

/// The engine's options from the flags: Ctrl-C stops the search (the
/// best layout found is still written); incumbents on a terminal's stderr.
fn synth_options(
    a: &SynthArgs,
    like_scenes: Option<&[Scene]>,
    warm_start: Vec<Scene>,
    tuning: rccpack::synth::Tuning,
) -> SynthOptions {
    let cancel = Arc::new(AtomicBool::new(false));
    {
        let c = cancel.clone();
        // Ctrl-C stops the search; the best layout found is still written.
        super::signals::on_signal(move || c.store(true, Ordering::Relaxed));
    }
    let show = !a.quiet && std::io::stderr().is_terminal();
    let progress = show.then(|| {
        ProgressFn(Arc::new(|p: &Progress| {
            ewriteln!(
                "  incumbent score {:.6} at {:.1} ms",
                p.score,
                p.elapsed.as_secs_f64() * 1000.0
            );
        }))
    });
    let mut stop = Stop::within(a.time_limit).with_cancel(cancel);
    if let Some(n) = a.node_limit {
        stop = stop.with_nodes(n);
    }
    SynthOptions {
        contact: a.contact,
        stop,
        seed: a.seed,
        symmetry_breaking: !a.no_symmetry_breaking,
        redundant: !a.no_redundant,
        progress,
        like: like_scenes.map(ResemblanceTarget::new),
        warm_start,
        tuning,
        ..SynthOptions::default()
    }
}

/// The layout to `-o` or stdout and its summary on stderr, or why there
/// is none; the exit code.
fn write_result(a: &SynthArgs, result: &SynthResult) -> Result<ExitCode> {
    let ev = result.evaluation.as_ref();
    match result.status {
        Status::Optimal | Status::Feasible => {
            let scene = result.scene.as_ref().expect("a solution has a scene");
            let text = scene.to_json();
            match &a.output {
                Some(p) => super::write_file(p, text, "solution")?,
                None => super::out(text)?,
            }
            if !a.quiet {
                let e = ev.expect("a solution has an evaluation");
                ewriteln!(
                    "{}: score {:.6} ({} / {}){}{}, {:.1} ms, {} nodes",
                    match result.status {
                        Status::Optimal => "optimal",
                        _ => "feasible (limit reached)",
                    },
                    e.score,
                    e.satisfied_weight,
                    e.total_weight,
                    bound_text(result),
                    resemblance_text(result.resemblance),
                    result.stats.time_ms,
                    result.stats.nodes
                );
            }
            Ok(ExitCode::SUCCESS)
        }
        Status::Infeasible => {
            let c = result.conflict.clone().unwrap_or_default();
            let msg = format!("infeasible: {}", conflict_text(&c));
            ewriteln!("{msg}");
            Ok(ExitCode::from(2))
        }
        Status::Unknown => {
            ewriteln!(
                "unknown: a limit stopped the search before any solution ({:.1} ms, {} nodes)",
                result.stats.time_ms,
                result.stats.nodes
            );
            Ok(ExitCode::from(3))
        }
    }
}

pub use rccpack::synth::report::{bound_text, conflict_text, resemblance_text};
