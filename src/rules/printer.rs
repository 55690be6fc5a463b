//! Pretty-printer whose output re-parses to the same rule set.
//!
//! Default target quantifiers are written implicitly (`DR_N(B, R)`, not
//! `DR_N(B, every R)`), so a first-edition rule set prints as it always did;
//! a scene-level rule prints its scope `Q A: ` before the formula.

use super::{Formula, Rule, RuleSet, Scope, Strength};

/// Formulas whose one-line form is longer than this are wrapped: each
/// top-level disjunct after the first goes on a continuation line.
const WRAP_WIDTH: usize = 100;

/// Format a float so that it re-parses to the same value.
///
/// Uses plain notation for 1e-4 ≤ |v| < 1e15 and exponent notation
/// otherwise; both are Rust's shortest round-trip forms.
pub fn format_number(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || ((1e-4..1e15).contains(&a)) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Operator precedence: `|` < `&` < `!`/atoms.
fn prec(f: &Formula) -> u8 {
    match f {
        Formula::Or(v) if v.len() != 1 => 1,
        Formula::And(v) if v.len() != 1 => 2,
        _ => 3,
    }
}

fn write_formula(f: &Formula, out: &mut String) {
    match f {
        Formula::Atom(a) => out.push_str(&a.to_string()),
        Formula::Shape(sh) => out.push_str(&sh.to_string()),
        Formula::Turned(c) => {
            out.push_str("turned(");
            out.push_str(c);
            out.push(')');
        }
        Formula::Not(g) => {
            out.push('!');
            write_operand(g, 3, out);
        }
        Formula::And(v) => write_nary(v, " & ", 2, out),
        Formula::Or(v) => write_nary(v, " | ", 1, out),
    }
}

fn write_nary(v: &[Formula], sep: &str, p: u8, out: &mut String) {
    if v.is_empty() {
        // Not produced by the parser; print something that re-parses to
        // an error rather than silently to another formula.
        out.push_str("()");
        return;
    }
    for (i, g) in v.iter().enumerate() {
        if i > 0 {
            out.push_str(sep);
        }
        // Same-operator children get parentheses so the structure is kept
        // visible (the parser flattens them anyway).
        write_operand(g, p + 1, out);
    }
}

fn write_operand(g: &Formula, min_prec: u8, out: &mut String) {
    if prec(g) < min_prec {
        out.push('(');
        write_formula(g, out);
        out.push(')');
    } else {
        write_formula(g, out);
    }
}

/// Print a formula with minimal parentheses.
pub fn print_formula(f: &Formula) -> String {
    let mut out = String::new();
    write_formula(f, &mut out);
    out
}

fn strength_text(s: &Strength) -> Option<String> {
    match *s {
        Strength::Weight(1.0) => None,
        Strength::Weight(w) => Some(format!("weight {}", format_number(w))),
        Strength::P(p) => Some(format!("p {}", format_number(p))),
        Strength::Hard => Some("hard".to_string()),
    }
}

/// Print one rule (comments first, as `# ` lines).
pub fn print_rule(r: &Rule) -> String {
    let mut out = String::new();
    for c in &r.comments {
        for line in c.split('\n') {
            let line = line.trim_end_matches('\r');
            if line.is_empty() {
                out.push_str("#\n");
            } else {
                out.push_str("# ");
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    let mut head = match strength_text(&r.strength) {
        Some(m) => format!("rule {} {m}: ", r.name),
        None => format!("rule {}: ", r.name),
    };
    // `Scope::Each` is the ordinary rule: no `every A:` is written.
    if let Scope::Scene(q) = r.scope {
        head.push_str(&format!("{q} {}: ", r.formula.subject()));
    }
    out.push_str(&head);
    let one_line = print_formula(&r.formula);
    match &r.formula {
        Formula::Or(v) if v.len() > 1 && head.len() + one_line.len() > WRAP_WIDTH => {
            let indent = " ".repeat(head.len().saturating_sub(2).min(40));
            for (i, g) in v.iter().enumerate() {
                if i > 0 {
                    out.push('\n');
                    out.push_str(&indent);
                    out.push_str("| ");
                }
                write_operand(g, 2, &mut out);
            }
        }
        _ => out.push_str(&one_line),
    }
    out.push('\n');
    out
}

/// Print a rule set.
pub fn print_rules(r: &RuleSet) -> String {
    r.rules.iter().map(print_rule).collect()
}
