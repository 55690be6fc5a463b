//! Suspects (docs/guide.md#questions-about-suspects): the question whether
//! a demonstration that breaks rules the others keep is as the person
//! meant it, and learning with the answers — a slip sure, meant
//! demonstrations' exceptions no longer allowed.

use super::{AskOptions, Asker, Question};
use crate::ask::answers::Answer;
use crate::infer::{InferError, Learned};
use crate::rules::RuleSet;
use crate::scene::Scene;
use serde::Serialize;
use std::collections::BTreeSet;

/// What a question about a suspect demonstration asks about.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct SuspectQuestion {
    /// The demonstration's index in `demos.json`.
    pub demonstration: usize,
    /// Its block likeliest a slip (outlined in the picture): one block.
    pub objects: Vec<String>,
    /// Every rule it breaks that the other demonstrations keep.
    pub breaks: Vec<String>,
}

/// The demonstrations answered as slips and as meant in `answers`.
pub(super) fn suspect_answers(answers: &[Answer]) -> (BTreeSet<usize>, BTreeSet<usize>) {
    let mut slipped = BTreeSet::new();
    let mut meant = BTreeSet::new();
    for a in answers {
        if let Some(s) = &a.suspect {
            if a.accepted {
                meant.insert(s.demonstration);
            } else {
                slipped.insert(s.demonstration);
            }
        }
    }
    (slipped, meant)
}

/// Learn as the session learns: with the session's priors, the likeliest
/// slip of each demonstration answered as holding one sure, and no
/// exception in one answered as meant.
pub(super) fn learn_session(
    demos: &[Scene],
    statements: Option<&RuleSet>,
    opts: &AskOptions,
    slipped: &BTreeSet<usize>,
    meant: &BTreeSet<usize>,
) -> Result<Learned, InferError> {
    let slipped: Vec<usize> = slipped.iter().copied().collect();
    let meant: Vec<usize> = meant.iter().copied().collect();
    // The flag that stops the probe searches stops learning too.
    let stop = crate::stop::Stop::never().cancel_with(opts.probe.stop.cancel_flag().cloned());
    crate::infer::learn_with(
        demos,
        statements,
        &opts.learn,
        &crate::infer::LearnOptions {
            priors: opts.priors.as_deref(),
            stop,
            slipped: &slipped,
            meant: &meant,
        },
    )
}

impl Asker {
    /// The first question about a suspect (docs/guide.md#slips): the
    /// demonstration with the most rules held with an exception there, not
    /// answered about yet; `None` when there is none (always with a slip
    /// rate of 0).
    pub(super) fn suspect_question(&self) -> Option<Question> {
        let suspects = self.learned.suspects();
        let first = suspects.iter().find(|s| {
            !self.meant.contains(&s.demonstration) && !self.slipped.contains(&s.demonstration)
        })?;
        let d = first.demonstration;
        let mut objects: Vec<String> = Vec::new();
        let mut breaks: Vec<String> = Vec::new();
        for s in suspects.iter().filter(|s| s.demonstration == d) {
            if !s.object.is_empty() && !objects.contains(&s.object) {
                objects.push(s.object.clone());
            }
            for b in &s.breaks {
                if !breaks.contains(b) {
                    breaks.push(b.clone());
                }
            }
        }
        let rule = breaks.first()?.clone();
        let stmt = self.learned.statements.iter().find(|s| s.name == rule)?;
        Some(Question {
            rule,
            statement: crate::infer::statement_text(stmt.scope, &stmt.formula),
            english: stmt.english.clone(),
            probe: crate::ask::probe::Probe {
                rule: stmt.name.clone(),
                scene: self.demos.get(d)?.clone(),
                broken: objects.clone(),
                cost: 0,
                time_ms: 0.0,
                edit: None,
            },
            also_broken: breaks[1..].to_vec(),
            group: Vec::new(),
            suspect: Some(SuspectQuestion {
                demonstration: d,
                objects,
                breaks,
            }),
        })
    }

    /// The demonstrations answered as holding a slip.
    pub fn slipped(&self) -> impl Iterator<Item = usize> + '_ {
        self.slipped.iter().copied()
    }
}
