//! The command line as a user meets it: exit codes, messages, JSON output.

use crate::support::{rccpack, scratch, stderr, write_file};

const PILOT: &str = "examples/box-packing/pilot.rcc";
const DEMOS: &str = "examples/box-packing/demos.json";
const PROBLEM: &str = "examples/box-packing/problem.json";

#[test]
fn check_accepts_the_pilot_rules() {
    let o = rccpack(&["check", PILOT, "--scene", PROBLEM]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("12 rules"));
}

#[test]
fn check_reports_unknown_class_with_location() {
    let dir = scratch("cli-check_reports_unknown_class_with_location");
    let rules = write_file(&dir, "unknown_class.rcc", "rule q: DR_N(B, Q)\n");
    let o = rccpack(&["check", &rules, "--scene", PROBLEM]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("unknown_class.rcc:1:9"), "{e}");
    assert!(e.contains("`Q`"), "{e}");
}

#[test]
fn check_reports_unknown_landmark_with_location() {
    let dir = scratch("cli-check_reports_unknown_landmark_with_location");
    let rules = write_file(
        &dir,
        "bad_landmark.rcc",
        "rule ok: some R: EC_E(R, @w_west)\nrule far: EC_W(R, @w_far) | DR_N(R, B)\n",
    );
    let o = rccpack(&["check", &rules, "--scene", PROBLEM]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("bad_landmark.rcc:2:11"), "{e}");
    assert!(e.contains("`@w_far`"), "{e}");
    assert!(e.contains("rule `far`"), "{e}");
    assert!(
        e.contains("the scene's fixed objects are w_south, w_north, w_west, w_east"),
        "{e}"
    );
    // The same rules pass without a scene (landmarks need one), and other
    // commands that evaluate the rules refuse them the same way.
    let o = rccpack(&["check", &rules]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = rccpack(&["score", PROBLEM, "--rules", &rules]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("bad_landmark.rcc:2:11"),
        "{}",
        stderr(&o)
    );
    // `learn --statements` checks them against each demonstration.
    let o = rccpack(&["learn", DEMOS, "--statements", &rules]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("bad_landmark.rcc:2:11"),
        "{}",
        stderr(&o)
    );
    // A good landmark is fine.
    let good = write_file(
        &dir,
        "good_landmark.rcc",
        "rule ok: some R: EC_E(R, @w_west)\n",
    );
    let o = rccpack(&["check", &good, "--scene", PROBLEM]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn score_json_is_an_array_for_demonstrations() {
    let o = rccpack(&["score", DEMOS, "--rules", PILOT, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let arr = v.as_array().expect("array for a demonstrations file");
    assert_eq!(arr.len(), 8);
    for s in arr {
        assert_eq!(s["score"], 1.0);
        assert_eq!(s["satisfied_weight"], s["total_weight"]);
        let rules = s["rules"].as_array().unwrap();
        assert_eq!(rules.len(), 12);
        for key in [
            "name",
            "weight",
            "hard",
            "satisfied",
            "subjects",
            "violators",
        ] {
            assert!(rules[0].get(key).is_some(), "missing {key}");
        }
    }
}

#[test]
fn score_json_is_an_object_for_one_scene_and_names_violators() {
    let dir = scratch("cli-score_json_is_an_object_for_one_scene_and_names_violators");
    let scene = write_file(
        &dir,
        "one.json",
        r#"{"space":{"width":100,"height":100},"objects":[
        {"id":"b1","class":"B","x":0,"y":0,"width":10,"height":10},
        {"id":"r1","class":"R","x":0,"y":50,"width":10,"height":10}]}"#,
    );
    let rules = write_file(
        &dir,
        "one.rcc",
        "rule north: DR_N(B, R)\nrule south hard: DR_S(B, R)\n",
    );
    let o = rccpack(&["score", &scene, "--rules", &rules, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["score"], 0.0);
    assert_eq!(v["rules"][0]["violators"][0], "b1");
    assert_eq!(v["rules"][1]["hard"], true);
    assert_eq!(v["hard_violations"], 0);
    // The human table lists the violator too.
    let o = rccpack(&["score", &scene, "--rules", &rules]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("north") && out.contains("0/1") && out.contains("b1"),
        "{out}"
    );
}

#[test]
fn bad_json_names_file_and_field() {
    let dir = scratch("cli-bad_json_names_file_and_field");
    let scene = write_file(
        &dir,
        "float.json",
        r#"{"space":{"width":100,"height":100},"objects":[{"class":"R","x":12.5,"y":0,"width":1,"height":1}]}"#,
    );
    let o = rccpack(&["score", &scene, "--rules", PILOT]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("float.json") && e.contains("objects[0].x") && e.contains("12.5"),
        "{e}"
    );
}

#[test]
fn missing_file_is_a_clear_error() {
    let o = rccpack(&["check", "no/such/file.rcc"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("no/such/file.rcc: cannot read file"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn render_writes_svg_and_png() {
    let dir = scratch("cli-render");
    for ext in ["svg", "png"] {
        let out = dir.join(format!("demo.{ext}"));
        let o = rccpack(&[
            "render",
            DEMOS,
            "--index",
            "2",
            "--rules",
            PILOT,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let bytes = std::fs::read(&out).unwrap();
        assert!(bytes.len() > 100);
    }
    let o = rccpack(&["render", DEMOS, "-o", dir.join("x.png").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("--index"), "{}", stderr(&o));
    let o = rccpack(&["render", PROBLEM, "-o", dir.join("x.gif").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
}

/// `RCCPACK_DEBUG=1`: the library's debug lines reach stderr through the
/// CLI's logger (the library itself never prints); without it, none.
#[test]
fn debug_log_only_when_asked() {
    let args = ["synth", PROBLEM, "--rules", PILOT, "--node-limit", "2000"];
    let with = crate::support::command()
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("RCCPACK_DEBUG", "1")
        .output()
        .unwrap();
    assert!(with.status.success(), "{}", stderr(&with));
    assert!(stderr(&with).contains("model "), "{}", stderr(&with));
    let without = rccpack(&args);
    assert!(!stderr(&without).contains("model "), "{}", stderr(&without));
}

/// The `RCCPACK_*` engine tuning variables: read by the command line only,
/// a value that is not a choice is a usage error naming it (exit 1), and a
/// valid choice changes the encoding, never the layout's score.
#[test]
fn engine_tuning_comes_from_the_environment_and_never_changes_the_score() {
    let args = ["synth", PROBLEM, "--rules", PILOT, "--node-limit", "20000"];
    let with = |name: &str, value: &str| {
        crate::support::command()
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env(name, value)
            .output()
            .unwrap()
    };
    let bad = with("RCCPACK_NO_OVERLAP", "clause");
    assert_eq!(bad.status.code(), Some(1), "{}", stderr(&bad));
    assert!(
        stderr(&bad).contains("RCCPACK_NO_OVERLAP=\"clause\"")
            && stderr(&bad).contains("expected clauses, propagator or pairs"),
        "{}",
        stderr(&bad)
    );
    let score = |o: &std::process::Output| {
        assert!(o.status.success(), "{}", stderr(o));
        let s = stderr(o);
        let at = s.find("score ").expect("a score line");
        s[at..].split_whitespace().nth(1).unwrap().to_string()
    };
    // The variable reaches the model: the non-overlap clauses (72 on this
    // problem) go to the propagator (the debug line counts the clauses).
    let clauses = |value: Option<&str>| {
        let mut c = crate::support::command();
        c.args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env("RCCPACK_DEBUG", "1");
        if let Some(v) = value {
            c.env("RCCPACK_NO_OVERLAP", v);
        }
        let e = stderr(&c.output().unwrap());
        let at = e.find(" clauses)").expect("a model debug line");
        let n: usize = e[..at].rsplit(' ').next().unwrap().parse().unwrap();
        n
    };
    assert!(clauses(None) > 0);
    assert_eq!(clauses(Some("propagator")), 0);
    let default = score(&rccpack(&args));
    for (name, value) in [
        ("RCCPACK_NO_OVERLAP", "propagator"),
        ("RCCPACK_CONNECTIVITY", "circuit"),
        ("RCCPACK_DIFFERENCE", "off"),
        ("RCCPACK_WARM_GROW", "off"),
    ] {
        assert_eq!(score(&with(name, value)), default, "{name}={value}");
    }
}
