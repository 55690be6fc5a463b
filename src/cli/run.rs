//! `rccpack run DIR`: the whole pipeline on a task folder.
//!
//! `DIR/demos.json` → learn (with `DIR/statements.rcc` when present, else the
//! templates) → `OUT/learned.rcc`; `DIR/problem.json` → synth with the learned
//! rules → `OUT/solution.json`, `OUT/solution.png` (and `OUT/learn-report.json`); a
//! short summary on stdout. `OUT` defaults to `DIR`.

use super::learn::learn_files;
use super::{outln, read_scene, read_scenes, write_file, Reported};
use anyhow::Result;
use clap::Args;
use rccpack::infer::{LearnParams, Templates};
use rccpack::relations::Contact;
use rccpack::render::{render_to_path, RenderOptions};
use rccpack::rules::missing_classes_note;
use rccpack::synth::{Status, SynthOptions};
use rccpack::task::{self, files, Like};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
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
    #[arg(long, default_value_t = 1000)]
    samples: usize,
    /// Learn candidates whose posterior is below this, in (0, 1).
    #[arg(long, default_value_t = 0.01)]
    cutoff: f64,
    /// Seed for learning and synthesis.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Stop the layout search after this many seconds, keeping the best found.
    #[arg(long, value_name = "SECONDS", default_value = "60", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Duration,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value = "point")]
    contact: Contact,
    /// Among the best-scoring layouts, prefer the one most like these scenes
    /// (SPEC §12): by default the task's demonstrations; `none` turns it off.
    #[arg(long, value_name = "SCENES.json|none")]
    like: Option<PathBuf>,
    /// Which templates to learn with when there is no `statements.rcc`:
    /// `second` (SPEC §11.5) or `first` (exactly SPEC §8).
    #[arg(long, default_value = "second", value_name = "first|second")]
    templates: Templates,
}

fn write(path: &Path, bytes: impl AsRef<[u8]>) -> Result<()> {
    write_file(path, bytes, "file")
}

pub fn run(a: RunArgs) -> Result<ExitCode> {
    let out = a.out.clone().unwrap_or_else(|| a.dir.clone());
    std::fs::create_dir_all(&out).map_err(|e| {
        Reported(format!(
            "error: {}: cannot create folder: {e}",
            out.display()
        ))
    })?;
    // The folder `run` writes is locked as `ask` and the studio lock it:
    // nothing is written while another session writes there.
    let _lock = super::io::lock_folder(&out)?;
    // Every input is read and checked before anything is written.
    let problem_path = a.dir.join(files::PROBLEM);
    let problem = read_scene(&problem_path)?;
    let like = match a.like.as_deref() {
        Some(p) if p == Path::new("none") => Like::Off,
        Some(p) => Like::Scenes(read_scenes(p)?.0),
        None => Like::Demos,
    };
    let demos = read_scenes(&a.dir.join(files::DEMOS))?.0;
    let statements = a.dir.join(files::STATEMENTS);
    let statements = statements.exists().then_some(statements);
    let params = LearnParams {
        samples: a.samples,
        cutoff: a.cutoff,
        seed: a.seed,
        contact: a.contact,
        templates: a.templates,
        ..LearnParams::default()
    };
    // The time limit covers the whole command: learning stops at it (exit
    // 3, nothing learned), synthesis gets what is left.
    let start = std::time::Instant::now();
    let deadline = start.checked_add(a.time_limit);
    let learned = learn_files(
        &a.dir.join(files::DEMOS),
        statements.as_deref(),
        &params,
        false,
        deadline,
    )?;
    let rules = learned.rules();
    let opts = SynthOptions {
        contact: a.contact,
        time_limit: Some(a.time_limit.saturating_sub(start.elapsed())),
        seed: a.seed,
        ..SynthOptions::default()
    };
    let placement = task::place(&problem, &rules, &demos, &like, &opts).map_err(|e| {
        Reported(format!(
            "error: {}: {}",
            problem_path.display(),
            super::task_error_text(&e)
        ))
    })?;
    // A curated learned.rcc (confirmed by `ask` or the studio, or edited)
    // is never lost: confirmed marks carry over to the rules learned again
    // unchanged, and a file that would still change is kept as a backup.
    let learned_path = out.join(files::LEARNED);
    let old = files::read_optional(&out, files::LEARNED).map_err(|e| {
        Reported(format!(
            "error: {}: cannot read file: {e}",
            learned_path.display()
        ))
    })?;
    let (rcc, backup) = files::carry_confirmed(old.as_deref(), &learned.rcc_header(), &rules);
    if backup {
        let bak = out.join(files::LEARNED_BACKUP);
        write(&bak, old.unwrap_or_default())?;
        outln(format!(
            "note: {} was not what this run learned; kept as {}",
            learned_path.display(),
            bak.display()
        ))?;
    }
    write(&learned_path, rcc)?;
    write(&out.join(files::LEARN_REPORT), learned.report_json())?;
    let result = placement.result;
    let like = placement.like;
    // Learned rules about a class today's problem lacks hold as SPEC §4
    // says (SPEC §15): a note, then a layout.
    let absent = missing_classes_note(&placement.missing_classes);
    if let Some(note) = &absent {
        outln(note)?;
    }
    let candidates = learned.statements.iter().filter(|s| s.candidate).count();
    outln(format!(
        "learned {} rules ({} candidates of {} statements) from {} demonstrations -> {}",
        rules.rules.len(),
        candidates,
        learned.statements.len(),
        learned.demos,
        out.join(files::LEARNED).display()
    ))?;
    let code = match (&result.scene, &result.evaluation) {
        (Some(scene), Some(ev)) => {
            write(&out.join(files::SOLUTION), scene.to_json())?;
            let png = out.join(files::SOLUTION_PNG);
            let ropts = RenderOptions {
                contact: a.contact,
                scale: 1.0,
                title: Some(format!("{} — synthesised", a.dir.display())),
                like,
                ..RenderOptions::default()
            };
            render_to_path(scene, Some(&rules), &ropts, &png)
                .map_err(|e| Reported(format!("error: {}: {e}", png.display())))?;
            let broken: Vec<String> = ev
                .rules
                .iter()
                .filter(|r| r.satisfied < r.subjects)
                .map(|r| format!("{} {}/{}", r.name, r.satisfied, r.subjects))
                .collect();
            outln(format!(
                "placed {} objects: {} score {:.6} (weight {:.3} / {:.3}){}{} in {:.1} ms -> {}, {}",
                problem.objects.iter().filter(|o| !o.is_placed()).count(),
                match result.status {
                    Status::Optimal => "optimal,",
                    _ => "feasible (time limit),",
                },
                ev.score,
                ev.satisfied_weight,
                ev.total_weight,
                super::synth::bound_text(&result),
                super::synth::resemblance_text(result.resemblance),
                result.stats.time_ms,
                out.join(files::SOLUTION).display(),
                png.display()
            ))?;
            if broken.is_empty() {
                outln("every placed object keeps every learned rule")?;
            } else {
                outln(format!(
                    "rules not kept by every object: {}",
                    broken.join(", ")
                ))?;
            }
            ExitCode::SUCCESS
        }
        _ if result.status == Status::Infeasible => {
            let c = result.conflict.clone().unwrap_or_default();
            ewriteln!("infeasible: {}", super::synth::conflict_text(&c));
            ExitCode::from(2)
        }
        _ => {
            ewriteln!("unknown: the time limit stopped the search before any layout was found");
            ExitCode::from(3)
        }
    };
    Ok(code)
}
