//! `rccpack-bench noisy`: learning from demonstrations as they are recorded.

use crate::cli::{out, outln, write_file};
use anyhow::Result;
use clap::Args;
use rccpack::rules::RuleSet;
use rccpack_bench::noisy::{self, NoisyConfig, Suspect};
use serde_json::Value;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

#[derive(Args, Debug)]
pub(super) struct NoisyArgs {
    /// Seed of the tasks and of every change made to their demonstrations.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Generated tasks (0 to 100).
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u16).range(0..=100))]
    tasks: u16,
    /// Leave out the bundled example.
    #[arg(long = "no-example")]
    no_example: bool,
    /// Time limit of each solve of the slip check.
    #[arg(long, value_name = "SECONDS", default_value = "10", value_parser = crate::cli::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Duration,
    /// The slip rate of the learner measured (the reference learns with
    /// 0, the thesis's model).
    #[arg(long = "slip-rate", default_value_t = rccpack::infer::SUGGESTED_SLIP_RATE)]
    slip_rate: f64,
    /// Also write the whole report (per task, per variant) as JSON here.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
}

/// What `rccpack learn --slip-rate ETA` does with the demonstrations:
/// read as measured (snapped to the grid), then learned.
fn learn(demos: &Value, slip_rate: f64) -> Result<(RuleSet, Vec<Suspect>), String> {
    let text = demos.to_string();
    let scenes = rccpack::scene::measured::measured_from_json(&text, None)
        .map_err(|e| e.to_string())?
        .scenes;
    let params = rccpack::infer::LearnParams {
        slip_rate,
        ..rccpack::infer::LearnParams::default()
    };
    let learned = rccpack::infer::learn(&scenes, None, &params).map_err(|e| e.to_string())?;
    let suspects = learned
        .suspects()
        .into_iter()
        .map(|s| (s.demonstration, s.object))
        .collect();
    Ok((learned.rules(), suspects))
}

pub(super) fn run_noisy(a: NoisyArgs) -> Result<ExitCode> {
    let cfg = NoisyConfig {
        tasks: usize::from(a.tasks),
        example: !a.no_example,
        time_limit: a.time_limit,
        ..NoisyConfig::full(a.seed)
    };
    let started = std::time::Instant::now();
    let progress = |row: &noisy::NoisyRow| {
        ewriteln!(
            "[{:>6.1} s] {}: {} exact rules",
            started.elapsed().as_secs_f64(),
            row.name,
            row.exact
        );
    };
    let reference = |d: &Value| learn(d, 0.0);
    let measured = |d: &Value| learn(d, a.slip_rate);
    let report = noisy::run(&cfg, [&reference, &measured], &progress)?;
    outln(format!(
        "rccpack-bench noisy --seed {} --tasks {}{} --time-limit {} --slip-rate {}",
        cfg.seed,
        cfg.tasks,
        if cfg.example { "" } else { " --no-example" },
        cfg.time_limit.as_secs_f64(),
        a.slip_rate
    ))?;
    outln("")?;
    out(noisy::table_markdown(&report))?;
    if let Some(path) = &a.json {
        write_file(
            path,
            serde_json::to_string_pretty(&report)? + "\n",
            "the report",
        )?;
        ewriteln!("wrote {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}
