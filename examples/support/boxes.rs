//! Shared by the example generators (`gen_box_demos`, `gen_shelf_demos`):
//! the box of four fixed walls on a 600×600 table, 20×20 blocks, the scene.

use rccpack::scene::{Object, Scene, Space};
use std::path::Path;

/// `(class, [(x, y), ...])` per class; every block is 20×20.
pub type Demo = [(&'static str, &'static [(i64, i64)]); 3];

pub fn walls() -> Vec<Object> {
    [
        ("w_south", 190, 190, 220, 10),
        ("w_north", 190, 400, 220, 10),
        ("w_west", 190, 200, 10, 200),
        ("w_east", 400, 200, 10, 200),
    ]
    .into_iter()
    .map(|(id, x, y, w, h)| Object::fixed_at(id, "W", x, y, w, h))
    .collect()
}

pub fn block(class: &str, i: usize, pos: Option<(i64, i64)>) -> Object {
    Object {
        id: format!("{}{}", class.to_ascii_lowercase(), i + 1),
        class: class.into(),
        x: pos.map(|p| p.0),
        y: pos.map(|p| p.1),
        width: 20,
        height: 20,
        fixed: false,
        turnable: false,
        turned: false,
    }
}

pub fn scene(objects: Vec<Object>) -> Scene {
    Scene {
        space: Space {
            x: 0,
            y: 0,
            width: 600,
            height: 600,
        },
        grid: 10,
        objects,
    }
}

/// One complete scene per demonstration: the walls plus its blocks.
pub fn demos(demos: &[Demo]) -> Vec<Scene> {
    demos
        .iter()
        .map(|demo| {
            let mut objects = walls();
            for (class, cells) in demo {
                objects.extend(
                    cells
                        .iter()
                        .enumerate()
                        .map(|(i, &p)| block(class, i, Some(p))),
                );
            }
            scene(objects)
        })
        .collect()
}

/// Write each `(name, text)` into `dir`, or with `--check` on the command
/// line fail when a file differs (it is stale; rerun `generator`).
pub fn write_or_check(dir: &Path, files: &[(&str, String)], generator: &str) {
    let check = std::env::args().any(|a| a == "--check");
    for (name, text) in files {
        let path = dir.join(name);
        if check {
            let old = std::fs::read_to_string(&path).unwrap_or_default();
            assert!(
                &old == text,
                "{} is stale; rerun {generator}",
                path.display()
            );
        } else {
            std::fs::write(&path, text).expect("write");
            println!("wrote {}", path.display());
        }
    }
}
