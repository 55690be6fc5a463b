//! `rccpack ask` on the bundled example with the pilot study's twelve rules
//! as the oracle (docs/guide.md#questions), resuming, aborting, and `score --require`.

use rccpack::ask::negation;
use rccpack::rules::{parse_rules, Rule, RuleSet, Strength};
use rccpack::scene::{scenes_from_json, Scene};
use rccpack::synth::{synthesize, Status, SynthOptions};
use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::Duration;

fn example() -> PathBuf {
    crate::support::example("box-packing")
}

/// A fresh copy of the bundled task folder (problem, demos, pilot rules).
fn task(name: &str) -> PathBuf {
    crate::support::example_copy(
        &format!("ask-{name}"),
        "box-packing",
        &["problem.json", "demos.json", "pilot.rcc"],
    )
}

fn ask(dir: &Path, extra: &[&str]) -> Output {
    let oracle = format!(
        "'{}' score --rules '{}' --require",
        env!("CARGO_BIN_EXE_rccpack"),
        dir.join("pilot.rcc").display()
    );
    crate::support::command()
        .arg("ask")
        .arg(dir)
        // The node budgets bound every solve and make the runs
        // reproducible; the time limit is only a safety net, set out of
        // reach so that a loaded test machine cannot change a question.
        .args([
            "--oracle",
            &oracle,
            "--samples",
            "1000",
            "--time-limit",
            "600",
            "--question-seconds",
            "600",
        ])
        .args(extra)
        .output()
        .unwrap()
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn read(dir: &Path, f: &str) -> String {
    std::fs::read_to_string(dir.join(f)).unwrap()
}

fn hard(set: &RuleSet) -> Vec<Rule> {
    set.rules
        .iter()
        .map(|r| Rule {
            strength: Strength::Hard,
            ..r.clone()
        })
        .collect()
}

/// Whether `premises` imply `rule` on `problem`'s objects: the premises
/// hard and the rule's negation hard admit no layout (the engine is exact).
fn implies_on(problem: &Scene, premises: &RuleSet, rule: &Rule) -> bool {
    let Some(neg) = negation(rule) else {
        return true;
    };
    let mut rules = hard(premises);
    rules.push(neg);
    let opts = SynthOptions {
        explain: false,
        stop: rccpack::stop::Stop::after(Duration::from_secs(60)),
        ..SynthOptions::default()
    };
    let r = synthesize(problem, &RuleSet::new(rules), &opts).unwrap();
    assert_ne!(r.status, Status::Unknown, "no verdict on `{}`", rule.name);
    r.status == Status::Infeasible
}

/// The problem with another mix of blocks: `n` of each class, unplaced.
fn mix(problem: &Scene, counts: [(&str, usize); 3]) -> Scene {
    let mut s = problem.clone();
    let block = s
        .objects
        .iter()
        .find(|o| !o.fixed)
        .cloned()
        .expect("a block");
    s.objects.retain(|o| o.fixed);
    for (class, n) in counts {
        for i in 0..n {
            let mut o = block.clone();
            o.id = format!("{}{}", class.to_lowercase(), i + 1);
            o.class = class.into();
            o.x = None;
            o.y = None;
            s.objects.push(o);
        }
    }
    s
}

#[test]
fn pilot_oracle_keeps_the_twelve_and_drops_the_habits() {
    let dir = task("pilot");
    let before = scenes_from_json(&read(&dir, "demos.json")).unwrap().len();
    let o = ask(&dir, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let out = text(&o);
    eprintln!("{out}");
    assert!(out.contains("rules dropped"), "{out}");

    let learned = parse_rules(&read(&dir, "learned.rcc")).unwrap();
    let pilot = parse_rules(&read(&dir, "pilot.rcc")).unwrap();
    let problem = Scene::from_json(&read(&dir, "problem.json")).unwrap();
    let answers: serde_json::Value = serde_json::from_str(&read(&dir, "answers.json")).unwrap();
    let answers = answers["answers"].as_array().unwrap();
    let accepted = answers.iter().filter(|a| a["accepted"] == true).count();
    let rejected = answers.len() - accepted;
    assert!(accepted > 0 && rejected > 0, "{out}");
    // Every accepted probe joined the demonstrations.
    let after = scenes_from_json(&read(&dir, "demos.json")).unwrap().len();
    assert_eq!(after, before + accepted);
    // Every rejected rule is marked confirmed and still held.
    let marked = read(&dir, "learned.rcc").matches("# confirmed\n").count();
    assert_eq!(marked, rejected, "{}", read(&dir, "learned.rcc"));

    // (1) Every remaining rule is implied by the twelve, on the problem and
    // on other mixes of blocks.
    let mixes = [
        problem.clone(),
        mix(&problem, [("R", 2), ("G", 2), ("B", 2)]),
        mix(&problem, [("R", 4), ("G", 2), ("B", 3)]),
        mix(&problem, [("R", 2), ("G", 4), ("B", 2)]),
    ];
    for p in &mixes {
        for r in &learned.rules {
            assert!(
                implies_on(p, &pilot, r),
                "`{}` is held but the pilot rules do not imply it",
                r.name
            );
        }
    }
    // (2) All twelve are still learned: the held rules imply each.
    for g in &pilot.rules {
        assert!(
            implies_on(&problem, &learned, g),
            "the held rules no longer imply `{}`",
            g.name
        );
    }
    // (3) `run`'s layout keeps all twelve.
    let o = crate::support::command()
        .args(["run"])
        .arg(&dir)
        .args(["--time-limit", "60"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let o = crate::support::command()
        .arg("score")
        .arg(dir.join("solution.json"))
        .arg("--rules")
        .arg(dir.join("pilot.rcc"))
        .arg("--require")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn abort_keeps_answers_and_a_second_run_resumes() {
    let dir = task("resume");
    // Two questions, then stop at the budget.
    let o = ask(&dir, &["--max-questions", "2"]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("--max-questions 2"), "{}", text(&o));
    let first: serde_json::Value = serde_json::from_str(&read(&dir, "answers.json")).unwrap();
    assert_eq!(first["answers"].as_array().unwrap().len(), 2);
    let demos_after_two = read(&dir, "demos.json");

    // An oracle that exits 2 aborts: exit 1, nothing lost.
    let o = crate::support::command()
        .arg("ask")
        .arg(&dir)
        .args(["--oracle", "exit 2", "--samples", "1000"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(text(&o).contains("exited with 2"), "{}", text(&o));
    assert!(text(&o).contains("resuming: 2 answers"), "{}", text(&o));
    let kept: serde_json::Value = serde_json::from_str(&read(&dir, "answers.json")).unwrap();
    assert_eq!(kept, first, "an aborted answer changed answers.json");
    assert_eq!(read(&dir, "demos.json"), demos_after_two);

    // End of input on the terminal aborts the same way.
    let o = crate::support::command()
        .arg("ask")
        .arg(&dir)
        .args(["--samples", "1000"])
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("is this layout acceptable?"),
        "{}",
        text(&o)
    );
    assert!(text(&o).contains("picture: "), "{}", text(&o));

    // Resume to the end: the same result as one uninterrupted run.
    let o = ask(&dir, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let whole = task("whole");
    let o2 = ask(&whole, &[]);
    assert!(o2.status.success(), "{}", text(&o2));
    assert_eq!(read(&dir, "learned.rcc"), read(&whole, "learned.rcc"));
    assert_eq!(read(&dir, "answers.json"), read(&whole, "answers.json"));
    assert_eq!(read(&dir, "demos.json"), read(&whole, "demos.json"));
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&whole);
}

#[test]
fn an_answer_saved_only_in_answers_json_is_added_to_the_demos() {
    let dir = task("journal");
    let o = ask(&dir, &["--max-questions", "1"]);
    assert!(o.status.success(), "{}", text(&o));
    let v: serde_json::Value = serde_json::from_str(&read(&dir, "answers.json")).unwrap();
    assert_eq!(
        v["answers"][0]["accepted"], true,
        "the first probe is a habit's"
    );
    // Simulate a crash between the two writes: demos.json without the probe.
    std::fs::copy(example().join("demos.json"), dir.join("demos.json")).unwrap();
    let o = ask(&dir, &["--max-questions", "0"]);
    assert!(o.status.success(), "{}", text(&o));
    let demos = scenes_from_json(&read(&dir, "demos.json")).unwrap();
    let original = scenes_from_json(&read(&example(), "demos.json")).unwrap();
    assert_eq!(demos.len(), original.len() + 1);
    let probe: Scene = serde_json::from_value(v["answers"][0]["probe"].clone()).unwrap();
    assert_eq!(demos.last(), Some(&probe));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_answers_file_is_a_clear_error() {
    let dir = task("bad");
    std::fs::write(dir.join("answers.json"), r#"{"answers": [{"rule": 3}]}"#).unwrap();
    let o = ask(&dir, &[]);
    assert_eq!(o.status.code(), Some(1));
    let t = text(&o);
    assert!(
        t.contains("answers.json") && t.contains("answers[0].rule"),
        "{t}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn score_require_is_an_oracle() {
    let ex = example();
    let pilot = ex.join("pilot.rcc");
    let demos = scenes_from_json(&read(&ex, "demos.json")).unwrap();
    let dir = task("require");
    let good = dir.join("good.json");
    std::fs::write(&good, demos[0].to_json()).unwrap();
    let run = |scene: &Path| {
        crate::support::command()
            .arg("score")
            .arg(scene)
            .arg("--rules")
            .arg(&pilot)
            .arg("--require")
            .output()
            .unwrap()
    };
    let o = run(&good);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(text(&o).contains("every rule holds for every object"));
    // Move one red block far outside the box: it breaks rules.
    let mut bad = demos[0].clone();
    let r = bad.objects.iter_mut().find(|o| o.class == "R").unwrap();
    r.x = Some(bad.space.x);
    r.y = Some(bad.space.y);
    let badp = dir.join("bad.json");
    std::fs::write(&badp, bad.to_json()).unwrap();
    let o = run(&badp);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(text(&o).contains("red_inside_box"), "{}", text(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The node budgets take whole numbers of at least 1; anything else is a
/// usage error: exit 1, naming the flag and the value.
#[test]
fn bad_node_budgets_exit_1() {
    let dir = task("budgets");
    for (flag, value) in [
        ("--node-limit", "0"),
        ("--check-nodes", "0"),
        ("--check-nodes", "abc"),
        ("--node-limit", "-5"),
    ] {
        let o = crate::support::command()
            .arg("ask")
            .arg(&dir)
            .args([flag, value])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1), "{flag} {value}: {}", text(&o));
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains(flag) && e.contains(value), "{flag} {value}: {e}");
    }
}

/// The look-ahead (the next question for both answers, computed while the
/// oracle looks) writes nothing of the branch not taken: a session with it
/// and one without (`--no-lookahead`) leave the same files, byte for byte,
/// and ask the same questions.
#[test]
fn lookahead_writes_what_a_session_without_it_writes() {
    let with = task("lookahead-on");
    let without = task("lookahead-off");
    let a = ask(&with, &["--max-questions", "8"]);
    let b = ask(&without, &["--max-questions", "8", "--no-lookahead"]);
    assert!(a.status.success(), "{}", text(&a));
    assert!(b.status.success(), "{}", text(&b));
    let questions = |o: &Output| -> Vec<String> {
        String::from_utf8_lossy(&o.stdout)
            .lines()
            .filter(|l| l.starts_with("question "))
            .map(str::to_string)
            .collect()
    };
    assert_eq!(questions(&a).len(), 8, "{}", text(&a));
    assert_eq!(questions(&a), questions(&b));
    for f in ["answers.json", "demos.json", "learned.rcc"] {
        assert_eq!(read(&with, f), read(&without, f), "{f}");
    }
    for n in 1..=8 {
        let f = format!("probes/probe-{n}.json");
        assert_eq!(read(&with, &f), read(&without, &f), "{f}");
    }
    let _ = std::fs::remove_dir_all(&with);
    let _ = std::fs::remove_dir_all(&without);
}

/// Hardening, third pass, items 11 and 13: a hand-edited answer for a rule
/// that is no statement of the task, or an accepted probe whose index is
/// past the end of demos.json, is refused naming the answer — never
/// counted confirmed, never called "a different scene".
#[test]
fn an_answer_the_task_cannot_hold_is_refused_naming_it() {
    let dir = task("edited-answers");
    // Answers about one rule each (the hand edits below rename or repeat
    // one).
    let o = ask(&dir, &["--max-questions", "2", "--no-groups"]);
    assert!(o.status.success(), "{}", text(&o));
    let good = read(&dir, "answers.json");
    let mut v: serde_json::Value = serde_json::from_str(&good).unwrap();
    // A confirmed rule renamed by hand (item 11).
    {
        let mut w = v.clone();
        let mut bogus = w["answers"][0].clone();
        bogus["rule"] = serde_json::json!("No_such_rule");
        bogus["accepted"] = serde_json::json!(false);
        bogus.as_object_mut().unwrap().remove("demo");
        let answers = w["answers"].as_array_mut().unwrap();
        answers.push(bogus);
        let i = answers.len() - 1;
        std::fs::write(dir.join("answers.json"), w.to_string()).unwrap();
        let o = ask(&dir, &["--max-questions", "0"]);
        assert_eq!(o.status.code(), Some(1), "{}", text(&o));
        let t = text(&o);
        assert!(
            t.contains(&format!(
                "answers[{i}]: rule: `No_such_rule` is not a statement of this task"
            )),
            "{t}"
        );
    }
    // Two answers about one rule: the second contradicts the first.
    {
        let mut w = v.clone();
        let mut again = w["answers"][0].clone();
        again["accepted"] = serde_json::json!(false);
        again.as_object_mut().unwrap().remove("demo");
        let answers = w["answers"].as_array_mut().unwrap();
        answers.push(again);
        let i = answers.len() - 1;
        std::fs::write(dir.join("answers.json"), w.to_string()).unwrap();
        let o = ask(&dir, &["--max-questions", "0"]);
        assert_eq!(o.status.code(), Some(1), "{}", text(&o));
        let t = text(&o);
        assert!(
            t.contains(&format!("answers[{i}]: rule: `"))
                && t.contains("was answered already by answers[0] (acceptable: dropped)"),
            "{t}"
        );
    }
    // An accepted probe far past the end (item 13).
    let accepted = v["answers"]
        .as_array()
        .unwrap()
        .iter()
        .position(|a| a["accepted"] == true)
        .expect("the first probe is accepted");
    v["answers"][accepted]["demo"] = serde_json::json!(50);
    std::fs::write(dir.join("answers.json"), v.to_string()).unwrap();
    let o = ask(&dir, &["--max-questions", "0"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let t = text(&o);
    assert!(
        t.contains(&format!("answers[{accepted}]: demo: 50 is out of range")),
        "{t}"
    );
    assert!(!t.contains("different scene"), "{t}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Hardening, third pass, item 3: an oracle that answers at once but leaves
/// a child in a session of its own holding its standard error (an image
/// viewer it opened) does not make `ask` wait for that child.
#[test]
fn an_oracles_lingering_child_is_not_waited_for() {
    let dir = task("lingering-child");
    let start = std::time::Instant::now();
    let o = crate::support::command()
        .arg("ask")
        .arg(&dir)
        .args([
            "--samples",
            "200",
            "--max-questions",
            "1",
            "--oracle",
            "setsid sleep 30 & exit 1",
        ])
        .output()
        .unwrap();
    let took = start.elapsed();
    assert!(o.status.success(), "{}", text(&o));
    // The oracle said no: a rule confirmed, or a group's "one of them is
    // meant".
    assert!(text(&o).contains("not acceptable"), "{}", text(&o));
    assert!(
        took < std::time::Duration::from_secs(20),
        "ask waited {took:?} for the oracle's child"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
