//! What learning consumes of the priors learned across tasks
//! ([`crate::priors`]): the [`Priors`] themselves (a prior per [`Kind`] of
//! statement), a statement's kind ([`kind`]) and applying the priors to one
//! learning run ([`apply`]). Estimating priors from a library and reading
//! and writing the priors file live above learning, in [`crate::priors`],
//! which re-exports everything public here.

pub mod apply;
pub mod kind;

pub(crate) use apply::{PriorsUsed, RuledOut};
pub(crate) use kind::Kind;

use crate::infer::Templates;
use crate::relations::Contact;

/// Priors per kind, from a library of tasks.
#[derive(Debug, Clone, PartialEq)]
pub struct Priors {
    /// The estimator's parameters and the candidates' template set and
    /// contact mode.
    pub params: PriorParams,
    /// Tasks in the library.
    pub tasks: u64,
    /// Hash of the library's inputs (order-independent).
    pub inputs: u64,
    /// Every node of the hierarchy seen in the library (the root first),
    /// sorted by key.
    pub kinds: Vec<KindEntry>,
}

/// Parameters of the estimator (and of the candidates it counts).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PriorParams {
    /// The shrinkage strength `m` in pseudo-candidates, ≥ 1 (default 4).
    pub strength: u32,
    /// Rule a kind out after this many tasks in which it was a candidate
    /// and never kept; 0: never rule out (default 10).
    pub rule_out_after: u64,
    /// The template set whose statements are counted (default third, as learning).
    pub templates: Templates,
    /// The contact mode candidates are found with (default point).
    pub contact: Contact,
}

impl Default for PriorParams {
    fn default() -> Self {
        PriorParams {
            strength: 4,
            rule_out_after: 10,
            // The candidates learning finds by default.
            templates: crate::infer::LearnParams::default().templates,
            contact: crate::infer::LearnParams::default().contact,
        }
    }
}

/// One node of the hierarchy, as written.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KindEntry {
    /// The node's key (`*`, `TEMPLATE`, `TEMPLATE/ROLE`, `TEMPLATE/ROLE/DIR`).
    pub kind: String,
    /// Candidates over the library.
    pub candidates: u64,
    /// Of these, kept.
    pub kept: u64,
    /// Of these, confirmed.
    pub confirmed: u64,
    /// Tasks with a candidate of the node.
    pub tasks: u64,
    /// Tasks that kept one.
    pub tasks_kept: u64,
    /// The probability that a candidate of the kind is a rule.
    pub prior: f64,
    /// Left out of the statements when learning.
    pub ruled_out: bool,
}

/// The prior a learning run gave one statement, and where it came from.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StatementPrior {
    /// The probability that the statement is intended (`1 − π`).
    pub prior: f64,
    /// The statement's kind (`None`: a given statement, no template).
    pub kind: Option<String>,
    /// The node of the priors file that gave the prior (the kind itself or
    /// an ancestor); `None` for a given statement (the uniform prior).
    pub from: Option<String>,
}

/// The priors file format's version string.
pub const VERSION: &str = "rccpack-priors/1";

/// FNV-1a, 64 bits, over `bytes`, continuing from `h`.
pub fn fnv1a(mut h: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// The FNV-1a offset basis.
pub const FNV_BASIS: u64 = 0xcbf2_9ce4_8422_2325;

/// A hash as the priors file and the `.rcc` header write it (`fnv1a64:…`).
pub(crate) fn hex(h: u64) -> String {
    format!("fnv1a64:{h:016x}")
}

impl Priors {
    /// The content hash: everything but the priors (which follow from the
    /// counts).
    pub(crate) fn hash(&self) -> u64 {
        let mut text = format!(
            "{VERSION}\n{}\n{}\n{}\n{:016x}\n{}\n{}\n",
            self.params.templates,
            self.params.contact,
            self.tasks,
            self.inputs,
            self.params.strength,
            self.params.rule_out_after
        );
        for k in &self.kinds {
            text.push_str(&format!(
                "{} {} {} {} {} {}\n",
                k.kind, k.candidates, k.kept, k.confirmed, k.tasks, k.tasks_kept
            ));
        }
        fnv1a(FNV_BASIS, text.as_bytes())
    }

    /// The content hash as written in the file (`fnv1a64:…`).
    pub fn hash_text(&self) -> String {
        hex(self.hash())
    }

    /// The node that decides `kind`: the most specific of its nodes in the
    /// file (the root at least).
    pub fn lookup(&self, kind: &Kind) -> &KindEntry {
        for key in kind.path().iter().rev() {
            if let Ok(i) = self.kinds.binary_search_by(|e| e.kind.as_str().cmp(key)) {
                return &self.kinds[i];
            }
        }
        self.root()
    }

    /// The root node.
    pub fn root(&self) -> &KindEntry {
        // `from_nodes` always has the root, which sorts first (`*` < `{`).
        &self.kinds[0]
    }
}
