//! Semantic checks that need a scene (classes named by rules exist in it;
//! landmarks name fixed objects of it).

use super::{Diagnostic, DiagnosticKind, RuleSet, RulesError, Scope, Span, Target};
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
        format!("the scene has classes {}", cut_list(&classes))
    };
    unknown_classes(rules, &classes, |class, rule| {
        format!(
            "unknown class `{}` in rule `{}`: {listing}",
            crate::limits::cut(class),
            crate::limits::cut(rule)
        )
    })
}

/// Check that every class named by `rules` exists in at least one of
/// `scenes` (docs/language.md#classes-a-scene-lacks: a class some scene the command reads has is
/// ordinary, its rules hold vacuously where it is absent; a class no scene
/// has is the likely misspelling). Each error names the closest class the
/// scenes have.
pub fn check_classes_across(rules: &RuleSet, scenes: &[&Scene]) -> Result<(), RulesError> {
    let mut classes: Vec<&str> = Vec::new();
    for s in scenes {
        for c in s.classes() {
            if !classes.contains(&c) {
                classes.push(c);
            }
        }
    }
    let listing = if classes.is_empty() {
        "the scenes have no objects".to_string()
    } else if scenes.len() == 1 {
        format!("the scene has classes {}", cut_list(&classes))
    } else {
        format!("the scenes have classes {}", cut_list(&classes))
    };
    unknown_classes(rules, &classes, |class, rule| {
        let hint = closest(class, &classes)
            .map(|c| format!(" (did you mean `{c}`?)"))
            .unwrap_or_default();
        format!(
            "unknown class `{}` in rule `{}`{hint}: expected a class of the scenes read; {listing}",
            crate::limits::cut(class),
            crate::limits::cut(rule)
        )
    })
}

/// One diagnostic per atom naming a class (subject or target) not in
/// `classes`, at the atom's span when the rule was parsed; `message(class,
/// rule name)` words it.
fn unknown_classes(
    rules: &RuleSet,
    classes: &[&str],
    message: impl Fn(&str, &str) -> String,
) -> Result<(), RulesError> {
    let mut diags = Vec::new();
    for rule in &rules.rules {
        if let Some((shape, _)) = rule.formula.shape() {
            if !classes.contains(&shape.class.as_str()) {
                let span = rule
                    .origin
                    .as_ref()
                    .and_then(|o| o.atoms.first().copied())
                    .unwrap_or(Span::new(0, 0));
                diags.push(Diagnostic::new(
                    DiagnosticKind::UnknownClass,
                    span,
                    message(&shape.class, &rule.name),
                ));
            }
        }
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
                        DiagnosticKind::UnknownClass,
                        span,
                        message(class, &rule.name),
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

/// A list of classes for a message, cut after a few.
fn cut_list(classes: &[&str]) -> String {
    const SHOWN: usize = 12;
    let mut s: Vec<String> = classes
        .iter()
        .take(SHOWN)
        .map(|c| crate::limits::cut(c))
        .collect();
    if classes.len() > SHOWN {
        s.push(format!("and {} more", classes.len() - SHOWN));
    }
    s.join(", ")
}

/// The class of `classes` closest to `name` (case-insensitive equality
/// first, then the smallest edit distance, at most half the name's
/// length), if any.
fn closest<'a>(name: &str, classes: &[&'a str]) -> Option<&'a str> {
    if name.chars().count() > crate::limits::MAX_ECHO {
        return None;
    }
    if let Some(c) = classes.iter().find(|c| c.eq_ignore_ascii_case(name)) {
        return Some(c);
    }
    let limit = name.chars().count().div_ceil(2).max(1);
    classes
        .iter()
        .filter(|c| c.chars().count() <= crate::limits::MAX_ECHO)
        .map(|c| (edit_distance(name, c), *c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Levenshtein distance over characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

/// The classes named by `rules` (as subject or target) that `scene` has no
/// object of, in order of first mention. For *learned* rules this is
/// ordinary (docs/language.md#group-statements: no blue blocks today) and their rules hold as docs/language.md#class-rules
/// says; [`check_classes`] guards hand-written rules instead.
pub fn missing_classes(rules: &RuleSet, scene: &Scene) -> Vec<String> {
    let classes = scene.classes();
    let mut out: Vec<String> = Vec::new();
    for rule in &rules.rules {
        // A group statement names its class in its shape, not in atoms.
        if rule.scope == Scope::Group {
            let class = rule.formula.subject();
            if !classes.contains(&class) && !out.iter().any(|o| o == class) {
                out.push(class.to_string());
            }
        }
        for atom in rule.formula.atoms() {
            let mut named = vec![atom.subject.as_str()];
            if let Target::Class(c) = &atom.target {
                named.push(c);
            }
            for class in named {
                if !classes.contains(&class) && !out.iter().any(|o| o == class) {
                    out.push(class.to_string());
                }
            }
        }
    }
    out
}

/// The rules about a class in `missing` that a scene without it breaks
/// instead of keeping vacuously (docs/language.md#classes-a-scene-lacks): a
/// scene rule that needs a subject (`some Q: …`, `at least K Q: …`) and a
/// negated group statement (`not group(Q)`: the empty class is one group).
pub fn rules_needing(rules: &RuleSet, missing: &[String]) -> Vec<String> {
    rules
        .rules
        .iter()
        .filter(|r| missing.iter().any(|m| m == r.formula.subject()))
        .filter(|r| match r.scope {
            Scope::Scene(q) => !q.holds(0, 0),
            Scope::Group => r.formula.shape().is_some_and(|(_, negated)| negated),
            Scope::Each => false,
        })
        .map(|r| r.name.clone())
        .collect()
}

/// [`missing_classes_note`] for `rules` on `scene`.
#[doc(hidden)]
pub fn absent_classes_note(rules: &RuleSet, scene: &Scene) -> Option<String> {
    let missing = missing_classes(rules, scene);
    missing_classes_note(&missing, &rules_needing(rules, &missing))
}

/// The note a command prints for [`missing_classes`] (docs/language.md#classes-a-scene-lacks), or `None`;
/// `needing`: the rules [`rules_needing`] names, which cannot hold.
/// Shared with the command line (a separate crate); not part of the API.
#[doc(hidden)]
pub fn missing_classes_note(missing: &[String], needing: &[String]) -> Option<String> {
    let except = match needing {
        [] => String::new(),
        [one] => format!(", except `{one}`, which needs one and cannot hold"),
        many => format!(
            ", except {}, which need one and cannot hold",
            many.iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    match missing {
        [] => None,
        [one] => Some(format!(
            "note: the problem has no objects of class {one}; its rules hold vacuously{except}"
        )),
        many => Some(format!(
            "note: the problem has no objects of classes {}; their rules hold vacuously{except}",
            many.join(", ")
        )),
    }
}

/// Check that every landmark `@ID` named by `rules` is a fixed object of
/// `scene` (docs/language.md#landmarks, docs/language.md#syntax).
///
/// Ids are as written in the scene or the docs/scenes.md#fields default `<class><index>`
/// (already filled in by [`Scene::from_json`]); an object whose id is not
/// an identifier cannot be a landmark. Reports every atom naming a missing
/// or movable object, at the atom's span when the rule was parsed, naming
/// the rule and the id and listing the scene's fixed objects.
pub fn check_landmarks(rules: &RuleSet, scene: &Scene) -> Result<(), RulesError> {
    let fixed: Vec<&str> = scene
        .objects
        .iter()
        .filter(|o| o.fixed && o.is_placed() && is_identifier(&o.id))
        .map(|o| o.id.as_str())
        .collect();
    let listing = if fixed.is_empty() {
        "the scene has no fixed objects that can be landmarks".to_string()
    } else {
        format!("the scene's fixed objects are {}", cut_list(&fixed))
    };
    let mut diags = Vec::new();
    for rule in &rules.rules {
        for (i, atom) in rule.formula.atoms().into_iter().enumerate() {
            let Target::Landmark(id) = &atom.target else {
                continue;
            };
            if fixed.contains(&id.as_str()) {
                continue;
            }
            let span = rule
                .origin
                .as_ref()
                .and_then(|o| o.atoms.get(i).copied())
                .unwrap_or(Span::new(0, 0));
            let movable = scene.objects.iter().any(|o| &o.id == id && !o.fixed);
            let message = if movable {
                format!(
                    "landmark `@{}` in rule `{}` is not a fixed object: expected the id of a fixed object; {listing}",
                    crate::limits::cut(id),
                    crate::limits::cut(&rule.name)
                )
            } else {
                format!(
                    "unknown landmark `@{}` in rule `{}`: expected the id of a fixed object; {listing}",
                    crate::limits::cut(id),
                    crate::limits::cut(&rule.name)
                )
            };
            diags.push(Diagnostic::new(
                DiagnosticKind::UnknownLandmark,
                span,
                message,
            ));
        }
    }
    if diags.is_empty() {
        Ok(())
    } else {
        Err(RulesError::new(diags))
    }
}

/// Whether `s` is an identifier `[A-Za-z_][A-Za-z0-9_]*` (only such ids can
/// be written after `@`).
fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}
