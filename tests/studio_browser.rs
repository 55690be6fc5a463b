//! End-to-end test of `rccpack studio` in headless Chromium: runs
//! `tests/e2e/studio.test.mjs` (Node + playwright-core driving the system
//! Chromium at /usr/bin/chromium, or `RCCPACK_CHROMIUM`).
//!
//! Ignored by a plain `cargo test`; `.ci/run` installs Chromium, Node's
//! packages (`cd tests/e2e && npm ci`) and runs it, and a missing piece is
//! a failure naming it.

use std::path::Path;
use std::process::Command;

#[test]
#[ignore = "needs Chromium, Node and tests/e2e/node_modules: run by .ci/run"]
fn studio_in_headless_chromium() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let chromium = std::env::var("RCCPACK_CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    let node_ok = Command::new("node")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        Path::new(&chromium).exists(),
        "{chromium} not found (apt-get install chromium chromium-driver)"
    );
    assert!(node_ok, "node not found");
    assert!(
        root.join("tests/e2e/node_modules/playwright-core").exists(),
        "tests/e2e/node_modules missing (cd tests/e2e && npm ci)"
    );
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("studio-e2e");
    let status = Command::new("node")
        .arg(root.join("tests/e2e/studio.test.mjs"))
        .env("RCCPACK_BIN", env!("CARGO_BIN_EXE_rccpack"))
        .env("RCCPACK_EXAMPLE", root.join("examples/box-packing"))
        .env("RCCPACK_E2E_OUT", &out)
        .env("RCCPACK_CHROMIUM", &chromium)
        .status()
        .expect("run node");
    assert!(
        status.success(),
        "browser test failed; screenshots in {}",
        out.display()
    );
    println!("screenshots in {}", out.display());
}
