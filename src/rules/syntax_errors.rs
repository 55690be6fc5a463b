//! What the `.rcc` parser says when the text is not a rule file: nesting
//! too deep (found before pest recurses, and per rule over its tokens),
//! pest's errors in words a user would type (grammar rule names renamed),
//! and a group statement written where the grammar does not take one.

use super::diagnostic::{Diagnostic, DiagnosticKind};
use super::parser::grammar::Rule as R;
use super::parser::MAX_DEPTH;
use super::{ShapeKind, Span};
use pest::error::{ErrorVariant, InputLocation};
use pest::iterators::Pair;

pub(super) fn paren_depth_check(src: &str) -> Option<Diagnostic> {
    let mut depth = 0usize;
    let mut in_comment = false;
    for (i, b) in src.bytes().enumerate() {
        match b {
            b'\n' | b'\r' => in_comment = false,
            _ if in_comment => {}
            b'#' => in_comment = true,
            b'(' => {
                depth += 1;
                if depth > MAX_DEPTH + 1 {
                    return Some(too_deep(Span::new(i, i + 1)));
                }
            }
            b')' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    None
}

fn too_deep(span: Span) -> Diagnostic {
    Diagnostic::new(
        DiagnosticKind::TooDeep,
        span,
        format!(
            "formula nested too deeply: more than {MAX_DEPTH} levels of parentheses and negations"
        ),
    )
}

/// Stage 3a: nesting depth of one rule, iteratively over its tokens.
pub(super) fn token_depth_check(rule: &Pair<'_, R>) -> Option<Diagnostic> {
    // The token walk as an explicit stack over the rule's pairs (not
    // `Pair::tokens`, which re-checks the whole file's token queue on
    // every call in debug builds: quadratic on a file of many rules).
    enum Frame<'i> {
        Enter(Pair<'i, R>),
        Exit(R, usize),
    }
    let mut depth = 0usize;
    let mut stack = vec![Frame::Enter(rule.clone())];
    while let Some(frame) = stack.pop() {
        match frame {
            Frame::Enter(p) => {
                let r = p.as_rule();
                let saved = depth;
                if matches!(r, R::group | R::not_op) {
                    depth += 1;
                    if depth > MAX_DEPTH {
                        let s = p.as_span().start();
                        return Some(too_deep(Span::new(s, s + 1)));
                    }
                }
                stack.push(Frame::Exit(r, saved));
                let children: Vec<Pair<'_, R>> = p.into_inner().collect();
                stack.extend(children.into_iter().rev().map(Frame::Enter));
            }
            Frame::Exit(R::unary, saved) => depth = saved,
            Frame::Exit(R::group, _) => depth = depth.saturating_sub(1),
            Frame::Exit(..) => {}
        }
    }
    None
}

/// User-facing names of grammar rules, for pest's "expected ..." messages.
fn describe(r: R) -> &'static str {
    match r {
        R::EOI => "end of input",
        R::eol => "end of line",
        R::file | R::rule_def | R::kw_rule => "a rule",
        R::name => "a rule name",
        R::colon => "`:`",
        R::modifier | R::weight_mod | R::p_mod | R::hard_mod => {
            "a modifier (`weight W`, `p P` or `hard`)"
        }
        R::kw_weight => "`weight`",
        R::kw_p => "`p`",
        R::kw_hard => "`hard`",
        R::number => "a number",
        R::formula | R::disjunction | R::conjunction | R::unary => "a formula",
        R::group | R::lparen => "`(`",
        R::rparen => "`)`",
        R::or_op => "`|`",
        R::and_op => "`&`",
        R::not_op => "`!`",
        R::atom | R::relation => "a relation such as DR_N or EC_W",
        R::comma => "`,`",
        R::subject | R::class => "a class name",
        R::target | R::object => "a class name or `*`",
        R::body | R::scope => "a formula",
        R::shape_stmt | R::shape_kw => "a group statement such as column(R)",
        R::scope_colon => "`:`",
        R::any => "`*`",
        R::landmark => "a landmark `@ID`",
        R::landmark_id => "an object id right after `@`",
        R::quant | R::kw_every | R::kw_some | R::kw_no | R::kw_at => "a quantifier",
        R::kw_least => "`least`",
        R::kw_most => "`most`",
        R::count => "a count (a whole number such as 2)",
        _ => "something else",
    }
}

/// What the text holds at `pos`, for "found ..." (and the span to underline).
fn found_at(src: &str, pos: usize) -> (String, Span) {
    let rest = src.get(pos..).unwrap_or("");
    let Some(c) = rest.chars().next() else {
        return ("end of input".to_string(), Span::new(pos, pos));
    };
    if c == '\n' || c == '\r' {
        return ("end of line".to_string(), Span::new(pos, pos));
    }
    let word_len: usize = rest
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .map(char::len_utf8)
        .sum();
    let len = if word_len > 0 {
        word_len.min(64)
    } else {
        c.len_utf8()
    };
    let shown: String = rest[..len].chars().flat_map(char::escape_debug).collect();
    (format!("`{shown}`"), Span::new(pos, pos + len))
}

pub(super) fn pest_diagnostic(src: &str, e: &pest::error::Error<R>) -> Diagnostic {
    let pos = match e.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    };
    if let Some(d) = misplaced_shape(src, pos) {
        return d;
    }
    let (found, span) = found_at(src, pos);
    let message = match &e.variant {
        ErrorVariant::ParsingError { positives, .. } if !positives.is_empty() => {
            let mut names: Vec<&str> = Vec::new();
            for r in positives {
                let n = describe(*r);
                if !names.contains(&n) {
                    names.push(n);
                }
            }
            format!("expected {}, found {found}", join_or(&names))
        }
        ErrorVariant::ParsingError { .. } => format!("unexpected {found}"),
        ErrorVariant::CustomError { message } => message.to_lowercase(),
    };
    Diagnostic::new(DiagnosticKind::Syntax, span, message)
}

/// A group statement where the grammar does not take it (`(group(R))`,
/// `!(row(R))`, `some R: group(R)`, `GROUP(R)`): the text before the error
/// at `pos` ends with `KEYWORD(CLASS`, a shape keyword in any case, which
/// the parser then read as a relation missing its `,`.
fn misplaced_shape(src: &str, pos: usize) -> Option<Diagnostic> {
    let before = src.get(..pos)?;
    let is_ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let rest = before.trim_end();
    let class = rest.trim_end_matches(is_ident);
    if class.len() == rest.len() {
        return None;
    }
    let rest = class.trim_end().strip_suffix('(')?.trim_end();
    let start = rest.trim_end_matches(is_ident).len();
    let word = &rest[start..];
    let lower = word.to_ascii_lowercase();
    ShapeKind::from_name(&lower)?;
    let span = Span::new(start, rest.len());
    let message = if word != lower {
        format!(
            "unknown keyword `{word}`: the group statement keyword is lowercase, write `{lower}`"
        )
    } else {
        format!(
            "a group statement (group, row, column, block) stands alone as a rule's whole \
             formula: `{word}` cannot be parenthesised, combined with `&` or `|`, or follow \
             a scene scope such as `some R:`; write `rule NAME: {word}(CLASS)` or \
             `rule NAME: not {word}(CLASS)`"
        )
    };
    Some(Diagnostic::new(DiagnosticKind::Syntax, span, message))
}

fn join_or(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => (*one).to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}
