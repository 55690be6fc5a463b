//! Statement templates (SPEC §8): the statement set used when the user gives
//! none, generated from the classes of the demonstrations.
//!
//! # Practical
//!
//! Templates are data: [`PAIR_TEMPLATES`] are instantiated for every movable
//! subject class `A` and every target (`A` itself, every other class, fixed
//! ones included, and `*`), [`SUBJECT_TEMPLATES`] once per movable subject.
//! A template whose name contains `{d}` is expanded over the four directions.
//! Generated statements with the same formula as an earlier one are dropped,
//! and names stay unique (a clash gets a numeric suffix).
//!
//! # How to extend
//!
//! Add an entry to one of the tables: a name pattern (`{A}` subject, `{B}`
//! target — `any` for `*` —, `{d}` lower-case direction letter) and a
//! function building the formula from [`TemplateArgs`]. Order in the table is
//! the order of the generated statements.

use crate::relations::{Dir, Kind, Relation};
use crate::rules::{Atom, Formula, Rule, RuleSet, Target};
use crate::scene::Scene;
use std::collections::HashSet;

/// What a template is instantiated with.
#[derive(Debug, Clone)]
pub struct TemplateArgs<'a> {
    /// The subject class.
    pub subject: &'a str,
    /// The target (for subject-only templates: `*`).
    pub target: &'a Target,
    /// The direction (for templates without `{d}`: north).
    pub dir: Dir,
}

impl TemplateArgs<'_> {
    /// The atom `rel(subject, target)` with this instance's subject and target.
    pub fn atom(&self, kind: Kind, dir: Dir) -> Formula {
        self.atom_to(kind, dir, self.target.clone())
    }
    /// The atom `rel(subject, target)` with an explicit target.
    pub fn atom_to(&self, kind: Kind, dir: Dir, target: Target) -> Formula {
        Formula::Atom(Atom::new(Relation::new(kind, dir), self.subject, target))
    }
}

/// One statement template.
#[derive(Debug, Clone, Copy)]
pub struct Template {
    /// Name pattern: `{A}` subject, `{B}` target (`any` for `*`), `{d}`
    /// direction letter (lower case; the template is expanded over `N S E W`).
    pub name: &'static str,
    /// Builds the formula.
    pub build: fn(&TemplateArgs) -> Formula,
}

impl Template {
    fn per_direction(&self) -> bool {
        self.name.contains("{d}")
    }
}

/// Templates over a subject class and a target (§8).
pub const PAIR_TEMPLATES: &[Template] = &[
    Template {
        name: "{A}_dr_{d}_{B}",
        build: |t| t.atom(Kind::DR, t.dir),
    },
    Template {
        name: "{A}_ec_{d}_{B}",
        build: |t| t.atom(Kind::EC, t.dir),
    },
    Template {
        name: "{A}_not_dr_{d}_{B}",
        build: |t| Formula::not(t.atom(Kind::DR, t.dir)),
    },
    Template {
        name: "{A}_touches_{B}",
        build: |t| Formula::Or(Dir::ALL.iter().map(|&d| t.atom(Kind::EC, d)).collect()),
    },
    Template {
        name: "{A}_inside_{B}",
        build: |t| {
            Formula::And(
                Dir::ALL
                    .iter()
                    .map(|&d| Formula::not(t.atom(Kind::DR, d)))
                    .collect(),
            )
        },
    },
];

/// Templates over a subject class alone (§8).
pub const SUBJECT_TEMPLATES: &[Template] = &[Template {
    // Contact on two adjacent sides: NW | WS | SE | EN.
    name: "{A}_corner",
    build: |t| {
        let pairs = [
            (Dir::N, Dir::W),
            (Dir::W, Dir::S),
            (Dir::S, Dir::E),
            (Dir::E, Dir::N),
        ];
        Formula::Or(
            pairs
                .iter()
                .map(|&(a, b)| {
                    Formula::And(vec![
                        t.atom_to(Kind::EC, a, Target::Any),
                        t.atom_to(Kind::EC, b, Target::Any),
                    ])
                })
                .collect(),
        )
    },
}];

/// The classes of the demonstrations in order of first appearance, and
/// whether each is movable (has at least one object that is not fixed).
pub fn demo_classes(demos: &[Scene]) -> Vec<(String, bool)> {
    let mut out: Vec<(String, bool)> = Vec::new();
    for s in demos {
        for o in &s.objects {
            match out.iter_mut().find(|(c, _)| *c == o.class) {
                Some((_, movable)) => *movable |= !o.fixed,
                None => out.push((o.class.clone(), !o.fixed)),
            }
        }
    }
    out
}

/// Generate the §8 statement set for the classes of `demos`: every rule has
/// the default weight and no comments.
pub fn generate(demos: &[Scene]) -> RuleSet {
    let classes = demo_classes(demos);
    let mut targets: Vec<Target> = classes
        .iter()
        .map(|(c, _)| Target::Class(c.clone()))
        .collect();
    targets.push(Target::Any);
    let mut out = Generated::default();
    for (subject, movable) in &classes {
        if !movable {
            continue;
        }
        for target in &targets {
            for t in PAIR_TEMPLATES {
                out.expand(t, subject, target);
            }
        }
        for t in SUBJECT_TEMPLATES {
            out.expand(t, subject, &Target::Any);
        }
    }
    RuleSet::new(out.rules)
}

#[derive(Default)]
struct Generated {
    rules: Vec<Rule>,
    names: HashSet<String>,
    formulas: HashSet<Formula>,
}

impl Generated {
    fn expand(&mut self, t: &Template, subject: &str, target: &Target) {
        let dirs: &[Dir] = if t.per_direction() {
            &Dir::ALL
        } else {
            &[Dir::N]
        };
        let target_name = match target {
            Target::Any => "any",
            Target::Class(c) | Target::Landmark(c) => c.as_str(),
        };
        for &dir in dirs {
            let args = TemplateArgs {
                subject,
                target,
                dir,
            };
            let formula = (t.build)(&args);
            if !self.formulas.insert(formula.clone()) {
                continue;
            }
            let base = t
                .name
                .replace("{A}", subject)
                .replace("{B}", target_name)
                .replace("{d}", &dir.letter().to_ascii_lowercase().to_string());
            let mut name = base.clone();
            let mut k = 2;
            while self.names.contains(&name) {
                name = format!("{base}_{k}");
                k += 1;
            }
            self.names.insert(name.clone());
            self.rules.push(Rule::new(name, formula));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicate_formulas_are_dropped_and_names_stay_unique() {
        let mut g = Generated::default();
        let any = Target::Any;
        g.expand(&PAIR_TEMPLATES[0], "B", &any);
        g.expand(&PAIR_TEMPLATES[0], "B", &any);
        assert_eq!(g.rules.len(), 4, "the second expansion adds nothing");
        // A class literally named `any` gets distinct names from `*`.
        g.expand(&PAIR_TEMPLATES[0], "B", &Target::Class("any".into()));
        let names: Vec<&str> = g.rules.iter().map(|r| r.name.as_str()).collect();
        assert!(names.contains(&"B_dr_n_any") && names.contains(&"B_dr_n_any_2"));
    }
}
