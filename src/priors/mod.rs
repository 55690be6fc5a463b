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
//! Per task: [`crate::task::library::task_counts`] (reads `demos.json` and
//! `learned.rcc`) or the pure [`estimate::task_counts`]. For a library:
//! [`crate::task::library::library`] (streams the folders over rayon's
//! threads; the same bytes on any number of threads) or [`combine`] on counts gathered
//! elsewhere: [`TaskCounts::to_json`] / [`TaskCounts::from_json`] carry one
//! task's counts as plain data ([`counts`]; Python's `task_counts` /
//! `combine_priors`, a Dask cluster).
//! [`Priors::to_json`] / [`Priors::from_json`] write and read the file
//! ([`mod@file`]).

pub mod counts;
pub mod estimate;
pub mod file;

// What learning consumes lives below it, in `infer`; its public paths stay
// here.
pub use crate::infer::priors::{apply, kind, KindEntry, PriorParams, Priors, StatementPrior};
pub use apply::{PriorsUsed, RuledOut};
pub use counts::{counts_from_json_list, COUNTS_VERSION};
pub use estimate::{combine, task_counts, Count, TaskCounts};
pub use kind::{Kind, Role};

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
}

impl PriorsError {
    pub(crate) fn field(field: &str, message: String) -> PriorsError {
        PriorsError::Field {
            field: field.to_string(),
            message,
        }
    }
}
