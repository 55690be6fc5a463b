//! Third hardening pass, through the built binary: what a hostile but
//! fair user tried on the fourth edition, and what the tool must answer.

use crate::support::{rccpack, scratch, stderr, write_file};
use std::time::{Duration, Instant};

/// A problem with `n` movable 10×10 `R` objects in a square space.
fn r_problem(n: usize) -> String {
    let side = 10 * ((2 * n) as f64).sqrt().ceil() as i64 + 20;
    let objects: Vec<String> = (0..n)
        .map(|i| format!(r#"{{"id": "r{i}", "class": "R", "width": 10, "height": 10}}"#))
        .collect();
    format!(
        r#"{{"space": {{"width": {side}, "height": {side}}}, "grid": 10, "objects": [{}]}}"#,
        objects.join(", ")
    )
}

/// Item 1: a group statement counts toward the pair limit like any other
/// rule. `group(R)` over 600 objects (179 700 pairs, four relations each)
/// built until the memory ran out and aborted; it is refused at once with
/// exit 1, as `EC_N(R, R)` over the same objects is. Every shape and
/// negated shape is counted; a small class still synthesises.
#[test]
fn group_statements_count_toward_the_pair_limit() {
    let d = scratch("harden3-group-pairs");
    let p = write_file(&d, "p.json", &r_problem(600));
    for rule in [
        "group(R)",
        "not block(R)",
        "row(R)",
        "column(R)",
        "EC_N(R, R)",
    ] {
        let r = write_file(&d, "r.rcc", &format!("rule g: {rule}\n"));
        let start = Instant::now();
        let o = rccpack(&["synth", &p, "--rules", &r, "--quiet", "-o", "/dev/null"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{rule}: {e}");
        assert!(
            e.contains("pairs of objects") && e.contains("120000"),
            "{rule}: {e}"
        );
        assert!(start.elapsed() < Duration::from_secs(10), "{rule}");
    }
    let small = write_file(&d, "small.json", &r_problem(6));
    let r = write_file(&d, "r.rcc", "rule g: group(R)\n");
    let o = rccpack(&["synth", &small, "--rules", &r, "--quiet", "-o", "/dev/null"]);
    assert!(o.status.success(), "{}", stderr(&o));
}
