//! Questions under a budget: every probe a real probe (edits of a
//! demonstration included, with exactly the moved objects marked), and the
//! same questions on one and two threads and after a resume.

use rccpack::ask::{AskOptions, Asker, Question, QuestionBudget};
use rccpack::eval::evaluate;
use rccpack::relations::Contact;
use rccpack::rules::{parse_rules, RuleSet};
use rccpack::scene::{scenes_from_json, Scene};

fn example(name: &str) -> (Scene, Vec<Scene>, RuleSet) {
    let dir = crate::support::path(&format!("examples/{name}"));
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
    let oracle = if name == "shelf" {
        "intended.rcc"
    } else {
        "pilot.rcc"
    };
    (
        Scene::from_json(&read("problem.json")).unwrap(),
        scenes_from_json(&read("demos.json")).unwrap(),
        parse_rules(&read(oracle)).unwrap(),
    )
}

/// The defaults with the wall-clock cap out of reach (a loaded test
/// machine must not change a question) and `nodes` of budget.
fn options(nodes: u64) -> AskOptions {
    AskOptions {
        budget: QuestionBudget { nodes, wall: None },
        ..AskOptions::default()
    }
}

fn keeps(scene: &Scene, rules: &RuleSet) -> bool {
    evaluate(scene, rules, Contact::Point)
        .rules
        .iter()
        .all(|r| r.satisfied == r.subjects)
}

/// Whether `q`'s probe is a real probe of the session's held rules: it
/// breaks its rule (for a group question: each rule of its group) for at
/// least one object and keeps every other held rule but the ones it names
/// in `also_broken`; an edit of a demonstration
/// differs from it in exactly the objects it marks as moved, each marked
/// with where it was.
fn check_probe(asker: &Asker, q: &Question) {
    let ev = evaluate(&q.probe.scene, asker.held(), Contact::Point);
    let group = q.group_names();
    for r in &ev.rules {
        if r.name == q.rule && group.is_empty() {
            assert!(r.satisfied < r.subjects, "{} is not broken", q.rule);
            assert_eq!(r.violators, q.probe.broken, "{}", q.rule);
        } else if group.contains(&r.name) {
            // A group question breaks each of its rules.
            assert!(r.satisfied < r.subjects, "{} is not broken", r.name);
            assert!(r.violators.iter().all(|v| q.probe.broken.contains(v)));
        } else if !q.also_broken.contains(&r.name) {
            assert_eq!(r.satisfied, r.subjects, "{} breaks {}", q.rule, r.name);
        }
    }
    if let Some(e) = &q.probe.edit {
        let demo = &asker.demos()[e.demo];
        assert_eq!(demo.objects.len(), q.probe.scene.objects.len());
        let mut moved = Vec::new();
        for (a, b) in demo.objects.iter().zip(&q.probe.scene.objects) {
            assert_eq!((&a.id, &a.class, a.fixed), (&b.id, &b.class, b.fixed));
            if (a.x, a.y) != (b.x, b.y) {
                moved.push((a.id.clone(), a.x.unwrap(), a.y.unwrap()));
            }
        }
        let marked: Vec<(String, i64, i64)> =
            e.moved.iter().map(|m| (m.id.clone(), m.x, m.y)).collect();
        assert_eq!(marked, moved, "{}", q.rule);
        assert!(!moved.is_empty() && moved.len() <= 2, "{}", q.rule);
    }
}

/// A session answered by `oracle`, at most `stop_after` questions;
/// `threads` 2 computes each next question ahead for both answers.
/// Returns the transcript and the session.
fn session(
    (problem, demos, oracle): &(Scene, Vec<Scene>, RuleSet),
    opts: &AskOptions,
    threads: usize,
    stop_after: usize,
) -> (Vec<(String, Scene, bool)>, Asker) {
    let mut asker = Asker::new(
        problem.clone(),
        demos.clone(),
        None,
        Vec::new(),
        opts.clone(),
    )
    .unwrap();
    let mut out = Vec::new();
    let mut next = asker.next_question().unwrap();
    while let Some(q) = next {
        if stop_after == out.len() {
            break;
        }
        check_probe(&asker, &q);
        let ok = keeps(&q.probe.scene, oracle);
        out.push((q.rule.clone(), q.probe.scene.clone(), ok));
        let (a, n) = asker.look_ahead(&q, threads).answer(ok).unwrap();
        asker = a;
        next = n;
    }
    (out, asker)
}

/// Every probe of a session is a real probe, under the default budget and
/// under a budget so small that searches stop early; some are edits of a
/// demonstration.
#[test]
fn probes_under_a_budget_are_real_probes() {
    let bp = example("box-packing");
    for (nodes, least) in [(rccpack::ask::DEFAULT_QUESTION_NODES, 10), (3_000, 3)] {
        let (t, asker) = session(&bp, &options(nodes), 1, 10);
        assert!(t.len() >= least, "{nodes}: {} questions", t.len());
        let edits = asker.answers().iter().filter(|a| a.edit.is_some()).count();
        assert!(edits > 0, "{nodes}: no edit");
    }
}

/// The same questions, probes and answers on one thread and with the
/// look-ahead on two, and the same files at the end.
#[test]
fn the_same_questions_on_one_and_two_threads() {
    let bp = example("box-packing");
    let opts = options(rccpack::ask::DEFAULT_QUESTION_NODES);
    let (one, a) = session(&bp, &opts, 1, 10);
    let (two, b) = session(&bp, &opts, 2, 10);
    assert_eq!(one, two);
    assert_eq!(a.answers(), b.answers());
    assert_eq!(a.demos(), b.demos());
    assert_eq!(a.learned_rcc(), b.learned_rcc());
}

/// A session resumed after `k` answers (a new session from the files the
/// first one would have written) asks what the uninterrupted one asks.
#[test]
fn a_resumed_session_asks_the_same() {
    let bp = example("box-packing");
    let opts = options(rccpack::ask::DEFAULT_QUESTION_NODES);
    let (whole, _) = session(&bp, &opts, 1, 12);
    for k in [3, 8] {
        let (_, cut) = session(&bp, &opts, 1, k);
        let mut resumed = Asker::new(
            bp.0.clone(),
            cut.demos().to_vec(),
            None,
            cut.answers().to_vec(),
            opts.clone(),
        )
        .unwrap();
        let mut rest = Vec::new();
        while let Some(q) = resumed.next_question().unwrap() {
            if k + rest.len() == whole.len() {
                break;
            }
            let ok = keeps(&q.probe.scene, &bp.2);
            rest.push((q.rule.clone(), q.probe.scene.clone(), ok));
            resumed.answer(&q, ok).unwrap();
        }
        assert_eq!(rest, whole[k..].to_vec(), "resumed after {k}");
    }
}
