//! Regenerate `examples/shelf/demos.json` and `problem.json`, and check that
//! every demonstration keeps every ground-truth rule of
//! `examples/shelf/intended.rcc`.
//!
//! ```text
//! cargo run --example gen_shelf_demos            # writes the files
//! cargo run --example gen_shelf_demos -- --check # fails if they are stale
//! ```
//!
//! The demonstrations show what the first edition of the language cannot
//! say: the reds stand in one flush row on the floor, the four greens form a
//! 2×2 block, at least one blue leans on the west wall, and no red touches a
//! blue. Everything else (where the row starts, where the block sits, how
//! many blocks of each colour) varies.

use rccpack::eval::evaluate;
use rccpack::relations::Contact;
use rccpack::rules::parse_rules;
#[path = "support/boxes.rs"]
mod boxes;

use boxes::{block, scene, walls, write_or_check, Demo};
use rccpack::scene::{scenes_to_json, Scene};
use std::path::Path;

const DEMOS: [Demo; 8] = [
    [
        ("R", &[(220, 200), (240, 200), (260, 200)]),
        ("G", &[(340, 200), (360, 200), (340, 220), (360, 220)]),
        ("B", &[(200, 300), (200, 320)]),
    ],
    [
        ("R", &[(200, 200), (220, 200)]),
        ("G", &[(300, 300), (320, 300), (300, 320), (320, 320)]),
        ("B", &[(200, 360), (220, 360), (260, 380)]),
    ],
    [
        ("R", &[(300, 200), (320, 200), (340, 200), (360, 200)]),
        ("G", &[(200, 340), (220, 340), (200, 360), (220, 360)]),
        ("B", &[(200, 260), (260, 260)]),
    ],
    [
        ("R", &[(240, 200), (260, 200), (280, 200)]),
        ("G", &[(340, 340), (360, 340), (340, 360), (360, 360)]),
        ("B", &[(200, 240), (220, 300)]),
    ],
    [
        ("R", &[(260, 200), (280, 200), (300, 200)]),
        ("G", &[(240, 260), (260, 260), (240, 280), (260, 280)]),
        ("B", &[(200, 380), (380, 380), (380, 300)]),
    ],
    [
        ("R", &[(200, 200), (220, 200), (240, 200)]),
        ("G", &[(320, 240), (340, 240), (320, 260), (340, 260)]),
        ("B", &[(200, 320), (220, 320)]),
    ],
    [
        ("R", &[(320, 200), (340, 200), (360, 200)]),
        ("G", &[(200, 200), (220, 200), (200, 220), (220, 220)]),
        ("B", &[(200, 360), (300, 300), (320, 300)]),
    ],
    [
        ("R", &[(220, 200), (240, 200)]),
        ("G", &[(280, 320), (300, 320), (280, 340), (300, 340)]),
        ("B", &[(200, 280), (360, 260), (360, 380)]),
    ],
];

/// Four reds, four greens and three blues for the empty box.
fn problem() -> Scene {
    let mut objects = walls();
    for (class, n) in [("R", 4), ("G", 4), ("B", 3)] {
        objects.extend((0..n).map(|i| block(class, i, None)));
    }
    scene(objects)
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/shelf");
    let intended_text =
        std::fs::read_to_string(dir.join("intended.rcc")).expect("read intended.rcc");
    let intended = parse_rules(&intended_text).expect("intended.rcc parses");
    let demos = boxes::demos(&DEMOS);
    for (i, d) in demos.iter().enumerate() {
        d.validate()
            .unwrap_or_else(|e| panic!("demonstration {i} is invalid: {e}"));
        for contact in [Contact::Point, Contact::Edge] {
            let e = evaluate(d, &intended, contact);
            let broken: Vec<String> = e
                .rules
                .iter()
                .filter(|r| r.satisfied != r.subjects)
                .map(|r| format!("{} {:?}", r.name, r.violators))
                .collect();
            assert!(
                broken.is_empty(),
                "demonstration {i} ({contact}) breaks {broken:?}"
            );
        }
    }
    let problem = problem();
    problem.validate().expect("problem is invalid");
    let files = [
        ("demos.json", scenes_to_json(&demos)),
        ("problem.json", problem.to_json()),
    ];
    write_or_check(&dir, &files, "gen_shelf_demos");
}
