//! Demonstrations as recorded (docs/guide.md#real-demonstrations): measured
//! positions snapped to the grid, slips weighed, suspects named.

use crate::support::{rccpack, scratch, stderr, write_file};
use rand::SeedableRng;
use rccpack::ask::{AskOptions, Asker};
use rccpack::infer::{learn, LearnParams};
use rccpack::scene::Scene;
use rccpack_bench::noisy;
use rccpack_bench::tasks::{generate_task, TasksConfig};
use std::time::Duration;

fn box_demos() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/box-packing/demos.json"
    ))
    .unwrap()
}

/// The bundled demonstrations with every movable block moved by up to
/// ±3 px in tenths (deterministic).
fn jittered_box_demos() -> String {
    let v: serde_json::Value = serde_json::from_str(&box_demos()).unwrap();
    let exact: Vec<serde_json::Value> = v.as_array().unwrap().clone();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    noisy::jittered(&exact, 3.0, 0.0, &mut rng).to_string()
}

#[test]
fn jittered_demonstrations_learn_what_the_exact_ones_learn() {
    let dir = scratch("measured-jittered");
    let jit = write_file(&dir, "jit.json", &jittered_box_demos());
    let exact = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/box-packing/demos.json"
    );
    let a = rccpack(&["learn", exact, "--samples", "200"]);
    let b = rccpack(&[
        "learn",
        &jit,
        "--samples",
        "200",
        "--report",
        dir.join("r.json").to_str().unwrap(),
    ]);
    assert!(a.status.success() && b.status.success(), "{}", stderr(&b));
    assert_eq!(a.stdout, b.stdout, "the same learned.rcc, byte for byte");
    let err = stderr(&b);
    assert!(err.contains("8 demonstrations as measured:"), "{err}");
    assert!(err.contains("objects moved by at most"), "{err}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("r.json")).unwrap()).unwrap();
    let moves = r["measured"]["moves"].as_array().expect("moves listed");
    assert!(!moves.is_empty());
    for m in moves {
        assert!(
            m["distance"].as_f64().unwrap() <= 3.0 * 2f64.sqrt() + 1e-9,
            "{m}"
        );
    }
    // Exact demonstrations: nothing printed, no `measured` in the report.
    assert!(stderr(&a).is_empty(), "{}", stderr(&a));
}

#[test]
fn tolerance_zero_reads_exactly_and_refuses_fractions() {
    let dir = scratch("measured-tolerance-zero");
    let jit = write_file(&dir, "jit.json", &jittered_box_demos());
    let o = rccpack(&["learn", &jit, "--samples", "50", "--tolerance", "0"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains("jit.json") && err.contains("floating point"),
        "{err}"
    );
}

#[test]
fn bad_measured_input_names_file_demonstration_objects_and_value() {
    let dir = scratch("measured-bad");
    let scene = |objects: &str| {
        format!(r#"[{{"space":{{"width":100,"height":100}},"objects":[{objects}]}}]"#)
    };
    // Two blocks recorded on top of each other: beyond any tolerance.
    let f = write_file(
        &dir,
        "overlap.json",
        &scene(
            r#"{"id":"a","class":"R","x":10,"y":0,"width":10,"height":10},{"id":"b","class":"R","x":10.4,"y":0,"width":10,"height":10}"#,
        ),
    );
    let o = rccpack(&["learn", &f, "--samples", "50"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    for want in ["overlap.json", "demonstration 0", "`a`", "`b`", "9.6 px"] {
        assert!(err.contains(want), "{want}: {err}");
    }
    // A string as a coordinate.
    let f = write_file(
        &dir,
        "string.json",
        &scene(r#"{"class":"R","x":"12.5","y":0,"width":10,"height":10}"#),
    );
    let o = rccpack(&["learn", &f, "--samples", "50"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains("string.json") && err.contains("[0].objects[0].x"),
        "{err}"
    );
    // Not a number JSON can hold.
    let f = write_file(
        &dir,
        "nan.json",
        &scene(r#"{"class":"R","x":NaN,"y":0,"width":10,"height":10}"#),
    );
    let o = rccpack(&["learn", &f, "--samples", "50"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("nan.json"), "{}", stderr(&o));
    // A tolerance at or past half the grid step, or negative.
    let ok = write_file(
        &dir,
        "ok.json",
        &scene(r#"{"class":"R","x":10.5,"y":0,"width":10,"height":10}"#),
    );
    for (t, want) in [
        ("5", "below half the grid step"),
        ("-1", "not a number of pixels"),
        ("inf", "not a number of pixels"),
    ] {
        let o = rccpack(&["learn", &ok, "--samples", "50", "--tolerance", t]);
        assert_eq!(o.status.code(), Some(1), "--tolerance {t}");
        let err = stderr(&o);
        assert!(
            err.contains("--tolerance") && err.contains(want),
            "--tolerance {t}: {err}"
        );
    }
}

fn task0() -> rccpack_bench::tasks::BenchTask {
    let cfg = TasksConfig {
        tasks: 1,
        sizes: vec![1.0],
        ..TasksConfig::quick(0, Duration::from_secs(1))
    };
    generate_task(&cfg, 0).unwrap()
}

#[test]
fn a_slip_keeps_its_rules_and_is_the_first_suspect() {
    let task = task0();
    let params = LearnParams::default();
    let exact = learn(&task.demos, None, &params).unwrap();
    let exact_rules = exact.rules();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    rng.set_stream(1);
    let (slipped, sl) = noisy::slip(&task.demos, &exact_rules, &mut rng).expect("a slip");
    // Today's model (slip rate 0, the default): the rules the slip breaks
    // are lost, and nobody is suspected.
    let today = learn(&slipped, None, &params).unwrap();
    let today_names: Vec<String> = today.rules().rules.iter().map(|r| r.name.clone()).collect();
    assert!(
        sl.breaks.iter().all(|b| !today_names.contains(b)),
        "{:?}",
        sl.breaks
    );
    assert!(today.suspects().is_empty());
    // With slips: every exact rule is kept, the ones it breaks included,
    // and the slip is the first suspect.
    let with = LearnParams {
        slip_rate: rccpack::infer::SUGGESTED_SLIP_RATE,
        ..params
    };
    let learned = learn(&slipped, None, &with).unwrap();
    let names: Vec<String> = learned
        .rules()
        .rules
        .iter()
        .map(|r| r.name.clone())
        .collect();
    let lost: Vec<&String> = sl.breaks.iter().filter(|b| !names.contains(b)).collect();
    assert!(lost.is_empty(), "{lost:?} of {:?}", sl.breaks);
    let exact_names: Vec<String> = exact_rules.rules.iter().map(|r| r.name.clone()).collect();
    let missed: Vec<&String> = exact_names.iter().filter(|n| !names.contains(n)).collect();
    assert!(missed.is_empty(), "{missed:?}");
    let first = learned.suspects().into_iter().next().expect("a suspect");
    assert_eq!(
        (first.demonstration, first.object.as_str()),
        (sl.demonstration, sl.object.as_str())
    );
    // The learned file marks the exception.
    let rcc = learned.to_rcc();
    assert!(
        rcc.contains(&format!(
            "demonstration {} breaks it ({})",
            sl.demonstration, sl.object
        )),
        "{rcc}"
    );
    // The report carries the suspects.
    let r: serde_json::Value = serde_json::from_str(&learned.report_json()).unwrap();
    assert_eq!(r["suspects"][0]["demonstration"], sl.demonstration);
    assert_eq!(r["suspects"][0]["object"], sl.object.as_str());
}

/// Law, over generated tasks and random slips: learning with the slip rate
/// keeps every rule the exact demonstrations give, adds few that the exact
/// demonstrations do not give at that rate, and names the slip first.
#[test]
fn random_slips_of_generated_tasks_keep_every_exact_rule() {
    let cfg = TasksConfig {
        tasks: 4,
        sizes: vec![1.0],
        ..TasksConfig::quick(0, Duration::from_secs(1))
    };
    let with = LearnParams {
        slip_rate: rccpack::infer::SUGGESTED_SLIP_RATE,
        ..LearnParams::default()
    };
    let names = |l: &rccpack::infer::Learned| -> std::collections::BTreeSet<String> {
        l.rules().rules.iter().map(|r| r.name.clone()).collect()
    };
    for t in 1..4 {
        let task = generate_task(&cfg, t).unwrap();
        let exact = learn(&task.demos, None, &LearnParams::default()).unwrap();
        let exact_at_rate = names(&learn(&task.demos, None, &with).unwrap());
        for seed in [5u64, 6] {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let (slipped, sl) = noisy::slip(&task.demos, &exact.rules(), &mut rng).expect("a slip");
            let learned = learn(&slipped, None, &with).unwrap();
            let got = names(&learned);
            let missed: Vec<String> = names(&exact).difference(&got).cloned().collect();
            assert!(
                missed.is_empty(),
                "task {t} seed {seed}: {missed:?} lost ({sl:?})"
            );
            // Beyond what the exact demonstrations give at the rate: at most
            // one rule in ten of the exact ones.
            let extra: Vec<&String> = got.difference(&exact_at_rate).collect();
            assert!(
                extra.len() * 10 <= exact.order.len(),
                "task {t} seed {seed}: {extra:?} added"
            );
            let first = learned.suspects().into_iter().next().expect("a suspect");
            assert_eq!(
                (first.demonstration, first.object.as_str()),
                (sl.demonstration, sl.object.as_str()),
                "task {t} seed {seed}"
            );
        }
    }
}

#[test]
fn slip_rate_zero_is_todays_output_byte_for_byte() {
    let task = task0();
    let a = learn(&task.demos, None, &LearnParams::default()).unwrap();
    let b = learn(
        &task.demos,
        None,
        &LearnParams {
            slip_rate: 0.0,
            ..LearnParams::default()
        },
    )
    .unwrap();
    assert_eq!(a.to_rcc(), b.to_rcc());
    assert_eq!(a.report_json(), b.report_json());
    assert!(!a.report_json().contains("suspects"));
    assert!(!a.report_json().contains("exception"));
}

#[test]
fn a_slip_is_named_on_the_command_line() {
    let task = task0();
    let exact = learn(&task.demos, None, &LearnParams::default()).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    rng.set_stream(1);
    let (slipped, sl) = noisy::slip(&task.demos, &exact.rules(), &mut rng).expect("a slip");
    let dir = scratch("measured-slip-cli");
    let f = write_file(
        &dir,
        "demos.json",
        &rccpack::scene::scenes_to_json(&slipped),
    );
    let o = rccpack(&[
        "learn",
        &f,
        "--slip-rate",
        "0.01",
        "-o",
        dir.join("l.rcc").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    let line = format!(
        "demonstration {}: `{}` at ({}, {})",
        sl.demonstration, sl.object, sl.to.0, sl.to.1
    );
    assert!(
        err.lines().next().unwrap_or("").starts_with(&line),
        "{line}\n{err}"
    );
    assert!(err.contains("— a slip?"), "{err}");
    for bad in ["-0.1", "0.5", "nan"] {
        let o = rccpack(&["learn", &f, "--slip-rate", bad]);
        assert_eq!(
            o.status.code(),
            Some(1),
            "--slip-rate {bad}: {}",
            stderr(&o)
        );
    }
}

#[test]
fn a_task_folder_reads_its_demonstrations_as_measured() {
    let dir = scratch("measured-task-folder");
    let src = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing");
    std::fs::copy(format!("{src}/problem.json"), dir.join("problem.json")).unwrap();
    std::fs::write(dir.join("demos.json"), jittered_box_demos()).unwrap();
    let measured = rccpack::task::Task::load(&dir).unwrap();
    let exact = rccpack::task::Task::load(src).unwrap();
    assert_eq!(measured.demos, exact.demos);
}

/// A slipped demonstration of generated task 0 with its problem.
pub(crate) fn slipped_task0() -> (Scene, Vec<Scene>, noisy::Slip) {
    let task = task0();
    let exact = learn(&task.demos, None, &LearnParams::default()).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    rng.set_stream(1);
    let (slipped, sl) = noisy::slip(&task.demos, &exact.rules(), &mut rng).expect("a slip");
    (task.problems[0].scene.clone(), slipped, sl)
}

fn slip_ask_options() -> AskOptions {
    AskOptions {
        learn: LearnParams {
            slip_rate: rccpack::infer::SUGGESTED_SLIP_RATE,
            ..LearnParams::default()
        },
        ..AskOptions::default()
    }
}

/// The question loop asks about the suspect first; "no" (a slip) makes
/// the slip sure (it no longer counts against the rules it breaks) and
/// confirms those rules, "yes" (meant) drops them; a resumed session ends
/// where the answered one did.
#[test]
fn a_suspect_is_asked_about_first_and_both_answers_do_what_they_say() {
    let (problem, slipped, sl) = slipped_task0();
    let opts = slip_ask_options();
    let mut asker = Asker::new(
        problem.clone(),
        slipped.clone(),
        None,
        Vec::new(),
        opts.clone(),
    )
    .unwrap();
    let q = asker.next_question().unwrap().expect("a question");
    let s = q.suspect.clone().expect("the suspect is asked about first");
    assert_eq!(s.demonstration, sl.demonstration);
    assert!(s.objects.contains(&sl.object), "{s:?}");
    assert_eq!(q.probe.scene, slipped[sl.demonstration]);
    assert_eq!(q.rule, s.breaks[0]);

    let mut no = asker.clone();
    no.answer(&q, false).unwrap();
    assert_eq!(no.slipped().collect::<Vec<_>>(), vec![sl.demonstration]);
    assert_eq!(no.demos(), &slipped[..], "demos.json keeps the slip");
    // Learning with the slip sure: every demonstration still counts.
    let sure = rccpack::infer::learn_with(
        &slipped,
        None,
        &opts.learn,
        &rccpack::infer::LearnOptions {
            slipped: &[sl.demonstration],
            ..Default::default()
        },
    )
    .unwrap();
    let slip = sure
        .slips
        .iter()
        .find(|x| x.demonstration == sl.demonstration)
        .expect("the answered slip");
    assert_eq!(slip.object, sl.object);
    assert!(slip.chance() == 1.0, "{slip:?}");
    let names = |set: &rccpack::RuleSet| -> Vec<String> {
        set.rules.iter().map(|r| r.name.clone()).collect()
    };
    assert_eq!(names(no.held()), names(&sure.rules()));
    for b in &s.breaks {
        assert!(no.is_confirmed(b), "{b} confirmed");
    }
    let rcc = no.learned_rcc();
    assert!(
        rcc.contains(&format!(
            "# demonstration {}: `{}` answered as a slip; it no longer counts against the rules it breaks",
            sl.demonstration, sl.object
        )),
        "{rcc}"
    );
    assert_eq!(no.answers()[0].demo, None);
    assert_eq!(
        no.answers()[0].suspect.as_ref().map(|a| a.demonstration),
        Some(sl.demonstration)
    );

    let mut yes = asker.clone();
    yes.answer(&q, true).unwrap();
    let held = names(yes.held());
    for b in &s.breaks {
        assert!(!held.contains(b), "{b} dropped: the exception is meant");
    }
    assert!(yes
        .learned()
        .suspects()
        .iter()
        .all(|x| x.demonstration != sl.demonstration));
    assert_eq!(yes.progress().dropped, s.breaks.len());

    // Resumed from the journal: the same state.
    for answered in [&no, &yes] {
        let resumed = Asker::new(
            problem.clone(),
            slipped.clone(),
            None,
            answered.answers().to_vec(),
            opts.clone(),
        )
        .unwrap();
        assert_eq!(resumed.learned_rcc(), answered.learned_rcc());
    }
}

/// `rccpack ask --slip-rate`: the suspect is the first question, its
/// picture drawn; Ctrl-C while it waits loses nothing; "no" journals a
/// slip that a resumed run does not ask about again; "yes" drops the rules
/// it breaks.
#[test]
fn ask_asks_about_a_suspect_both_ways_and_resumes_after_ctrl_c() {
    use std::process::Stdio;
    use std::time::Instant;
    let (problem, slipped, sl) = slipped_task0();
    let folder = |tag: &str| {
        let dir = scratch(tag);
        write_file(&dir, "problem.json", &problem.to_json());
        write_file(
            &dir,
            "demos.json",
            &rccpack::scene::scenes_to_json(&slipped),
        );
        dir
    };
    let dir = folder("measured-ask-suspect");
    let d = dir.to_str().unwrap();

    // Ctrl-C while the oracle looks at the suspect: exit 1, nothing lost.
    let child = crate::support::command()
        .args([
            "ask",
            d,
            "--slip-rate",
            "0.01",
            "--oracle",
            "sleep 60; true",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !dir.join("probes").join("probe-1.json").exists()
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
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("interrupted (Ctrl-C)"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("answers.json").exists());

    // "No": a slip.
    let o = rccpack(&[
        "ask",
        d,
        "--slip-rate",
        "0.01",
        "--oracle",
        "exit 1",
        "--max-questions",
        "1",
    ]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "{out}\n{}", stderr(&o));
    assert!(
        out.contains(&format!("question 1: demonstration {} (", sl.demonstration))
            && out.contains("-> a slip: it no longer counts, rules confirmed"),
        "{out}"
    );
    let answers: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("answers.json")).unwrap()).unwrap();
    assert_eq!(
        answers["answers"][0]["suspect"]["demonstration"],
        sl.demonstration
    );
    assert_eq!(answers["answers"][0]["accepted"], false);
    let learned = std::fs::read_to_string(dir.join("learned.rcc")).unwrap();
    assert!(
        learned.contains(&format!(
            "# demonstration {}: `{}` answered as a slip",
            sl.demonstration, sl.object
        )),
        "{learned}"
    );
    assert!(dir.join("probes").join("probe-1.png").exists());
    // demos.json is never rewritten for a slip.
    assert_eq!(
        std::fs::read_to_string(dir.join("demos.json")).unwrap(),
        rccpack::scene::scenes_to_json(&slipped)
    );
    // Resumed: the slip is not asked about again.
    let o = rccpack(&[
        "ask",
        d,
        "--slip-rate",
        "0.01",
        "--oracle",
        "exit 1",
        "--max-questions",
        "1",
    ]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "{out}\n{}", stderr(&o));
    assert!(out.contains("resuming: 1 answers"), "{out}");
    assert!(
        !out.contains(&format!(": demonstration {} (", sl.demonstration)),
        "{out}"
    );

    // "Yes": meant, and the rules it breaks are dropped.
    let dir = folder("measured-ask-suspect-meant");
    let d = dir.to_str().unwrap();
    let o = rccpack(&[
        "ask",
        d,
        "--slip-rate",
        "0.01",
        "--oracle",
        "exit 0",
        "--max-questions",
        "1",
    ]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "{out}\n{}", stderr(&o));
    assert!(out.contains("-> meant: rules dropped"), "{out}");
    let learned = std::fs::read_to_string(dir.join("learned.rcc")).unwrap();
    for b in &sl.breaks {
        assert!(!learned.contains(&format!("rule {b}:")), "{b}\n{learned}");
    }
}

/// `rccpack ask` on measured demonstrations: the same questions as on the
/// exact ones, and an accepted probe is appended after the recorded
/// entries, which keep their measured positions (never snapped in place).
#[test]
fn ask_reads_measured_demonstrations_and_keeps_them_as_recorded() {
    let jit = jittered_box_demos();
    let folder = |tag: &str, demos: &str| {
        let dir = scratch(tag);
        std::fs::copy(
            concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/examples/box-packing/problem.json"
            ),
            dir.join("problem.json"),
        )
        .unwrap();
        write_file(&dir, "demos.json", demos);
        dir
    };
    let exact = folder("measured-ask-exact", &box_demos());
    let measured = folder("measured-ask-jit", &jit);
    let run = |dir: &std::path::Path| {
        rccpack(&[
            "ask",
            dir.to_str().unwrap(),
            "--samples",
            "200",
            "--oracle",
            "exit 0",
            "--max-questions",
            "1",
        ])
    };
    let (a, b) = (run(&exact), run(&measured));
    assert!(a.status.success() && b.status.success(), "{}", stderr(&b));
    // The question line (the summary's timing differs).
    let out = |o: &std::process::Output, _dir: &std::path::Path| {
        String::from_utf8_lossy(&o.stdout)
            .lines()
            .next()
            .unwrap_or("")
            .to_string()
    };
    assert_eq!(out(&a, &exact), out(&b, &measured), "the same question");
    assert!(
        stderr(&b).contains("8 demonstrations as measured:"),
        "{}",
        stderr(&b)
    );
    let before: Vec<serde_json::Value> = serde_json::from_str(&jit).unwrap();
    let after: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(measured.join("demos.json")).unwrap())
            .unwrap();
    assert_eq!(after.len(), before.len() + 1, "the accepted probe appended");
    assert_eq!(&after[..before.len()], &before[..], "recorded entries kept");
    let exact_after: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(exact.join("demos.json")).unwrap()).unwrap();
    assert_eq!(
        after[before.len()],
        exact_after[before.len()],
        "the same probe"
    );
    assert_eq!(
        std::fs::read_to_string(measured.join("learned.rcc")).unwrap(),
        std::fs::read_to_string(exact.join("learned.rcc")).unwrap()
    );
}
