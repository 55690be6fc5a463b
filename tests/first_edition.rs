//! Every first-edition file keeps its meaning, its score and its report,
//! byte for byte (docs/language.md): the outputs under
//! `tests/fixtures/first-edition/golden/` were written by the first-edition
//! binary (commit 3900fd4) and this test runs today's binary on the same
//! inputs.
//!
//! Inputs: the pilot rules, the rules the first edition learned from the
//! bundled demonstrations, every one of the first edition's 213 docs/guide.md#learning template
//! statements for that task, and a file with every docs/language.md#syntax syntax form; scenes:
//! the 8 demonstrations, the problem (partly placed) and a synthesised
//! solution; both contact modes.

use std::path::{Path, PathBuf};

const RULES: [&str; 4] = ["templates", "learned", "pilot", "syntax"];
const SCENES: [&str; 3] = ["demos", "problem", "solution"];

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/first-edition")
}

/// Run the binary in the fixture folder; stdout+stderr and the exit code as
/// the golden files hold them.
fn run(args: &[&str]) -> (String, i32) {
    let out = crate::support::rccpack_in(&dir(), args);
    let mut s = String::from_utf8(out.stdout).expect("utf-8 stdout");
    s.push_str(&String::from_utf8(out.stderr).expect("utf-8 stderr"));
    (s, out.status.code().unwrap_or(-1))
}

fn golden(name: &str) -> String {
    std::fs::read_to_string(dir().join("golden").join(name))
        .unwrap_or_else(|e| panic!("golden file {name}: {e}"))
}

#[test]
fn score_json_and_table_are_byte_identical() {
    let mut checked = 0;
    for r in RULES {
        for s in SCENES {
            for c in ["point", "edge"] {
                let rules = format!("{r}.rcc");
                let scene = format!("{s}.json");
                let base = ["score", &scene, "--rules", &rules, "--contact", c];
                let (json, code) = run(&[&base[..], &["--json"]].concat());
                assert_eq!(code, 0, "{r} {s} {c}: {json}");
                assert_eq!(
                    json,
                    golden(&format!("score-{r}-{s}-{c}.json")),
                    "{r} {s} {c} --json"
                );
                let (table, code) = run(&base);
                assert_eq!(code, 0);
                assert_eq!(
                    table,
                    golden(&format!("score-{r}-{s}-{c}.txt")),
                    "{r} {s} {c}"
                );
                checked += 2;
            }
        }
    }
    assert_eq!(checked, 48);
}

#[test]
fn check_is_byte_identical() {
    for r in RULES {
        for s in SCENES {
            let (out, code) = run(&[
                "check",
                &format!("{r}.rcc"),
                "--scene",
                &format!("{s}.json"),
            ]);
            assert_eq!(
                format!("{out}rc={code}\n"),
                golden(&format!("check-{r}-{s}.txt"))
            );
        }
    }
}

#[test]
fn render_with_rules_is_byte_identical() {
    let tmp = crate::support::scratch("first-edition-render");
    for (args, name) in [
        (
            vec!["demos.json", "--index", "0", "--rules", "pilot.rcc"],
            "render-pilot-demo0.svg",
        ),
        (
            vec!["solution.json", "--rules", "learned.rcc"],
            "render-learned-solution.svg",
        ),
    ] {
        let out = tmp.join(name);
        let out_s = out.to_str().unwrap();
        let (msg, code) = run(&[&["render"][..], &args, &["-o", out_s]].concat());
        assert_eq!(code, 0, "{msg}");
        let got = std::fs::read_to_string(&out).unwrap();
        assert_eq!(got, golden(name), "{name}");
    }
    std::fs::remove_dir_all(&tmp).ok();
}

/// The first edition's printer wrote `learned.rcc`; today's printer prints
/// its rules to the same lines.
#[test]
fn printer_reprints_first_edition_rules_identically() {
    for r in RULES {
        let text = std::fs::read_to_string(dir().join(format!("{r}.rcc"))).unwrap();
        let rules = rccpack::rules::parse_rules(&text).unwrap();
        let printed = rccpack::rules::print_rules(&rules);
        let reparsed = rccpack::rules::parse_rules(&printed).unwrap();
        assert!(reparsed.same_rules(&rules), "{r}: print -> parse differs");
        if r == "learned" {
            let code = |t: &str| -> Vec<String> {
                t.lines()
                    .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
                    .map(String::from)
                    .collect()
            };
            assert_eq!(code(&printed), code(&text), "{r}");
        }
    }
}
