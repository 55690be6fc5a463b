//! Layouts like the demonstrations (docs/guide.md#layouts-like-the-demonstrations): the second objective on the
//! bundled example, under limits, and through the command line.

use rccpack::eval::evaluate;
use rccpack::infer::{learn, LearnParams};
use rccpack::relations::Contact;
use rccpack::resemblance::ResemblanceTarget;
use rccpack::rules::{parse_rules, RuleSet};
use rccpack::scene::{scenes_from_json, Scene};
use rccpack::synth::{synthesize, Status, SynthOptions};

use crate::support::example;

fn task(name: &str) -> (Vec<Scene>, Scene) {
    let dir = example(name);
    let demos =
        scenes_from_json(&std::fs::read_to_string(dir.join("demos.json")).unwrap()).unwrap();
    let problem =
        Scene::from_json(&std::fs::read_to_string(dir.join("problem.json")).unwrap()).unwrap();
    (demos, problem)
}

fn learned(demos: &[Scene]) -> RuleSet {
    learn(demos, None, &LearnParams::default()).unwrap().rules()
}

fn with_like(like: Option<ResemblanceTarget>) -> SynthOptions {
    SynthOptions {
        like,
        ..SynthOptions::default()
    }
}

/// Centre of the blocks of `class`, and the box's centre line (300, 300).
fn centre(scene: &Scene, class: &str) -> (f64, f64) {
    let v: Vec<(f64, f64)> = scene
        .objects
        .iter()
        .filter(|o| o.class == class)
        .map(|o| (o.x.unwrap() as f64 + 10.0, o.y.unwrap() as f64 + 10.0))
        .collect();
    let n = v.len() as f64;
    (
        v.iter().map(|p| p.0).sum::<f64>() / n,
        v.iter().map(|p| p.1).sum::<f64>() / n,
    )
}

/// `run examples/box-packing` places the blocks where the demonstrations
/// put them: reds low in the west, blues above them in the west, greens on
/// the east side, every block at a position some demonstration used — at
/// score 1, the same score as without `--like`.
#[test]
fn bundled_example_sits_where_the_demonstrations_did() {
    let (demos, problem) = task("box-packing");
    let rules = learned(&demos);
    let plain = synthesize(&problem, &rules, &with_like(None)).unwrap();
    let like = ResemblanceTarget::new(&demos);
    let r = synthesize(&problem, &rules, &with_like(Some(like.clone()))).unwrap();
    assert_eq!(r.status, Status::Optimal);
    let sol = r.scene.as_ref().unwrap();
    let score = evaluate(sol, &rules, Contact::Point).score;
    assert_eq!(score, 1.0);
    assert_eq!(score, plain.evaluation.unwrap().score);
    let res = r.resemblance.unwrap();
    assert!(res.proven);
    assert_eq!(res.cost, like.cost(&problem, sol));
    assert_eq!(res.cost, 0, "every block on a demonstrated position");
    let (rx, ry) = centre(sol, "R");
    let (bx, by) = centre(sol, "B");
    let (gx, _) = centre(sol, "G");
    assert!(
        rx < 300.0 && ry < 300.0,
        "reds in the south-west: {rx}, {ry}"
    );
    assert!(
        bx < 300.0 && by > ry,
        "blues west, above the reds: {bx}, {by}"
    );
    assert!(gx > 300.0, "greens east: {gx}");
}

/// The second example keeps its intended rules and sits on shown cells too.
#[test]
fn shelf_example_with_its_intended_rules() {
    let (demos, problem) = task("shelf");
    let rules =
        parse_rules(&std::fs::read_to_string(example("shelf").join("intended.rcc")).unwrap())
            .unwrap();
    let r = synthesize(
        &problem,
        &rules,
        &with_like(Some(ResemblanceTarget::new(&demos))),
    )
    .unwrap();
    assert_eq!(r.status, Status::Optimal);
    assert_eq!(r.evaluation.unwrap().score, 1.0);
    assert!(r.resemblance.unwrap().proven);
}

/// A node limit that strikes in the second phase keeps the best-score
/// layout, says the cost is not proven, and gives the same layout every
/// time.
#[test]
fn limits_in_the_second_phase_keep_the_score_and_are_deterministic() {
    let (demos, problem) = task("box-packing");
    // The second edition's rules: with the third edition's group
    // statements the example reaches cost 0 (proven minimal at once)
    // within the first few nodes of the second phase, and none of these
    // limits strikes before it.
    let params = LearnParams {
        templates: rccpack::infer::Templates::Second,
        ..LearnParams::default()
    };
    let rules = learn(&demos, None, &params).unwrap().rules();
    let full = synthesize(&problem, &rules, &with_like(None)).unwrap();
    let first_phase_nodes = full.stats.nodes;
    let like = ResemblanceTarget::new(&demos);
    let cheapest = synthesize(&problem, &rules, &with_like(Some(like.clone()))).unwrap();
    let cheapest = cheapest.resemblance.unwrap();
    assert!(cheapest.proven);
    assert_eq!(cheapest.bound, cheapest.cost);
    let mut stopped_in_phase_two = false;
    for extra in [1, 5, 20, 60] {
        let opts = SynthOptions {
            stop: rccpack::stop::Stop::never().with_nodes(first_phase_nodes + extra),
            ..with_like(Some(like.clone()))
        };
        let a = synthesize(&problem, &rules, &opts).unwrap();
        let b = synthesize(&problem, &rules, &opts).unwrap();
        assert_eq!(a.scene, b.scene, "same seed and limits, same layout");
        assert_eq!(a.resemblance, b.resemblance);
        let Some(sol) = &a.scene else { continue };
        // The first phase finished: the score is the optimum.
        if a.status == Status::Optimal {
            assert_eq!(evaluate(sol, &rules, Contact::Point).score, 1.0);
            let res = a.resemblance.unwrap();
            assert_eq!(res.cost, like.cost(&problem, sol));
            stopped_in_phase_two |= !res.proven;
            // The reported bound is a lower bound of the proven minimum,
            // and equals the cost exactly when the cost is proven.
            assert!(res.bound <= cheapest.cost, "{res:?} against {cheapest:?}");
            assert_eq!(res.proven, res.bound == res.cost, "{res:?}");
        }
    }
    assert!(
        stopped_in_phase_two,
        "some limit struck during the second phase"
    );
}

fn rccpack(args: &[&str]) -> (String, String, i32) {
    let out = crate::support::rccpack(args);
    let (stdout, stderr) = (crate::support::stdout(&out), crate::support::stderr(&out));
    (stdout, stderr, out.status.code().unwrap_or(-1))
}

#[test]
fn cli_synth_like_reports_the_cost_and_run_uses_the_demonstrations() {
    let dir = crate::support::scratch("like-cli");
    let ex = example("box-packing");
    let report = dir.join("report.json");
    let (_, err, code) = rccpack(&[
        "synth",
        ex.join("problem.json").to_str().unwrap(),
        "--rules",
        ex.join("pilot.rcc").to_str().unwrap(),
        "--like",
        ex.join("demos.json").to_str().unwrap(),
        "-o",
        dir.join("s.json").to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("resemblance cost"), "{err}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(r["status"], "optimal");
    assert!(r["resemblance"]["cost"].is_u64());
    assert_eq!(r["resemblance"]["proven"], true);
    // Without --like the report has no resemblance field.
    let (_, _, code) = rccpack(&[
        "synth",
        ex.join("problem.json").to_str().unwrap(),
        "--rules",
        ex.join("pilot.rcc").to_str().unwrap(),
        "-o",
        dir.join("s2.json").to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(code, 0);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert!(r.get("resemblance").is_none());
    // `run` uses the demonstrations unless told `--like none`.
    let (out, err, code) = rccpack(&["run", ex.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("resemblance cost 0 (proven minimal)"), "{out}");
    let (out, _, code) = rccpack(&[
        "run",
        ex.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--like",
        "none",
    ]);
    assert_eq!(code, 0);
    assert!(!out.contains("resemblance"), "{out}");
    // Bad like-scenes are bad input.
    std::fs::write(dir.join("bad.json"), "[{\"space\":{\"width\":10,\"height\":10},\"objects\":[{\"class\":\"A\",\"x\":0.5,\"y\":0,\"width\":1,\"height\":1}]}]").unwrap();
    let (_, err, code) = rccpack(&[
        "synth",
        ex.join("problem.json").to_str().unwrap(),
        "--rules",
        ex.join("pilot.rcc").to_str().unwrap(),
        "--like",
        dir.join("bad.json").to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("bad.json") && err.contains("objects[0].x"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
