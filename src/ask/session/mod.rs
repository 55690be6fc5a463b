//! The question loop (docs/guide.md#questions), without I/O: which rule to ask about next,
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
//! # Reuse
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

mod belief;
mod checks;
mod group;
mod question;
mod resume;
mod reuse;
mod scan;
mod suspects;
mod sweep;

pub use question::{Asked, Question, Tally, Unasked};
pub use suspects::SuspectQuestion;
use suspects::{learn_session, suspect_answers};

use super::answers::{Answer, SuspectAnswer, CONFIRMED};
use super::budget::{Meter, QuestionBudget};
use super::checker::ProbeChecker;
use super::probe::{Probe, ProbeOptions};
use crate::infer::{InferError, LearnParams, Learned};
use crate::resemblance::ResemblanceTarget;
use crate::rules::{print_rule, RuleSet};
use crate::scene::Scene;
use crate::synth::SynthError;
use reuse::Pool;
use scan::Scan;
use std::collections::{BTreeSet, HashMap};

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

/// Settings of the loop.
#[derive(Debug, Clone)]
pub struct AskOptions {
    /// Learning parameters (as for `learn`/`run`).
    pub learn: LearnParams,
    /// Probe search settings (`like` is filled from the demonstrations when
    /// `resemble` is on; `contact` is the learning's,
    /// [`LearnParams::contact`], whatever is set here: one session, one
    /// meaning of touching).
    pub probe: ProbeOptions,
    /// Probes resemble the demonstrations (docs/guide.md#layouts-like-the-demonstrations).
    pub resemble: bool,
    /// Reuse what earlier checks found (on by default): a layout a solve
    /// found answers later checks it decides (evaluated, no solve), a
    /// proof that some rules imply a rule answers later checks with more
    /// premises, and decided answers outlive a relearning. Off, every
    /// check is a solve (for comparisons and tests); the
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
    /// Ask about groups of rules that are likely habits with one probe
    /// (on by default; docs/guide.md#questions). Off, every question is
    /// about one rule.
    pub groups: bool,
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
            groups: true,
        }
    }
}

#[derive(Debug, Clone)]
enum Known {
    Probe(Probe),
    Implied,
    Unknown,
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
    /// Demonstrations answered as holding a slip: its likeliest slip is
    /// one for sure when learning.
    slipped: BTreeSet<usize>,
    /// Demonstrations answered as meant, exceptions and all.
    meant: BTreeSet<usize>,
    /// Rules of a rejected group not settled yet: at least one of them is
    /// meant (the next questions narrow it down).
    pending: Vec<String>,
    /// Rules confirmed by deduction: the one left of a rejected group.
    deduced: BTreeSet<String>,
    /// Held rules an accepted probe broke besides those it asked about
    /// (habits too, for the families; rebuilt by a replay).
    also_dropped: BTreeSet<String>,
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
        resume::check_answers(&answers, &mut demos)?;
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
                Some(q)
                    if q.rule == a.rule
                        && q.group_names() == a.group
                        && q.probe.scene == a.probe =>
                {
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
        mut opts: AskOptions,
    ) -> Result<Asker, AskError> {
        // The learning's contact is the session's (see `AskOptions::probe`).
        opts.probe.contact = opts.learn.contact;
        let (slipped, meant) = suspect_answers(&answers);
        let learned = learn_session(&demos, statements.as_ref(), &opts, &slipped, &meant)?;
        // A confirmed rule must be one of the task's statements (a hand
        // edit or a renamed rule would be counted confirmed and marked
        // nowhere).
        for (i, a) in answers.iter().enumerate() {
            let named: Vec<&String> = match &a.suspect {
                Some(s) => s.breaks.iter().collect(),
                None => std::iter::once(&a.rule).chain(&a.group).collect(),
            };
            for rule in named {
                if !learned.statements.iter().any(|s| &s.name == rule) {
                    return Err(AskError::BadAnswer {
                        index: i,
                        why: format!(
                            "rule: `{}` is not a statement of this task (renamed, or edited by hand?); expected the name of a learned rule — fix or remove the answer",
                            crate::limits::cut(rule)
                        ),
                    });
                }
            }
        }
        let like = opts.resemble.then(|| ResemblanceTarget::new(&demos));
        let (pending, deduced) = group::replay_groups(&answers);
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
                .filter(|a| !a.accepted && a.group.is_empty())
                .flat_map(|a| match &a.suspect {
                    Some(s) => s.breaks.clone(),
                    None => vec![a.rule.clone()],
                })
                .chain(deduced.iter().cloned())
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
            slipped,
            meant,
            pending,
            deduced,
            also_dropped: BTreeSet::new(),
        };
        asker.held = asker.held_rules();
        asker.settle_pending();
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

    /// Stop every solve when `cancel` is set (`None`: no flag).
    pub(crate) fn set_cancel(
        &mut self,
        cancel: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    ) {
        self.opts.probe.stop = self.opts.probe.stop.clone().cancel_with(cancel);
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
        if !self.slipped.is_empty() {
            // In the header, before its closing blank line.
            let blank = out.ends_with("\n\n");
            if blank {
                out.pop();
            }
            for d in &self.slipped {
                let object = self
                    .learned
                    .slips
                    .iter()
                    .find(|s| s.demonstration == *d)
                    .map_or(String::new(), |s| format!(" `{}`", s.object));
                out.push_str(&format!(
                    "# demonstration {d}:{object} answered as a slip; it no longer counts against the rules it breaks (answers.json)\n"
                ));
            }
            if blank {
                out.push('\n');
            }
        }
        for r in &self.held.rules {
            out.push_str(&print_rule(r));
        }
        out
    }

    /// Held rules in asking order: weakest evidence first; with
    /// [`AskOptions::groups`], likeliest habit first (ties: weakest
    /// evidence first).
    fn asking_order(&self) -> Vec<usize> {
        if self.opts.groups {
            self.asking_order_with(&self.meant_chances())
        } else {
            // `held` is strongest first.
            (0..self.held.rules.len()).rev().collect()
        }
    }

    /// [`Asker::asking_order`] with the chances `p` that each held rule is
    /// meant.
    fn asking_order_with(&self, p: &[f64]) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.held.rules.len()).rev().collect();
        if self.opts.groups {
            order.sort_by(|&a, &b| p[a].total_cmp(&p[b]));
        }
        order
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
        if let Some(q) = self.suspect_question() {
            self.open = Some(q.rule.clone());
            return Ok(Some(q));
        }
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

    /// The answer to `q` as [`Asker::answer`] will record it (for a journal
    /// written before the answer is applied).
    pub fn answer_record(&self, q: &Question, accepted: bool) -> Answer {
        Answer {
            rule: q.rule.clone(),
            statement: q.statement.clone(),
            english: q.english.clone(),
            accepted,
            demo: (accepted && q.suspect.is_none()).then_some(self.demos.len()),
            broken: q.probe.broken.clone(),
            probe: q.probe.scene.clone(),
            edit: q.probe.edit.clone(),
            suspect: q.suspect.as_ref().map(|s| SuspectAnswer {
                demonstration: s.demonstration,
                breaks: s.breaks.clone(),
            }),
            group: q.group_names(),
        }
    }

    /// Apply the person's answer to question `q` (docs/guide.md#questions): accepted → the
    /// probe becomes a demonstration and learning is redone; rejected → the
    /// rule is confirmed. Returns the answer to save.
    pub fn answer(&mut self, q: &Question, accepted: bool) -> Result<&Answer, AskError> {
        if self.open.as_deref() != Some(q.rule.as_str()) {
            return Err(AskError::NotAsked(q.rule.clone()));
        }
        self.open = None;
        let a = self.answer_record(q, accepted);
        if let Some(s) = &q.suspect {
            // A demonstration meant as it is (its exceptions are meant: the
            // rules it breaks are no candidates) or a slip (its likeliest
            // slip sure, the rules confirmed); learning is redone either way.
            if accepted {
                self.meant.insert(s.demonstration);
            } else {
                self.slipped.insert(s.demonstration);
                self.confirmed.extend(s.breaks.iter().cloned());
            }
            let demos = self.demos.clone();
            self.relearn(demos)?;
        } else if accepted {
            let asked = a.asked();
            self.also_dropped.extend(
                (q.also_broken.iter())
                    .filter(|n| !asked.contains(&n.as_str()))
                    .cloned(),
            );
            let mut demos = self.demos.clone();
            demos.push(q.probe.scene.clone());
            self.relearn(demos)?;
        } else if q.group.is_empty() {
            self.confirmed.insert(q.rule.clone());
            // The held rules are the same, so is every probe and every
            // proof; a rule the budget deferred stays deferred (it is
            // looked at again when learning is redone).
        }
        if q.suspect.is_none() {
            group::narrow(&mut self.pending, &a.asked(), accepted);
        }
        self.held = self.held_rules();
        self.answers.push(a);
        if self.settle_pending() {
            self.held = self.held_rules();
        }
        Ok(self.answers.last().expect("just pushed"))
    }

    /// Learn again from `demos` (the session's slips and meant
    /// demonstrations applied) and drop what depended on the held rules.
    fn relearn(&mut self, demos: Vec<Scene>) -> Result<(), AskError> {
        let learned = learn_session(
            &demos,
            self.statements.as_ref(),
            &self.opts,
            &self.slipped,
            &self.meant,
        )?;
        {
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
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ask::checker::Checked;
    use crate::scene::scenes_from_json;

    /// The bundled example's problem and demonstrations.
    fn example() -> (Scene, Vec<Scene>) {
        let demos = scenes_from_json(include_str!("../../../examples/box-packing/demos.json"))
            .expect("demonstrations");
        let problem = Scene::from_json(include_str!("../../../examples/box-packing/problem.json"))
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
    /// The learning's contact is the probes' too, whatever the probe
    /// options say: one session, one meaning of touching.
    #[test]
    fn the_probes_take_the_learnings_contact() {
        let (problem, demos) = example();
        let mut opts = AskOptions::default();
        opts.learn.contact = crate::relations::Contact::Edge;
        opts.probe.contact = crate::relations::Contact::Point;
        let asker = Asker::new(problem, demos, None, Vec::new(), opts).unwrap();
        assert_eq!(asker.opts.probe.contact, crate::relations::Contact::Edge);
    }

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
