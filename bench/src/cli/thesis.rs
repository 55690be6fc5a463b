//! `rccpack-bench thesis`.

use super::{available_peers, parse_peer, verify_text};
use crate::cli::{out, outln, write_file};
use anyhow::{Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rccpack::relations::Contact;
use rccpack::synth::synthesize;
use rccpack_bench::chart;
use rccpack_bench::peers::Peer;
use rccpack_bench::thesis::{self, Series, StudyConfig, StudyEvent};
use rccpack_bench::Solver;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

#[derive(Args, Debug)]
pub(super) struct ThesisArgs {
    /// Seed of every random choice (rule draws, object classes, solver).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Time limit per problem, in seconds (also for the viability solves).
    #[arg(long = "time-limit", value_name = "SECONDS", default_value = "10", value_parser = crate::cli::time_limit_arg, allow_hyphen_values = true)]
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

/// `bench thesis`: run the study, print its tables, write `thesis.json`
/// and the charts; exit 1 when a problem failed.
pub(super) fn run_thesis(a: ThesisArgs) -> Result<ExitCode> {
    let mut cfg = thesis_config(&a);
    cfg.tuning = super::tuning()?;
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
        "rccpack-bench thesis: seed {}, time limit {} s, {} viable sets from {} draws, {} problems",
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
                "rccpack-bench thesis: median runtime, n = 2..6 objects (seed {}, {} sets)",
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
                    "rccpack-bench thesis: scale series, k = {:?} (seed {})",
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
