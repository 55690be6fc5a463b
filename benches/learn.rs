//! Learning benchmark: `cargo bench --bench learn`.
//!
//! A hand-written timing harness (median of several runs, wall clock): the
//! bundled box-packing demonstrations with generated templates at 1000
//! samples (first- and second-edition templates), growth with samples (1k,
//! 10k, 100k) and growth with objects per scene (10, 40, 160; synthetic
//! scenes in a 1200×1200 space), with the second-edition templates.

use rccpack::infer::{learn, LearnParams, Learned, Templates};
use rccpack::scene::{scenes_from_json, Object, Scene, Space};
use std::time::{Duration, Instant};

fn median_time(runs: usize, mut f: impl FnMut() -> Learned) -> (Duration, Learned) {
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs {
        let t = Instant::now();
        let l = f();
        times.push(t.elapsed());
        last = Some(l);
    }
    times.sort();
    (times[runs / 2], last.expect("runs ≥ 1"))
}

/// Four demonstrations with `n` 20×20 blocks (classes R, G, B in bands,
/// packed in rows) inside fixed walls, in a 1200×1200 space.
fn synthetic(n: usize) -> Vec<Scene> {
    (0..4)
        .map(|d| {
            let mut objects = vec![
                wall("ws", 100, 100, 1000, 10),
                wall("wn", 100, 1090, 1000, 10),
                wall("ww", 100, 110, 10, 980),
                wall("we", 1090, 110, 10, 980),
            ];
            let per_row = 16 + d; // a little variety between demos
            for i in 0..n {
                let class = ["R", "G", "B"][i * 3 / n];
                objects.push(Object {
                    id: format!("o{i}"),
                    class: class.into(),
                    x: Some(110 + 20 * (i % per_row) as i64),
                    y: Some(110 + 20 * (i / per_row) as i64),
                    width: 20,
                    height: 20,
                    fixed: false,
                    turnable: false,
                    turned: false,
                });
            }
            Scene {
                space: Space {
                    x: 0,
                    y: 0,
                    width: 1200,
                    height: 1200,
                },
                grid: 10,
                objects,
            }
        })
        .collect()
}

fn wall(id: &str, x: i64, y: i64, w: i64, h: i64) -> Object {
    Object::fixed_at(id, "W", x, y, w, h)
}

fn row(case: &str, demos: &[Scene], templates: Templates, samples: usize, runs: usize) {
    let params = LearnParams {
        samples,
        templates,
        ..LearnParams::default()
    };
    let (t, l) = median_time(runs, || learn(demos, None, &params).expect("learn"));
    let objects = demos.iter().map(|s| s.objects.len()).sum::<usize>() as f64 / demos.len() as f64;
    let candidates = l.statements.iter().filter(|s| s.candidate).count();
    println!(
        "{case:<22} {templates:>9} {samples:>8} {objects:>9.1} {:>10} {candidates:>10} {:>7} {:>10.2}",
        l.statements.len(),
        l.order.len(),
        t.as_secs_f64() * 1e3
    );
}

fn main() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/box-packing/demos.json"
    );
    let demos = scenes_from_json(&std::fs::read_to_string(path).expect("demos")).expect("parse");
    println!(
        "threads: {}  (median wall time of the runs)",
        rayon::current_num_threads()
    );
    println!(
        "{:<22} {:>9} {:>8} {:>9} {:>10} {:>10} {:>7} {:>10}",
        "case", "templates", "samples", "objects", "statements", "candidates", "learned", "ms"
    );
    let (first, second) = (Templates::First, Templates::Second);
    row("box-packing", &demos, first, 1_000, 21);
    row("box-packing", &demos, second, 1_000, 21);
    row("box-packing", &demos, second, 10_000, 5);
    row("box-packing", &demos, second, 100_000, 3);
    for n in [10, 40, 160] {
        row(
            &format!("synthetic {n} blocks"),
            &synthetic(n),
            second,
            1_000,
            5,
        );
    }
}
