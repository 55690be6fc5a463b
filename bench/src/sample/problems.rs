//! The tiny problems the uniformity bench and the tests use: few enough
//! layouts to enumerate by brute force.

use rccpack::rules::{parse_rules, RuleSet};
use rccpack::scene::{Object, Scene, Space};

fn block(id: &str, class: &str, w: i64, h: i64) -> Object {
    Object {
        id: id.into(),
        class: class.into(),
        x: None,
        y: None,
        width: w,
        height: h,
        fixed: false,
        turnable: false,
        turned: false,
    }
}

/// Small problems whose layouts brute force enumerates in milliseconds:
/// `(name, problem, rules)`.
pub fn tiny_problems() -> Vec<(&'static str, Scene, RuleSet)> {
    let space = |w, h| Space {
        x: 0,
        y: 0,
        width: w,
        height: h,
    };
    let scene = |sp, objects| Scene {
        space: sp,
        grid: 10,
        objects,
    };
    let rules = |t: &str| parse_rules(t).expect("the tiny rules parse");
    vec![
        (
            "two-touching",
            // Two interchangeable blocks that touch, on a 5×4 table.
            scene(
                space(50, 40),
                vec![block("a1", "A", 10, 10), block("a2", "A", 10, 10)],
            ),
            rules("rule touch: EC_N(A, A) | EC_S(A, A) | EC_E(A, A) | EC_W(A, A)\n"),
        ),
        (
            "b-on-wall",
            // A blue north of a red, the blue touching the east wall.
            scene(
                space(50, 50),
                vec![
                    Object::fixed_at("wall", "W", 40, 0, 10, 50),
                    block("r1", "R", 10, 10),
                    block("b1", "B", 10, 10),
                ],
            ),
            rules(
                "rule b_north: DR_N(B, R)\n\
                 rule b_wall weight 2: EC_W(B, W)\n",
            ),
        ),
        (
            "row-of-three",
            // Three in one row, flush, on a 6×3 table (optimum below 1 is
            // impossible to avoid for the corner rule).
            scene(
                space(60, 30),
                vec![
                    block("g1", "G", 10, 10),
                    block("g2", "G", 10, 10),
                    block("g3", "G", 20, 10),
                ],
            ),
            rules(
                "rule row: AL_S(G, every G)\n\
                 rule flush: FL_E(G, G) | FL_W(G, G)\n",
            ),
        ),
    ]
}
