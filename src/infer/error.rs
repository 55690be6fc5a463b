//! Why learning cannot run.

use crate::rules::Span;
use crate::scene::SceneError;

/// Why learning cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InferError {
    /// A parameter is out of its range.
    #[error("learning parameter `{param}` is {value}; expected {expected}")]
    BadParameter {
        /// The parameter's name, as in [`LearnParams`](super::LearnParams) (`samples`,
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
    /// A demonstration breaks docs/scenes.md#geometry.
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
    /// Demonstrations with different grids.
    #[error("demonstration [{demo}] has grid {found}, but demonstration [0] has grid {expected}; all demonstrations must share one grid")]
    GridMismatch {
        /// Index of the first demonstration that differs.
        demo: usize,
        /// Grid of demonstration 0.
        expected: i64,
        /// Grid of demonstration `demo`.
        found: i64,
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
    /// Learning was cancelled ([`learn_with`](super::learn_with)'s stop: the studio's client
    /// left, or a newer request replaced it).
    #[error("learning was cancelled; nothing was learned")]
    Cancelled,
}
