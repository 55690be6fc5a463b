//! `answers.json`: the journal of a question session — every answered
//! question with its probe, written before the demonstrations and the
//! rules it changes — and the comment that marks a confirmed rule.

use super::edit::Edit;
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

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
    /// When the question asked whether a demonstration that looks like a
    /// slip is as the person meant it (`probe` is that demonstration):
    /// which one and the rules it breaks. Accepted: it is meant, and the
    /// rules it breaks are dropped; rejected: its likeliest slip is a slip
    /// for sure, so it no longer counts against the rules it breaks (it
    /// stays in `demos.json`), and those rules are confirmed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub suspect: Option<SuspectAnswer>,
    /// For a group question (docs/guide.md#questions): every rule the
    /// probe was chosen to break, `rule` first. Accepted: all are dropped;
    /// rejected: at least one is meant, and the session narrows the group
    /// down. Empty for a question about one rule.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub group: Vec<String>,
}

impl Answer {
    /// The rules the question asked about: its group, or its one rule.
    pub fn asked(&self) -> Vec<&str> {
        if self.group.is_empty() {
            vec![self.rule.as_str()]
        } else {
            self.group.iter().map(String::as_str).collect()
        }
    }
}

/// The demonstration a suspect question asked about, in `answers.json`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuspectAnswer {
    /// Its index in `demos.json`.
    pub demonstration: usize,
    /// The learned rules it breaks (the others keep them).
    pub breaks: Vec<String>,
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
