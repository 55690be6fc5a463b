//! Inputs that must not panic or wrap, and every documented limit
//! at and just past its bound (accepted and solved correctly at the limit,
//! refused with a clear message just past it).

use crate::support::{rccpack, stderr, stdout};
use rccpack::relations::Contact;
use rccpack::rules::{parse_rules, RuleSet};
use rccpack::scene::Scene;
use rccpack::synth::verify_solution;
use rccpack::synth::{
    synthesize, Status, SynthError, SynthOptions, MAX_POSITIONS, MAX_SYNTH_COORD,
};
use std::time::Duration;

fn problem(x: i64, y: i64, w: i64, h: i64, grid: i64, objects: &str) -> Scene {
    Scene::from_json(&format!(
        r#"{{"space":{{"x":{x},"y":{y},"width":{w},"height":{h}}},"grid":{grid},"objects":[{objects}]}}"#
    ))
    .expect("valid scene")
}

const TWO_BLOCKS: &str = r#"{"id":"b1","class":"B","width":10,"height":10},
                            {"id":"b2","class":"B","width":10,"height":10}"#;

fn solve(p: &Scene, rules: &RuleSet) -> Result<rccpack::synth::SynthResult, SynthError> {
    let opts = SynthOptions {
        stop: rccpack::stop::Stop::never().with_nodes(200_000),
        ..SynthOptions::default()
    };
    synthesize(p, rules, &opts)
}

fn assert_optimal(p: &Scene, rules: &RuleSet) {
    let r = solve(p, rules).expect("solvable");
    assert_eq!(r.status, Status::Optimal, "{:?}", r.stats);
    let s = r.scene.expect("a layout");
    verify_solution(p, &s, rules, Contact::Point).expect("verified");
    assert_eq!(r.evaluation.expect("evaluated").score, 1.0);
}

/// The issue's crash: symmetry breaking between two interchangeable blocks
/// in a 200000×200000 space with grid 1 overflowed Pumpkin's i32
/// (`gy·NX + gx`); now the order is posted without products and the
/// problem is solved.
#[test]
fn symmetry_term_in_a_huge_space_does_not_overflow() {
    let p = problem(0, 0, 200_000, 200_000, 1, TWO_BLOCKS);
    let rules = parse_rules("rule touch: EC_E(B, B) | EC_W(B, B)\n").unwrap();
    assert_optimal(&p, &rules);
    assert_optimal(&p, &RuleSet::default());
}

/// At the engine's bounds: coordinates at ±2^28 and exactly
/// `MAX_POSITIONS` grid positions per axis (grid 1024 over 2^28), a fixed
/// object near the far corner, interchangeable objects, cumulative sums
/// past i32 (nine full-height objects): solved and verified.
#[test]
fn synthesis_at_the_coordinate_bound() {
    let m = MAX_SYNTH_COORD;
    let g = m / MAX_POSITIONS; // 1024
    let p = problem(0, 0, m, m, g, TWO_BLOCKS);
    let rules = parse_rules("rule north: DR_N(B, B) | DR_S(B, B)\n").unwrap();
    assert_optimal(&p, &rules);
    // Negative corner: the space spans [-2^27, 2^27]; the wall sits so that
    // a block can touch it on the grid.
    let h = m / 2;
    let at = h - 2 * g + 10;
    let wall = format!(
        r#"{{"id":"w","class":"W","x":{at},"y":{at},"width":1100,"height":1100,"fixed":true}},"#
    );
    let p = problem(-h, -h, m, m, g, &(wall + TWO_BLOCKS));
    let rules = parse_rules("rule near: EC_S(B, W) | EC_W(B, W)\n").unwrap();
    assert_optimal(&p, &rules);
    // Nine objects of the space's full height side by side: the demands of
    // the redundant cumulative sum past i32, so it is left out.
    let tall: Vec<String> = (0..9)
        .map(|i| format!(r#"{{"id":"t{i}","class":"T","width":1,"height":{m}}}"#))
        .collect();
    let p = problem(0, 0, m, m, g, &tall.join(","));
    assert_optimal(&p, &parse_rules("rule row: AL_S(T, T)\n").unwrap());
    // Grid 1: exactly MAX_POSITIONS positions along x is accepted ...
    let p = problem(0, 0, MAX_POSITIONS + 9, 10, 1, TWO_BLOCKS);
    assert_optimal(
        &p,
        &parse_rules("rule touch: EC_E(B, B) | EC_W(B, B)\n").unwrap(),
    );
    // ... one more is refused, naming the object and the limit.
    let p = problem(0, 0, MAX_POSITIONS + 10, 10, 1, TWO_BLOCKS);
    match solve(&p, &RuleSet::default()) {
        Err(e @ SynthError::TooLarge(_)) => {
            let m = e.to_string();
            assert!(
                m.contains("objects[0] `b1` has 262145 grid positions along x"),
                "{m}"
            );
            assert!(m.contains("at most 262144"), "{m}");
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
}

/// Just past the bound: a typed error naming the value, never a panic.
#[test]
fn synthesis_past_the_coordinate_bound_is_refused() {
    let m = MAX_SYNTH_COORD;
    let cases = [
        (problem(0, 0, m + 1, 100, 1, TWO_BLOCKS), "space.width"),
        (problem(0, -m - 1, 100, 100, 1, TWO_BLOCKS), "space.y"),
        (problem(1, 0, m, 100, 1, TWO_BLOCKS), "space reaches x"),
        (problem(-m, 0, m + 1, 100, 1, TWO_BLOCKS), "space.width"),
        (
            problem(
                0,
                0,
                m + 100,
                100,
                1,
                r#"{"class":"B","x":268435466,"y":0,"width":10,"height":10}"#,
            ),
            "space.width",
        ),
    ];
    for (p, what) in cases {
        match solve(&p, &RuleSet::default()) {
            Err(e @ SynthError::TooLarge(_)) => {
                let m = e.to_string();
                assert!(m.contains(what), "{m}");
                assert!(m.contains("268435456"), "names the limit: {m}");
            }
            other => panic!("expected TooLarge for {what}, got {other:?}"),
        }
    }
}

/// A time limit beyond what `Instant` holds means "no deadline", never an
/// overflow panic in `start + limit`.
#[test]
fn huge_library_time_limit_is_no_deadline() {
    let p = problem(0, 0, 40, 40, 10, TWO_BLOCKS);
    let opts = SynthOptions {
        stop: rccpack::stop::Stop::after(Duration::MAX),
        ..SynthOptions::default()
    };
    let r = synthesize(&p, &RuleSet::default(), &opts).unwrap();
    assert_eq!(r.status, Status::Optimal);
}

// ---- command line ----------------------------------------------------------

/// `run … --time-limit 1e20` panicked in `Duration::from_secs_f64`; every
/// command's time limit now goes through one validated parser: exit 1 with
/// a message naming the value and the range.
#[test]
fn bad_time_limits_exit_1_everywhere() {
    let out = crate::support::scratch("robust-time-limits").join("out");
    let out = out.to_str().unwrap();
    let problem = "examples/box-packing/problem.json";
    let rules = "examples/box-packing/pilot.rcc";
    for bad in ["1e20", "-1", "nan", "inf", "1000001", "soon"] {
        for args in [
            vec![
                "run",
                "examples/box-packing",
                "--out",
                out,
                "--time-limit",
                bad,
            ],
            vec!["synth", problem, "--rules", rules, "--time-limit", bad],
        ] {
            let o = rccpack(&args);
            let e = stderr(&o);
            assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
            assert!(!e.contains("panicked"), "{args:?}: {e}");
            assert!(
                e.contains("expected a number of seconds from 0 to 1000000"),
                "{args:?}: {e}"
            );
        }
    }
}

/// The largest time limit is accepted (and the problem solved well before).
#[test]
fn largest_time_limit_is_accepted() {
    let o = rccpack(&[
        "synth",
        "examples/box-packing/problem.json",
        "--rules",
        "examples/box-packing/pilot.rcc",
        "--time-limit",
        "1000000",
        "--quiet",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// Usage errors are bad input (exit 1), never clap's 2, which docs/cli.md
/// reserves for "infeasible"; help and version still exit 0.
#[test]
fn usage_errors_exit_1_help_exits_0() {
    let pilot = "examples/box-packing/pilot.rcc";
    let demos = "examples/box-packing/demos.json";
    for args in [
        vec!["score", demos, "--rules", pilot, "--contact", "bogus"],
        vec!["score", demos, "--rules", pilot, "--bogus"],
        vec!["synth", "x.json", "--rules", pilot, "--time-limit", "-1"],
        vec!["learn"],
        vec!["synth", "x.json"],
        vec!["frobnicate"],
        vec![],
        vec!["learn", demos, "--samples", "many"],
        vec!["learn", demos, "--samples", "100000000000000000000000"],
    ] {
        let o = rccpack(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).is_empty(), "{args:?}: a message");
    }
    for args in [
        vec!["--help"],
        vec!["--version"],
        vec!["synth", "--help"],
        vec!["help"],
    ] {
        let o = rccpack(&args);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
        assert!(!o.stdout.is_empty(), "{args:?}: printed to stdout");
    }
}

/// `learn --samples 1000000000000000` ran until killed; now refused at
/// once, naming the documented cap. The cap itself is accepted (checked on
/// the parameters, without drawing a million scenes here).
#[test]
fn absurd_sample_counts_are_refused() {
    let o = rccpack(&[
        "learn",
        "examples/box-packing/demos.json",
        "--samples",
        "1000000000000000",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains(
            "invalid --samples 1000000000000000: expected a whole number of at most 1000000"
        ),
        "{e}"
    );
    use rccpack::infer::LearnParams;
    use rccpack::limits::MAX_SAMPLES;
    assert_eq!(MAX_SAMPLES, 1_000_000, "the message writes the cap out");
    let at = LearnParams {
        samples: MAX_SAMPLES,
        ..LearnParams::default()
    };
    assert!(at.validate().is_ok());
    let past = LearnParams {
        samples: MAX_SAMPLES + 1,
        ..LearnParams::default()
    };
    assert!(past.validate().is_err());
}

/// The 200000×200000 problem of the issue through the command line: solved,
/// exit 0 (it used to panic inside Pumpkin).
#[test]
fn huge_space_through_the_command_line() {
    let dir = crate::support::scratch("robust-huge-space");
    let p = dir.join("huge.json");
    std::fs::write(
        &p,
        format!(
            r#"{{"space":{{"width":200000,"height":200000}},"grid":1,"objects":[{TWO_BLOCKS}]}}"#
        ),
    )
    .unwrap();
    let r = dir.join("r.rcc");
    std::fs::write(&r, "rule touch: EC_E(B, B) | EC_W(B, B)\n").unwrap();
    let o = rccpack(&[
        "synth",
        p.to_str().unwrap(),
        "--rules",
        r.to_str().unwrap(),
        "--quiet",
        "--node-limit",
        "100000",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // Past the bound: exit 1 naming the field.
    std::fs::write(
        &p,
        format!(
            r#"{{"space":{{"width":300000000,"height":10}},"grid":1,"objects":[{TWO_BLOCKS}]}}"#
        ),
    )
    .unwrap();
    let o = rccpack(&["synth", p.to_str().unwrap(), "--rules", r.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("space.width = 300000000 is too large"),
        "{}",
        stderr(&o)
    );
}

/// A rule built in code with a NaN, infinite or non-positive weight is a
/// typed error naming the rule (NaN used to become a coefficient of 1).
#[test]
fn non_finite_weights_are_refused() {
    use rccpack::rules::{Rule, Strength};
    let p = problem(0, 0, 40, 40, 10, TWO_BLOCKS);
    let base = parse_rules("rule touch: EC_E(B, B) | EC_W(B, B)\n").unwrap();
    for w in [f64::NAN, f64::INFINITY, 0.0, -1.0] {
        let mut rules = base.clone();
        let r: Rule = rules.rules[0].clone().with_strength(Strength::Weight(w));
        rules.rules[0] = r;
        match solve(&p, &rules) {
            Err(e @ SynthError::BadWeight { .. }) => {
                let SynthError::BadWeight { rule, weight } = &e else {
                    unreachable!()
                };
                assert_eq!((rule.as_str(), weight.as_str()), ("touch", &*w.to_string()));
                let m = e.to_string();
                assert!(m.contains("expected a finite number greater than 0"), "{m}");
            }
            other => panic!("weight {w}: expected BadWeight, got {other:?}"),
        }
    }
}

/// Found by the first probes: on this infeasible problem (the
/// bundled example with 54 learned rules hard and one negated) Pumpkin's
/// `extract_core` panicked or ran for minutes past the time limit. The
/// conflict is now shrunk by deletion, every solve under the limits.
#[test]
fn infeasible_probe_problem_is_explained_without_core_extraction() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let p = Scene::from_json(
        &std::fs::read_to_string(root.join("examples/box-packing/problem.json")).unwrap(),
    )
    .unwrap();
    let rules = parse_rules(
        &std::fs::read_to_string(root.join("tests/fixtures/regressions/core-hang.rcc")).unwrap(),
    )
    .unwrap();
    let opts = SynthOptions {
        stop: rccpack::stop::Stop::after(Duration::from_secs(120)),
        ..SynthOptions::default()
    };
    let started = std::time::Instant::now();
    let r = synthesize(&p, &rules, &opts).unwrap();
    assert_eq!(r.status, Status::Infeasible);
    let c = r.conflict.expect("a conflict");
    assert!(!c.objects_cannot_fit);
    assert!(
        c.hard_rules.contains(&"not_R_touches_flush_R".to_string()),
        "{c:?}"
    );
    assert!(c.hard_rules.len() < rules.rules.len(), "{c:?}");
    assert!(started.elapsed() < Duration::from_secs(150));
}

/// At most `MAX_OBJECTS` objects per scene: a scene at the limit (a row of
/// 1×1 blocks, one per cell, no overlap) is valid and its relations are
/// computed; one more object is refused with the count and the limit named,
/// at the JSON field `objects`.
#[test]
fn object_count_limit() {
    use rccpack::limits::MAX_OBJECTS;
    assert_eq!(MAX_OBJECTS, 10_000, "the README writes the limit out");
    let scene = |n: usize| {
        let objects: Vec<String> = (0..n)
            .map(|i| {
                format!(
                    r#"{{"id":"o{i}","class":"B","x":{},"y":{},"width":1,"height":1}}"#,
                    i % 100,
                    i / 100 + 1
                )
            })
            .collect();
        format!(
            r#"{{"space":{{"width":100,"height":102}},"grid":1,"objects":[{}]}}"#,
            objects.join(",")
        )
    };
    let at = Scene::from_json(&scene(MAX_OBJECTS)).expect("a scene at the limit is valid");
    assert_eq!(at.objects.len(), MAX_OBJECTS);
    let rules = parse_rules("rule r: !DR_N(B, B)\n").unwrap();
    let ev = rccpack::eval::evaluate(&at, &rules, Contact::Point);
    assert_eq!(ev.rules[0].subjects, MAX_OBJECTS);
    let e = Scene::from_json(&scene(MAX_OBJECTS + 1))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("objects") && e.contains("10001 objects is too many; expected at most 10000"),
        "{e}"
    );
}

/// Found by the `synth` fuzz target: a space starting at y = −1 made a task
/// of the redundant cumulative start at −1, which Pumpkin 0.5's time-table
/// takes for its "no profile yet" mark, and it panicked ("negative
/// resource usage"). Starts are now shifted to be at least 0.
#[test]
fn cumulative_start_at_minus_one_does_not_panic() {
    let p = Scene::from_json(
        r#"{"space":{"x":11,"y":-1,"width":60,"height":23},"grid":20,"objects":[
            {"id":"o0","class":"B","width":10,"height":20},
            {"id":"o1","class":"B","width":20,"height":10}]}"#,
    )
    .unwrap();
    // The fuzz input's rules: r1 is infeasible (two Bs, each east of every
    // other object), so `explain` solves again under assumptions.
    let rules = parse_rules(
        "rule r0: FL_E(B, at least 1 W) & EC_N(B, *) & AL_E(B, A) | (FL_E(B, at least 2 W) | DR_E(B, *) | DR_E(B, some *))
rule r1 hard: (DR_E(B, *) & DR_E(B, at least 0 *)) & DR_E(B, *) & DR_S(B, no B)
rule r2 weight 2: !AL_E(B, no B) & (DR_W(B, W) | DR_W(B, W) | DR_W(B, A))
",
    )
    .unwrap();
    let opts = SynthOptions {
        contact: Contact::Point,
        stop: rccpack::stop::Stop::never().with_nodes(1691),
        seed: 12948890938015724467,
        symmetry_breaking: true,
        redundant: true,
        explain: true,
        ..SynthOptions::default()
    };
    let r = synthesize(&p, &rules, &opts).unwrap();
    assert_eq!(r.status, Status::Infeasible);
    let c = r.conflict.expect("an explanation");
    assert_eq!(c.hard_rules, vec!["r1".to_string()]);
}

/// More documented limits, at and just past their bounds: the rule text size,
/// the statements one learning run weighs, values echoed in messages,
/// `--oracle-timeout`.
#[test]
fn issue_21_limits_at_and_past_their_bounds() {
    use rccpack::limits::{cut, MAX_ECHO, MAX_RULES_BYTES, MAX_STATEMENTS};
    // Rule text: at the limit parsed, one byte past refused before parsing.
    let mut text = String::from("rule r: DR_N(R, R)\n");
    text.push_str(&"#".repeat(MAX_RULES_BYTES - text.len() - 1));
    text.push('\n');
    assert_eq!(text.len(), MAX_RULES_BYTES);
    assert!(parse_rules(&text).is_ok());
    text.push(' ');
    let e = parse_rules(&text).unwrap_err().to_string();
    assert!(e.contains("expected at most 16777216 bytes"), "{e}");
    // Statements: exactly MAX_STATEMENTS given statements are weighed,
    // one more is refused.
    let demo = Scene::from_json(
        r#"{"space": {"width": 100, "height": 100}, "objects": [
            {"class": "R", "x": 0, "y": 0, "width": 10, "height": 10},
            {"class": "G", "x": 50, "y": 50, "width": 10, "height": 10}]}"#,
    )
    .unwrap();
    let statements = |n: usize| {
        let text: String = (0..n)
            .map(|i| format!("rule s{i}: DR_N(R, G) | DR_E(R, G)\n"))
            .collect();
        parse_rules(&text).unwrap()
    };
    let params = rccpack::infer::LearnParams {
        samples: 1,
        ..rccpack::infer::LearnParams::default()
    };
    let demos = [demo];
    let at = statements(MAX_STATEMENTS);
    assert!(rccpack::infer::learn(&demos, Some(&at), &params).is_ok());
    let past = statements(MAX_STATEMENTS + 1);
    let e = rccpack::infer::learn(&demos, Some(&past), &params)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("50001 statements") && e.contains("at most 50000"),
        "{e}"
    );
    // Echoed values: whole at 80 characters, cut past it.
    let v = "x".repeat(MAX_ECHO);
    assert_eq!(cut(&v), v);
    let past = cut(&"x".repeat(MAX_ECHO + 1));
    assert_eq!(past.chars().count(), 61);
    assert!(past.ends_with('…'));
    // --oracle-timeout takes the time-limit range.
    let o = rccpack(&["ask", "examples/box-packing", "--oracle-timeout", "1000001"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("expected a number of seconds from 0 to 1000000"));
}

/// `rccpack bench …` runs `rccpack-bench` from the same folder with the
/// same arguments and exits with its code; without it beside `rccpack`, it
/// exits 1 naming the binary it looked for.
#[test]
fn bench_delegates_to_rccpack_bench_beside_it() {
    // `cargo test` at the root builds it; fails naming it otherwise.
    let _ = crate::support::bench_command();
    let o = rccpack(&["bench", "tasks", "--help"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("Usage: rccpack-bench tasks [OPTIONS]"),
        "{}",
        stdout(&o)
    );
    let o = rccpack(&["bench", "thesis", "--sets", "0"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("invalid value '0' for '--sets"),
        "{}",
        stderr(&o)
    );
    let dir = crate::support::scratch("bench-delegate-alone");
    let alone = dir.join("rccpack");
    std::fs::copy(env!("CARGO_BIN_EXE_rccpack"), &alone).expect("copy rccpack");
    let o = std::process::Command::new(&alone)
        .args(["bench", "thesis"])
        .output()
        .expect("run the copy");
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains(&format!(
            "{} not found",
            dir.join("rccpack-bench").display()
        )),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
