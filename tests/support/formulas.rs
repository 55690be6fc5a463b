//! Formulas for the tests: atoms written as in the language (`atom("EC_N",
//! "B", "*")`), `and`/`or`/`not`, and random second-edition formulas for
//! the differential tests (`synth_differential`, `ask_probes`, `emit`):
//! atoms with every relation, quantifier and target kind, and trees of them.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use rccpack::relations::{Dir, Kind, Quant, Relation};
use rccpack::rules::{Atom, Formula, Target};

/// A relation as the tests name it: a [`Relation`], or its name (`"EC_N"`).
pub trait AsRelation {
    /// The relation.
    fn relation(self) -> Relation;
}

impl AsRelation for Relation {
    fn relation(self) -> Relation {
        self
    }
}

impl AsRelation for &str {
    fn relation(self) -> Relation {
        Relation::from_name(self).unwrap_or_else(|| panic!("no relation {self:?}"))
    }
}

impl AsRelation for &&str {
    fn relation(self) -> Relation {
        (*self).relation()
    }
}

impl AsRelation for &String {
    fn relation(self) -> Relation {
        self.as_str().relation()
    }
}

/// The atom `REL(subject, target)` with the relation's default quantifier;
/// `target` is a class, or `*` for any object.
pub fn atom(rel: impl AsRelation, subject: &str, target: &str) -> Formula {
    let target = if target == "*" {
        Target::Any
    } else {
        Target::Class(target.into())
    };
    Formula::Atom(Atom::new(rel.relation(), subject, target))
}

/// `f1 & f2 & …`
pub fn and(v: Vec<Formula>) -> Formula {
    Formula::And(v)
}

/// `f1 | f2 | …`
pub fn or(v: Vec<Formula>) -> Formula {
    Formula::Or(v)
}

/// `!f`
pub fn not(f: Formula) -> Formula {
    Formula::not(f)
}

/// The names a generator draws targets from.
pub struct Vocabulary {
    /// Six class names, drawn uniformly (repeat a name to weigh it).
    pub classes: [&'static str; 6],
    /// A landmark id that is never a fixed object (an empty target).
    pub absent: &'static str,
}

/// A uniform element of `v`.
pub fn pick<T: Copy>(rng: &mut ChaCha8Rng, v: &[T]) -> T {
    v[rng.random_range(0..v.len())]
}

/// A random quantifier for an atom: the default about half the time; `K`
/// in 0..=4, around the number of target objects.
pub fn random_quant(rng: &mut ChaCha8Rng, rel: Relation) -> Quant {
    let k = rng.random_range(0..=4u32);
    match rng.random_range(0..10) {
        0..=4 => rel.default_quant(),
        5 => Quant::Every,
        6 => Quant::Some,
        7 => Quant::No,
        8 => Quant::AtLeast(k),
        _ => Quant::AtMost(k),
    }
}

/// A random target: a class (half the time), `*`, or a landmark — `@f`,
/// `@g` (fixed objects when the case has them, else missing) or
/// `voc.absent` (never fixed).
pub fn random_target(rng: &mut ChaCha8Rng, voc: &Vocabulary) -> Target {
    match rng.random_range(0..12usize) {
        i @ 0..=5 => Target::Class(voc.classes[i].into()),
        6..=7 => Target::Any,
        8..=9 => Target::Landmark("f".into()),
        10 => Target::Landmark("g".into()),
        _ => Target::Landmark(voc.absent.into()),
    }
}

/// One random atom of `subject` (a landmark keeps the default quantifier,
/// docs/language.md#landmarks).
pub fn random_atom(rng: &mut ChaCha8Rng, voc: &Vocabulary, subject: &str) -> Formula {
    let rel = pick(rng, &Relation::ALL);
    let target = random_target(rng, voc);
    let quant = match target {
        Target::Landmark(_) => rel.default_quant(),
        _ => random_quant(rng, rel),
    };
    Formula::Atom(Atom::quantified(rel, subject, quant, target))
}

/// A random formula of depth at most `depth`.
pub fn random_tree(rng: &mut ChaCha8Rng, voc: &Vocabulary, subject: &str, depth: u32) -> Formula {
    if depth <= 1 {
        return random_atom(rng, voc, subject);
    }
    match rng.random_range(0..6) {
        0 | 1 => random_atom(rng, voc, subject),
        2 => Formula::not(random_tree(rng, voc, subject, depth - 1)),
        k => {
            let n = rng.random_range(2..=3);
            let v = (0..n)
                .map(|_| random_tree(rng, voc, subject, depth - 1))
                .collect();
            if k == 3 {
                Formula::And(v)
            } else {
                Formula::Or(v)
            }
        }
    }
}

/// The atom `KIND_DIR(subject, quant target)`.
pub fn q_atom(kind: Kind, dir: Dir, subject: &str, quant: Quant, target: &Target) -> Formula {
    Formula::Atom(Atom::quantified(
        Relation::new(kind, dir),
        subject,
        quant,
        target.clone(),
    ))
}
