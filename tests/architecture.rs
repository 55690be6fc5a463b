//! What ARCHITECTURE.md claims and a reader of the source can check: each
//! test reads files as text and fails naming the file and line that breaks
//! a claim, so the document cannot drift from the code.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under the folder `dir` of the crate root, relative to
/// the root, sorted.
fn rust_files_under(dir: &str) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in fs::read_dir(dir).unwrap_or_else(|e| panic!("read {}: {e}", dir.display())) {
            let p = entry.expect("entry").path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p.strip_prefix(root()).expect("under root").to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(&root().join(dir), &mut out);
    out.sort();
    out
}

/// Every `.rs` file under `src/`, relative to the crate root, sorted.
fn sources() -> Vec<PathBuf> {
    rust_files_under("src")
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
        "src/stop.rs",
    ];
    let upper = [
        "crate::infer",
        "crate::synth",
        "crate::ask",
        "crate::task",
        "crate::studio",
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
            "src/studio/",
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
        &["src/cli/", "src/main.rs"],
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

/// The library's behaviour is a function of its arguments: no hidden
/// switch in the environment. Engine tuning is `synth::Tuning`, filled
/// from `RCCPACK_*` variables by the command line only (`from_env` is
/// where it reads them).
#[test]
fn the_library_never_reads_the_environment() {
    let found = occurrences(
        &["env::var", "env::vars"],
        &[
            "src/cli/",
            "src/main.rs",
            "src/fuzzing/",
            "src/synth/tuning.rs",
        ],
    );
    assert!(
        found.is_empty(),
        "the library reads the environment:\n{}",
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
    // One section per room (`### `src/room/``); a file is named in its
    // room's section, by its path or by its name beside its folder's path.
    let sections: Vec<&str> = map.split("\n### ").skip(1).collect();
    let files: BTreeSet<String> = sources().iter().map(|f| unix(f)).collect();
    let missing: Vec<&String> = files
        .iter()
        .filter(|f| {
            let first = f
                .trim_start_matches("src/")
                .split('/')
                .next()
                .unwrap_or_default()
                .trim_end_matches(".rs");
            let Some(section) = sections.iter().find(|s| {
                let heading = s.lines().next().unwrap_or_default();
                heading.contains(&format!("`src/{first}/`"))
                    || heading.contains(&format!("`src/{first}.rs`"))
            }) else {
                return true;
            };
            let file = Path::new(f.as_str())
                .file_name()
                .expect("name")
                .to_string_lossy()
                .to_string();
            let dir = Path::new(f.as_str()).parent().map(unix).unwrap_or_default();
            !(section.contains(f.as_str())
                || (section.contains(&format!("`{dir}/`"))
                    && section.contains(&format!("`{file}`"))))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "source files missing from their room's section of ARCHITECTURE.md's code map: {missing:?}"
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

fn architecture_md() -> String {
    fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md")
}

/// The names in backticks in `text`.
fn quoted(text: &str) -> Vec<&str> {
    text.split('`').skip(1).step_by(2).collect()
}

/// The public enums named `…Error` in `src/` and the bench library marked
/// `#[non_exhaustive]` are exactly those the invariant "Library errors are
/// typed" lists.
#[test]
fn the_non_exhaustive_error_enums_are_those_listed() {
    let mut marked = BTreeSet::new();
    for f in sources().into_iter().chain(bench_library_sources()) {
        let lines = code_lines(&f);
        for (i, (_, line)) in lines.iter().enumerate() {
            let Some(rest) = line.trim().strip_prefix("pub enum ") else {
                continue;
            };
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            // The attributes right above the enum.
            let attributes = lines[..i]
                .iter()
                .rev()
                .take_while(|(_, l)| l.trim().starts_with("#["));
            if name.ends_with("Error")
                && attributes
                    .into_iter()
                    .any(|(_, l)| l.trim() == "#[non_exhaustive]")
            {
                marked.insert(name);
            }
        }
    }
    let doc = architecture_md();
    let claim = doc
        .split("The error enums that are `#[non_exhaustive]`")
        .nth(1)
        .expect("ARCHITECTURE.md lists the #[non_exhaustive] error enums")
        .split("(checked)")
        .next()
        .expect("the list ends with (checked)");
    let listed: BTreeSet<String> = quoted(claim).into_iter().map(String::from).collect();
    let unlisted: Vec<&String> = marked.difference(&listed).collect();
    let unmarked: Vec<&String> = listed.difference(&marked).collect();
    assert!(
        unlisted.is_empty() && unmarked.is_empty(),
        "#[non_exhaustive] in src/ but not listed in ARCHITECTURE.md: {unlisted:?}; \
         listed but not #[non_exhaustive] in src/: {unmarked:?}"
    );
}

/// One row of ARCHITECTURE.md's layer table: the room's layer (0 at the
/// bottom) and the rooms it may use (`None`: any below it, "library API"
/// or "everything").
#[derive(Debug, Clone)]
struct Room {
    layer: u32,
    may_use: Option<BTreeSet<String>>,
}

/// The rows of the table under `## Layers` (`| layer | room | may use |`):
/// module → its [`Room`].
fn layer_table() -> BTreeMap<String, Room> {
    let doc = architecture_md();
    let section = doc
        .split("\n## Layers")
        .nth(1)
        .expect("ARCHITECTURE.md has a `## Layers` section")
        .split("\n## ")
        .next()
        .expect("the section");
    let mut table = BTreeMap::new();
    for line in section.lines() {
        let cells: Vec<&str> = line.split(" | ").collect();
        if cells.len() < 3 || !line.starts_with("| ") {
            continue;
        }
        let Ok(layer) = cells[0].trim_start_matches("| ").trim().parse::<u32>() else {
            continue;
        };
        let may = cells[cells.len() - 1].trim_end_matches('|').trim();
        let may_use = if may.contains("library API") || may.contains("everything") {
            None
        } else {
            Some(
                quoted(may)
                    .into_iter()
                    .map(|m| m.split("::").next().unwrap_or(m).to_string())
                    .collect(),
            )
        };
        for path in quoted(cells[1]) {
            if let Some(module) = module_of(path) {
                table.insert(
                    module,
                    Room {
                        layer,
                        may_use: may_use.clone(),
                    },
                );
            }
        }
    }
    table
}

/// The layer table's "may use" column: module → the modules it may use
/// (`None`: any below it).
fn may_use_table() -> BTreeMap<String, Option<BTreeSet<String>>> {
    layer_table()
        .into_iter()
        .map(|(module, room)| (module, room.may_use))
        .collect()
}

/// The arrows between rooms the code draws: (from, to) → the first
/// `file:line` naming `to` in `from` (test modules left out).
fn room_arrows() -> BTreeMap<(String, String), String> {
    let modules: BTreeSet<String> = sources()
        .iter()
        .filter_map(|f| module_of(&unix(f)))
        .collect();
    let mut arrows = BTreeMap::new();
    for f in sources() {
        let name = unix(&f);
        let Some(module) = module_of(&name) else {
            continue;
        };
        for (other, line) in crate_references(&f) {
            if other != module && modules.contains(&other) {
                arrows
                    .entry((module.clone(), other))
                    .or_insert(format!("{name}:{line}"));
            }
        }
    }
    arrows
}

/// The arrows that do not point to a lower layer (the same layer counts
/// as running back: rooms beside each other do not use each other), and
/// the rooms with no layer.
fn back_arrows(
    arrows: &BTreeMap<(String, String), String>,
    layers: &BTreeMap<String, u32>,
) -> Vec<String> {
    let mut wrong = Vec::new();
    for ((from, to), at) in arrows {
        match (layers.get(from), layers.get(to)) {
            (Some(a), Some(b)) if b < a => {}
            (Some(a), Some(b)) => wrong.push(format!(
                "{at}: `{from}` (layer {a}) uses `{to}` (layer {b}), which is not below it"
            )),
            _ => wrong.push(format!("{at}: `{from}` → `{to}`: a room with no layer")),
        }
    }
    wrong
}

/// The circles of a graph: one closed path (`a → b → … → a`) per group of
/// rooms that reach each other, found by depth-first search.
fn circles(arrows: &BTreeMap<(String, String), String>) -> Vec<Vec<String>> {
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (from, to) in arrows.keys() {
        next.entry(from.as_str()).or_default().push(to.as_str());
        next.entry(to.as_str()).or_default();
    }
    // Reachability by search from every room (the graph is small).
    let reach = |start: &str| -> BTreeSet<&str> {
        let mut seen = BTreeSet::new();
        let mut todo = vec![start];
        while let Some(v) = todo.pop() {
            for &w in &next[v] {
                if seen.insert(w) {
                    todo.push(w);
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<&str, BTreeSet<&str>> = next.keys().map(|&v| (v, reach(v))).collect();
    let mut done: BTreeSet<&str> = BTreeSet::new();
    let mut found = Vec::new();
    for &v in next.keys() {
        if done.contains(v) || !reachable[v].contains(v) {
            continue;
        }
        let group: BTreeSet<&str> = reachable[v]
            .iter()
            .copied()
            .filter(|w| reachable[w].contains(v))
            .collect();
        done.extend(group.iter().copied());
        // A shortest closed path through `v`, by breadth-first search.
        let mut parent: BTreeMap<&str, &str> = BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([v]);
        'search: while let Some(u) = queue.pop_front() {
            for &w in &next[u] {
                if w == v {
                    let mut path = vec![u.to_string()];
                    let mut x = u;
                    while x != v {
                        x = parent[x];
                        path.push(x.to_string());
                    }
                    path.reverse();
                    path.push(v.to_string());
                    found.push(path);
                    break 'search;
                }
                if group.contains(w) && !parent.contains_key(w) && w != v {
                    parent.insert(w, u);
                    queue.push_back(w);
                }
            }
        }
    }
    found
}

/// The top-level module of a path under `src/` (`src/rules/check.rs` →
/// `rules`, `src/scene.rs` → `scene`); `None` for the crate root and the
/// binary (`lib.rs`, `main.rs`, `cli/`), which are no library module.
fn module_of(path: &str) -> Option<String> {
    let rest = path.strip_prefix("src/")?;
    let first = rest.split('/').next()?.trim_end_matches(".rs");
    (!["lib", "main", "cli", ""].contains(&first)).then(|| first.to_string())
}

/// The top-level modules a file names through `crate::` (single paths and
/// `crate::{…}` groups, over several lines too), outside its test module,
/// with the line of the first mention.
fn crate_references(rel: &Path) -> BTreeMap<String, usize> {
    let mut code = String::new();
    let mut numbers = Vec::new();
    for (n, line) in code_lines(rel) {
        if line.starts_with("#[cfg(test)]") {
            break;
        }
        // A trailing comment is no reference.
        let line = line.split(" // ").next().unwrap_or_default();
        code.push_str(line);
        code.push('\n');
        numbers.resize(code.len(), n);
    }
    let mut found = BTreeMap::new();
    let mut note = |name: &str, at: usize| {
        let name = name.trim();
        if !name.is_empty() && name.chars().all(|c| c.is_alphanumeric() || c == '_') {
            found.entry(name.to_string()).or_insert(numbers[at]);
        }
    };
    for (at, _) in code.match_indices("crate::") {
        if at > 0 && code[..at].ends_with('$') {
            continue;
        }
        let rest = &code[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // Top-level items of the group: split at commas outside braces.
            let mut depth = 0;
            let mut item = String::new();
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        note(item.split("::").next().unwrap_or_default(), at);
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                item.push(c);
            }
            note(item.split("::").next().unwrap_or_default(), at);
        } else {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            note(&name, at);
        }
    }
    found
}

/// Every `crate::` reference in a library module is an edge the code
/// map's "may use" column allows; the check is per module, so new files
/// under an existing module need no change here.
#[test]
fn modules_use_only_what_the_code_map_allows() {
    let table = may_use_table();
    assert!(table.len() >= 15, "code map rows found: {table:?}");
    let modules: BTreeSet<String> = sources()
        .iter()
        .filter_map(|f| module_of(&unix(f)))
        .collect();
    let mut wrong = Vec::new();
    for f in sources() {
        let name = unix(&f);
        let Some(module) = module_of(&name) else {
            continue;
        };
        let Some(allowed) = table.get(&module) else {
            wrong.push(format!(
                "{name}: module `{module}` has no row in the code map"
            ));
            continue;
        };
        let Some(allowed) = allowed else {
            continue;
        };
        for (other, line) in crate_references(&f) {
            if other != module && modules.contains(&other) && !allowed.contains(&other) {
                wrong.push(format!(
                    "{name}:{line}: `{module}` uses `{other}`, not in its \"may use\" column"
                ));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "ARCHITECTURE.md's code map does not allow:\n{}",
        wrong.join("\n")
    );
}

/// Every file of `tests/` (and of `tests/support/`) is named in the code
/// map's `tests/` row.
#[test]
fn every_test_file_is_in_the_test_map() {
    let doc = architecture_md();
    let row = doc
        .lines()
        .find(|l| l.starts_with("| `tests/` |"))
        .expect("a tests/ row in the code map");
    let named: BTreeSet<&str> = quoted(row).into_iter().collect();
    let mut missing = Vec::new();
    for dir in ["tests", "tests/support"] {
        for entry in fs::read_dir(root().join(dir)).expect("read tests/") {
            let p = entry.expect("entry").path();
            let file = p.file_name().expect("name").to_string_lossy().to_string();
            if p.extension().is_some_and(|e| e == "rs")
                && file != "integration.rs"
                && !named.contains(file.as_str())
            {
                missing.push(format!("{dir}/{file}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "test files missing from ARCHITECTURE.md's tests/ row: {missing:?}"
    );
}

/// Tests ignored because they need a tool (`#[ignore = "needs …"]`) are
/// run by `.ci/run` by their full names, so CI cannot pass without them.
#[test]
fn tests_that_need_a_tool_run_in_ci() {
    let ci = fs::read_to_string(root().join(".ci/run")).expect(".ci/run");
    let mut missing = Vec::new();
    let mut found = 0;
    for entry in fs::read_dir(root().join("tests")).expect("read tests/") {
        let p = entry.expect("entry").path();
        if p.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        let stem = p.file_stem().expect("stem").to_string_lossy().to_string();
        let text = fs::read_to_string(&p).expect("read a test file");
        let mut needs = false;
        for line in text.lines() {
            let t = line.trim();
            if t.starts_with("#[ignore = \"needs ") {
                needs = true;
            } else if let Some(rest) = t.strip_prefix("fn ").filter(|_| needs) {
                needs = false;
                found += 1;
                let name = rest.split('(').next().unwrap_or_default();
                let full = format!("{stem}::{name}");
                if !ci.split_whitespace().any(|w| w == full) {
                    missing.push(full);
                }
            }
        }
    }
    assert!(found >= 4, "found {found} tests that need a tool");
    assert!(
        missing.is_empty(),
        ".ci/run does not run these ignored tests by name: {missing:?}"
    );
}

fn arrows_of(list: &[(&str, &str)]) -> BTreeMap<(String, String), String> {
    list.iter()
        .map(|(a, b)| ((a.to_string(), b.to_string()), format!("{a}.rs:1")))
        .collect()
}

/// The two checks below find what they are for on a made-up graph.
#[test]
fn the_layer_checks_find_back_arrows_and_circles() {
    let arrows = arrows_of(&[
        ("task", "priors"),
        ("priors", "task"),
        ("infer", "priors"),
        ("priors", "infer"),
        ("task", "infer"),
        ("infer", "scene"),
    ]);
    let layers: BTreeMap<String, u32> = [("scene", 0), ("infer", 1), ("priors", 2), ("task", 3)]
        .into_iter()
        .map(|(m, l)| (m.to_string(), l))
        .collect();
    assert_eq!(
        back_arrows(&arrows, &layers),
        [
            "infer.rs:1: `infer` (layer 1) uses `priors` (layer 2), which is not below it",
            "priors.rs:1: `priors` (layer 2) uses `task` (layer 3), which is not below it",
        ]
    );
    assert_eq!(
        circles(&arrows),
        [vec!["infer", "priors", "infer"]],
        "one group of rooms that reach each other, one closed path"
    );
    let beside = arrows_of(&[("infer", "synth")]);
    let same: BTreeMap<String, u32> = [("infer", 1), ("synth", 1)]
        .into_iter()
        .map(|(m, l)| (m.to_string(), l))
        .collect();
    assert_eq!(
        back_arrows(&beside, &same).len(),
        1,
        "rooms beside each other"
    );
    assert!(circles(&arrows_of(&[("a", "b"), ("b", "c"), ("a", "c")])).is_empty());
    let three = circles(&arrows_of(&[
        ("a", "b"),
        ("b", "c"),
        ("c", "a"),
        ("c", "d"),
    ]));
    assert_eq!(three, [vec!["a", "b", "c", "a"]]);
}

/// Every arrow between rooms points down ARCHITECTURE.md's layer table,
/// the rooms' graph has no circle, and the table's own "may use" column
/// names only rooms below each row. Run with `--nocapture` for the counts.
#[test]
fn rooms_use_only_rooms_below_them_and_form_no_circle() {
    let table = layer_table();
    assert!(table.len() >= 15, "layer table rows found: {table:?}");
    let layers: BTreeMap<String, u32> = table.iter().map(|(m, r)| (m.clone(), r.layer)).collect();
    let arrows = room_arrows();
    let back = back_arrows(&arrows, &layers);
    let found = circles(&arrows);
    eprintln!(
        "rooms {}, arrows {}, arrows running back up {}, circles {}",
        layers.len(),
        arrows.len(),
        back.len(),
        found.len()
    );
    assert!(
        back.is_empty(),
        "arrows that do not point down ARCHITECTURE.md's layer table:\n{}",
        back.join("\n")
    );
    assert!(
        found.is_empty(),
        "circles between rooms: {}",
        found
            .iter()
            .map(|c| c.join(" → "))
            .collect::<Vec<_>>()
            .join("; ")
    );
    let mut wrong = Vec::new();
    for (module, room) in &table {
        for other in room.may_use.iter().flatten() {
            match layers.get(other) {
                Some(l) if *l < room.layer => {}
                Some(l) => wrong.push(format!(
                    "`{module}` (layer {}) may use `{other}` (layer {l})",
                    room.layer
                )),
                None => wrong.push(format!("`{module}` may use `{other}`, which has no row")),
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "the layer table's \"may use\" column names a room not below the row:\n{}",
        wrong.join("\n")
    );
}

/// The `.rs` files of the bench crate's library (`bench/src/` without the
/// binary's `main.rs` and `cli/`), relative to the repository root.
fn bench_library_sources() -> Vec<PathBuf> {
    let mut out = rust_files_under("bench/src");
    out.retain(|f| {
        let name = unix(f);
        name != "bench/src/main.rs" && !name.starts_with("bench/src/cli/")
    });
    out
}

/// "The library never depends on the bench crate": no file of `src/`
/// names it, and the root package lists it only as a dev-dependency.
#[test]
fn the_library_never_depends_on_the_bench_crate() {
    let found = occurrences(&["rccpack_bench", "rccpack-bench ="], &[]);
    assert!(
        found.is_empty(),
        "the library names the bench crate:\n{}",
        found.join("\n")
    );
    assert!(
        !dependencies().iter().any(|d| d == "rccpack_bench"),
        "rccpack-bench is a [dependencies] entry of Cargo.toml (only a dev-dependency may be)"
    );
    let toml = fs::read_to_string(root().join("Cargo.toml")).expect("Cargo.toml");
    assert!(
        !toml.contains("plotters") && !toml.contains("indicatif"),
        "the root package depends on the bench crate's chart or progress crates"
    );
}

/// The bench library starts processes only for the peers, and never
/// prints (its binary, `bench/src/cli/`, does).
#[test]
fn the_bench_library_starts_peers_only_and_never_prints() {
    let sources = bench_library_sources();
    assert!(sources.len() >= 20, "found {sources:?}");
    let mut found = Vec::new();
    for f in &sources {
        let name = unix(f);
        let peers = name == "bench/src/peers.rs" || name == "bench/src/sample/diversity.rs";
        for (n, line) in code_lines(f) {
            let process = ["std::process::Command", "Command::new", "process::exit"]
                .iter()
                .any(|x| line.contains(x));
            let prints = ["println!", "eprintln!", "print!(", "eprint!(", "dbg!("]
                .iter()
                .any(|x| line.contains(x));
            if (process && !peers) || prints {
                found.push(format!("{name}:{n}: {}", line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "the bench library starts a process outside the peers, or prints:\n{}",
        found.join("\n")
    );
}
