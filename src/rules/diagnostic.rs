//! Located errors for `.rcc` text, rendered with a caret under the span.

use super::Span;
use ariadne::{Config, IndexType, Label, Report, ReportKind, Source};

/// Lines longer than this (in bytes) are reported without a source snippet.
const MAX_SNIPPET_LINE: usize = 10_000;

/// What kind of problem a [`Diagnostic`] reports, for code that reacts to
/// it (tests, editors, the studio) instead of reading the message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum DiagnosticKind {
    /// The text does not follow the grammar (`grammar/rcc.pest`).
    Syntax,
    /// The text is larger than [`crate::limits::MAX_RULES_BYTES`].
    TooLarge,
    /// A formula nests deeper than the parser allows.
    TooDeep,
    /// A rule name is defined twice ([`Diagnostic::related`]: the first
    /// definition).
    DuplicateName,
    /// A rule's atoms are about different subject classes, or a scene
    /// scope's class differs from an atom's subject.
    MixedSubjects,
    /// A scene scope (`some A:`, `at least K A:`) is malformed.
    BadScope,
    /// A count (`at least K`) is missing or out of range.
    BadCount,
    /// A number does not parse.
    BadNumber,
    /// A weight is not a finite number greater than 0.
    BadWeight,
    /// A `p` is not strictly between 0 and 1.
    BadProbability,
    /// A relation name that is not in the table.
    UnknownRelation,
    /// A quantifier before a landmark (`every @w`).
    LandmarkQuantifier,
    /// A class the scene (or demonstrations) does not have.
    UnknownClass,
    /// A landmark `@ID` that names no fixed object of the scene.
    UnknownLandmark,
}

/// One located problem.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// What kind of problem.
    pub kind: DiagnosticKind,
    /// Where.
    pub span: Span,
    /// What is wrong and what was expected (lowercase).
    pub message: String,
    /// A second place that matters, with what it is (the first definition
    /// of a duplicate rule name).
    pub related: Option<(Span, String)>,
}

impl Diagnostic {
    /// A diagnostic of `kind` at `span`.
    pub fn new(kind: DiagnosticKind, span: Span, message: impl Into<String>) -> Self {
        Diagnostic {
            kind,
            span,
            message: message.into(),
            related: None,
        }
    }

    /// The same diagnostic with a second place.
    pub fn with_related(mut self, span: Span, what: impl Into<String>) -> Self {
        self.related = Some((span, what.into()));
        self
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
/// (offsets past the end or inside a character are clamped). A line ends at
/// `\n`, `\r\n` or a lone `\r` (as the grammar's `NEWLINE`), so a file with
/// old Mac line endings gets the same line numbers everywhere.
pub(crate) fn line_col(src: &str, offset: usize) -> (usize, usize) {
    LineIndex::new(src).line_col(src, offset)
}

/// Start offsets of the lines of a text, computed once: `line_col` is then
/// a binary search (linear error reports on texts with many errors).
pub(crate) struct LineIndex {
    starts: Vec<usize>,
}

impl LineIndex {
    /// Index the lines of `src` (`\n`, `\r\n` and lone `\r` end a line).
    pub(crate) fn new(src: &str) -> Self {
        let b = src.as_bytes();
        let mut starts = vec![0];
        for (i, &c) in b.iter().enumerate() {
            if c == b'\n' || (c == b'\r' && b.get(i + 1) != Some(&b'\n')) {
                starts.push(i + 1);
            }
        }
        LineIndex { starts }
    }

    /// 1-based line and character column of byte `offset`.
    pub(crate) fn line_col(&self, src: &str, offset: usize) -> (usize, usize) {
        let offset = floor_boundary(src, offset);
        let line = self.starts.partition_point(|&s| s <= offset);
        let start = self.starts[line - 1].min(offset);
        let col = src[start..offset].chars().count() + 1;
        (line, col)
    }

    /// Byte range of the line holding `offset` (without its line end).
    fn line_range(&self, src: &str, offset: usize) -> (usize, usize) {
        let line = self.starts.partition_point(|&s| s <= offset);
        let start = self.starts[line - 1];
        let end = self.starts.get(line).map_or(src.len(), |&next| {
            let b = src.as_bytes();
            let mut e = next;
            while e > start && matches!(b[e - 1], b'\n' | b'\r') {
                e -= 1;
            }
            e
        });
        (start, end.max(start))
    }
}

/// At most this many diagnostics are rendered; the rest are counted
/// ("… and N more errors"), so a file with 100,000 errors is reported in
/// linear time and a screenful of text.
pub(super) const MAX_SHOWN_DIAGNOSTICS: usize = 20;

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

    /// Render as `file:line:col: message`, the source line and a caret;
    /// past the first 20 only their number.
    pub fn render(&self, file: &str, src: &str, color: bool) -> String {
        // ariadne ends lines at `\n` only: lone `\r` line ends become `\n`
        // (the same length, so every span still holds) so that the header
        // and the snippet agree on the line.
        let has_lone_cr = src
            .as_bytes()
            .iter()
            .enumerate()
            .any(|(i, &c)| c == b'\r' && src.as_bytes().get(i + 1) != Some(&b'\n'));
        let normalized;
        let src = if has_lone_cr {
            let b = src.as_bytes();
            let bytes: Vec<u8> = b
                .iter()
                .enumerate()
                .map(|(i, &c)| {
                    if c == b'\r' && b.get(i + 1) != Some(&b'\n') {
                        b'\n'
                    } else {
                        c
                    }
                })
                .collect();
            normalized = String::from_utf8(bytes).expect("ASCII replaced by ASCII");
            normalized.as_str()
        } else {
            src
        };
        let index = LineIndex::new(src);
        let mut out = String::new();
        for d in self.diagnostics.iter().take(MAX_SHOWN_DIAGNOSTICS) {
            out.push_str(&render_one(d, file, src, &index, color));
        }
        let more = self.diagnostics.len().saturating_sub(MAX_SHOWN_DIAGNOSTICS);
        if more > 0 {
            out.push_str(&format!(
                "error: {file}: … and {more} more error{}\n",
                if more == 1 { "" } else { "s" }
            ));
        }
        out
    }
}

fn render_one(d: &Diagnostic, file: &str, src: &str, index: &LineIndex, color: bool) -> String {
    let start = floor_boundary(src, d.span.start);
    let end = floor_boundary(src, d.span.end.max(start));
    let (line, col) = index.line_col(src, start);
    let header = format!("{file}:{line}:{col}: {}", d.message);
    let (line_start, line_end) = index.line_range(src, start);
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
