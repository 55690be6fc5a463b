//! What one held-out task learns under one condition (recall, rare rules,
//! spurious rules, truth ruled out) and how many questions the question
//! loop needs with the truth as the oracle.

use super::conditions::Statements;
use super::population::PopTask;
use super::{PriorsBenchConfig, PriorsBenchError};
use crate::tasks::block;
use rccpack::ask::{AskOptions, Asker, ProbeOptions, QuestionBudget};
use rccpack::eval::evaluate;
use rccpack::infer::rule_implies;
use rccpack::infer::{learn_with, LearnOptions};
use rccpack::priors::Priors;
use rccpack::rules::{Formula, Rule, RuleSet, Scope};
use rccpack::scene::Scene;
use serde::Serialize;
use std::collections::{BTreeSet, HashSet};
use std::sync::Arc;

/// What learning on one held-out task gave under one condition.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Outcome {
    /// Truth rules that are candidates of the demonstrations.
    pub truth: usize,
    /// Of these, learned (or implied by a learned truth rule).
    pub recalled: usize,
    /// Truth rules of a kind rare in the population.
    pub rare: usize,
    /// Of these, recalled.
    pub rare_recalled: usize,
    /// Rules learned.
    pub learned: usize,
    /// Learned rules neither in the truth nor implied by a truth rule.
    pub spurious: usize,
    /// Truth rules whose kind the priors ruled out.
    pub truth_ruled_out: usize,
    /// Statements left out (ruled-out kinds).
    pub left_out: usize,
}

impl Outcome {
    /// Add `o`, counter by counter (saturating).
    pub(super) fn add(&mut self, o: &Outcome) {
        self.truth = self.truth.saturating_add(o.truth);
        self.recalled = self.recalled.saturating_add(o.recalled);
        self.rare = self.rare.saturating_add(o.rare);
        self.rare_recalled = self.rare_recalled.saturating_add(o.rare_recalled);
        self.learned = self.learned.saturating_add(o.learned);
        self.spurious = self.spurious.saturating_add(o.spurious);
        self.truth_ruled_out = self.truth_ruled_out.saturating_add(o.truth_ruled_out);
        self.left_out = self.left_out.saturating_add(o.left_out);
    }
}

/// A held-out task with what every condition needs: its truth rules that
/// are candidates of its demonstrations, each with whether its kind is
/// rare.
pub(super) struct HeldOut {
    /// The task.
    pub(super) task: PopTask,
    st: Statements,
    truth: Vec<(Rule, bool)>,
}

impl HeldOut {
    /// The held-out task `task` with its truth rules that are candidates,
    /// each marked rare or not by `true_priors`.
    pub(super) fn new(
        task: PopTask,
        true_priors: &Priors,
        cfg: &PriorsBenchConfig,
    ) -> Result<Self, PriorsBenchError> {
        let st = Statements::of(&task.demos, &cfg.params, task.stream)?;
        let truth = task
            .truth
            .rules
            .iter()
            .filter_map(|r| {
                let i = st.index_of(r)?;
                let rare = is_rare(true_priors, &st.kinds[i], cfg.rare_percent);
                st.candidate[i].then(|| (r.clone(), rare))
            })
            .collect();
        Ok(HeldOut { task, st, truth })
    }

    fn is_truth(&self, scope: Scope, f: &Formula) -> bool {
        self.truth
            .iter()
            .any(|(t, _)| t.scope == scope && t.formula == *f)
    }

    /// Recall and spurious rules of `rules` (learned or held).
    fn score(&self, rules: &RuleSet, contact: rccpack::relations::Contact) -> Outcome {
        let held: HashSet<(Scope, &Formula)> =
            rules.rules.iter().map(|r| (r.scope, &r.formula)).collect();
        let held_truth: Vec<&Rule> = rules
            .rules
            .iter()
            .filter(|r| self.is_truth(r.scope, &r.formula))
            .collect();
        let mut o = Outcome {
            learned: rules.rules.len(),
            ..Outcome::default()
        };
        for (t, rare) in &self.truth {
            let recalled = held.contains(&(t.scope, &t.formula))
                || held_truth
                    .iter()
                    .any(|h| rule_implies((h.scope, &h.formula), (t.scope, &t.formula), contact));
            o.add(&Outcome {
                truth: 1,
                recalled: usize::from(recalled),
                rare: usize::from(*rare),
                rare_recalled: usize::from(*rare && recalled),
                ..Outcome::default()
            });
        }
        o.spurious = self.spurious(rules, contact).count();
        o
    }

    /// The rules of `rules` that are neither truth rules nor implied by
    /// one.
    fn spurious<'a>(
        &'a self,
        rules: &'a RuleSet,
        contact: rccpack::relations::Contact,
    ) -> impl Iterator<Item = &'a Rule> + 'a {
        rules.rules.iter().filter(move |r| {
            !self.is_truth(r.scope, &r.formula)
                && !self
                    .task
                    .truth
                    .rules
                    .iter()
                    .any(|t| rule_implies((t.scope, &t.formula), (r.scope, &r.formula), contact))
        })
    }

    /// The kinds of the spurious rules of `rules`.
    fn spurious_kinds(&self, rules: &RuleSet, contact: rccpack::relations::Contact) -> Vec<String> {
        self.spurious(rules, contact)
            .map(|r| {
                self.st
                    .index_of(r)
                    .map_or_else(|| "(given)".to_string(), |i| self.st.kinds[i].clone())
            })
            .collect()
    }
}

/// Whether `kind` was kept in fewer than `percent` % of the true
/// library's tasks (a kind it never saw is rare).
fn is_rare(true_priors: &Priors, kind: &str, percent: u64) -> bool {
    let kept = true_priors
        .kinds
        .binary_search_by(|e| e.kind.as_str().cmp(kind))
        .map_or(0, |i| true_priors.kinds[i].tasks_kept);
    kept.saturating_mul(100) < percent.saturating_mul(true_priors.tasks)
}

/// Learn `h`'s rules under `priors` and score them.
pub(super) fn learn_outcome(
    h: &HeldOut,
    priors: Option<&Priors>,
    cfg: &PriorsBenchConfig,
) -> Result<(Outcome, Vec<String>), PriorsBenchError> {
    let opts = LearnOptions {
        priors,
        ..LearnOptions::default()
    };
    let learned = learn_with(&h.task.demos, None, &cfg.learn_params(), &opts).map_err(|error| {
        PriorsBenchError::Learn {
            stream: h.task.stream,
            error,
        }
    })?;
    let rules = learned.rules();
    let mut o = h.score(&rules, cfg.params.contact);
    let kinds = h.spurious_kinds(&rules, cfg.params.contact);
    if let Some(used) = &learned.priors {
        let out: BTreeSet<&str> = used.ruled_out.iter().map(|r| r.name.as_str()).collect();
        o.left_out = out.len();
        o.truth_ruled_out = h
            .truth
            .iter()
            .filter(|(t, _)| out.contains(t.name.as_str()))
            .count();
    }
    Ok((o, kinds))
}

/// What the question loop gave on one held-out task.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct AskOutcome {
    /// Questions answered.
    pub questions: usize,
    /// Stopped by [`PriorsBenchConfig::max_questions`] with questions left.
    pub capped: bool,
    /// The held rules before the first question.
    pub before: Outcome,
    /// The held rules after the last one.
    pub after: Outcome,
}

/// The task's problem: its box with each class's largest count, unplaced.
pub fn problem_scene(task: &PopTask) -> Scene {
    let mut scene = task.geom.scene();
    for c in &task.classes {
        scene
            .objects
            .extend((0..c.max_count).map(|j| block(&c.class, j, c.width, c.height, None)));
    }
    scene
}

/// Whether every truth rule holds for every object of `scene` (the oracle).
pub(super) fn oracle(scene: &Scene, truth: &RuleSet, contact: rccpack::relations::Contact) -> bool {
    evaluate(scene, truth, contact)
        .rules
        .iter()
        .all(|r| r.satisfied == r.subjects)
}

/// The question loop on `h` under `priors` with the truth as the oracle.
pub(super) fn ask_outcome(
    h: &HeldOut,
    priors: Option<Arc<Priors>>,
    cfg: &PriorsBenchConfig,
) -> Result<AskOutcome, PriorsBenchError> {
    let contact = cfg.params.contact;
    let stream = h.task.stream;
    let fail = |e: rccpack::ask::AskError| PriorsBenchError::Ask {
        stream,
        message: e.to_string(),
    };
    let opts = AskOptions {
        learn: cfg.learn_params(),
        probe: ProbeOptions {
            contact,
            solve_time: None,
            ..ProbeOptions::default()
        },
        budget: QuestionBudget {
            wall: None,
            ..QuestionBudget::default()
        },
        priors,
        groups: cfg.ask_groups,
        ..AskOptions::default()
    };
    let mut asker = Asker::new(
        problem_scene(&h.task),
        h.task.demos.clone(),
        None,
        Vec::new(),
        opts,
    )
    .map_err(fail)?;
    let before = h.score(asker.held(), contact);
    let mut capped = false;
    while let Some(q) = asker.next_question().map_err(fail)? {
        if asker.progress().asked >= cfg.max_questions {
            capped = true;
            break;
        }
        let accepted = oracle(&q.probe.scene, &h.task.truth, contact);
        asker.answer(&q, accepted).map_err(fail)?;
    }
    Ok(AskOutcome {
        questions: asker.progress().asked,
        capped,
        before,
        after: h.score(asker.held(), contact),
    })
}
