//! `rccpack learn` on the command line: output, report, exit codes and
//! messages.

use std::path::PathBuf;
use std::process::{Command, Output};

fn rccpack(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rccpack"))
        .args(args)
        .output()
        .expect("run rccpack")
}

fn demos() -> String {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/box-packing/demos.json"
    )
    .to_string()
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rccpack-learn-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn learn_writes_rules_and_report_that_score_reads() {
    let out = tmp("learned.rcc");
    let report = tmp("report.json");
    let o = rccpack(&[
        "learn",
        &demos(),
        "--samples",
        "200",
        "-o",
        out.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.is_empty(), "nothing on stdout with -o");
    assert!(
        o.stderr.is_empty(),
        "no progress when stderr is not a terminal"
    );
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("rule B_dr_n_R p "), "{text}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let st = r["statements"].as_array().unwrap();
    let b = st.iter().find(|s| s["name"] == "B_dr_n_R").unwrap();
    assert_eq!(b["formula"], "DR_N(B, R)");
    assert_eq!(b["candidate"], true);
    assert_eq!(b["learned"], true);
    assert!(b["q"].as_f64().unwrap() > 0.0);
    let broken = st.iter().find(|s| s["candidate"] == false).unwrap();
    assert!(broken["broken_by"]["object"].is_string());
    // The learned file feeds `rccpack score`: every demonstration scores 1.
    let o = rccpack(&[
        "score",
        &demos(),
        "--rules",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let scores: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for s in scores.as_array().unwrap() {
        assert_eq!(s["score"], 1.0);
    }
}

#[test]
fn learn_prints_to_stdout_without_output_flag() {
    let o = rccpack(&["learn", &demos(), "--samples", "100", "--seed", "3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.starts_with("# learned by rccpack from 8 demonstrations"));
    assert!(rccpack::rules::parse_rules(&text).is_ok());
}

#[test]
fn learn_with_a_statement_file() {
    let st = tmp("statements.rcc");
    std::fs::write(
        &st,
        "rule blue_north: DR_N(B, R)\nrule blue_south: DR_S(B, R)\n",
    )
    .unwrap();
    let o = rccpack(&["learn", &demos(), "--statements", st.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("rule blue_north p "), "{text}");
    assert!(!text.contains("rule blue_south"), "{text}");
}

#[test]
fn statement_file_with_an_unknown_class_is_located() {
    let st = tmp("unknown.rcc");
    std::fs::write(&st, "rule ok: DR_N(B, R)\nrule bad: DR_N(B, Q)\n").unwrap();
    let o = rccpack(&["learn", &demos(), "--statements", st.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("unknown.rcc"), "{e}");
    assert!(
        e.contains("rule `bad` names class `Q`, which no demonstration has"),
        "{e}"
    );
    assert!(e.contains(":2:"), "line 2 named: {e}");
}

#[test]
fn bad_parameters_exit_1_naming_the_flag() {
    for (args, msg) in [
        (
            vec!["--cutoff", "1.5"],
            "invalid --cutoff 1.5: expected a number strictly between 0 and 1",
        ),
        (
            vec!["--samples", "0"],
            "invalid --samples 0: expected a whole number of at least 1",
        ),
        (
            vec!["--prior", "0"],
            "invalid --prior 0: expected a number strictly between 0 and 1",
        ),
        (
            vec!["--epsilon", "2"],
            "invalid --epsilon 2: expected a number strictly between 0 and 1",
        ),
    ] {
        let d = demos();
        let mut all = vec!["learn", d.as_str()];
        all.extend(args);
        let o = rccpack(&all);
        assert_eq!(o.status.code(), Some(1));
        assert!(stderr(&o).contains(msg), "{}", stderr(&o));
    }
}

#[test]
fn empty_demonstrations_exit_1() {
    let p = tmp("empty.json");
    std::fs::write(&p, "[]").unwrap();
    let o = rccpack(&["learn", p.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("no demonstrations"), "{}", stderr(&o));
}
