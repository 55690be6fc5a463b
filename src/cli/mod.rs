//! Command-line front end: clap commands, file reading, exit codes.
//!
//! Exit codes (docs/cli.md): 0 success; 1 bad input; 2 infeasible; 3 a limit
//! stopped the search before any solution.

/// `eprintln!` that never panics: a failed write to standard error
/// (`2>/dev/full`, a closed terminal) is ignored, as there is nowhere left
/// to report it; the exit code still tells.
macro_rules! ewriteln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($t)*);
    }};
}

/// `eprint!` that never panics (see `ewriteln!`).
macro_rules! ewrite {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stderr(), $($t)*);
    }};
}

mod ask;
mod bench;
mod check;
mod io;
mod learn;
mod oracle;
mod priors;
mod render;
mod run;
mod sample;
mod score;
mod signals;
mod studio;
mod synth;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

pub use io::{
    guard_outputs, learn_error_text, out, outln, read_rules, read_rules_seen, read_scene,
    read_scenes, read_text_at_most, synth_error_text, task_error_text, write_file, LimitStruck,
    Reported,
};

/// Clap value parser for `--time-limit SECONDS` (the library's shared,
/// validated parser: finite, 0 to `limits::MAX_TIME_LIMIT_SECS`).
fn time_limit_arg(text: &str) -> Result<std::time::Duration, String> {
    rccpack::limits::parse_time_limit(text).map_err(|e| e.to_string())
}

/// Learn spatial placement rules from demonstrations and lay out new objects
/// that keep them.
#[derive(Parser, Debug)]
#[command(name = "rccpack", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Parse and validate a `.rcc` rule file (optionally against a scene's classes).
    Check(check::CheckArgs),
    /// Score scenes against rules (docs/language.md#the-score): per rule and per object.
    Score(score::ScoreArgs),
    /// Learn rules from demonstrations (docs/guide.md#learning).
    Learn(learn::LearnArgs),
    /// Priors per kind of statement from a library of finished task folders.
    Priors(priors::PriorsArgs),
    /// Serve the studio page: record demonstrations, learn, synthesise.
    Studio(studio::StudioArgs),
    /// Draw a scene as SVG or PNG, optionally marking rule violations.
    Render(render::RenderArgs),
    /// Place the unplaced objects of a problem so that the rules hold as well
    /// as possible (docs/guide.md#synthesis).
    Synth(synth::SynthArgs),
    /// Many distinct layouts that keep the rules, for property tests and data (docs/guide.md#sampling).
    Sample(sample::SampleArgs),
    /// The whole pipeline on a task folder: learn, synthesise, render.
    Run(run::RunArgs),
    /// Check the learned rules of a task folder with the person: show probe
    /// layouts that break one rule each, drop or confirm it (docs/guide.md#questions).
    Ask(ask::AskArgs),
    /// Benchmarks: runs `rccpack-bench` (docs/performance.md), which
    /// `cargo build --release` builds beside rccpack.
    #[command(disable_help_flag = true)]
    Bench(bench::BenchArgs),
}

/// Parse arguments, run the command, map errors to exit codes.
/// `RCCPACK_DEBUG=1`: the library's `log::debug!` lines (model size, LNS
/// rounds) on standard error. The library itself never prints.
struct DebugLog;

impl log::Log for DebugLog {
    fn enabled(&self, m: &log::Metadata) -> bool {
        m.target().starts_with("rccpack")
    }
    fn log(&self, r: &log::Record) {
        if self.enabled(r.metadata()) {
            ewriteln!("{}", r.args());
        }
    }
    fn flush(&self) {}
}

fn init_debug_log() {
    static LOGGER: DebugLog = DebugLog;
    if std::env::var_os("RCCPACK_DEBUG").is_some() && log::set_logger(&LOGGER).is_ok() {
        log::set_max_level(log::LevelFilter::Debug);
    }
}

pub fn main() -> ExitCode {
    restore_sigpipe();
    init_debug_log();
    // Usage errors are bad input: exit 1 (docs/cli.md keeps 2 for
    // "infeasible"); `--help` and `--version` print to stdout and exit 0.
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let printed = e.print();
            // `--help > /dev/full`: nothing was written, so not a success.
            return if e.use_stderr() || printed.is_err() {
                ExitCode::from(1)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    // The studio stops gracefully on its own; `rccpack-bench` handles its
    // signals itself.
    if !matches!(cli.command, Command::Studio(_) | Command::Bench(_)) {
        signals::install();
    }
    let result = match cli.command {
        Command::Check(a) => check::run(a),
        Command::Score(a) => score::run(a),
        Command::Render(a) => render::run(a),
        Command::Learn(a) => learn::run(a),
        Command::Priors(a) => priors::run(a),
        Command::Synth(a) => synth::run(a),
        Command::Run(a) => run::run(a),
        Command::Sample(a) => sample::run(a),
        Command::Studio(a) => studio::run(a),
        Command::Ask(a) => ask::run(a),
        Command::Bench(a) => bench::run(a),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            if let Some(l) = e.downcast_ref::<LimitStruck>() {
                ewriteln!("{}", l.0);
                return ExitCode::from(3);
            }
            if let Some(r) = e.downcast_ref::<Reported>() {
                ewrite!("{}", r.0);
                if !r.0.ends_with('\n') {
                    ewriteln!("");
                }
            } else {
                ewriteln!("error: {e:#}");
            }
            ExitCode::from(1)
        }
    }
}

/// Die quietly on a closed pipe (`rccpack score … | head`) like other Unix
/// tools, instead of panicking in `println!`.
fn restore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any thread exists; resetting a
    // signal disposition to its default has no memory-safety preconditions.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
