//! `rccpack sample` as a user meets it (issue 24): the JSON array written,
//! exit codes and messages.

use rccpack::scene::{scenes_from_json, Scene};
use std::path::PathBuf;
use std::process::{Command, Output};

fn rccpack(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rccpack"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run rccpack")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn tmp(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rccpack-sample-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const PILOT: &str = "examples/box-packing/pilot.rcc";
const PROBLEM: &str = "examples/box-packing/problem.json";

/// Two interchangeable blocks on a 3×1 table: 3 distinct layouts.
const TINY: &str = r#"{"space": {"width": 30, "height": 10}, "grid": 10, "objects": [
  {"id": "a1", "class": "A", "width": 10, "height": 10},
  {"id": "a2", "class": "A", "width": 10, "height": 10}]}"#;

#[test]
fn writes_n_distinct_layouts_of_score_one() {
    let out = tmp("box.json", "");
    let o = rccpack(&[
        "sample",
        PROBLEM,
        "--rules",
        PILOT,
        "-n",
        "12",
        "--all-rules",
        "--seed",
        "5",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let layouts: Vec<Scene> = scenes_from_json(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(layouts.len(), 12);
    assert!(
        stderr(&o).contains("12 distinct layouts of score 1"),
        "{}",
        stderr(&o)
    );
    // Same seed, same bytes on stdout.
    let a = rccpack(&[
        "sample", PROBLEM, "--rules", PILOT, "-n", "5", "--seed", "5", "--quiet",
    ]);
    let b = rccpack(&[
        "sample", PROBLEM, "--rules", PILOT, "-n", "5", "--seed", "5", "--quiet",
    ]);
    assert!(a.status.success());
    assert_eq!(a.stdout, b.stdout);
}

#[test]
fn fewer_layouts_than_asked_is_a_message_and_exit_zero() {
    let p = tmp("tiny.json", TINY);
    let r = tmp("none.rcc", "");
    let o = rccpack(&[
        "sample",
        p.to_str().unwrap(),
        "--rules",
        r.to_str().unwrap(),
        "-n",
        "10",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let layouts = scenes_from_json(&String::from_utf8_lossy(&o.stdout)).unwrap();
    assert_eq!(layouts.len(), 3);
    assert!(
        stderr(&o).contains("only 3 distinct layouts"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn all_rules_without_a_score_one_layout_exits_2() {
    let p = tmp("tiny2.json", TINY);
    let r = tmp("west.rcc", "rule west: DR_W(A, A)\n");
    let o = rccpack(&[
        "sample",
        p.to_str().unwrap(),
        "--rules",
        r.to_str().unwrap(),
        "-n",
        "3",
        "--all-rules",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("no layout keeps every rule (score 1); the best score is 0.5"),
        "{}",
        stderr(&o)
    );
    assert!(o.stdout.is_empty());
    let hard = tmp("west_hard.rcc", "rule west hard: DR_W(A, A)\n");
    let o = rccpack(&[
        "sample",
        p.to_str().unwrap(),
        "--rules",
        hard.to_str().unwrap(),
        "-n",
        "3",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("infeasible: "), "{}", stderr(&o));
}

#[test]
fn bad_input_exits_1_with_a_clear_message() {
    let o = rccpack(&[
        "sample",
        PROBLEM,
        "--rules",
        PILOT,
        "-n",
        "3",
        "--min-score",
        "1.5",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("--min-score 1.5: expected a number from 0 to 1"),
        "{}",
        stderr(&o)
    );
    let o = rccpack(&["sample", "no-such.json", "--rules", PILOT, "-n", "3"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("no-such.json"), "{}", stderr(&o));
    let o = rccpack(&[
        "sample",
        PROBLEM,
        "--rules",
        PILOT,
        "-n",
        "3",
        "--all-rules",
        "--min-score",
        "0.5",
    ]);
    assert_eq!(o.status.code(), Some(1));
}
