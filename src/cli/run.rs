//! `rccpack run DIR`: the whole pipeline on a task folder.
//!
//! `DIR/demos.json` → learn (with `DIR/statements.rcc` when present, else the
//! templates) → `OUT/learned.rcc`; `DIR/problem.json` → synth with the learned
//! rules → `OUT/solution.json`, `OUT/solution.png` (and `OUT/learn-report.json`); a
//! short summary on stdout. `OUT` defaults to `DIR`.

use super::learn::{learn_error, read_statements};
use super::{outln, read_scene, read_scenes, Reported};
use anyhow::Result;
use clap::Args;
use rccpack::infer::{LearnParams, Templates};
use rccpack::relations::Contact;
use rccpack::stop::Stop;
use rccpack::synth::SynthOptions;
use rccpack::task::folder::{self, Ending, FolderError};
use rccpack::task::{files, Like, RunOptions, Task, TaskError};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

/// `rccpack run DIR [--out OUT] [--samples N] [--seed S] [--time-limit SECONDS]`
#[derive(Args, Debug)]
pub struct RunArgs {
    /// Task folder with `demos.json`, `problem.json` and optionally `statements.rcc`.
    dir: PathBuf,
    /// Where to write `learned.rcc`, `learn-report.json`, `solution.json`, `solution.png` (default: DIR).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Random scenes in the null model.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().samples, allow_hyphen_values = true)]
    samples: usize,
    /// Learn candidates whose posterior is below this, in (0, 1).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().cutoff, allow_hyphen_values = true)]
    cutoff: f64,
    /// Seed for learning and synthesis.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().seed, allow_hyphen_values = true)]
    seed: u64,
    /// Stop the layout search after this many seconds, keeping the best found.
    #[arg(long, value_name = "SECONDS", default_value = "60", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Duration,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().contact)]
    contact: Contact,
    /// Among the best-scoring layouts, prefer the one most like these scenes
    /// (docs/guide.md#layouts-like-the-demonstrations): by default the task's demonstrations; `none` turns it off.
    #[arg(long, value_name = "SCENES.json|none")]
    like: Option<PathBuf>,
    /// Which templates to learn with when there is no `statements.rcc`:
    /// `third` (with group shapes), `second` or `first` (see `learn`).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().templates, value_name = "first|second|third")]
    templates: Templates,
    /// Priors learned across tasks (`rccpack priors`).
    #[arg(long, value_name = "PRIORS.json")]
    priors: Option<PathBuf>,
    /// Demonstrations as measured: every position goes to the grid, moving
    /// at most about this many px (see `learn`).
    #[arg(long, value_name = "PX", value_parser = super::learn::tolerance_arg, allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// The chance that one object of a demonstration is a slip (see
    /// `learn`); 0 is the thesis's model.
    #[arg(long = "slip-rate", default_value_t = rccpack::infer::DEFAULT_SLIP_RATE, allow_hyphen_values = true)]
    slip_rate: f64,
}

pub fn run(a: RunArgs) -> Result<ExitCode> {
    let out = a.out.clone().unwrap_or_else(|| a.dir.clone());
    refuse_outputs_as_inputs(&a, &out)?;
    // The folder `run` writes is locked as `ask` and the studio lock it:
    // nothing is written while another session writes there.
    let lock = folder::lock(&out).map_err(|e| Reported(format!("error: {e}")))?;
    // Every input is read and checked before anything is written.
    let (task, mut opts, sources) = read_inputs(&a)?;
    // The time limit covers the whole command: learning stops at it (exit
    // 3, nothing learned), synthesis gets what is left. A curated
    // learned.rcc (confirmed by `ask` or the studio, or edited) is never
    // lost: confirmed marks carry over to the rules learned again
    // unchanged, and a file that would still change is kept as a backup.
    opts.synth.stop = Stop::after(a.time_limit);
    let ran =
        folder::run_locked(&lock, &task, &a.dir, &out, &opts).map_err(|e| sources.error(e))?;
    let said = folder::summary(&ran);
    for line in &said.stdout {
        outln(line)?;
    }
    if let Some(line) = &said.stderr {
        ewriteln!("{line}");
    }
    Ok(ExitCode::from(exit_code(ran.ending())))
}

/// Outputs are never inputs: `--like` or `--priors` naming a file `run`
/// writes in `out` is refused before anything is read or written.
fn refuse_outputs_as_inputs(a: &RunArgs, out: &Path) -> Result<()> {
    let written: Vec<PathBuf> = [
        files::LEARNED,
        files::LEARNED_BACKUP,
        files::LEARN_REPORT,
        files::SOLUTION,
        files::SOLUTION_PNG,
    ]
    .iter()
    .map(|f| out.join(f))
    .collect();
    let outputs: Vec<(&str, Option<&Path>)> = written
        .iter()
        .map(|p| ("--out", Some(p.as_path())))
        .collect();
    super::guard_outputs(
        &[],
        &outputs,
        &[
            ("--like", a.like.as_deref()),
            ("--priors", a.priors.as_deref()),
        ],
    )
}

/// Where a run's inputs came from, for its error messages.
struct Sources {
    problem: PathBuf,
    demos: PathBuf,
    statements: Option<PathBuf>,
    /// The statements' text as read.
    text: String,
}

impl Sources {
    /// A failed run in the CLI's words, naming the file at fault.
    fn error(&self, e: FolderError) -> anyhow::Error {
        match e {
            FolderError::Task(TaskError::Learn(e)) => {
                learn_error(e, &self.demos, self.statements.as_deref(), &self.text)
            }
            FolderError::Task(e) => Reported(format!(
                "error: {}: {}",
                self.problem.display(),
                super::task_error_text(&e)
            ))
            .into(),
            e => Reported(format!("error: {e}")).into(),
        }
    }
}

/// Read and check every input of the run: the task, the options it runs
/// with, and where each input came from.
fn read_inputs(a: &RunArgs) -> Result<(Task, RunOptions, Sources)> {
    let problem_path = a.dir.join(files::PROBLEM);
    let problem = read_scene(&problem_path)?;
    let like = match a.like.as_deref() {
        Some(p) if p == Path::new("none") => Like::Off,
        Some(p) => Like::Scenes(read_scenes(p)?.0),
        None => Like::Demos,
    };
    let demos_path = a.dir.join(files::DEMOS);
    let demos = super::io::read_demos(&demos_path, a.tolerance)?.scenes;
    let priors = super::priors::read_priors_opt(a.priors.as_deref())?;
    let statements = a.dir.join(files::STATEMENTS);
    let statements_path = statements.exists().then_some(statements);
    let params = LearnParams {
        samples: a.samples,
        cutoff: a.cutoff,
        seed: a.seed,
        contact: a.contact,
        templates: a.templates,
        slip_rate: a.slip_rate,
        ..LearnParams::default()
    };
    params
        .validate()
        .map_err(|e| Reported(format!("error: {}", super::learn_error_text(&e))))?;
    let (statements, text) = read_statements(statements_path.as_deref(), &demos)?;
    let task = Task {
        demos,
        statements,
        problem,
    };
    let opts = RunOptions {
        learn: params,
        synth: SynthOptions {
            contact: a.contact,
            seed: a.seed,
            tuning: super::io::tuning()?,
            ..SynthOptions::default()
        },
        like,
        priors: priors.map(Arc::new),
    };
    let sources = Sources {
        problem: problem_path,
        demos: demos_path,
        statements: statements_path,
        text,
    };
    Ok((task, opts, sources))
}

/// The exit code of a run (docs/cli.md): 0 a layout, 2 infeasible, 3 a
/// limit before any layout.
pub fn exit_code(ending: Ending) -> u8 {
    match ending {
        Ending::Layout => 0,
        Ending::Infeasible => 2,
        _ => 3,
    }
}
