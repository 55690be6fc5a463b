//! `rccpack-bench tasks`: the realistic-task generator is
//! deterministic, its demonstrations are valid scenes that keep every rule
//! learned from them, its problems have the requested counts and fit their
//! box; and a quick CLI run exits 0 and writes problems that `synth` reruns.

use rccpack::eval::evaluate;
use rccpack::relations::Contact;
use rccpack_bench::tasks::{all_tasks, scaled, TaskSeries, TasksConfig, TASK_CLASSES};
use std::collections::BTreeMap;
use std::time::Duration;

fn counts(scene: &rccpack::scene::Scene) -> BTreeMap<String, usize> {
    let mut m = BTreeMap::new();
    for o in scene.objects.iter().filter(|o| !o.fixed) {
        *m.entry(o.class.clone()).or_insert(0) += 1;
    }
    m
}

#[test]
fn generator_is_deterministic_valid_and_sized() {
    let mut cfg = TasksConfig::quick(5, Duration::from_secs(1));
    cfg.tasks = 4;
    cfg.sizes = vec![1.0, 1.5, 2.0, 3.0];
    cfg.example_counts = vec![5, 12];
    let a = all_tasks(&cfg).expect("tasks");
    let b = all_tasks(&cfg).expect("tasks");
    assert_eq!(a, b, "same seed, same tasks");
    assert_eq!(a.len(), 5);
    // Another seed gives other tasks.
    let mut other = cfg.clone();
    other.seed = 6;
    assert_ne!(all_tasks(&other).unwrap()[0].demos, a[0].demos);
    // Fewer sizes (up to 3) do not change the problems that remain.
    let mut fewer = cfg.clone();
    fewer.sizes = vec![1.5];
    let f = all_tasks(&fewer).unwrap();
    assert_eq!(f[1].problems[0].scene, a[1].problems[1].scene);
    assert_eq!(f[1].rcc, a[1].rcc);

    for t in &a {
        let label = format!("{} {}", t.series.name(), t.index);
        assert!(
            (3..=8).contains(&t.demos.len()),
            "{label}: {} demos",
            t.demos.len()
        );
        assert!(!t.rules.rules.is_empty(), "{label}: no rules learned");
        let walls: Vec<_> = t.demos[0].objects.iter().filter(|o| o.fixed).collect();
        assert_eq!(walls.len(), 4, "{label}: four walls");
        assert!(walls.iter().all(|w| w.class == "W"));
        // The interior: between the west and east, south and north walls.
        let r = |id: &str| {
            walls
                .iter()
                .find(|w| w.id == id)
                .and_then(|w| w.rect())
                .unwrap()
        };
        let (ix0, iy0) = (
            r("w_west").x + r("w_west").w,
            r("w_south").y + r("w_south").h,
        );
        let (ix1, iy1) = (r("w_east").x, r("w_north").y);
        let interior = (ix1 - ix0) * (iy1 - iy0);
        for (i, d) in t.demos.iter().enumerate() {
            d.validate()
                .unwrap_or_else(|e| panic!("{label} demo {i} invalid: {e}"));
            assert!(d.is_complete(), "{label} demo {i} incomplete");
            assert_eq!(d.space, t.demos[0].space, "{label}: one space");
            for o in d.objects.iter().filter(|o| !o.fixed) {
                assert!(d.on_grid(o), "{label} demo {i}: {} off grid", o.id);
                let q = o.rect().unwrap();
                assert!(
                    q.x >= ix0 && q.y >= iy0 && q.x + q.w <= ix1 && q.y + q.h <= iy1,
                    "{label} demo {i}: {} outside the box",
                    o.id
                );
            }
            // Every learned rule is a candidate: every demonstration keeps it.
            let ev = evaluate(d, &t.rules, Contact::Point);
            assert!(ev.hard_ok());
            let broken: Vec<_> = ev
                .rules
                .iter()
                .filter(|r| r.satisfied < r.subjects || !r.violators.is_empty())
                .map(|r| r.name.clone())
                .collect();
            assert!(
                (ev.score - 1.0).abs() < 1e-12,
                "{label} demo {i} scores {} under its learned rules; broken: {broken:?}",
                ev.score
            );
        }
        if t.series == TaskSeries::Tasks {
            assert!((2..=4).contains(&t.classes.len()));
            let max_shown: BTreeMap<String, usize> =
                t.demos.iter().fold(BTreeMap::new(), |mut m, d| {
                    for (c, n) in counts(d) {
                        let e = m.entry(c).or_insert(0);
                        *e = (*e).max(n);
                    }
                    m
                });
            for (ci, c) in t.classes.iter().enumerate() {
                assert_eq!(c.class, TASK_CLASSES[ci]);
                assert_eq!(max_shown[&c.class], c.max_count, "{label}: {}", c.class);
                assert!((2..=6).contains(&c.max_count));
            }
            assert_eq!(t.problems.len(), cfg.sizes.len());
            for (p, &m) in t.problems.iter().zip(&cfg.sizes) {
                let got = counts(&p.scene);
                let mut area = 0;
                for c in &t.classes {
                    assert_eq!(got[&c.class], scaled(c.max_count, m), "{}", p.name);
                    area += got[&c.class] as i64 * c.width * c.height;
                }
                assert!(
                    (10..=60).contains(&p.movable),
                    "{}: {} objects",
                    p.name,
                    p.movable
                );
                assert!(
                    2 * area <= interior,
                    "{}: blocks of area {area} in an interior of {interior}",
                    p.name
                );
            }
        } else {
            for (p, n) in t.problems.iter().zip([5usize, 12]) {
                assert!(counts(&p.scene).values().all(|&k| k == n), "{}", p.name);
                assert_eq!(p.movable, 3 * n);
            }
        }
        for p in &t.problems {
            p.scene.validate().unwrap();
            assert_eq!(
                p.scene.space, t.demos[0].space,
                "{}: the demos' space",
                p.name
            );
            assert!(p
                .scene
                .objects
                .iter()
                .filter(|o| !o.fixed)
                .all(|o| o.x.is_none()));
        }
    }
}

#[test]
fn quick_cli_run_exits_zero_and_problems_rerun() {
    let out = crate::support::scratch("bench-tasks-quick").join("out");
    let problems = out.join("problems");
    let o = crate::support::bench_command()
        .args(["tasks", "--quick", "--time-limit", "0.2", "--out"])
        .arg(&out)
        .arg("--problems-out")
        .arg(&problems)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "exit {:?}\nstdout:\n{stdout}\nstderr:\n{}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(stdout.contains("tasks    1x"), "{stdout}");
    // Not a terminal: one progress line per solved problem on stderr.
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("[5/5] example-5 (15 objects"), "{stderr}");
    assert!(stdout.contains("example  5/class"), "{stdout}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("tasks.json")).unwrap()).unwrap();
    // 2 tasks × 2 sizes + the example at 5 per class.
    assert_eq!(json["rows"].as_array().unwrap().len(), 5);
    // Without --turnable, tasks.json has none of its fields.
    let text = std::fs::read_to_string(out.join("tasks.json")).unwrap();
    for key in ["turnable", "habits_", "orientation", "not_applicable"] {
        assert!(!text.contains(key), "{key} in tasks.json");
    }
    for f in ["task00-1x.json", "task01-1.5x.rcc", "example-5.demos.json"] {
        assert!(problems.join(f).is_file(), "{f} missing");
    }
    let o = crate::support::command()
        .current_dir(&problems)
        .args([
            "synth",
            "task00-1x.json",
            "--rules",
            "task00-1x.rcc",
            "--like",
            "task00-1x.demos.json",
            "--time-limit",
            "0.2",
            "-o",
            "sol.json",
        ])
        .output()
        .unwrap();
    assert!(
        matches!(o.status.code(), Some(0) | Some(3)),
        "synth rerun: {:?}\n{}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
    let _ = std::fs::remove_dir_all(&out);
}

/// Out-of-range flags are refused at once (exit 1, naming the flag and the
/// value), before anything is generated or written.
#[test]
fn bad_flags_are_refused() {
    let out = crate::support::scratch("bench-tasks-refuse").join("out");
    for (args, names) in [
        (vec!["--sizes", "0"], "invalid value '0' for '--sizes"),
        (vec!["--sizes", "1,11"], "invalid value '11' for '--sizes"),
        (vec!["--sizes", "nan"], "invalid value 'nan' for '--sizes"),
        (vec!["--tasks", "1001"], "invalid value '1001' for '--tasks"),
        (
            vec!["--example-counts", "5,0"],
            "invalid value '0' for '--example-counts",
        ),
        (vec!["--peers", "cplex"], "unknown peer `cplex`"),
        (
            vec!["--time-limit", "nan"],
            "invalid value 'nan' for '--time-limit",
        ),
    ] {
        let o = crate::support::bench_command()
            .args(["tasks", "--out"])
            .arg(&out)
            .args(&args)
            .output()
            .unwrap();
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(e.contains(names), "{args:?}: message names {names}: {e}");
        assert!(!out.exists(), "{args:?}: refused before writing");
    }
}

/// Generated tasks without `--turnable` are those of earlier versions,
/// byte for byte: the demonstrations, problems and learned rules of seed
/// 0's first two tasks, kept in `tests/fixtures/tasks-seed0.txt` (written
/// before `--turnable` existed; regenerate with `RCCPACK_BLESS=1` only on
/// purpose).
#[test]
fn generated_tasks_without_turnable_are_unchanged() {
    let mut cfg = TasksConfig::quick(0, Duration::from_secs(1));
    cfg.example_counts.clear();
    let mut text = String::new();
    for t in all_tasks(&cfg).expect("tasks") {
        text.push_str(&format!("# task {}: {}\n", t.index, t.style));
        text.push_str(&rccpack::scene::scenes_to_json(&t.demos));
        text.push('\n');
        for p in &t.problems {
            text.push_str(&format!("# {}\n{}\n", p.name, p.scene.to_json()));
        }
        text.push_str(&t.rcc);
    }
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/tasks-seed0.txt"
    );
    if std::env::var_os("RCCPACK_BLESS").is_some() {
        std::fs::write(path, &text).unwrap();
    }
    let want = std::fs::read_to_string(path).expect("tests/fixtures/tasks-seed0.txt");
    assert!(text == want, "the generated tasks changed");
}

/// `--turnable`: the oblong classes turn, the demonstrator lays each flat
/// or stands it on end, and the classes, habits and box are those of the
/// flat tasks (the coins come from a stream of their own).
#[test]
fn turnable_tasks_turn_the_oblong_classes_and_stand_some_on_end() {
    use rccpack::rules::Formula;
    use rccpack_bench::tasks::Orientation;
    let mut cfg = TasksConfig::quick(0, Duration::from_secs(1));
    cfg.example_counts.clear();
    cfg.tasks = 6;
    let flat = all_tasks(&cfg).expect("tasks");
    cfg.turnable = true;
    let turning = all_tasks(&cfg).expect("tasks");
    assert_eq!(all_tasks(&cfg).unwrap(), turning, "same seed, same tasks");
    let (mut on_end, mut laid_flat, mut learned) = (0, 0, 0);
    for (f, t) in flat.iter().zip(&turning) {
        assert_eq!(
            f.demos[0].space, t.demos[0].space,
            "task {}: same box",
            t.index
        );
        for (fc, tc) in f.classes.iter().zip(&t.classes) {
            assert_eq!(
                (&fc.class, fc.width, fc.height, fc.max_count, fc.habit),
                (&tc.class, tc.width, tc.height, tc.max_count, tc.habit)
            );
            assert_eq!(fc.orientation, Orientation::Fixed);
            let oblong = tc.width != tc.height;
            assert_eq!(tc.orientation != Orientation::Fixed, oblong, "{}", tc.class);
            // Every block of the class in the demonstrations: turnable when
            // the class turns, turned when it stands on end.
            for o in t.demos.iter().flat_map(|d| &d.objects) {
                if o.class == tc.class {
                    assert_eq!((o.width, o.height), (tc.width, tc.height), "own size");
                    assert_eq!(o.turnable, oblong);
                    assert_eq!(o.turned, tc.orientation == Orientation::OnEnd);
                }
            }
            for p in &t.problems {
                for o in p.scene.objects.iter().filter(|o| o.class == tc.class) {
                    assert!(!o.is_placed() && o.turnable == oblong && !o.turned);
                }
            }
            let meant = tc.orientation.meant(&tc.class);
            match tc.orientation {
                Orientation::OnEnd => on_end += 1,
                Orientation::Flat => laid_flat += 1,
                Orientation::Fixed => assert!(meant.is_none()),
            }
            if let Some(m) = meant {
                let want = if tc.orientation == Orientation::OnEnd {
                    Formula::Turned(tc.class.clone())
                } else {
                    Formula::not(Formula::Turned(tc.class.clone()))
                };
                assert_eq!(m, want);
                learned += usize::from(t.rules.rules.iter().any(|r| r.formula == m));
            }
        }
    }
    assert!(
        on_end > 0 && laid_flat > 0,
        "on end {on_end}, flat {laid_flat}"
    );
    // Every demonstration keeps the habit: learning keeps it (at most one
    // miss over the six tasks).
    assert!(
        learned + 1 >= on_end + laid_flat,
        "{learned} of {}",
        on_end + laid_flat
    );
}

/// The emitted model of a turnable task has orientation variables, so a
/// peer solves it (checked, when CP-SAT is installed); a peer cell that
/// is "n/a (turnable)" (an emitted model that could not turn a block) is
/// not a failure: in the line, the peer cell and the failure count.
#[test]
fn a_peer_solves_turnable_blocks_and_not_applicable_is_not_failed() {
    use rccpack::synth::{synthesize, verify_solution};
    use rccpack_bench::peers::Peer;
    use rccpack_bench::tasks::{
        peer_not_applicable, row_line, solve_peer, summarize, table_text, TaskRow,
    };
    let mut cfg = TasksConfig::quick(0, Duration::from_secs(1));
    cfg.example_counts.clear();
    cfg.tasks = 1;
    cfg.turnable = true;
    let t = all_tasks(&cfg).unwrap().remove(0);
    let p = &t.problems[0];
    assert!(p.scene.objects.iter().any(|o| o.turnable), "{}", t.style);
    let verify = |a: &rccpack::scene::Scene,
                  b: &rccpack::scene::Scene,
                  r: &rccpack::rules::RuleSet,
                  c| { verify_solution(a, b, r, c).map_err(|e| e.to_string()) };
    let engine = rccpack_bench::Solver {
        solve: &synthesize,
        verify: &verify,
    };
    let opts = rccpack_bench::tasks::solve_options(&cfg, &[], false);
    let e = rccpack::synth::emit::emitted(&p.scene, &t.rules, &opts).expect("emitted");
    assert!(e.model.vars.iter().any(|v| v.turn), "orientation variables");
    if rccpack_bench::peers::check_available(Peer::CpSat).is_ok() {
        let row = solve_peer(engine, &cfg, &p.scene, &t.rules, Peer::CpSat);
        assert!(!peer_not_applicable(&row), "{row:?}");
        assert!(row.status.is_some() && row.error.is_none(), "{row:?}");
    }
    let row = rccpack_bench::thesis::PeerRow {
        peer: Peer::CpSat.name().into(),
        status: None,
        time_ms: 0.0,
        process_ms: 0.0,
        score: None,
        verified: None,
        error: Some(format!(
            "{}: no orientation in the emitted model",
            rccpack_bench::tasks::PEER_NOT_APPLICABLE
        )),
    };
    assert!(peer_not_applicable(&row), "{row:?}");
    let so = rccpack_bench::tasks::solve_once(engine, &p.scene, &t.rules, &opts);
    let task_row = TaskRow {
        series: TaskSeries::Tasks,
        task: 0,
        size_index: 0,
        size: p.size.clone(),
        name: p.name.clone(),
        movable: p.movable,
        rules: t.rules.rules.len(),
        score_only: so,
        like: None,
        peers: vec![row],
        turnable: p.scene.objects.iter().filter(|o| o.turnable).count(),
        habits_learned: Some([1, 1]),
    };
    let line = row_line(&task_row);
    assert!(line.contains("cp-sat n/a (turnable)"), "{line}");
    assert!(!line.contains("failed"), "{line}");
    let summary = summarize(&[task_row]);
    let cell = &summary[0].peers[0];
    assert_eq!((cell.failures, cell.not_applicable, cell.proven), (0, 1, 0));
    let text = table_text(&summary);
    assert!(text.contains("n/a (turnable) 1"), "{text}");
    assert!(text.contains("turnable"), "{text}");
}

/// `bench tasks --turnable` runs, every layout checked, and its table says
/// how many turnable blocks and orientation habits there were.
#[test]
fn turnable_cli_run_reports_orientation_habits() {
    let out = crate::support::scratch("bench-tasks-turnable").join("out");
    let o = crate::support::bench_command()
        .args([
            "tasks",
            "--turnable",
            "--tasks",
            "2",
            "--sizes",
            "1",
            "--no-example",
            "--no-like",
            "--time-limit",
            "0.5",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        stdout.contains("turnable, stood on end") || stdout.contains("turnable, laid flat"),
        "{stdout}"
    );
    assert!(
        stdout.contains("turnable    learned    kept_so"),
        "{stdout}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("tasks.json")).unwrap()).unwrap();
    assert_eq!(json["config"]["turnable"], true);
    let rows = json["rows"].as_array().unwrap();
    assert!(rows.iter().any(|r| r["turnable"].as_u64().unwrap_or(0) > 0));
    let _ = std::fs::remove_dir_all(&out);
}
