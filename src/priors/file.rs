//! The priors file (`rccpack-priors/1`, JSON): written by `rccpack priors`,
//! read by `--priors`. Same inputs, same bytes.
//!
//! ```json
//! {
//!   "version": "rccpack-priors/1",
//!   "templates": "third",
//!   "contact": "point",
//!   "library": { "tasks": 40, "inputs": "fnv1a64:…" },
//!   "parameters": { "strength": 4, "rule_out_after": 10 },
//!   "kinds": [
//!     { "kind": "*", "candidates": 5120, "kept": 98, "confirmed": 0,
//!       "tasks": 40, "tasks_kept": 40, "prior": 0.0192, "ruled_out": false },
//!     …
//!   ],
//!   "hash": "fnv1a64:…"
//! }
//! ```
//!
//! `hash` covers everything but the priors (which follow from the counts):
//! on reading, the hash is recomputed and every `prior` and `ruled_out` is
//! recomputed from the counts and compared, so a hand edit is caught.

use super::estimate::{self, Count, NodeCounts};
use super::kind;
use super::{Priors, PriorsError};
use crate::infer::priors::{hex, PriorParams};
pub use crate::infer::priors::{KindEntry, VERSION};
use crate::infer::Templates;
use crate::relations::Contact;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Library {
    tasks: u64,
    inputs: String,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Parameters {
    strength: u32,
    rule_out_after: u64,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileForm {
    version: String,
    templates: String,
    contact: String,
    library: Library,
    parameters: Parameters,
    kinds: Vec<KindEntry>,
    hash: String,
}

pub(super) fn unhex(field: &str, s: &str) -> Result<u64, PriorsError> {
    s.strip_prefix("fnv1a64:")
        .filter(|h| h.len() == 16)
        .and_then(|h| u64::from_str_radix(h, 16).ok())
        .ok_or_else(|| {
            PriorsError::field(
                field,
                format!(
                    "is `{}`; expected `fnv1a64:` and 16 hexadecimal digits",
                    crate::limits::cut(s)
                ),
            )
        })
}

impl Priors {
    /// Build from summed nodes (the estimate is computed here).
    pub(crate) fn from_nodes(
        params: &PriorParams,
        tasks: u64,
        inputs: u64,
        nodes: BTreeMap<String, NodeCounts>,
    ) -> Priors {
        let est = estimate::estimate(&nodes, params.strength, params.rule_out_after);
        let kinds = nodes
            .iter()
            .map(|(k, n)| {
                let (prior, ruled_out) = est[k];
                KindEntry {
                    kind: k.clone(),
                    candidates: n.count.candidates,
                    kept: n.count.kept,
                    confirmed: n.count.confirmed,
                    tasks: n.tasks,
                    tasks_kept: n.tasks_kept,
                    prior,
                    ruled_out,
                }
            })
            .collect();
        Priors {
            params: *params,
            tasks,
            inputs,
            kinds,
        }
    }

    /// The file's text (pretty JSON, a final newline).
    pub fn to_json(&self) -> String {
        let form = FileForm {
            version: VERSION.into(),
            templates: self.params.templates.to_string(),
            contact: self.params.contact.to_string(),
            library: Library {
                tasks: self.tasks,
                inputs: hex(self.inputs),
            },
            parameters: Parameters {
                strength: self.params.strength,
                rule_out_after: self.params.rule_out_after,
            },
            kinds: self.kinds.clone(),
            hash: hex(self.hash()),
        };
        let mut s = serde_json::to_string_pretty(&form).expect("priors serialise");
        s.push('\n');
        s
    }

    /// Read a priors file's text. Every error names the field.
    pub fn from_json(text: &str) -> Result<Priors, PriorsError> {
        let form = read_form(text)?;
        let params = read_params(&form)?;
        let inputs = unhex("library.inputs", &form.library.inputs)?;
        let claimed = unhex("hash", &form.hash)?;
        let nodes = read_nodes(&form.kinds)?;
        let sorted = form.kinds.windows(2).all(|w| w[0].kind < w[1].kind);
        let priors = Priors::from_nodes(&params, form.library.tasks, inputs, nodes);
        if !sorted {
            return Err(PriorsError::field(
                "kinds",
                "is not sorted by kind; expected the order `rccpack priors` writes".into(),
            ));
        }
        let actual = priors.hash();
        if actual != claimed {
            return Err(PriorsError::field(
                "hash",
                format!(
                    "is {}, but the file's counts and parameters hash to {}: the file was edited or damaged",
                    hex(claimed),
                    hex(actual)
                ),
            ));
        }
        check_recomputed(&form.kinds, &priors.kinds)?;
        Ok(priors)
    }
}

/// The file's JSON form, of this version.
fn read_form(text: &str) -> Result<FileForm, PriorsError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let form: FileForm =
        serde_path_to_error::deserialize(&mut de).map_err(|e| PriorsError::Json {
            field: e.path().to_string(),
            message: e.inner().to_string(),
        })?;
    if form.version != VERSION {
        return Err(PriorsError::field(
            "version",
            format!(
                "is `{}`; expected `{VERSION}`",
                crate::limits::cut(&form.version)
            ),
        ));
    }
    Ok(form)
}

/// The parameters the priors were estimated with, checked.
fn read_params(form: &FileForm) -> Result<PriorParams, PriorsError> {
    let templates: Templates = form
        .templates
        .parse()
        .map_err(|e: String| PriorsError::field("templates", e))?;
    let contact: Contact = form
        .contact
        .parse()
        .map_err(|e: String| PriorsError::field("contact", e))?;
    if form.parameters.strength == 0 {
        return Err(PriorsError::field(
            "parameters.strength",
            "is 0; expected a whole number of at least 1".into(),
        ));
    }
    Ok(PriorParams {
        strength: form.parameters.strength,
        rule_out_after: form.parameters.rule_out_after,
        templates,
        contact,
    })
}

/// The counts per kind: every kind known, its prior in (0, 1), its counts
/// consistent, after its parent, once; the root present.
fn read_nodes(kinds: &[KindEntry]) -> Result<BTreeMap<String, NodeCounts>, PriorsError> {
    let mut nodes: BTreeMap<String, NodeCounts> = BTreeMap::new();
    for (i, k) in kinds.iter().enumerate() {
        let field = |f: &str| format!("kinds[{i}].{f}");
        kind::check_key(&k.kind).map_err(|e| {
            PriorsError::field(
                &field("kind"),
                format!(
                    "is `{}`, a kind this version does not know: {e}",
                    crate::limits::cut(&k.kind)
                ),
            )
        })?;
        if !(k.prior > 0.0 && k.prior < 1.0) {
            return Err(PriorsError::field(
                &field("prior"),
                format!(
                    "is {}; expected a number strictly between 0 and 1",
                    crate::limits::number(k.prior)
                ),
            ));
        }
        if k.kept > k.candidates || k.confirmed > k.kept || k.tasks_kept > k.tasks {
            return Err(PriorsError::field(
                &field("kept"),
                format!(
                    "the counts of `{}` are inconsistent: expected confirmed ≤ kept ≤ candidates and tasks_kept ≤ tasks",
                    crate::limits::cut(&k.kind)
                ),
            ));
        }
        if let Some(p) = kind::parent_key(&k.kind) {
            if !nodes.contains_key(&p) {
                return Err(PriorsError::field(
                    &field("kind"),
                    format!(
                        "`{}` comes before its parent `{}` (or the parent is missing); kinds are sorted, the root `*` first",
                        crate::limits::cut(&k.kind),
                        crate::limits::cut(&p)
                    ),
                ));
            }
        }
        let node = NodeCounts {
            count: Count {
                candidates: k.candidates,
                kept: k.kept,
                confirmed: k.confirmed,
            },
            tasks: k.tasks,
            tasks_kept: k.tasks_kept,
        };
        if nodes.insert(k.kind.clone(), node).is_some() {
            return Err(PriorsError::field(
                &field("kind"),
                format!("`{}` appears twice", crate::limits::cut(&k.kind)),
            ));
        }
    }
    if !nodes.contains_key(kind::ROOT) {
        return Err(PriorsError::field("kinds", "has no root kind `*`".into()));
    }
    Ok(nodes)
}

/// Each kind's prior and ruled-out flag as written equal those its counts
/// give (`recomputed`).
fn check_recomputed(written: &[KindEntry], recomputed: &[KindEntry]) -> Result<(), PriorsError> {
    for (i, (k, e)) in written.iter().zip(recomputed).enumerate() {
        let tol = 1e-9 * e.prior.max(1e-300);
        if (k.prior - e.prior).abs() > tol {
            return Err(PriorsError::field(
                &format!("kinds[{i}].prior"),
                format!(
                    "is {}, but the counts of `{}` give {}",
                    crate::limits::number(k.prior),
                    crate::limits::cut(&k.kind),
                    crate::limits::number(e.prior)
                ),
            ));
        }
        if k.ruled_out != e.ruled_out {
            return Err(PriorsError::field(
                &format!("kinds[{i}].ruled_out"),
                format!(
                    "is {}, but the counts of `{}` and rule_out_after give {}",
                    k.ruled_out,
                    crate::limits::cut(&k.kind),
                    e.ruled_out
                ),
            ));
        }
    }
    Ok(())
}
