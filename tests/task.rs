//! The library's task pipeline (`rccpack::task`): loading a folder, its
//! typed errors naming the file, and `run` on the bundled example.

use crate::support::{path, scratch};
use rccpack::task::{self, files, RunOptions, Task, TaskError};
use rccpack::{DiagnosticKind, SceneErrorKind, Status};

fn copy_example(tag: &str) -> std::path::PathBuf {
    let d = scratch(tag);
    for f in [files::DEMOS, files::PROBLEM] {
        std::fs::copy(path("examples/box-packing").join(f), d.join(f)).unwrap();
    }
    d
}

#[test]
fn load_errors_name_the_file_and_the_kind() {
    let d = scratch("task-missing");
    match Task::load(&d).unwrap_err() {
        TaskError::Read { path, .. } => assert_eq!(path, d.join(files::DEMOS)),
        e => panic!("expected Read, got {e:?}"),
    }

    let d = copy_example("task-bad-problem");
    std::fs::write(
        d.join(files::PROBLEM),
        r#"{"space": {"width": 10, "height": 10}, "grid": 0, "objects": []}"#,
    )
    .unwrap();
    match Task::load(&d).unwrap_err() {
        TaskError::Scene { path, source } => {
            assert_eq!(path, d.join(files::PROBLEM));
            assert_eq!(source.kind(), SceneErrorKind::BadGrid);
        }
        e => panic!("expected Scene, got {e:?}"),
    }

    let d = copy_example("task-bad-statements");
    std::fs::write(d.join(files::STATEMENTS), "rule a: DR_X(B, R)\n").unwrap();
    let e = Task::load(&d).unwrap_err();
    assert!(
        e.to_string()
            .starts_with(&d.join(files::STATEMENTS).display().to_string()),
        "{e}"
    );
    match e {
        TaskError::Rules { source, text, .. } => {
            assert_eq!(source.diagnostics[0].kind, DiagnosticKind::UnknownRelation);
            assert_eq!(text, "rule a: DR_X(B, R)\n");
        }
        e => panic!("expected Rules, got {e:?}"),
    }
}

#[test]
fn place_refuses_a_landmark_the_problem_lacks() {
    let task = Task::load(path("examples/box-packing")).unwrap();
    let rules = rccpack::parse_rules("rule r_on_nowhere: EC_N(R, @nowhere)\n").unwrap();
    let e = task::place(
        &task.problem,
        &rules,
        &task.demos,
        &task::Like::Demos,
        &Default::default(),
    )
    .unwrap_err();
    assert!(matches!(e, TaskError::Landmark(_)), "{e:?}");
}

#[test]
fn run_learns_and_places_the_bundled_example() {
    let task = Task::load(path("examples/box-packing")).unwrap();
    let mut opts = RunOptions::default();
    opts.learn.samples = 200;
    opts.synth.stop = rccpack::stop::Stop::never().with_nodes(20_000);
    let out = task::run(&task, &opts).unwrap();
    let r = &out.placement.result;
    assert_eq!(r.status, Status::Optimal);
    let layout = r.scene.as_ref().unwrap();
    rccpack::synth::verify_solution(&task.problem, layout, &out.rules, rccpack::Contact::Point)
        .unwrap();
    assert_eq!(r.evaluation.as_ref().unwrap().score, 1.0);
    // The demonstrations were the resemblance target.
    assert!(out.placement.like.is_some() && r.resemblance.is_some());
    assert!(out.placement.missing_classes.is_empty());
}

/// The one question session (`task::session::Session`): the open question
/// is asked again unchanged, an answer about another rule is refused, and
/// a file edited by hand since the session wrote it is never overwritten.
#[test]
fn a_session_never_overwrites_a_file_changed_on_disk() {
    use rccpack::task::session::{Session, SessionError, SessionOptions};
    let d = copy_example("session-changed");
    let mut opts = SessionOptions::default();
    opts.ask.learn.samples = 200;
    let mut s = Session::open(&d, opts).unwrap();
    let shown = s.next_question().unwrap().expect("a question");
    let again = s.next_question().unwrap().expect("the same question");
    assert_eq!(
        (again.number, &again.question.rule),
        (shown.number, &shown.question.rule)
    );
    match s.answer("no_such_rule", false) {
        Err(SessionError::NotOpen { rule, open }) => {
            assert_eq!(rule, "no_such_rule");
            assert_eq!(open.as_deref(), Some(shown.question.rule.as_str()));
        }
        r => panic!("expected NotOpen, got {r:?}"),
    }
    std::fs::write(d.join(files::LEARNED), "# edited by hand\n").unwrap();
    match s.answer(&shown.question.rule, false) {
        Err(SessionError::Changed { dir }) => assert_eq!(dir, d),
        r => panic!("expected Changed, got {r:?}"),
    }
    assert_eq!(
        std::fs::read_to_string(d.join(files::LEARNED)).unwrap(),
        "# edited by hand\n"
    );
    assert!(!d.join(files::ANSWERS).exists(), "nothing journaled");
    // Still open: the person can answer once the file is put back.
    assert_eq!(
        s.open_question().map(|o| o.question.rule.clone()),
        Some(shown.question.rule.clone())
    );
}
