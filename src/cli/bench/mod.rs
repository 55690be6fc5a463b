//! `rccpack bench`: one file per bench command (`thesis.rs`, `tasks.rs`,
//! `priors.rs`, `noisy.rs`; `sample` lives beside `rccpack sample`), and what they share
//! (the independent check, the peers asked for).

mod noisy;
mod priors;
mod tasks;
mod thesis;

use anyhow::Result;
use clap::{Args, Subcommand};
use noisy::{run_noisy, NoisyArgs};
use priors::{run_priors, PriorsBenchArgs};
use rccpack::bench::peers::{self, Peer};
use rccpack::synth::verify_solution;
use std::process::ExitCode;
use tasks::{run_tasks, TasksArgs};
use thesis::{run_thesis, ThesisArgs};

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
    Sample(crate::cli::sample::BenchSampleArgs),
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

pub fn run(a: BenchArgs) -> Result<ExitCode> {
    match a.which {
        Which::Thesis(t) => run_thesis(t),
        Which::Tasks(t) => run_tasks(t),
        Which::Sample(t) => crate::cli::sample::run_bench(t),
        Which::Priors(t) => run_priors(t),
        Which::Noisy(t) => run_noisy(t),
    }
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

fn parse_peer(s: &str) -> Result<Peer, String> {
    s.parse()
}
