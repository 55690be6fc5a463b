//! `rccpack sample` as a user meets it: the JSON array written,
//! exit codes and messages.

use crate::support::{rccpack, scratch, stderr, write_file};
use rccpack::scene::{scenes_from_json, Scene};
use std::process::Output;

const PILOT: &str = "examples/box-packing/pilot.rcc";
const PROBLEM: &str = "examples/box-packing/problem.json";

/// Two interchangeable blocks on a 3×1 table: 3 distinct layouts.
const TINY: &str = r#"{"space": {"width": 30, "height": 10}, "grid": 10, "objects": [
  {"id": "a1", "class": "A", "width": 10, "height": 10},
  {"id": "a2", "class": "A", "width": 10, "height": 10}]}"#;

#[test]
fn writes_n_distinct_layouts_of_score_one() {
    let dir = scratch("sample-cli-writes_n_distinct_layouts_of_score_one");
    let out = write_file(&dir, "box.json", "");
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
        &out,
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

/// `rccpack sample TINY --rules (rules) -n N (extra)`.
fn sample_tiny(name: &str, rules: &str, n: &str, extra: &[&str]) -> Output {
    let dir = scratch(&format!("sample-cli-{name}"));
    let p = write_file(&dir, &format!("{name}.json"), TINY);
    let r = write_file(&dir, &format!("{name}.rcc"), rules);
    let mut args = vec!["sample", &p, "--rules", &r, "-n", n];
    args.extend_from_slice(extra);
    rccpack(&args)
}

#[test]
fn fewer_layouts_than_asked_is_a_message_and_exit_zero() {
    let o = sample_tiny("none", "", "10", &[]);
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
    let o = sample_tiny("west", "rule west: DR_W(A, A)\n", "3", &["--all-rules"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let msg = "no layout keeps every rule (score 1); the best score is 0.5";
    assert!(stderr(&o).contains(msg), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
    let o = sample_tiny("west_hard", "rule west hard: DR_W(A, A)\n", "3", &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("infeasible: "), "{}", stderr(&o));
}

#[test]
fn bad_input_exits_1_with_a_clear_message() {
    let boxed = |extra: &[&str]| {
        let mut args = vec!["sample", PROBLEM, "--rules", PILOT, "-n", "3"];
        args.extend_from_slice(extra);
        rccpack(&args)
    };
    let o = boxed(&["--min-score", "1.5"]);
    assert_eq!(o.status.code(), Some(1));
    let msg = "--min-score 1.5: expected a number from 0 to 1";
    assert!(stderr(&o).contains(msg), "{}", stderr(&o));
    let o = rccpack(&["sample", "no-such.json", "--rules", PILOT, "-n", "3"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("no-such.json"), "{}", stderr(&o));
    let o = boxed(&["--all-rules", "--min-score", "0.5"]);
    assert_eq!(o.status.code(), Some(1));
}
