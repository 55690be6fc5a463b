//! Questions (SPEC §13): confirm or drop learned rules by showing the person
//! probe layouts.
//!
//! - `probe`: the layout that breaks one held rule and keeps the others
//!   (built from the language: the other rules hard, the rule's negation
//!   hard), or the proof that none exists;
//! - `session`: the question loop without I/O — which rule next, what an
//!   answer does ([`Asker`]); the command line (`rccpack ask`) and the
//!   studio save what it returns.

mod probe;
mod session;

pub use probe::{
    find_probe, negation, probe_rules, Probe, ProbeOptions, ProbeOutcome, DEFAULT_CHECK_NODES,
    DEFAULT_PROBE_NODES,
};
pub use session::{
    Answer, AnswersFile, AnswersFileError, AskError, AskOptions, Asker, Question, Tally, CONFIRMED,
};
