//! `rccpack priors TASK_DIR... -o PRIORS.json`: priors per kind of
//! statement from a library of finished task folders, and the
//! `--priors FILE` reader of `learn`, `run`, `ask` and the studio.

use super::{read_text_at_most, write_file, Reported};
use anyhow::Result;
use clap::Args;
use rccpack::infer::Templates;
use rccpack::priors::{PriorParams, Priors};
use rccpack::relations::Contact;
use rccpack::task::files;
use rccpack::task::library::{self, LibraryError};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `rccpack priors DIR... [-o PRIORS.json] [--threads N]`
#[derive(Args, Debug)]
pub struct PriorsArgs {
    /// Task folders, each with `demos.json` and `learned.rcc` (the rules
    /// the person kept; `# confirmed` marks count twice). A single file
    /// `@LIST` names one folder per line.
    #[arg(required = true)]
    dirs: Vec<PathBuf>,
    /// Write the priors here (default: standard output).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Shrinkage strength: pseudo-candidates of the parent kind, at least 1.
    #[arg(long, default_value_t = PriorParams::default().strength, allow_hyphen_values = true)]
    strength: u32,
    /// Rule a kind out after this many tasks in which it was a candidate
    /// and never kept (0: never).
    #[arg(long, default_value_t = PriorParams::default().rule_out_after, allow_hyphen_values = true)]
    rule_out_after: u64,
    /// The template set whose candidates are counted.
    #[arg(long, default_value_t = PriorParams::default().templates, value_name = "first|second|third")]
    templates: Templates,
    /// How EC decides that two sides touch: `point` or `edge`.
    #[arg(long, default_value_t = PriorParams::default().contact)]
    contact: Contact,
    /// Threads (default: every core). The output is the same for any number.
    #[arg(long, allow_hyphen_values = true)]
    threads: Option<usize>,
}

fn expand(dirs: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for d in dirs {
        match d.to_str().and_then(|s| s.strip_prefix('@')) {
            Some(list) => {
                let text = read_text_at_most(Path::new(list), rccpack::limits::MAX_LIST_BYTES)?;
                out.extend(
                    text.lines()
                        .map(str::trim)
                        .filter(|l| !l.is_empty())
                        .map(PathBuf::from),
                );
            }
            None => out.push(d.clone()),
        }
    }
    Ok(out)
}

/// Each folder once, by its canonical path (`T T`, `T ./T/` or a repeated
/// `@LIST` line would count a task twice); a note on stderr names each
/// folder dropped as a repeat. A folder that cannot be resolved is kept as
/// given (reading it reports the error).
fn once_each(dirs: Vec<PathBuf>) -> Vec<PathBuf> {
    let mut seen: std::collections::HashMap<PathBuf, PathBuf> = std::collections::HashMap::new();
    let mut out = Vec::new();
    for d in dirs {
        let key = std::fs::canonicalize(&d).unwrap_or_else(|_| d.clone());
        match seen.get(&key) {
            Some(first) => ewriteln!(
                "note: task folder {} is the same folder as {}; counted once",
                d.display(),
                first.display()
            ),
            None => {
                seen.insert(key, d.clone());
                out.push(d);
            }
        }
    }
    out
}

pub fn run(a: PriorsArgs) -> Result<ExitCode> {
    if a.strength == 0 {
        return Err(Reported(
            "error: --strength is 0; expected a whole number of at least 1".into(),
        )
        .into());
    }
    if a.threads == Some(0) {
        return Err(Reported(
            "error: --threads is 0; expected a whole number of at least 1".into(),
        )
        .into());
    }
    // Outputs are never inputs: `-o` naming the `@LIST` file is refused
    // before it is read, and naming a task's file before any is read.
    let lists: Vec<&Path> = a
        .dirs
        .iter()
        .filter_map(|d| d.to_str()?.strip_prefix('@').map(Path::new))
        .collect();
    let output = [("-o", a.output.as_deref())];
    super::guard_outputs(&lists, &output, &[])?;
    let dirs = once_each(expand(&a.dirs)?);
    let task_files: Vec<PathBuf> = dirs
        .iter()
        .flat_map(|d| [d.join(files::DEMOS), d.join(files::LEARNED)])
        .collect();
    let task_files: Vec<&Path> = task_files.iter().map(PathBuf::as_path).collect();
    super::guard_outputs(&task_files, &output, &[])?;
    let params = PriorParams {
        strength: a.strength,
        rule_out_after: a.rule_out_after,
        templates: a.templates,
        contact: a.contact,
    };
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = a.threads {
        pool = pool.num_threads(n);
    }
    let pool = pool
        .build()
        .map_err(|e| Reported(format!("error: cannot start the threads: {e}")))?;
    let priors = pool
        .install(|| library::library(&dirs, &params))
        .map_err(|e| Reported(priors_error_text(&e)))?;
    let text = priors.to_json();
    match &a.output {
        Some(p) => {
            write_file(p, &text, "priors")?;
            if std::io::stderr().is_terminal() {
                ewriteln!(
                    "wrote {} ({} tasks, {} kinds)",
                    p.display(),
                    priors.tasks,
                    priors.kinds.len()
                );
            }
        }
        None => super::out(&text)?,
    }
    Ok(ExitCode::SUCCESS)
}

fn priors_error_text(e: &LibraryError) -> String {
    format!(
        "error: task {}: {}",
        e.dir.display(),
        super::task_error_text(&e.source)
    )
}

/// Read `--priors FILE`; errors name the file and the field.
pub fn read_priors(path: &Path) -> Result<Priors> {
    let text = read_text_at_most(path, rccpack::limits::MAX_PRIORS_BYTES)?;
    Priors::from_json(&text).map_err(|e| Reported(format!("error: {}: {e}", path.display())).into())
}

/// Read an optional `--priors FILE`.
pub fn read_priors_opt(path: Option<&Path>) -> Result<Option<Priors>> {
    path.map(read_priors).transpose()
}
