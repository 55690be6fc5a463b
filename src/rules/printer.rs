//! Pretty-printer whose output re-parses to the same rule set.

use super::{Formula, Rule, RuleSet};

/// Format a float so that it re-parses to the same value.
pub fn format_number(_v: f64) -> String {
    todo!("parser helper")
}
/// Print a formula with minimal parentheses.
pub fn print_formula(_f: &Formula) -> String {
    todo!("parser helper")
}
/// Print one rule (comments first, as `# ` lines).
pub fn print_rule(_r: &Rule) -> String {
    todo!("parser helper")
}
/// Print a rule set.
pub fn print_rules(_r: &RuleSet) -> String {
    todo!("parser helper")
}
