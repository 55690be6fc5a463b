//! What ARCHITECTURE.md claims and a reader of the source can check: each
//! test reads files as text and fails naming the file and line that breaks
//! a claim, so the document cannot drift from the code.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `src/`, relative to the crate root, sorted.
fn sources() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in fs::read_dir(dir).expect("read src") {
            let p = entry.expect("entry").path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p.strip_prefix(root()).expect("under root").to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(&root().join("src"), &mut out);
    out.sort();
    out
}

/// The code lines of a file (comments and doc comments left out), with
/// their 1-based numbers.
fn code_lines(rel: &Path) -> Vec<(usize, String)> {
    let text = fs::read_to_string(root().join(rel)).expect("read source");
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim_start().starts_with("//"))
        .map(|(i, l)| (i + 1, l.to_string()))
        .collect()
}

fn unix(p: &Path) -> String {
    p.to_string_lossy().replace('\\', "/")
}

/// Places (file:line) where any of `needles` occurs in code outside the
/// files whose path starts with one of `allowed`.
fn occurrences(needles: &[&str], allowed: &[&str]) -> Vec<String> {
    let mut found = Vec::new();
    for f in sources() {
        let name = unix(&f);
        if allowed.iter().any(|a| name.starts_with(a)) {
            continue;
        }
        for (n, line) in code_lines(&f) {
            if needles.iter().any(|needle| line.contains(needle)) {
                found.push(format!("{name}:{n}: {}", line.trim()));
            }
        }
    }
    found
}

#[test]
fn only_the_engine_names_pumpkin() {
    let found = occurrences(&["pumpkin_"], &["src/synth/engine/"]);
    assert!(
        found.is_empty(),
        "Pumpkin named outside synth/engine/:\n{}",
        found.join("\n")
    );
}

/// Places in the files under `dir` whose code contains `needle`.
fn uses(dir: &str, needle: &str) -> Vec<String> {
    let mut found = Vec::new();
    for f in sources() {
        let name = unix(&f);
        if !name.starts_with(dir) {
            continue;
        }
        for (n, line) in code_lines(&f) {
            if line.contains(needle) {
                found.push(format!("{name}:{n}: {}", line.trim()));
            }
        }
    }
    found
}

#[test]
fn infer_and_synth_do_not_import_each_other() {
    let infer = uses("src/infer/", "crate::synth");
    assert!(infer.is_empty(), "infer uses synth:\n{}", infer.join("\n"));
    let synth = uses("src/synth/", "crate::infer");
    assert!(synth.is_empty(), "synth uses infer:\n{}", synth.join("\n"));
}

#[test]
fn nothing_below_learning_and_solving_knows_them() {
    let lower = [
        "src/scene.rs",
        "src/relations.rs",
        "src/rules",
        "src/eval.rs",
        "src/resemblance.rs",
        "src/limits.rs",
        "src/fsutil.rs",
    ];
    let upper = [
        "crate::infer",
        "crate::synth",
        "crate::ask",
        "crate::task",
        "crate::studio",
        "crate::bench",
        "crate::render",
    ];
    let found: Vec<String> = lower
        .iter()
        .flat_map(|l| upper.iter().flat_map(move |u| uses(l, u)))
        .collect();
    assert!(
        found.is_empty(),
        "a lower module uses a higher one:\n{}",
        found.join("\n")
    );
}

/// File I/O only where ARCHITECTURE.md's "The core does no file I/O" allows.
#[test]
fn file_io_only_in_the_allowed_modules() {
    let found = occurrences(
        &["std::fs", "fs::read", "fs::write", "File::", "OpenOptions"],
        &[
            "src/fsutil.rs",
            "src/task/",
            "src/priors/folder.rs",
            "src/studio/",
            "src/bench/",
            "src/fuzzing/",
            "src/cli/",
        ],
    );
    assert!(
        found.is_empty(),
        "file I/O outside the allow-list:\n{}",
        found.join("\n")
    );
    let writes = occurrences(
        &["fs::write", "File::create", "OpenOptions"],
        &["src/fsutil.rs", "src/fuzzing/"],
    );
    assert!(
        writes.is_empty(),
        "a write that bypasses fsutil::atomic_write:\n{}",
        writes.join("\n")
    );
}

#[test]
fn processes_only_where_allowed() {
    let found = occurrences(
        &["std::process::Command", "Command::new", "process::exit"],
        &[
            "src/bench/peers.rs",
            "src/bench/chart.rs",
            "src/bench/sample/diversity.rs",
            "src/cli/",
            "src/main.rs",
        ],
    );
    assert!(
        found.is_empty(),
        "a process started outside the allow-list:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_library_never_prints() {
    let found = occurrences(
        &["println!", "eprintln!", "print!(", "eprint!(", "dbg!("],
        // The fuzz harnesses print a failing input under RCCPACK_FUZZ_DEBUG.
        &["src/cli/", "src/main.rs", "src/fuzzing/"],
    );
    assert!(
        found.is_empty(),
        "the library prints:\n{}",
        found.join("\n")
    );
}

/// `[dependencies]` of Cargo.toml, as crate names (`-` → `_`).
fn dependencies() -> Vec<String> {
    let toml = fs::read_to_string(root().join("Cargo.toml")).expect("Cargo.toml");
    let mut deps = Vec::new();
    let mut inside = false;
    for line in toml.lines() {
        let t = line.trim();
        if t.starts_with('[') {
            inside = t == "[dependencies]" || t == "[target.'cfg(unix)'.dependencies]";
            continue;
        }
        if inside && !t.starts_with('#') {
            if let Some((name, _)) = t.split_once('=') {
                deps.push(name.trim().replace('-', "_"));
            }
        }
    }
    deps
}

#[test]
fn every_dependency_is_used() {
    let all: String = sources()
        .iter()
        .map(|f| fs::read_to_string(root().join(f)).expect("read"))
        .collect();
    let unused: Vec<String> = dependencies()
        .into_iter()
        .filter(|d| !(all.contains(&format!("{d}::")) || all.contains(&format!("use {d}"))))
        .collect();
    assert!(
        unused.is_empty(),
        "dependencies no source file uses: {unused:?}"
    );
}

#[test]
fn every_dependency_is_explained_in_architecture_md() {
    let doc = fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let section = doc
        .split("## Dependencies and why")
        .nth(1)
        .expect("a dependencies section");
    let missing: Vec<String> = dependencies()
        .into_iter()
        .filter(|d| !section.replace('-', "_").contains(d.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "dependencies ARCHITECTURE.md does not explain: {missing:?}"
    );
}

/// Every public module of the crate root is in lib.rs's guide, and every
/// file under `src/` in ARCHITECTURE.md's code map.
#[test]
fn every_module_is_documented() {
    let lib = fs::read_to_string(root().join("src/lib.rs")).expect("lib.rs");
    let guide: String = lib
        .lines()
        .filter(|l| l.starts_with("//!"))
        .collect::<Vec<_>>()
        .join("\n");
    let modules: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod "))
        .map(|m| m.trim_end_matches(';'))
        .collect();
    assert!(modules.len() >= 10, "found {modules:?}");
    let hidden = ["fuzzing"];
    let missing: Vec<&&str> = modules
        .iter()
        .filter(|m| {
            !hidden.contains(m)
                && !guide.contains(&format!("[`{m}`]"))
                && !guide.contains(&format!("[`mod@{m}`]"))
                && !guide.contains(&format!("`{m}` (feature"))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "public modules missing from lib.rs's guide: {missing:?}"
    );

    let arch = fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let map = arch
        .split("## Code map")
        .nth(1)
        .expect("code map")
        .split("\n## ")
        .next()
        .expect("map");
    let files: BTreeSet<String> = sources().iter().map(|f| unix(f)).collect();
    let missing: Vec<&String> = files
        .iter()
        .filter(|f| {
            let file = Path::new(f.as_str())
                .file_name()
                .expect("name")
                .to_string_lossy()
                .to_string();
            let dir = Path::new(f.as_str()).parent().map(unix).unwrap_or_default();
            !(map.contains(f.as_str())
                || (map.contains(&format!("`{dir}/`")) && map.contains(&format!("`{file}`"))))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "source files missing from ARCHITECTURE.md's code map: {missing:?}"
    );
}

/// With `autotests = false`, a test file not declared in
/// `tests/integration.rs` would silently never run.
#[test]
fn every_test_file_is_in_the_integration_binary() {
    let main = fs::read_to_string(root().join("tests/integration.rs")).expect("integration.rs");
    let mut missing = Vec::new();
    for entry in fs::read_dir(root().join("tests")).expect("tests/") {
        let p = entry.expect("entry").path();
        let Some(stem) = p.file_stem().map(|s| s.to_string_lossy().to_string()) else {
            continue;
        };
        if p.extension().is_some_and(|e| e == "rs")
            && stem != "integration"
            && !main.contains(&format!("mod {stem};"))
        {
            missing.push(stem);
        }
    }
    assert!(
        missing.is_empty(),
        "test files tests/integration.rs does not declare: {missing:?}"
    );
}
