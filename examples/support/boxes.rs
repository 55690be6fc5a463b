//! Shared by the example generators (`gen_box_demos`, `gen_shelf_demos`):
//! the box of four fixed walls on a 600×600 table, 20×20 blocks, the scene.

use rccpack::scene::{Object, Scene, Space};

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
