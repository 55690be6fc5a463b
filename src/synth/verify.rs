//! An independent checker for synthesis output (SPEC §9), shared by the
//! synthesis tests and the differential tests against the brute-force
//! solver.

use crate::eval::evaluate;
use crate::relations::Contact;
use crate::rules::RuleSet;
use crate::scene::Scene;

/// Check that `solution` is a valid answer to `problem` under `rules`:
/// same space, grid, ids, classes, sizes and order; every object placed and
/// inside the space; previously placed objects (fixed or not) unmoved;
/// newly placed objects on the grid; no two interiors overlapping; every
/// hard rule holding for every subject, and every hard scene-level rule
/// (§11.4) holding in the scene (by the evaluator).
///
/// The error names the first problem found.
pub fn verify_solution(
    problem: &Scene,
    solution: &Scene,
    rules: &RuleSet,
    contact: Contact,
) -> Result<(), String> {
    if problem.space != solution.space {
        return Err("the space changed".into());
    }
    if problem.grid != solution.grid {
        return Err("the grid changed".into());
    }
    if problem.objects.len() != solution.objects.len() {
        return Err(format!(
            "{} objects in the problem, {} in the solution",
            problem.objects.len(),
            solution.objects.len()
        ));
    }
    let space = solution.space.rect();
    let mut rects = Vec::with_capacity(solution.objects.len());
    for (i, (p, s)) in problem.objects.iter().zip(&solution.objects).enumerate() {
        if p.id != s.id || p.class != s.class || p.width != s.width || p.height != s.height {
            return Err(format!(
                "objects[{i}]: `{}` ({} {}x{}) became `{}` ({} {}x{})",
                p.id, p.class, p.width, p.height, s.id, s.class, s.width, s.height
            ));
        }
        if p.fixed != s.fixed {
            return Err(format!("objects[{i}] `{}`: `fixed` changed", p.id));
        }
        let Some(r) = s.rect() else {
            return Err(format!("objects[{i}] `{}` is not placed", s.id));
        };
        if p.is_placed() {
            if p.x != s.x || p.y != s.y {
                return Err(format!(
                    "objects[{i}] `{}` was placed at ({}, {}) and moved to ({}, {})",
                    p.id,
                    p.x.unwrap_or_default(),
                    p.y.unwrap_or_default(),
                    r.x,
                    r.y
                ));
            }
        } else if !solution.on_grid(s) {
            return Err(format!(
                "objects[{i}] `{}` at ({}, {}) is off the grid",
                s.id, r.x, r.y
            ));
        }
        if !r.inside(&space) {
            return Err(format!(
                "objects[{i}] `{}` at ({}, {}) lies outside the space",
                s.id, r.x, r.y
            ));
        }
        rects.push(r);
    }
    for a in 0..rects.len() {
        for b in a + 1..rects.len() {
            if rects[a].interiors_overlap(&rects[b]) {
                return Err(format!(
                    "objects `{}` and `{}` overlap",
                    solution.objects[a].id, solution.objects[b].id
                ));
            }
        }
    }
    let e = evaluate(solution, rules, contact);
    for r in &e.rules {
        // `satisfied < subjects`, not "has violators": a failing scene-level
        // rule (`some A: …`, `at least K A: …`) has no violating object.
        if !r.hard || r.satisfied >= r.subjects {
            continue;
        }
        return Err(match &r.scene {
            Some(s) => format!(
                "hard scene-level rule `{}` ({} …) does not hold: {} of {} subject objects satisfy its formula",
                r.name, s.quantifier, s.satisfying, s.objects
            ),
            None => format!(
                "hard rule `{}` is broken by {}",
                r.name,
                r.violators.join(", ")
            ),
        });
    }
    Ok(())
}
