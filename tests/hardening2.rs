//! More hardening, through the built binary: what a hostile but fair user
//! tries, and what the tool must answer.

use crate::support::{example_copy, rccpack, scratch, stderr, stdout, write_file};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::{Duration, Instant};

/// A copy of the bundled example's task folder.
fn example_task(tag: &str) -> PathBuf {
    example_copy(
        &format!("harden2-{tag}"),
        "box-packing",
        &["problem.json", "demos.json"],
    )
}

/// A 100×100 scene with one 10×10 object per `(id, class, x, y)`.
fn scene(objects: &[(&str, &str, i64, i64)]) -> String {
    let o: Vec<String> = objects
        .iter()
        .map(|(id, c, x, y)| {
            format!(
                r#"{{"id": "{id}", "class": "{c}", "x": {x}, "y": {y}, "width": 10, "height": 10}}"#
            )
        })
        .collect();
    format!(
        r#"{{"space": {{"width": 100, "height": 100}}, "grid": 10, "objects": [{}]}}"#,
        o.join(", ")
    )
}

const PILOT: &str = "examples/box-packing/pilot.rcc";

/// Item 1: an oracle that fails (a mistyped rules path in the README's
/// ready-made oracle, a script that crashes with exit 1 and an error on
/// stderr) aborts `ask` and confirms nothing.
#[test]
fn a_failing_oracle_confirms_nothing() {
    let task = example_task("oracle-fails");
    let t = task.to_str().unwrap();
    for oracle in [
        format!(
            "{} score --rules no-such-rules.rcc --require",
            env!("CARGO_BIN_EXE_rccpack")
        ),
        "sh -c 'echo \"Traceback: boom\" >&2; exit 1'".to_string(),
    ] {
        let o = rccpack(&["ask", t, "--oracle", &oracle, "--samples", "200"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{oracle}: {e}");
        assert!(e.contains("failed rather than answered"), "{e}");
        assert!(!stdout(&o).contains("not acceptable"), "{}", stdout(&o));
        if let Ok(a) = std::fs::read_to_string(task.join("answers.json")) {
            let v: serde_json::Value = serde_json::from_str(&a).unwrap();
            assert_eq!(v["answers"], serde_json::json!([]), "{a}");
        }
    }
    // A silent exit 1 is still "not acceptable".
    let o = rccpack(&[
        "ask",
        t,
        "--oracle",
        "false",
        "--samples",
        "200",
        "--max-questions",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // About one rule: confirmed; about a group (the box's first question):
    // one of them is meant.
    assert!(stdout(&o).contains("not acceptable"), "{}", stdout(&o));
}

/// Item 2: one rule for classes a scene lacks. A class some scene the
/// command reads has (here: the other demonstration) is a note and its
/// rules hold vacuously; so is any class of a learned file; a hand-written
/// class no scene has is refused, naming the closest class.
#[test]
fn absent_classes_are_one_rule_everywhere() {
    let d = scratch("harden2-absent2");
    let both = scene(&[("r0", "red", 0, 0), ("g0", "green", 0, 10)]);
    let reds = scene(&[("r0", "red", 0, 0)]);
    let demos = write_file(&d, "demos.json", &format!("[{both}, {reds}]"));
    let only_red = write_file(&d, "red.json", &reds);
    let hand = write_file(&d, "hand.rcc", "rule g_on_r: EC_N(green, red)\n");
    let learned = write_file(
        &d,
        "learned.rcc",
        "# learned by rccpack from 2 demonstrations: 1 of 1 candidates out of 1 statements (given)\n\nrule g_on_r: EC_N(green, red)\n",
    );
    let o = rccpack(&["score", &demos, "--rules", &hand]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).contains("note:") && stderr(&o).contains("green"));
    let o = rccpack(&["check", &hand, "--scene", &demos]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for args in [
        vec!["score", &only_red, "--rules", &learned],
        vec!["check", &learned, "--scene", &only_red],
        vec!["score", &only_red, "--rules", &learned, "--require"],
    ] {
        let o = rccpack(&args);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("no objects of class green"),
            "{}",
            stderr(&o)
        );
    }
    let svg = d.join("red.svg");
    let o = rccpack(&[
        "render",
        &only_red,
        "--rules",
        &learned,
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // Hand-written, and in no scene read: the likely misspelling.
    let o = rccpack(&["score", &only_red, "--rules", &hand]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("unknown class `green`"),
        "{}",
        stderr(&o)
    );
    let typo = write_file(&d, "typo.rcc", "rule g_on_r: EC_N(gren, red)\n");
    let o = rccpack(&["check", &typo, "--scene", &demos]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("did you mean `green`?"),
        "{}",
        stderr(&o)
    );
}

/// A hand-curated learned.rcc: one rule confirmed, one written by hand.
const CURATED: &str = "# my rules\n\n# confirmed\nrule mine: EC_N(R, *) | !EC_N(R, *)\n";

/// Item 3: `run` checks its inputs before it writes, respects the folder
/// lock, and never drops a curated `learned.rcc` (kept as a backup).
#[test]
fn run_never_destroys_curated_rules() {
    let task = example_task("run-curated");
    let t = task.to_str().unwrap();
    std::fs::write(task.join("learned.rcc"), CURATED).unwrap();
    let good = std::fs::read_to_string(task.join("problem.json")).unwrap();
    std::fs::write(task.join("problem.json"), "{\"space\": 3}").unwrap();
    let o = rccpack(&["run", t, "--samples", "200", "--time-limit", "5"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("problem.json"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(task.join("learned.rcc")).unwrap(),
        CURATED
    );
    std::fs::write(task.join("problem.json"), &good).unwrap();
    {
        let _held = rccpack::fsutil::DirLock::try_lock(&task).unwrap().unwrap();
        let o = rccpack(&["run", t, "--samples", "200", "--time-limit", "5"]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(
            stderr(&o).contains("another `rccpack ask`"),
            "{}",
            stderr(&o)
        );
        assert!(!task.join("solution.json").exists());
    }
    let o = rccpack(&["run", t, "--samples", "200", "--time-limit", "5"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("learned.rcc.bak"), "{}", stdout(&o));
    assert_eq!(
        std::fs::read_to_string(task.join("learned.rcc.bak")).unwrap(),
        CURATED
    );
    assert!(std::fs::read_to_string(task.join("learned.rcc"))
        .unwrap()
        .starts_with("# learned by rccpack"));
}

/// Item 5: Ctrl-C while `ask` relearns from an accepted probe keeps that
/// answer: the journal is written first. The oracle accepts and has a
/// process outside its group send the Ctrl-C a moment later, while the
/// answer is relearned.
#[cfg(unix)]
#[test]
fn ctrl_c_while_relearning_keeps_the_answer() {
    let task = example_task("relearn-int");
    let oracle = "setsid sh -c \"sleep 0.3; kill -INT $PPID\" >/dev/null 2>&1 & true";
    let o = crate::support::command()
        .args([
            "ask",
            task.to_str().unwrap(),
            "--oracle",
            oracle,
            "--samples",
            "20000",
        ])
        .output()
        .unwrap();
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("interrupted"), "{e}");
    let a = std::fs::read_to_string(task.join("answers.json")).expect("the answer is journaled");
    let v: serde_json::Value = serde_json::from_str(&a).unwrap();
    let answers = v["answers"].as_array().unwrap();
    // (On a fast machine a second answer may be journaled before the
    // signal arrives.)
    assert!(!answers.is_empty(), "{a}");
    assert_eq!(answers[0]["accepted"], true, "{a}");
}

/// Item 7: a full standard error never panics (exit 101): the command's
/// own exit code stands.
#[cfg(unix)]
#[test]
fn a_full_stderr_never_panics() {
    let d = scratch("harden2-full-stderr");
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap()
    };
    let run = |args: &[&str]| {
        crate::support::command()
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdout(Stdio::null())
            .stderr(full())
            .status()
            .unwrap()
            .code()
    };
    let sol = d.join("sol.json");
    let svg = d.join("p.svg");
    let problem = write_file(&d, "p.json", &scene(&[("r0", "R", 0, 0)]));
    let free = write_file(
        &d,
        "free.json",
        r#"{"space": {"width": 40, "height": 40}, "grid": 10, "objects": [{"id": "r0", "class": "R", "width": 10, "height": 10}]}"#,
    );
    let rules = write_file(&d, "r.rcc", "rule t: EC_N(R, *) | !EC_N(R, *)\n");
    assert_eq!(
        run(&[
            "synth",
            &free,
            "--rules",
            &rules,
            "-o",
            sol.to_str().unwrap()
        ]),
        Some(0)
    );
    assert!(sol.exists());
    assert_eq!(
        run(&["render", &problem, "-o", svg.to_str().unwrap()]),
        Some(0)
    );
    assert_eq!(run(&["check", "no-such.rcc"]), Some(1));
    assert_eq!(run(&["score", &problem, "--rules", "no-such.rcc"]), Some(1));
    // `--help` that cannot be written is not a success.
    let o = crate::support::command()
        .arg("--help")
        .stdout(full())
        .status()
        .unwrap();
    assert_eq!(o.code(), Some(1));
}

/// Item 9: ids with U+FFFE/U+FFFF (not XML characters) still draw a
/// well-formed SVG and a PNG.
#[test]
fn non_characters_draw() {
    let d = scratch("harden2-fffe");
    let p = write_file(
        &d,
        "s.json",
        &scene(&[("a\u{fffe}b", "R", 0, 0), ("c\u{ffff}", "G", 20, 0)]),
    );
    let svg = d.join("s.svg");
    let png = d.join("s.png");
    for out in [&svg, &png] {
        let o = rccpack(&["render", &p, "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(!text.contains('\u{fffe}') && !text.contains('\u{ffff}'));
    assert!(text.contains('\u{fffd}'));
}

/// Item 10: integer weights are reduced by their common factor before the
/// size check; weights too large even then are blamed on the rule file.
#[test]
fn weights_are_reduced_before_the_size_check() {
    let d = scratch("harden2-weights");
    let p = write_file(
        &d,
        "p.json",
        r#"{"space": {"width": 40, "height": 40}, "grid": 10, "objects": [{"id": "r0", "class": "R", "width": 10, "height": 10}, {"id": "r1", "class": "R", "width": 10, "height": 10}]}"#,
    );
    let big = write_file(
        &d,
        "big.rcc",
        "rule a weight 1000000000: EC_N(R, *)\nrule b weight 2000000000: DR_N(R, *) | DR_S(R, *)\n",
    );
    let o = rccpack(&["synth", &p, "--rules", &big, "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let odd = write_file(
        &d,
        "odd.rcc",
        "rule a weight 1000000000: EC_N(R, *)\nrule b weight 1000000001: DR_N(R, *) | DR_S(R, *)\n",
    );
    let o = rccpack(&["synth", &p, "--rules", &odd, "--quiet"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("odd.rcc") && !e.contains("p.json"), "{e}");
    assert!(e.contains("weights are too large"), "{e}");
    let o = rccpack(&["sample", &p, "--rules", &odd, "-n", "1", "--quiet"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("odd.rcc") && !e.contains("p.json"), "{e}");
}

/// Item 12: values echoed in errors are cut (60 characters and `…`).
#[test]
fn echoed_values_are_cut() {
    let d = scratch("harden2-echo");
    let long = "x".repeat(100_000);
    let p = write_file(&d, "p.json", &scene(&[("r0", "R", 0, 0)]));
    let mut rules = String::new();
    for i in 0..30 {
        rules.push_str(&format!("rule r{i}: EC_N({long}, R)\n"));
    }
    let r = write_file(&d, "r.rcc", &rules);
    let o = rccpack(&["score", &p, "--rules", &r]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("unknown class"),
        "{}",
        &stderr(&o)[..200]
    );
    assert!(o.stderr.len() < 100_000, "{} bytes", o.stderr.len());
    let dup = write_file(
        &d,
        "dup.rcc",
        &format!("rule {long}: EC_N(R, *)\nrule {long}: EC_N(R, *)\n"),
    );
    let o = rccpack(&["check", &dup]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("duplicate rule name"),
        "{}",
        &stderr(&o)[..200]
    );
    assert!(o.stderr.len() < 20_000, "{} bytes", o.stderr.len());
    let rel = write_file(&d, "rel.rcc", &format!("rule a: {long}(R, R)\n"));
    let o = rccpack(&["check", &rel]);
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stderr.len() < 20_000, "{} bytes", o.stderr.len());
    let land = write_file(&d, "land.rcc", &format!("rule a: EC_N(R, @{long})\n"));
    let o = rccpack(&["check", &land, "--scene", &p]);
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stderr.len() < 20_000, "{} bytes", o.stderr.len());
    let o = rccpack(&["learn", &p, "--cutoff=-1e-320"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("-1e-320") && e.len() < 200, "{e}");
}

/// Item 13: files with old Mac line ends (`\r` alone) are located by line
/// as an editor shows them.
#[test]
fn cr_line_ends_are_counted() {
    let d = scratch("harden2-cr");
    let p = write_file(
        &d,
        "p.json",
        "{\r  \"space\": {\"width\": 100, \"height\": 100},\r  \"grid\": 10,\r  \"objects\": [\r    {\"id\": \"r0\", \"class\": \"R\", \"width\": 10, \"height\": true}\r  ]\r}\r",
    );
    let o = rccpack(&["score", &p, "--rules", PILOT]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("line 5"), "{e}");
    let bad = d.join("bad.rcc");
    std::fs::write(&bad, b"rule a: EC_N(R, *)\rrule b: EC_N(R, *)\r# \xff\r").unwrap();
    let o = rccpack(&["check", bad.to_str().unwrap()]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("(line 3)"), "{e}");
}

/// Item 14: SIGTERM and SIGHUP are handled like Ctrl-C: a command that
/// cannot stop cleanly removes the temporary files of its writes in flight
/// and exits 1 with a message (it is not killed half-way through a write);
/// `synth` stops the search and writes the best layout found, whole.
#[cfg(unix)]
#[test]
fn sigterm_and_sighup_are_handled() {
    let d = scratch("harden2-sigterm");
    let demos = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing/demos.json");
    let stray = || -> Vec<_> {
        std::fs::read_dir(&d)
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
            .collect()
    };
    for sig in [libc::SIGTERM, libc::SIGHUP] {
        let child = crate::support::command()
            .arg("learn")
            .arg(&demos)
            .args(["--samples", "1000000", "-o"])
            .arg(d.join("l.rcc"))
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(700));
        // SAFETY: a signal to the child this test started.
        unsafe {
            libc::kill(child.id() as i32, sig);
        }
        let o = child.wait_with_output().unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "signal {sig}: {:?} {e}", o.status);
        assert!(e.contains("interrupted by a signal"), "{e}");
        assert!(stray().is_empty(), "{:?}", stray());
    }
}

/// Item 15: an output that is an input or another output is refused before
/// anything is written.
#[test]
fn outputs_never_overwrite_inputs() {
    let d = scratch("harden2-same-file");
    let p = write_file(&d, "p.json", &scene(&[("r0", "R", 0, 0)]));
    let rules_text = "rule t: EC_N(R, *) | !EC_N(R, *)\n";
    let r = write_file(&d, "r.rcc", rules_text);
    let x = d.join("x.rcc");
    let x = x.to_str().unwrap();
    let y = d.join("y.json").to_str().unwrap().to_string();
    let demos = write_file(
        &d,
        "demos.json",
        &format!("[{}]", scene(&[("r0", "R", 0, 0)])),
    );
    let cases: Vec<Vec<&str>> = vec![
        vec!["learn", &demos, "-o", x, "--report", x],
        vec!["learn", &demos, "-o", &demos],
        vec!["synth", &p, "--rules", &r, "-o", &r],
        vec!["synth", &p, "--rules", &r, "-o", &y, "--emit", &y],
        vec!["synth", &p, "--rules", &r, "--report", &p],
        vec!["render", &p, "-o", &p],
        vec!["sample", &p, "--rules", &r, "-n", "1", "-o", &r],
    ];
    for args in cases {
        let o = rccpack(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(e.contains("the same file as"), "{args:?}: {e}");
    }
    assert_eq!(std::fs::read_to_string(&r).unwrap(), rules_text);
    assert!(!Path::new(x).exists() && !Path::new(&y).exists());
    // Devices may be shared.
    let o = rccpack(&[
        "synth",
        &p,
        "--rules",
        &r,
        "-o",
        "/dev/null",
        "--report",
        "/dev/null",
        "--quiet",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// The smaller findings: a rule file's size limit applies while reading
/// (`check /dev/zero` is refused at once, not after filling the memory).
#[cfg(unix)]
#[test]
fn endless_rule_files_are_refused_while_reading() {
    let start = Instant::now();
    let o = rccpack(&["check", "/dev/zero"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("larger than 16777216 bytes"), "{e}");
    assert!(start.elapsed() < Duration::from_secs(10));
}

/// `n` unplaced 10×10 blocks of class R above a fixed base, with a rule
/// about the base only (no rule needs a pair of blocks): what is left of
/// the model's size is non-overlap.
fn base_problem(n: usize) -> String {
    let side = 10 * ((2 * n) as f64).sqrt().ceil() as i64 + 20;
    let mut objects = vec![format!(
        r#"{{"id": "base", "class": "W", "x": 0, "y": 0, "width": {side}, "height": 10, "fixed": true}}"#
    )];
    objects.extend(
        (0..n).map(|i| format!(r#"{{"id": "r{i}", "class": "R", "width": 10, "height": 10}}"#)),
    );
    format!(
        r#"{{"space": {{"width": {side}, "height": {side}}}, "grid": 10, "objects": [{}]}}"#,
        objects.join(", ")
    )
}

/// Peak resident memory (KiB) and exit code of one `rccpack` run.
#[cfg(target_os = "linux")]
#[allow(clippy::zombie_processes)] // waited for by `wait4`, below
fn peak_kib(args: &[&str]) -> (i64, Option<i32>) {
    let child = crate::support::command()
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut status = 0;
    // SAFETY: an all-zero rusage is valid; wait4 on the child this
    // function started, which std has not waited for.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let pid = unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    assert!(pid > 0);
    let code = libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status));
    (usage.ru_maxrss, code)
}

/// Item 6: `synth`'s memory grows about linearly with the objects when no
/// rule relates them pairwise (it grew with the square: 503 MB at 200
/// movable objects, 2 GB at 400). Measured as a ratio, 2n objects against
/// n.
#[cfg(target_os = "linux")]
#[test]
fn synth_memory_is_near_linear_in_the_objects() {
    let d = scratch("harden2-memory");
    let rules = write_file(&d, "r.rcc", "rule above: DR_N(R, @base)\n");
    let mut peaks = Vec::new();
    for n in [150, 300] {
        let p = write_file(&d, &format!("p{n}.json"), &base_problem(n));
        let (kib, code) = peak_kib(&[
            "synth",
            &p,
            "--rules",
            &rules,
            "--node-limit",
            "3000",
            "--time-limit",
            "5",
            "--quiet",
            "-o",
            "/dev/null",
        ]);
        assert_eq!(code, Some(0), "{n} objects");
        peaks.push(kib as f64);
    }
    let ratio = peaks[1] / peaks[0];
    assert!(
        ratio < 2.5,
        "peak memory {} KiB at 150 objects, {} KiB at 300: ratio {ratio:.2}",
        peaks[0],
        peaks[1]
    );
}

/// Item 6, the other half: rules that relate too many pairs of objects are
/// refused at once with exit 1 and a message, before the memory runs out
/// (400 objects under `EC_N(R, *)`: 160 000 pair literals, about 2 GB).
#[test]
fn too_many_rule_pairs_are_refused_at_once() {
    let d = scratch("harden2-pairs");
    let p = write_file(&d, "p.json", &base_problem(400));
    let r = write_file(&d, "r.rcc", "rule t: EC_N(R, *)\n");
    let start = Instant::now();
    let o = rccpack(&["synth", &p, "--rules", &r, "--quiet"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("pairs of objects") && e.contains("120000"),
        "{e}"
    );
    assert!(start.elapsed() < Duration::from_secs(5));
}
