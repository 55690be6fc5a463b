//! `rccpack sample`: many distinct layouts that keep the rules (docs/guide.md#sampling).

use super::{read_rules_seen, read_scene, read_scenes, LimitStruck, Reported};
use anyhow::Result;
use clap::Args;
use rccpack::relations::Contact;
use rccpack::sample::{sample, Quality, Repair, SampleError, SampleOptions, State};
use rccpack::scene::scenes_to_json;
use rccpack::stop::Stop;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// `rccpack sample PROBLEM --rules R -n N [--seed S] [--all-rules | --min-score X]
/// [--like SCENES] [-o OUT]`
///
/// Exit codes: 0 layouts written (also when fewer than N exist, or a limit
/// struck after at least one), 1 bad input, 2 no layout of the quality
/// asked for, 3 a limit struck before any layout.
#[derive(Args, Debug)]
pub struct SampleArgs {
    /// Problem scene JSON (objects without `x`/`y` are to be placed).
    problem: PathBuf,
    /// The `.rcc` rule file.
    #[arg(long)]
    rules: PathBuf,
    /// How many distinct layouts to write.
    #[arg(short = 'n', value_name = "N", allow_hyphen_values = true)]
    n: usize,
    /// Seed of every random choice: the same seed gives the same layouts.
    #[arg(long, default_value_t = 0, allow_hyphen_values = true)]
    seed: u64,
    /// Only layouts of score 1 (every rule kept by every object).
    #[arg(long, conflicts_with = "min_score")]
    all_rules: bool,
    /// Only layouts of score at least X (0 to 1). Default: the optimum score.
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    min_score: Option<f64>,
    /// Lean towards the positions objects have in these scenes (one scene or
    /// an array, usually the demonstrations): half of the random hints are
    /// their positions.
    #[arg(long, value_name = "SCENES.json")]
    like: Option<PathBuf>,
    /// How each random hint is completed into a layout: `random` (a random
    /// variable and value at each decision; closer to uniform) or
    /// `activity` (the solver's own search; faster).
    #[arg(long, default_value = "random", value_parser = ["random", "activity"])]
    repair: String,
    /// Write the JSON array of layouts here (default: stdout).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Stop after this many seconds in all and write what was found.
    #[arg(long, value_name = "SECONDS", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Option<Duration>,
    /// Give up the search for the next layout after this many decisions
    /// (deterministic).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    layout_node_limit: Option<u64>,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value = "point")]
    contact: Contact,
    /// No summary on stderr.
    #[arg(long)]
    quiet: bool,
}

/// Draw up to `-n` distinct layouts and write them; exit 2 when there is
/// none of the quality asked.
pub fn run(a: SampleArgs) -> Result<ExitCode> {
    super::guard_outputs(
        &[&a.problem, &a.rules],
        &[("-o", a.output.as_deref())],
        &[("--like", a.like.as_deref())],
    )?;
    let problem = read_scene(&a.problem)?;
    let like = match &a.like {
        Some(p) => read_scenes(p)?.0,
        None => Vec::new(),
    };
    let rules = read_rules_seen(&a.rules, std::slice::from_ref(&problem), &like)?;
    let opts = sample_options(&a, like)?;
    let quality = opts.quality;
    let start = Instant::now();
    let mut sampler = sample(&problem, &rules, &opts).map_err(|e| failure(&a, e))?;
    let (layouts, limit) = match draw(&a, &mut sampler)? {
        Ok(drawn) => drawn,
        Err(code) => return Ok(code),
    };
    let ms = start.elapsed().as_secs_f64() * 1000.0;
    if layouts.is_empty() && limit {
        return Err(LimitStruck(format!(
            "unknown: a limit stopped the search before any layout ({ms:.1} ms)"
        ))
        .into());
    }
    let text = scenes_to_json(&layouts);
    match &a.output {
        Some(p) => super::write_file(p, text, "layouts")?,
        None => super::out(text)?,
    }
    let k = layouts.len();
    if limit {
        ewriteln!("a limit stopped the search: {k} of {} layouts written", a.n);
    } else if k < a.n && sampler.state() == State::Exhausted {
        ewriteln!(
            "only {k} distinct layouts of this quality exist (the solver proved there is no other); all {k} written"
        );
    }
    if !a.quiet {
        let what = match (quality, sampler.target_proven()) {
            (Quality::AllRules, _) => "score 1".to_string(),
            (Quality::MinScore(x), _) => format!("score at least {x}"),
            (_, Some(false)) => "the best score found (a limit stopped synthesis)".to_string(),
            _ => "the optimum score".to_string(),
        };
        ewriteln!("{k} distinct layouts of {what} in {ms:.1} ms");
    }
    Ok(ExitCode::SUCCESS)
}

/// The sampler's options from the flags (`--min-score` checked); Ctrl-C
/// stops the search and what was found is still written.
fn sample_options(a: &SampleArgs, like: Vec<rccpack::scene::Scene>) -> Result<SampleOptions> {
    let quality = match (a.all_rules, a.min_score) {
        (true, _) => Quality::AllRules,
        (false, Some(x)) => {
            if !(0.0..=1.0).contains(&x) {
                return Err(Reported(format!(
                    "error: --min-score {}: expected a number from 0 to 1",
                    rccpack::limits::number(x)
                ))
                .into());
            }
            Quality::MinScore(x)
        }
        (false, None) => Quality::Optimum,
    };
    let cancel = Arc::new(AtomicBool::new(false));
    {
        let c = cancel.clone();
        // Ctrl-C stops the search; what was found is still written.
        super::signals::on_signal(move || c.store(true, Ordering::Relaxed));
    }
    Ok(SampleOptions {
        quality,
        seed: a.seed,
        contact: a.contact,
        stop: Stop::within(a.time_limit).with_cancel(cancel),
        layout_node_limit: a.layout_node_limit,
        like,
        repair: if a.repair == "activity" {
            Repair::Activity
        } else {
            Repair::Random
        },
        tuning: super::io::tuning()?,
        ..SampleOptions::default()
    })
}

/// A sampling error naming its file: a fault of the rules (their
/// weights) the rule file, any other the problem.
fn failure(a: &SampleArgs, e: SampleError) -> Reported {
    let file = match &e {
        SampleError::Synth(
            rccpack::SynthError::WeightsTooLarge | rccpack::SynthError::BadWeight { .. },
        ) => &a.rules,
        _ => &a.problem,
    };
    Reported(format!("error: {}: {e}", file.display()))
}

/// Up to `-n` layouts from `sampler`, and whether a limit stopped it; or
/// the exit code when the problem has none (infeasible: 2).
fn draw(
    a: &SampleArgs,
    sampler: &mut rccpack::sample::Sampler,
) -> Result<Result<(Vec<rccpack::scene::Scene>, bool), ExitCode>> {
    let mut layouts = Vec::with_capacity(a.n.min(1 << 16));
    let mut limit = false;
    while layouts.len() < a.n {
        match sampler.next() {
            None => break,
            Some(Ok(s)) => layouts.push(s),
            Some(Err(SampleError::LimitReached { .. })) => {
                limit = true;
                break;
            }
            Some(Err(SampleError::Infeasible(c))) => {
                ewriteln!("infeasible: {}", super::synth::conflict_text(&c));
                return Ok(Err(ExitCode::from(2)));
            }
            Some(Err(e @ SampleError::NoLayout { .. })) => {
                ewriteln!("{e}");
                return Ok(Err(ExitCode::from(2)));
            }
            Some(Err(e)) => return Err(failure(a, e).into()),
        }
    }
    Ok(Ok((layouts, limit)))
}
