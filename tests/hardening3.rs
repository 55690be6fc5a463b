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

/// Width and height of a PNG file, read from its header.
fn png_size(path: &std::path::Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap();
    assert_eq!(&b[1..4], b"PNG", "{}", path.display());
    let be = |i: usize| u32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
    (be(16), be(20))
}

/// A scene on a table `width` units wide (millimetres), with an `A` and a
/// `B` object side by side at `x`.
fn wide_scene(width: i64, x: i64) -> String {
    format!(
        r#"{{"space": {{"width": {width}, "height": 2000}}, "grid": 500, "objects": [
            {{"id": "a", "class": "A", "x": {x}, "y": 0, "width": 1000, "height": 1000}},
            {{"id": "b", "class": "B", "x": {}, "y": 0, "width": 1000, "height": 1000}}]}}"#,
        x + 1000
    )
}

/// Items 4 and 16: `run` on a valid task whose table is 40 000 units wide
/// wrote `learned.rcc`, the report and `solution.json`, then failed to
/// draw `solution.png`; the picture is now drawn scaled to fit the PNG
/// limits, and `render` says at what scale.
#[test]
fn a_wide_table_is_drawn_scaled_to_fit() {
    let d = scratch("harden3-wide");
    write_file(
        &d,
        "demos.json",
        &format!(
            "[{}, {}]",
            wide_scene(40_000, 0),
            wide_scene(40_000, 20_000)
        ),
    );
    write_file(
        &d,
        "problem.json",
        r#"{"space": {"width": 40000, "height": 2000}, "grid": 500, "objects": [
            {"id": "a", "class": "A", "width": 1000, "height": 1000},
            {"id": "b", "class": "B", "width": 1000, "height": 1000}]}"#,
    );
    let t = d.to_str().unwrap();
    let o = rccpack(&["run", t, "--samples", "200", "--time-limit", "10"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h) = png_size(&d.join("solution.png"));
    assert!(w <= 32_000 && h <= 32_000, "{w}x{h}");
    assert!(w > 16_000, "scaled no more than needed: {w}x{h}");
    let out = d.join("wide.png");
    let o = rccpack(&[
        "render",
        &d.join("problem.json").to_string_lossy(),
        "-o",
        &out.to_string_lossy(),
        "--scale",
        "2",
    ]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("at scale 0.") && e.contains("32000 pixels a side"),
        "{e}"
    );
    let (w, _) = png_size(&out);
    assert!(w <= 32_000, "{w}");
}
