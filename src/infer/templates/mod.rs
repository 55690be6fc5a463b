//! Statement templates (docs/guide.md#learning): the statement set used when the user
//! gives none, generated from the classes (and fixed objects) of the
//! demonstrations.
//!
//! # Background
//!
//! The first edition (docs/guide.md#learning) instantiates, per movable subject class `A` and
//! target `B`, the single atoms `DR_d`, `EC_d`, `!DR_d`, "touches some B" and
//! "among the Bs", plus "in a corner" per subject. The second edition
//! (docs/guide.md#learning) keeps all of these and adds flush contact, "touches no B", rows,
//! columns, flush neighbours and, per fixed object `f`, the scene-level
//! statements `some A: touches(f)` and `no A: touches(f)`.
//!
//! # Practical
//!
//! Templates are data. Per movable subject `A`, in this order:
//!
//! 1. for every target (`A` itself, every other class, fixed ones included,
//!    then `*`): [`PAIR_TEMPLATES`], then (second edition)
//!    [`FLUSH_PAIR_TEMPLATES`];
//! 2. (second edition) [`SELF_TEMPLATES`] with target `A`;
//! 3. [`SUBJECT_TEMPLATES`];
//! 4. (second edition) [`LANDMARK_TEMPLATES`] for every landmark of
//!    [`demo_landmarks`], in the order of the first demonstration;
//! 5. (third edition, the default) [`GROUP_TEMPLATES`]: the class forms one
//!    group, row, column or block.
//!
//! A template whose name contains `{d}` is expanded over the four
//! directions. Generated statements with the same scope and formula as an
//! earlier one are dropped, and names stay unique (a clash gets a numeric
//! suffix). With [`Templates::First`] the output is exactly the first
//! edition's set: same statements, names and order.
//!
//! The formulas are built by the public builders of this module
//! ([`atom`], [`touches`], [`inside`], [`corner`], …), which the runtime
//! study's pool (the bench crate's `pool`) uses too.
//!
//! # How to extend
//!
//! Add an entry to one of the tables: a name pattern (`{A}` subject, `{B}`
//! target — `any` for `*`, the id for a landmark —, `{d}` lower-case
//! direction letter), a scope, and a function building the formula from
//! [`TemplateArgs`] (preferably through a builder). Order in the table is
//! the order of the generated statements.

use crate::relations::{Dir, Kind, Quant};
use crate::rules::{Formula, Rule, RuleSet, Scope, Target};
use crate::scene::Scene;
use crate::shapes::ShapeKind;
use std::collections::HashSet;
use std::fmt;

/// Which template set to generate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Templates {
    /// The first edition's set (docs/guide.md#learning), exactly.
    First,
    /// The second edition's set: the first edition's and more.
    Second,
    /// The third edition's set, the default: the second edition's and the
    /// group statements ([`GROUP_TEMPLATES`]) per movable class.
    #[default]
    Third,
}

impl Templates {
    /// Whether this is the first edition.
    pub fn is_first(&self) -> bool {
        matches!(self, Templates::First)
    }
}

impl std::str::FromStr for Templates {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "first" => Ok(Templates::First),
            "second" => Ok(Templates::Second),
            "third" => Ok(Templates::Third),
            _ => Err(format!(
                "unknown template set `{s}`; expected `first`, `second` or `third`"
            )),
        }
    }
}

impl fmt::Display for Templates {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Templates::First => "first",
            Templates::Second => "second",
            Templates::Third => "third",
        })
    }
}

mod builders;
pub use builders::{
    any_side, apart, atom, column, contacts_flush, corner, flush_neighbour_ew, flush_neighbour_ns,
    group_shape, inside, quantified, row, touches, touches_flush,
};

// ---- tables ---------------------------------------------------------------

/// What a template is instantiated with.
#[derive(Debug, Clone)]
pub struct TemplateArgs<'a> {
    /// The subject class.
    pub subject: &'a str,
    /// The target (for subject-only templates: `*`; for self templates the
    /// subject class; for landmark templates the landmark).
    pub target: &'a Target,
    /// The direction (for templates without `{d}`: north).
    pub dir: Dir,
}

impl TemplateArgs<'_> {
    /// The atom `rel(subject, target)` with this instance's subject and target.
    pub fn atom(&self, kind: Kind, dir: Dir) -> Formula {
        atom(kind, dir, self.subject, self.target)
    }
    /// The atom `rel(subject, target)` with an explicit target.
    pub fn atom_to(&self, kind: Kind, dir: Dir, target: Target) -> Formula {
        atom(kind, dir, self.subject, &target)
    }
}

/// One statement template.
#[derive(Debug, Clone, Copy)]
pub struct Template {
    /// Name pattern: `{A}` subject, `{B}` target (`any` for `*`), `{d}`
    /// direction letter (lower case; the template is expanded over `N S E W`).
    pub name: &'static str,
    /// Per object, or about the whole scene.
    pub scope: Scope,
    /// Builds the formula.
    pub build: fn(&TemplateArgs) -> Formula,
}

impl Template {
    fn per_direction(&self) -> bool {
        self.name.contains("{d}")
    }
}

const EACH: Scope = Scope::Each;

/// Templates over a subject class and a target (docs/guide.md#learning).
pub const PAIR_TEMPLATES: &[Template] = &[
    Template {
        name: "{A}_dr_{d}_{B}",
        scope: EACH,
        build: |t| t.atom(Kind::DR, t.dir),
    },
    Template {
        name: "{A}_ec_{d}_{B}",
        scope: EACH,
        build: |t| t.atom(Kind::EC, t.dir),
    },
    Template {
        name: "{A}_not_dr_{d}_{B}",
        scope: EACH,
        build: |t| Formula::not(t.atom(Kind::DR, t.dir)),
    },
    Template {
        name: "{A}_touches_{B}",
        scope: EACH,
        build: |t| touches(t.subject, t.target),
    },
    Template {
        name: "{A}_inside_{B}",
        scope: EACH,
        build: |t| inside(t.subject, t.target),
    },
];

/// Second-edition templates over a subject class and a target (docs/guide.md#learning).
pub const FLUSH_PAIR_TEMPLATES: &[Template] = &[
    Template {
        name: "{A}_fl_{d}_{B}",
        scope: EACH,
        build: |t| t.atom(Kind::FL, t.dir),
    },
    Template {
        name: "{A}_touches_flush_{B}",
        scope: EACH,
        build: |t| touches_flush(t.subject, t.target),
    },
    Template {
        name: "{A}_contacts_flush_{B}",
        scope: EACH,
        build: |t| contacts_flush(t.subject, t.target),
    },
    Template {
        name: "{A}_apart_{B}",
        scope: EACH,
        build: |t| apart(t.subject, t.target),
    },
];

/// Second-edition templates about a subject class and its own objects
/// (docs/guide.md#learning, `B = A`).
pub const SELF_TEMPLATES: &[Template] = &[
    Template {
        name: "{A}_row",
        scope: EACH,
        build: |t| row(t.subject),
    },
    Template {
        name: "{A}_column",
        scope: EACH,
        build: |t| column(t.subject),
    },
    Template {
        name: "{A}_neighbour_ew",
        scope: EACH,
        build: |t| flush_neighbour_ew(t.subject),
    },
    Template {
        name: "{A}_neighbour_ns",
        scope: EACH,
        build: |t| flush_neighbour_ns(t.subject),
    },
];

/// Templates over a subject class alone (docs/guide.md#learning).
pub const SUBJECT_TEMPLATES: &[Template] = &[Template {
    // Contact on two adjacent sides: NW | WS | SE | EN.
    name: "{A}_corner",
    scope: EACH,
    build: |t| corner(t.subject),
}];

/// Second-edition scene-level templates over a subject class and a landmark
/// `f` (docs/guide.md#learning): `some A: touches(f)` and `no A: touches(f)`.
pub const LANDMARK_TEMPLATES: &[Template] = &[
    Template {
        name: "{A}_some_touch_{B}",
        scope: Scope::Scene(Quant::Some),
        build: |t| touches(t.subject, t.target),
    },
    Template {
        name: "{A}_none_touch_{B}",
        scope: Scope::Scene(Quant::No),
        build: |t| touches(t.subject, t.target),
    },
];

/// Third-edition group templates over a subject class as a whole: "the
/// `A`s form one group / row / column / block" (see [`crate::shapes`]).
pub const GROUP_TEMPLATES: &[Template] = &[
    Template {
        name: "{A}_one_group",
        scope: Scope::Group,
        build: |t| group_shape(ShapeKind::Group, t.subject),
    },
    Template {
        name: "{A}_one_row",
        scope: Scope::Group,
        build: |t| group_shape(ShapeKind::Row, t.subject),
    },
    Template {
        name: "{A}_one_column",
        scope: Scope::Group,
        build: |t| group_shape(ShapeKind::Column, t.subject),
    },
    Template {
        name: "{A}_one_block",
        scope: Scope::Group,
        build: |t| group_shape(ShapeKind::Block, t.subject),
    },
];

/// Third-edition orientation templates over a subject class whose objects
/// turn in the demonstrations (an object of the class that is not square
/// lies turned in one, or is `turnable`): "every `A` lies turned", "no `A`
/// lies turned" (docs/language.md#orientation).
pub const ORIENTATION_TEMPLATES: &[Template] = &[
    Template {
        name: "{A}_turned",
        scope: EACH,
        build: |t| Formula::Turned(t.subject.to_string()),
    },
    Template {
        name: "{A}_not_turned",
        scope: EACH,
        build: |t| Formula::not(Formula::Turned(t.subject.to_string())),
    },
];

/// Whether class `class` turns in `demos`: some object of it that is not
/// square lies turned or is `turnable` (the orientation templates are
/// generated for it).
pub fn class_turns(demos: &[Scene], class: &str) -> bool {
    demos
        .iter()
        .flat_map(|s| &s.objects)
        .any(|o| o.class == class && !o.fixed && o.is_oblong() && (o.turned || o.turnable))
}

/// Every template table, for the names `crate::priors` accepts as a kind's
/// template. A new table is added here too (a test checks that every
/// generated statement's template is listed).
pub const TABLES: &[&[Template]] = &[
    PAIR_TEMPLATES,
    FLUSH_PAIR_TEMPLATES,
    SELF_TEMPLATES,
    SUBJECT_TEMPLATES,
    LANDMARK_TEMPLATES,
    GROUP_TEMPLATES,
    ORIENTATION_TEMPLATES,
];

/// The template named `name` in [`TABLES`].
pub fn template_named(name: &str) -> Option<&'static Template> {
    TABLES
        .iter()
        .flat_map(|t| t.iter())
        .find(|t| t.name == name)
}

/// Whether the template's name contains `{d}` (it is expanded over the
/// four directions).
pub fn is_per_direction(t: &Template) -> bool {
    t.per_direction()
}

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

/// Whether `s` is an identifier `[A-Za-z_][A-Za-z0-9_]*` (a landmark id).
pub fn is_identifier(s: &str) -> bool {
    let mut c = s.chars();
    c.next()
        .is_some_and(|f| f.is_ascii_alphabetic() || f == '_')
        && c.all(|x| x.is_ascii_alphanumeric() || x == '_')
}

/// The landmarks the templates use (docs/guide.md#learning): the ids of the first
/// demonstration's fixed, placed objects that every demonstration has as a
/// fixed, placed object, whose id is an identifier; in the first
/// demonstration's order.
pub fn demo_landmarks(demos: &[Scene]) -> Vec<String> {
    let Some(first) = demos.first() else {
        return Vec::new();
    };
    let is_landmark = |s: &Scene, id: &str| {
        s.objects
            .iter()
            .any(|o| o.id == id && o.fixed && o.is_placed())
    };
    first
        .objects
        .iter()
        .filter(|o| o.fixed && o.is_placed() && is_identifier(&o.id))
        .map(|o| o.id.clone())
        .filter(|id| demos.iter().all(|s| is_landmark(s, id)))
        .collect()
}

/// Generate the default (third-edition) statement set for `demos`.
pub fn generate(demos: &[Scene]) -> RuleSet {
    generate_set(demos, Templates::Third)
}

/// Generate the statement set `which` for the classes (and, for the second
/// edition, the landmarks) of `demos`: every rule has the default weight and
/// no comments.
pub fn generate_set(demos: &[Scene], which: Templates) -> RuleSet {
    generate_with_origins(demos, which).0
}

/// Where a generated statement came from: its template (the entry's name
/// pattern, e.g. `{A}_dr_{d}_{B}`), the target it was instantiated with and
/// the direction of a `{d}` template. `crate::priors` derives a statement's
/// *kind* from it, so a new table needs no change there.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct TemplateOrigin {
    /// The template's name pattern ([`Template::name`]).
    pub template: &'static str,
    /// The subject class.
    pub subject: String,
    /// The target the template was instantiated with.
    pub target: Target,
    /// The direction, for a template whose name contains `{d}`.
    pub dir: Option<Dir>,
}

/// [`generate_set`] and, per generated rule (same order), its
/// [`TemplateOrigin`].
pub fn generate_with_origins(demos: &[Scene], which: Templates) -> (RuleSet, Vec<TemplateOrigin>) {
    let second = which != Templates::First;
    let third = which == Templates::Third;
    let classes = demo_classes(demos);
    let mut targets: Vec<Target> = classes
        .iter()
        .map(|(c, _)| Target::Class(c.clone()))
        .collect();
    targets.push(Target::Any);
    let landmarks: Vec<Target> = if second {
        demo_landmarks(demos)
            .into_iter()
            .map(Target::Landmark)
            .collect()
    } else {
        Vec::new()
    };
    let mut out = Generated::default();
    for (subject, movable) in &classes {
        if !movable {
            continue;
        }
        for target in &targets {
            for t in PAIR_TEMPLATES {
                out.expand(t, subject, target);
            }
            if second {
                for t in FLUSH_PAIR_TEMPLATES {
                    out.expand(t, subject, target);
                }
            }
        }
        if second {
            let own = Target::Class(subject.clone());
            for t in SELF_TEMPLATES {
                out.expand(t, subject, &own);
            }
        }
        for t in SUBJECT_TEMPLATES {
            out.expand(t, subject, &Target::Any);
        }
        for f in &landmarks {
            for t in LANDMARK_TEMPLATES {
                out.expand(t, subject, f);
            }
        }
        if third {
            for t in GROUP_TEMPLATES {
                out.expand(t, subject, &Target::Any);
            }
            if class_turns(demos, subject) {
                for t in ORIENTATION_TEMPLATES {
                    out.expand(t, subject, &Target::Any);
                }
            }
        }
    }
    (RuleSet::new(out.rules), out.origins)
}

/// An upper bound on the number of statements [`generate_set`] makes for
/// `demos` (before duplicates are dropped), computed without making them:
/// learning refuses demonstrations past [`crate::limits::MAX_STATEMENTS`]
/// before spending memory on them.
pub fn estimate_set(demos: &[Scene], which: Templates) -> usize {
    let second = which != Templates::First;
    let classes = demo_classes(demos);
    let per = |ts: &[Template]| -> usize {
        ts.iter()
            .map(|t| if t.per_direction() { 4 } else { 1 })
            .sum()
    };
    let targets = classes.len() + 1;
    let landmarks = if second {
        demo_landmarks(demos).len()
    } else {
        0
    };
    let movable = classes.iter().filter(|(_, m)| *m).count();
    let mut each = targets * per(PAIR_TEMPLATES)
        + per(SUBJECT_TEMPLATES)
        + landmarks * per(LANDMARK_TEMPLATES);
    if second {
        each += targets * per(FLUSH_PAIR_TEMPLATES) + per(SELF_TEMPLATES);
    }
    if which == Templates::Third {
        each += per(GROUP_TEMPLATES) + per(ORIENTATION_TEMPLATES);
    }
    movable.saturating_mul(each)
}

#[derive(Default)]
struct Generated {
    rules: Vec<Rule>,
    names: HashSet<String>,
    statements: HashSet<(Scope, Formula)>,
    origins: Vec<TemplateOrigin>,
}

impl Generated {
    fn expand(&mut self, t: &Template, subject: &str, target: &Target) {
        let per_direction = t.per_direction();
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
            if !self.statements.insert((t.scope, formula.clone())) {
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
            self.rules
                .push(Rule::new(name, formula).with_scope(t.scope));
            self.origins.push(TemplateOrigin {
                template: t.name,
                subject: subject.to_string(),
                target: target.clone(),
                dir: per_direction.then_some(dir),
            });
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

    #[test]
    fn same_formula_with_another_scope_is_kept() {
        let mut g = Generated::default();
        let f = Target::Landmark("w".into());
        for t in LANDMARK_TEMPLATES {
            g.expand(t, "B", &f);
            g.expand(t, "B", &f);
        }
        let names: Vec<&str> = g.rules.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["B_some_touch_w", "B_none_touch_w"]);
        assert_eq!(g.rules[0].formula, g.rules[1].formula);
        assert_ne!(g.rules[0].scope, g.rules[1].scope);
    }

    #[test]
    fn every_generated_template_is_in_tables() {
        let demos = crate::scene::scenes_from_json(
            r#"[{"space":{"width":40,"height":40},"objects":[
              {"class":"B","x":0,"y":0,"width":5,"height":5},
              {"class":"B","x":10,"y":0,"width":5,"height":5},
              {"class":"R","x":20,"y":0,"width":5,"height":5},
              {"class":"W","x":0,"y":35,"width":40,"height":5,"fixed":true,"id":"w"}]}]"#,
        )
        .unwrap();
        let (set, origins) = generate_with_origins(&demos, Templates::Second);
        assert_eq!(set.rules.len(), origins.len());
        for o in &origins {
            assert!(
                template_named(o.template).is_some(),
                "{} not in TABLES",
                o.template
            );
        }
    }

    #[test]
    fn identifiers() {
        assert!(is_identifier("w_west") && is_identifier("_a1"));
        assert!(!is_identifier("1w") && !is_identifier("w-west") && !is_identifier(""));
    }
}
