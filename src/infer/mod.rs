//! Learning rules from demonstrations (SPEC §7, thesis §3.2).
//!
//! # Background
//!
//! A statement that every demonstration satisfies (a *candidate*) may be one
//! of the demonstrator's rules or may hold by chance. The chance is measured
//! on random scenes made from the demonstrations (the null model): a rule
//! that random scenes rarely satisfy but every demonstrated object does is
//! unlikely to be an accident. Learned rules are the candidates whose
//! posterior probability of *not* being intended is below a cutoff.
//!
//! # Practical
//!
//! [`learn`] runs the whole pipeline: [`templates::generate`] (when no
//! statements are given), [`candidates::find_candidates`],
//! [`null_model::NullModel::count`] (parallel, deterministic for a seed) and
//! [`posterior::Posterior`] (log space). Truth values come from
//! [`crate::relations::ClassAtoms`] and [`crate::eval::CompiledFormula`], the
//! evaluator's own code. [`Learned::to_rcc`] writes the learned rules,
//! [`Learned::report_json`] every statement with its numbers.
//!
//! ```
//! use rccpack::{infer::{learn, LearnParams}, scene::scenes_from_json};
//! let demos = scenes_from_json(r#"[{"space":{"width":100,"height":100},"objects":[
//!   {"class":"B","x":0,"y":50,"width":10,"height":10},
//!   {"class":"R","x":0,"y":0,"width":10,"height":10}]}]"#).unwrap();
//! let params = LearnParams { samples: 50, ..LearnParams::default() };
//! let learned = learn(&demos, None, &params).unwrap();
//! assert!(learned.statements.iter().any(|s| s.name == "B_dr_n_R" && s.candidate));
//! ```

mod candidates;
pub(crate) mod english;
mod null_model;
mod posterior;
pub mod templates;

pub use candidates::{find_candidates, Provenance};
pub use english::{reading, statement_reading};
pub use null_model::NullModel;
pub use posterior::{chance_p, log10_posterior, Posterior, P_FLOOR};
pub use templates::Templates;

use crate::eval::CompiledRule;
use crate::relations::{ClassIndex, Contact};
use crate::rules::{
    print_formula, print_rule, Formula, Rule, RuleSet, Scope, Span, Strength, Target,
};
use crate::scene::{Scene, SceneError, Space};
use serde::Serialize;
use std::fmt::Write as _;

/// Why learning cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InferError {
    /// A parameter is out of its range.
    #[error("learning parameter `{param}` is {value}; expected {expected}")]
    BadParameter {
        /// The parameter's name, as in [`LearnParams`] (`samples`,
        /// `cutoff`, `prior`, `epsilon`).
        param: &'static str,
        /// The value given.
        value: String,
        /// The expected range, in words.
        expected: &'static str,
    },
    /// No demonstrations at all.
    #[error("no demonstrations: the demonstrations file holds an empty array; learning needs at least one complete scene")]
    NoDemonstrations,
    /// A demonstration breaks SPEC §1.
    #[error("demonstration [{demo}] is invalid: {error}")]
    InvalidDemonstration {
        /// Index of the demonstration.
        demo: usize,
        /// What is wrong.
        error: SceneError,
    },
    /// A demonstration has an unplaced object.
    #[error("demonstration [{demo}] is incomplete: object `{object}` has no position; every object of a demonstration must be placed")]
    IncompleteDemonstration {
        /// Index of the demonstration.
        demo: usize,
        /// Id of the unplaced object.
        object: String,
    },
    /// Demonstrations with different spaces.
    #[error("demonstration [{demo}] has space {found}, but demonstration [0] has space {expected}; all demonstrations must share one space")]
    SpaceMismatch {
        /// Index of the first demonstration that differs.
        demo: usize,
        /// Space of demonstration 0, as `x,y WxH`.
        expected: String,
        /// Space of demonstration `demo`.
        found: String,
    },
    /// A statement names a class that no demonstration has.
    #[error("rule `{rule}` names class `{class}`, which no demonstration has (classes: {known})")]
    UnknownClass {
        /// Rule name.
        rule: String,
        /// The unknown class.
        class: String,
        /// The demonstrations' classes, comma-separated.
        known: String,
        /// Source span of the offending atom, when the rule was parsed.
        span: Option<Span>,
    },
    /// A statement names a landmark that is not a fixed object of every
    /// demonstration.
    #[error("rule `{rule}` names landmark `@{id}`, which is not a fixed object of demonstration [{demo}]")]
    UnknownLandmark {
        /// Rule name.
        rule: String,
        /// The landmark id.
        id: String,
        /// The first demonstration without it.
        demo: usize,
        /// Source span of the offending atom, when the rule was parsed.
        span: Option<Span>,
    },
    /// A statement whose atoms have different subject classes.
    #[error("rule `{rule}` mixes subject classes `{first}` and `{other}`; every atom of a rule must have the same subject")]
    MixedSubjects {
        /// Rule name.
        rule: String,
        /// The first atom's subject.
        first: String,
        /// Another subject.
        other: String,
    },
    /// Two statements with one name.
    #[error("two statements are named `{name}`; names must be unique")]
    DuplicateName {
        /// The name.
        name: String,
    },
    /// The null model cannot place a demonstration's objects.
    #[error("the null model cannot place object `{object}` of demonstration [{demo}] at random: {reason}")]
    CannotPlace {
        /// Index of the demonstration.
        demo: usize,
        /// Id of the object.
        object: String,
        /// Why.
        reason: String,
    },
    /// Learning would weigh more statements than [`crate::limits::MAX_STATEMENTS`].
    #[error("learning would weigh {statements} statements ({classes} classes); expected at most {max} — use fewer classes or give the statements to weigh", max = crate::limits::MAX_STATEMENTS)]
    TooManyStatements {
        /// How many.
        statements: usize,
        /// Classes of the demonstrations.
        classes: usize,
    },
    /// The deadline passed while the null model drew its random scenes.
    #[error("the time limit struck while learning ({samples} random scenes to draw); nothing was learned — allow more time or fewer samples")]
    TimeLimit {
        /// The samples asked for.
        samples: usize,
    },
    /// Learning was cancelled ([`learn_cancellable`]: the studio's client
    /// left, or a newer request replaced it).
    #[error("learning was cancelled; nothing was learned")]
    Cancelled,
}

/// Learning parameters (SPEC §7; the defaults are the spec's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LearnParams {
    /// Random scenes in the null model, ≥ 1 (default 1000).
    pub samples: usize,
    /// Learn candidates with posterior below this, in (0, 1) (default 0.01).
    pub cutoff: f64,
    /// Prior that a statement is not intended, in (0, 1) (default 0.5).
    pub prior: f64,
    /// Floor of the chance rate, in (0, 1); `None`: `0.5 / N_A` per subject
    /// class.
    pub epsilon: Option<f64>,
    /// Seed of the null model (default 0).
    pub seed: u64,
    /// Contact mode of `EC` (default point).
    pub contact: Contact,
    /// The template set used when no statements are given (default: the
    /// second edition, §11.5).
    pub templates: Templates,
}

impl Default for LearnParams {
    fn default() -> Self {
        LearnParams {
            samples: 1000,
            cutoff: 0.01,
            prior: 0.5,
            epsilon: None,
            seed: 0,
            contact: Contact::Point,
            templates: Templates::Third,
        }
    }
}

impl LearnParams {
    /// Check every range; the error names the parameter.
    pub fn validate(&self) -> Result<(), InferError> {
        let open_unit = |param: &'static str, v: f64| {
            if v > 0.0 && v < 1.0 {
                Ok(())
            } else {
                Err(InferError::BadParameter {
                    param,
                    value: crate::limits::number(v),
                    expected: "a number strictly between 0 and 1",
                })
            }
        };
        if self.samples == 0 {
            return Err(InferError::BadParameter {
                param: "samples",
                value: "0".into(),
                expected: "a whole number of at least 1",
            });
        }
        if self.samples > crate::limits::MAX_SAMPLES {
            return Err(InferError::BadParameter {
                param: "samples",
                value: self.samples.to_string(),
                // `crate::limits::MAX_SAMPLES`, written out.
                expected: "a whole number of at most 1000000",
            });
        }
        open_unit("cutoff", self.cutoff)?;
        open_unit("prior", self.prior)?;
        if let Some(e) = self.epsilon {
            open_unit("epsilon", e)?;
        }
        Ok(())
    }
}

/// Per subject class: object counts and the floor `ε`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClassStats {
    /// Class name.
    pub class: String,
    /// `n_A`: objects of the class over all demonstrations.
    pub demo_objects: u64,
    /// `N_A`: objects of the class over all random scenes.
    pub sample_objects: u64,
    /// `ε` for statements about this class.
    pub epsilon: f64,
}

/// Everything computed about one statement.
#[derive(Debug, Clone, PartialEq)]
pub struct StatementResult {
    /// Index in the statement set.
    pub index: usize,
    /// Name.
    pub name: String,
    /// Formula.
    pub formula: Formula,
    /// Per object, or about the whole scene (§11.4).
    pub scope: Scope,
    /// Subject class.
    pub subject: String,
    /// Whether every demonstration satisfies it.
    pub candidate: bool,
    /// For a non-candidate, the first demonstration (and object) breaking
    /// it.
    pub broken_by: Option<Provenance>,
    /// `n`: subject objects over the demonstrations; for a scene-level
    /// statement the number of demonstrations `d` (§11.5).
    pub n: u64,
    /// Candidates only: subject objects of the random scenes satisfying it;
    /// for a scene-level statement the random scenes in which it holds.
    pub satisfied: Option<u64>,
    /// Candidates only: chance rate `q` (per object, or per scene for a
    /// scene-level statement).
    pub q: Option<f64>,
    /// Candidates only: `p`, `log10 L`, `log10 P`.
    pub posterior: Option<Posterior>,
    /// Whether it is learned.
    pub learned: bool,
    /// For a learned rule, a stronger learned rule that implies it.
    pub implied_by: Option<String>,
    /// One-line English reading.
    pub english: String,
    /// With priors ([`learn_with_priors`]): the statement's prior and
    /// where it came from; `None` without.
    pub prior: Option<crate::priors::StatementPrior>,
}

/// Where the statements came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StatementSource {
    /// A statement file.
    Given,
    /// The §8 templates.
    Templates,
}

/// The result of [`learn`].
#[derive(Debug, Clone, PartialEq)]
pub struct Learned {
    /// The parameters used.
    pub params: LearnParams,
    /// Number of demonstrations.
    pub demos: usize,
    /// Where the statements came from.
    pub source: StatementSource,
    /// Per class that is the subject of some statement, in class order.
    pub classes: Vec<ClassStats>,
    /// `ε_s` for scene-level statements: `0.5 / d_r`, or the fixed ε.
    pub scene_epsilon: f64,
    /// Every statement, in statement order.
    pub statements: Vec<StatementResult>,
    /// Indices into `statements` of the learned rules, strongest first
    /// (smallest posterior; ties by statement order).
    pub order: Vec<usize>,
    /// With priors: the library's summary and the statements left out.
    pub priors: Option<crate::priors::PriorsUsed>,
}

/// Learn rules from `demos`. `statements`: the statement set, or `None` for
/// the templates `params.templates` (§8, §11.5) over the demonstrations'
/// classes and landmarks. Strengths and comments of given statements are
/// ignored.
pub fn learn(
    demos: &[Scene],
    statements: Option<&RuleSet>,
    params: &LearnParams,
) -> Result<Learned, InferError> {
    learn_until(demos, statements, params, None)
}

/// [`learn`] that gives up with [`InferError::TimeLimit`] once `deadline`
/// passes (checked per random scene of the null model), so a command's
/// time limit covers learning too.
pub fn learn_until(
    demos: &[Scene],
    statements: Option<&RuleSet>,
    params: &LearnParams,
    deadline: Option<std::time::Instant>,
) -> Result<Learned, InferError> {
    learn_cancellable(demos, statements, params, deadline, None)
}

/// [`learn_until`] that also gives up with [`InferError::Cancelled`] once
/// `cancel` is set (checked per random scene of the null model).
pub fn learn_cancellable(
    demos: &[Scene],
    statements: Option<&RuleSet>,
    params: &LearnParams,
    deadline: Option<std::time::Instant>,
    cancel: Option<&std::sync::atomic::AtomicBool>,
) -> Result<Learned, InferError> {
    learn_with_priors(demos, statements, params, None, deadline, cancel)
}

/// Which of `set`'s statements every demonstration satisfies (the
/// candidates, as [`learn`] finds them), without the null model.
pub fn candidate_flags(
    demos: &[Scene],
    set: &RuleSet,
    contact: Contact,
) -> Result<Vec<bool>, InferError> {
    check_demos(demos)?;
    let mut classes = ClassIndex::default();
    for (c, _) in &templates::demo_classes(demos) {
        classes.intern(c);
    }
    for id in set.landmarks() {
        classes.intern_landmark(&id);
    }
    let compiled: Vec<CompiledRule> = set
        .rules
        .iter()
        .map(|r| CompiledRule::compile(r, &mut classes.clone()))
        .collect();
    Ok(find_candidates(demos, &classes, &compiled, contact)
        .into_iter()
        .map(|b| b.is_none())
        .collect())
}

/// [`learn_cancellable`] with priors learned across tasks
/// ([`crate::priors`]): a generated statement gets the prior of its kind
/// (`π = 1 − prior`), a statement of a ruled-out kind is left out of the
/// statements, and given statements keep `params.prior`. `None`: exactly
/// [`learn_cancellable`].
pub fn learn_with_priors(
    demos: &[Scene],
    statements: Option<&RuleSet>,
    params: &LearnParams,
    priors: Option<&crate::priors::Priors>,
    deadline: Option<std::time::Instant>,
    cancel: Option<&std::sync::atomic::AtomicBool>,
) -> Result<Learned, InferError> {
    params.validate()?;
    check_demos(demos)?;
    let class_list = templates::demo_classes(demos);
    let mut classes = ClassIndex::default();
    for (c, _) in &class_list {
        classes.intern(c);
    }
    let generated;
    let mut statement_priors: Option<Vec<crate::priors::StatementPrior>> = None;
    let mut ruled_out: Vec<crate::priors::RuledOut> = Vec::new();
    let (set, source) = match statements {
        Some(s) => {
            check_statements(s, &classes)?;
            check_demo_landmarks(s, demos)?;
            if priors.is_some() {
                statement_priors = Some(crate::priors::apply::given(s, params.prior));
            }
            (s, StatementSource::Given)
        }
        None => {
            let estimate = templates::estimate_set(demos, params.templates);
            if estimate > crate::limits::MAX_STATEMENTS {
                return Err(InferError::TooManyStatements {
                    statements: estimate,
                    classes: class_list.len(),
                });
            }
            let (set, origins) = templates::generate_with_origins(demos, params.templates);
            generated = match priors {
                Some(p) => {
                    let (set, used, out) = crate::priors::apply::generated(p, demos, set, &origins);
                    statement_priors = Some(used);
                    ruled_out = out;
                    set
                }
                None => set,
            };
            (&generated, StatementSource::Templates)
        }
    };
    if set.rules.len() > crate::limits::MAX_STATEMENTS {
        return Err(InferError::TooManyStatements {
            statements: set.rules.len(),
            classes: class_list.len(),
        });
    }
    // Every landmark is interned before compiling, so that each scene's
    // atom table resolves it.
    for id in set.landmarks() {
        classes.intern_landmark(&id);
    }
    let compiled: Vec<CompiledRule> = set
        .rules
        .iter()
        .map(|r| CompiledRule::compile(r, &mut classes.clone()))
        .collect();
    let subjects: Vec<usize> = compiled.iter().map(|r| r.subject).collect();
    debug_assert!(subjects.iter().all(|&c| c < classes.len()), "checked");

    let broken = find_candidates(demos, &classes, &compiled, params.contact);
    let cand: Vec<CompiledRule> = (0..compiled.len())
        .filter(|&k| broken[k].is_none())
        .map(|k| compiled[k].clone())
        .collect();
    let counts = if cand.is_empty() {
        Vec::new()
    } else {
        NullModel::new(demos, params.seed)?.count_until(
            params.samples,
            &classes,
            &cand,
            params.contact,
            deadline,
            cancel,
        )?
    };

    // n_A and N_A per class.
    let d = demos.len();
    let per_demo: Vec<Vec<u64>> = demos
        .iter()
        .map(|s| {
            let mut v = vec![0u64; classes.len()];
            for o in &s.objects {
                v[classes.get(&o.class).expect("interned")] += 1;
            }
            v
        })
        .collect();
    let full = (params.samples / d) as u64;
    let rest = params.samples % d;
    let stats: Vec<ClassStats> = (0..classes.len())
        .map(|c| {
            let n: u64 = per_demo.iter().map(|v| v[c]).sum();
            let big_n = full
                .saturating_mul(n)
                .saturating_add(per_demo[..rest].iter().map(|v| v[c]).sum::<u64>());
            ClassStats {
                class: classes.name(c).to_string(),
                demo_objects: n,
                sample_objects: big_n,
                epsilon: params.epsilon.unwrap_or(0.5 / big_n.max(1) as f64),
            }
        })
        .collect();
    // Scene-level statements (§11.5): q per random scene, n = d.
    let scene_epsilon = params.epsilon.unwrap_or(0.5 / params.samples as f64);

    let mut results: Vec<StatementResult> = Vec::with_capacity(set.rules.len());
    let mut ci = 0;
    for (k, rule) in set.rules.iter().enumerate() {
        let st = &stats[subjects[k]];
        let (n, trials, epsilon) = match rule.scope {
            Scope::Each => (st.demo_objects, st.sample_objects, st.epsilon),
            Scope::Scene(_) | Scope::Group => (d as u64, params.samples as u64, scene_epsilon),
        };
        let mut r = StatementResult {
            index: k,
            name: rule.name.clone(),
            formula: rule.formula.clone(),
            scope: rule.scope,
            subject: rule.subject().to_string(),
            candidate: broken[k].is_none(),
            broken_by: broken[k].clone(),
            n,
            satisfied: None,
            q: None,
            posterior: None,
            learned: false,
            implied_by: None,
            english: english::statement_reading(rule.scope, &rule.formula),
            prior: statement_priors.as_ref().map(|p| p[k].clone()),
        };
        if r.candidate {
            let sat = counts[ci];
            ci += 1;
            let q = sat as f64 / trials.max(1) as f64;
            let prior = statement_priors
                .as_ref()
                .map_or(params.prior, |p| 1.0 - p[k].prior);
            let post = Posterior::new(q, epsilon, r.n, prior);
            r.satisfied = Some(sat);
            r.q = Some(q);
            r.learned = post.learned(params.cutoff);
            r.posterior = Some(post);
        }
        results.push(r);
    }
    let mut order: Vec<usize> = (0..results.len()).filter(|&k| results[k].learned).collect();
    let key = |k: usize| results[k].posterior.map_or(0.0, |p| p.log10_posterior);
    order.sort_by(|&a, &b| key(a).total_cmp(&key(b)).then(a.cmp(&b)));
    for (i, &k) in order.iter().enumerate() {
        let (rk, implied) = (&results[k], &order[..i]);
        let by = implied
            .iter()
            .find(|&&s| {
                let rs = &results[s];
                english::rule_implies(
                    (rs.scope, &rs.formula),
                    (rk.scope, &rk.formula),
                    params.contact,
                )
            })
            .map(|&s| results[s].name.clone());
        results[k].implied_by = by;
    }
    let used: Vec<bool> = (0..classes.len()).map(|c| subjects.contains(&c)).collect();
    Ok(Learned {
        params: *params,
        demos: d,
        source,
        classes: stats
            .into_iter()
            .zip(used)
            .filter_map(|(s, u)| u.then_some(s))
            .collect(),
        scene_epsilon,
        statements: results,
        order,
        priors: priors.map(|p| crate::priors::apply::summary(p, ruled_out)),
    })
}

fn space_text(s: &Space) -> String {
    format!("{},{} {}x{}", s.x, s.y, s.width, s.height)
}

/// Demonstrations: at least one, each valid and complete, one shared space.
pub fn check_demos(demos: &[Scene]) -> Result<(), InferError> {
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
    }
    Ok(())
}

/// Statements: unique names, one subject per rule, only known classes.
pub fn check_statements(set: &RuleSet, classes: &ClassIndex) -> Result<(), InferError> {
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
/// object of every demonstration (SPEC §11.3: evaluating a rule whose
/// landmark the scene lacks is bad input).
pub(crate) fn check_demo_landmarks(set: &RuleSet, demos: &[Scene]) -> Result<(), InferError> {
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

/// `Q A: ` for a scene-level rule about `subject`, `""` for a per-object one.
pub fn scope_prefix(scope: Scope, subject: &str) -> String {
    match scope {
        Scope::Each | Scope::Group => String::new(),
        Scope::Scene(q) => format!("{q} {subject}: "),
    }
}

/// A statement as `.rcc` text after `rule NAME:`: the formula, preceded by
/// `Q A: ` for a scene-level statement.
pub fn statement_text(scope: Scope, formula: &Formula) -> String {
    format!(
        "{}{}",
        scope_prefix(scope, formula.subject()),
        print_formula(formula)
    )
}

/// Format a number for a comment: 4 significant digits.
fn short(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e4).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        let t = format!("{v:.digits$}");
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        }
    } else {
        format!("{v:.3e}")
    }
}

impl Learned {
    /// The learned rules, strongest first, each with `p P` and comments (the
    /// English reading, `q`, `n`, `log10 L`, and the stronger rule implying
    /// it, if any).
    pub fn rules(&self) -> RuleSet {
        RuleSet::new(
            self.order
                .iter()
                .map(|&k| {
                    let s = &self.statements[k];
                    let post = s.posterior.expect("learned rules are candidates");
                    let st = self
                        .classes
                        .iter()
                        .find(|c| c.class == s.subject)
                        .expect("subject stats");
                    let numbers = match s.scope {
                        Scope::Each => format!(
                            "q = {} ({} of {} {} objects in {} random scenes), n = {}, log10 L = {}",
                            short(s.q.unwrap_or(0.0)),
                            s.satisfied.unwrap_or(0),
                            st.sample_objects,
                            s.subject,
                            self.params.samples,
                            s.n,
                            short(post.log10_likelihood)
                        ),
                        Scope::Scene(_) | Scope::Group => format!(
                            "q = {} (holds in {} of {} random scenes), n = {} demonstrations, log10 L = {}",
                            short(s.q.unwrap_or(0.0)),
                            s.satisfied.unwrap_or(0),
                            self.params.samples,
                            s.n,
                            short(post.log10_likelihood)
                        ),
                    };
                    let mut comments = vec![s.english.clone(), numbers];
                    if let Some(by) = &s.implied_by {
                        comments.push(format!("implied by {by}"));
                    }
                    Rule {
                        name: s.name.clone(),
                        strength: Strength::P(post.written()),
                        scope: s.scope,
                        formula: s.formula.clone(),
                        comments,
                        origin: None,
                    }
                })
                .collect(),
        )
    }

    /// The `.rcc` text: a header comment with the parameters, then
    /// [`Learned::rules`].
    pub fn to_rcc(&self) -> String {
        let mut s = self.rcc_header();
        for r in &self.rules().rules {
            s.push_str(&print_rule(r));
        }
        s
    }

    /// The header comment of [`Learned::to_rcc`] (parameters, ε), ending in
    /// a blank line.
    pub fn rcc_header(&self) -> String {
        let p = &self.params;
        let mut s = String::new();
        let candidates = self.statements.iter().filter(|s| s.candidate).count();
        let _ = writeln!(
            s,
            "# learned by rccpack from {} demonstrations: {} of {} candidates out of {} statements ({})",
            self.demos,
            self.order.len(),
            candidates,
            self.statements.len(),
            match (self.source, self.params.templates) {
                (StatementSource::Given, _) => "given",
                (StatementSource::Templates, Templates::First) => "templates",
                (StatementSource::Templates, Templates::Second) => "templates, second edition",
                (StatementSource::Templates, Templates::Third) => "templates, third edition",
            }
        );
        let _ = writeln!(
            s,
            "# samples {}, seed {}, cutoff {}, prior {}, contact {}",
            p.samples, p.seed, p.cutoff, p.prior, p.contact
        );
        let mut eps: Vec<String> = self
            .classes
            .iter()
            .map(|c| format!("{} {}", c.class, short(c.epsilon)))
            .collect();
        if self.statements.iter().any(|s| s.scope.is_scene()) {
            eps.push(format!("scene-level {}", short(self.scene_epsilon)));
        }
        let _ = writeln!(s, "# epsilon: {}", eps.join(", "));
        if let Some(line) = self.priors_header() {
            let _ = writeln!(s, "{line}");
        }
        s.push('\n');
        s
    }

    /// The report: parameters, class counts and every statement.
    pub fn report(&self) -> Report {
        Report {
            parameters: ReportParams {
                samples: self.params.samples,
                cutoff: self.params.cutoff,
                prior: self.params.prior,
                epsilon: self.params.epsilon,
                seed: self.params.seed,
                contact: self.params.contact.to_string(),
                templates: match (self.source, self.params.templates) {
                    (StatementSource::Templates, Templates::Second) => Some("second".into()),
                    (StatementSource::Templates, Templates::Third) => Some("third".into()),
                    _ => None,
                },
            },
            demonstrations: self.demos,
            source: self.source,
            classes: self.classes.clone(),
            scene_epsilon: self
                .statements
                .iter()
                .any(|s| s.scope.is_scene())
                .then_some(self.scene_epsilon),
            priors: self.priors.clone(),
            statements: self
                .statements
                .iter()
                .map(|s| ReportStatement {
                    name: s.name.clone(),
                    formula: statement_text(s.scope, &s.formula),
                    scope: match s.scope {
                        Scope::Each => None,
                        Scope::Scene(q) => Some(q.to_string()),
                        Scope::Group => Some("group".to_string()),
                    },
                    subject: s.subject.clone(),
                    english: s.english.clone(),
                    candidate: s.candidate,
                    broken_by: s.broken_by.clone(),
                    n: s.n,
                    satisfied: s.satisfied,
                    q: s.q,
                    p: s.posterior.map(|p| p.p),
                    log10_likelihood: s.posterior.map(|p| p.log10_likelihood),
                    log10_posterior: s.posterior.map(|p| p.log10_posterior),
                    posterior: s.posterior.map(|p| p.written()),
                    learned: s.learned,
                    rank: self.order.iter().position(|&k| k == s.index),
                    implied_by: s.implied_by.clone(),
                    prior: s.prior.clone(),
                })
                .collect(),
        }
    }

    /// [`Learned::report`] as pretty JSON.
    pub fn report_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(&self.report()).expect("report serialises");
        s.push('\n');
        s
    }
}

/// The JSON report of `rccpack learn --report`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Parameters used.
    pub parameters: ReportParams,
    /// Number of demonstrations.
    pub demonstrations: usize,
    /// `given` or `templates`.
    pub source: StatementSource,
    /// Per subject class: `n_A`, `N_A`, `ε`.
    pub classes: Vec<ClassStats>,
    /// `ε_s` of the scene-level statements (§11.5); absent when there are
    /// none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene_epsilon: Option<f64>,
    /// With priors: the library's summary and the statements left out.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub priors: Option<crate::priors::PriorsUsed>,
    /// Every statement, in statement order.
    pub statements: Vec<ReportStatement>,
}

/// Parameters in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportParams {
    /// Random scenes.
    pub samples: usize,
    /// Cutoff.
    pub cutoff: f64,
    /// Prior.
    pub prior: f64,
    /// Fixed ε, or null for `0.5 / N_A` per class.
    pub epsilon: Option<f64>,
    /// Seed.
    pub seed: u64,
    /// `point` or `edge`.
    pub contact: String,
    /// `second` when the second-edition templates were used; absent for
    /// the first edition's templates and for given statements.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub templates: Option<String>,
}

/// One statement in the report. Chance numbers are null for non-candidates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportStatement {
    /// Name.
    pub name: String,
    /// The statement as `.rcc` text after `rule NAME:` (with `Q A: ` for a
    /// scene-level statement).
    pub formula: String,
    /// The subject quantifier of a scene-level statement (`some`, `no`,
    /// `at least 2`, …); absent for a per-object statement.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scope: Option<String>,
    /// Subject class.
    pub subject: String,
    /// English reading.
    pub english: String,
    /// Satisfied by every demonstration.
    pub candidate: bool,
    /// First demonstration and object breaking it (non-candidates).
    pub broken_by: Option<Provenance>,
    /// `n`: subject objects over the demonstrations (scene-level: the
    /// number of demonstrations).
    pub n: u64,
    /// Subject objects of the random scenes that satisfy it (scene-level:
    /// random scenes in which it holds).
    pub satisfied: Option<u64>,
    /// Chance rate `q`.
    pub q: Option<f64>,
    /// `p = max(ε, q)` (scene-level: `max(ε_s, q)`).
    pub p: Option<f64>,
    /// `log10 L`.
    pub log10_likelihood: Option<f64>,
    /// `log10 P`.
    pub log10_posterior: Option<f64>,
    /// `P` as written (floored at 1e-300).
    pub posterior: Option<f64>,
    /// Learned at the cutoff.
    pub learned: bool,
    /// Position among learned rules (0 = strongest).
    pub rank: Option<usize>,
    /// A stronger learned rule implying this one.
    pub implied_by: Option<String>,
    /// With priors: the statement's prior and its source.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prior: Option<crate::priors::StatementPrior>,
}
