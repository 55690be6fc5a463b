//! Third hardening pass, through the built binary: what a hostile but
//! fair user tried on the fourth edition, and what the tool must answer.

use crate::support::{example_copy, rccpack, scratch, stderr, write_file};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A problem with `n` movable 10×10 `R` objects in a square space.
fn r_problem(n: usize) -> String {
    let side = 10 * ((2 * n) as f64).sqrt().ceil() as i64 + 20;
    let objects: Vec<String> = (0..n)
        .map(|i| format!(r#"{{"id": "r{i}", "class": "R", "width": 10, "height": 10}}"#))
        .collect();
    format!(
        r#"{{"space": {{"width": {side}, "height": {side}}}, "grid": 10, "objects": [{}]}}"#,
        objects.join(", ")
    )
}

/// Item 1: a group statement counts toward the pair limit like any other
/// rule. `group(R)` over 600 objects (179 700 pairs, four relations each)
/// built until the memory ran out and aborted; it is refused at once with
/// exit 1, as `EC_N(R, R)` over the same objects is. Every shape and
/// negated shape is counted; a small class still synthesises.
#[test]
fn group_statements_count_toward_the_pair_limit() {
    let d = scratch("harden3-group-pairs");
    let p = write_file(&d, "p.json", &r_problem(600));
    for rule in [
        "group(R)",
        "not block(R)",
        "row(R)",
        "column(R)",
        "EC_N(R, R)",
    ] {
        let r = write_file(&d, "r.rcc", &format!("rule g: {rule}\n"));
        let start = Instant::now();
        let o = rccpack(&["synth", &p, "--rules", &r, "--quiet", "-o", "/dev/null"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{rule}: {e}");
        assert!(
            e.contains("pairs of objects") && e.contains("120000"),
            "{rule}: {e}"
        );
        assert!(start.elapsed() < Duration::from_secs(10), "{rule}");
    }
    let small = write_file(&d, "small.json", &r_problem(6));
    let r = write_file(&d, "r.rcc", "rule g: group(R)\n");
    let o = rccpack(&["synth", &small, "--rules", &r, "--quiet", "-o", "/dev/null"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// Width and height of a PNG file, read from its header.
fn png_size(path: &std::path::Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap();
    assert_eq!(&b[1..4], b"PNG", "{}", path.display());
    let be = |i: usize| u32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
    (be(16), be(20))
}

/// A scene on a table `width` units wide (millimetres), with an `A` and a
/// `B` object side by side at `x`.
fn wide_scene(width: i64, x: i64) -> String {
    format!(
        r#"{{"space": {{"width": {width}, "height": 2000}}, "grid": 500, "objects": [
            {{"id": "a", "class": "A", "x": {x}, "y": 0, "width": 1000, "height": 1000}},
            {{"id": "b", "class": "B", "x": {}, "y": 0, "width": 1000, "height": 1000}}]}}"#,
        x + 1000
    )
}

/// Items 4 and 16: `run` on a valid task whose table is 40 000 units wide
/// wrote `learned.rcc`, the report and `solution.json`, then failed to
/// draw `solution.png`; the picture is now drawn scaled to fit the PNG
/// limits, and `render` says at what scale.
#[test]
fn a_wide_table_is_drawn_scaled_to_fit() {
    let d = scratch("harden3-wide");
    write_file(
        &d,
        "demos.json",
        &format!(
            "[{}, {}]",
            wide_scene(40_000, 0),
            wide_scene(40_000, 20_000)
        ),
    );
    write_file(
        &d,
        "problem.json",
        r#"{"space": {"width": 40000, "height": 2000}, "grid": 500, "objects": [
            {"id": "a", "class": "A", "width": 1000, "height": 1000},
            {"id": "b", "class": "B", "width": 1000, "height": 1000}]}"#,
    );
    let t = d.to_str().unwrap();
    let o = rccpack(&["run", t, "--samples", "200", "--time-limit", "10"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h) = png_size(&d.join("solution.png"));
    assert!(w <= 32_000 && h <= 32_000, "{w}x{h}");
    assert!(w > 16_000, "scaled no more than needed: {w}x{h}");
    let out = d.join("wide.png");
    let o = rccpack(&[
        "render",
        &d.join("problem.json").to_string_lossy(),
        "-o",
        &out.to_string_lossy(),
        "--scale",
        "2",
    ]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("at scale 0.") && e.contains("32000 pixels a side"),
        "{e}"
    );
    let (w, _) = png_size(&out);
    assert!(w <= 32_000, "{w}");
}

/// A studio request through the router: status and JSON body (a body that
/// is not JSON becomes a string, so a plain-text answer fails the test).
async fn studio_call(
    app: &axum::Router,
    method: axum::http::Method,
    uri: &str,
    body: String,
) -> (axum::http::StatusCode, serde_json::Value) {
    use http_body_util::BodyExt;
    use tower::ServiceExt;
    let req = axum::http::Request::builder()
        .method(method)
        .uri(uri)
        .header("content-type", "application/json")
        .body(axum::body::Body::from(body))
        .unwrap();
    let res = app.clone().oneshot(req).await.unwrap();
    let status = res.status();
    let bytes = res.into_body().collect().await.unwrap().to_bytes();
    let v = serde_json::from_slice(&bytes).unwrap_or(serde_json::Value::String(
        String::from_utf8_lossy(&bytes).into(),
    ));
    (status, v)
}

/// Item 15: the studio echoed `{"min_score": 1e300}` as a 301-digit number
/// and `time_limit: 1e-300` with 300 zeros; `learn --cutoff 1e-300` wrote a
/// 358-character header line. Echoed numbers are written as the CLI writes
/// them (`1e300`), and an ordinary cutoff is written as before.
#[tokio::test]
async fn echoed_numbers_stay_short() {
    use axum::http::{Method, StatusCode};
    let dir = example_copy(
        "harden3-numbers",
        "box-packing",
        &["problem.json", "demos.json"],
    );
    let app = rccpack::studio::router(&dir).unwrap();
    for (uri, body, field) in [
        (
            "/api/sample",
            r#"{"rules": "", "min_score": 1e300}"#,
            "min_score",
        ),
        (
            "/api/synth",
            r#"{"rules": "", "time_limit": 1e-300}"#,
            "time_limit",
        ),
        (
            "/api/synth",
            r#"{"rules": "", "time_limit": 1e300}"#,
            "time_limit",
        ),
    ] {
        let (s, v) = studio_call(&app, Method::POST, uri, body.into()).await;
        assert_eq!(s, StatusCode::BAD_REQUEST, "{body}: {v}");
        let e = v["error"].as_str().unwrap();
        assert!(e.contains(field) && e.len() < 150, "{body}: {e}");
        assert!(e.contains("e300") || e.contains("e-300"), "{body}: {e}");
    }
    let demos = dir.join("demos.json");
    for (cutoff, line) in [
        ("1e-300", "cutoff 1e-300, prior"),
        ("0.01", "cutoff 0.01, prior"),
    ] {
        let out = dir.join("learned.rcc");
        let o = rccpack(&[
            "learn",
            &demos.to_string_lossy(),
            "--samples",
            "100",
            "--cutoff",
            cutoff,
            "-o",
            &out.to_string_lossy(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let text = std::fs::read_to_string(&out).unwrap();
        let header = text.lines().find(|l| l.contains("cutoff")).unwrap();
        assert!(header.contains(line) && header.len() < 100, "{header}");
    }
}

/// Item 12: a group statement where the grammar does not take it got
/// "expected `,`, found `)`"; the error says what is wrong, and a keyword
/// in capitals is named in lowercase.
#[test]
fn misplaced_group_statements_are_explained() {
    let d = scratch("harden3-misplaced-group");
    for body in [
        "(group(R))",
        "!(row(R))",
        "some R: group(R)",
        "not (column(R))",
    ] {
        let r = write_file(&d, "r.rcc", &format!("rule g: {body}\n"));
        let o = rccpack(&["check", &r]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{body}: {e}");
        assert!(
            e.contains("stands alone as a rule's whole formula") && !e.contains("expected `,`"),
            "{body}: {e}"
        );
    }
    let r = write_file(&d, "r.rcc", "rule g: GROUP(R)\n");
    let o = rccpack(&["check", &r]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("`GROUP`") && e.contains("write `group`"), "{e}");
    // What the grammar takes still parses.
    let r = write_file(&d, "r.rcc", "rule g: not group(R)\nrule h: !row(R)\n");
    let o = rccpack(&["check", &r]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// Item 14: `render` of an empty demonstrations array suggested
/// `--index 0..0`; it says the array is empty.
#[test]
fn render_of_an_empty_array_says_it_is_empty() {
    let d = scratch("harden3-render-empty");
    let p = write_file(&d, "demos.json", "[]");
    for extra in [&[][..], &["--index", "0"][..]] {
        let mut args = vec!["render", &p, "-o", "/dev/null"];
        args.extend_from_slice(extra);
        let o = rccpack(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{e}");
        assert!(
            e.contains("empty demonstrations array") && !e.contains("0..0"),
            "{e}"
        );
    }
}

/// Smaller findings: a negative value after a numeric flag is reported as
/// out of range or invalid, not as an unknown argument `-0`.
#[test]
fn negative_flag_values_are_reported_as_values() {
    let d = scratch("harden3-negative");
    let p = write_file(&d, "p.json", &r_problem(2));
    let r = write_file(&d, "r.rcc", "rule g: group(R)\n");
    let demos = write_file(&d, "demos.json", &format!("[{}]", r_problem(2)));
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "sample",
            &p,
            "--rules",
            &r,
            "-n",
            "1",
            "--min-score",
            "-0.1",
        ],
        vec!["learn", &demos, "--cutoff", "-0.5"],
        vec!["learn", &demos, "--prior", "-0.5"],
        vec!["learn", &demos, "--samples", "-3"],
        vec!["render", &p, "-o", "/dev/null", "--scale", "-2"],
    ];
    for args in cases {
        let o = rccpack(&args);
        let e = stderr(&o);
        assert!(matches!(o.status.code(), Some(1 | 2)), "{args:?}: {e}");
        assert!(!e.contains("unexpected argument"), "{args:?}: {e}");
        let flag_value = args[args.len() - 1];
        assert!(e.contains(flag_value), "{args:?}: {e}");
    }
}

/// Smaller findings: a repeated `version` parameter on
/// `DELETE /api/demos/{i}` answered plain text; it answers JSON naming it.
#[tokio::test]
async fn a_repeated_delete_version_answers_json() {
    use axum::http::{Method, StatusCode};
    let dir = example_copy(
        "harden3-delete-version",
        "box-packing",
        &["problem.json", "demos.json"],
    );
    let before = std::fs::read_to_string(dir.join("demos.json")).unwrap();
    let app = rccpack::studio::router(&dir).unwrap();
    let (s, v) = studio_call(
        &app,
        Method::DELETE,
        "/api/demos/0?version=a&version=b",
        String::new(),
    )
    .await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    let e = v["error"].as_str().expect("a JSON error");
    assert!(e.contains("version") && e == e.to_lowercase(), "{e}");
    assert_eq!(v["path"], "version");
    assert_eq!(
        std::fs::read_to_string(dir.join("demos.json")).unwrap(),
        before
    );
}

/// A task folder `name` in `d` for `priors`: the bundled example's
/// demonstrations and its pilot rules as `learned.rcc`.
fn priors_task(d: &Path, name: &str) -> PathBuf {
    let t = d.join(name);
    std::fs::create_dir_all(&t).unwrap();
    let src = crate::support::example("box-packing");
    std::fs::copy(src.join("demos.json"), t.join("demos.json")).unwrap();
    std::fs::copy(src.join("pilot.rcc"), t.join("learned.rcc")).unwrap();
    t
}

/// Item 5: outputs overwrite inputs. `priors -o` naming a task's
/// `learned.rcc` or `demos.json` or the `@LIST` file, and `run --out OUT`
/// with `--like`/`--priors` naming a file `run` writes in OUT, are refused
/// before anything is read or written, naming both paths.
#[test]
fn priors_and_run_never_write_over_their_inputs() {
    let d = scratch("harden3-outputs-inputs");
    let t = priors_task(&d, "t");
    let ts = t.to_str().unwrap();
    let list = write_file(&d, "list.txt", &format!("{ts}\n"));
    let at_list = format!("@{list}");
    let learned = t.join("learned.rcc");
    let demos = t.join("demos.json");
    let (l, m) = (learned.to_str().unwrap(), demos.to_str().unwrap());
    let before = |p: &str| std::fs::read(p).unwrap();
    let (lb, mb, listb) = (before(l), before(m), before(&list));
    let out = d.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let solution = write_file(&out, "solution.json", "{}");
    let report = write_file(&out, "learn-report.json", "{}");
    let os = out.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["priors", ts, "-o", l], l),
        (vec!["priors", ts, "-o", m], m),
        (vec!["priors", &at_list, "-o", &list], &list),
        (vec!["run", ts, "--out", os, "--like", &solution], &solution),
        (vec!["run", ts, "--out", os, "--priors", &report], &report),
        (vec!["run", ts, "--priors", l], l),
    ];
    for (args, input) in cases {
        let start = Instant::now();
        let o = rccpack(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(e.contains("the same file as"), "{args:?}: {e}");
        assert!(e.matches(input).count() >= 1, "{args:?}: {e}");
        assert!(start.elapsed() < Duration::from_secs(10), "{args:?}");
    }
    assert_eq!((before(l), before(m), before(&list)), (lb, mb, listb));
    assert_eq!(std::fs::read_to_string(&solution).unwrap(), "{}");
    assert_eq!(std::fs::read_to_string(&report).unwrap(), "{}");
    assert!(!out.join("learned.rcc").exists());
}

/// The `"tasks"` count of a priors file.
fn priors_tasks(text: &str) -> u64 {
    let v: serde_json::Value = serde_json::from_str(text).unwrap();
    v["library"]["tasks"].as_u64().unwrap()
}

/// Item 6: `priors` counted a folder once per mention (`T T`, `T ./T/`, a
/// repeated `@LIST` line); each folder counts once, with a note.
#[test]
fn priors_counts_each_folder_once() {
    let d = scratch("harden3-priors-once");
    let t = priors_task(&d, "t");
    let u = priors_task(&d, "u");
    let ts = t.to_str().unwrap().to_string();
    let us = u.to_str().unwrap().to_string();
    let dotted = format!("{}/./t/", d.display());
    let list = write_file(&d, "list.txt", &format!("{ts}\n{us}\n{ts}\n"));
    let at_list = format!("@{list}");
    let base = rccpack(&["priors", &ts, &us]);
    assert!(base.status.success(), "{}", stderr(&base));
    assert_eq!(priors_tasks(&crate::support::stdout(&base)), 2);
    for args in [
        vec!["priors", &ts, &us, &ts],
        vec!["priors", &ts, &dotted, &us],
        vec!["priors", &at_list],
    ] {
        let o = rccpack(&args);
        let e = stderr(&o);
        assert!(o.status.success(), "{args:?}: {e}");
        assert_eq!(
            crate::support::stdout(&o),
            crate::support::stdout(&base),
            "{args:?}"
        );
        assert!(
            e.contains("counted once") && e.contains("/t"),
            "{args:?}: {e}"
        );
    }
}

/// Item 8: the `@LIST` file of `priors`, scene files and `--priors` files
/// are read with a bound, as rule files are: an endless device is refused
/// at once (exit 1) naming the file and the limit, not read until the
/// memory runs out.
#[cfg(target_os = "linux")]
#[test]
fn endless_inputs_are_refused_while_reading() {
    let demos = crate::support::example("box-packing").join("demos.json");
    let demos = demos.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["priors", "@/dev/zero"], "16 MiB"),
        (vec!["learn", demos, "--priors", "/dev/zero"], "16 MiB"),
        (vec!["render", "/dev/zero", "-o", "/dev/null"], "256 MiB"),
    ];
    for (args, limit) in cases {
        let start = Instant::now();
        let o = rccpack(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(
            e.contains("/dev/zero") && e.contains(limit),
            "{args:?}: {e}"
        );
        assert!(start.elapsed() < Duration::from_secs(10), "{args:?}");
    }
}
