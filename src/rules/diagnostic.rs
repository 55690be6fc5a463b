//! Located errors for `.rcc` text, rendered with a caret under the span.

use super::Span;
use ariadne::{Config, IndexType, Label, Report, ReportKind, Source};

/// Lines longer than this (in bytes) are reported without a source snippet.
const MAX_SNIPPET_LINE: usize = 10_000;

/// One located problem.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// Where.
    pub span: Span,
    /// What is wrong and what was expected (lowercase).
    pub message: String,
}

impl Diagnostic {
    /// A diagnostic at `span`.
    pub fn new(span: Span, message: impl Into<String>) -> Self {
        Diagnostic {
            span,
            message: message.into(),
        }
    }

    /// 1-based line and 1-based character column of the span's start in `src`.
    pub fn line_col(&self, src: &str) -> (usize, usize) {
        line_col(src, self.span.start)
    }
}

/// Every problem found in one `.rcc` text.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}", .diagnostics.first().map(|d| d.message.as_str()).unwrap_or("invalid rules"))]
pub struct RulesError {
    /// At least one.
    pub diagnostics: Vec<Diagnostic>,
}

/// 1-based line and 1-based character column of byte `offset` in `src`
/// (offsets past the end or inside a character are clamped).
pub(crate) fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let offset = floor_boundary(src, offset);
    let before = &src[..offset];
    let line = before.bytes().filter(|&b| b == b'\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let col = before[line_start..].chars().count() + 1;
    (line, col)
}

fn floor_boundary(src: &str, mut i: usize) -> usize {
    i = i.min(src.len());
    while !src.is_char_boundary(i) {
        i -= 1;
    }
    i
}

impl RulesError {
    /// An error from diagnostics (at least one).
    pub fn new(diagnostics: Vec<Diagnostic>) -> Self {
        RulesError { diagnostics }
    }

    /// Line and column (1-based, characters) of the first diagnostic.
    pub fn line_col(&self, src: &str) -> (usize, usize) {
        self.diagnostics.first().map_or((1, 1), |d| d.line_col(src))
    }

    /// Render as `file:line:col: message`, the source line and a caret.
    pub fn render(&self, file: &str, src: &str, color: bool) -> String {
        let mut out = String::new();
        for d in &self.diagnostics {
            out.push_str(&render_one(d, file, src, color));
        }
        out
    }
}

fn render_one(d: &Diagnostic, file: &str, src: &str, color: bool) -> String {
    let start = floor_boundary(src, d.span.start);
    let end = floor_boundary(src, d.span.end.max(start));
    let (line, col) = line_col(src, start);
    let header = format!("{file}:{line}:{col}: {}", d.message);
    let line_start = src[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = src[start..].find('\n').map_or(src.len(), |i| start + i);
    if line_end - line_start > MAX_SNIPPET_LINE {
        return format!("error: {header}\n");
    }
    // Keep the label on the first line of the span.
    let end = end.min(line_end).max(start);
    let report = Report::build(ReportKind::Error, (file, start..end))
        .with_config(
            Config::default()
                .with_color(color)
                .with_index_type(IndexType::Byte),
        )
        .with_message(&header)
        .with_label(Label::new((file, start..end)).with_message(&d.message))
        .finish();
    let mut buf = Vec::new();
    match report.write((file, Source::from(src)), &mut buf) {
        // ariadne capitalises the kind; our messages are lowercase.
        Ok(()) => String::from_utf8_lossy(&buf).replacen("Error:", "error:", 1),
        Err(_) => format!("error: {header}\n"),
    }
}
