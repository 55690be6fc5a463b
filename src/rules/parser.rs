//! The pest parser over `grammar/rcc.pest`.

use super::{RuleSet, RulesError};

/// Parse and check `.rcc` text (syntax, one subject per rule, unique names,
/// modifier ranges).
pub fn parse_rules(_src: &str) -> Result<RuleSet, RulesError> {
    todo!("parser helper")
}
