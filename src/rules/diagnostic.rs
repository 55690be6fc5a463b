//! Located errors for `.rcc` text, rendered with a caret under the span.

use super::Span;

/// One located problem.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// Where.
    pub span: Span,
    /// What is wrong and what was expected (lowercase).
    pub message: String,
}

/// Every problem found in one `.rcc` text.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}", .diagnostics.first().map(|d| d.message.as_str()).unwrap_or("invalid rules"))]
pub struct RulesError {
    /// At least one.
    pub diagnostics: Vec<Diagnostic>,
}

impl RulesError {
    /// Render as `file:line:col: message`, the source line and a caret.
    pub fn render(&self, _file: &str, _src: &str, _color: bool) -> String {
        todo!("parser helper")
    }
}
