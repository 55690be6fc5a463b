//! Exhaustive reference solver for **tiny** problems (tests and differential
//! checks only).
//!
//! [`solve`] enumerates every assignment of grid positions to the unplaced
//! objects — each object wholly inside the space, on the grid of docs/guide.md#synthesis —
//! skips assignments in which two interiors overlap (fixed and already-placed
//! objects included), and asks the evaluator ([`crate::eval::Evaluator`], the
//! one implementation of docs/language.md#class-rules and docs/language.md#the-score) whether every hard rule holds and what the
//! numerator over **all** placed objects is. It keeps the largest
//! numerator.
//!
//! An unplaced `turnable` object that is not square is tried in both
//! orientations (its domain holds the positions of both footprints).
//!
//! There is no pruning by rules and no symmetry breaking: the point is to be
//! obviously correct, not fast. The search space is the product of the
//! per-object domain sizes; [`solve`] refuses (returns
//! [`BruteError::TooLarge`]) when that product exceeds [`MAX_LAYOUTS`] (or a
//! caller-given limit through [`solve_with_limit`]).
//!
//! Numerators are compared with [`approx_eq`] (tolerance
//! `1e-9·(1+|x|)`), so ties between optima are harmless: any optimum may be
//! returned.

use crate::eval::Evaluator;
use crate::relations::Contact;
use crate::resemblance::ResemblanceTarget;
use crate::rules::RuleSet;
use crate::scene::{Rect, Scene};

/// Default cap on the product of domain sizes (10^7).
pub const MAX_LAYOUTS: u128 = 10_000_000;

/// What the exhaustive search found.
#[derive(Debug, Clone, PartialEq)]
pub struct BruteResult {
    /// Some layout places every object without overlap and keeps every hard
    /// rule.
    pub feasible: bool,
    /// The largest numerator (`satisfied_weight`) over feasible layouts;
    /// `f64::NEG_INFINITY` when infeasible.
    pub best_numerator: f64,
    /// One optimal complete scene, when feasible.
    pub best: Option<Scene>,
    /// With like-scenes: the smallest resemblance cost among the layouts of
    /// the best numerator (the lexicographic optimum of docs/guide.md#layouts-like-the-demonstrations); 0
    /// without.
    pub best_cost: u64,
    /// Complete non-overlapping layouts handed to the evaluator.
    pub layouts_checked: u64,
    /// How many of those kept every hard rule.
    pub layouts_feasible: u64,
}

/// Why the exhaustive search refused to run.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BruteError {
    /// The product of domain sizes exceeds the limit.
    #[error("search space too large for brute force: {layouts} candidate layouts > limit {limit}")]
    TooLarge {
        /// Product of the per-object domain sizes (saturating).
        layouts: u128,
        /// The limit in force.
        limit: u128,
    },
    /// The problem scene is not valid (docs/scenes.md#geometry).
    #[error("bad problem: {0}")]
    BadProblem(String),
}

/// Whether two numerators are equal within `1e-9·(1+|x|)`.
pub fn approx_eq(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
}

/// Whether `a` is larger than `b` by more than the tolerance of [`approx_eq`].
pub fn approx_gt(a: f64, b: f64) -> bool {
    a > b && !approx_eq(a, b)
}

/// Grid positions (min corners) at which an object of size `w × h` lies
/// wholly inside the space of `scene`, in row-major order (y, then x).
pub fn grid_positions(scene: &Scene, w: i64, h: i64) -> Vec<(i64, i64)> {
    let s = scene.space.rect();
    let g = scene.grid.max(1);
    let mut out = Vec::new();
    let mut y = s.y;
    while y + h <= s.y2() {
        let mut x = s.x;
        while x + w <= s.x2() {
            out.push((x, y));
            x += g;
        }
        y += g;
    }
    out
}

/// Exhaustively solve `problem` with the default limit [`MAX_LAYOUTS`].
pub fn solve(
    problem: &Scene,
    rules: &RuleSet,
    contact: Contact,
) -> Result<BruteResult, BruteError> {
    solve_with_limit(problem, rules, contact, MAX_LAYOUTS)
}

/// Exhaustively solve `problem` for the lexicographic objective of
/// docs/guide.md#layouts-like-the-demonstrations: the largest numerator, then the smallest resemblance cost
/// ([`ResemblanceTarget::cost`], the one resemblance function).
pub fn solve_like(
    problem: &Scene,
    rules: &RuleSet,
    contact: Contact,
    like: &ResemblanceTarget,
    limit: u128,
) -> Result<BruteResult, BruteError> {
    run(problem, rules, contact, Some(like), limit)
}

/// Exhaustively solve `problem`, refusing when the product of domain sizes
/// exceeds `limit`.
///
/// Domains: every grid position inside the space whose interior overlaps no
/// already-placed (fixed or not) object. Overlaps between unplaced objects
/// are skipped during enumeration.
pub fn solve_with_limit(
    problem: &Scene,
    rules: &RuleSet,
    contact: Contact,
    limit: u128,
) -> Result<BruteResult, BruteError> {
    run(problem, rules, contact, None, limit)
}

fn run(
    problem: &Scene,
    rules: &RuleSet,
    contact: Contact,
    like: Option<&ResemblanceTarget>,
    limit: u128,
) -> Result<BruteResult, BruteError> {
    problem
        .validate()
        .map_err(|e| BruteError::BadProblem(e.to_string()))?;
    let placed: Vec<Rect> = problem.objects.iter().filter_map(|o| o.rect()).collect();
    let free: Vec<usize> = (0..problem.objects.len())
        .filter(|&i| !problem.objects[i].is_placed())
        .collect();
    let domains: Vec<Vec<(Rect, bool)>> = free
        .iter()
        .map(|&i| {
            let o = &problem.objects[i];
            // A turnable object that is not square lies either way.
            let turns: &[bool] = if o.turnable && o.is_oblong() {
                &[false, true]
            } else {
                &[false]
            };
            turns
                .iter()
                .flat_map(|&t| {
                    let (w, h) = if t {
                        (o.height, o.width)
                    } else {
                        (o.width, o.height)
                    };
                    grid_positions(problem, w, h)
                        .into_iter()
                        .map(move |(x, y)| (Rect::new(x, y, w, h), t))
                })
                .filter(|(r, _)| placed.iter().all(|p| !p.interiors_overlap(r)))
                .collect()
        })
        .collect();
    let layouts = domains
        .iter()
        .fold(1u128, |acc, d| acc.saturating_mul(d.len() as u128));
    if layouts > limit {
        return Err(BruteError::TooLarge { layouts, limit });
    }
    let mut search = Search {
        rules,
        contact,
        like,
        problem,
        scene: problem.clone(),
        free: &free,
        domains: &domains,
        chosen: Vec::with_capacity(free.len()),
        result: BruteResult {
            feasible: false,
            best_numerator: f64::NEG_INFINITY,
            best: None,
            best_cost: 0,
            layouts_checked: 0,
            layouts_feasible: 0,
        },
    };
    search.dfs(0);
    Ok(search.result)
}

struct Search<'a> {
    rules: &'a RuleSet,
    contact: Contact,
    like: Option<&'a ResemblanceTarget>,
    problem: &'a Scene,
    scene: Scene,
    free: &'a [usize],
    domains: &'a [Vec<(Rect, bool)>],
    chosen: Vec<Rect>,
    result: BruteResult,
}

impl Search<'_> {
    fn dfs(&mut self, depth: usize) {
        if depth == self.free.len() {
            self.leaf();
            return;
        }
        let obj = self.free[depth];
        for &(r, turned) in &self.domains[depth] {
            if self.chosen.iter().any(|c| c.interiors_overlap(&r)) {
                continue;
            }
            self.scene.objects[obj].x = Some(r.x);
            self.scene.objects[obj].y = Some(r.y);
            self.scene.objects[obj].turned = turned;
            self.chosen.push(r);
            self.dfs(depth + 1);
            self.chosen.pop();
        }
        self.scene.objects[obj].x = None;
        self.scene.objects[obj].y = None;
        self.scene.objects[obj].turned = false;
    }

    fn leaf(&mut self) {
        self.result.layouts_checked += 1;
        let ev = Evaluator::new(&self.scene, self.rules, self.contact).evaluate(self.rules);
        if !ev.hard_ok() {
            return;
        }
        self.result.layouts_feasible += 1;
        let num = ev.satisfied_weight;
        let cost = self.like.map_or(0, |l| l.cost(self.problem, &self.scene));
        let better = !self.result.feasible
            || approx_gt(num, self.result.best_numerator)
            || (approx_eq(num, self.result.best_numerator) && cost < self.result.best_cost);
        if better {
            self.result.feasible = true;
            self.result.best_numerator = num;
            self.result.best_cost = cost;
            self.result.best = Some(self.scene.clone());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::relations::{Dir, Kind, Relation};
    use crate::rules::{Atom, Formula, Rule, Strength, Target};
    use crate::scene::{Object, Space};

    fn obj(id: &str, class: &str, pos: Option<(i64, i64)>, w: i64, fixed: bool) -> Object {
        Object {
            id: id.into(),
            class: class.into(),
            x: pos.map(|p| p.0),
            y: pos.map(|p| p.1),
            width: w,
            height: w,
            fixed,
            turnable: false,
            turned: false,
        }
    }

    fn scene(w: i64, h: i64, objects: Vec<Object>) -> Scene {
        Scene {
            space: Space {
                x: 0,
                y: 0,
                width: w,
                height: h,
            },
            grid: 10,
            objects,
        }
    }

    fn atom(kind: Kind, dir: Dir, s: &str, t: Option<&str>) -> Formula {
        Formula::Atom(Atom::new(
            Relation::new(kind, dir),
            s,
            match t {
                Some(c) => Target::Class(c.into()),
                None => Target::Any,
            },
        ))
    }

    #[test]
    fn grid_positions_keep_object_inside() {
        let s = scene(30, 20, vec![]);
        assert_eq!(
            grid_positions(&s, 10, 10),
            vec![(0, 0), (10, 0), (20, 0), (0, 10), (10, 10), (20, 10)]
        );
        assert_eq!(grid_positions(&s, 20, 20), vec![(0, 0), (10, 0)]);
        assert!(grid_positions(&s, 40, 10).is_empty());
    }

    /// One 10×10 A in a 30×30 space (9 positions), one fixed F in the
    /// middle (so 8 positions remain). Soft rule EC_N(A, F) weight 2: only
    /// the three cells of the top row touch F's north side... with point
    /// contact the corners (0,20) and (20,20) touch too, so all three top
    /// cells qualify; numerator 2.
    #[test]
    fn hand_checked_one_object_one_rule() {
        let s = scene(
            30,
            30,
            vec![
                obj("f", "F", Some((10, 10)), 10, true),
                obj("a", "A", None, 10, false),
            ],
        );
        let rules = RuleSet::new(vec![Rule::new(
            "a_on_f",
            atom(Kind::EC, Dir::N, "A", Some("F")),
        )
        .with_strength(Strength::Weight(2.0))]);
        let r = solve(&s, &rules, Contact::Point).unwrap();
        assert!(r.feasible);
        assert_eq!(r.layouts_checked, 8);
        assert_eq!(r.layouts_feasible, 8);
        assert!(approx_eq(r.best_numerator, 2.0));
        let best = r.best.unwrap();
        assert_eq!(best.objects[1].y, Some(20));
        // Edge contact: only the middle top cell (10, 20) touches; still 2.
        let r = solve(&s, &rules, Contact::Edge).unwrap();
        assert!(approx_eq(r.best_numerator, 2.0));
        let best = r.best.unwrap();
        assert_eq!((best.objects[1].x, best.objects[1].y), (Some(10), Some(20)));
    }

    /// Made hard, the same rule leaves 3 feasible layouts (point contact)
    /// or 1 (edge contact), and the numerator is 0 (no soft rules).
    #[test]
    fn hand_checked_hard_rule_counts() {
        let s = scene(
            30,
            30,
            vec![
                obj("f", "F", Some((10, 10)), 10, true),
                obj("a", "A", None, 10, false),
            ],
        );
        let rules = RuleSet::new(vec![Rule::new(
            "a_on_f",
            atom(Kind::EC, Dir::N, "A", Some("F")),
        )
        .with_strength(Strength::Hard)]);
        let r = solve(&s, &rules, Contact::Point).unwrap();
        assert_eq!((r.layouts_checked, r.layouts_feasible), (8, 3));
        assert_eq!(r.best_numerator, 0.0);
        let r = solve(&s, &rules, Contact::Edge).unwrap();
        assert_eq!((r.layouts_checked, r.layouts_feasible), (8, 1));
    }

    /// Two A objects in a 20×10 strip: 2 ordered layouts. DR_E(A, A) can
    /// hold for only one of them (the eastern one): numerator 1 of 2.
    #[test]
    fn hand_checked_two_objects_mutual_rule() {
        let s = scene(
            20,
            10,
            vec![
                obj("a1", "A", None, 10, false),
                obj("a2", "A", None, 10, false),
            ],
        );
        let rules = RuleSet::new(vec![Rule::new(
            "east",
            atom(Kind::DR, Dir::E, "A", Some("A")),
        )]);
        let r = solve(&s, &rules, Contact::Point).unwrap();
        assert_eq!(r.layouts_checked, 2);
        assert!(approx_eq(r.best_numerator, 1.0));
        // As a hard rule nothing is feasible.
        let hard = RuleSet::new(vec![rules.rules[0].clone().with_strength(Strength::Hard)]);
        let r = solve(&s, &hard, Contact::Point).unwrap();
        assert!(!r.feasible);
        assert!(r.best.is_none());
        assert_eq!(r.best_numerator, f64::NEG_INFINITY);
    }

    /// Already-placed movable objects count in the numerator and block
    /// positions; objects that cannot fit make the problem infeasible.
    #[test]
    fn placed_objects_count_and_no_fit_is_infeasible() {
        let s = scene(
            20,
            10,
            vec![
                obj("b", "B", Some((0, 0)), 10, false),
                obj("a", "A", None, 10, false),
            ],
        );
        let rules = RuleSet::new(vec![
            Rule::new("b_west", atom(Kind::EC, Dir::W, "B", Some("A"))),
            Rule::new("a_east", atom(Kind::DR, Dir::E, "A", None)),
        ]);
        let r = solve(&s, &rules, Contact::Point).unwrap();
        assert_eq!(r.layouts_checked, 1);
        assert!(approx_eq(r.best_numerator, 2.0));
        let s = scene(
            10,
            10,
            vec![
                obj("a1", "A", None, 10, false),
                obj("a2", "A", None, 10, false),
            ],
        );
        let r = solve(&s, &rules, Contact::Point).unwrap();
        assert!(!r.feasible);
        assert_eq!(r.layouts_checked, 0);
    }

    /// A hard scene-level rule counts as a hard violation when it fails,
    /// although no object violates it. Three 10×10 A in a 60×30 strip
    /// whose west 10 columns are a fixed wall `w`: 15 cells, 15·14·13 =
    /// 2730 layouts. `at least 2 A: EC_E(A, @w)` needs two of them in the
    /// column x = 10 (3 cells): exactly two, 3 pairs · 3·2 cells · 12 cells
    /// for the third = 216; all three, 3! = 6; so 222 layouts.
    #[test]
    fn hand_checked_hard_scene_level_rule() {
        use crate::relations::Quant;
        use crate::rules::Scope;
        let mut objects = vec![Object {
            width: 10,
            height: 30,
            ..obj("w", "W", Some((0, 0)), 10, true)
        }];
        for i in 0..3 {
            objects.push(obj(&format!("a{i}"), "A", None, 10, false));
        }
        let s = scene(60, 30, objects);
        let touches = Formula::Atom(Atom::new(
            Relation::new(Kind::EC, Dir::E),
            "A",
            Target::Landmark("w".into()),
        ));
        let rule = |q| {
            RuleSet::new(vec![Rule::new("wall", touches.clone())
                .with_scope(Scope::Scene(q))
                .with_strength(Strength::Hard)])
        };
        let r = solve(&s, &rule(Quant::AtLeast(2)), Contact::Point).unwrap();
        assert_eq!((r.layouts_checked, r.layouts_feasible), (2730, 222));
        // `no A: …`: every layout without a block in the column, 12·11·10.
        let r = solve(&s, &rule(Quant::No), Contact::Point).unwrap();
        assert_eq!(r.layouts_feasible, 1320);
        // `at least 4`: impossible with three blocks.
        let r = solve(&s, &rule(Quant::AtLeast(4)), Contact::Point).unwrap();
        assert!(!r.feasible);
        // Soft, weight 2: one term, so the best numerator is 2, not 6.
        let soft = RuleSet::new(vec![Rule::new("wall", touches.clone())
            .with_scope(Scope::Scene(Quant::Some))
            .with_strength(Strength::Weight(2.0))]);
        let r = solve(&s, &soft, Contact::Point).unwrap();
        assert!(approx_eq(r.best_numerator, 2.0));
    }

    #[test]
    fn refuses_large_problems() {
        let s = scene(
            600,
            600,
            vec![
                obj("a1", "A", None, 10, false),
                obj("a2", "A", None, 10, false),
            ],
        );
        let e = solve(&s, &RuleSet::default(), Contact::Point).unwrap_err();
        assert!(matches!(
            e,
            BruteError::TooLarge {
                layouts: 12_960_000,
                ..
            }
        ));
        assert!(solve_with_limit(&s, &RuleSet::default(), Contact::Point, 100).is_err());
    }

    #[test]
    fn tolerance() {
        assert!(approx_eq(1.0, 1.0 + 1e-12));
        assert!(approx_eq(1e6, 1e6 + 1e-4));
        assert!(!approx_eq(1.0, 1.0 + 1e-6));
        assert!(approx_gt(2.0, 1.0));
        assert!(!approx_gt(1.0 + 1e-12, 1.0));
    }
}
