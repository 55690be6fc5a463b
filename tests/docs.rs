//! Every shell example in the documentation runs, and prints what the page
//! says it prints.
//!
//! The pages are `README.md`, `CONTRIBUTING.md`, `docs/*.md` and the
//! bundled examples' `examples/*/README.md`. A fenced
//! block whose language is `console` is a session, in the syntax of
//! `trycmd` (which cargo and clap use for the same purpose):
//!
//! - `$ COMMAND` starts a command, `> MORE` continues it on the next line
//!   (joined with a space);
//! - `? CODE` (optional, right after the command) is the exit code it must
//!   end with (0 when absent);
//! - the lines up to the next `$` are its standard output and standard error
//!   together, where a line `...` stands for any number of lines and `[..]`
//!   inside a line for any text (timings, for example).
//!
//! The commands of one page run in order, through `sh`, in one scratch
//! folder that holds a copy of `examples/`, with the `rccpack` under test
//! first on `PATH` (`cargo run --release --` and `target/release/rccpack`
//! are read as that binary; `rccpack-bench`, from the bench crate, lies
//! beside it when `cargo test` runs at the root). A block marked `console ignore` is shown, not
//! run: installing software, and measurements that take minutes. A block
//! whose language is `rcc` must parse as a rule file (`rcc ignore`: shown
//! only, e.g. a file with an error on purpose). Shell
//! blocks in any other language (`sh`, `bash`, `shell`) are refused, so an
//! example cannot escape the test by its fence.
//!
//! Why not `trycmd` itself: it runs a page's commands in the folder of the
//! page, or in a copy of a `PAGE.in/` folder kept beside each page; these
//! pages run against the bundled examples, which would then be copied next
//! to every page. The format is trycmd's, so a reader who knows one knows
//! the other.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::support;

/// One command of a page, with what it must print and exit with.
#[derive(Debug)]
struct Step {
    line: usize,
    /// The 0-based index of the first line of the expected output.
    output_at: usize,
    command: String,
    code: i32,
    expected: Vec<String>,
}

/// The pages whose console blocks run.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![support::path("README.md"), support::path("CONTRIBUTING.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(support::path("docs"))
        .expect("read docs/")
        .map(|e| e.expect("a docs/ entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    for example in ["box-packing", "shelf"] {
        pages.push(support::path(&format!("examples/{example}/README.md")));
    }
    pages
}

/// The steps of a page's `console` blocks, in order; an error for a shell
/// block in another language or a malformed session.
fn steps(page: &str, text: &str) -> Result<Vec<Step>, String> {
    let mut steps = Vec::new();
    let mut fence: Option<(String, bool)> = None; // (info, runs)
    for (i, raw) in text.lines().enumerate() {
        let n = i + 1;
        let trimmed = raw.trim_start();
        if let Some(info) = trimmed.strip_prefix("```") {
            if fence.take().is_some() {
                continue;
            }
            let info = info.trim().to_string();
            let lang = info.split([' ', ',']).next().unwrap_or("");
            if matches!(lang, "sh" | "bash" | "shell" | "zsh") {
                return Err(format!(
                    "{page}:{n}: a `{lang}` block: write shell examples as `console` (run by \
                     tests/docs.rs) or `console ignore` (shown only)"
                ));
            }
            let runs = lang == "console" && !info.split([' ', ',']).any(|w| w == "ignore");
            fence = Some((info, runs));
            continue;
        }
        let Some((_, true)) = &fence else { continue };
        if let Some(cmd) = raw.strip_prefix("$ ") {
            steps.push(Step {
                line: n,
                output_at: n,
                command: cmd.to_string(),
                code: 0,
                expected: Vec::new(),
            });
        } else if let Some(more) = raw.strip_prefix("> ") {
            let step = steps
                .last_mut()
                .ok_or(format!("{page}:{n}: `>` before any `$`"))?;
            step.command.push(' ');
            step.command.push_str(more.trim_start());
            step.output_at = n;
        } else if let Some(code) = raw.strip_prefix("? ") {
            let step = steps
                .last_mut()
                .ok_or(format!("{page}:{n}: `?` before any `$`"))?;
            step.code = code
                .trim()
                .parse()
                .map_err(|_| format!("{page}:{n}: `? {code}`: expected an exit code"))?;
            step.output_at = n;
        } else {
            let step = steps.last_mut().ok_or(format!(
                "{page}:{n}: output before any `$` in a console block"
            ))?;
            step.expected.push(raw.to_string());
        }
    }
    Ok(steps)
}

/// Whether `line` matches `pattern`, where `[..]` stands for any text.
fn line_matches(pattern: &str, line: &str) -> bool {
    let mut parts = pattern.split("[..]");
    let first = parts.next().unwrap_or("");
    let Some(mut rest) = line.strip_prefix(first) else {
        return false;
    };
    let parts: Vec<&str> = parts.collect();
    for (k, part) in parts.iter().enumerate() {
        if k + 1 == parts.len() {
            return rest.ends_with(part);
        }
        match rest.find(part) {
            Some(at) => rest = &rest[at + part.len()..],
            None => return false,
        }
    }
    rest.is_empty()
}

/// Whether `lines` match `expected`, where a line `...` stands for any number
/// of lines (backtracking, so `...` may be followed by any pattern).
fn lines_match(expected: &[String], lines: &[&str]) -> bool {
    match expected.split_first() {
        None => lines.is_empty(),
        Some((first, rest)) if first.trim() == "..." => {
            (0..=lines.len()).any(|skip| lines_match(rest, &lines[skip..]))
        }
        Some((first, rest)) => match lines.split_first() {
            Some((line, more)) => {
                line_matches(first.trim_end(), line.trim_end()) && lines_match(rest, more)
            }
            None => false,
        },
    }
}

/// Read the documented spellings of the binaries as the binaries under
/// test (`rccpack-bench`, the bench crate's, lies beside `rccpack`).
fn as_binary(command: &str) -> String {
    command
        .replace("cargo run --release -p rccpack-bench -- ", "rccpack-bench ")
        .replace("target/release/rccpack-bench ", "rccpack-bench ")
        .replace("cargo run --release -- ", "rccpack ")
        .replace("target/release/rccpack ", "rccpack ")
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("create a folder");
    for entry in std::fs::read_dir(from).expect("read a folder") {
        let entry = entry.expect("a folder entry");
        let target = to.join(entry.file_name());
        if entry.file_type().expect("a file type").is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).expect("copy a file");
        }
    }
}

/// Whether the expected output of `step` elides anything (then it is never
/// rewritten by `RCCPACK_BLESS`).
fn elides(step: &Step) -> bool {
    step.expected
        .iter()
        .any(|l| l.trim() == "..." || l.contains("[..]"))
}

/// Rewrite the expected outputs of `fixes` (a step and what it printed) in
/// `text`, from the last to the first so that line indices stay valid.
fn bless(text: &str, mut fixes: Vec<(&Step, String)>) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    fixes.sort_by_key(|(step, _)| std::cmp::Reverse(step.output_at));
    for (step, printed) in fixes {
        let new: Vec<String> = printed.lines().map(|l| l.trim_end().to_string()).collect();
        let at = step.output_at;
        lines.splice(at..at + step.expected.len(), new);
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}

/// Run one page's sessions; the failures, each naming the page and line.
/// Under `RCCPACK_BLESS`, outputs without elisions are rewritten instead.
fn run_page(page: &Path, tag: &str) -> Vec<String> {
    let name = page
        .strip_prefix(support::root())
        .unwrap_or(page)
        .display()
        .to_string();
    let text = std::fs::read_to_string(page).unwrap_or_else(|e| panic!("read {name}: {e}"));
    let steps = match steps(&name, &text) {
        Ok(steps) => steps,
        Err(e) => return vec![e],
    };
    if steps.is_empty() {
        return Vec::new();
    }
    if steps
        .iter()
        .any(|s| as_binary(&s.command).contains("rccpack-bench"))
    {
        // Built by `cargo test` at the root (the bench crate is a default
        // member); fails naming it when it is missing.
        let _ = support::bench_command();
    }
    let dir = support::scratch(&format!("docs-{tag}"));
    copy_dir(&support::path("examples"), &dir.join("examples"));
    let bin_dir = Path::new(env!("CARGO_BIN_EXE_rccpack"))
        .parent()
        .expect("the binary's folder");
    let path = format!(
        "{}:{}",
        bin_dir.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let blessing = std::env::var_os("RCCPACK_BLESS").is_some();
    let mut failures = Vec::new();
    let mut fixes = Vec::new();
    for step in &steps {
        let mut cmd = Command::new("sh");
        cmd.arg("-c")
            .arg(format!("exec 2>&1\n{}", as_binary(&step.command)))
            .current_dir(&dir)
            .env("PATH", &path)
            .env("NO_COLOR", "1");
        for (key, _) in std::env::vars() {
            if key.starts_with("RCCPACK_") {
                cmd.env_remove(key);
            }
        }
        let out = cmd.output().expect("run sh");
        let printed = String::from_utf8_lossy(&out.stdout).into_owned();
        let lines: Vec<&str> = printed.lines().collect();
        let code = out.status.code().unwrap_or(-1);
        if code != step.code || !lines_match(&step.expected, &lines) {
            if blessing && code == step.code && !elides(step) {
                fixes.push((step, printed));
                continue;
            }
            failures.push(format!(
                "{name}:{}: `{}` exited {code} (expected {}) and printed:\n{printed}--- the page says:\n{}\n",
                step.line,
                step.command,
                step.code,
                step.expected.join("\n")
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    if !fixes.is_empty() {
        std::fs::write(page, bless(&text, fixes)).expect("rewrite a page");
    }
    failures
}

#[test]
fn every_console_example_in_the_docs_runs_as_shown() {
    let mut failures = Vec::new();
    let mut ran = 0;
    for (k, page) in pages().iter().enumerate() {
        let text = std::fs::read_to_string(page).unwrap_or_default();
        ran += steps("", &text).map(|s| s.len()).unwrap_or(0);
        failures.extend(run_page(page, &k.to_string()));
    }
    assert!(
        ran >= 10,
        "only {ran} documented commands found: is the parser broken?"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The `rcc` blocks of a page, each with its line: `(line, text)`.
fn rcc_blocks(text: &str) -> Vec<(usize, String)> {
    let mut blocks = Vec::new();
    let mut open: Option<(usize, String)> = None;
    let mut in_other = false;
    for (i, raw) in text.lines().enumerate() {
        if let Some(info) = raw.trim_start().strip_prefix("```") {
            if let Some(block) = open.take() {
                blocks.push(block);
            } else if in_other {
                in_other = false;
            } else if info.trim() == "rcc" {
                open = Some((i + 1, String::new()));
            } else {
                in_other = true;
            }
            continue;
        }
        if let Some((_, body)) = open.as_mut() {
            body.push_str(raw);
            body.push('\n');
        }
    }
    blocks
}

#[test]
fn every_rcc_example_in_the_docs_parses() {
    let mut failures = Vec::new();
    let mut parsed = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap_or_default();
        for (line, body) in rcc_blocks(&text) {
            parsed += 1;
            if let Err(e) = rccpack::parse_rules(&body) {
                failures.push(format!("{}:{line}: {e}", page.display()));
            }
        }
    }
    assert!(
        parsed >= 3,
        "only {parsed} rcc blocks found: is the scanner broken?"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_matcher_elides_as_documented() {
    let exp = |s: &str| s.lines().map(str::to_string).collect::<Vec<_>>();
    assert!(lines_match(
        &exp("a [..] c\n...\nz"),
        &["a b c", "x", "y", "z"]
    ));
    assert!(lines_match(&exp("...\nz"), &["z"]));
    assert!(!lines_match(&exp("a [..] c"), &["a b d"]));
    assert!(!lines_match(&exp("a"), &["a", "b"]));
    assert!(line_matches("in [..] ms", "in 3.2 ms"));
    assert!(!line_matches("in [..] ms", "in 3.2 s"));
    assert!(line_matches("[..]", "anything"));
    let s = steps(
        "p",
        "```console\n$ a\n> b\n? 2\nout\n```\n```console ignore\n$ c\n```\n",
    )
    .unwrap();
    assert_eq!(s.len(), 1);
    assert_eq!(
        (s[0].command.as_str(), s[0].code, s[0].expected.len()),
        ("a b", 2, 1)
    );
    assert!(steps("p", "```sh\nrccpack run\n```\n").is_err());
    let page = "x\n```console\n$ a\nold\nold2\n$ b\nkeep\n```\n";
    let s = steps("p", page).unwrap();
    let blessed = bless(page, vec![(&s[0], "new\n".to_string())]);
    assert_eq!(blessed, "x\n```console\n$ a\nnew\n$ b\nkeep\n```\n");
}
