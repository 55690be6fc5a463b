//! `rccpack-bench sample`: uniformity, diversity and speed of the sampler.

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

/// `rccpack-bench sample [--seed S] [-n N] [--draws-per-layout K] [--tasks T]
/// [--peers] [--out DIR]`
#[derive(Args, Debug)]
pub(super) struct BenchSampleArgs {
    /// Seed of the sampler (and the first seed of the CP-SAT baseline).
    #[arg(long, default_value_t = 0, allow_hyphen_values = true)]
    seed: u64,
    /// Layouts per problem.
    #[arg(short = 'n', default_value_t = 100, allow_hyphen_values = true)]
    n: usize,
    /// Uniformity: draws per layout of each tiny problem.
    #[arg(long, default_value_t = 20, allow_hyphen_values = true)]
    draws_per_layout: usize,
    /// Generated realistic tasks (the 1x problem of each).
    #[arg(long, default_value_t = 3, allow_hyphen_values = true)]
    tasks: usize,
    /// Also run the baseline: CP-SAT with randomised search, one seed per
    /// layout, on the emitted model (needs python3 and ortools).
    #[arg(long)]
    peers: bool,
    /// Per problem, stop the sampler after this many seconds.
    #[arg(long, value_name = "SECONDS", default_value = "60", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Duration,
    /// Write `sample.json` into this directory.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Run `rccpack-bench sample`: the tables on stdout, `sample.json` with
/// `--out`.
pub(super) fn run_bench(a: BenchSampleArgs) -> Result<ExitCode> {
    use rccpack_bench::sample::{report_text, run_bench, BenchConfig};
    let cfg = BenchConfig {
        seed: a.seed,
        n: a.n,
        draws_per_layout: a.draws_per_layout,
        tasks: a.tasks,
        baseline: a.peers,
        time_limit_s: a.time_limit.as_secs_f64(),
    };
    let report = run_bench(&cfg, &mut |what| ewriteln!("  {what}"));
    super::out(report_text(&report))?;
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir)?;
        let text = serde_json::to_string_pretty(&report)? + "\n";
        super::write_file(&dir.join("sample.json"), text, "report")?;
    }
    Ok(ExitCode::SUCCESS)
}
