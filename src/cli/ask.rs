//! `rccpack ask DIR`: check learned rules with the person (docs/guide.md#questions).
//!
//! Reads `DIR/problem.json`, `DIR/demos.json`, optional `DIR/statements.rcc`
//! and, when resuming, `DIR/answers.json`. Each question writes the probe to
//! `DIR/probes/probe-N.json` and `.png` and asks on the terminal (`y`/`n`)
//! or runs `--oracle CMD`. After each answer, in this order and each
//! atomically: `answers.json` (the journal), `demos.json` (an accepted probe
//! joins the demonstrations), `learned.rcc` (confirmed rules marked). An
//! abort (end of input, `q`, an oracle failure, Ctrl-C) loses nothing
//! already answered; running again resumes.

use super::oracle::Verdict;
use super::{out, outln, read_rules, read_scene, Reported};
use anyhow::Result;
use clap::Args;
use rccpack::ask::{AskOptions, Asker, ProbeOptions, Question};
use rccpack::infer::{LearnParams, Templates};
use rccpack::relations::Contact;
use rccpack::task;
use rccpack::task::session::{Locking, Session, SessionError, SessionInputs, SessionOptions};
use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// `rccpack ask DIR [--max-questions N] [--oracle CMD]`
#[derive(Args, Debug)]
pub struct AskArgs {
    /// Task folder with `demos.json`, `problem.json` and optionally `statements.rcc`.
    dir: PathBuf,
    /// Ask at most this many questions in this run (answers of earlier runs
    /// do not count).
    #[arg(long, default_value_t = 50)]
    max_questions: usize,
    /// Answer with a command instead of the terminal: it is run through
    /// `sh -c` with the probe scene's path appended as its one argument; exit
    /// 0 means acceptable, 1 not acceptable, anything else aborts.
    #[arg(long, value_name = "CMD")]
    oracle: Option<String>,
    /// Stop an oracle that has not answered after this many seconds (its
    /// whole process group is ended) and abort with exit 1; what was
    /// answered before is kept.
    #[arg(long, value_name = "SECONDS", default_value = "600", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    oracle_timeout: Duration,
    /// Random scenes in the null model.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().samples)]
    samples: usize,
    /// Learn candidates whose posterior is below this, in (0, 1).
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().cutoff)]
    cutoff: f64,
    /// Seed for learning and probes.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().seed)]
    seed: u64,
    /// Stop each probe search or check after this many seconds: a safety
    /// net (what it stops depends on the machine's speed; the node budgets
    /// below do not).
    #[arg(long, value_name = "SECONDS", default_value = "10", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    time_limit: Duration,
    /// Stop a probe search after this many search nodes (the best probe
    /// found so far is shown).
    #[arg(long, value_name = "N", default_value_t = rccpack::ask::DEFAULT_PROBE_NODES, value_parser = clap::value_parser!(u64).range(1..), allow_hyphen_values = true)]
    node_limit: u64,
    /// Stop a check (does a probe exist? does one rule imply another?) after
    /// this many search nodes (the rule is then left unsettled, not asked).
    #[arg(long, value_name = "N", default_value_t = rccpack::ask::DEFAULT_CHECK_NODES, value_parser = clap::value_parser!(u64).range(1..), allow_hyphen_values = true)]
    check_nodes: u64,
    /// Search nodes each question may cost, over every check and probe
    /// search it needs (deterministic: the same folder, answers and budget
    /// ask the same questions on any machine); a rule the budget does not
    /// decide is deferred, never waited on.
    #[arg(long, value_name = "N", default_value_t = rccpack::ask::DEFAULT_QUESTION_NODES, value_parser = clap::value_parser!(u64).range(1..), allow_hyphen_values = true)]
    question_nodes: u64,
    /// Wall-clock cap per question in seconds: a safety net for slow
    /// machines (what it stops depends on the machine's speed).
    #[arg(long, value_name = "SECONDS", default_value = "10", value_parser = super::time_limit_arg, allow_hyphen_values = true)]
    question_seconds: Duration,
    /// Only probes of the problem: never a demonstration with a few objects
    /// moved.
    #[arg(long)]
    no_edits: bool,
    /// Ask about one rule per question: never one probe that breaks a
    /// group of likely habits at once (docs/guide.md#questions).
    #[arg(long)]
    no_groups: bool,
    /// Do not compute the next question for both answers while a question
    /// waits (the questions are the same either way; with it, the next one
    /// is usually ready when the answer comes). Off with `--oracle`, which
    /// answers at once.
    #[arg(long)]
    no_lookahead: bool,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().contact)]
    contact: Contact,
    /// Which templates to learn with when there is no `statements.rcc`.
    #[arg(long, default_value_t = rccpack::infer::LearnParams::default().templates, value_name = "first|second|third")]
    templates: Templates,
    /// The chance that one object of a demonstration is a slip, in [0,
    /// 0.5), as for `learn`; above 0 the session first asks about each
    /// demonstration that looks like a slip.
    #[arg(long = "slip-rate", default_value_t = rccpack::infer::DEFAULT_SLIP_RATE, allow_hyphen_values = true)]
    slip_rate: f64,
    /// Priors learned across tasks (`rccpack priors`) for every learning
    /// run of the session.
    #[arg(long, value_name = "PRIORS.json")]
    priors: Option<PathBuf>,
}

fn show_question(q: &Question, number: usize, picture: &Path) -> Result<()> {
    outln("")?;
    if let Some(s) = &q.suspect {
        let first =
            s.objects.first().map(
                |id| match q.probe.scene.objects.iter().find(|o| &o.id == id) {
                    Some(o) => format!(
                        "`{id}` at ({}, {})",
                        o.x.map_or("?".into(), |v| v.to_string()),
                        o.y.map_or("?".into(), |v| v.to_string())
                    ),
                    None => format!("`{id}`"),
                },
            );
        outln(format!(
            "question {number}: demonstration {} as you meant it?",
            s.demonstration
        ))?;
        outln(format!(
            "  {} (outlined){} breaks {} rules the other demonstrations keep: {}",
            first.unwrap_or_else(|| "it".into()),
            if s.objects.len() > 1 {
                format!(", with {},", s.objects[1..].join(", "))
            } else {
                String::new()
            },
            s.breaks.len(),
            cut_list(&s.breaks.iter().map(String::as_str).collect::<Vec<_>>(), 6)
        ))?;
        outln(format!("  rule {}: {}", q.rule, q.english))?;
        outln("  yes: it is meant, and those rules are dropped; no: a slip, it no longer counts against them (demos.json keeps it)")?;
        outln(format!("  picture: {}", picture.display()))?;
        return Ok(());
    }
    if !q.group.is_empty() {
        return show_group_question(q, number, picture);
    }
    outln(format!(
        "question {number}: rule `{}`: {}",
        q.rule, q.english
    ))?;
    outln(format!("  rule {}: {}", q.rule, q.statement))?;
    if let Some(e) = &q.probe.edit {
        let ids: Vec<&str> = e.moved.iter().map(|m| m.id.as_str()).collect();
        outln(format!(
            "  this is demonstration [{}] with {} moved (outlined; dashed: where it was)",
            e.demo,
            ids.join(" and ")
        ))?;
    }
    if q.probe.broken.is_empty() {
        outln("  this layout breaks it and keeps every other learned rule")?;
    } else {
        outln(format!(
            "  this layout breaks it for {} and keeps every other learned rule",
            q.probe.broken.join(", ")
        ))?;
    }
    if !q.also_broken.is_empty() {
        outln(format!(
            "  it also breaks {}, which the other rules imply",
            q.also_broken.join(", ")
        ))?;
    }
    outln(format!("  picture: {}", picture.display()))?;
    Ok(())
}

/// A question about a group of rules: every rule it breaks, and what each
/// answer does.
fn show_group_question(q: &Question, number: usize, picture: &Path) -> Result<()> {
    outln(format!(
        "question {number}: this layout breaks {} rules and keeps every other learned rule:",
        q.group.len()
    ))?;
    for g in &q.group {
        outln(format!(
            "  rule {}: {} ({})",
            g.rule, g.english, g.statement
        ))?;
    }
    if !q.probe.broken.is_empty() {
        outln(format!("  broken by {}", q.probe.broken.join(", ")))?;
    }
    let others: Vec<&str> = q
        .also_broken
        .iter()
        .map(String::as_str)
        .filter(|n| !q.group.iter().any(|g| g.rule == *n))
        .collect();
    if !others.is_empty() {
        outln(format!(
            "  it also breaks {}, which the other rules imply",
            others.join(", ")
        ))?;
    }
    outln("  yes: none of them is meant, all are dropped; no: at least one is meant, and the next questions find which")?;
    outln(format!("  picture: {}", picture.display()))?;
    Ok(())
}

/// At most `n` names, then how many more.
fn cut_list(names: &[&str], n: usize) -> String {
    let mut out = names[..names.len().min(n)].join(", ");
    if names.len() > n {
        out.push_str(&format!(" and {} more", names.len() - n));
    }
    out
}

/// Which held rules the session leaves unasked, and why.
fn show_unasked(asker: &Asker) -> Result<()> {
    let unasked = asker.unasked();
    let mut reasons: Vec<rccpack::ask::Unasked> = Vec::new();
    for (_, why) in &unasked {
        if !reasons.contains(why) {
            reasons.push(*why);
        }
    }
    for why in reasons {
        let names: Vec<&str> = unasked
            .iter()
            .filter(|(_, w)| *w == why)
            .map(|(n, _)| n.as_str())
            .collect();
        let hint = if why == rccpack::ask::Unasked::Deferred {
            " (a larger --question-nodes gives them more)"
        } else {
            ""
        };
        outln(format!("unasked, {why}{hint}: {}", cut_list(&names, 12)))?;
    }
    Ok(())
}

fn ask_terminal(q: &Question, number: usize, picture: &Path) -> Verdict {
    if let Err(e) = show_question(q, number, picture) {
        return Verdict::Abort(e.to_string());
    }
    let stdin = std::io::stdin();
    loop {
        let prompt = if q.suspect.is_some() {
            "  is this demonstration as you meant it? [y/n, q to stop] "
        } else {
            "  is this layout acceptable? [y/n, q to stop] "
        };
        if let Err(e) = out(prompt) {
            return Verdict::Abort(e.to_string());
        }
        let mut line = String::new();
        match stdin.lock().read_line(&mut line) {
            Ok(0) => return Verdict::Abort("end of input".into()),
            Ok(_) => {}
            Err(e) => return Verdict::Abort(format!("cannot read the answer: {e}")),
        }
        match line.trim().to_ascii_lowercase().as_str() {
            "y" | "yes" => return Verdict::Yes,
            "n" | "no" => return Verdict::No,
            "q" | "quit" => return Verdict::Abort("stopped by the person".into()),
            _ => {
                if let Err(e) = outln("  please answer y (acceptable) or n (not acceptable)") {
                    return Verdict::Abort(e.to_string());
                }
            }
        }
    }
}

/// Ctrl-C: end the oracle (its process group), remove this process's
/// temporary files in the task folder, say what is saved, exit 1 (docs/guide.md#questions:
/// an abort loses nothing answered; the next run resumes).
fn on_interrupt(dir: PathBuf, answers: PathBuf) {
    super::signals::on_signal(move || {
        super::oracle::kill_current();
        rccpack::fsutil::remove_own_temp_files(&dir);
        rccpack::fsutil::remove_own_temp_files(&dir.join(task::files::PROBES));
        ewriteln!(
            "error: interrupted (Ctrl-C); every answer given is saved in {}, run again to resume",
            answers.display()
        );
        std::process::exit(1);
    });
}

/// How the question loop ended.
struct LoopEnd {
    /// Per question, ms from the answer before it until it was ready.
    times: Vec<f64>,
    /// Why the session was aborted, if it was.
    aborted: Option<String>,
}

/// Run a question session in the task folder (see the module doc): the
/// library's [`Session`] asks; this adapter shows the questions, takes the
/// verdicts and prints.
pub fn run(a: AskArgs) -> Result<ExitCode> {
    // One session per task folder (the studio takes the same lock to
    // write), held by this adapter for the whole run.
    let _lock = super::io::lock_folder(&a.dir)?;
    on_interrupt(a.dir.clone(), a.dir.join(task::files::ANSWERS));
    let inputs = read_inputs(&a.dir)?;
    let opts = session_options(&a)?;
    let mut session = Session::open_with(&a.dir, inputs, opts).map_err(session_error)?;
    say_start(&session)?;
    let end = question_loop(&a, &mut session)?;
    finish(&a, &session, end)
}

/// The task's problem, demonstrations and statements, read with the
/// command line's errors (a `.rcc` error drawn at its place).
fn read_inputs(dir: &Path) -> Result<SessionInputs> {
    let problem = read_scene(&dir.join(task::files::PROBLEM))?;
    // As measured, as `learn` reads them (a note says what moved); a
    // measured file keeps its recorded entries when probes are appended.
    let demos_path = dir.join(task::files::DEMOS);
    let measured = super::io::read_demos(&demos_path, None)?;
    let demos = if measured.moves.is_empty() {
        task::files::DemosFile::from(measured.scenes)
    } else {
        task::files::DemosFile::parse(&super::io::read_text(&demos_path)?)
            .map_err(|e| Reported(format!("error: {}: {e}", demos_path.display())))?
    };
    let statements_path = dir.join(task::files::STATEMENTS);
    let statements = if statements_path.exists() {
        Some(read_rules(&statements_path, &demos.scenes)?)
    } else {
        None
    };
    Ok(SessionInputs {
        problem,
        demos,
        statements,
    })
}

/// The options of the session from the flags (reads `--priors`).
fn session_options(a: &AskArgs) -> Result<SessionOptions> {
    let ask = AskOptions {
        learn: LearnParams {
            samples: a.samples,
            cutoff: a.cutoff,
            seed: a.seed,
            contact: a.contact,
            templates: a.templates,
            slip_rate: a.slip_rate,
            ..LearnParams::default()
        },
        probe: ProbeOptions {
            seed: a.seed,
            solve_time: Some(a.time_limit),
            stop: rccpack::stop::Stop::never().with_nodes(a.node_limit),
            check_nodes: Some(a.check_nodes),
            tuning: super::io::tuning()?,
            ..ProbeOptions::default()
        },
        resemble: true,
        budget: rccpack::ask::QuestionBudget {
            nodes: a.question_nodes,
            wall: Some(a.question_seconds),
        },
        edits: !a.no_edits,
        groups: !a.no_groups,
        priors: super::priors::read_priors_opt(a.priors.as_deref())?.map(std::sync::Arc::new),
        ..AskOptions::default()
    };
    Ok(SessionOptions {
        ask,
        max_questions: Some(a.max_questions),
        // The folder lock is this adapter's (see `run`).
        locking: Locking::Caller,
        // An oracle answers at once: the branch not taken would only cost
        // CPU (measured: 12 questions of the bundled example took 13.7 s
        // with the look-ahead, 4.6 s without, on 2 cores). A person takes
        // seconds to look, which the look-ahead uses.
        lookahead_threads: if a.no_lookahead || a.oracle.is_some() {
            1
        } else {
            std::thread::available_parallelism().map_or(1, |n| n.get())
        },
        ..SessionOptions::default()
    })
}

/// A session's error in the command line's words: the file at fault, and
/// learning's errors as `learn` words them.
fn session_error(e: SessionError) -> anyhow::Error {
    let text = match &e {
        SessionError::Ask { path, source } => match source.as_ref() {
            rccpack::ask::AskError::Learn(l) => {
                format!("{}: {}", path.display(), super::learn_error_text(l))
            }
            _ => e.to_string(),
        },
        _ => e.to_string(),
    };
    Reported(format!("error: {text}")).into()
}

/// Say what the start kept, what is resumed and which learned rules are
/// about a class the problem lacks.
fn say_start(session: &Session) -> Result<()> {
    let dir = session.dir();
    if session.backup_written() {
        outln(format!(
            "note: {} was not learned from {} with these settings; kept as {}",
            dir.join(task::files::LEARNED).display(),
            dir.join(task::files::DEMOS).display(),
            dir.join(task::files::LEARNED_BACKUP).display()
        ))?;
    }
    if session.resumed() > 0 {
        outln(format!(
            "resuming: {} answers in {}",
            session.resumed(),
            dir.join(task::files::ANSWERS).display()
        ))?;
    }
    // docs/language.md#classes-a-scene-lacks: learned rules about a class today's problem lacks.
    if let Some(note) =
        rccpack::rules::absent_classes_note(session.asker().held(), session.problem())
    {
        outln(note)?;
    }
    Ok(())
}

/// Ask until no question is left, `--max-questions` is reached or the
/// person (or the oracle) aborts.
fn question_loop(a: &AskArgs, session: &mut Session) -> Result<LoopEnd> {
    let mut times: Vec<f64> = Vec::new();
    let mut aborted: Option<String> = None;
    let t = Instant::now();
    let mut next = session.next_question().map_err(session_error)?;
    // The wait before the first question, then answer → next question.
    let mut ready_ms = t.elapsed().as_secs_f64() * 1000.0;
    while let Some(shown) = next.take() {
        times.push(ready_ms);
        let (q, number) = (&shown.question, shown.number);
        let json = shown
            .json
            .as_deref()
            .expect("the session writes probe files");
        let png = shown
            .png
            .as_deref()
            .expect("the session writes probe files");
        let verdict = match &a.oracle {
            Some(cmd) => super::oracle::ask_oracle(cmd, json, a.oracle_timeout),
            None => ask_terminal(q, number, png),
        };
        let accepted = match verdict {
            Verdict::Yes => true,
            Verdict::No => false,
            Verdict::Abort(why) => {
                aborted = Some(why);
                break;
            }
        };
        if a.oracle.is_some() {
            outln(match &q.suspect {
                Some(s) => format!(
                    "question {number}: demonstration {} ({}) -> {}",
                    s.demonstration,
                    s.breaks.join(", "),
                    if accepted {
                        "meant: rules dropped"
                    } else {
                        "a slip: it no longer counts, rules confirmed"
                    }
                ),
                None if !q.group.is_empty() => format!(
                    "question {number}: {} rules ({}) -> {}",
                    q.group.len(),
                    q.group_names().join(", "),
                    if accepted {
                        "acceptable: all dropped"
                    } else {
                        "not acceptable: at least one is meant"
                    }
                ),
                None => format!(
                    "question {number}: `{}` ({}) -> {}",
                    q.rule,
                    q.english,
                    if accepted {
                        "acceptable: dropped"
                    } else {
                        "not acceptable: confirmed"
                    }
                ),
            })?;
        }
        let t = Instant::now();
        session.answer(&q.rule, accepted).map_err(session_error)?;
        next = session.next_question().map_err(session_error)?;
        ready_ms = t.elapsed().as_secs_f64() * 1000.0;
    }
    Ok(LoopEnd { times, aborted })
}

/// The session's summary line, the unasked rules (when it ran to the
/// end), why it stopped; exit 1 when it was aborted.
fn finish(a: &AskArgs, session: &Session, end: LoopEnd) -> Result<ExitCode> {
    let LoopEnd { times, aborted } = end;
    let (asker, asked_now) = (session.asker(), session.asked_now());
    let out_of_budget = session.out_of_budget();
    let learned = session.dir().join(task::files::LEARNED);
    let answers = session.dir().join(task::files::ANSWERS);
    let p = asker.progress();
    let median = {
        let mut t = times.clone();
        t.sort_by(f64::total_cmp);
        t.get(t.len() / 2).copied()
    };
    outln("")?;
    outln(format!(
        "asked {} questions ({} in this run{}{}): {} rules dropped{}, {} confirmed{}; {} rules held, {} need no question (the others imply them{}){} -> {}",
        p.asked,
        asked_now,
        median.map_or(String::new(), |m| format!(", median {m:.0} ms to a question")),
        if p.grouped > 0 {
            format!(", {} about a group of rules", p.grouped)
        } else {
            String::new()
        },
        p.dropped,
        if p.dropped_in_groups > 0 {
            format!(" ({} in group questions)", p.dropped_in_groups)
        } else {
            String::new()
        },
        p.confirmed,
        if p.deduced > 0 {
            format!(" ({} as the one left of a rejected group)", p.deduced)
        } else {
            String::new()
        },
        p.held,
        p.implied,
        if out_of_budget || aborted.is_some() {
            "; of the rules looked at so far"
        } else {
            ""
        },
        if p.unknown > 0 {
            format!(", {} deferred (the question budget did not decide them)", p.unknown)
        } else {
            String::new()
        },
        learned.display()
    ))?;
    if !out_of_budget && aborted.is_none() {
        show_unasked(asker)?;
    }
    if let Some(used) = asker.learned().priors.as_ref() {
        if !used.ruled_out.is_empty() {
            outln(format!(
                "ruled out by the priors (never held, never asked): {} statements",
                used.ruled_out.len()
            ))?;
        }
    }
    if out_of_budget {
        outln(format!(
            "stopped at --max-questions {}; run again to go on",
            a.max_questions
        ))?;
    }
    if let Some(why) = aborted {
        ewriteln!(
            "error: aborted ({why}); {} answers are saved in {}, run again to resume",
            p.asked,
            answers.display()
        );
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}
