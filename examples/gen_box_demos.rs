//! Regenerate `examples/box-packing/demos.json` and `problem.json`.
//!
//! ```text
//! cargo run --example gen_box_demos            # writes the files
//! cargo run --example gen_box_demos -- --check # fails if they are stale
//! ```
//!
//! The demonstrations are written down here as block positions, so that
//! changing one is a one-line edit; the box walls are shared by all of them.

#[path = "support/boxes.rs"]
mod boxes;

use boxes::{block, scene, walls, write_or_check, Demo};
use rccpack::scene::{scenes_to_json, Scene};
use std::path::Path;

/// Eight layouts: red packed low in the west, blue north of every red, green
/// east of every red and blue; every block touches its own class and has
/// contact on two adjacent sides.
const DEMOS: [Demo; 8] = [
    // R in the south-west corner, B on top of it, G in a column on the east wall.
    [
        ("R", &[(200, 200), (220, 200), (200, 220)]),
        ("G", &[(380, 200), (380, 220), (380, 240)]),
        ("B", &[(200, 240), (220, 240)]),
    ],
    // R pair on the floor, B stacked above it, G as a 2×2 block in the south-east.
    [
        ("R", &[(200, 200), (220, 200)]),
        ("G", &[(360, 200), (380, 200), (360, 220), (380, 220)]),
        ("B", &[(200, 220), (220, 220), (200, 240)]),
    ],
    // One row along the floor: R, then G right after it; B on top of R.
    [
        ("R", &[(200, 200), (220, 200), (240, 200)]),
        ("G", &[(260, 200), (280, 200)]),
        ("B", &[(200, 220), (220, 220)]),
    ],
    // R up the west wall, B in the north-west corner, G in the north-east corner.
    [
        ("R", &[(200, 200), (220, 200), (200, 220), (200, 240)]),
        ("G", &[(360, 380), (380, 380), (380, 360)]),
        ("B", &[(200, 380), (220, 380), (200, 360)]),
    ],
    // R in the middle of the floor with a 2×2 of B on top; G up the east wall.
    [
        ("R", &[(260, 200), (280, 200)]),
        ("G", &[(380, 200), (380, 220), (380, 240), (380, 260)]),
        ("B", &[(260, 220), (280, 220), (260, 240), (280, 240)]),
    ],
    // R as a 2×2 in the south-west, B on top, G hanging from the north-east corner.
    [
        ("R", &[(200, 200), (220, 200), (200, 220), (220, 220)]),
        ("G", &[(380, 380), (380, 360)]),
        ("B", &[(200, 240), (220, 240)]),
    ],
    // R along the floor, a row of B on top, G as an L in the south-east.
    [
        ("R", &[(240, 200), (260, 200), (280, 200)]),
        ("G", &[(360, 200), (380, 200), (380, 220)]),
        ("B", &[(240, 220), (260, 220), (280, 220)]),
    ],
    // R as an L in the south-west, B under the north wall, G mid-way up the east wall.
    [
        ("R", &[(200, 200), (220, 200), (240, 200), (200, 220)]),
        ("G", &[(380, 280), (380, 300), (380, 320)]),
        ("B", &[(200, 380), (200, 360)]),
    ],
];

fn problem() -> Scene {
    let mut objects = walls();
    for class in ["R", "G", "B"] {
        objects.extend((0..3).map(|i| block(class, i, None)));
    }
    scene(objects)
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing");
    let demos = boxes::demos(&DEMOS);
    for (i, d) in demos.iter().enumerate() {
        d.validate()
            .unwrap_or_else(|e| panic!("demonstration {i} is invalid: {e}"));
    }
    let problem = problem();
    problem.validate().expect("problem is invalid");
    let files = [
        ("demos.json", scenes_to_json(&demos)),
        ("problem.json", problem.to_json()),
    ];
    write_or_check(&dir, &files, "gen_box_demos");
}
