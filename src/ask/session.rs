//! The question loop (SPEC §13), without I/O: which rule to ask about next,
//! and what an answer does. The command line and the studio drive it and
//! save what it returns.
//!
//! # Order of questions
//!
//! The held rules are visited **weakest evidence first** (the learned rule
//! whose posterior is closest to the cutoff first, i.e. [`Learned::order`]
//! reversed): a habit of a few demonstrations has less evidence than a rule
//! the person kept every time, so with a small `--max-questions` budget the
//! questions go where doubt is largest. A rule is skipped, without a
//! question, when
//!
//! - it is confirmed already;
//! - another held rule implies it on every scene (the syntactic test
//!   [`crate::infer::english::rule_implies`], no solve), unless the two
//!   imply each other (then the first in the order stands for both);
//! - no probe exists: the engine proves that on the problem's objects the
//!   other held rules imply it ([`ProbeChecker`]: one engine per scan, one
//!   solve under assumptions per rule; only for the rule asked about is the
//!   probe to show searched, by [`find_probe`]).
//!
//! What the engine decides — a probe, a proof that none exists, a proof
//! that one rule alone implies another — depends only on the problem and
//! the held rules, so it is kept while they stay the same (a rejected probe
//! confirms a rule, it changes no held rule) and dropped when learning is
//! redone. Every solve has a node budget (deterministic) besides the time
//! limit (a safety net); a check its budget stops is tried again at the
//! next question. So the next question depends only on the demonstrations,
//! the held rules and the confirmed ones, and a resumed session asks what
//! an uninterrupted one would (tested), on any machine — unless a check
//! reaches its budget: how far a stopped search gets depends on what the
//! engine learned from earlier solves. When no rule has a probe that keeps
//! all the others, groups of rules that follow from one another are asked
//! about as one ([`Asker::next_question`]).
//!
//! # Reuse (issue 20: questions at the speed of a conversation)
//!
//! With [`AskOptions::reuse`] (the default) most checks need no solve:
//!
//! - **a pool of layouts**: every layout a check or a probe search finds is
//!   a layout of the problem, kept for the whole session (the problem
//!   never changes). A check "does `k` have a probe when these rules may
//!   break" is answered yes by any pool layout that breaks `k` and keeps
//!   every premise, and "does `a` alone imply `b`" no by any that keeps
//!   `a` and breaks `b` — the evaluator decides, so the answer is sound;
//! - **proofs for fewer premises**: a proof that premises `P` imply `k`
//!   (statement texts) answers every later check of `k` whose premises
//!   include `P`, also after learning is redone; so does a premise that
//!   alone implies `k` (syntactically or proven);
//! - **implications between two rules** (decided ones) outlive a
//!   relearning: they depend only on the two statements and the problem;
//! - **a short first try**: a check gets `FIRST_TRY_NODES` nodes on the
//!   scan's checker, and the full budget on a fresh checker of the
//!   premises and the rule only when they do not decide it (a long-lived
//!   engine can slow down by orders of magnitude).
//!
//! A rule is still called implied only when the engine proved it. The
//! decided answers are the same as without reuse; only a check that
//! reaches its budget can come out differently (decided where it was not).
//! The bench (`cargo bench --bench ask -- --compare`) and
//! `tests/ask_tasks.rs` check that the questions stay the same.

use super::budget::{Meter, QuestionBudget};
use super::edit::{Edit, EditSearch};
use super::probe::{search_probe, Checked, Probe, ProbeChecker, ProbeOptions, ProbeOutcome};
use crate::infer::english::rule_implies;
use crate::infer::{InferError, LearnParams, Learned};
use crate::resemblance::ResemblanceTarget;
use crate::rules::{print_rule, RuleSet};
use crate::scene::Scene;
use crate::synth::SynthError;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeSet, HashMap};

/// The comment line that marks a confirmed rule in `learned.rcc`.
pub const CONFIRMED: &str = "confirmed";

/// `answers.json` is not an answers file: the field path and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("at `{path}`: {message}")]
pub struct AnswersFileError {
    /// Field path such as `answers[2].rule`.
    pub path: String,
    /// What is wrong, with line and column.
    pub message: String,
}

/// Why the question loop cannot go on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AskError {
    /// Learning failed (bad demonstrations or statements).
    #[error(transparent)]
    Learn(#[from] InferError),
    /// The problem cannot be used for probes.
    #[error("the problem cannot be used for probes: {0}")]
    Synth(#[from] SynthError),
    /// `answers.json` does not fit the task.
    #[error("answers[{index}]: {why}")]
    BadAnswer {
        /// Index of the answer.
        index: usize,
        /// What is wrong.
        why: String,
    },
    /// An answer for a question that is not the one asked.
    #[error("no question about rule `{0}` is open")]
    NotAsked(String),
}

/// One answered question, as kept in `answers.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Answer {
    /// The probed rule's name.
    pub rule: String,
    /// Its `.rcc` text (after `rule NAME:`).
    pub statement: String,
    /// Its English reading.
    pub english: String,
    /// Whether the person found the probe acceptable.
    pub accepted: bool,
    /// For an accepted probe: its index in `demos.json` (it is that
    /// demonstration).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub demo: Option<usize>,
    /// Objects breaking the rule in the probe.
    pub broken: Vec<String>,
    /// The probe layout.
    pub probe: Scene,
    /// When the probe was a demonstration with a few objects moved: which
    /// one, and what moved from where.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edit: Option<Edit>,
}

/// The `answers.json` file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnswersFile {
    /// Every answer, in the order given.
    pub answers: Vec<Answer>,
}

impl AnswersFile {
    /// Parse `answers.json`; the error names the JSON field (e.g. `answers[0].rule`).
    pub fn from_json(text: &str) -> Result<AnswersFile, AnswersFileError> {
        let de = &mut serde_json::Deserializer::from_str(text);
        serde_path_to_error::deserialize(de).map_err(|e| AnswersFileError {
            path: e.path().to_string(),
            message: e.inner().to_string(),
        })
    }

    /// Pretty JSON, ending in a newline.
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).expect("answers serialise");
        text.push('\n');
        text
    }
}

/// A question: is this probe acceptable?
#[derive(Debug, Clone, PartialEq)]
pub struct Question {
    /// The rule it asks about.
    pub rule: String,
    /// The rule's `.rcc` text (after `rule NAME:`).
    pub statement: String,
    /// The rule's English reading.
    pub english: String,
    /// The probe.
    pub probe: Probe,
    /// Other held rules the probe breaks too: rules of a group that imply
    /// one another (see [`Asker::next_question`]); usually empty.
    pub also_broken: Vec<String>,
}

/// Why a held rule was not asked about ([`Asker::unasked`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unasked {
    /// The other held rules imply it on the problem (proven, or on every
    /// scene); with `edits_tried`, no demonstration with one or two objects
    /// moved breaks it either.
    Implied {
        /// The demonstrations' edits were searched too.
        edits_tried: bool,
    },
    /// The question budget (or a limit) stopped its check or probe search
    /// before it decided.
    Deferred,
}

impl std::fmt::Display for Unasked {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Unasked::Implied { edits_tried: true } => {
                "follows from the others on the problem and on every demonstration edit tried"
            }
            Unasked::Implied { edits_tried: false } => "follows from the others on the problem",
            Unasked::Deferred => "the question budget did not decide it",
        })
    }
}

/// How far the questions have come (counts of a session).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Tally {
    /// Questions answered (over all runs).
    pub asked: usize,
    /// Rules dropped by accepted probes.
    pub dropped: usize,
    /// Rules confirmed by rejected probes.
    pub confirmed: usize,
    /// Held rules not asked because the others imply them.
    pub implied: usize,
    /// Held rules deferred: the question budget (or a limit) stopped their
    /// check or probe search before it decided them.
    pub unknown: usize,
    /// Held rules now.
    pub held: usize,
}

/// Settings of the loop.
#[derive(Debug, Clone)]
pub struct AskOptions {
    /// Learning parameters (as for `learn`/`run`).
    pub learn: LearnParams,
    /// Probe search settings (`like` is filled from the demonstrations when
    /// `resemble` is on).
    pub probe: ProbeOptions,
    /// Probes resemble the demonstrations (SPEC §12).
    pub resemble: bool,
    /// Reuse what earlier checks found (on by default): a layout a solve
    /// found answers later checks it decides (evaluated, no solve), a
    /// proof that some rules imply a rule answers later checks with more
    /// premises, and decided answers outlive a relearning. Off, every
    /// check is a solve, as before (for comparisons and tests); the
    /// questions are the same either way unless a check reaches its
    /// budget.
    pub reuse: bool,
    /// How much search one question may cost (see [`QuestionBudget`]).
    pub budget: QuestionBudget,
    /// Look for probes that are a demonstration with one or two objects
    /// moved before searching the problem (on by default).
    pub edits: bool,
    /// Priors learned across tasks ([`crate::priors`]) for every learning
    /// run of the session; `None`: the uniform prior.
    pub priors: Option<std::sync::Arc<crate::priors::Priors>>,
}

impl Default for AskOptions {
    fn default() -> Self {
        AskOptions {
            learn: LearnParams::default(),
            probe: ProbeOptions::default(),
            resemble: true,
            reuse: true,
            budget: QuestionBudget::default(),
            edits: true,
            priors: None,
        }
    }
}

/// How a scan for the next question ended.
enum Scan {
    Question(Box<Question>),
    /// The question's budget ran out before any rule had a probe; the rule
    /// that used it up is decided or deferred, so the next scan goes on.
    OutOfBudget,
    Done,
}

#[derive(Debug, Clone)]
enum Known {
    Probe(Probe),
    Implied,
    Unknown,
}

/// With `reuse`, a check first gets this many search nodes on the
/// checker of the scan, which has learned from every earlier solve; when
/// they do not decide it, a fresh checker holding only the premises and
/// the rule (a smaller model) gets the full budget
/// ([`ProbeOptions::check_nodes`]). The long-lived engine can slow down a
/// lot: on the shelf one proof ran 10 s (7 524 nodes, stopped by the time
/// limit) on it and took 296 nodes (49 ms) on a fresh engine, while
/// building one costs 10–30 ms; at cutoff 0.3 the smaller model halved the
/// session (86 → 47 s). Node counts, so still deterministic.
const FIRST_TRY_NODES: u64 = 1_000;

/// At most this many layouts are kept in the pool (a pool check costs a
/// look at every layout's row).
const MAX_POOL: usize = 4096;

/// Layouts of the problem (see [`Asker::settled`]).
#[derive(Debug, Clone, Default)]
struct Pool {
    scenes: Vec<Scene>,
    /// Per layout, per held rule: whether it holds (evaluated for the
    /// current held rules; cleared when they change).
    holds: Vec<Vec<bool>>,
}

/// The classes a rule is about (subject and target classes), `None` when it
/// is about any object (`*`) or a landmark.
fn classes(r: &crate::rules::Rule) -> Option<BTreeSet<&str>> {
    let mut out = BTreeSet::new();
    if let Some((shape, _)) = r.formula.shape() {
        out.insert(shape.class.as_str());
    }
    for a in r.formula.atoms() {
        out.insert(a.subject.as_str());
        match &a.target {
            crate::rules::Target::Class(c) => {
                out.insert(c.as_str());
            }
            crate::rules::Target::Any | crate::rules::Target::Landmark(_) => return None,
        }
    }
    Some(out)
}

/// Whether two rules may constrain one another: they share a class, or one
/// is about any object.
fn related(a: &crate::rules::Rule, b: &crate::rules::Rule) -> bool {
    match (classes(a), classes(b)) {
        (Some(x), Some(y)) => !x.is_disjoint(&y),
        _ => true,
    }
}

/// The question loop's state.
#[derive(Debug, Clone)]
pub struct Asker {
    problem: Scene,
    demos: Vec<Scene>,
    statements: Option<RuleSet>,
    opts: AskOptions,
    learned: Learned,
    held: RuleSet,
    answers: Vec<Answer>,
    confirmed: BTreeSet<String>,
    /// Resemblance to the demonstrations (accepted probes included).
    like: Option<ResemblanceTarget>,
    known: HashMap<String, Known>,
    /// Which held rule alone implies which (by statement text; `None`: a
    /// limit stopped the check, which counts as "no"), while the held
    /// rules stay the same; with `reuse` the decided ones are kept when
    /// learning is redone.
    alone: std::cell::RefCell<HashMap<(String, String), Option<bool>>>,
    /// With `reuse`: layouts of the problem found by checks and probe
    /// searches, for the whole session (the problem never changes).
    pool: std::cell::RefCell<Pool>,
    /// With `reuse`: every proof "these premises imply this rule"
    /// (statement texts), for the whole session: it stays a proof for any
    /// larger set of premises.
    proofs: std::cell::RefCell<Vec<(String, BTreeSet<String>)>>,
    /// Decided [`ProbeChecker::has_probe`] checks (rule, rules allowed to
    /// break with it), while the held rules stay the same.
    checks: std::cell::RefCell<HashMap<(String, Vec<String>), bool>>,
    /// What is left of the current question's budget.
    meter: std::cell::RefCell<Meter>,
    /// Rules implied on the problem whose edits were searched in the last
    /// pass, while the held rules stay the same.
    edit_tried: std::cell::RefCell<BTreeSet<String>>,
    /// The weight of a node of a probe search on the problem (the
    /// problem checker's, once one is built).
    weight: std::cell::Cell<u64>,
    open: Option<String>,
}

impl Asker {
    /// Start (or resume) on a task: `demos` as in `demos.json` (accepted
    /// probes of earlier runs included), `answers` as in `answers.json`.
    pub fn new(
        problem: Scene,
        demos: Vec<Scene>,
        statements: Option<RuleSet>,
        answers: Vec<Answer>,
        opts: AskOptions,
    ) -> Result<Asker, AskError> {
        let mut demos = demos;
        for (i, a) in answers.iter().enumerate() {
            if !a.accepted {
                continue;
            }
            // An accepted probe is a demonstration; one saved in the
            // answers but not yet in the demonstrations (an abort between
            // the two writes) is added again.
            match a.demo {
                Some(d) if demos.get(d) == Some(&a.probe) => {}
                Some(d) if d == demos.len() => demos.push(a.probe.clone()),
                Some(d) => {
                    return Err(AskError::BadAnswer {
                        index: i,
                        why: format!(
                            "the accepted probe should be demonstration [{d}], but demos.json has {} demonstrations and [{d}] is a different scene",
                            demos.len()
                        ),
                    })
                }
                None => {
                    return Err(AskError::BadAnswer {
                        index: i,
                        why: "an accepted answer needs `demo`, its index in demos.json".into(),
                    })
                }
            }
        }
        if let Some(asker) = Self::replay(&problem, &demos, &statements, &answers, &opts)? {
            return Ok(asker);
        }
        Self::start(problem, demos, statements, answers, opts)
    }

    /// Resume by asking the answered questions again: the session is then
    /// in the state an uninterrupted one would be in (the layouts and
    /// proofs found on the way, the budget spent the same way), so it asks
    /// the same next question. `None` when the answers do not replay (the
    /// accepted probes are not the last demonstrations in order, or a
    /// question comes out differently — other options, or the wall-clock
    /// cap struck): the session then starts from the answers as they are.
    fn replay(
        problem: &Scene,
        demos: &[Scene],
        statements: &Option<RuleSet>,
        answers: &[Answer],
        opts: &AskOptions,
    ) -> Result<Option<Asker>, AskError> {
        if answers.is_empty() {
            return Ok(None);
        }
        let accepted: Vec<usize> = answers.iter().filter_map(|a| a.demo).collect();
        let Some(n0) = demos.len().checked_sub(accepted.len()) else {
            return Ok(None);
        };
        if !accepted.iter().copied().eq(n0..demos.len()) {
            return Ok(None);
        }
        let mut asker = Self::start(
            problem.clone(),
            demos[..n0].to_vec(),
            statements.clone(),
            Vec::new(),
            opts.clone(),
        )?;
        for a in answers {
            match asker.next_question()? {
                Some(q) if q.rule == a.rule && q.probe.scene == a.probe => {
                    asker.answer(&q, a.accepted)?;
                }
                _ => {
                    log::debug!("ask: the answers do not replay at `{}`", a.rule);
                    return Ok(None);
                }
            }
        }
        Ok((asker.demos == demos).then_some(asker))
    }

    /// A session on `demos` with `answers` taken as given (no replay).
    fn start(
        problem: Scene,
        demos: Vec<Scene>,
        statements: Option<RuleSet>,
        answers: Vec<Answer>,
        opts: AskOptions,
    ) -> Result<Asker, AskError> {
        let learned = crate::infer::learn_with_priors(
            &demos,
            statements.as_ref(),
            &opts.learn,
            opts.priors.as_deref(),
            None,
            None,
        )?;
        let like = opts.resemble.then(|| ResemblanceTarget::new(&demos));
        let mut asker = Asker {
            problem,
            demos,
            statements,
            opts,
            held: RuleSet::default(),
            learned,
            like,
            confirmed: answers
                .iter()
                .filter(|a| !a.accepted)
                .map(|a| a.rule.clone())
                .collect(),
            answers,
            known: HashMap::new(),
            alone: Default::default(),
            pool: Default::default(),
            proofs: Default::default(),
            checks: Default::default(),
            meter: std::cell::RefCell::new(Meter::unlimited()),
            edit_tried: Default::default(),
            weight: std::cell::Cell::new(1),
            open: None,
        };
        asker.held = asker.held_rules();
        Ok(asker)
    }

    fn held_rules(&self) -> RuleSet {
        let mut set = self.learned.rules();
        for r in &mut set.rules {
            if self.confirmed.contains(&r.name) {
                r.comments.push(CONFIRMED.into());
            }
        }
        set
    }

    /// Stop every solve when `cancel` is set (`None`: never).
    pub(crate) fn set_cancel(
        &mut self,
        cancel: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    ) {
        self.opts.probe.cancel = cancel;
    }

    /// The demonstrations, accepted probes included (what `demos.json`
    /// should hold).
    pub fn demos(&self) -> &[Scene] {
        &self.demos
    }

    /// Every answer so far (what `answers.json` should hold).
    pub fn answers(&self) -> &[Answer] {
        &self.answers
    }

    /// The current learning result.
    pub fn learned(&self) -> &Learned {
        &self.learned
    }

    /// The held rules, confirmed ones marked with a `confirmed` comment.
    pub fn held(&self) -> &RuleSet {
        &self.held
    }

    /// Whether the rule named `name` has been confirmed.
    pub fn is_confirmed(&self, name: &str) -> bool {
        self.confirmed.contains(name)
    }

    /// `learned.rcc`: [`Learned::to_rcc`] with the confirmed rules marked.
    pub fn learned_rcc(&self) -> String {
        let mut out = self.learned.rcc_header();
        for r in &self.held.rules {
            out.push_str(&print_rule(r));
        }
        out
    }

    /// The progress so far.
    pub fn progress(&self) -> Tally {
        let count = |f: fn(&Known) -> bool| {
            self.held
                .rules
                .iter()
                .filter(|r| !self.confirmed.contains(&r.name))
                .filter(|r| self.known.get(&r.name).is_some_and(f))
                .count()
        };
        Tally {
            asked: self.answers.len(),
            dropped: self.answers.iter().filter(|a| a.accepted).count(),
            confirmed: self.confirmed.len(),
            implied: count(|k| matches!(k, Known::Implied)),
            unknown: count(|k| matches!(k, Known::Unknown)),
            held: self.held.rules.len(),
        }
    }

    /// The held rules not confirmed and not open to a question now, with
    /// why, in asking order (after [`Asker::next_question`] returned
    /// `None`: every rule the session leaves unasked).
    pub fn unasked(&self) -> Vec<(String, Unasked)> {
        self.asking_order()
            .into_iter()
            .map(|k| &self.held.rules[k].name)
            .filter(|name| !self.confirmed.contains(*name))
            .filter_map(|name| {
                let why = match self.known.get(name)? {
                    Known::Implied if self.edit_tried.borrow().contains(name) => {
                        Unasked::Implied { edits_tried: true }
                    }
                    Known::Implied => Unasked::Implied { edits_tried: false },
                    Known::Unknown => Unasked::Deferred,
                    Known::Probe(_) => return None,
                };
                Some((name.clone(), why))
            })
            .collect()
    }

    /// Held rules in asking order: weakest evidence first.
    fn asking_order(&self) -> Vec<usize> {
        // `held` is strongest first.
        (0..self.held.rules.len()).rev().collect()
    }

    /// Whether another held rule implies rule `k` on every scene
    /// (syntactically) and is not implied by it.
    fn syntactically_implied(&self, k: usize) -> bool {
        let r = &self.held.rules[k];
        let contact = self.opts.learn.contact;
        let implies = |a: &crate::rules::Rule, b: &crate::rules::Rule| {
            rule_implies((a.scope, &a.formula), (b.scope, &b.formula), contact)
        };
        self.held
            .rules
            .iter()
            .enumerate()
            .any(|(j, h)| j != k && implies(h, r) && !implies(r, h))
    }

    fn checker<'c>(
        &self,
        checker: &'c mut Option<ProbeChecker>,
    ) -> Result<&'c mut ProbeChecker, AskError> {
        Ok(match checker {
            Some(c) => c,
            None => {
                let t = std::time::Instant::now();
                let c = ProbeChecker::new(&self.problem, &self.held, &self.opts.probe)?;
                self.weight.set(c.weight());
                log::debug!(
                    "ask: checker built in {:.1} ms (weight {})",
                    t.elapsed().as_secs_f64() * 1e3,
                    c.weight()
                );
                checker.insert(c)
            }
        })
    }

    /// The probe for rule `k` keeping every held rule but `k` and those in
    /// `equivalent`.
    fn search(&self, k: usize, equivalent: &[bool]) -> Result<Known, AskError> {
        let mut opts = ProbeOptions {
            like: self.like.clone(),
            ..self.opts.probe.clone()
        };
        {
            let meter = self.meter.borrow();
            let want = opts.node_limit.unwrap_or(u64::MAX);
            let Some(nodes) = meter.grant(want, self.weight.get()) else {
                return Ok(Known::Unknown);
            };
            opts.node_limit = Some(nodes);
            if let Some(d) = meter.deadline() {
                let left = d.saturating_duration_since(std::time::Instant::now());
                opts.time_limit = Some(opts.time_limit.map_or(left, |t| t.min(left)));
            }
        }
        let keep: Vec<usize> = (0..self.held.rules.len())
            .filter(|&j| j == k || !equivalent[j])
            .collect();
        let set = RuleSet::new(keep.iter().map(|&j| self.held.rules[j].clone()).collect());
        let at = keep.iter().position(|&j| j == k).expect("kept");
        let t = std::time::Instant::now();
        let (found, nodes) = search_probe(&self.problem, &set, at, &opts)?;
        self.meter.borrow_mut().spend(nodes, self.weight.get());
        log::debug!(
            "ask: probe search {} ({} may break): {} in {:.1} ms",
            self.held.rules[k].name,
            self.held.rules.len() - keep.len(),
            match &found {
                ProbeOutcome::Probe(_) => "probe",
                ProbeOutcome::Implied { .. } => "implied",
                ProbeOutcome::Unknown => "unknown",
            },
            t.elapsed().as_secs_f64() * 1e3
        );
        Ok(match found {
            ProbeOutcome::Probe(p) => {
                self.remember(p.scene.clone());
                Known::Probe(p)
            }
            ProbeOutcome::Implied { .. } => Known::Implied,
            // A layout a check found is a probe too (not the most like
            // the demonstrations, but the budget found no better).
            ProbeOutcome::Unknown => match self.pool_probe(k, equivalent) {
                Some(p) => Known::Probe(p),
                None => Known::Unknown,
            },
        })
    }

    /// A pool layout that breaks rule `k` and keeps every held rule but
    /// those in `removed`, as a probe.
    fn pool_probe(&self, k: usize, removed: &[bool]) -> Option<Probe> {
        let n = self.held.rules.len();
        let premise = |j: usize| j != k && !removed.get(j).copied().unwrap_or(false);
        let pool = self.pool_holds();
        let at = pool
            .holds
            .iter()
            .position(|h| !h[k] && (0..n).filter(|&j| premise(j)).all(|j| h[j]))?;
        let scene = pool.scenes[at].clone();
        drop(pool);
        let one = RuleSet::new(vec![self.held.rules[k].clone()]);
        let broken = crate::eval::evaluate(&scene, &one, self.opts.probe.contact).rules[0]
            .violators
            .clone();
        Some(Probe {
            rule: self.held.rules[k].name.clone(),
            cost: self
                .like
                .as_ref()
                .map_or(0, |l| l.cost(&self.problem, &scene)),
            scene,
            broken,
            time_ms: 0.0,
            edit: None,
        })
    }

    /// The key of held rule `k` that stays the same when learning is
    /// redone: its statement text.
    fn text(&self, k: usize) -> String {
        let r = &self.held.rules[k];
        crate::infer::statement_text(r.scope, &r.formula)
    }

    /// Whether each held rule holds in each pool layout (rows in pool
    /// order), brought up to date with the pool.
    fn pool_holds(&self) -> std::cell::Ref<'_, Pool> {
        {
            let mut pool = self.pool.borrow_mut();
            let pool = &mut *pool;
            while pool.holds.len() < pool.scenes.len() {
                let scene = &pool.scenes[pool.holds.len()];
                let ev = crate::eval::evaluate(scene, &self.held, self.opts.probe.contact);
                pool.holds
                    .push(ev.rules.iter().map(|r| r.satisfied == r.subjects).collect());
            }
        }
        self.pool.borrow()
    }

    /// Keep a layout of the problem that a solve found (with `reuse`).
    fn remember(&self, scene: Scene) {
        if self.opts.reuse {
            let mut pool = self.pool.borrow_mut();
            if pool.scenes.len() < MAX_POOL && !pool.scenes.contains(&scene) {
                pool.scenes.push(scene);
            }
        }
    }

    /// What is already known about "does rule `k` have a probe when the
    /// rules in `removed` may break with it" without a solve (with
    /// `reuse`): `Some(true)` when a pool layout breaks `k` and keeps every
    /// premise (the other rules not removed) — the evaluator decides, so
    /// the layout is a probe; `Some(false)` when a proof of the session
    /// showed that fewer premises imply `k`, or one premise alone implies
    /// it (syntactically or proven).
    fn settled(&self, k: usize, removed: &[bool]) -> Option<bool> {
        if !self.opts.reuse {
            return None;
        }
        let n = self.held.rules.len();
        let premise = |j: usize| j != k && !removed.get(j).copied().unwrap_or(false);
        let pool = self.pool_holds();
        if pool
            .holds
            .iter()
            .any(|h| !h[k] && (0..n).filter(|&j| premise(j)).all(|j| h[j]))
        {
            return Some(true);
        }
        drop(pool);
        let text = self.text(k);
        let premises: BTreeSet<String> = (0..n)
            .filter(|&j| premise(j))
            .map(|j| self.text(j))
            .collect();
        if self
            .proofs
            .borrow()
            .iter()
            .any(|(r, by)| *r == text && by.is_subset(&premises))
        {
            return Some(false);
        }
        let rk = &self.held.rules[k];
        let alone = self.alone.borrow();
        let implied = (0..n).filter(|&j| premise(j)).any(|j| {
            let rj = &self.held.rules[j];
            alone.get(&(self.text(j), text.clone())) == Some(&Some(true))
                || rule_implies(
                    (rj.scope, &rj.formula),
                    (rk.scope, &rk.formula),
                    self.opts.learn.contact,
                )
        });
        implied.then_some(false)
    }

    /// [`ProbeChecker::has_probe`], making a new checker after a limit.
    fn check(
        &self,
        checker: &mut Option<ProbeChecker>,
        k: usize,
        removed: &[bool],
    ) -> Result<Option<bool>, AskError> {
        let key = (
            self.held.rules[k].name.clone(),
            (0..self.held.rules.len())
                .filter(|&j| removed.get(j).copied().unwrap_or(false))
                .map(|j| self.held.rules[j].name.clone())
                .collect::<Vec<_>>(),
        );
        if let Some(&v) = self.checks.borrow().get(&key) {
            return Ok(Some(v));
        }
        if let Some(v) = self.settled(k, removed) {
            log::debug!(
                "ask: check {} ({} may break): {v} without a solve",
                key.0,
                key.1.len()
            );
            self.checks.borrow_mut().insert(key, v);
            return Ok(Some(v));
        }
        let t = std::time::Instant::now();
        // At most half of what is left: an undecided check leaves the
        // other half to the demonstrations' edits and the probe search.
        let c = self.checker(checker)?;
        let want = self
            .opts
            .probe
            .check_nodes
            .unwrap_or(u64::MAX)
            .min(self.meter.borrow().half_nodes(c.weight()));
        let deadline = self.meter.borrow().deadline();
        let Some(grant) = self.meter.borrow().grant(want, c.weight()) else {
            // The question's budget is spent: undecided, not remembered.
            return Ok(None);
        };
        // With `reuse`: a short first try on the checker of the scan, then
        // the full budget on a fresh one of the premises and the rule only
        // (see `FIRST_TRY_NODES`).
        let first = if self.opts.reuse {
            FIRST_TRY_NODES.min(grant)
        } else {
            grant
        };
        c.set_deadline(deadline);
        let before = c.nodes();
        let mut checked = c.has_probe_within(k, removed, Some(first));
        let w = c.weight();
        self.meter.borrow_mut().spend(c.nodes() - before, w);
        let more = self.meter.borrow().grant(want, w);
        if let (true, Checked::Stopped, Some(more)) = (self.opts.reuse, &checked, more) {
            log::debug!(
                "ask: check {} stopped at the first try after {:.1} ms: a fresh checker",
                key.0,
                t.elapsed().as_secs_f64() * 1e3
            );
            // Later checks must not depend on how far this one got.
            *checker = None;
            // The premises and the rule only: a smaller model.
            let keep: Vec<usize> = (0..self.held.rules.len())
                .filter(|&j| j == k || !removed.get(j).copied().unwrap_or(false))
                .collect();
            let set = RuleSet::new(keep.iter().map(|&j| self.held.rules[j].clone()).collect());
            let at = keep.iter().position(|&j| j == k).expect("kept");
            let mut fresh = ProbeChecker::new(&self.problem, &set, &self.opts.probe)?;
            fresh.set_deadline(deadline);
            checked = fresh.has_probe_within(at, &[], Some(more));
            self.meter.borrow_mut().spend(fresh.nodes(), fresh.weight());
        }
        log::debug!(
            "ask: check {} ({} may break): {} in {:.1} ms",
            key.0,
            key.1.len(),
            checked.name(),
            t.elapsed().as_secs_f64() * 1e3
        );
        let verdict = match checked {
            Checked::Witness(scene) => {
                self.remember(scene);
                Some(true)
            }
            Checked::Proven => {
                if self.opts.reuse {
                    let premises = (0..self.held.rules.len())
                        .filter(|&j| j != k && !removed.get(j).copied().unwrap_or(false))
                        .map(|j| self.text(j))
                        .collect();
                    self.proofs.borrow_mut().push((self.text(k), premises));
                }
                Some(false)
            }
            // A stopped search: a fresh engine for the next checks, so
            // that they do not depend on how far this one got.
            Checked::Stopped => {
                *checker = None;
                None
            }
        };
        if let Some(v) = verdict {
            self.checks.borrow_mut().insert(key, v);
        }
        Ok(verdict)
    }

    /// Whether held rule `a` alone implies held rule `b` on this problem
    /// (syntactically, or proven by the checker; a limit counts as no).
    /// Memoised while the held rules stay the same (with `reuse`: decided
    /// answers for the whole session, keyed by statement text).
    fn alone_implies(
        &self,
        checker: &mut Option<ProbeChecker>,
        a: usize,
        b: usize,
    ) -> Result<bool, AskError> {
        let key = (self.text(a), self.text(b));
        if let Some(&v) = self.alone.borrow().get(&key) {
            return Ok(v == Some(true));
        }
        let (ra, rb) = (&self.held.rules[a], &self.held.rules[b]);
        let v = if !related(ra, rb) {
            // No class in common: neither says anything about the other's
            // objects (a rule impossible or certain on its own would be the
            // exception; missing it only costs a question).
            Some(false)
        } else if rule_implies(
            (ra.scope, &ra.formula),
            (rb.scope, &rb.formula),
            self.opts.learn.contact,
        ) {
            Some(true)
        } else if self.opts.reuse && self.pool_holds().holds.iter().any(|h| h[a] && !h[b]) {
            // A layout keeping `a` and breaking `b`.
            Some(false)
        } else {
            let want = self.opts.probe.check_nodes.unwrap_or(u64::MAX);
            let deadline = self.meter.borrow().deadline();
            let c = self.checker(checker)?;
            let Some(grant) = self.meter.borrow().grant(want, c.weight()) else {
                // The question's budget is spent: "no", not remembered.
                return Ok(false);
            };
            c.set_deadline(deadline);
            let t = std::time::Instant::now();
            let before = c.nodes();
            let checked = c.implies_within(a, b, Some(grant));
            self.meter
                .borrow_mut()
                .spend(c.nodes() - before, c.weight());
            log::debug!(
                "ask: implies {} -> {}: {} in {:.1} ms",
                ra.name,
                rb.name,
                checked.name(),
                t.elapsed().as_secs_f64() * 1e3
            );
            match checked {
                Checked::Witness(scene) => {
                    self.remember(scene);
                    Some(false)
                }
                Checked::Proven => Some(true),
                Checked::Stopped => {
                    // A stopped search: a fresh engine for the next checks.
                    *checker = None;
                    None
                }
            }
        };
        self.alone.borrow_mut().insert(key, v);
        Ok(v == Some(true))
    }

    /// The next question, or `None` when every held rule is confirmed or
    /// needs no question. Computes probes lazily, in asking order.
    ///
    /// When no rule has a probe that keeps every other held rule, rules
    /// that follow from one another would never be asked about: e.g.
    /// `DR_S(R, G)` and `DR_N(G, R)` (the same habit written two ways), or
    /// `R_inside_W` and the four `!DR_d(R, W)` that together say the same.
    /// Then further passes visit the unconfirmed rules, in asking order:
    ///
    /// 1. a rule that another unconfirmed rule alone implies, but not the
    ///    other way round, is skipped (the stronger one is asked about);
    /// 2. the rules that alone imply it and that it alone implies (the same
    ///    statement on this problem) may break with it; if the rest still
    ///    imply it, its parts (the unconfirmed rules it alone implies) are
    ///    added one at a time, weakest evidence first, until a probe exists;
    /// 3. only in the last pass, when no rule could be asked about so, every
    ///    unconfirmed rule about one of its classes may break too (one
    ///    solve: e.g. the same habit written two ways, `DR_S(R, G)` and
    ///    `DR_N(G, R)`, that a probe can break only by also breaking a
    ///    habit "no G on the floor");
    /// 4. each rule so added is kept hard again when a probe exists without
    ///    it (strongest first), so the probe breaks the rule and the fewest
    ///    others; [`Question::also_broken`] names them.
    ///
    /// Every check is a solve with a node budget
    /// ([`ProbeOptions::check_nodes`], deterministic), so the questions
    /// depend on the budgets, never on the machine's speed, unless the
    /// time limit (a safety net) stops a solve first.
    pub fn next_question(&mut self) -> Result<Option<Question>, AskError> {
        // One checker of the problem and one per demonstration for every
        // scan of this question (built when first needed).
        let mut checker: Option<ProbeChecker> = None;
        let mut edit_checkers: Vec<Option<ProbeChecker>> = Vec::new();
        loop {
            match self.scan(&mut checker, &mut edit_checkers)? {
                Scan::Question(q) => {
                    self.open = Some(q.rule.clone());
                    return Ok(Some(*q));
                }
                Scan::OutOfBudget => {}
                Scan::Done => {
                    self.open = None;
                    return Ok(None);
                }
            }
        }
    }

    /// A probe for rule `k` that is a demonstration with a few objects
    /// moved, within the question's budget.
    fn edit_probe(&self, k: usize, checkers: &mut Vec<Option<ProbeChecker>>) -> Option<Probe> {
        if !self.opts.edits {
            return None;
        }
        let search = EditSearch {
            demos: &self.demos,
            like: self.like.as_ref(),
            contact: self.opts.probe.contact,
            seed: self.opts.probe.seed,
            time_limit: self.opts.probe.time_limit,
            cancel: self.opts.probe.cancel.clone(),
        };
        let t = std::time::Instant::now();
        let found = search.find(&self.held, k, checkers, &mut self.meter.borrow_mut());
        log::debug!(
            "ask: edit search {}: {} in {:.1} ms",
            self.held.rules[k].name,
            if found.is_some() { "probe" } else { "none" },
            t.elapsed().as_secs_f64() * 1e3
        );
        found
    }

    /// One scan of the held rules for the next question, under a fresh
    /// question budget (see [`Asker::next_question`]).
    fn scan(
        &mut self,
        checker: &mut Option<ProbeChecker>,
        edit_checkers: &mut Vec<Option<ProbeChecker>>,
    ) -> Result<Scan, AskError> {
        *self.meter.get_mut() = Meter::start(&self.opts.budget);
        let mut decided = 0usize;
        // Decided checks so far: a group pass that runs out of budget after
        // deciding new ones goes on in the next scan (the decided ones are
        // kept), so every scan makes progress and the loop ends.
        let settled = |a: &Asker| a.checks.borrow().len() + a.alone.borrow().len();
        let settled_before = settled(self);
        let order = self.asking_order();
        let n = self.held.rules.len();
        let none = vec![false; n];
        let mut group: Option<Probe> = None;
        for pass in 0..4 {
            if pass > 0 {
                // The group passes and the last one get budgets of their
                // own.
                *self.meter.get_mut() = Meter::start(&self.opts.budget);
            }
            let mut tried = 0usize;
            for &k in &order {
                let name = self.held.rules[k].name.clone();
                if self.confirmed.contains(&name) {
                    continue;
                }
                if pass == 3 {
                    // Other mixes: a rule the others imply on the problem
                    // may still break in a demonstration with an object or
                    // two moved.
                    if !matches!(self.known.get(&name), Some(Known::Implied))
                        || !self.opts.edits
                        || !self.edit_tried.borrow_mut().insert(name.clone())
                    {
                        continue;
                    }
                    if tried > 0 && self.meter.borrow().exhausted() {
                        self.edit_tried.borrow_mut().remove(&name);
                        return Ok(Scan::OutOfBudget);
                    }
                    tried += 1;
                    if self.syntactically_implied(k) {
                        continue;
                    }
                    match self.edit_probe(k, edit_checkers) {
                        Some(p) => group = Some(p),
                        None => continue,
                    }
                }
                if pass == 0 && !self.known.contains_key(&name) {
                    if decided > 0 && self.meter.borrow().exhausted() {
                        // Every rule so far is decided or deferred: the
                        // next scan goes on from here with a fresh budget.
                        return Ok(Scan::OutOfBudget);
                    }
                    // The problem first: a rule the others imply there is
                    // not asked about now (the last pass looks at other
                    // mixes); one that can break is shown as an edit of a
                    // demonstration when one breaks it, else as a layout of
                    // the problem.
                    let known = if self.syntactically_implied(k) {
                        Known::Implied
                    } else {
                        match self.check(checker, k, &none)? {
                            Some(false) => Known::Implied,
                            _ => match self.edit_probe(k, edit_checkers) {
                                Some(p) => Known::Probe(p),
                                None => self.search(k, &none)?,
                            },
                        }
                    };
                    decided += 1;
                    self.known.insert(name.clone(), known);
                }
                if (pass == 1 || pass == 2)
                    && self.meter.borrow().exhausted()
                    && settled(self) > settled_before
                {
                    return Ok(Scan::OutOfBudget);
                }
                if (pass == 1 || pass == 2) && matches!(self.known.get(&name), Some(Known::Implied))
                {
                    // The unconfirmed implied rules; skip `k` when one of
                    // them alone implies it and not the other way round
                    // (the stronger rule is asked about, and once settled,
                    // settles `k`); group it with those that say the same
                    // on this problem (each alone implies the other).
                    let open: Vec<usize> = (0..n)
                        .filter(|&j| {
                            let other = &self.held.rules[j].name;
                            j != k
                                && !self.confirmed.contains(other)
                                && matches!(self.known.get(other), Some(Known::Implied))
                        })
                        .collect();
                    let mut with = vec![false; n];
                    let mut parts = vec![false; n];
                    let mut weaker = false;
                    for &j in &open {
                        let j_k = self.alone_implies(checker, j, k)?;
                        let k_j = self.alone_implies(checker, k, j)?;
                        if j_k && !k_j {
                            weaker = true;
                            break;
                        }
                        with[j] = j_k && k_j;
                        parts[j] = k_j && !j_k;
                    }
                    if weaker {
                        continue;
                    }
                    // Grow the group with the rule's parts (the rules it
                    // alone implies), weakest evidence first, until the
                    // firm rules no longer imply `k`; then keep hard every
                    // part that can be kept: the fewest break with `k`.
                    let mut probe_able =
                        with.iter().any(|&w| w) && self.check(checker, k, &with)? == Some(true);
                    for &j in order.iter().filter(|&&j| parts[j]) {
                        if probe_able {
                            break;
                        }
                        with[j] = true;
                        probe_able = self.check(checker, k, &with)? == Some(true);
                    }
                    if !probe_able && pass == 2 {
                        // Last pass, one solve: every open rule about the same
                        // classes may break (e.g. a habit of the same
                        // objects that the probe must break too).
                        let mut all = with.clone();
                        for &j in &open {
                            all[j] |= related(&self.held.rules[k], &self.held.rules[j]);
                        }
                        if all != with && self.check(checker, k, &all)? == Some(true) {
                            with = all;
                            probe_able = true;
                        }
                    }
                    if !probe_able {
                        // The firm rules imply it (or a limit): settled.
                        continue;
                    }
                    for j in 0..n {
                        if with[j] {
                            with[j] = false;
                            if self.check(checker, k, &with)? != Some(true) {
                                with[j] = true;
                            }
                        }
                    }
                    // Not cached: it depends on which rules are confirmed.
                    group = match self.search(k, &with)? {
                        Known::Probe(p) => Some(p),
                        _ => None,
                    };
                }
                let probe = match (&group, self.known.get(&name)) {
                    (Some(p), _) => Some(p),
                    (None, Some(Known::Probe(p))) if pass == 0 => Some(p),
                    _ => None,
                };
                if let Some(p) = probe {
                    let rule = &self.held.rules[k];
                    let stmt = self
                        .learned
                        .statements
                        .iter()
                        .find(|s| s.name == name)
                        .expect("a held rule is a statement");
                    let ev = crate::eval::evaluate(&p.scene, &self.held, self.opts.learn.contact);
                    let also_broken = ev
                        .rules
                        .iter()
                        .filter(|r| r.name != name && r.satisfied < r.subjects)
                        .map(|r| r.name.clone())
                        .collect();
                    let q = Question {
                        also_broken,
                        rule: name.clone(),
                        statement: crate::infer::statement_text(rule.scope, &rule.formula),
                        english: stmt.english.clone(),
                        probe: p.clone(),
                    };
                    return Ok(Scan::Question(Box::new(q)));
                }
            }
        }
        Ok(Scan::Done)
    }

    /// The answer to `q` as [`Asker::answer`] will record it (for a journal
    /// written before the answer is applied).
    pub fn answer_record(&self, q: &Question, accepted: bool) -> Answer {
        Answer {
            rule: q.rule.clone(),
            statement: q.statement.clone(),
            english: q.english.clone(),
            accepted,
            demo: accepted.then_some(self.demos.len()),
            broken: q.probe.broken.clone(),
            probe: q.probe.scene.clone(),
            edit: q.probe.edit.clone(),
        }
    }

    /// Apply the person's answer to question `q` (SPEC §13): accepted → the
    /// probe becomes a demonstration and learning is redone; rejected → the
    /// rule is confirmed. Returns the answer to save.
    pub fn answer(&mut self, q: &Question, accepted: bool) -> Result<&Answer, AskError> {
        if self.open.as_deref() != Some(q.rule.as_str()) {
            return Err(AskError::NotAsked(q.rule.clone()));
        }
        self.open = None;
        let a = self.answer_record(q, accepted);
        if accepted {
            let mut demos = self.demos.clone();
            demos.push(q.probe.scene.clone());
            let learned = crate::infer::learn_with_priors(
                &demos,
                self.statements.as_ref(),
                &self.opts.learn,
                self.opts.priors.as_deref(),
                None,
                None,
            )?;
            self.like = self.opts.resemble.then(|| ResemblanceTarget::new(&demos));
            self.demos = demos;
            self.learned = learned;
            self.known.clear();
            if self.opts.reuse {
                // Decided answers depend only on the two statements and
                // the problem; the pool's layouts and the proofs stay
                // layouts and proofs of the problem.
                self.alone.get_mut().retain(|_, v| v.is_some());
                self.pool.get_mut().holds.clear();
            } else {
                self.alone.get_mut().clear();
            }
            self.checks.get_mut().clear();
            self.edit_tried.get_mut().clear();
        } else {
            self.confirmed.insert(q.rule.clone());
            // The held rules are the same, so is every probe and every
            // proof; a rule the budget deferred stays deferred (it is
            // looked at again when learning is redone).
        }
        self.held = self.held_rules();
        self.answers.push(a);
        Ok(self.answers.last().expect("just pushed"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scenes_from_json;

    /// The bundled example's problem and demonstrations.
    fn example() -> (Scene, Vec<Scene>) {
        let demos = scenes_from_json(include_str!("../../examples/box-packing/demos.json"))
            .expect("demonstrations");
        let problem = Scene::from_json(include_str!("../../examples/box-packing/problem.json"))
            .expect("problem");
        (problem, demos)
    }

    /// A solve on a fresh checker: `Some(true)` witness, `Some(false)`
    /// proven, `None` stopped.
    fn solved(c: Checked) -> Option<bool> {
        match c {
            Checked::Witness(_) => Some(true),
            Checked::Proven => Some(false),
            Checked::Stopped => None,
        }
    }

    /// What the pool, the proofs and the implications settle without a
    /// solve is what a solve on a fresh checker decides — for every held
    /// rule of the bundled example after three questions (the first
    /// accepted: learning redone, the pool and proofs kept), with no rule
    /// and with random sets of rules allowed to break; and for every pair
    /// the pool says "does not alone imply". Every pool layout is a layout
    /// of the problem (the verifier, no rule).
    #[test]
    fn settled_checks_agree_with_solves() {
        let (problem, demos) = example();
        let mut asker = Asker::new(
            problem.clone(),
            demos,
            None,
            Vec::new(),
            AskOptions::default(),
        )
        .unwrap();
        for i in 0..3 {
            let q = asker.next_question().unwrap().expect("a question");
            asker.answer(&q, i == 0).unwrap();
        }
        asker.next_question().unwrap().expect("a question");
        for s in &asker.pool.borrow().scenes {
            crate::synth::verify_solution(
                &problem,
                s,
                &RuleSet::default(),
                asker.opts.probe.contact,
            )
            .expect("a layout of the problem");
        }
        let n = asker.held.rules.len();
        let mut fresh = ProbeChecker::new(&problem, &asker.held, &asker.opts.probe).unwrap();
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut settled = [0, 0];
        for k in 0..n {
            for round in 0..4 {
                let removed: Vec<bool> = (0..n)
                    .map(|_| {
                        state ^= state << 13;
                        state ^= state >> 7;
                        state ^= state << 17;
                        round > 0 && state % 4 == 0
                    })
                    .collect();
                let Some(v) = asker.settled(k, &removed) else {
                    continue;
                };
                settled[usize::from(v)] += 1;
                let s = solved(fresh.has_probe(k, &removed));
                assert!(
                    s.is_none() || s == Some(v),
                    "rule {}: settled {v}, solved {s:?}",
                    asker.held.rules[k].name
                );
            }
        }
        assert!(settled[0] > 0 && settled[1] > 0, "{settled:?}");
        let mut refuted = 0;
        for a in 0..n {
            for b in 0..n {
                let by_pool = a != b && asker.pool_holds().holds.iter().any(|h| h[a] && !h[b]);
                if by_pool && refuted < 200 {
                    refuted += 1;
                    assert_ne!(
                        fresh.implies(a, b),
                        Checked::Proven,
                        "{} -> {}",
                        asker.held.rules[a].name,
                        asker.held.rules[b].name
                    );
                }
            }
        }
        assert!(refuted > 0);
    }

    /// A proof for some premises settles the check for more premises,
    /// never for fewer.
    #[test]
    fn a_proof_settles_only_larger_premises() {
        let (problem, demos) = example();
        let asker = Asker::new(problem, demos, None, Vec::new(), AskOptions::default()).unwrap();
        let n = asker.held.rules.len();
        let mut removed = vec![false; n];
        let mut fewer = vec![false; n];
        // A rule that nothing settles when three others may break.
        let k = (3..n)
            .find(|&k| {
                fewer = (0..n).map(|j| j < 3).collect();
                asker.settled(k, &fewer).is_none()
            })
            .expect("an unsettled check");
        removed[0] = true;
        removed[1] = true;
        let premises: BTreeSet<String> = (0..n)
            .filter(|&j| j != k && !removed[j])
            .map(|j| asker.text(j))
            .collect();
        asker.proofs.borrow_mut().push((asker.text(k), premises));
        assert_eq!(asker.settled(k, &removed), Some(false));
        assert_eq!(asker.settled(k, &vec![false; n]), Some(false));
        assert_eq!(asker.settled(k, &fewer), None, "fewer premises");
    }
}
