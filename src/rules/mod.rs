//! The `.rcc` rule language (docs/language.md#syntax): AST, parser, semantic checks,
//! pretty-printer and diagnostics.
//!
//! The grammar in `grammar/rcc.pest` is the single source of truth for the
//! syntax. The parser does no I/O: callers pass the text and, for
//! diagnostics, a file name.

mod ast;
mod check;
mod diagnostic;
mod parser;
mod printer;
mod syntax_errors;

pub use ast::{
    Atom, Formula, Quant, Rule, RuleOrigin, RuleSet, Scope, Shape, ShapeKind, Span, Strength,
    Target,
};
pub use check::{
    absent_classes_note, check_classes, check_classes_across, check_landmarks, missing_classes,
    missing_classes_note, rules_needing,
};
pub use diagnostic::{Diagnostic, DiagnosticKind, RulesError};
pub use parser::parse_rules;
pub use printer::{format_number, print_formula, print_rule, print_rules};
