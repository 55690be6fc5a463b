//! One task's counts as plain data (`rccpack-task-counts/1`): the per-task
//! step of `rccpack priors` made portable, so that the tasks of a library
//! can be counted elsewhere (Python's `task_counts`, on the workers of a
//! Dask cluster) and combined afterwards ([`super::combine`], Python's
//! `combine_priors`) into exactly the bytes `rccpack priors` writes.
//!
//! ```json
//! {
//!   "version": "rccpack-task-counts/1",
//!   "templates": "third",
//!   "contact": "point",
//!   "hash": "fnv1a64:…",
//!   "kinds": { "{A}_dr_{d}_{B}/fixed/s": { "candidates": 2, "kept": 1, "confirmed": 0 } }
//! }
//! ```
//!
//! `templates` and `contact` are the ones the candidates were found with;
//! combining checks them against its own, so counts of another template
//! set cannot slip in. `hash` is the task's input hash
//! ([`super::estimate::input_hash`]); `kinds` holds the most specific kind
//! keys with at least one candidate, as [`super::task_counts`] makes them.

use super::estimate::{Count, PriorParams, TaskCounts};
use super::file::unhex;
use super::kind;
use super::PriorsError;
use crate::infer::priors::hex;
use crate::infer::Templates;
use crate::limits::cut;
use crate::relations::Contact;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The plain-data format's version string.
pub const COUNTS_VERSION: &str = "rccpack-task-counts/1";

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CountsForm {
    version: String,
    templates: String,
    contact: String,
    hash: String,
    kinds: BTreeMap<String, Count>,
}

fn field_error(field: String, message: String) -> PriorsError {
    PriorsError::Counts { field, message }
}

fn json_error(prefix: &str, e: serde_path_to_error::Error<serde_json::Error>) -> PriorsError {
    let path = e.path().to_string();
    let field = match path.as_str() {
        "" | "." => prefix.to_string(),
        p if p.starts_with('[') => format!("{prefix}{p}"),
        p if prefix.is_empty() => p.to_string(),
        p => format!("{prefix}.{p}"),
    };
    PriorsError::CountsJson {
        field,
        message: e.inner().to_string(),
    }
}

impl TaskCounts {
    /// The counts as plain data (compact JSON) for candidates found with
    /// `params.templates` and `params.contact`.
    pub fn to_json(&self, params: &PriorParams) -> String {
        serde_json::to_string(&CountsForm {
            version: COUNTS_VERSION.into(),
            templates: params.templates.to_string(),
            contact: params.contact.to_string(),
            hash: hex(self.hash),
            kinds: self.kinds.clone(),
        })
        .expect("task counts serialise")
    }

    /// Read counts written by [`TaskCounts::to_json`], for combining with
    /// `params` (whose template set and contact mode they must have).
    /// Every error names the field.
    pub fn from_json(text: &str, params: &PriorParams) -> Result<TaskCounts, PriorsError> {
        let mut de = serde_json::Deserializer::from_str(text);
        let form: CountsForm =
            serde_path_to_error::deserialize(&mut de).map_err(|e| json_error("", e))?;
        checked(form, params, "")
    }
}

/// Read a JSON array of counts (each as [`TaskCounts::to_json`] writes
/// it); errors name the field as `counts[3].kinds…`.
pub fn counts_from_json_list(
    text: &str,
    params: &PriorParams,
) -> Result<Vec<TaskCounts>, PriorsError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let forms: Vec<CountsForm> =
        serde_path_to_error::deserialize(&mut de).map_err(|e| json_error("counts", e))?;
    forms
        .into_iter()
        .enumerate()
        .map(|(i, f)| checked(f, params, &format!("counts[{i}].")))
        .collect()
}

/// The counts' `what` must be the combine's.
fn same<T: PartialEq + std::fmt::Display>(
    field: String,
    got: T,
    want: T,
    what: &str,
) -> Result<(), PriorsError> {
    if got == want {
        return Ok(());
    }
    Err(field_error(
        field,
        format!(
            "is `{got}`, but the priors are combined for `{want}`: count every task with the same {what}"
        ),
    ))
}

fn checked(
    form: CountsForm,
    params: &PriorParams,
    prefix: &str,
) -> Result<TaskCounts, PriorsError> {
    let at = |f: &str| format!("{prefix}{f}");
    if form.version != COUNTS_VERSION {
        return Err(field_error(
            at("version"),
            format!("is `{}`; expected `{COUNTS_VERSION}`", cut(&form.version)),
        ));
    }
    let templates: Templates = form
        .templates
        .parse()
        .map_err(|e: String| field_error(at("templates"), e))?;
    same(at("templates"), templates, params.templates, "templates")?;
    let contact: Contact = form
        .contact
        .parse()
        .map_err(|e: String| field_error(at("contact"), e))?;
    same(at("contact"), contact, params.contact, "contact mode")?;
    let hash = unhex(&at("hash"), &form.hash).map_err(|e| match e {
        PriorsError::Field { field, message } => field_error(field, message),
        other => other,
    })?;
    for (key, c) in &form.kinds {
        let field = || at(&format!("kinds.{key}"));
        kind::check_most_specific(key).map_err(|e| {
            field_error(
                field(),
                format!("names `{}`, not a kind this version counts: {e}", cut(key)),
            )
        })?;
        if c.candidates == 0 {
            return Err(field_error(
                field() + ".candidates",
                "is 0; expected at least 1 (kinds without candidates are left out)".into(),
            ));
        }
        if c.kept > c.candidates || c.confirmed > c.kept {
            return Err(field_error(
                field() + ".kept",
                format!(
                    "the counts ({} candidates, {} kept, {} confirmed) are inconsistent: expected confirmed ≤ kept ≤ candidates",
                    c.candidates, c.kept, c.confirmed
                ),
            ));
        }
    }
    Ok(TaskCounts {
        hash,
        kinds: form.kinds,
    })
}
