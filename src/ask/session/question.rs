//! What a session shows and counts: a question (about one rule, a group
//! of rules, or a demonstration that looks like a slip), why a rule was
//! not asked about, and the tally of a session.

use super::{Asker, Known, SuspectQuestion};
use crate::ask::probe::Probe;
use serde::Serialize;

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
    /// one another (see [`Asker::next_question`](super::Asker::next_question)); usually empty.
    pub also_broken: Vec<String>,
    /// For a group question (docs/guide.md#questions): every held rule the
    /// probe was chosen to break, `rule` first ("acceptable" drops them
    /// all; "not acceptable" says at least one is meant, and the next
    /// questions narrow the group down). Empty for a question about one
    /// rule.
    pub group: Vec<Asked>,
    /// `Some` when the question is whether a demonstration that looks like
    /// a slip is as the person meant it (docs/guide.md#slips): the probe is
    /// that demonstration, `probe.broken` its suspect objects, `rule` and
    /// `also_broken` the rules it breaks that the others keep.
    pub suspect: Option<SuspectQuestion>,
}

impl Question {
    /// The names of the rules of a group question (empty for one rule).
    pub fn group_names(&self) -> Vec<String> {
        self.group.iter().map(|a| a.rule.clone()).collect()
    }
}

/// One rule a group question asks about.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Asked {
    /// Its name.
    pub rule: String,
    /// Its `.rcc` text (after `rule NAME:`).
    pub statement: String,
    /// Its English reading.
    pub english: String,
}

/// Why a held rule was not asked about ([`Asker::unasked`](super::Asker::unasked)).
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
    /// Rules dropped by accepted questions about a group of rules (a
    /// sweep or a group; among `dropped`): asked in a group, not alone.
    pub dropped_in_groups: usize,
    /// Rules confirmed by rejected probes.
    pub confirmed: usize,
    /// Held rules not asked because the others imply them.
    pub implied: usize,
    /// Held rules deferred: the question budget (or a limit) stopped their
    /// check or probe search before it decided them.
    pub unknown: usize,
    /// Held rules now.
    pub held: usize,
    /// Questions about a group of rules (among `asked`).
    pub grouped: usize,
    /// Rules confirmed without a question of their own: the last rule of a
    /// rejected group that the other answers left (among `confirmed`).
    pub deduced: usize,
}

impl Asker {
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
            dropped: self
                .answers
                .iter()
                .filter(|a| a.accepted)
                .map(|a| {
                    a.suspect
                        .as_ref()
                        .map_or(a.asked().len(), |s| s.breaks.len())
                })
                .sum(),
            dropped_in_groups: self
                .answers
                .iter()
                .filter(|a| a.accepted && a.suspect.is_none())
                .map(|a| a.group.len())
                .sum(),
            confirmed: self.confirmed.len(),
            implied: count(|k| matches!(k, Known::Implied)),
            unknown: count(|k| matches!(k, Known::Unknown)),
            held: self.held.rules.len(),
            grouped: self.answers.iter().filter(|a| !a.group.is_empty()).count(),
            deduced: self.deduced.len(),
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
}
