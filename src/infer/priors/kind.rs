//! The *kind* of a generated statement: what a prior is about.
//!
//! A kind never names a class (class names differ between tasks). It is
//! the statement's template (its name pattern, e.g. `{A}_dr_{d}_{B}`), the
//! [`Role`] of its target, and the direction of a `{d}` template. Kinds form
//! a hierarchy, most general first:
//!
//! ```text
//! *                                   the root: every generated statement
//! {A}_dr_{d}_{B}                      the template
//! {A}_dr_{d}_{B}/fixed                template × the target's role
//! {A}_dr_{d}_{B}/fixed/s              … × direction ({d} templates only)
//! ```
//!
//! Kinds come from [`TemplateOrigin`] (which `generate_with_origins`
//! records for every table), so a new template table needs no change here
//! beyond listing it in [`templates::TABLES`].

use crate::infer::templates::{self, TemplateOrigin};
use crate::relations::Dir;
use crate::rules::Target;
use std::fmt;

/// The key of the root of the hierarchy.
pub const ROOT: &str = "*";

/// The role of a statement's target relative to its subject.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Role {
    /// The subject's own class (`B = A`).
    Own,
    /// Another class with movable objects.
    Movable,
    /// A class whose objects are all fixed.
    Fixed,
    /// `*`: any other object (also the target of subject-only templates).
    Any,
    /// A landmark `@ID`.
    Landmark,
}

impl Role {
    /// Every role, in the order of their names.
    pub const ALL: [Role; 5] = [
        Role::Own,
        Role::Movable,
        Role::Fixed,
        Role::Any,
        Role::Landmark,
    ];

    /// The name used in kind keys.
    pub fn name(self) -> &'static str {
        match self {
            Role::Own => "self",
            Role::Movable => "movable",
            Role::Fixed => "fixed",
            Role::Any => "any",
            Role::Landmark => "landmark",
        }
    }

    /// The role named `s`.
    pub fn from_name(s: &str) -> Option<Role> {
        Role::ALL.into_iter().find(|r| r.name() == s)
    }
}

/// A statement's kind at its most specific level.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Kind {
    /// The template's name pattern.
    pub template: &'static str,
    /// The target's role.
    pub role: Role,
    /// The direction, for a `{d}` template.
    pub dir: Option<Dir>,
}

fn dir_name(d: Dir) -> char {
    d.letter().to_ascii_lowercase()
}

fn dir_from(s: &str) -> Option<Dir> {
    Dir::ALL
        .into_iter()
        .find(|&d| s.len() == 1 && s.starts_with(dir_name(d)))
}

impl Kind {
    /// The kind of a generated statement. `movable(c)`: whether class `c`
    /// has movable objects in the task's demonstrations.
    pub fn of(origin: &TemplateOrigin, movable: impl Fn(&str) -> bool) -> Kind {
        let role = match &origin.target {
            Target::Any => Role::Any,
            Target::Landmark(_) => Role::Landmark,
            Target::Class(c) if *c == origin.subject => Role::Own,
            Target::Class(c) if movable(c) => Role::Movable,
            Target::Class(_) => Role::Fixed,
        };
        Kind {
            template: origin.template,
            role,
            dir: origin.dir,
        }
    }

    /// The keys of this kind's nodes, most general first: the root, the
    /// template, template × role, and (for a `{d}` template) × direction.
    pub fn path(&self) -> Vec<String> {
        let t = self.template.to_string();
        let tr = format!("{t}/{}", self.role.name());
        let mut out = vec![ROOT.to_string(), t, tr.clone()];
        if let Some(d) = self.dir {
            out.push(format!("{tr}/{}", dir_name(d)));
        }
        out
    }

    /// The most specific key.
    pub fn key(&self) -> String {
        self.path().pop().unwrap_or_default()
    }
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.key())
    }
}

/// Why a kind key is not one this version knows.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct UnknownKind(pub String);

/// Check a node key (`*`, `TEMPLATE`, `TEMPLATE/ROLE` or
/// `TEMPLATE/ROLE/DIR`) against the template tables; returns its depth
/// (0 for the root).
pub fn check_key(key: &str) -> Result<usize, UnknownKind> {
    if key == ROOT {
        return Ok(0);
    }
    let mut parts = key.split('/');
    let name = parts.next().unwrap_or("");
    let t = templates::template_named(name).ok_or_else(|| {
        UnknownKind(format!(
            "template `{name}` is not one of the template tables' names"
        ))
    })?;
    let Some(role) = parts.next() else {
        return Ok(1);
    };
    if Role::from_name(role).is_none() {
        return Err(UnknownKind(format!(
            "role `{role}` is unknown; expected one of self, movable, fixed, any, landmark"
        )));
    }
    let Some(dir) = parts.next() else {
        return Ok(2);
    };
    if !templates::is_per_direction(t) {
        return Err(UnknownKind(format!(
            "template `{name}` has no direction, but the kind names direction `{dir}`"
        )));
    }
    if dir_from(dir).is_none() {
        return Err(UnknownKind(format!(
            "direction `{dir}` is unknown; expected n, s, e or w"
        )));
    }
    if let Some(extra) = parts.next() {
        return Err(UnknownKind(format!(
            "unexpected part `{extra}` after the direction"
        )));
    }
    Ok(3)
}

/// Check that `key` is a most specific kind (`TEMPLATE/ROLE`, and
/// `TEMPLATE/ROLE/DIR` for a `{d}` template), the keys a task's counts hold.
pub fn check_most_specific(key: &str) -> Result<(), UnknownKind> {
    let depth = check_key(key)?;
    let per_direction = key
        .split('/')
        .next()
        .and_then(templates::template_named)
        .is_some_and(templates::is_per_direction);
    let expected = if per_direction { 3 } else { 2 };
    if depth == expected {
        return Ok(());
    }
    Err(UnknownKind(format!(
        "a task counts most specific kinds only: expected {}",
        if per_direction {
            "TEMPLATE/ROLE/DIRECTION"
        } else {
            "TEMPLATE/ROLE"
        }
    )))
}

/// The key of the parent of a node (`None` for the root).
pub fn parent_key(key: &str) -> Option<String> {
    if key == ROOT {
        return None;
    }
    match key.rfind('/') {
        Some(i) => Some(key[..i].to_string()),
        None => Some(ROOT.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_and_parents() {
        let k = Kind {
            template: "{A}_dr_{d}_{B}",
            role: Role::Fixed,
            dir: Some(Dir::S),
        };
        assert_eq!(
            k.path(),
            [
                "*",
                "{A}_dr_{d}_{B}",
                "{A}_dr_{d}_{B}/fixed",
                "{A}_dr_{d}_{B}/fixed/s"
            ]
        );
        assert_eq!(check_key(&k.key()), Ok(3));
        assert_eq!(
            parent_key("{A}_dr_{d}_{B}/fixed").as_deref(),
            Some("{A}_dr_{d}_{B}")
        );
        assert_eq!(parent_key("{A}_dr_{d}_{B}").as_deref(), Some("*"));
        assert!(check_key("{A}_corner/any/n").is_err());
        assert!(check_key("{A}_nope").is_err());
        assert!(check_key("{A}_row/robot").is_err());
        assert_eq!(check_most_specific("{A}_dr_{d}_{B}/fixed/s"), Ok(()));
        assert_eq!(check_most_specific("{A}_corner/any"), Ok(()));
        assert!(check_most_specific("{A}_dr_{d}_{B}/fixed").is_err());
        assert!(check_most_specific("{A}_dr_{d}_{B}").is_err());
        assert!(check_most_specific("*").is_err());
    }
}
