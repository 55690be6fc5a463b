//! The rule AST: formulas over class-relation atoms, rules with modifiers,
//! rule sets (docs/language.md).
//!
//! Formulas carry no source spans, so two rule sets compare equal when they
//! mean the same text-independent thing; spans live beside them in
//! [`RuleOrigin`] for diagnostics.

pub use crate::relations::Quant;
use crate::relations::Relation;
pub use crate::shapes::ShapeKind;
use std::fmt;

/// A byte range in the source text.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// First byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

impl Span {
    /// A span from byte offsets.
    pub const fn new(start: usize, end: usize) -> Self {
        Span { start, end }
    }
}

/// The target of an atom: a class, `*` (every object of any class) or a
/// landmark `@ID` (one fixed object, docs/language.md#landmarks).
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Target {
    /// A named class.
    Class(String),
    /// `*`: every other object.
    Any,
    /// `@ID`: the fixed object with this id.
    Landmark(String),
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Target::Class(c) => f.write_str(c),
            Target::Any => f.write_str("*"),
            Target::Landmark(id) => write!(f, "@{id}"),
        }
    }
}

/// A class-relation atom `REL(subject, [Q] target)`.
///
/// The quantifier is always stored resolved: an atom written without one
/// holds the relation's default (docs/language.md#quantifiers), so `DR_N(B, R)` and
/// `DR_N(B, every R)` are the same atom. A landmark target always has the
/// default quantifier (a written one is an error).
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Atom {
    /// The relation.
    pub rel: Relation,
    /// The subject class.
    pub subject: String,
    /// The target quantifier.
    pub quant: Quant,
    /// The target class, `*` or landmark.
    pub target: Target,
}

impl Atom {
    /// An atom with the relation's default quantifier.
    pub fn new(rel: Relation, subject: impl Into<String>, target: Target) -> Self {
        Atom {
            rel,
            subject: subject.into(),
            quant: rel.default_quant(),
            target,
        }
    }
    /// An atom with an explicit quantifier.
    pub fn quantified(
        rel: Relation,
        subject: impl Into<String>,
        quant: Quant,
        target: Target,
    ) -> Self {
        Atom {
            rel,
            subject: subject.into(),
            quant,
            target,
        }
    }
    /// Whether the quantifier is the relation's default (printed implicitly).
    pub fn has_default_quant(&self) -> bool {
        self.quant == self.rel.default_quant()
    }
}

impl fmt::Display for Atom {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.has_default_quant() {
            write!(f, "{}({}, {})", self.rel, self.subject, self.target)
        } else {
            write!(
                f,
                "{}({}, {} {})",
                self.rel, self.subject, self.quant, self.target
            )
        }
    }
}

/// A group statement's shape and class: `column(R)` (fourth edition; see
/// [`crate::shapes`] for what each shape means).
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Shape {
    /// Which shape.
    pub kind: ShapeKind,
    /// The class that forms it.
    pub class: String,
}

impl Shape {
    /// A shape of a class.
    pub fn new(kind: ShapeKind, class: impl Into<String>) -> Self {
        Shape {
            kind,
            class: class.into(),
        }
    }
}

impl fmt::Display for Shape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}({})", self.kind, self.class)
    }
}

/// A Boolean formula over atoms. `And`/`Or` are n-ary (at least two
/// operands when produced by the parser, which flattens `a & (b & c)`).
///
/// A [`Formula::Shape`] is about a class as a whole: it appears only as
/// the whole formula of a group rule ([`Scope::Group`]), possibly under one
/// `Not` (checked by `rules::check`).
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Formula {
    /// An atom.
    Atom(Atom),
    /// A group statement's shape (only as a group rule's whole formula).
    Shape(Shape),
    /// `turned(A)`: the subject (of class `A`) lies turned by 90°
    /// (docs/language.md#orientation); never true of a square object.
    Turned(String),
    /// Negation.
    Not(Box<Formula>),
    /// Conjunction.
    And(Vec<Formula>),
    /// Disjunction.
    Or(Vec<Formula>),
}

impl Formula {
    /// `!f`
    #[allow(clippy::should_implement_trait)]
    pub fn not(f: Formula) -> Formula {
        Formula::Not(Box::new(f))
    }

    /// Every atom, left to right.
    pub fn atoms(&self) -> Vec<&Atom> {
        let mut out = Vec::new();
        let mut stack = vec![self];
        while let Some(f) = stack.pop() {
            match f {
                Formula::Atom(a) => out.push(a),
                Formula::Shape(_) | Formula::Turned(_) => {}
                Formula::Not(g) => stack.push(g),
                Formula::And(v) | Formula::Or(v) => stack.extend(v.iter().rev()),
            }
        }
        out
    }

    /// The subject class of the first atom (every atom of a checked rule has
    /// the same one); `""` for a formula without atoms (an empty `And`/`Or`
    /// built in code).
    pub fn subject(&self) -> &str {
        let mut f = self;
        loop {
            match f {
                Formula::Atom(a) => return &a.subject,
                Formula::Shape(s) => return &s.class,
                Formula::Turned(c) => return c,
                Formula::Not(g) => f = g,
                Formula::And(v) | Formula::Or(v) => match v.first() {
                    Some(g) => f = g,
                    None => return "",
                },
            }
        }
    }

    /// Whether an orientation statement `turned(A)` occurs in the formula.
    pub fn mentions_turns(&self) -> bool {
        match self {
            Formula::Turned(_) => true,
            Formula::Atom(_) | Formula::Shape(_) => false,
            Formula::Not(g) => g.mentions_turns(),
            Formula::And(v) | Formula::Or(v) => v.iter().any(Formula::mentions_turns),
        }
    }

    /// Nesting depth (an atom has depth 1).
    pub fn depth(&self) -> usize {
        match self {
            Formula::Atom(_) | Formula::Shape(_) | Formula::Turned(_) => 1,
            Formula::Not(g) => 1 + g.depth(),
            Formula::And(v) | Formula::Or(v) => 1 + v.iter().map(Formula::depth).max().unwrap_or(0),
        }
    }

    /// The shape of a group rule's formula and whether it is negated:
    /// `Some((shape, false))` for `column(R)`, `Some((shape, true))` for
    /// `!column(R)`; `None` for every other formula.
    pub fn shape(&self) -> Option<(&Shape, bool)> {
        let mut f = self;
        let mut neg = false;
        loop {
            match f {
                Formula::Shape(s) => return Some((s, neg)),
                Formula::Not(g) => {
                    neg = !neg;
                    f = g;
                }
                _ => return None,
            }
        }
    }

    /// Evaluate with a function giving each atom's value (a per-object
    /// formula; a [`Formula::Shape`], which is about the whole class, reads
    /// as false here — group rules are decided by [`crate::shapes::check`];
    /// so does [`Formula::Turned`], which is about the object, not a
    /// relation: see [`Formula::mentions_turns`]).
    pub fn eval(&self, atom: &mut impl FnMut(&Atom) -> bool) -> bool {
        match self {
            Formula::Atom(a) => atom(a),
            Formula::Shape(_) | Formula::Turned(_) => false,
            Formula::Not(g) => !g.eval(atom),
            Formula::And(v) => v.iter().all(|g| g.eval(atom)),
            Formula::Or(v) => v.iter().any(|g| g.eval(atom)),
        }
    }
}

/// How much a rule matters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Strength {
    /// `weight W`, W > 0 (the default is `Weight(1.0)`).
    Weight(f64),
    /// `p P`, 0 < P < 1: the posterior that the rule is not intended;
    /// weight = −ln P.
    P(f64),
    /// `hard`: must hold; not part of the score.
    Hard,
}

impl Default for Strength {
    fn default() -> Self {
        Strength::Weight(1.0)
    }
}

impl Strength {
    /// The weight in the score (0 for hard rules, which are constraints).
    pub fn weight(&self) -> f64 {
        match *self {
            Strength::Weight(w) => w,
            Strength::P(p) => -p.ln(),
            Strength::Hard => 0.0,
        }
    }
    /// Whether the rule is hard.
    pub fn is_hard(&self) -> bool {
        matches!(self, Strength::Hard)
    }
}

/// Who a rule is about (docs/language.md#scene-rules).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Scope {
    /// The ordinary rule: every object of the subject class must satisfy
    /// the formula (one term per object in the score). `every A:` parses to
    /// this.
    #[default]
    Each,
    /// A rule about the whole scene: `Q A: FORMULA` holds when the number of
    /// subject objects satisfying the formula meets `Q` (never
    /// [`Quant::Every`], which is [`Scope::Each`]).
    Scene(Quant),
    /// A group statement (fourth edition): the formula is a
    /// [`Formula::Shape`], possibly negated, about the subject class as a
    /// whole; scored like a scene-level rule (one term).
    Group,
}

impl Scope {
    /// `Scope::Each` for `every`, else `Scope::Scene(q)`.
    pub fn of(q: Quant) -> Scope {
        match q {
            Quant::Every => Scope::Each,
            q => Scope::Scene(q),
        }
    }
    /// Whether this is a scene-level rule (one term in the score): a
    /// quantified scope or a group statement.
    pub fn is_scene(&self) -> bool {
        matches!(self, Scope::Scene(_) | Scope::Group)
    }
}

/// Where a parsed rule came from (absent for rules built in code).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct RuleOrigin {
    /// The whole rule.
    pub span: Span,
    /// The rule's name.
    pub name: Span,
    /// The modifier, if any.
    pub modifier: Option<Span>,
    /// Each atom's span, in [`Formula::atoms`] order; for a group
    /// statement, the one span of its shape.
    pub atoms: Vec<Span>,
    /// The scene quantifier `Q A:`, if written.
    pub scope: Option<Span>,
}

/// A named rule: `rule NAME [MODIFIER]: FORMULA`.
#[derive(Debug, Clone, PartialEq)]
pub struct Rule {
    /// Unique name within its set.
    pub name: String,
    /// Weight, posterior or hard.
    pub strength: Strength,
    /// Per object, or about the whole scene.
    pub scope: Scope,
    /// The formula.
    pub formula: Formula,
    /// Comment lines written above the rule by the printer (without `# `).
    /// Not compared by [`Rule::same_rule`].
    pub comments: Vec<String>,
    /// Source spans, when parsed.
    pub origin: Option<RuleOrigin>,
}

impl Rule {
    /// A rule with default weight 1 and no origin.
    pub fn new(name: impl Into<String>, formula: Formula) -> Self {
        Rule {
            name: name.into(),
            strength: Strength::default(),
            scope: Scope::Each,
            formula,
            comments: Vec::new(),
            origin: None,
        }
    }
    /// The same rule with another scope.
    pub fn with_scope(mut self, s: Scope) -> Self {
        self.scope = s;
        self
    }
    /// The same rule with another strength.
    pub fn with_strength(mut self, s: Strength) -> Self {
        self.strength = s;
        self
    }
    /// The subject class.
    pub fn subject(&self) -> &str {
        self.formula.subject()
    }
    /// A group rule `rule NAME: column(R)` (or its negation).
    pub fn group(name: impl Into<String>, shape: Shape, negated: bool) -> Self {
        let f = Formula::Shape(shape);
        let formula = if negated { Formula::not(f) } else { f };
        Rule::new(name, formula).with_scope(Scope::Group)
    }
    /// Whether this is a group statement.
    pub fn is_group(&self) -> bool {
        self.scope == Scope::Group
    }
    /// Name, strength and formula equal (ignores spans and comments).
    pub fn same_rule(&self, other: &Rule) -> bool {
        self.name == other.name
            && self.strength == other.strength
            && self.scope == other.scope
            && self.formula == other.formula
    }
}

/// An ordered list of rules with unique names.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RuleSet {
    /// The rules, in file order.
    pub rules: Vec<Rule>,
}

impl RuleSet {
    /// A rule set from rules (names are not checked here; see `rules::check`).
    pub fn new(rules: Vec<Rule>) -> Self {
        RuleSet { rules }
    }
    /// Whether both sets hold the same rules in the same order (ignoring
    /// spans and comments).
    pub fn same_rules(&self, other: &RuleSet) -> bool {
        self.rules.len() == other.rules.len()
            && self
                .rules
                .iter()
                .zip(&other.rules)
                .all(|(a, b)| a.same_rule(b))
    }
    /// Every landmark id named by any atom, sorted.
    pub fn landmarks(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for r in &self.rules {
            for a in r.formula.atoms() {
                if let Target::Landmark(id) = &a.target {
                    out.push(id.clone());
                }
            }
        }
        out.sort();
        out.dedup();
        out
    }
    /// Every class named by any atom (subjects and targets), sorted.
    pub fn classes(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for r in &self.rules {
            if let Some((s, _)) = r.formula.shape() {
                out.push(s.class.clone());
            }
            for a in r.formula.atoms() {
                out.push(a.subject.clone());
                if let Target::Class(c) = &a.target {
                    out.push(c.clone());
                }
            }
        }
        out.sort();
        out.dedup();
        out
    }
}
