//! `rccpack-bench tasks`.

use super::{available_peers, parse_peer, verify_text};
use crate::cli::write_file;
use anyhow::{Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rccpack::synth::synthesize;
use rccpack_bench::peers::Peer;
use rccpack_bench::tasks::{self, TasksConfig};
use rccpack_bench::Solver;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

#[derive(Args, Debug)]
pub(super) struct TasksArgs {
    /// Seed of every random choice (tasks, demonstrations, solver).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Time limit per solve (each mode, each peer), in seconds (default 30,
    /// or 5 with --quick).
    #[arg(long = "time-limit", value_name = "SECONDS", value_parser = crate::cli::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Option<Duration>,
    /// Smoke run: 2 tasks, sizes 1 and 1.5, the example at 5 per class,
    /// 5 s per solve (flags given explicitly still win).
    #[arg(long)]
    quick: bool,
    /// Number of generated tasks (default 10, or 2 with --quick; 0 to
    /// 1000).
    #[arg(long, value_parser = clap::value_parser!(u16).range(0..=1000))]
    tasks: Option<u16>,
    /// Problem sizes: multipliers of the demonstrations' largest count per
    /// class, comma-separated, each in (0, 10] (default 1,1.5,2,3). The box
    /// of a task is sized for max(3, largest size), so sizes up to 3 do not
    /// change the problems of a seed.
    #[arg(long, value_delimiter = ',', value_parser = parse_size)]
    sizes: Option<Vec<f64>>,
    /// Blocks per class of the bundled example's problems, comma-separated,
    /// 1 to 50 each (default 5,6,8,12, or 5 with --quick).
    #[arg(long = "example-counts", value_delimiter = ',', value_parser = clap::value_parser!(u16).range(1..=50))]
    example_counts: Option<Vec<u16>>,
    /// Skip the bundled example's series.
    #[arg(long = "no-example")]
    no_example: bool,
    /// Skip the solves with `like` = the demonstrations (score only).
    #[arg(long = "no-like")]
    no_like: bool,
    /// Do not hand the demonstrations to the engine as a warm start.
    #[arg(long = "no-warm-start")]
    no_warm_start: bool,
    /// Solve without large-neighbourhood search (for comparison).
    #[arg(long = "no-lns")]
    no_lns: bool,
    /// Run peer solvers on every problem's score-only model: `cp-sat`
    /// (OR-Tools, one worker) and/or `gecode` (MiniZinc), comma-separated;
    /// `--peers` alone means both. A peer that is not installed is skipped
    /// with a message.
    #[arg(long, value_delimiter = ',', num_args = 0.., value_parser = parse_peer)]
    peers: Option<Vec<Peer>>,
    /// Also write every problem as `NAME.json` (problem), `NAME.rcc`
    /// (learned rules) and `NAME.demos.json` (demonstrations) here, so that
    /// `rccpack synth NAME.json --rules NAME.rcc --like NAME.demos.json`
    /// reruns it.
    #[arg(long = "problems-out", value_name = "DIR")]
    problems_out: Option<PathBuf>,
    /// Group-style tasks (each class one row, column or block in every
    /// demonstration), after the others (default 0; 0 to 1000). Their
    /// table says how many layouts keep the demonstrated shapes.
    #[arg(long, value_parser = clap::value_parser!(u16).range(0..=1000))]
    groups: Option<u16>,
    /// Generated tasks with blocks that turn: every oblong class's blocks
    /// are turnable, and the demonstrator lays each such class flat or
    /// stands every block on end (a coin per class); the report says how
    /// many orientation habits were learned and kept. Peers whose model
    /// cannot turn a block show "n/a (turnable)".
    #[arg(long)]
    turnable: bool,
    /// Templates to learn with (default third: with the group statements).
    #[arg(long, default_value = "third", value_name = "first|second|third")]
    templates: rccpack::infer::Templates,
    /// Output directory for `tasks.json`.
    #[arg(long, default_value = "bench-out")]
    out: PathBuf,
}

/// `bench tasks`: generate the tasks, solve every problem, print the
/// tables, write `tasks.json`; exit 1 when a solve failed.
pub(super) fn run_tasks(a: TasksArgs) -> Result<ExitCode> {
    let limit = a
        .time_limit
        .unwrap_or(Duration::from_secs(if a.quick { 5 } else { 30 }));
    let mut cfg = tasks_config(&a, limit);
    cfg.tuning = super::tuning()?;
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("{}: cannot create directory", a.out.display()))?;

    let all = tasks::all_tasks(&cfg)?;
    print_tasks(&cfg, limit, &all);
    if let Some(dir) = &a.problems_out {
        write_task_problems(dir, &all)?;
        ewriteln!("wrote the problems to {}", dir.display());
    }

    let started = std::time::Instant::now();
    let report = solve_tasks(&cfg, &all);
    print!("{}", tasks::table_text(&report.summary));
    println!(
        "(proven = score-only solves proved optimal; median/max = score-only wall time; like_pr = like solves with score and cost proven; like/so = like median / score-only median; rcc_below / rcc_above = problems where rccpack's score-only score is below / above the peer's) — {:.0} s in all",
        started.elapsed().as_secs_f64()
    );
    if cfg.turnable {
        println!(
            "(turnable = most turnable blocks in a problem; learned = orientation habits, one per class that turns and problem, whose statement learning kept; kept_so / kept_like = those the score-only / like layouts keep)"
        );
    }
    let bad = failed_solves(&report);
    if !bad.is_empty() {
        println!(
            "!!! {} solves FAILED (engine error or layout rejected by the checker) — a bug:",
            bad.len()
        );
        for b in &bad {
            println!("!!!   {b}");
        }
    }
    let json = a.out.join("tasks.json");
    write_file(
        &json,
        serde_json::to_string_pretty(&report)? + "\n",
        "the report",
    )?;
    ewriteln!("wrote {}", json.display());
    Ok(if bad.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// The benchmark's configuration from the flags (`--quick` first, flags
/// given explicitly win).
fn tasks_config(a: &TasksArgs, limit: Duration) -> TasksConfig {
    let mut cfg = if a.quick {
        TasksConfig::quick(a.seed, limit)
    } else {
        TasksConfig::full(a.seed, limit)
    };
    if let Some(n) = a.tasks {
        cfg.tasks = usize::from(n);
    }
    if let Some(s) = &a.sizes {
        cfg.sizes = s.clone();
    }
    if let Some(c) = &a.example_counts {
        cfg.example_counts = c.iter().map(|&n| usize::from(n)).collect();
    }
    if a.no_example {
        cfg.example_counts.clear();
    }
    if let Some(n) = a.groups {
        cfg.groups = usize::from(n);
    }
    cfg.templates = a.templates;
    cfg.turnable = a.turnable;
    cfg.like = !a.no_like;
    cfg.warm_start = !a.no_warm_start;
    cfg.lns = !a.no_lns;
    if let Some(ps) = &a.peers {
        cfg.peers = available_peers(ps, "tasks");
    }
    cfg
}

/// The run's header line and one line per task (series, index,
/// demonstrations, rules, objects per problem, style).
fn print_tasks(cfg: &TasksConfig, limit: Duration, all: &[tasks::BenchTask]) {
    println!(
        "rccpack-bench tasks: seed {}, time limit {} s, {} tasks{}, {} problems, {}{}{}",
        cfg.seed,
        limit.as_secs_f64(),
        cfg.tasks,
        if cfg.example_counts.is_empty() {
            ""
        } else {
            " + the bundled example"
        },
        all.iter().map(|t| t.problems.len()).sum::<usize>(),
        if cfg.like {
            "score-only and like"
        } else {
            "score-only"
        },
        if cfg.warm_start { ", warm start" } else { "" },
        if cfg.lns { "" } else { ", no LNS" },
    );
    if cfg.turnable {
        println!("  oblong blocks turnable; each such class laid flat or stood on end");
    }
    for t in all {
        println!(
            "  {} {:>2}: {} demos, {} rules; objects {}; {}",
            t.series.name(),
            t.index,
            t.demos.len(),
            t.rules.rules.len(),
            t.problems
                .iter()
                .map(|p| p.movable.to_string())
                .collect::<Vec<_>>()
                .join("/"),
            t.style
        );
    }
}

/// Every problem as `NAME.json`, `NAME.rcc` and `NAME.demos.json` in `dir`.
fn write_task_problems(dir: &std::path::Path, all: &[tasks::BenchTask]) -> Result<()> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("{}: cannot create directory", dir.display()))?;
    for t in all {
        let demos = rccpack::scene::scenes_to_json(&t.demos);
        for p in &t.problems {
            write_file(
                &dir.join(format!("{}.json", p.name)),
                p.scene.to_json() + "\n",
                "the problem",
            )?;
            write_file(&dir.join(format!("{}.rcc", p.name)), &t.rcc, "the rules")?;
            write_file(
                &dir.join(format!("{}.demos.json", p.name)),
                demos.clone() + "\n",
                "the demonstrations",
            )?;
        }
    }
    Ok(())
}

/// Solve every problem with the engine, a progress bar on a terminal and
/// one line per solved problem otherwise.
fn solve_tasks(cfg: &TasksConfig, all: &[tasks::BenchTask]) -> tasks::TasksReport {
    let total: usize = all.iter().map(|t| t.problems.len()).sum();
    let bar = ProgressBar::new(total as u64);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>8} [{bar:40}] {pos}/{len} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_prefix("solving");
    // indicatif draws nothing when stderr is not a terminal: then one line
    // per solved problem instead.
    let tty = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let mut progress = |p: &tasks::TasksEvent| match p {
        tasks::TasksEvent::Solving { done, label, .. } => {
            bar.set_position(*done as u64);
            bar.set_message(label.clone());
        }
        tasks::TasksEvent::Solved { done, total, line } => {
            if tty {
                bar.println(line);
            } else {
                ewriteln!("[{done}/{total}] {line}");
            }
        }
    };
    let engine = Solver {
        solve: &synthesize,
        verify: &verify_text,
    };
    let report = tasks::run_tasks(engine, cfg, all, &mut progress);
    bar.finish_and_clear();
    report
}

/// The solves that failed (engine error or layout rejected by the
/// checker), one line each.
fn failed_solves(report: &tasks::TasksReport) -> Vec<String> {
    report
        .rows
        .iter()
        .flat_map(|r| {
            std::iter::once(("score-only", &r.score_only))
                .chain(r.like.as_ref().map(|l| ("like", l)))
                .filter(|(_, s)| s.verified == Some(false) || s.status.is_none())
                .map(move |(mode, s)| {
                    format!(
                        "{} {mode}: {}",
                        r.name,
                        s.error.as_deref().unwrap_or("engine error")
                    )
                })
        })
        .collect()
}

fn parse_size(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= 10.0 => Ok(v),
        _ => Err("expected a multiplier in (0, 10], e.g. 1.5".to_string()),
    }
}
