//! The formula builder: disjunctions, conjunctions, negations, atoms,
//! `turned(A)` and targets, from a rule's pairs.

use super::grammar::Rule as R;
use super::{quant, span_of, subject_kind, words_span, written_text, Subject};
use crate::relations::Relation;
use crate::rules::diagnostic::{Diagnostic, DiagnosticKind};
use crate::rules::{Atom, Formula, Quant, Span, Target};
use pest::iterators::Pair;

/// Builds one rule's formula by recursion over its pairs, recording the
/// atoms' spans and subjects and the problems found.
pub(super) struct Builder<'a> {
    pub(super) atoms: &'a mut Vec<Span>,
    pub(super) subjects: &'a mut Vec<(String, Span)>,
    pub(super) diags: &'a mut Vec<Diagnostic>,
}

impl Builder<'_> {
    pub(super) fn disjunction(&mut self, p: Pair<'_, R>) -> Formula {
        let mut out = Vec::new();
        for c in p.into_inner().filter(|c| c.as_rule() == R::conjunction) {
            match self.conjunction(c) {
                Formula::Or(v) => out.extend(v),
                f => out.push(f),
            }
        }
        if out.len() == 1 {
            out.pop().unwrap_or(Formula::Or(Vec::new()))
        } else {
            Formula::Or(out)
        }
    }

    fn conjunction(&mut self, p: Pair<'_, R>) -> Formula {
        let mut out = Vec::new();
        for c in p.into_inner().filter(|c| c.as_rule() == R::unary) {
            match self.unary(c) {
                Formula::And(v) => out.extend(v),
                f => out.push(f),
            }
        }
        if out.len() == 1 {
            out.pop().unwrap_or(Formula::And(Vec::new()))
        } else {
            Formula::And(out)
        }
    }

    fn unary(&mut self, p: Pair<'_, R>) -> Formula {
        let mut nots = 0usize;
        let mut inner = None;
        for c in p.into_inner() {
            match c.as_rule() {
                R::not_op => nots += 1,
                R::atom => inner = Some(self.atom(c)),
                R::turned => inner = Some(self.turned(c)),
                R::group => {
                    inner = c
                        .into_inner()
                        .find(|g| g.as_rule() == R::disjunction)
                        .map(|d| self.disjunction(d))
                }
                _ => {}
            }
        }
        let mut f = inner.unwrap_or(Formula::Or(Vec::new()));
        for _ in 0..nots {
            f = Formula::not(f);
        }
        f
    }

    fn atom(&mut self, p: Pair<'_, R>) -> Formula {
        let span = span_of(&p);
        self.atoms.push(span);
        let mut rel = Relation::ALL[0];
        let mut subject = String::new();
        let mut quant = None;
        let mut target = Target::Any;
        for c in p.into_inner() {
            match c.as_rule() {
                R::relation => match Relation::from_name(c.as_str()) {
                    Some(r) => rel = r,
                    None => {
                        self.diags.push(Diagnostic::new(
                            DiagnosticKind::UnknownRelation,
                            span_of(&c),
                            format!(
                                "unknown relation `{}`: expected one of {}",
                                crate::limits::cut(c.as_str()),
                                Relation::ALL.map(|r| r.name()).join(", ")
                            ),
                        ));
                    }
                },
                R::subject => match subject_kind(c) {
                    Subject::Class(s) => {
                        subject = s;
                        self.subjects.push((subject.clone(), span));
                    }
                    Subject::Other(text, at, landmark) => {
                        let message = if landmark {
                            format!("expected a class name, found `{text}`: the subject of an atom is a class, not a landmark")
                        } else {
                            // The first edition's (syntax) message, kept.
                            format!("expected a class name, found `{text}`")
                        };
                        self.diags
                            .push(Diagnostic::new(DiagnosticKind::Syntax, at, message));
                    }
                },
                R::target => {
                    let (q, t) = self.target(c);
                    quant = q;
                    target = t;
                }
                _ => {}
            }
        }
        Formula::Atom(match quant {
            Some(q) => Atom::quantified(rel, subject, q, target),
            None => Atom::new(rel, subject, target),
        })
    }

    /// `turned(A)`: an orientation statement about the subject.
    fn turned(&mut self, p: Pair<'_, R>) -> Formula {
        let span = span_of(&p);
        self.atoms.push(span);
        let mut subject = String::new();
        for c in p.into_inner() {
            if c.as_rule() != R::subject {
                continue;
            }
            match subject_kind(c) {
                Subject::Class(s) => {
                    subject = s;
                    self.subjects.push((subject.clone(), span));
                }
                Subject::Other(text, at, _) => {
                    self.diags.push(Diagnostic::new(
                        DiagnosticKind::Syntax,
                        at,
                        format!("expected a class name, found `{text}`: `turned` is about the subject class's objects"),
                    ));
                }
            }
        }
        Formula::Turned(subject)
    }

    /// An atom's target: the written quantifier (if valid) and the object.
    fn target(&mut self, p: Pair<'_, R>) -> (Option<Quant>, Target) {
        let mut quant_pair = None;
        let mut target = Target::Any;
        for c in p.into_inner() {
            match c.as_rule() {
                R::quant => quant_pair = Some(c),
                R::object => {
                    let text = c.as_str();
                    target = match c.into_inner().next().map(|o| o.as_rule()) {
                        Some(R::landmark) => {
                            Target::Landmark(text.strip_prefix('@').unwrap_or(text).to_string())
                        }
                        Some(R::class) => Target::Class(text.to_string()),
                        _ => Target::Any,
                    };
                }
                _ => {}
            }
        }
        let Some(qp) = quant_pair else {
            return (None, target);
        };
        let written = written_text(qp.as_str());
        let qspan = words_span(&qp);
        let q = match quant(qp) {
            Ok(q) => Some(q),
            Err(d) => {
                self.diags.push(d);
                None
            }
        };
        if let Target::Landmark(id) = &target {
            self.diags.push(Diagnostic::new(DiagnosticKind::LandmarkQuantifier,
                qspan,
                format!(
                    "quantifier `{written}` before landmark `@{id}`: a landmark takes no quantifier; expected `@{id}` alone"
                ),
            ));
            return (None, target);
        }
        (q, target)
    }
}
