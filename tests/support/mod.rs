//! What the integration tests (and the benchmarks, through `#[path]`)
//! share: running the built binary, reading its output, fresh folders and
//! files, the bundled examples, a median; `formulas` builds atoms and random
//! formulas, `cases` the random problems of the differential tests,
//! `box_packing` the box-packing problem and its pilot rules.

#![allow(dead_code)] // each test module uses part of it

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The crate root (where `examples/` and `tests/fixtures/` are).
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A path inside the crate.
pub fn path(rel: &str) -> PathBuf {
    root().join(rel)
}

/// Run the `rccpack` binary with `args` in the crate root.
pub fn rccpack(args: &[&str]) -> Output {
    rccpack_in(root(), args)
}

/// A command running the built `rccpack` binary: the root package's tests
/// know its path; the bench crate's (`bench/tests/`) find it beside their
/// own executable, where a `cargo test` at the root builds it.
pub fn command() -> Command {
    Command::new(built_binary(
        option_env!("CARGO_BIN_EXE_rccpack"),
        "rccpack",
    ))
}

/// A command running the built `rccpack-bench` binary (the bench crate's
/// tests only).
pub fn bench_command() -> Command {
    Command::new(built_binary(
        option_env!("CARGO_BIN_EXE_rccpack-bench"),
        "rccpack-bench",
    ))
}

/// The path cargo gave for a binary of this package, else `name` in the
/// target folder of the running test (`target/debug/deps/..`); fails
/// naming the binary when it is not built.
fn built_binary(known: Option<&str>, name: &str) -> PathBuf {
    if let Some(p) = known {
        return PathBuf::from(p);
    }
    let exe = std::env::current_exe().expect("the test's own path");
    let dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("a test runs from target/<profile>/deps");
    let p = dir.join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    assert!(
        p.is_file(),
        "{}: the {name} binary is not built; run `cargo test` at the repository root",
        p.display()
    );
    p
}

/// Run the `rccpack` binary with `args` in `dir`.
pub fn rccpack_in(dir: &Path, args: &[&str]) -> Output {
    command()
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run rccpack")
}

/// Standard output, lossily decoded.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Standard error, lossily decoded.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh, empty folder for one test (`tag` must be unique among tests).
pub fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rccpack-test-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("create a scratch folder");
    d
}

/// A file `name` holding `text` in `dir`; its path as text, as the
/// command line takes it.
pub fn write_file(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    p.to_str().expect("a UTF-8 temporary path").to_string()
}

/// A file of the crate (`rel` from the crate root) as text.
pub fn read(rel: impl AsRef<Path>) -> String {
    let p = root().join(rel);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// A bundled example's folder (`examples/<name>`).
pub fn example(name: &str) -> PathBuf {
    root().join("examples").join(name)
}

/// A fresh folder `tag` (as [`scratch`]) holding a copy of `files` of the
/// bundled example `name`.
pub fn example_copy(tag: &str, name: &str, files: &[&str]) -> PathBuf {
    let dir = scratch(tag);
    for f in files {
        std::fs::copy(example(name).join(f), dir.join(f)).expect("copy an example file");
    }
    dir
}

/// A `w`×`h` table at the origin, grid 10, holding `objects`.
pub fn table(w: i64, h: i64, objects: Vec<rccpack::scene::Object>) -> rccpack::scene::Scene {
    rccpack::scene::Scene {
        space: rccpack::scene::Space {
            x: 0,
            y: 0,
            width: w,
            height: h,
        },
        grid: 10,
        objects,
    }
}

/// Whether `o` overlaps (interiors) a placed object of `objects`.
pub fn overlaps_any(objects: &[rccpack::scene::Object], o: &rccpack::scene::Object) -> bool {
    objects.iter().any(|p| match (p.rect(), o.rect()) {
        (Some(a), Some(b)) => a.interiors_overlap(&b),
        _ => false,
    })
}

/// Fails, naming what is missing, unless `peer` can run: a peer test is
/// `#[ignore]`d, and one that is run must run.
pub fn require_peer(peer: rccpack_bench::peers::Peer) {
    if let Err(why) = rccpack_bench::peers::check_available(peer) {
        panic!("{peer} cannot run: {why}");
    }
}

/// The median of `v`: its element at `len / 2` once sorted (the upper
/// one of an even count); the default value (0) when `v` is empty.
pub fn median<T: Copy + PartialOrd + Default>(v: &[T]) -> T {
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.partial_cmp(b).expect("no NaN"));
    s.get(s.len() / 2).copied().unwrap_or_default()
}

pub mod box_packing;
pub mod cases;
pub mod formulas;
pub mod turn_packing;
