use super::{out, outln, read_rules, read_scenes};
use anyhow::Result;
use clap::Args;
use rccpack::eval::{evaluate, Evaluation};
use rccpack::relations::Contact;
use std::path::PathBuf;
use std::process::ExitCode;

/// `rccpack score SCENE --rules R [--json] [--contact point|edge]`
///
/// SCENE is one scene or a demonstrations array; each scene is scored on its
/// own, in order.
#[derive(Args, Debug)]
pub struct ScoreArgs {
    /// Scene JSON (an object) or demonstrations JSON (an array of scenes).
    scene: PathBuf,
    /// The `.rcc` rule file.
    #[arg(long)]
    rules: PathBuf,
    /// Print JSON: one object per scene (an array for an array input) with
    /// `score`, `satisfied_weight`, `total_weight`, `hard_violations`,
    /// `off_grid` and `rules: [{name, weight, hard, subjects, satisfied, violators}]`.
    #[arg(long)]
    json: bool,
    /// How EC decides that two sides touch: `point` (corners count) or `edge`.
    #[arg(long, default_value = "point")]
    contact: Contact,
    /// Judge instead of report: exit 0 when every rule holds for every
    /// object of every scene, 1 otherwise (an oracle for `rccpack ask`).
    #[arg(long)]
    require: bool,
}

pub fn run(a: ScoreArgs) -> Result<ExitCode> {
    let (scenes, is_array) = read_scenes(&a.scene)?;
    let rules = read_rules(&a.rules, &scenes)?;
    if scenes.is_empty() {
        // An empty demonstrations array: say so rather than print nothing.
        return if a.json {
            outln("[]").map(|()| ExitCode::SUCCESS)
        } else {
            outln(format!(
                "{}: no scenes to score (an empty array)",
                a.scene.display()
            ))
            .map(|()| ExitCode::SUCCESS)
        };
    }
    let evals: Vec<Evaluation> = scenes
        .iter()
        .map(|s| evaluate(s, &rules, a.contact))
        .collect();
    if a.require {
        let mut kept = true;
        for (i, e) in evals.iter().enumerate() {
            let label = if is_array {
                format!("{} [{i}]", a.scene.display())
            } else {
                a.scene.display().to_string()
            };
            let broken: Vec<String> = e
                .rules
                .iter()
                .filter(|r| r.satisfied < r.subjects)
                .map(|r| format!("{} ({})", r.name, r.violators.join(", ")))
                .collect();
            if broken.is_empty() {
                outln(format!("{label}: every rule holds for every object"))?;
            } else {
                kept = false;
                outln(format!("{label}: rules broken: {}", broken.join("; ")))?;
            }
        }
        return Ok(if kept {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        });
    }
    if a.json {
        let text = if is_array {
            serde_json::to_string_pretty(&evals)?
        } else {
            serde_json::to_string_pretty(&evals[0])?
        };
        outln(text)?;
        return Ok(ExitCode::SUCCESS);
    }
    for (i, e) in evals.iter().enumerate() {
        if i > 0 {
            outln("")?;
        }
        let label = if is_array {
            format!("{} [{i}]", a.scene.display())
        } else {
            a.scene.display().to_string()
        };
        out(table(&label, e))?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The human-readable report of one scene.
fn table(label: &str, e: &Evaluation) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{label}: score {:.6}  (weight {} / {})",
        e.score,
        trim(e.satisfied_weight),
        trim(e.total_weight)
    );
    if e.hard_violations > 0 {
        let _ = writeln!(
            s,
            "  hard rules broken: {} (object, rule) pairs",
            e.hard_violations
        );
    }
    if !e.off_grid.is_empty() {
        let _ = writeln!(s, "  off the grid: {}", e.off_grid.join(", "));
    }
    let w = e
        .rules
        .iter()
        .map(|r| r.name.len())
        .max()
        .unwrap_or(4)
        .max(4);
    let _ = writeln!(
        s,
        "  {:<w$}  {:>8}  {:>9}  broken by",
        "rule", "weight", "satisfied"
    );
    for r in &e.rules {
        let weight = if r.hard {
            "hard".to_string()
        } else {
            trim(r.weight)
        };
        let _ = writeln!(
            s,
            "  {:<w$}  {:>8}  {:>9}  {}",
            r.name,
            weight,
            format!("{}/{}", r.satisfied, r.subjects),
            r.violators.join(", ")
        );
    }
    s
}

fn trim(v: f64) -> String {
    let t = format!("{v:.4}");
    let t = t.trim_end_matches('0').trim_end_matches('.');
    t.to_string()
}
