//! Semantic checks that need a scene (classes named by rules exist in it).

use super::{Diagnostic, RuleSet, RulesError, Span, Target};
use crate::scene::Scene;

/// Check that every class named by `rules` exists in `scene`.
///
/// Reports every atom naming a missing class (subject or target), at the
/// atom's span when the rule was parsed.
pub fn check_classes(rules: &RuleSet, scene: &Scene) -> Result<(), RulesError> {
    let classes = scene.classes();
    let listing = if classes.is_empty() {
        "the scene has no objects".to_string()
    } else {
        format!("the scene has classes {}", classes.join(", "))
    };
    let mut diags = Vec::new();
    for rule in &rules.rules {
        for (i, atom) in rule.formula.atoms().into_iter().enumerate() {
            let span = rule
                .origin
                .as_ref()
                .and_then(|o| o.atoms.get(i).copied())
                .unwrap_or(Span::new(0, 0));
            let mut named = vec![atom.subject.as_str()];
            if let Target::Class(c) = &atom.target {
                if c != &atom.subject {
                    named.push(c);
                }
            }
            for class in named {
                if !classes.contains(&class) {
                    diags.push(Diagnostic::new(
                        span,
                        format!("unknown class `{class}` in rule `{}`: {listing}", rule.name),
                    ));
                }
            }
        }
    }
    if diags.is_empty() {
        Ok(())
    } else {
        Err(RulesError::new(diags))
    }
}
