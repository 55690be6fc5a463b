//! An independent checker for synthesis output (docs/guide.md#synthesis), shared by the
//! synthesis tests and the differential tests against the brute-force
//! solver.

use crate::eval::evaluate;
use crate::relations::Contact;
use crate::rules::RuleSet;
use crate::scene::Scene;

/// Why a layout is not a valid answer to its problem (the first fault
/// found by [`verify_solution`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum VerifyError {
    /// The space differs from the problem's.
    #[error("the space changed")]
    SpaceChanged,
    /// The grid differs from the problem's.
    #[error("the grid changed")]
    GridChanged,
    /// Objects were added or removed.
    #[error("{problem} objects in the problem, {solution} in the solution")]
    ObjectCount {
        /// Objects in the problem.
        problem: usize,
        /// Objects in the layout.
        solution: usize,
    },
    /// An object's id, class or size changed (or the order did).
    #[error("objects[{index}]: {was} became {now}")]
    ObjectChanged {
        /// Its index.
        index: usize,
        /// The problem's object, described.
        was: String,
        /// The layout's object, described.
        now: String,
    },
    /// An object's `fixed` flag changed.
    #[error("objects[{index}] `{id}`: `fixed` changed")]
    FixedChanged {
        /// Its index.
        index: usize,
        /// Its id.
        id: String,
    },
    /// An object lies turned that may not turn (not `turnable` in the
    /// problem), a placed object's orientation changed, or `turnable`
    /// changed.
    #[error("objects[{index}] `{id}`: its orientation (`turned`/`turnable`) changed and it may not turn")]
    TurnChanged {
        /// Its index.
        index: usize,
        /// Its id.
        id: String,
    },
    /// An object has no position.
    #[error("objects[{index}] `{id}` is not placed")]
    Unplaced {
        /// Its index.
        index: usize,
        /// Its id.
        id: String,
    },
    /// A placed object of the problem moved.
    #[error("objects[{index}] `{id}` was placed at ({}, {}) and moved to ({}, {})", from.0, from.1, to.0, to.1)]
    Moved {
        /// Its index.
        index: usize,
        /// Its id.
        id: String,
        /// Where the problem placed it.
        from: (i64, i64),
        /// Where the layout has it.
        to: (i64, i64),
    },
    /// A newly placed object is not on the grid.
    #[error("objects[{index}] `{id}` at ({}, {}) is off the grid", at.0, at.1)]
    OffGrid {
        /// Its index.
        index: usize,
        /// Its id.
        id: String,
        /// Its position.
        at: (i64, i64),
    },
    /// An object leaves the space.
    #[error("objects[{index}] `{id}` at ({}, {}) lies outside the space", at.0, at.1)]
    Outside {
        /// Its index.
        index: usize,
        /// Its id.
        id: String,
        /// Its position.
        at: (i64, i64),
    },
    /// Two interiors overlap.
    #[error("objects `{a}` and `{b}` overlap")]
    Overlap {
        /// One object's id.
        a: String,
        /// The other's.
        b: String,
    },
    /// A hard rule is broken by these objects.
    #[error("hard rule `{rule}` is broken by {}", violators.join(", "))]
    HardRule {
        /// The rule's name.
        rule: String,
        /// The objects that break it.
        violators: Vec<String>,
    },
    /// A hard scene-level rule does not hold.
    #[error("hard scene-level rule `{rule}` ({quantifier} …) does not hold: {satisfying} of {objects} subject objects satisfy its formula")]
    HardSceneRule {
        /// The rule's name.
        rule: String,
        /// Its quantifier, as written.
        quantifier: String,
        /// Subjects that satisfy its formula.
        satisfying: usize,
        /// Subjects.
        objects: usize,
    },
}

/// Check that `solution` is a valid answer to `problem` under `rules`:
/// same space, grid, ids, classes, sizes and order; every object placed and
/// inside the space; previously placed objects (fixed or not) unmoved;
/// newly placed objects on the grid; no two interiors overlapping; every
/// hard rule holding for every subject, and every hard scene-level rule
/// (docs/language.md#scene-rules) holding in the scene (by the evaluator).
///
/// The error names the first problem found.
pub fn verify_solution(
    problem: &Scene,
    solution: &Scene,
    rules: &RuleSet,
    contact: Contact,
) -> Result<(), VerifyError> {
    if problem.space != solution.space {
        return Err(VerifyError::SpaceChanged);
    }
    if problem.grid != solution.grid {
        return Err(VerifyError::GridChanged);
    }
    if problem.objects.len() != solution.objects.len() {
        return Err(VerifyError::ObjectCount {
            problem: problem.objects.len(),
            solution: solution.objects.len(),
        });
    }
    let space = solution.space.rect();
    let mut rects = Vec::with_capacity(solution.objects.len());
    for (i, (p, s)) in problem.objects.iter().zip(&solution.objects).enumerate() {
        rects.push(check_object(i, p, s, solution, &space)?);
    }
    for a in 0..rects.len() {
        for b in a + 1..rects.len() {
            if rects[a].interiors_overlap(&rects[b]) {
                return Err(VerifyError::Overlap {
                    a: solution.objects[a].id.clone(),
                    b: solution.objects[b].id.clone(),
                });
            }
        }
    }
    check_hard_rules(solution, rules, contact)
}

/// Object `i` of the solution against the problem's: the same object,
/// placed, where the problem placed it (or on the grid), inside the space.
fn check_object(
    i: usize,
    p: &crate::scene::Object,
    s: &crate::scene::Object,
    solution: &Scene,
    space: &crate::scene::Rect,
) -> Result<crate::scene::Rect, VerifyError> {
    if p.id != s.id || p.class != s.class || p.width != s.width || p.height != s.height {
        return Err(VerifyError::ObjectChanged {
            index: i,
            was: format!("`{}` ({} {}x{})", p.id, p.class, p.width, p.height),
            now: format!("`{}` ({} {}x{})", s.id, s.class, s.width, s.height),
        });
    }
    if p.fixed != s.fixed {
        return Err(VerifyError::FixedChanged {
            index: i,
            id: p.id.clone(),
        });
    }
    // A placed object keeps its orientation; an unplaced one lies turned
    // only when it may turn.
    let turn_ok = p.turnable == s.turnable
        && if p.is_placed() {
            p.turned == s.turned
        } else {
            !s.turned || p.turnable
        };
    if !turn_ok {
        return Err(VerifyError::TurnChanged {
            index: i,
            id: p.id.clone(),
        });
    }
    let Some(r) = s.rect() else {
        return Err(VerifyError::Unplaced {
            index: i,
            id: s.id.clone(),
        });
    };
    if p.is_placed() {
        if p.x != s.x || p.y != s.y {
            return Err(VerifyError::Moved {
                index: i,
                id: p.id.clone(),
                from: (p.x.unwrap_or_default(), p.y.unwrap_or_default()),
                to: (r.x, r.y),
            });
        }
    } else if !solution.on_grid(s) {
        return Err(VerifyError::OffGrid {
            index: i,
            id: s.id.clone(),
            at: (r.x, r.y),
        });
    }
    if !r.inside(space) {
        return Err(VerifyError::Outside {
            index: i,
            id: s.id.clone(),
            at: (r.x, r.y),
        });
    }
    Ok(r)
}

/// Every hard rule holds for every subject (by the evaluator).
fn check_hard_rules(
    solution: &Scene,
    rules: &RuleSet,
    contact: Contact,
) -> Result<(), VerifyError> {
    let e = evaluate(solution, rules, contact);
    for r in &e.rules {
        // `satisfied < subjects`, not "has violators": a failing scene-level
        // rule (`some A: …`, `at least K A: …`) has no violating object.
        if !r.hard || r.satisfied >= r.subjects {
            continue;
        }
        return Err(match &r.scene {
            Some(s) => VerifyError::HardSceneRule {
                rule: r.name.clone(),
                quantifier: s.quantifier.clone(),
                satisfying: s.satisfying,
                objects: s.objects,
            },
            None => VerifyError::HardRule {
                rule: r.name.clone(),
                violators: r.violators.clone(),
            },
        });
    }
    Ok(())
}
