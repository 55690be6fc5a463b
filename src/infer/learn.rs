//! The learning pipeline: statements (given, or generated from the
//! templates, with priors when given), candidates, the null model's counts,
//! the posteriors and the order of the learned rules.

use super::checks::{check_demo_landmarks, check_demos, check_statements};
use super::slips::{Answered, Evidence, Slip, Weighed};
use super::{
    english, find_candidates, find_exceptions, templates, ClassStats, Exception, InferError,
    LearnParams, Learned, NullModel, Posterior, Provenance, StatementResult, StatementSource,
};
use crate::eval::CompiledRule;
use crate::relations::{ClassIndex, Contact};
use crate::rules::{RuleSet, Scope};
use crate::scene::Scene;
use crate::stop::Stop;
use std::borrow::Cow;

/// Learn rules from `demos`. `statements`: the statement set, or `None` for
/// the templates `params.templates` (docs/guide.md#learning) over the demonstrations'
/// classes and landmarks. Strengths and comments of given statements are
/// ignored.
pub fn learn(
    demos: &[Scene],
    statements: Option<&RuleSet>,
    params: &LearnParams,
) -> Result<Learned, InferError> {
    learn_with(demos, statements, params, &LearnOptions::default())
}

/// What [`learn_with`] takes besides the demonstrations, the statements
/// and the parameters: priors learned across tasks, and when to stop.
#[derive(Debug, Clone, Default)]
pub struct LearnOptions<'a> {
    /// Priors learned across tasks ([`crate::priors`]): a generated
    /// statement gets the prior of its kind (`π = 1 − prior`), a statement
    /// of a ruled-out kind is left out of the statements, and given
    /// statements keep `params.prior`. `None`: the parameters' prior.
    pub priors: Option<&'a crate::infer::priors::Priors>,
    /// When to give up: [`InferError::TimeLimit`] once the deadline
    /// passes, [`InferError::Cancelled`] once the flag is set (both checked
    /// per random scene of the null model).
    pub stop: Stop,
    /// Demonstrations the person answered as holding a slip (indices into
    /// the demonstrations): with a slip rate, the likeliest slip of each is
    /// a slip for sure (docs/guide.md#questions-about-suspects), so it no
    /// longer counts against the rules it breaks.
    pub slipped: &'a [usize],
    /// Demonstrations the person confirmed as meant, exceptions and all: no
    /// slip is looked for there, so a statement one of them breaks is no
    /// candidate.
    pub meant: &'a [usize],
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

/// [`learn`] with options: priors and when to stop ([`LearnOptions`]);
/// the one entry point every front end learns through.
pub fn learn_with(
    demos: &[Scene],
    statements: Option<&RuleSet>,
    params: &LearnParams,
    opts: &LearnOptions<'_>,
) -> Result<Learned, InferError> {
    let priors = opts.priors;
    params.validate()?;
    check_demos(demos)?;
    let (mut classes, class_count) = demo_class_index(demos);
    let st = statement_set(demos, statements, params, priors, &classes, class_count)?;
    let set = st.set.as_ref();
    let compiled = compile_statements(set, &mut classes);
    let subjects: Vec<usize> = compiled.iter().map(|r| r.subject).collect();
    debug_assert!(subjects.iter().all(|&c| c < classes.len()), "checked");

    let broken = find_candidates(demos, &classes, &compiled, params.contact);
    let exceptions = broken_once(demos, &classes, &compiled, params, opts, &broken);
    let weighed: Vec<bool> = (0..compiled.len())
        .map(|k| broken[k].is_none() || exceptions[k].is_some())
        .collect();
    let counts = chance_counts(demos, params, &classes, &compiled, &weighed, &opts.stop)?;
    let stats = class_stats(demos, &classes, params);
    // Scene-level statements (docs/guide.md#learning): q per random scene, n = d.
    let scene_epsilon = params.epsilon.unwrap_or(0.5 / params.samples as f64);
    let numbers = Numbers {
        demos: demos.len(),
        params,
        stats: &stats,
        subjects: &subjects,
        scene_epsilon,
        priors: st.priors.as_deref(),
    };
    let chances = chances(set, &broken, &exceptions, &counts, &numbers);
    let slips = find_slips(
        demos,
        &classes,
        &compiled,
        params,
        &broken,
        &exceptions,
        &chances,
        opts,
    );
    let mut results = weigh(set, &broken, &chances, &slips, &numbers);
    let order = rank(&mut results, params.contact);
    Ok(Learned {
        params: *params,
        demos: demos.len(),
        source: st.source,
        classes: stats
            .into_iter()
            .enumerate()
            .filter_map(|(c, s)| subjects.contains(&c).then_some(s))
            .collect(),
        scene_epsilon,
        statements: results,
        order,
        priors: priors.map(|p| crate::infer::priors::apply::summary(p, st.ruled_out)),
        slips,
    })
}

/// The demonstrations' classes, interned in order, and how many there are.
fn demo_class_index(demos: &[Scene]) -> (ClassIndex, usize) {
    let class_list = templates::demo_classes(demos);
    let mut classes = ClassIndex::default();
    for (c, _) in &class_list {
        classes.intern(c);
    }
    (classes, class_list.len())
}

/// `set`'s statements compiled against `classes`, every landmark interned
/// first so that each scene's atom table resolves it.
fn compile_statements(set: &RuleSet, classes: &mut ClassIndex) -> Vec<CompiledRule> {
    for id in set.landmarks() {
        classes.intern_landmark(&id);
    }
    set.rules
        .iter()
        .map(|r| CompiledRule::compile(r, &mut classes.clone()))
        .collect()
}

/// With a slip rate, per statement the one demonstration breaking it
/// (none answered as meant); `None` everywhere at rate 0.
fn broken_once(
    demos: &[Scene],
    classes: &ClassIndex,
    compiled: &[CompiledRule],
    params: &LearnParams,
    opts: &LearnOptions<'_>,
    broken: &[Option<Provenance>],
) -> Vec<Option<usize>> {
    if params.slip_rate <= 0.0 {
        return vec![None; compiled.len()];
    }
    find_exceptions(demos, classes, compiled, params.contact, broken)
        .into_iter()
        .map(|d| d.filter(|d| !opts.meant.contains(d)))
        .collect()
}

/// The statements learning weighs, with their priors.
struct Statements<'a> {
    set: Cow<'a, RuleSet>,
    source: StatementSource,
    /// Per statement, with priors.
    priors: Option<Vec<crate::infer::priors::StatementPrior>>,
    /// Generated statements the priors left out.
    ruled_out: Vec<crate::infer::priors::RuledOut>,
}

/// The given statements, checked, or the templates' over the
/// demonstrations (at most [`crate::limits::MAX_STATEMENTS`]); with priors,
/// each statement's prior and the generated ones of a ruled-out kind left
/// out.
fn statement_set<'a>(
    demos: &[Scene],
    statements: Option<&'a RuleSet>,
    params: &LearnParams,
    priors: Option<&crate::infer::priors::Priors>,
    classes: &ClassIndex,
    class_count: usize,
) -> Result<Statements<'a>, InferError> {
    let too_many = |statements: usize| InferError::TooManyStatements {
        statements,
        classes: class_count,
    };
    let st = match statements {
        Some(s) => {
            check_statements(s, classes)?;
            check_demo_landmarks(s, demos)?;
            Statements {
                set: Cow::Borrowed(s),
                source: StatementSource::Given,
                priors: priors.map(|_| crate::infer::priors::apply::given(s, params.prior)),
                ruled_out: Vec::new(),
            }
        }
        None => {
            let estimate = templates::estimate_set(demos, params.templates);
            if estimate > crate::limits::MAX_STATEMENTS {
                return Err(too_many(estimate));
            }
            let (set, origins) = templates::generate_with_origins(demos, params.templates);
            let (set, used, ruled_out) = match priors {
                Some(p) => {
                    let (set, used, out) =
                        crate::infer::priors::apply::generated(p, demos, set, &origins);
                    (set, Some(used), out)
                }
                None => (set, None, Vec::new()),
            };
            Statements {
                set: Cow::Owned(set),
                source: StatementSource::Templates,
                priors: used,
                ruled_out,
            }
        }
    };
    if st.set.rules.len() > crate::limits::MAX_STATEMENTS {
        return Err(too_many(st.set.rules.len()));
    }
    Ok(st)
}

/// Per weighed statement (candidates, and with slips the statements
/// broken in one demonstration only), in order: how many
/// subject objects (scene-level: random scenes) of the null model's
/// random scenes satisfy it.
fn chance_counts(
    demos: &[Scene],
    params: &LearnParams,
    classes: &ClassIndex,
    compiled: &[CompiledRule],
    weighed: &[bool],
    stop: &Stop,
) -> Result<Vec<u64>, InferError> {
    let cand: Vec<CompiledRule> = (0..compiled.len())
        .filter(|&k| weighed[k])
        .map(|k| compiled[k].clone())
        .collect();
    if cand.is_empty() {
        return Ok(Vec::new());
    }
    NullModel::new(demos, params.seed)?.count_until(
        params.samples,
        classes,
        &cand,
        params.contact,
        stop,
    )
}

/// `n_A` and `N_A` per class, and the floor `ε`.
fn class_stats(demos: &[Scene], classes: &ClassIndex, params: &LearnParams) -> Vec<ClassStats> {
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
    (0..classes.len())
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
        .collect()
}

/// What [`weigh`] needs besides the statements and the counts.
struct Numbers<'a> {
    demos: usize,
    params: &'a LearnParams,
    stats: &'a [ClassStats],
    /// Per statement, its subject class.
    subjects: &'a [usize],
    scene_epsilon: f64,
    priors: Option<&'a [crate::infer::priors::StatementPrior]>,
}

/// A weighed statement's chance numbers.
#[derive(Debug, Clone, Copy)]
struct Chance {
    /// Random subjects (scene-level: random scenes) satisfying it.
    satisfied: u64,
    q: f64,
    epsilon: f64,
    /// Subjects in the demonstrations (scene-level: demonstrations).
    n: u64,
    /// `π`, the prior that it is not meant.
    prior: f64,
}

/// Per statement, its chance numbers when weighed (candidates, and with
/// a slip rate the statements broken in one demonstration only).
fn chances(
    set: &RuleSet,
    broken: &[Option<Provenance>],
    exceptions: &[Option<usize>],
    counts: &[u64],
    x: &Numbers,
) -> Vec<Option<Chance>> {
    let params = x.params;
    let mut ci = 0;
    set.rules
        .iter()
        .enumerate()
        .map(|(k, rule)| {
            if broken[k].is_some() && exceptions[k].is_none() {
                return None;
            }
            let st = &x.stats[x.subjects[k]];
            let (n, trials, epsilon) = match rule.scope {
                Scope::Each => (st.demo_objects, st.sample_objects, st.epsilon),
                Scope::Scene(_) | Scope::Group => {
                    (x.demos as u64, params.samples as u64, x.scene_epsilon)
                }
            };
            let satisfied = counts[ci];
            ci += 1;
            Some(Chance {
                satisfied,
                q: satisfied as f64 / trials.max(1) as f64,
                epsilon,
                n,
                prior: x.priors.map_or(params.prior, |p| 1.0 - p[k].prior),
            })
        })
        .collect()
}

/// The slips among the demonstrations ([`super::slips`]), none at slip
/// rate 0.
#[allow(clippy::too_many_arguments)]
fn find_slips(
    demos: &[Scene],
    classes: &ClassIndex,
    compiled: &[CompiledRule],
    params: &LearnParams,
    broken: &[Option<Provenance>],
    exceptions: &[Option<usize>],
    chances: &[Option<Chance>],
    opts: &LearnOptions<'_>,
) -> Vec<Slip> {
    if params.slip_rate <= 0.0 {
        return Vec::new();
    }
    let weighed: Vec<Option<Weighed>> = chances
        .iter()
        .map(|c| {
            c.map(|c| Weighed {
                p: super::posterior::chance_p(c.q, c.epsilon),
                log10_posterior: Posterior::new(c.q, c.epsilon, c.n, c.prior).log10_posterior,
            })
        })
        .collect();
    let candidate: Vec<bool> = broken.iter().map(Option::is_none).collect();
    let evidence = Evidence {
        classes,
        rules: compiled,
        contact: params.contact,
        exceptions,
        candidate: &candidate,
        weighed: &weighed,
    };
    let answered = Answered {
        meant: opts.meant,
        slipped: opts.slipped,
    };
    super::slips::find(demos, &evidence, params.slip_rate, answered)
}

/// Every statement's result: for a candidate its chance rate, posterior
/// and whether it is learned at the cutoff; for a statement a slip
/// repairs, the same with the slip's chance mixed in.
fn weigh(
    set: &RuleSet,
    broken: &[Option<Provenance>],
    chances: &[Option<Chance>],
    slips: &[Slip],
    x: &Numbers,
) -> Vec<StatementResult> {
    let params = x.params;
    let mut results: Vec<StatementResult> = Vec::with_capacity(set.rules.len());
    for (k, rule) in set.rules.iter().enumerate() {
        let st = &x.stats[x.subjects[k]];
        let n = match rule.scope {
            Scope::Each => st.demo_objects,
            Scope::Scene(_) | Scope::Group => x.demos as u64,
        };
        let repaired_by = slips.iter().find(|s| s.repairs.contains(&k));
        let mut r = StatementResult {
            index: k,
            name: rule.name.clone(),
            formula: rule.formula.clone(),
            scope: rule.scope,
            subject: rule.subject().to_string(),
            candidate: broken[k].is_none(),
            broken_by: broken[k].clone(),
            exception: repaired_by.map(|s| Exception {
                demo: s.demonstration,
                objects: vec![s.object.clone()],
            }),
            n,
            satisfied: None,
            q: None,
            posterior: None,
            learned: false,
            implied_by: None,
            english: english::statement_reading(rule.scope, &rule.formula),
            prior: x.priors.map(|p| p[k].clone()),
        };
        let post = match (chances[k], repaired_by) {
            (Some(c), _) if r.candidate => Some(Posterior::new(c.q, c.epsilon, c.n, c.prior)),
            (Some(c), Some(s)) => Some(Posterior::repaired(
                c.q,
                c.epsilon,
                c.n,
                c.prior,
                s.log10_odds,
            )),
            _ => None,
        };
        if let (Some(post), Some(c)) = (post, chances[k]) {
            r.satisfied = Some(c.satisfied);
            r.q = Some(c.q);
            r.learned = post.learned(params.cutoff);
            r.posterior = Some(post);
        }
        results.push(r);
    }
    results
}

/// The learned rules, strongest first (smallest posterior; ties by
/// statement order), each marked with the first stronger one implying it.
fn rank(results: &mut [StatementResult], contact: Contact) -> Vec<usize> {
    let mut order: Vec<usize> = (0..results.len()).filter(|&k| results[k].learned).collect();
    let key = |k: usize| results[k].posterior.map_or(0.0, |p| p.log10_posterior);
    order.sort_by(|&a, &b| key(a).total_cmp(&key(b)).then(a.cmp(&b)));
    for (i, &k) in order.iter().enumerate() {
        let (rk, implied) = (&results[k], &order[..i]);
        let by = implied
            .iter()
            .find(|&&s| {
                let rs = &results[s];
                english::rule_implies((rs.scope, &rs.formula), (rk.scope, &rk.formula), contact)
            })
            .map(|&s| results[s].name.clone());
        results[k].implied_by = by;
    }
    order
}
