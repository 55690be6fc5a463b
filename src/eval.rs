//! The evaluator: which placed object satisfies which rule, hard-rule
//! violations, the grid check and the §6 context score.
//!
//! This is the *one* implementation of SPEC §4 and §6. Learning reports, the
//! solver's re-check, the studio and every test get their truth values and
//! scores from here.
//!
//! Practical: [`Evaluator::new`] builds a [`ClassAtoms`] table once
//! (`O(n²)` pairs), after which every (object, rule) value is a walk over a
//! compiled formula with one byte lookup per atom.

use crate::relations::{ClassAtoms, ClassIndex, Contact, Relation};
use crate::rules::{Formula, RuleSet, Target};
use crate::scene::Scene;

/// A formula with class names resolved to indices.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CompiledFormula {
    /// Atom: relation bit and target (`None` = `*`).
    Atom {
        /// The relation.
        rel: Relation,
        /// Target class index, `None` for `*`.
        target: Option<usize>,
    },
    /// Negation.
    Not(Box<CompiledFormula>),
    /// Conjunction.
    And(Vec<CompiledFormula>),
    /// Disjunction.
    Or(Vec<CompiledFormula>),
}

impl CompiledFormula {
    /// Resolve class names through `classes`, interning unknown ones (a class
    /// with no object: `DR` atoms hold vacuously, `EC` atoms fail).
    pub fn compile(f: &Formula, classes: &mut ClassIndex) -> Self {
        match f {
            Formula::Atom(a) => CompiledFormula::Atom {
                rel: a.rel,
                target: match &a.target {
                    Target::Any => None,
                    Target::Class(c) => Some(classes.intern(c)),
                },
            },
            Formula::Not(g) => CompiledFormula::Not(Box::new(Self::compile(g, classes))),
            Formula::And(v) => CompiledFormula::And(v.iter().map(|g| Self::compile(g, classes)).collect()),
            Formula::Or(v) => CompiledFormula::Or(v.iter().map(|g| Self::compile(g, classes)).collect()),
        }
    }

    /// Evaluate for a placed object given its atom-byte lookup.
    #[inline]
    pub fn eval(&self, byte: &impl Fn(Option<usize>) -> u8) -> bool {
        match self {
            CompiledFormula::Atom { rel, target } => byte(*target) & rel.bit() != 0,
            CompiledFormula::Not(g) => !g.eval(byte),
            CompiledFormula::And(v) => v.iter().all(|g| g.eval(byte)),
            CompiledFormula::Or(v) => v.iter().any(|g| g.eval(byte)),
        }
    }
}

/// Per rule: who the subjects are and who breaks it.
#[derive(Debug, Clone, PartialEq)]
pub struct RuleReport {
    /// Rule name.
    pub name: String,
    /// Weight in the score (0 for hard rules).
    pub weight: f64,
    /// Whether the rule is hard.
    pub hard: bool,
    /// Placed objects of the subject class.
    pub subjects: usize,
    /// How many of them satisfy the rule.
    pub satisfied: usize,
    /// Ids of the subjects that break it, in scene order.
    pub violators: Vec<String>,
}

/// The result of evaluating a scene against a rule set.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// One report per rule, in rule-set order.
    pub rules: Vec<RuleReport>,
    /// §6 numerator: Σ over soft rules of weight × satisfied subjects.
    pub satisfied_weight: f64,
    /// §6 denominator: Σ over soft rules of weight × subjects.
    pub total_weight: f64,
    /// `satisfied_weight / total_weight`, or 1 when the denominator is 0.
    pub score: f64,
    /// Number of (object, hard rule) pairs that fail.
    pub hard_violations: usize,
    /// Ids of placed movable objects that are not on the grid.
    pub off_grid: Vec<String>,
}

impl Evaluation {
    /// Whether every hard rule holds for every subject.
    pub fn hard_ok(&self) -> bool {
        self.hard_violations == 0
    }
}

/// A scene prepared for repeated rule evaluation.
#[derive(Debug, Clone)]
pub struct Evaluator<'s> {
    scene: &'s Scene,
    classes: ClassIndex,
    atoms: ClassAtoms,
}

impl<'s> Evaluator<'s> {
    /// Prepare `scene`; `extra_classes` are classes named by rules that the
    /// scene may lack (interned so that atoms over them resolve).
    pub fn new(scene: &'s Scene, rules: &RuleSet, contact: Contact) -> Self {
        let mut classes = ClassIndex::of_scene(scene);
        for c in rules.classes() {
            classes.intern(&c);
        }
        let atoms = ClassAtoms::new(scene, &classes, contact);
        Evaluator { scene, classes, atoms }
    }

    /// The class index in use (scene classes first, then rule-only classes).
    pub fn classes(&self) -> &ClassIndex {
        &self.classes
    }

    /// The class-atom table.
    pub fn atoms(&self) -> &ClassAtoms {
        &self.atoms
    }

    /// Compile a formula against this evaluator's classes. Classes unknown to
    /// both scene and rule set compile to an empty class.
    pub fn compile(&self, f: &Formula) -> CompiledFormula {
        // Newly interned indices lie past the table, which reads them as a
        // class with no objects.
        CompiledFormula::compile(f, &mut self.classes.clone())
    }

    /// Whether placed object `obj` (index into `scene.objects`) satisfies `f`.
    /// Unplaced objects satisfy nothing.
    pub fn satisfies(&self, obj: usize, f: &CompiledFormula) -> bool {
        if self.atoms.byte(obj, None).is_none() {
            return false;
        }
        f.eval(&|t| self.atoms.byte(obj, t).unwrap_or(crate::relations::EMPTY_TARGET))
    }

    /// Evaluate every rule on every placed subject.
    pub fn evaluate(&self, rules: &RuleSet) -> Evaluation {
        let mut reports = Vec::with_capacity(rules.rules.len());
        let mut satisfied_weight = 0.0;
        let mut total_weight = 0.0;
        let mut hard_violations = 0;
        for rule in &rules.rules {
            let f = self.compile(&rule.formula);
            let subject = rule.subject();
            let mut subjects = 0;
            let mut satisfied = 0;
            let mut violators = Vec::new();
            for (i, o) in self.scene.objects.iter().enumerate() {
                if o.class != subject || !o.is_placed() {
                    continue;
                }
                subjects += 1;
                if self.satisfies(i, &f) {
                    satisfied += 1;
                } else {
                    violators.push(o.id.clone());
                }
            }
            let hard = rule.strength.is_hard();
            let weight = rule.strength.weight();
            if hard {
                hard_violations += subjects - satisfied;
            } else {
                satisfied_weight += weight * satisfied as f64;
                total_weight += weight * subjects as f64;
            }
            reports.push(RuleReport {
                name: rule.name.clone(),
                weight,
                hard,
                subjects,
                satisfied,
                violators,
            });
        }
        let score = if total_weight > 0.0 {
            satisfied_weight / total_weight
        } else {
            1.0
        };
        let off_grid = self
            .scene
            .objects
            .iter()
            .filter(|o| !o.fixed && !self.scene.on_grid(o))
            .map(|o| o.id.clone())
            .collect();
        Evaluation {
            rules: reports,
            satisfied_weight,
            total_weight,
            score,
            hard_violations,
            off_grid,
        }
    }
}

/// Evaluate `scene` against `rules` (the §6 score and per-rule reports).
///
/// ```
/// use rccpack::{eval::evaluate, relations::Contact, rules::parse_rules, scene::Scene};
/// let scene = Scene::from_json(r#"{"space":{"width":100,"height":100},"objects":[
///   {"class":"B","x":0,"y":50,"width":10,"height":10},
///   {"class":"R","x":0,"y":0,"width":10,"height":10}]}"#).unwrap();
/// let rules = parse_rules("rule b_north: DR_N(B, R)\n").unwrap();
/// assert_eq!(evaluate(&scene, &rules, Contact::Point).score, 1.0);
/// ```
pub fn evaluate(scene: &Scene, rules: &RuleSet, contact: Contact) -> Evaluation {
    Evaluator::new(scene, rules, contact).evaluate(rules)
}
