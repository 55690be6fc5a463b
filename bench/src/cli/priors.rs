//! `rccpack-bench priors`.

use crate::cli::{out, outln, write_file};
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub(super) struct PriorsBenchArgs {
    /// Seed of every random choice.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Library sizes, comma-separated (each library is the first N tasks
    /// of the largest), 1 to 1000 each.
    #[arg(long = "library-sizes", value_delimiter = ',', default_value = "5,10,20,40", value_parser = clap::value_parser!(u16).range(1..=1000))]
    library_sizes: Vec<u16>,
    /// Held-out tasks (1 to 1000).
    #[arg(long = "held-out", default_value_t = 12, value_parser = clap::value_parser!(u16).range(1..=1000))]
    held_out: u16,
    /// Tasks of the true-frequency library (1 to 10000).
    #[arg(long = "true-library", default_value_t = 200, value_parser = clap::value_parser!(u16).range(1..=10000))]
    true_library: u16,
    /// Demonstrations each task's truth is learned from (5 to 200).
    #[arg(long = "truth-demos", default_value_t = 40, value_parser = clap::value_parser!(u16).range(5..=200))]
    truth_demos: u16,
    /// Skip the question loop (quick).
    #[arg(long = "no-ask")]
    no_ask: bool,
    /// Stop the question loop after this many questions per task (1 to
    /// 1000).
    #[arg(long = "max-questions", default_value_t = 40, value_parser = clap::value_parser!(u16).range(1..=1000))]
    max_questions: u16,
    /// Run the question loop on the first N held-out tasks only (default:
    /// all; a loop takes half a minute to two minutes).
    #[arg(long = "ask-tasks", value_parser = clap::value_parser!(u16).range(0..=1000))]
    ask_tasks: Option<u16>,
    /// Ask about one rule per question in the loop (no group questions).
    #[arg(long = "no-groups")]
    no_groups: bool,
    /// A truth rule is rare when its kind was kept in fewer than this
    /// percentage of the true library's tasks (0 to 100).
    #[arg(long = "rare-percent", default_value_t = 15, value_parser = clap::value_parser!(u64).range(0..=100))]
    rare_percent: u64,
    /// Rule a kind out after this many tasks in which it was a candidate
    /// and never kept (0: never), as `rccpack priors`.
    #[arg(long = "rule-out-after", default_value_t = 10)]
    rule_out_after: u64,
    /// Shrinkage strength, as `rccpack priors` (at least 1).
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..))]
    strength: u32,
    /// Threads (default: every core). The table is the same for any number.
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    threads: Option<u16>,
    /// Also write the whole report (per task, per condition) as JSON here.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Also write the population as task folders here:
    /// `library/NN/{demos.json,learned.rcc}` (learned.rcc: the kept rules;
    /// `rccpack priors DIR/library/*/` counts them) and
    /// `held-out/NN/{demos.json,problem.json,truth.rcc}`.
    #[arg(long = "tasks-out", value_name = "DIR")]
    tasks_out: Option<PathBuf>,
}

pub(super) fn run_priors(a: PriorsBenchArgs) -> Result<ExitCode> {
    use rccpack_bench::priors::{self, PriorsBenchConfig};
    let mut cfg = PriorsBenchConfig::full(a.seed);
    cfg.library_sizes = a.library_sizes.iter().map(|&n| usize::from(n)).collect();
    cfg.held_out = usize::from(a.held_out);
    cfg.true_library = usize::from(a.true_library);
    cfg.truth_demos = usize::from(a.truth_demos);
    cfg.ask = !a.no_ask;
    cfg.max_questions = usize::from(a.max_questions);
    cfg.ask_tasks = a.ask_tasks.map(usize::from);
    cfg.ask_groups = !a.no_groups;
    cfg.params.rule_out_after = a.rule_out_after;
    cfg.rare_percent = a.rare_percent;
    cfg.params.strength = a.strength;
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = a.threads {
        pool = pool.num_threads(usize::from(n));
    }
    let pool = pool.build().context("cannot start the threads")?;
    let started = std::time::Instant::now();
    let progress = |line: &str| {
        ewriteln!("[{:>6.1} s] {line}", started.elapsed().as_secs_f64());
    };
    if let Some(dir) = &a.tasks_out {
        pool.install(|| write_population(dir, &cfg, &progress))?;
    }
    let report = pool.install(|| priors::run(&cfg, &progress))?;
    outln(format!(
        "rccpack-bench priors --seed {} --library-sizes {} --held-out {}{}",
        cfg.seed,
        cfg.library_sizes
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(","),
        cfg.held_out,
        if cfg.ask { "" } else { " --no-ask" }
    ))?;
    outln("")?;
    out(priors::table_markdown(&report))?;
    ewriteln!(
        "rccpack-bench priors: {:.0} s in all",
        started.elapsed().as_secs_f64()
    );
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

/// The population of `bench priors` as task folders under `dir`.
fn write_population(
    dir: &std::path::Path,
    cfg: &rccpack_bench::priors::PriorsBenchConfig,
    progress: rccpack_bench::priors::Progress<'_>,
) -> Result<()> {
    use rccpack::rules::print_rules;
    use rccpack::scene::scenes_to_json;
    use rccpack_bench::priors;
    let (held, library) = priors::population(cfg, progress)?;
    for (i, t) in library.iter().enumerate() {
        let d = dir
            .join("library")
            .join(format!("{:02}", i.saturating_add(1)));
        std::fs::create_dir_all(&d)
            .with_context(|| format!("{}: cannot create directory", d.display()))?;
        write_file(
            &d.join("demos.json"),
            scenes_to_json(&t.demos) + "\n",
            "the demonstrations",
        )?;
        let kept = priors::library_kept(t, cfg)?;
        write_file(&d.join("learned.rcc"), print_rules(&kept), "the kept rules")?;
    }
    for (i, t) in held.iter().enumerate() {
        let d = dir
            .join("held-out")
            .join(format!("{:02}", i.saturating_add(1)));
        std::fs::create_dir_all(&d)
            .with_context(|| format!("{}: cannot create directory", d.display()))?;
        write_file(
            &d.join("demos.json"),
            scenes_to_json(&t.demos) + "\n",
            "the demonstrations",
        )?;
        write_file(
            &d.join("problem.json"),
            priors::problem_scene(t).to_json() + "\n",
            "the problem",
        )?;
        write_file(&d.join("truth.rcc"), print_rules(&t.truth), "the truth")?;
    }
    ewriteln!("wrote the population to {}", dir.display());
    Ok(())
}
