//! Questions (docs/guide.md#questions): confirm or drop learned rules by showing the person
//! probe layouts.
//!
//! - `probe`: the layout that breaks one held rule and keeps the others
//!   (built from the language: the other rules hard, the rule's negation
//!   hard), or the proof that none exists;
//! - `edit`: probes that are a demonstration with one or two objects
//!   moved (the cheapest to find, the easiest to judge);
//! - `budget`: the node budget every question is produced under;
//! - `lookahead`: the next question for both answers, computed while the
//!   person looks;
//! - `answers`: the `answers.json` journal;
//! - `session`: the question loop without I/O — which rule next, what an
//!   answer does ([`Asker`]); the command line (`rccpack ask`) and the
//!   studio save what it returns.

mod answers;
mod budget;
mod checker;
mod edit;
mod lookahead;
mod probe;
mod session;

pub use budget::{QuestionBudget, DEFAULT_QUESTION_NODES, DEFAULT_QUESTION_WALL};
pub use edit::{Edit, Moved};
pub use lookahead::Lookahead;

pub use answers::{Answer, AnswersFile, AnswersFileError, SuspectAnswer, CONFIRMED};
pub use probe::{
    find_probe, group_probe_rules, negation, probe_rules, Probe, ProbeOptions, ProbeOutcome,
    DEFAULT_CHECK_NODES, DEFAULT_PROBE_NODES,
};
pub use session::{AskError, AskOptions, Asked, Asker, Question, SuspectQuestion, Tally, Unasked};
