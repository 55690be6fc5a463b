use super::{out, outln, write_file};
use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use rccpack::bench::chart;
use rccpack::bench::peers::{self, Peer};
use rccpack::bench::tasks::{self, TasksConfig};
use rccpack::bench::thesis::{self, Series, StudyConfig, StudyEvent};
use rccpack::bench::Solver;
use rccpack::relations::Contact;
use rccpack::synth::synthesize;
use rccpack::synth::verify_solution;

/// The independent check, its error as text (the benchmarks' checker is
/// injectable: tests add checks of their own).
fn verify_text(
    problem: &rccpack::Scene,
    layout: &rccpack::Scene,
    rules: &rccpack::RuleSet,
    contact: rccpack::Contact,
) -> Result<(), String> {
    verify_solution(problem, layout, rules, contact).map_err(|e| e.to_string())
}
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

/// `rccpack bench thesis [--seed S] [--time-limit SECONDS] [--quick] [--out DIR]`,
/// `rccpack bench tasks [--tasks N] [--sizes 1,1.5,2,3] [--peers cp-sat] …`
#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    which: Which,
}

#[derive(Subcommand, Debug)]
enum Which {
    /// Reproduce the thesis runtime study (§4.1, Figure 4-1): 10 viable rule
    /// sets, n = 2..6 objects × k = 1..5 rules per class, plus a scale series
    /// (n up to 96, k = 3 and 5). Prints a table; writes `thesis.json` and
    /// PNG charts to `--out`.
    Thesis(ThesisArgs),
    /// Realistic tasks: seeded tasks made the way users make
    /// them — a box of four walls (`W`), 2–4 block classes, 3–5
    /// demonstrations following a hidden style (bands against a wall,
    /// corners, stacks, clusters, one class north of another) — rules
    /// learned from them with the default templates, and problems with
    /// 1×, 1.5×, 2×, 3× the demonstrations' largest count per class in the
    /// task's box (sized for 3×); plus the bundled example with 5, 6, 8, 12
    /// blocks per class. Each problem is solved score-only and with `like` =
    /// the demonstrations (both with the demonstrations as warm start), and
    /// by the peers on the score-only model. Prints a table per size;
    /// writes `tasks.json` to `--out`.
    Tasks(TasksArgs),
    /// Sampling: uniformity on tiny problems against brute force,
    /// diversity and speed on the bundled example and generated tasks,
    /// optionally against CP-SAT with randomised search.
    Sample(super::sample::BenchSampleArgs),
    /// Priors learned across tasks: a seeded population of
    /// demonstrators (class names varying, styles far from uniform), a
    /// library of finished tasks and held-out tasks of 4 demonstrations,
    /// each learned with the uniform prior, priors from the library, a
    /// shuffled control and the true frequencies. Prints a markdown table
    /// (recall, rare-rule recall, spurious rules; questions `ask` needs
    /// with a truth oracle).
    Priors(PriorsBenchArgs),
}

#[derive(Args, Debug)]
struct PriorsBenchArgs {
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

#[derive(Args, Debug)]
struct TasksArgs {
    /// Seed of every random choice (tasks, demonstrations, solver).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Time limit per solve (each mode, each peer), in seconds (default 30,
    /// or 5 with --quick).
    #[arg(long = "time-limit", value_name = "SECONDS", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
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
    /// Templates to learn with (default third: with the group statements).
    #[arg(long, default_value = "third", value_name = "first|second|third")]
    templates: rccpack::infer::Templates,
    /// Output directory for `tasks.json`.
    #[arg(long, default_value = "bench-out")]
    out: PathBuf,
}

#[derive(Args, Debug)]
struct ThesisArgs {
    /// Seed of every random choice (rule draws, object classes, solver).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Time limit per problem, in seconds (also for the viability solves).
    #[arg(long = "time-limit", value_name = "SECONDS", default_value = "10", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Duration,
    /// Smoke run: 3 rule sets and no scale series.
    #[arg(long)]
    quick: bool,
    /// Number of viable rule sets (default 10, or 3 with --quick; 1 to
    /// 1000).
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=1000))]
    sets: Option<u16>,
    /// Skip the scale series.
    #[arg(long = "no-scale")]
    no_scale: bool,
    /// Object counts of the scale series, comma-separated (default
    /// 8,12,16,24,32,48,64,96).
    #[arg(long = "scale-ns", value_delimiter = ',', value_parser = clap::value_parser!(u16).range(1..=512))]
    scale_ns: Option<Vec<u16>>,
    /// Rules per class of the scale series, comma-separated (default 3,5).
    #[arg(long = "scale-ks", value_delimiter = ',', value_parser = clap::value_parser!(u8).range(1..=5))]
    scale_ks: Option<Vec<u8>>,
    /// Also write every problem as `PROBLEM.json` + `PROBLEM.rcc` here.
    #[arg(long = "problems-out", value_name = "DIR")]
    problems_out: Option<PathBuf>,
    /// Run peer solvers beside rccpack on every problem: `cp-sat`
    /// (OR-Tools, one worker) and/or `gecode` (MiniZinc), comma-separated;
    /// `--peers` alone means both. A peer that is not installed is skipped
    /// with a message.
    #[arg(long, value_delimiter = ',', num_args = 0.., value_parser = parse_peer)]
    peers: Option<Vec<Peer>>,
    /// Skip the pilot grid (n = 2..6); the scale series only.
    #[arg(long = "no-pilot")]
    no_pilot: bool,
    /// Solve without large-neighbourhood search (for comparison).
    #[arg(long = "no-lns")]
    no_lns: bool,
    /// Output directory for `thesis.json`, `thesis.png` and `thesis-scale.png`.
    #[arg(long, default_value = "bench-out")]
    out: PathBuf,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value = "point")]
    contact: Contact,
}

pub fn run(a: BenchArgs) -> Result<ExitCode> {
    match a.which {
        Which::Thesis(t) => run_thesis(t),
        Which::Tasks(t) => run_tasks(t),
        Which::Sample(t) => super::sample::run_bench(t),
        Which::Priors(t) => run_priors(t),
    }
}

fn run_priors(a: PriorsBenchArgs) -> Result<ExitCode> {
    use rccpack::bench::priors::{self, PriorsBenchConfig};
    let mut cfg = PriorsBenchConfig::full(a.seed);
    cfg.library_sizes = a.library_sizes.iter().map(|&n| usize::from(n)).collect();
    cfg.held_out = usize::from(a.held_out);
    cfg.true_library = usize::from(a.true_library);
    cfg.truth_demos = usize::from(a.truth_demos);
    cfg.ask = !a.no_ask;
    cfg.max_questions = usize::from(a.max_questions);
    cfg.ask_tasks = a.ask_tasks.map(usize::from);
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
        "rccpack bench priors --seed {} --library-sizes {} --held-out {}{}",
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
        "rccpack bench priors: {:.0} s in all",
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

/// The peers asked for (`--peers` alone: all) that are installed; the
/// others are skipped with a message.
fn available_peers(asked: &[Peer], bench: &str) -> Vec<Peer> {
    let wanted: Vec<Peer> = if asked.is_empty() {
        Peer::ALL.to_vec()
    } else {
        asked.to_vec()
    };
    wanted
        .into_iter()
        .filter(|&p| match peers::check_available(p) {
            Ok(()) => true,
            Err(why) => {
                ewriteln!("rccpack bench {bench}: skipping peer {p}: {why}");
                false
            }
        })
        .collect()
}

/// `bench tasks`: generate the tasks, solve every problem, print the
/// tables, write `tasks.json`; exit 1 when a solve failed.
fn run_tasks(a: TasksArgs) -> Result<ExitCode> {
    let limit = a
        .time_limit
        .unwrap_or(Duration::from_secs(if a.quick { 5 } else { 30 }));
    let cfg = tasks_config(&a, limit);
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
        "rccpack bench tasks: seed {}, time limit {} s, {} tasks{}, {} problems, {}{}{}",
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

/// The population of `bench priors` as task folders under `dir`.
fn write_population(
    dir: &std::path::Path,
    cfg: &rccpack::bench::priors::PriorsBenchConfig,
    progress: rccpack::bench::priors::Progress<'_>,
) -> Result<()> {
    use rccpack::bench::priors;
    use rccpack::rules::print_rules;
    use rccpack::scene::scenes_to_json;
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

fn parse_size(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= 10.0 => Ok(v),
        _ => Err("expected a multiplier in (0, 10], e.g. 1.5".to_string()),
    }
}

/// `bench thesis`: run the study, print its tables, write `thesis.json`
/// and the charts; exit 1 when a problem failed.
fn run_thesis(a: ThesisArgs) -> Result<ExitCode> {
    let cfg = thesis_config(&a);
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("{}: cannot create directory", a.out.display()))?;
    let report = run_study(&cfg, a.problems_out.as_deref())?;
    let bad = print_study(&a, &cfg, &report)?;
    write_study(&a, &cfg, &report)?;
    Ok(if bad > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// The study's configuration from the flags.
fn thesis_config(a: &ThesisArgs) -> StudyConfig {
    let limit = a.time_limit;
    let mut cfg = if a.quick {
        StudyConfig::quick(a.seed, limit)
    } else {
        StudyConfig::full(a.seed, limit)
    };
    if let Some(s) = a.sets {
        cfg.sets = usize::from(s);
    }
    if let Some(ns) = &a.scale_ns {
        cfg.scale_ns = ns.iter().map(|&n| usize::from(n)).collect();
    }
    if let Some(ks) = &a.scale_ks {
        cfg.scale_ks = ks.iter().map(|&k| usize::from(k)).collect();
    }
    if a.no_scale {
        cfg.scale_ns.clear();
    }
    cfg.contact = a.contact;
    cfg.lns = !a.no_lns;
    if a.no_pilot {
        cfg.ns.clear();
    }
    if let Some(ps) = &a.peers {
        cfg.peers = available_peers(ps, "thesis");
    }
    cfg
}

/// Run the study with a progress bar (drawing the sets, then solving);
/// with `problems_out`, write every problem there.
fn run_study(
    cfg: &StudyConfig,
    problems_out: Option<&std::path::Path>,
) -> Result<thesis::StudyReport> {
    let bar = ProgressBar::new(cfg.sets as u64);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>8} [{bar:40}] {pos}/{len} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_prefix("drawing");
    let mut solving = false;
    let mut progress = |p: &StudyEvent| match p {
        StudyEvent::Drawing {
            draws,
            viable,
            wanted,
        } => {
            bar.set_length(*wanted as u64);
            bar.set_position(*viable as u64);
            bar.set_message(format!("viable sets, {draws} draws"));
        }
        StudyEvent::Solving { done, total, label } => {
            if !solving {
                solving = true;
                bar.set_prefix("solving");
                bar.set_length(*total as u64);
            }
            bar.set_position(*done as u64);
            bar.set_message(label.clone());
        }
    };
    let engine = Solver {
        solve: &synthesize,
        verify: &verify_text,
    };
    let report = thesis::run_study(engine, cfg, &mut progress);
    if let Some(dir) = problems_out {
        write_problems(dir, cfg, &report)?;
    }
    bar.finish_and_clear();
    Ok(report)
}

/// The study's header, tables and failures on stdout; how many problems
/// failed.
fn print_study(a: &ThesisArgs, cfg: &StudyConfig, report: &thesis::StudyReport) -> Result<usize> {
    outln(format!(
        "rccpack bench thesis: seed {}, time limit {} s, {} viable sets from {} draws, {} problems",
        cfg.seed,
        a.time_limit.as_secs_f64(),
        report.sets.len(),
        report.draws,
        report.rows.len()
    ))?;
    out(thesis::table_text(&report.summary))?;
    if !report.peer_summary.is_empty() {
        outln("peers (ratio = peer median / rccpack median; rcc_wrs / peer_wrs = problems where that side's score is lower):")?;
        out(thesis::peer_table_text(&report.peer_summary))?;
    }
    let bad = report
        .rows
        .iter()
        .filter(|r| r.verified == Some(false) || r.status.is_none())
        .count();
    if bad > 0 {
        outln(format!("{bad} problems failed (engine error or solution rejected by the checker): see thesis.json"))?;
    }
    Ok(bad)
}

/// `thesis.json`, `thesis.png` and (with a scale series)
/// `thesis-scale.png` in `--out`.
fn write_study(a: &ThesisArgs, cfg: &StudyConfig, report: &thesis::StudyReport) -> Result<()> {
    let json = a.out.join("thesis.json");
    write_file(
        &json,
        serde_json::to_string_pretty(report)? + "\n",
        "the report",
    )?;
    let png = a.out.join("thesis.png");
    draw_atomic(&png, |tmp| {
        chart::draw(
            tmp,
            &format!(
                "rccpack bench thesis: median runtime, n = 2..6 objects (seed {}, {} sets)",
                cfg.seed,
                report.sets.len()
            ),
            &chart::lines(&report.summary, &[Series::Pilot]),
        )
        .map_err(|e| e.to_string())
    })?;
    let mut written = vec![json, png];
    if report.summary.iter().any(|s| s.series == Series::Scale) {
        let png = a.out.join("thesis-scale.png");
        let ks: Vec<usize> = cfg.scale_ks.clone();
        let cells: Vec<_> = report
            .summary
            .iter()
            .filter(|s| ks.contains(&s.k))
            .cloned()
            .collect();
        draw_atomic(&png, |tmp| {
            chart::draw(
                tmp,
                &format!(
                    "rccpack bench thesis: scale series, k = {:?} (seed {})",
                    ks, cfg.seed
                ),
                &chart::lines(&cells, &[Series::Pilot, Series::Scale]),
            )
            .map_err(|e| e.to_string())
        })?;
        written.push(png);
    }
    for p in written {
        ewriteln!("wrote {}", p.display());
    }
    Ok(())
}

/// Draw a chart whole or not at all (as `fsutil::atomic_write`): to a
/// temporary `.png` beside `png`, then renamed over it.
fn draw_atomic(
    png: &std::path::Path,
    draw: impl FnOnce(&std::path::Path) -> Result<(), String>,
) -> Result<()> {
    let name = png
        .file_stem()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = png.with_file_name(format!(".{name}.tmp-{}.png", std::process::id()));
    let done = draw(&tmp).map_err(anyhow::Error::msg).and_then(|()| {
        std::fs::rename(&tmp, png).with_context(|| format!("{}: cannot write", png.display()))
    });
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done
}

/// Every problem of the study as a scene and a rule file, named
/// `SERIES-sSET-nN-kK`.
fn write_problems(
    dir: &std::path::Path,
    cfg: &StudyConfig,
    report: &thesis::StudyReport,
) -> Result<()> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("{}: cannot create directory", dir.display()))?;
    for p in thesis::study_problems(cfg, &report.drawn) {
        let name = format!(
            "{}-s{}-n{}-k{}",
            match p.series {
                Series::Pilot => "pilot",
                Series::Scale => "scale",
            },
            p.set,
            p.n,
            p.k
        );
        let json = dir.join(format!("{name}.json"));
        write_file(&json, p.scene.to_json() + "\n", "the problem")?;
        let rcc = dir.join(format!("{name}.rcc"));
        write_file(&rcc, rccpack::rules::print_rules(&p.rules), "the rules")?;
    }
    Ok(())
}

fn parse_peer(s: &str) -> Result<Peer, String> {
    s.parse()
}
