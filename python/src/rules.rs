//! `Rule` and `RuleSet`: parsed `.rcc` text.

use crate::errors::{guard, rules_error};
use pyo3::exceptions::{PyIndexError, PyKeyError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyInt, PyString, PyTuple};
use rccpack_core::infer::{statement_reading, statement_text};
use rccpack_core::rules::{print_rule, print_rules, Strength};
use rccpack_core::{parse_rules, Rule as CoreRule, RuleSet as CoreRuleSet};

/// One rule: `rule NAME [MODIFIER]: FORMULA`.
#[pyclass(module = "rccpack", name = "Rule", frozen)]
#[derive(Clone)]
pub struct PyRule {
    pub(crate) inner: CoreRule,
}

#[pymethods]
impl PyRule {
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }
    /// Weight in the score: `weight W`, `−ln P` for `p P`, 0 for hard rules.
    #[getter]
    fn weight(&self) -> f64 {
        self.inner.strength.weight()
    }
    #[getter]
    fn hard(&self) -> bool {
        self.inner.strength.is_hard()
    }
    /// `P` of a `p P` rule (learned rules), else `None`.
    #[getter]
    fn posterior(&self) -> Option<f64> {
        match self.inner.strength {
            Strength::P(p) => Some(p),
            _ => None,
        }
    }
    /// The one-line English reading ("every B is north of every R").
    #[getter]
    fn reading(&self) -> String {
        statement_reading(self.inner.scope, &self.inner.formula)
    }
    /// The subject class.
    #[getter]
    fn subject(&self) -> &str {
        self.inner.subject()
    }
    /// Whether it is a rule about the whole scene (`some A: …`).
    #[getter]
    fn scene_level(&self) -> bool {
        self.inner.scope.is_scene()
    }
    /// The statement after `rule NAME:` (with `Q A: ` when scene-level).
    #[getter]
    fn formula(&self) -> String {
        statement_text(self.inner.scope, &self.inner.formula)
    }
    /// Comment lines printed above it (learned rules: reading and numbers).
    #[getter]
    fn comments(&self) -> Vec<String> {
        self.inner.comments.clone()
    }
    /// The `.rcc` text of the rule, without comments.
    #[getter]
    fn text(&self) -> String {
        let mut r = self.inner.clone();
        r.comments.clear();
        print_rule(&r).trim_end().to_string()
    }
    fn __str__(&self) -> String {
        self.text()
    }
    fn __repr__(&self) -> String {
        format!("<Rule {}>", self.text())
    }
}

/// An ordered set of rules with unique names (`RuleSet.parse(text)`).
#[pyclass(module = "rccpack", name = "RuleSet", frozen)]
#[derive(Clone)]
pub struct PyRuleSet {
    pub(crate) inner: CoreRuleSet,
    /// The text it was parsed from (for located errors of later checks).
    pub(crate) source: Option<String>,
    /// The name used in error messages (a path, or `<rules>`).
    pub(crate) file: String,
}

impl PyRuleSet {
    pub(crate) fn wrap(inner: CoreRuleSet) -> Self {
        PyRuleSet {
            inner,
            source: None,
            file: "<rules>".into(),
        }
    }

    pub(crate) fn parse_named(text: &str, file: &str) -> PyResult<Self> {
        let text = rccpack_core::scene::strip_bom(text);
        match guard(|| parse_rules(text))? {
            Ok(inner) => Ok(PyRuleSet {
                inner,
                source: Some(text.to_string()),
                file: file.to_string(),
            }),
            Err(e) => Err(rules_error(&e, text, file)),
        }
    }

    /// A located error of a check against a scene (`check_landmarks`, …):
    /// against the source when there is one, else against the printed text.
    pub(crate) fn error(&self, e: &rccpack_core::RulesError) -> PyErr {
        match &self.source {
            Some(src) => rules_error(e, src, &self.file),
            None => {
                // Rules built in code (learned) carry no spans that point
                // into a text: report the message alone.
                let printed = print_rules(&self.inner);
                let cleared = rccpack_core::RulesError::new(
                    e.diagnostics
                        .iter()
                        .map(|d| {
                            rccpack_core::Diagnostic::new(
                                d.kind,
                                rccpack_core::rules::Span::new(0, 0),
                                d.message.clone(),
                            )
                        })
                        .collect(),
                );
                rules_error(&cleared, &printed, &self.file)
            }
        }
    }

    fn rule_obj(&self, i: usize) -> PyRule {
        PyRule {
            inner: self.inner.rules[i].clone(),
        }
    }
}

#[pymethods]
impl PyRuleSet {
    /// Parse and check `.rcc` text; `file` names it in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, file = "<rules>"))]
    fn parse(text: &str, file: &str) -> PyResult<Self> {
        Self::parse_named(text, file)
    }

    /// Check against a scene: every class it names exists there and every
    /// landmark `@ID` is a fixed object of it (`rccpack check --scene`).
    fn check(&self, scene: &crate::scene::PyScene) -> PyResult<()> {
        let s = &scene.inner;
        guard(|| rccpack_core::rules::check_classes(&self.inner, s))?
            .map_err(|e| self.error(&e))?;
        guard(|| rccpack_core::rules::check_landmarks(&self.inner, s))?.map_err(|e| self.error(&e))
    }

    /// The rules, in order.
    #[getter]
    fn rules<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let items: Vec<PyRule> = (0..self.inner.rules.len())
            .map(|i| self.rule_obj(i))
            .collect();
        PyTuple::new(py, items)
    }
    /// The rule names, in order.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.inner.rules.iter().map(|r| r.name.clone()).collect()
    }
    /// Every class named by any rule, sorted.
    #[getter]
    fn classes(&self) -> Vec<String> {
        self.inner.classes()
    }
    fn __len__(&self) -> usize {
        self.inner.rules.len()
    }
    /// By position or by name.
    fn __getitem__(&self, key: &Bound<'_, PyAny>) -> PyResult<PyRule> {
        if key.is_instance_of::<PyInt>() {
            let i: isize = key.extract()?;
            let n = self.inner.rules.len() as isize;
            let j = if i < 0 { i + n } else { i };
            if j < 0 || j >= n {
                return Err(PyIndexError::new_err(format!(
                    "rule index {i} is out of range; the set has {n} rules"
                )));
            }
            return Ok(self.rule_obj(j as usize));
        }
        if let Ok(name) = key.cast::<PyString>() {
            let name = name.to_string_lossy();
            return match self.inner.rules.iter().position(|r| r.name == name) {
                Some(i) => Ok(self.rule_obj(i)),
                None => Err(PyKeyError::new_err(format!("no rule named `{name}`"))),
            };
        }
        Err(PyTypeError::new_err(
            "a rule is looked up by index (int) or name (str)",
        ))
    }
    fn __contains__(&self, name: &str) -> bool {
        self.inner.rules.iter().any(|r| r.name == name)
    }
    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(self.rules(py)?.into_any().try_iter()?.into_any())
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.cast::<PyRuleSet>() {
            Ok(o) => self.inner.same_rules(&o.get().inner),
            Err(_) => false,
        }
    }
    /// The `.rcc` text (comments included).
    fn __str__(&self) -> String {
        print_rules(&self.inner)
    }
    fn __repr__(&self) -> String {
        format!("<RuleSet of {} rules>", self.inner.rules.len())
    }
}
