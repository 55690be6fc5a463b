//! The box-packing example built in code (as `examples/box-packing/`):
//! four fixed walls, blocks of classes R, G, B, and the thesis's twelve
//! pilot rules.

use super::formulas::{and, atom, not, or};
use rccpack::rules::{Formula, Rule, RuleSet};
use rccpack::scene::{Object, Scene};

/// `x` touches another `x` on some side.
pub fn touches(x: &str) -> Formula {
    or(["EC_N", "EC_S", "EC_E", "EC_W"]
        .iter()
        .map(|r| atom(r, x, x))
        .collect())
}

/// `x` is held on two adjacent sides.
pub fn corner(x: &str) -> Formula {
    or(vec![
        and(vec![atom("EC_N", x, "*"), atom("EC_W", x, "*")]),
        and(vec![atom("EC_W", x, "*"), atom("EC_S", x, "*")]),
        and(vec![atom("EC_S", x, "*"), atom("EC_E", x, "*")]),
        and(vec![atom("EC_E", x, "*"), atom("EC_N", x, "*")]),
    ])
}

/// `x` is not outside the walls in any direction.
pub fn inside(x: &str) -> Formula {
    and(["DR_N", "DR_S", "DR_E", "DR_W"]
        .iter()
        .map(|r| not(atom(r, x, "W")))
        .collect())
}

/// The thesis's 12 pilot rules.
pub fn pilot_rules() -> RuleSet {
    let mut rules = vec![
        Rule::new("blue_north_of_red", atom("DR_N", "B", "R")),
        Rule::new("green_east_of_red", atom("DR_E", "G", "R")),
        Rule::new("green_east_of_blue", atom("DR_E", "G", "B")),
    ];
    for x in ["B", "R", "G"] {
        rules.push(Rule::new(format!("{x}_touches_{x}"), touches(x)));
        rules.push(Rule::new(format!("{x}_corner"), corner(x)));
        rules.push(Rule::new(format!("{x}_inside"), inside(x)));
    }
    RuleSet::new(rules)
}

/// An object of `class`, `w`×`h`, at `pos` (unplaced when `None`).
pub fn obj(id: &str, class: &str, w: i64, h: i64, pos: Option<(i64, i64)>, fixed: bool) -> Object {
    Object {
        id: id.into(),
        class: class.into(),
        x: pos.map(|p| p.0),
        y: pos.map(|p| p.1),
        width: w,
        height: h,
        fixed,
        turnable: false,
        turned: false,
    }
}

/// The box: four fixed walls of class W around a 200×200 inside.
pub fn walls() -> Vec<Object> {
    vec![
        obj("w_south", "W", 220, 10, Some((190, 190)), true),
        obj("w_north", "W", 220, 10, Some((190, 400)), true),
        obj("w_west", "W", 10, 200, Some((190, 200)), true),
        obj("w_east", "W", 10, 200, Some((400, 200)), true),
    ]
}

/// The box with `per_class` unplaced 20×20 blocks of each class R, G, B
/// (3: the bundled problem).
pub fn box_problem(per_class: usize) -> Scene {
    let mut objects = walls();
    for c in ["R", "G", "B"] {
        for i in 0..per_class {
            objects.push(obj(
                &format!("{}{}", c.to_lowercase(), i + 1),
                c,
                20,
                20,
                None,
                false,
            ));
        }
    }
    super::table(600, 600, objects)
}
