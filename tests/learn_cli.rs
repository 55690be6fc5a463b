//! `rccpack learn` on the command line: output, report, exit codes and
//! messages.

use crate::support::{example_copy, rccpack, read, scratch, stderr, write_file};

fn demos() -> String {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/box-packing/demos.json"
    )
    .to_string()
}

#[test]
fn learn_writes_rules_and_report_that_score_reads() {
    let dir = scratch("learn-cli-learn_writes_rules_and_report_that_score_reads");
    let out = dir.join("learned.rcc");
    let report = dir.join("report.json");
    let o = rccpack(&[
        "learn",
        &demos(),
        "--samples",
        "200",
        "--templates",
        "second",
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
    let o = rccpack(&[
        "learn",
        &demos(),
        "--samples",
        "100",
        "--seed",
        "3",
        "--templates",
        "second",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.starts_with("# learned by rccpack from 8 demonstrations"));
    assert!(rccpack::rules::parse_rules(&text).is_ok());
}

#[test]
fn learn_with_a_statement_file() {
    let dir = scratch("learn-cli-learn_with_a_statement_file");
    let st = write_file(
        &dir,
        "statements.rcc",
        "rule blue_north: DR_N(B, R)\nrule blue_south: DR_S(B, R)\n",
    );
    let o = rccpack(&["learn", &demos(), "--statements", &st]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("rule blue_north p "), "{text}");
    assert!(!text.contains("rule blue_south"), "{text}");
}

#[test]
fn statement_file_with_an_unknown_class_is_located() {
    let dir = scratch("learn-cli-statement_file_with_an_unknown_class_is_located");
    let st = write_file(
        &dir,
        "unknown.rcc",
        "rule ok: DR_N(B, R)\nrule bad: DR_N(B, Q)\n",
    );
    let o = rccpack(&["learn", &demos(), "--statements", &st]);
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
    let dir = scratch("learn-cli-empty_demonstrations_exit_1");
    let p = write_file(&dir, "empty.json", "[]");
    let o = rccpack(&["learn", &p]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("no demonstrations"), "{}", stderr(&o));
}

fn fixture(name: &str) -> String {
    read(format!("tests/fixtures/first-edition/{name}"))
}

/// `--templates first` keeps the first edition's output byte for byte: the
/// goldens in `tests/fixtures/first-edition/` were written by the binary
/// of commit 03cf7e0 (before the second-edition templates).
#[test]
fn templates_first_is_byte_identical_to_the_first_edition() {
    let dir = scratch("learn-cli-templates_first_is_byte_identical_to_the_first_edition");
    let cases: [(&[&str], &str, &str); 2] = [
        (&[], "learned.rcc", "report.json"),
        (
            &["--contact", "edge", "--seed", "3", "--samples", "300"],
            "learned-edge-s3.rcc",
            "report-edge-s3.json",
        ),
    ];
    for (i, (extra, rcc, report)) in cases.into_iter().enumerate() {
        let out = dir.join(format!("first-{i}.rcc"));
        let rep = dir.join(format!("first-{i}.json"));
        let d = demos();
        let mut args = vec![
            "learn",
            d.as_str(),
            "--templates",
            "first",
            "-o",
            out.to_str().unwrap(),
            "--report",
            rep.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = rccpack(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(
            std::fs::read_to_string(&out).unwrap() == fixture(rcc),
            "{rcc} differs"
        );
        assert!(
            std::fs::read_to_string(&rep).unwrap() == fixture(report),
            "{report} differs"
        );
    }
}

/// `run --templates first` learns the same file as `learn --templates first`.
#[test]
fn run_accepts_templates_first() {
    let dir = example_copy(
        "learn-cli-run-templates-first",
        "box-packing",
        &["demos.json", "problem.json"],
    );
    let o = rccpack(&[
        "run",
        dir.to_str().unwrap(),
        "--templates",
        "first",
        "--time-limit",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(dir.join("learned.rcc")).unwrap() == fixture("learned.rcc"));
    assert!(
        std::fs::read_to_string(dir.join("learn-report.json")).unwrap() == fixture("report.json")
    );
}

/// The default is the third edition (`--templates third` says so
/// explicitly); `second` is the second edition's set without group
/// statements; an unknown set is refused.
#[test]
fn templates_third_is_the_default() {
    let d = demos();
    let a = rccpack(&["learn", &d, "--samples", "100"]);
    let b = rccpack(&["learn", &d, "--samples", "100", "--templates", "third"]);
    assert!(a.status.success() && b.status.success(), "{}", stderr(&a));
    assert_eq!(a.stdout, b.stdout);
    let text = String::from_utf8(a.stdout).unwrap();
    assert!(
        text.lines()
            .next()
            .unwrap()
            .ends_with("(templates, third edition)"),
        "{text}"
    );
    assert!(text.contains(", scene-level 0.005\n"), "{text}");
    let s = rccpack(&["learn", &d, "--samples", "100", "--templates", "second"]);
    let s = String::from_utf8(s.stdout).unwrap();
    assert!(s
        .lines()
        .next()
        .unwrap()
        .ends_with("(templates, second edition)"));
    assert!(!s.contains("group(") && !s.contains("column(") && !s.contains("row("));
    let o = rccpack(&["learn", &d, "--templates", "fourth"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("fourth"), "{}", stderr(&o));
}

/// The `[default: …]` `--help` shows for `flag` (the text from the flag to
/// the next option, in case the help is wrapped).
fn help_default(help: &str, flag: &str) -> Option<String> {
    let at = help.find(&format!("--{flag} <"))?;
    let rest = &help[at..];
    let end = rest[2..].find("\n  ").map_or(rest.len(), |e| e + 2);
    let item = &rest[..end];
    let d = item.find("[default: ")? + "[default: ".len();
    Some(item[d..d + item[d..].find(']')?].to_string())
}

#[test]
fn learning_flags_default_to_the_library_defaults() {
    let p = rccpack::infer::LearnParams::default();
    let expected = [
        ("samples", p.samples.to_string()),
        ("cutoff", p.cutoff.to_string()),
        ("prior", p.prior.to_string()),
        ("seed", p.seed.to_string()),
        ("contact", p.contact.to_string()),
        ("templates", p.templates.to_string()),
        ("slip-rate", p.slip_rate.to_string()),
    ];
    for command in ["learn", "run", "ask"] {
        let o = rccpack(&[command, "--help"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let help = String::from_utf8(o.stdout).unwrap();
        let mut seen = 0;
        for (flag, value) in &expected {
            // `--prior` is `learn`'s alone.
            if *flag == "prior" && command != "learn" {
                assert_eq!(help_default(&help, flag), None, "{command} --{flag}");
                continue;
            }
            assert_eq!(
                help_default(&help, flag).as_deref(),
                Some(value.as_str()),
                "`rccpack {command} --{flag}` shows another default than LearnParams::default()\n{help}"
            );
            seen += 1;
        }
        assert!(seen >= 6, "{command}: {seen} flags checked");
    }
    // `priors` counts the candidates learning finds by default, and its
    // own flags default to the estimator's.
    let q = rccpack::priors::PriorParams::default();
    let o = rccpack(&["priors", "--help"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let help = String::from_utf8(o.stdout).unwrap();
    for (flag, value) in [
        ("strength", q.strength.to_string()),
        ("rule-out-after", q.rule_out_after.to_string()),
        ("templates", p.templates.to_string()),
        ("contact", p.contact.to_string()),
    ] {
        // This help is in clap's long layout: the text on the next lines.
        let at = help.find(&format!("--{flag} <")).expect(flag);
        let item = &help[at..];
        let item = &item[..item[2..].find("\n  -").map_or(item.len(), |e| e + 2)];
        assert!(
            item.contains(&format!("[default: {value}]")),
            "`rccpack priors --{flag}` shows another default than the library's\n{help}"
        );
    }
}

/// Hardening, third pass: demonstrations of one task share the grid
/// (docs/scenes.md); one on another grid is refused naming it, not learned
/// from.
#[test]
fn demonstrations_on_another_grid_are_refused() {
    let demos: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(crate::support::path("examples/box-packing/demos.json")).unwrap(),
    )
    .unwrap();
    let dir = crate::support::scratch("learn-cli-mismatch");
    type Change = Box<dyn Fn(&mut serde_json::Value)>;
    let cases: [(&str, Change, &str); 1] = [(
        "grid",
        Box::new(|d| d[2]["grid"] = serde_json::json!(5)),
        "demonstration [2] has grid 5, but demonstration [0] has grid 10",
    )];
    for (tag, change, expected) in cases {
        let mut d = demos.clone();
        change(&mut d);
        let f = crate::support::write_file(&dir, &format!("{tag}.json"), &d.to_string());
        let o = crate::support::rccpack(&["learn", &f, "--samples", "50"]);
        assert_eq!(o.status.code(), Some(1), "{tag}");
        let err = crate::support::stderr(&o);
        assert!(err.contains(expected), "{tag}: {err}");
    }
}
