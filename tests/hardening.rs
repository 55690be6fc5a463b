//! Hardening, through the built binary: what a hostile but fair user
//! tries, and what the tool must answer.

use crate::support::{rccpack, scratch, stderr, stdout, write_file};
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

/// `n` unplaced `w`×`h` blocks of class R in a `size`² space.
fn blocks(n: usize, size: i64, grid: i64, w: i64) -> String {
    let objects: Vec<String> = (0..n)
        .map(|i| format!(r#"{{"id": "r{i}", "class": "R", "width": {w}, "height": {w}}}"#))
        .collect();
    format!(
        r#"{{"space": {{"width": {size}, "height": {size}}}, "grid": {grid}, "objects": [{}]}}"#,
        objects.join(", ")
    )
}

const PILOT: &str = "examples/box-packing/pilot.rcc";
const DEMOS: &str = "examples/box-packing/demos.json";
const PROBLEM: &str = "examples/box-packing/problem.json";

/// Items 2 and 3: the issue's problems are decided by area at once (exit 2,
/// the objects named), and nothing is ever printed as a conflict that was
/// not proven.
#[test]
fn area_decides_at_once_and_nothing_unproven_is_blamed() {
    let d = scratch("harden-area");
    let p101 = write_file(&d, "p101.json", &blocks(101, 100, 10, 10));
    let p145 = write_file(&d, "p145.json", &blocks(145, 120, 10, 10));
    let t = write_file(&d, "t.rcc", "rule t: EC_N(R, R) | !EC_N(R, R)\n");
    let touch = write_file(
        &d,
        "touch.rcc",
        "rule touch hard: EC_N(R, *) | EC_S(R, *) | EC_E(R, *) | EC_W(R, *)\n",
    );
    for (p, rules, limit) in [(&p101, &t, "4"), (&p101, &touch, "5"), (&p145, &touch, "5")] {
        let report = d.join("report.json");
        let start = Instant::now();
        let o = rccpack(&[
            "synth",
            p,
            "--rules",
            rules,
            "--time-limit",
            limit,
            "--report",
            report.to_str().unwrap(),
        ]);
        let took = start.elapsed();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.contains("infeasible: the objects cannot all be placed in the space"),
            "{e}"
        );
        assert!(!e.contains("touch") && !e.contains("`t`"), "{e}");
        assert!(took < Duration::from_secs(2), "{took:?}");
        let r: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        assert_eq!(r["conflict"]["objects_cannot_fit"], true, "{r}");
        assert_eq!(r["conflict"]["hard_rules"], serde_json::json!([]), "{r}");
    }
    // At the boundary: 100 blocks fill the space exactly and are placed.
    let p100 = write_file(&d, "p100.json", &blocks(100, 100, 10, 10));
    let o = rccpack(&["synth", &p100, "--rules", &t, "--time-limit", "60"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// Item 2: when a limit strikes before the conflict is explained (here the
/// node limit stops the "do the objects fit at all?" check of 36 blocks
/// filling their space exactly), no rule is blamed: the rule might be
/// harmless for all that was proven.
#[test]
fn a_limit_during_the_explanation_blames_nothing() {
    let d = scratch("harden-explain");
    let p = write_file(&d, "p36.json", &blocks(36, 60, 10, 10));
    let x = write_file(&d, "x.rcc", "rule x hard: DR_N(R, R)\n");
    let report = d.join("report.json");
    let o = rccpack(&[
        "synth",
        &p,
        "--rules",
        &x,
        "--node-limit",
        "5",
        "--report",
        report.to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("infeasible: a limit struck before the conflict was explained"),
        "{e}"
    );
    assert!(!e.contains("`x`"), "{e}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(r["conflict"]["limit_struck"], true, "{r}");
    assert_eq!(r["conflict"]["hard_rules"], serde_json::json!([]), "{r}");
    // Without the limit the rule is proven to blame.
    let o = rccpack(&["synth", &p, "--rules", &x]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("the hard rules `x` cannot all hold together") && !e.contains("limit"),
        "{e}"
    );
}

/// Item 4: a failed write to standard output is an error naming it, not a
/// panic (exit 101).
#[cfg(target_os = "linux")]
#[test]
fn full_standard_output_is_an_error_not_a_panic() {
    let d = scratch("harden-full");
    let learned = d.join("learned.rcc");
    let learned = learned.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec!["check", PILOT],
        vec!["score", PROBLEM, "--rules", PILOT, "--json"],
        vec!["score", DEMOS, "--rules", PILOT],
        vec!["learn", DEMOS, "--samples", "20"],
        vec![
            "synth",
            PROBLEM,
            "--rules",
            PILOT,
            "--node-limit",
            "2000",
            "--quiet",
        ],
        vec!["learn", DEMOS, "--samples", "20", "-o", learned],
    ];
    for args in &cases[..5] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = crate::support::command()
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdout(Stdio::from(full))
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(
            e.contains("error: cannot write to standard output: "),
            "{args:?}: {e}"
        );
        assert!(!e.contains("panicked"), "{args:?}: {e}");
    }
    assert!(rccpack(&cases[5]).status.success());
}

/// Item 5: every writer replaces a file whole or not at all, and none
/// replaces a read-only file (`--emit` did).
#[test]
fn writes_are_atomic_and_read_only_files_are_kept() {
    let d = scratch("harden-atomic");
    let ro = d.join("ro.out");
    std::fs::write(&ro, "keep me").unwrap();
    let mut perm = std::fs::metadata(&ro).unwrap().permissions();
    perm.set_readonly(true);
    std::fs::set_permissions(&ro, perm).unwrap();
    let ro_svg = d.join("ro.svg");
    std::fs::copy(&ro, &ro_svg).unwrap();
    let ro_json = d.join("ro.json");
    std::fs::copy(&ro, &ro_json).unwrap();
    let ro_s = ro.to_str().unwrap();
    let ro_json_s = ro_json.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec!["synth", PROBLEM, "--rules", PILOT, "--emit", ro_json_s],
        vec![
            "synth",
            PROBLEM,
            "--rules",
            PILOT,
            "--node-limit",
            "500",
            "-o",
            ro_s,
        ],
        vec![
            "synth",
            PROBLEM,
            "--rules",
            PILOT,
            "--node-limit",
            "500",
            "--report",
            ro_s,
        ],
        vec!["render", PROBLEM, "-o", ro_svg.to_str().unwrap()],
        vec!["learn", DEMOS, "--samples", "20", "-o", ro_s],
        vec!["learn", DEMOS, "--samples", "20", "--report", ro_s],
    ];
    for args in &cases {
        let o = rccpack(args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(e.contains("read-only"), "{args:?}: {e}");
        for p in [&ro, &ro_svg, &ro_json] {
            assert_eq!(std::fs::read_to_string(p).unwrap(), "keep me", "{args:?}");
        }
    }
    // A successful write leaves no temporary file behind, and a writable
    // file is replaced.
    let out = d.join("sol.json");
    std::fs::write(&out, "old").unwrap();
    let o = rccpack(&[
        "synth",
        PROBLEM,
        "--rules",
        PILOT,
        "--node-limit",
        "500",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&out)
        .unwrap()
        .contains("\"objects\""));
    let stray: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
        .collect();
    assert!(stray.is_empty(), "{stray:?}");
    // Writing to a device still works (and does not replace it).
    let o = rccpack(&["check", PILOT]);
    assert!(stdout(&o).contains("ok"));
    #[cfg(unix)]
    {
        let o = rccpack(&["learn", DEMOS, "--samples", "20", "-o", "/dev/null"]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
}

/// Item 9: a key given twice is refused inside a demonstrations array as in
/// a single scene.
#[test]
fn duplicate_keys_are_refused_in_demonstration_arrays() {
    let d = scratch("harden-dupkeys");
    let rules = write_file(&d, "r.rcc", "rule r: DR_N(R, R)\n");
    let scene = r#"{"space": {"width": 100, "height": 100}, "objects": [{"class": "R", "x": 0, "y": 0, "width": 10, "height": 10}], "objects": []}"#;
    let fixed = r#"{"space": {"width": 100, "height": 100}, "objects": [{"class": "R", "x": 0, "y": 0, "width": 10, "height": 10, "fixed": true, "fixed": false}]}"#;
    for (name, text) in [
        ("one.json", scene.to_string()),
        ("arr.json", format!("[{scene}]")),
        ("fixed.json", format!("[{fixed}]")),
    ] {
        let p = write_file(&d, name, &text);
        let o = rccpack(&["score", &p, "--rules", &rules]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{name}: {e}");
        assert!(e.contains("duplicate field"), "{name}: {e}");
    }
}

/// Item 14: byte-order marks, invalid UTF-8, CR-only line ends, `-0`,
/// 2^64, long values, `score` on `[]`.
#[test]
fn small_edges_of_the_input() {
    let d = scratch("harden-edges");
    // A BOM in .rcc and JSON is accepted.
    let rules = write_file(&d, "bom.rcc", "\u{feff}rule r: DR_N(R, R)\n");
    let scene = write_file(
        &d,
        "bom.json",
        "\u{feff}{\"space\": {\"width\": 100, \"height\": 100}, \"objects\": [{\"class\": \"R\", \"x\": -0, \"y\": 0, \"width\": 10, \"height\": 10}]}",
    );
    let o = rccpack(&["score", &scene, "--rules", &rules]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Invalid UTF-8: the byte offset.
    let bad = d.join("bad.rcc");
    std::fs::write(&bad, b"rule r: DR_N(R, R)\nrule \xff: x\n").unwrap();
    let o = rccpack(&["check", bad.to_str().unwrap()]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("byte offset 24") && e.contains("line 2"), "{e}");
    // CR-only line ends: one line number for one error.
    let cr = write_file(&d, "cr.rcc", "rule a: DR_N(R, R)\rrule b: DR_N(R, R\r");
    let o = rccpack(&["check", &cr]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("cr.rcc:2:"), "{e}");
    assert!(!e.contains("cr.rcc:1:"), "{e}");
    // 2^64 is out of range, not floating point.
    let big = write_file(
        &d,
        "big.json",
        r#"{"space": {"width": 18446744073709551616, "height": 100}, "objects": []}"#,
    );
    let o = rccpack(&["score", &big, "--rules", &rules]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("out of range") && !e.contains("floating"), "{e}");
    // A fraction is still a floating-point error.
    let frac = write_file(
        &d,
        "frac.json",
        r#"{"space": {"width": 10.5, "height": 100}, "objects": []}"#,
    );
    assert!(stderr(&rccpack(&["score", &frac, "--rules", &rules])).contains("floating point"));
    // A 100 000-character id is cut in the message.
    let long = "x".repeat(100_000);
    let dup = write_file(
        &d,
        "long.json",
        &format!(
            r#"{{"space": {{"width": 100, "height": 100}}, "objects": [{{"id": "{long}", "class": "R", "width": 10, "height": 10}}, {{"id": "{long}", "class": "R", "width": 10, "height": 10}}]}}"#
        ),
    );
    let o = rccpack(&["score", &dup, "--rules", &rules]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.len() < 1000 && e.contains("…"), "{} bytes", e.len());
    // `score` on an empty array says so.
    let empty = write_file(&d, "empty.json", "[]");
    let o = rccpack(&["score", &empty, "--rules", &rules]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("no scenes"), "{}", stdout(&o));
    let o = rccpack(&["score", &empty, "--rules", &rules, "--json"]);
    assert_eq!(stdout(&o).trim(), "[]");
}

/// Item 14: `R`, `r` and `red` are three classes in three colours.
#[test]
fn similar_class_names_get_different_colours() {
    let d = scratch("harden-colours");
    let scene = write_file(
        &d,
        "s.json",
        r#"{"space": {"width": 100, "height": 100}, "objects": [
            {"class": "R", "x": 0, "y": 0, "width": 10, "height": 10},
            {"class": "r", "x": 20, "y": 0, "width": 10, "height": 10},
            {"class": "red", "x": 40, "y": 0, "width": 10, "height": 10}]}"#,
    );
    let svg = d.join("s.svg");
    let o = rccpack(&["render", &scene, "-o", svg.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&svg).unwrap();
    let red = text.matches("#d9534f").count();
    assert!(red >= 1, "R is red");
    let s = rccpack::scene::Scene::from_json(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    let c = rccpack::render::class_colours(&s);
    assert_ne!(c["R"], c["r"]);
    assert_ne!(c["R"], c["red"]);
    assert_ne!(c["r"], c["red"]);
}

/// Item 12: a rule file past 16 MiB is refused before parsing, naming the
/// limit; at the limit it is read.
#[test]
fn rule_file_size_limit() {
    let d = scratch("harden-rulesize");
    let line = "rule r: DR_N(R, R)\n";
    let pad = "#".repeat(1 << 20) + "\n";
    let mut at = String::from(line);
    while at.len() + pad.len() <= rccpack::limits::MAX_RULES_BYTES {
        at.push_str(&pad);
    }
    at.push_str(&"#".repeat(rccpack::limits::MAX_RULES_BYTES - at.len() - 1));
    at.push('\n');
    assert_eq!(at.len(), rccpack::limits::MAX_RULES_BYTES);
    let p = write_file(&d, "at.rcc", &at);
    let o = rccpack(&["check", &p]);
    assert!(o.status.success(), "{}", stderr(&o));
    at.push('\n');
    let p = write_file(&d, "past.rcc", &at);
    let o = rccpack(&["check", &p]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("16777217 bytes") && e.contains("16 MiB"), "{e}");
}

/// Item 10: learning is bounded: too many statements are refused before
/// anything is made, and `run --time-limit` covers learning (exit 3).
#[test]
fn learning_is_bounded() {
    let d = scratch("harden-learnbound");
    // 120 classes, one object each, in two demonstrations.
    let objects: Vec<String> = (0..120)
        .map(|i| {
            format!(
                r#"{{"class": "C{i}", "x": {}, "y": {}, "width": 1, "height": 1}}"#,
                (i % 12) * 2,
                (i / 12) * 2
            )
        })
        .collect();
    let scene = format!(
        r#"{{"space": {{"width": 30, "height": 30}}, "grid": 1, "objects": [{}]}}"#,
        objects.join(", ")
    );
    let demos = write_file(&d, "demos.json", &format!("[{scene}, {scene}]"));
    let start = Instant::now();
    let o = rccpack(&["learn", &demos, "--samples", "10"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("statements") && e.contains("at most 50000"),
        "{e}"
    );
    assert!(start.elapsed() < Duration::from_secs(10));
    // `run` on the bundled example with 10^6 samples and a 1 s limit stops
    // learning at the limit.
    let task = scratch("harden-learnbound-task");
    for f in ["problem.json", "demos.json"] {
        std::fs::copy(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("examples/box-packing")
                .join(f),
            task.join(f),
        )
        .unwrap();
    }
    let start = Instant::now();
    let o = rccpack(&[
        "run",
        task.to_str().unwrap(),
        "--samples",
        "1000000",
        "--time-limit",
        "1",
    ]);
    let took = start.elapsed();
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(3), "{e}");
    assert!(e.contains("time limit struck while learning"), "{e}");
    assert!(took < Duration::from_secs(8), "{took:?}");
    assert!(!task.join("learned.rcc").exists());
}

/// Item 11: `run` on a problem without one of the demonstrations' classes
/// notes it and lays out the rest; `synth` with hand-written rules still
/// refuses an unknown class.
#[test]
fn a_class_the_problem_lacks_is_noted() {
    let task = scratch("harden-absent");
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing");
    std::fs::copy(ex.join("demos.json"), task.join("demos.json")).unwrap();
    let mut problem: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ex.join("problem.json")).unwrap()).unwrap();
    problem["objects"]
        .as_array_mut()
        .unwrap()
        .retain(|o| o["class"] != "B");
    std::fs::write(task.join("problem.json"), problem.to_string()).unwrap();
    let o = rccpack(&[
        "run",
        task.to_str().unwrap(),
        "--samples",
        "200",
        "--time-limit",
        "30",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("note: the problem has no objects of class B; its rules hold vacuously"),
        "{out}"
    );
    assert!(task.join("solution.json").exists());
    let o = rccpack(&[
        "synth",
        task.join("problem.json").to_str().unwrap(),
        "--rules",
        PILOT,
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("`B`"), "{}", stderr(&o));
    // `ask` notes it too, and asks.
    let o = rccpack(&[
        "ask",
        task.to_str().unwrap(),
        "--oracle",
        "false",
        "--max-questions",
        "1",
        "--samples",
        "200",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("note: the problem has no objects of class B"),
        "{}",
        stdout(&o)
    );
}

/// Items 7 and 13: one `ask` per folder; a hung oracle is stopped after
/// `--oracle-timeout` with its whole process group, exit 1 and a message,
/// no temporary file left.
#[cfg(unix)]
#[test]
fn ask_lock_and_oracle_timeout() {
    let task = scratch("harden-asklock");
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing");
    for f in ["problem.json", "demos.json"] {
        std::fs::copy(ex.join(f), task.join(f)).unwrap();
    }
    let t = task.to_str().unwrap();
    {
        let _held = rccpack::fsutil::DirLock::try_lock(&task).unwrap().unwrap();
        let o = rccpack(&["ask", t, "--oracle", "true", "--samples", "200"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{e}");
        assert!(e.contains("another `rccpack ask` or the studio"), "{e}");
        assert!(!task.join("answers.json").exists());
    }
    // The oracle starts a grandchild that would outlive a plain kill.
    let marker = task.join("grandchild-alive");
    let oracle = format!(
        "sh -c 'sleep 3; touch {}' & sleep 30; true",
        marker.display()
    );
    let start = Instant::now();
    let o = rccpack(&[
        "ask",
        t,
        "--oracle",
        &oracle,
        "--oracle-timeout",
        "1",
        "--samples",
        "200",
    ]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("--oracle-timeout"), "{e}");
    assert!(start.elapsed() < Duration::from_secs(25));
    std::thread::sleep(Duration::from_secs(3));
    assert!(!marker.exists(), "the oracle's process group outlived it");
    let stray: Vec<_> = std::fs::read_dir(&task)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
        .collect();
    assert!(stray.is_empty(), "{stray:?}");
    // Ctrl-C while the oracle hangs: exit 1 with a message, the oracle
    // ended, no temporary file.
    let _ = std::fs::remove_dir_all(task.join("probes"));
    let child = crate::support::command()
        .args(["ask", t, "--oracle", "sleep 60; true", "--samples", "200"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !task.join("probes").join("probe-1.json").exists()
        && start.elapsed() < Duration::from_secs(60)
    {
        std::thread::sleep(Duration::from_millis(50));
    }
    std::thread::sleep(Duration::from_millis(300));
    // SAFETY: a signal to the child this test started.
    unsafe {
        libc::kill(child.id() as i32, libc::SIGINT);
    }
    let o = child.wait_with_output().unwrap();
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("interrupted (Ctrl-C)"), "{e}");
    let stray: Vec<_> = std::fs::read_dir(&task)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
        .collect();
    assert!(stray.is_empty(), "{stray:?}");
}

/// Item 3's overshoot: the time limit covers posting the model to the
/// engine (144 blocks exactly filling their space with a hard contact
/// rule: about a second of posting in release builds). Timed as a ratio
/// against the same problem without a limit.
#[test]
fn the_time_limit_covers_building_the_engine() {
    let d = scratch("harden-build-limit");
    let p = write_file(&d, "p144.json", &blocks(144, 120, 10, 10));
    let touch = write_file(
        &d,
        "touch.rcc",
        "rule touch hard: EC_N(R, *) | EC_S(R, *) | EC_E(R, *) | EC_W(R, *)\n",
    );
    let timed = |limit: &str| {
        let t = Instant::now();
        let o = rccpack(&[
            "synth",
            &p,
            "--rules",
            &touch,
            "--time-limit",
            limit,
            "--quiet",
        ]);
        (o, t.elapsed())
    };
    let (full, t_full) = timed("600");
    assert_eq!(full.status.code(), Some(0), "{}", stderr(&full));
    let (cut, t_cut) = timed("0.01");
    assert_eq!(cut.status.code(), Some(3), "{}", stderr(&cut));
    assert!(
        t_cut * 3 < t_full,
        "limited {t_cut:?}, unlimited {t_full:?}: the limit did not cut the build short"
    );
}
