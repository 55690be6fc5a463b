//! The input checks of learning: demonstrations (valid, complete, one
//! space), statements (unique names, one subject, known classes) and the
//! landmarks given statements name.

use super::InferError;
use crate::relations::ClassIndex;
use crate::rules::{RuleSet, Target};
use crate::scene::{Scene, Space};

fn space_text(s: &Space) -> String {
    format!("{},{} {}x{}", s.x, s.y, s.width, s.height)
}

/// Demonstrations: at least one, each valid and complete, one shared space.
pub(crate) fn check_demos(demos: &[Scene]) -> Result<(), InferError> {
    let first = demos.first().ok_or(InferError::NoDemonstrations)?;
    for (d, s) in demos.iter().enumerate() {
        s.validate()
            .map_err(|error| InferError::InvalidDemonstration { demo: d, error })?;
        if let Some(o) = s.objects.iter().find(|o| !o.is_placed()) {
            return Err(InferError::IncompleteDemonstration {
                demo: d,
                object: o.id.clone(),
            });
        }
        if s.space != first.space {
            return Err(InferError::SpaceMismatch {
                demo: d,
                expected: space_text(&first.space),
                found: space_text(&s.space),
            });
        }
        if s.grid != first.grid {
            return Err(InferError::GridMismatch {
                demo: d,
                expected: first.grid,
                found: s.grid,
            });
        }
    }
    Ok(())
}

/// Statements: unique names, one subject per rule, only known classes.
pub(super) fn check_statements(set: &RuleSet, classes: &ClassIndex) -> Result<(), InferError> {
    let mut names = std::collections::HashSet::new();
    for rule in &set.rules {
        if !names.insert(rule.name.as_str()) {
            return Err(InferError::DuplicateName {
                name: rule.name.clone(),
            });
        }
        let subject = rule.subject();
        if let Some((shape, _)) = rule.formula.shape() {
            if classes.get(&shape.class).is_none() {
                return Err(InferError::UnknownClass {
                    rule: rule.name.clone(),
                    class: shape.class.clone(),
                    known: classes.names().join(", "),
                    span: rule.origin.as_ref().and_then(|o| o.atoms.first().copied()),
                });
            }
        }
        for (i, a) in rule.formula.atoms().into_iter().enumerate() {
            if a.subject != subject {
                return Err(InferError::MixedSubjects {
                    rule: rule.name.clone(),
                    first: subject.to_string(),
                    other: a.subject.clone(),
                });
            }
            let target = match &a.target {
                Target::Class(c) => Some(c),
                Target::Any | Target::Landmark(_) => None,
            };
            for c in std::iter::once(&a.subject).chain(target) {
                if classes.get(c).is_none() {
                    return Err(InferError::UnknownClass {
                        rule: rule.name.clone(),
                        class: c.clone(),
                        known: classes.names().join(", "),
                        span: rule.origin.as_ref().and_then(|o| o.atoms.get(i).copied()),
                    });
                }
            }
        }
    }
    Ok(())
}

/// Landmarks of given statements: every `@ID` must be a fixed, placed
/// object of every demonstration (docs/language.md#landmarks: evaluating a rule whose
/// landmark the scene lacks is bad input).
pub(super) fn check_demo_landmarks(set: &RuleSet, demos: &[Scene]) -> Result<(), InferError> {
    for rule in &set.rules {
        for (i, a) in rule.formula.atoms().into_iter().enumerate() {
            let Target::Landmark(id) = &a.target else {
                continue;
            };
            let missing = demos.iter().position(|s| {
                !s.objects
                    .iter()
                    .any(|o| &o.id == id && o.fixed && o.is_placed())
            });
            if let Some(demo) = missing {
                return Err(InferError::UnknownLandmark {
                    rule: rule.name.clone(),
                    id: id.clone(),
                    demo,
                    span: rule.origin.as_ref().and_then(|o| o.atoms.get(i).copied()),
                });
            }
        }
    }
    Ok(())
}
