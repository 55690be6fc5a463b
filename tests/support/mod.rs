//! What the integration tests share: running the built binary, reading its
//! output, fresh folders, the bundled example's paths.

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

/// Run the `rccpack` binary with `args` in `dir`.
pub fn rccpack_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rccpack"))
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
pub mod formulas;
