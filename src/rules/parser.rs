//! The pest parser over `grammar/rcc.pest`.
//!
//! Parsing runs in three stages, none of which can panic or overflow the
//! stack on any input:
//!
//! 1. an iterative scan rejects parenthesis nesting deeper than
//!    [`MAX_DEPTH`] before pest (which recurses per `(`) sees the text;
//! 2. pest parses the text; its errors are turned into user messages
//!    (grammar rule names are renamed to what a user would type);
//! 3. for each rule the nesting depth (parentheses and `!`) is measured
//!    iteratively over the token stream, and only then is the formula built
//!    by recursion; finally the semantic checks run (relation names, one
//!    subject class per rule, or the scene scope's class; quantifier counts;
//!    no quantifier before a landmark; unique names, modifier ranges).

use super::diagnostic::{Diagnostic, DiagnosticKind, LineIndex};
use super::{
    Formula, Quant, Rule, RuleOrigin, RuleSet, RulesError, Scope, Shape, ShapeKind, Span, Strength,
};
use crate::relations::MAX_COUNT;
use pest::iterators::Pair;
use pest::Parser as _;
use std::collections::HashMap;

/// The deepest nesting of parentheses and negations a formula may have.
pub(super) const MAX_DEPTH: usize = 256;

#[allow(missing_docs)]
pub(super) mod grammar {
    /// The parser generated from `grammar/rcc.pest`.
    #[derive(pest_derive::Parser)]
    #[grammar = "grammar/rcc.pest"]
    pub(super) struct RccParser;
}

use super::syntax_errors::{paren_depth_check, pest_diagnostic, token_depth_check};
use formula::Builder;
use grammar::{RccParser, Rule as R};

mod formula;

/// Parse and check `.rcc` text (syntax, one subject per rule, unique names,
/// modifier ranges).
pub fn parse_rules(src: &str) -> Result<RuleSet, RulesError> {
    if src.len() > crate::limits::MAX_RULES_BYTES {
        return Err(RulesError::new(vec![Diagnostic::new(
            DiagnosticKind::TooLarge,
            Span::new(0, 0),
            format!(
                "the rule text is {} bytes; expected at most {} bytes (16 MiB)",
                src.len(),
                crate::limits::MAX_RULES_BYTES
            ),
        )]));
    }
    if let Some(d) = paren_depth_check(src) {
        return Err(RulesError::new(vec![d]));
    }
    let mut pairs = match RccParser::parse(R::file, src) {
        Ok(p) => p,
        Err(e) => return Err(RulesError::new(vec![pest_diagnostic(src, &e)])),
    };
    let Some(file) = pairs.next() else {
        return Err(RulesError::new(vec![Diagnostic::new(
            DiagnosticKind::Syntax,
            Span::new(0, 0),
            "empty parse",
        )]));
    };
    let mut diags = Vec::new();
    let mut rules = Vec::new();
    let mut seen: HashMap<String, Span> = HashMap::new();
    let mut lines: Option<LineIndex> = None;
    for pair in file.into_inner() {
        if pair.as_rule() != R::rule_def {
            continue;
        }
        if let Some(d) = token_depth_check(&pair) {
            diags.push(d);
            continue;
        }
        let before = diags.len();
        let rule = build_rule(pair, &mut diags);
        if let Some(rule) = rule {
            let origin = rule.origin.as_ref().map(|o| o.name).unwrap_or_default();
            if let Some(first) = seen.get(&rule.name) {
                let index = lines.get_or_insert_with(|| LineIndex::new(src));
                let (line, _) = index.line_col(src, first.start);
                diags.push(
                    Diagnostic::new(
                        DiagnosticKind::DuplicateName,
                        origin,
                        format!(
                            "duplicate rule name `{}`: it is already defined on line {line}",
                            crate::limits::cut(&rule.name)
                        ),
                    )
                    .with_related(*first, "first defined here"),
                );
            } else {
                seen.insert(rule.name.clone(), origin);
            }
            if diags.len() == before {
                rules.push(rule);
            }
        }
    }
    if diags.is_empty() {
        Ok(RuleSet::new(rules))
    } else {
        diags.sort_by_key(|d| (d.span.start, d.span.end));
        Err(RulesError::new(diags))
    }
}

/// Stage 1: parenthesis depth over the raw text (comments skipped). An
/// atom's own `(` adds one level, so the limit here is one above
/// [`MAX_DEPTH`]; stage 3 measures the exact depth.
fn span_of(p: &Pair<'_, R>) -> Span {
    let s = p.as_span();
    Span::new(s.start(), s.end())
}

/// Stage 3b: build one rule and run the per-rule checks.
fn build_rule(pair: Pair<'_, R>, diags: &mut Vec<Diagnostic>) -> Option<Rule> {
    let whole = span_of(&pair);
    let mut name = None;
    let mut strength = Strength::default();
    let mut modifier_span = None;
    let mut body = Body::default();
    for p in pair.into_inner() {
        match p.as_rule() {
            R::name => name = Some((p.as_str().to_string(), span_of(&p))),
            R::modifier => {
                modifier_span = Some(span_of(&p));
                match modifier(p) {
                    Ok(s) => strength = s,
                    Err(d) => diags.push(d),
                }
            }
            R::body => body.read(p, diags),
            _ => {}
        }
    }
    let (name, name_span) = name?;
    let formula = body.formula.take()?;
    body.check_subjects(&name, diags);
    let rule = Rule {
        name,
        strength,
        scope: body.scope,
        formula,
        comments: Vec::new(),
        origin: Some(RuleOrigin {
            span: whole,
            name: name_span,
            modifier: modifier_span,
            atoms: body.atom_spans,
            scope: body.scope_span,
        }),
    };
    // A rule with errors still takes part in the duplicate-name check; the
    // caller drops it since diagnostics were recorded.
    Some(rule)
}

/// What a rule's body says: its scope, its formula, and where its atoms and
/// subjects are written.
#[derive(Default)]
struct Body {
    scope: Scope,
    /// A scene scope's quantifier as written and its class.
    scope_written: Option<(String, String)>,
    scope_span: Option<Span>,
    formula: Option<Formula>,
    atom_spans: Vec<Span>,
    subjects: Vec<(String, Span)>,
}

impl Body {
    /// Read a `body` pair: a scene scope, then a group statement or a formula.
    fn read(&mut self, p: Pair<'_, R>, diags: &mut Vec<Diagnostic>) {
        for b in p.into_inner() {
            match b.as_rule() {
                R::scope => {
                    self.scope_span = Some(span_of(&b));
                    if let Some((q, written, class)) = scene_scope(b, diags) {
                        self.scope = Scope::of(q);
                        if let Some(class) = class {
                            self.scope_written = Some((written, class));
                        }
                    }
                }
                R::shape_stmt => {
                    self.scope = Scope::Group;
                    // A group statement has no atoms; its span
                    // stands where the atoms' would.
                    self.atom_spans.push(span_of(&b));
                    self.formula = shape_stmt(b, &mut self.subjects, diags);
                }
                R::formula => {
                    let mut builder = Builder {
                        atoms: &mut self.atom_spans,
                        subjects: &mut self.subjects,
                        diags,
                    };
                    self.formula = b.into_inner().next().map(|d| builder.disjunction(d));
                }
                _ => {}
            }
        }
    }

    /// One subject class per rule: the scene scope's class, or else the
    /// first atom's.
    fn check_subjects(&self, name: &str, diags: &mut Vec<Diagnostic>) {
        let subjects = &self.subjects;
        if let Some((written, class)) = &self.scope_written {
            // A scene scope fixes the subject class of every atom.
            if let Some((other, span)) = subjects.iter().find(|(s, _)| s != class) {
                diags.push(Diagnostic::new(DiagnosticKind::MixedSubjects,
                    *span,
                    format!(
                        "rule `{name}` is about `{class}` (`{written} {class}:`), but this atom is about `{other}`: expected every atom's subject to be `{class}`"
                    ),
                ));
            }
        } else if let Some((first, _)) = subjects.first() {
            // One subject class per rule.
            if let Some((other, span)) = subjects.iter().find(|(s, _)| s != first) {
                diags.push(Diagnostic::new(DiagnosticKind::MixedSubjects,
                    *span,
                    format!(
                        "rule `{name}` mixes subject classes: this atom is about `{other}`, but the rule's first atom is about `{first}`"
                    ),
                ));
            }
        }
    }
}

/// A group statement `[!]SHAPE(CLASS)`: its formula (a shape under as many
/// `Not`s as written). The class is recorded in `subjects`; `*` and `@ID`
/// are reported.
fn shape_stmt(
    p: Pair<'_, R>,
    subjects: &mut Vec<(String, Span)>,
    diags: &mut Vec<Diagnostic>,
) -> Option<Formula> {
    let mut nots = 0usize;
    let mut kind = None;
    let mut class = None;
    for c in p.into_inner() {
        match c.as_rule() {
            R::not_op => nots += 1,
            R::shape_kw => kind = ShapeKind::from_name(c.as_str()),
            R::subject => {
                let span = span_of(&c);
                match subject_kind(c) {
                    Subject::Class(name) => {
                        subjects.push((name.clone(), span));
                        class = Some(name);
                    }
                    Subject::Other(text, _, landmark) => {
                        let why = if landmark {
                            "a group statement is about the objects of one class, not a landmark"
                        } else {
                            "a group statement is about the objects of one class"
                        };
                        diags.push(Diagnostic::new(
                            DiagnosticKind::Syntax,
                            span,
                            format!("expected a class name in the group statement, found `{text}`: {why}"),
                        ));
                    }
                }
            }
            _ => {}
        }
    }
    let mut f = Formula::Shape(Shape::new(kind?, class?));
    for _ in 0..nots {
        f = Formula::not(f);
    }
    Some(f)
}

/// A scene scope `Q A:`: the quantifier (when valid), how it was written and
/// the class (when it is one). Problems are pushed to `diags`.
fn scene_scope(
    p: Pair<'_, R>,
    diags: &mut Vec<Diagnostic>,
) -> Option<(Quant, String, Option<String>)> {
    let mut q = None;
    let mut written = String::new();
    let mut class = None;
    for c in p.into_inner() {
        match c.as_rule() {
            R::quant => {
                written = written_text(c.as_str());
                match quant(c) {
                    Ok(v) => q = Some(v),
                    Err(d) => diags.push(d),
                }
            }
            R::subject => match subject_kind(c) {
                Subject::Class(s) => class = Some(s),
                Subject::Other(text, span, landmark) => {
                    let why = if landmark {
                        "a scene scope counts the objects of one class, not a landmark"
                    } else {
                        "a scene scope counts the objects of one class"
                    };
                    diags.push(Diagnostic::new(
                        DiagnosticKind::BadScope,
                        span,
                        format!("expected a class name after `{written}`, found `{text}`: {why}"),
                    ));
                }
            },
            _ => {}
        }
    }
    Some((q?, written, class))
}

/// What a `subject` pair names.
enum Subject {
    /// A class name.
    Class(String),
    /// `*` or `@ID` (text, span, whether a landmark).
    Other(String, Span, bool),
}

fn subject_kind(p: Pair<'_, R>) -> Subject {
    let span = span_of(&p);
    let text = p.as_str().to_string();
    match p.into_inner().next().map(|c| c.as_rule()) {
        Some(R::class) => Subject::Class(text),
        Some(R::landmark) => Subject::Other(text, span, true),
        _ => Subject::Other(text, span, false),
    }
}

/// The span of a quantifier's words and count, without the whitespace that
/// `every`/`some`/`no`'s lookahead skipped.
fn words_span(p: &Pair<'_, R>) -> Span {
    let start = p.as_span().start();
    let end = p
        .clone()
        .into_inner()
        .last()
        .map_or(p.as_span().end(), |c| c.as_span().end());
    Span::new(start, end)
}

/// Text as written with whitespace runs collapsed, shortened when long.
fn written_text(s: &str) -> String {
    let joined = s.split_whitespace().collect::<Vec<_>>().join(" ");
    shorten(&joined)
}

/// At most [`SHOWN`] characters of `s` (with `…` when cut).
fn shorten(s: &str) -> String {
    if s.chars().count() <= SHOWN {
        s.to_string()
    } else {
        let mut out: String = s.chars().take(SHOWN - 4).collect();
        out.push('…');
        out
    }
}

/// The longest bad value quoted in full in a message.
const SHOWN: usize = 24;

/// A quantifier pair: `every`, `some`, `no`, `at least K`, `at most K`.
fn quant(p: Pair<'_, R>) -> Result<Quant, Diagnostic> {
    let whole = span_of(&p);
    let mut least = true;
    let mut count = None;
    for c in p.into_inner() {
        match c.as_rule() {
            R::kw_every => return Ok(Quant::Every),
            R::kw_some => return Ok(Quant::Some),
            R::kw_no => return Ok(Quant::No),
            R::kw_least => least = true,
            R::kw_most => least = false,
            R::count => count = Some(c),
            _ => {}
        }
    }
    let words = if least { "at least" } else { "at most" };
    let Some(c) = count else {
        // The grammar requires a count; kept as an error, not a panic.
        return Err(Diagnostic::new(
            DiagnosticKind::BadCount,
            whole,
            format!("missing count after `{words}`: expected a whole number from 0 to {MAX_COUNT}"),
        ));
    };
    let k = parse_count(c.as_str(), words)
        .map_err(|m| Diagnostic::new(DiagnosticKind::BadCount, span_of(&c), m))?;
    Ok(if least {
        Quant::AtLeast(k)
    } else {
        Quant::AtMost(k)
    })
}

/// `K` of `at least K` / `at most K`: decimal digits, at most
/// [`MAX_COUNT`]. Never overflows, whatever the length.
fn parse_count(text: &str, words: &str) -> Result<u32, String> {
    if text.is_empty() || !text.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!(
            "bad count `{}` after `{words}`: expected a whole number in decimal digits, such as `{words} 2`",
            shorten(text)
        ));
    }
    let significant = text.trim_start_matches('0');
    let value = if significant.len() > 5 {
        None
    } else if significant.is_empty() {
        Some(0)
    } else {
        significant.parse::<u32>().ok().filter(|v| *v <= MAX_COUNT)
    };
    value.ok_or_else(|| {
        let shown = if text.len() > SHOWN {
            format!("`{}` ({} digits)", shorten(text), text.len())
        } else {
            format!("`{text}`")
        };
        format!(
            "count {shown} after `{words}` is too large: expected a whole number from 0 to {MAX_COUNT}"
        )
    })
}

fn modifier(p: Pair<'_, R>) -> Result<Strength, Diagnostic> {
    let Some(m) = p.into_inner().next() else {
        return Ok(Strength::default());
    };
    let kind = m.as_rule();
    if kind == R::hard_mod {
        return Ok(Strength::Hard);
    }
    let Some(num) = m.into_inner().find(|q| q.as_rule() == R::number) else {
        return Ok(Strength::default());
    };
    let span = span_of(&num);
    let text = crate::limits::cut(num.as_str());
    let v: f64 = match num.as_str().parse() {
        Ok(v) => v,
        Err(_) => {
            return Err(Diagnostic::new(
                DiagnosticKind::BadNumber,
                span,
                format!("bad number `{text}`"),
            ));
        }
    };
    if kind == R::weight_mod {
        if !v.is_finite() {
            Err(Diagnostic::new(
                DiagnosticKind::BadWeight,
                span,
                format!("bad weight `{text}`: it is not finite; expected a finite number > 0"),
            ))
        } else if v <= 0.0 {
            Err(Diagnostic::new(
                DiagnosticKind::BadWeight,
                span,
                format!("bad weight `{text}`: expected a finite number > 0"),
            ))
        } else {
            Ok(Strength::Weight(v))
        }
    } else if !v.is_finite() {
        Err(Diagnostic::new(
            DiagnosticKind::BadProbability,
            span,
            format!("bad p `{text}`: it is not finite; expected a number with 0 < p < 1"),
        ))
    } else if v <= 0.0 || v >= 1.0 {
        Err(Diagnostic::new(
            DiagnosticKind::BadProbability,
            span,
            format!("bad p `{text}`: expected a number with 0 < p < 1"),
        ))
    } else {
        Ok(Strength::P(v))
    }
}
