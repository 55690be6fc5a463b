//! A question's probe files: `probes/probe-N.json` and its picture.

use super::{write_err, SessionError};
use crate::ask::Question;
use crate::render::{render_to_path, RenderOptions};
use crate::rules::RuleSet;
use crate::task::files;
use std::path::{Path, PathBuf};

/// Write a question's probe as `rccpack ask` does: `probes/probe-N.json`
/// (the scene) and `probes/probe-N.png` (drawn with the question's rule,
/// titled `question N: is this acceptable? (breaks RULE)`). Returns the two
/// paths.
pub fn write_probe_files(
    dir: &Path,
    held: &RuleSet,
    q: &Question,
    number: usize,
    contact: crate::relations::Contact,
) -> Result<(PathBuf, PathBuf), SessionError> {
    let probes = dir.join(files::PROBES);
    std::fs::create_dir_all(&probes).map_err(write_err(probes.clone()))?;
    let json = probes.join(format!("probe-{number}.json"));
    let png = probes.join(format!("probe-{number}.png"));
    crate::fsutil::atomic_write(&json, q.probe.scene.to_json()).map_err(write_err(json.clone()))?;
    // The rules the question is about: the probed one, or every rule a
    // suspect demonstration breaks.
    let about: Vec<&str> = match &q.suspect {
        Some(s) => s.breaks.iter().map(String::as_str).collect(),
        None if !q.group.is_empty() => q.group.iter().map(|g| g.rule.as_str()).collect(),
        None => vec![q.rule.as_str()],
    };
    let rule: Vec<_> = held
        .rules
        .iter()
        .filter(|r| about.contains(&r.name.as_str()))
        .cloned()
        .collect();
    let title = match &q.suspect {
        Some(s) => format!(
            "question {number}: demonstration {} as you meant it? (breaks {} rule{} the others keep)",
            s.demonstration,
            s.breaks.len(),
            if s.breaks.len() == 1 { "" } else { "s" }
        ),
        // The legend lists them.
        None if !q.group.is_empty() => format!(
            "question {number}: is this acceptable? (breaks {} rules)",
            q.group.len()
        ),
        None => format!("question {number}: is this acceptable? (breaks {})", q.rule),
    };
    let ropts = RenderOptions {
        contact,
        scale: 1.0,
        title: Some(title),
        like: None,
        moved: q
            .probe
            .edit
            .iter()
            .flat_map(|e| &e.moved)
            .map(|m| (m.id.clone(), m.x, m.y))
            .collect(),
        outlined: q
            .suspect
            .as_ref()
            .and_then(|s| s.objects.first().cloned())
            .into_iter()
            .collect(),
    };
    render_to_path(&q.probe.scene, Some(&RuleSet::new(rule)), &ropts, &png).map_err(|source| {
        SessionError::Render {
            path: png.clone(),
            source,
        }
    })?;
    Ok((json, png))
}
