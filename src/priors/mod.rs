//! Priors learned across tasks (thesis §5.2.1 and §5.2.3).
//!
//! # Background
//!
//! Learning gives every candidate the same prior. A library of finished
//! task folders says more: some *kinds* of statement (see [`kind`]) are
//! kept as rules again and again, others never. [`combine`] turns the
//! library's counts into a prior per kind, shrunk towards its parent kind
//! (empirical Bayes, see [`estimate`]), and rules out kinds that were
//! candidates in many tasks and never kept. [`crate::infer::learn_with`]
//! uses them: a generated statement's prior of *not* being intended is
//! `1 − prior(kind)`, and a ruled-out kind is left out of the statements.
//!
//! Statements given by the user (`statements.rcc`) have no template and so
//! no kind: they keep the uniform prior (`LearnParams::prior`) and are
//! never ruled out.
//!
//! # Practical
//!
//! Per task: [`folder::task_counts`] (reads `demos.json` and `learned.rcc`)
//! or the pure [`estimate::task_counts`]. For a library:
//! [`folder::library`] (streams the folders over rayon's threads; the same
//! bytes on any number of threads) or [`combine`] on counts gathered
//! elsewhere: [`TaskCounts::to_json`] / [`TaskCounts::from_json`] carry one
//! task's counts as plain data ([`counts`]; Python's `task_counts` /
//! `combine_priors`, a Dask cluster).
//! [`Priors::to_json`] / [`Priors::from_json`] write and read the file
//! ([`mod@file`]).

pub mod apply;
pub mod counts;
pub mod estimate;
pub mod file;
pub mod folder;
pub mod kind;

pub use apply::{PriorsUsed, RuledOut};
pub use counts::{counts_from_json_list, COUNTS_VERSION};
pub use estimate::{combine, task_counts, Count, PriorParams, TaskCounts};
pub use file::KindEntry;
pub use kind::{Kind, Role};

/// Priors per kind, from a library of tasks.
#[derive(Debug, Clone, PartialEq)]
pub struct Priors {
    /// The estimator's parameters and the candidates' template set and
    /// contact mode.
    pub params: PriorParams,
    /// Tasks in the library.
    pub tasks: u64,
    /// Hash of the library's inputs (order-independent).
    pub inputs: u64,
    /// Every node of the hierarchy seen in the library (the root first),
    /// sorted by key.
    pub kinds: Vec<KindEntry>,
}

/// Why priors cannot be read or made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PriorsError {
    /// A field of the priors file has a bad value.
    #[error("priors file: field `{field}` {message}")]
    Field {
        /// The field's path (`version`, `kinds[3].prior`, `hash`, …).
        field: String,
        /// What is wrong, naming the value.
        message: String,
    },
    /// The priors file is not valid JSON of the expected shape.
    #[error("priors file: {}{message}", if field.is_empty() || field == "." { String::new() } else { format!("field `{field}`: ") })]
    Json {
        /// The field's path, where known.
        field: String,
        /// The parser's message.
        message: String,
    },
    /// A field of a task's counts as plain data ([`counts`]) has a bad
    /// value.
    #[error("task counts: field `{field}` {message}")]
    Counts {
        /// The field's path (`counts[2].templates`, `kinds.….kept`, …).
        field: String,
        /// What is wrong, naming the value.
        message: String,
    },
    /// A task's counts are not valid JSON of the expected shape.
    #[error("task counts: {}{message}", if field.is_empty() { String::new() } else { format!("field `{field}`: ") })]
    CountsJson {
        /// The field's path, where known.
        field: String,
        /// The parser's message.
        message: String,
    },
    /// A task folder of the library cannot be read or counted.
    #[error("task {}: {source}", dir.display())]
    Task {
        /// The folder.
        dir: std::path::PathBuf,
        /// Why.
        source: Box<crate::task::TaskError>,
    },
}

impl PriorsError {
    pub(crate) fn field(field: &str, message: String) -> PriorsError {
        PriorsError::Field {
            field: field.to_string(),
            message,
        }
    }
}

/// The prior a learning run gave one statement, and where it came from.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StatementPrior {
    /// The probability that the statement is intended (`1 − π`).
    pub prior: f64,
    /// The statement's kind (`None`: a given statement, no template).
    pub kind: Option<String>,
    /// The node of the priors file that gave the prior (the kind itself or
    /// an ancestor); `None` for a given statement (the uniform prior).
    pub from: Option<String>,
}
