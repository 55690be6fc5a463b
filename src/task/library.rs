//! Reading a library of task folders (`rccpack priors`): each folder's
//! `demos.json` and `learned.rcc` (the rules the person kept, with their
//! `# confirmed` marks), counted on rayon's threads and combined into
//! [`Priors`] by [`crate::priors`].

use super::{files, read_text_at_most, TaskError};
use crate::priors::estimate::{self, PriorParams, TaskCounts};
use crate::priors::Priors;
use crate::rules::parse_rules;
use crate::scene::scenes_from_json;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// A task folder of the library that cannot be read or counted.
#[derive(Debug, thiserror::Error)]
#[error("task {}: {source}", dir.display())]
pub struct LibraryError {
    /// The folder.
    pub dir: PathBuf,
    /// Why.
    pub source: Box<TaskError>,
}

/// Count one task folder.
pub fn task_counts(dir: &Path, params: &PriorParams) -> Result<TaskCounts, LibraryError> {
    let wrap = |source: TaskError| LibraryError {
        dir: dir.to_path_buf(),
        source: Box::new(source),
    };
    let demos_path = files::file(dir, files::DEMOS);
    let learned_path = files::file(dir, files::LEARNED);
    let max = crate::limits::MAX_RULES_BYTES.saturating_mul(4);
    let demos_text = read_text_at_most(&demos_path, max).map_err(wrap)?;
    let learned_text =
        read_text_at_most(&learned_path, crate::limits::MAX_RULES_BYTES).map_err(wrap)?;
    let demos = scenes_from_json(&demos_text).map_err(|source| {
        wrap(TaskError::Scene {
            path: demos_path.clone(),
            source,
        })
    })?;
    let kept = parse_rules(&learned_text).map_err(|source| {
        wrap(TaskError::Rules {
            path: learned_path.clone(),
            text: learned_text.clone(),
            source,
        })
    })?;
    let confirmed = files::confirmed_names(&learned_text);
    let hash = estimate::input_hash(&[&demos_text, &learned_text]);
    estimate::task_counts(&demos, &kept, &confirmed, params, hash)
        .map_err(|e| wrap(TaskError::Learn(e)))
}

/// Count every folder of `dirs` on the current rayon pool and combine
/// them. The first failing folder (in `dirs` order) is the error. The
/// result does not depend on the number of threads nor on the order of
/// `dirs`.
pub fn library(dirs: &[PathBuf], params: &PriorParams) -> Result<Priors, LibraryError> {
    let counts: Vec<Result<TaskCounts, LibraryError>> =
        dirs.par_iter().map(|d| task_counts(d, params)).collect();
    let counts: Vec<TaskCounts> = counts.into_iter().collect::<Result<_, _>>()?;
    Ok(estimate::combine(&counts, params))
}
