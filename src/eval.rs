//! The evaluator: which placed object satisfies which rule, hard-rule
//! violations, the grid check and the context score.
//!
//! This is the *one* implementation of docs/language.md#class-rules and docs/language.md#the-score. Learning reports, the
//! solver's re-check, the studio and every test get their truth values and
//! scores from here.
//!
//! Practical: [`Evaluator::new`] builds a [`ClassAtoms`] table once
//! (`O(n²)` pairs), after which every (object, rule) value is a walk over a
//! compiled formula with one table lookup per atom.

use crate::relations::{ClassAtoms, ClassIndex, Contact, Quant, Relation};
use crate::rules::{Formula, Rule, RuleSet, Scope, ShapeKind, Target};
use crate::scene::Scene;
use crate::shapes::{self, ShapeCheck};
use serde::Serialize;

/// A compiled atom's target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompiledTarget {
    /// A class index (possibly past the table: a class with no objects).
    Class(usize),
    /// `*`.
    Any,
    /// A landmark: index into [`ClassIndex::landmarks`].
    Landmark(usize),
}

/// A formula with class names and landmark ids resolved to indices.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CompiledFormula {
    /// Atom: relation, quantifier and target.
    Atom {
        /// The relation.
        rel: Relation,
        /// The target quantifier.
        quant: Quant,
        /// The target.
        target: CompiledTarget,
    },
    /// A group statement's shape (decided for the whole class by
    /// `CompiledRule::group_check`; false read per object).
    Shape(ShapeKind),
    /// `turned(A)`: the object lies turned (and is not square).
    Turned,
    /// Negation.
    Not(Box<CompiledFormula>),
    /// Conjunction.
    And(Vec<CompiledFormula>),
    /// Disjunction.
    Or(Vec<CompiledFormula>),
}

impl CompiledFormula {
    /// Resolve class names and landmark ids through `classes`, interning
    /// unknown ones (a class with no object: the default quantifier decides,
    /// `DR` atoms hold vacuously, the others fail; likewise a landmark the
    /// scene lacks).
    pub fn compile(f: &Formula, classes: &mut ClassIndex) -> Self {
        match f {
            Formula::Atom(a) => CompiledFormula::Atom {
                rel: a.rel,
                quant: a.quant,
                target: match &a.target {
                    Target::Any => CompiledTarget::Any,
                    Target::Class(c) => CompiledTarget::Class(classes.intern(c)),
                    Target::Landmark(id) => CompiledTarget::Landmark(classes.intern_landmark(id)),
                },
            },
            Formula::Shape(sh) => {
                classes.intern(&sh.class);
                CompiledFormula::Shape(sh.kind)
            }
            Formula::Turned(c) => {
                classes.intern(c);
                CompiledFormula::Turned
            }
            Formula::Not(g) => CompiledFormula::Not(Box::new(Self::compile(g, classes))),
            Formula::And(v) => {
                CompiledFormula::And(v.iter().map(|g| Self::compile(g, classes)).collect())
            }
            Formula::Or(v) => {
                CompiledFormula::Or(v.iter().map(|g| Self::compile(g, classes)).collect())
            }
        }
    }

    /// Whether placed object `obj` satisfies the formula in the scene of
    /// `atoms` (false when `obj` is unplaced).
    #[inline]
    pub fn eval(&self, atoms: &ClassAtoms, obj: usize) -> bool {
        match self {
            CompiledFormula::Atom { rel, quant, target } => {
                let count = match *target {
                    CompiledTarget::Class(t) => atoms.count(obj, Some(t)).copied(),
                    CompiledTarget::Any => atoms.count(obj, None).copied(),
                    CompiledTarget::Landmark(l) => atoms.landmark_count(obj, l),
                };
                count.is_some_and(|c| c.holds(*rel, *quant))
            }
            CompiledFormula::Shape(_) => false,
            CompiledFormula::Turned => atoms.lies_turned(obj),
            CompiledFormula::Not(g) => atoms.is_placed(obj) && !g.eval(atoms, obj),
            CompiledFormula::And(v) => atoms.is_placed(obj) && v.iter().all(|g| g.eval(atoms, obj)),
            CompiledFormula::Or(v) => v.iter().any(|g| g.eval(atoms, obj)),
        }
    }
}

/// A rule compiled for evaluation: scope, subject class index, formula.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompiledRule {
    /// Per object or scene-level.
    pub scope: Scope,
    /// Subject class index (possibly past the table: no objects).
    pub subject: usize,
    /// The formula.
    pub formula: CompiledFormula,
}

impl CompiledRule {
    /// Compile `rule` (its scope, subject and formula) through `classes`.
    pub fn compile(rule: &Rule, classes: &mut ClassIndex) -> Self {
        Self::compile_parts(rule.scope, &rule.formula, classes)
    }

    /// Compile a scope and formula (a statement without name or strength).
    pub(crate) fn compile_parts(scope: Scope, f: &Formula, classes: &mut ClassIndex) -> Self {
        let subject = classes.intern(f.subject());
        CompiledRule {
            scope,
            subject,
            formula: CompiledFormula::compile(f, classes),
        }
    }

    /// How many placed subject objects satisfy the formula, and how many
    /// placed subject objects there are: `(c, m)`.
    pub fn count(&self, atoms: &ClassAtoms, objects: usize) -> (u32, u32) {
        let (mut c, mut m) = (0u32, 0u32);
        for o in 0..objects {
            if atoms.is_placed(o) && atoms.class_of(o) == self.subject {
                m += 1;
                if self.formula.eval(atoms, o) {
                    c += 1;
                }
            }
        }
        (c, m)
    }

    /// For a scene-level rule, whether it holds in the scene of `atoms`
    /// (which has `objects` objects); for a per-object rule, whether every
    /// placed subject satisfies it.
    pub(crate) fn scene_holds(&self, atoms: &ClassAtoms, objects: usize) -> bool {
        if let Some((check, neg)) = self.group_check(atoms, objects) {
            return check.holds != neg;
        }
        let (c, m) = self.count(atoms, objects);
        match self.scope {
            Scope::Each => c == m,
            Scope::Scene(q) => q.holds(c, m),
            Scope::Group => false,
        }
    }

    /// The shape of a group rule and whether it is negated.
    pub(crate) fn group_shape(&self) -> Option<(ShapeKind, bool)> {
        let mut f = &self.formula;
        let mut neg = false;
        loop {
            match f {
                CompiledFormula::Shape(k) => return Some((*k, neg)),
                CompiledFormula::Not(g) => {
                    neg = !neg;
                    f = g;
                }
                _ => return None,
            }
        }
    }

    /// For a group rule: the verdict of [`shapes::check`] on the placed
    /// subject objects (indices into the scene's objects), and whether the
    /// rule is the shape's negation.
    pub(crate) fn group_check(
        &self,
        atoms: &ClassAtoms,
        objects: usize,
    ) -> Option<(ShapeCheck, bool)> {
        let (kind, neg) = self.group_shape()?;
        let (ids, rects): (Vec<usize>, Vec<_>) = (0..objects)
            .filter(|&o| atoms.is_placed(o) && atoms.class_of(o) == self.subject)
            .filter_map(|o| atoms.rect(o).map(|r| (o, r)))
            .unzip();
        let mut check = shapes::check(kind, &rects, atoms.contact());
        for c in &mut check.components {
            for i in c.iter_mut() {
                *i = ids[*i];
            }
        }
        Some((check, neg))
    }
}

/// Per rule: who the subjects are and who breaks it.
///
/// Serialises as `{name, weight, hard, satisfied, subjects, violators}`: a
/// stable format read by scripts (`rccpack score --json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
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
    /// Ids of the subjects that break it, in scene order. For a scene-level
    /// rule (docs/language.md#scene-rules): the objects that satisfy the formula when a `no` or
    /// `at most` rule fails, none otherwise.
    pub violators: Vec<String>,
    /// Only for a scene-level rule: its quantifier and counts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene: Option<SceneRuleReport>,
    /// Only for a group statement: the shape and the groups found.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub group: Option<GroupRuleReport>,
}

/// The group part of a [`RuleReport`]; serialised as `{shape, negated,
/// objects, groups, bbox?}`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct GroupRuleReport {
    /// `group`, `row`, `column` or `block`.
    pub shape: String,
    /// Whether the rule is the shape's negation (`!column(R)`).
    pub negated: bool,
    /// Placed subject objects.
    pub objects: usize,
    /// The groups under the shape's adjacency, largest first, as object
    /// ids in scene order.
    pub groups: Vec<Vec<String>>,
    /// For a block: the bounding box `[width, height]` and whether it fits.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bbox: Option<BlockBox>,
}

/// A block's bounding box in a [`GroupRuleReport`].
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct BlockBox {
    /// Width of the class's bounding box.
    pub width: i64,
    /// Height of the class's bounding box.
    pub height: i64,
    /// Whether it fits one of the block's boxes (see [`shapes::block_boxes`]).
    pub fits: bool,
}

/// The scene-level part of a [`RuleReport`] (docs/language.md#scene-rules); serialised as
/// `{quantifier, satisfying, objects}`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct SceneRuleReport {
    /// The subject quantifier as written (`some`, `at least 2`, ...).
    pub quantifier: String,
    /// Placed subject objects that satisfy the formula (`c`).
    pub satisfying: usize,
    /// Placed subject objects (`m`).
    pub objects: usize,
}

/// The result of evaluating a scene against a rule set.
///
/// Serialises as `{score, satisfied_weight, total_weight, hard_violations,
/// off_grid, rules}`: the stable format of `rccpack score --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluation {
    /// `satisfied_weight / total_weight`, or 1 when the denominator is 0.
    pub score: f64,
    /// numerator: Σ over soft rules of weight × satisfied subjects.
    pub satisfied_weight: f64,
    /// denominator: Σ over soft rules of weight × subjects.
    pub total_weight: f64,
    /// Number of (object, hard rule) pairs that fail (a failing hard
    /// scene-level rule counts once).
    pub hard_violations: usize,
    /// Ids of placed movable objects that are not on the grid.
    pub off_grid: Vec<String>,
    /// One report per rule, in rule-set order.
    pub rules: Vec<RuleReport>,
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
    /// Prepare `scene`; classes named by `rules` that the scene lacks are
    /// interned (they have no objects), and so are the rules' landmarks.
    pub fn new(scene: &'s Scene, rules: &RuleSet, contact: Contact) -> Self {
        let mut classes = ClassIndex::of_scene(scene);
        for c in rules.classes() {
            classes.intern(&c);
        }
        for l in rules.landmarks() {
            classes.intern_landmark(&l);
        }
        let atoms = ClassAtoms::new(scene, &classes, contact);
        Evaluator {
            scene,
            classes,
            atoms,
        }
    }

    /// The class index in use (scene classes first, then rule-only classes).
    pub fn classes(&self) -> &ClassIndex {
        &self.classes
    }

    /// The class-atom table.
    pub fn atoms(&self) -> &ClassAtoms {
        &self.atoms
    }

    /// Compile a formula against this evaluator's classes. Classes and
    /// landmarks unknown to both scene and rule set compile to empty targets.
    pub fn compile(&self, f: &Formula) -> CompiledFormula {
        // Newly interned indices lie past the table, which reads them as
        // targets with no objects.
        CompiledFormula::compile(f, &mut self.classes.clone())
    }

    /// Whether placed object `obj` (index into `scene.objects`) satisfies `f`.
    /// Unplaced objects satisfy nothing.
    pub fn satisfies(&self, obj: usize, f: &CompiledFormula) -> bool {
        f.eval(&self.atoms, obj)
    }

    /// Evaluate one rule: its report, its numerator and denominator
    /// terms, and its number of hard violations.
    pub fn evaluate_rule(&self, rule: &Rule) -> RuleReport {
        if rule.is_group() {
            return self.evaluate_group(rule);
        }
        let f = self.compile(&rule.formula);
        let subject = rule.subject();
        let mut subjects = 0;
        let mut satisfied = 0;
        let mut violators = Vec::new();
        let mut holders = Vec::new();
        for (i, o) in self.scene.objects.iter().enumerate() {
            if o.class != subject || !o.is_placed() {
                continue;
            }
            subjects += 1;
            if self.satisfies(i, &f) {
                satisfied += 1;
                holders.push(o.id.clone());
            } else {
                violators.push(o.id.clone());
            }
        }
        let hard = rule.strength.is_hard();
        let weight = rule.strength.weight();
        match rule.scope {
            Scope::Each => RuleReport {
                name: rule.name.clone(),
                weight,
                hard,
                subjects,
                satisfied,
                violators,
                scene: None,
                group: None,
            },
            Scope::Group => self.evaluate_group(rule),
            Scope::Scene(q) => {
                let c = u32::try_from(satisfied).unwrap_or(u32::MAX);
                let m = u32::try_from(subjects).unwrap_or(u32::MAX);
                let holds = q.holds(c, m);
                let violators = if !holds && matches!(q, Quant::No | Quant::AtMost(_)) {
                    holders
                } else {
                    Vec::new()
                };
                RuleReport {
                    name: rule.name.clone(),
                    weight,
                    hard,
                    subjects: 1,
                    satisfied: usize::from(holds),
                    violators,
                    scene: Some(SceneRuleReport {
                        quantifier: q.to_string(),
                        satisfying: satisfied,
                        objects: subjects,
                    }),
                    group: None,
                }
            }
        }
    }

    /// A group statement's report: one term; the violators are the
    /// objects off the largest group when the shape is asked and fails.
    fn evaluate_group(&self, rule: &Rule) -> RuleReport {
        let compiled = CompiledRule::compile(rule, &mut self.classes.clone());
        let name = rule.name.clone();
        let (weight, hard) = (rule.strength.weight(), rule.strength.is_hard());
        let Some((check, neg)) = compiled.group_check(&self.atoms, self.scene.objects.len()) else {
            // Not a shape formula (a group scope built in code around
            // something else): it never holds.
            return RuleReport {
                name,
                weight,
                hard,
                subjects: 1,
                satisfied: 0,
                violators: Vec::new(),
                scene: None,
                group: None,
            };
        };
        let holds = check.holds != neg;
        let id = |i: usize| self.scene.objects[i].id.clone();
        let violators = if holds || neg {
            Vec::new()
        } else {
            check.off_main().into_iter().map(id).collect()
        };
        let (kind, _) = compiled.group_shape().expect("a group rule");
        RuleReport {
            name,
            weight,
            hard,
            subjects: 1,
            satisfied: usize::from(holds),
            violators,
            scene: None,
            group: Some(GroupRuleReport {
                shape: kind.name().to_string(),
                negated: neg,
                objects: check.components.iter().map(Vec::len).sum(),
                groups: check
                    .components
                    .iter()
                    .map(|c| c.iter().map(|&i| id(i)).collect())
                    .collect(),
                bbox: check.bbox.map(|((width, height), fits)| BlockBox {
                    width,
                    height,
                    fits,
                }),
            }),
        }
    }

    /// Evaluate every rule on every placed subject.
    pub fn evaluate(&self, rules: &RuleSet) -> Evaluation {
        let mut reports = Vec::with_capacity(rules.rules.len());
        let mut satisfied_weight = 0.0;
        let mut total_weight = 0.0;
        let mut hard_violations = 0;
        for rule in &rules.rules {
            let r = self.evaluate_rule(rule);
            if r.hard {
                hard_violations += r.subjects - r.satisfied;
            } else {
                satisfied_weight += r.weight * r.satisfied as f64;
                total_weight += r.weight * r.subjects as f64;
            }
            reports.push(r);
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

/// Evaluate `scene` against `rules` (the score and per-rule reports).
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
