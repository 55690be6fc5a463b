//! The `rccpack-bench` command line: one file per bench command
//! (`thesis.rs`, `tasks.rs`, `sample.rs`, `priors.rs`, `noisy.rs`), and what
//! they share (the independent check, the peers asked for, writing output).
//!
//! Exit codes as `rccpack`'s (docs/cli.md): 0 success, 1 bad input or a
//! failure.

/// `eprintln!` that never panics: a failed write to standard error is
/// ignored, as there is nowhere left to report it; the exit code still tells.
macro_rules! ewriteln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($t)*);
    }};
}

mod noisy;
mod priors;
mod sample;
mod tasks;
mod thesis;

use anyhow::Result;
use clap::{Parser, Subcommand};
use noisy::{run_noisy, NoisyArgs};
use priors::{run_priors, PriorsBenchArgs};
use rccpack::synth::verify_solution;
use rccpack_bench::peers::{self, Peer};
use sample::{run_bench, BenchSampleArgs};
use std::path::Path;
use std::process::ExitCode;
use tasks::{run_tasks, TasksArgs};
use thesis::{run_thesis, ThesisArgs};

/// An error whose full text is already formatted for the user.
#[derive(Debug)]
struct Reported(String);

impl std::fmt::Display for Reported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Reported {}

/// Write a whole file atomically ([`rccpack::fsutil::atomic_write`]); `what`
/// names the contents in the error ("cannot write report").
/// The engine tuning the `RCCPACK_*` environment variables ask for (to
/// compare encodings; a value that is not a choice is an error).
fn tuning() -> Result<rccpack::synth::Tuning> {
    rccpack::synth::Tuning::from_env().map_err(|e| Reported(format!("error: {e}")).into())
}

fn write_file(path: &Path, contents: impl AsRef<[u8]>, what: &str) -> Result<()> {
    rccpack::fsutil::atomic_write(path, contents).map_err(|e| {
        Reported(format!(
            "error: {}: cannot write {what}: {e}",
            path.display()
        ))
        .into()
    })
}

/// Print to standard output, reporting a failed write (`> /dev/full`) as an
/// error instead of panicking as `print!` does.
fn out(text: impl AsRef<str>) -> Result<()> {
    use std::io::Write as _;
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_ref().as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| Reported(format!("error: cannot write to standard output: {e}")).into())
}

/// [`out`] with a line end.
fn outln(text: impl AsRef<str>) -> Result<()> {
    out(format!("{}\n", text.as_ref()))
}

/// Clap value parser for `--time-limit SECONDS` (the library's validated
/// parser, as in `rccpack`).
fn time_limit_arg(text: &str) -> Result<std::time::Duration, String> {
    rccpack::limits::parse_time_limit(text).map_err(|e| e.to_string())
}

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

/// Benchmarks of rccpack: `thesis` reproduces the thesis runtime study;
/// `tasks` measures realistic learned tasks.
#[derive(Parser, Debug)]
#[command(name = "rccpack-bench", version, about, long_about = None)]
struct Cli {
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
    Sample(BenchSampleArgs),
    /// Priors learned across tasks: a seeded population of
    /// demonstrators (class names varying, styles far from uniform), a
    /// library of finished tasks and held-out tasks of 4 demonstrations,
    /// each learned with the uniform prior, priors from the library, a
    /// shuffled control and the true frequencies. Prints a markdown table
    /// (recall, rare-rule recall, spurious rules; questions `ask` needs
    /// with a truth oracle).
    Priors(PriorsBenchArgs),
    /// Demonstrations as they are recorded: the generated tasks and the
    /// bundled example learned from their exact demonstrations and from
    /// four recorded variants (every block jittered ±3 px, one slipped
    /// block, both, rough positions); prints per task the exact rules kept
    /// and the rules added, and whether the slip is named a suspect.
    Noisy(NoisyArgs),
}

/// Parse arguments, run the command, map errors to exit codes.
pub fn main() -> ExitCode {
    restore_sigpipe();
    // Usage errors are bad input: exit 1; `--help` and `--version` print to
    // stdout and exit 0.
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let printed = e.print();
            return if e.use_stderr() || printed.is_err() {
                ExitCode::from(1)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    install_signals();
    let result = match cli.which {
        Which::Thesis(t) => run_thesis(t),
        Which::Tasks(t) => run_tasks(t),
        Which::Sample(t) => run_bench(t),
        Which::Priors(t) => run_priors(t),
        Which::Noisy(t) => run_noisy(t),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            if let Some(r) = e.downcast_ref::<Reported>() {
                ewriteln!("{}", r.0.strip_suffix('\n').unwrap_or(&r.0));
            } else {
                ewriteln!("error: {e:#}");
            }
            ExitCode::from(1)
        }
    }
}

/// Die quietly on a closed pipe (`rccpack-bench thesis | head`).
fn restore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any thread exists; resetting a
    // signal disposition to its default has no memory-safety preconditions.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// Ctrl-C, SIGTERM, SIGHUP: end at once, exit 1, after removing the
/// temporary files of the writes going on, so no report is left
/// half-written.
fn install_signals() {
    let _ = ctrlc::set_handler(|| {
        rccpack::fsutil::remove_in_flight();
        ewriteln!("error: interrupted by a signal; no file was left half-written");
        std::process::exit(1);
    });
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
                ewriteln!("rccpack-bench {bench}: skipping peer {p}: {why}");
                false
            }
        })
        .collect()
}

fn parse_peer(s: &str) -> Result<Peer, String> {
    s.parse()
}
