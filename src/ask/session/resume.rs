//! Resuming a session from `answers.json`: the checks an answers file
//! must pass before a session starts from it.

use super::AskError;
use crate::ask::answers::Answer;
use crate::scene::Scene;

/// Check `answers` against the demonstrations (`demos` as in
/// `demos.json`): no question answered twice, suspect answers about
/// demonstrations that exist, and every accepted probe at its place in
/// `demos` — one saved in the answers but not yet in the demonstrations
/// (an abort between the two writes) is added again.
pub(super) fn check_answers(answers: &[Answer], demos: &mut Vec<Scene>) -> Result<(), AskError> {
    check_groups(answers)?;
    check_asked_once(answers)?;
    check_demonstrations(answers, demos)
}

/// A group question's answer names two rules or more, its own first.
fn check_groups(answers: &[Answer]) -> Result<(), AskError> {
    for (i, a) in answers.iter().enumerate() {
        let distinct: std::collections::BTreeSet<&String> = a.group.iter().collect();
        if !a.group.is_empty()
            && (a.group.len() < 2 || distinct.len() != a.group.len() || a.group[0] != a.rule)
        {
            return Err(AskError::BadAnswer {
                index: i,
                why: format!(
                    "group: {:?} is not a group question's rules; expected two or more distinct rule names, `{}` first (or no `group` for a question about one rule)",
                    a.group.iter().map(|g| crate::limits::cut(g)).collect::<Vec<_>>(),
                    crate::limits::cut(&a.rule)
                ),
            });
        }
    }
    Ok(())
}

/// A session never asks about a rule twice: a second answer about one (a
/// hand edit) contradicts or repeats the first.
fn check_asked_once(answers: &[Answer]) -> Result<(), AskError> {
    for (i, a) in answers.iter().enumerate() {
        // A session never asks the same question twice (a rule of a
        // rejected group is asked about again only alone or in a
        // smaller group).
        if a.suspect.is_some() {
            continue;
        }
        let mut asked = a.asked();
        asked.sort_unstable();
        if let Some(j) = answers[..i].iter().position(|b| {
            let mut other = b.asked();
            other.sort_unstable();
            b.suspect.is_none() && other == asked
        }) {
            return Err(AskError::BadAnswer {
                index: i,
                why: format!(
                    "rule: `{}` was answered already by answers[{j}] ({}); a session asks about a rule once — keep one of the two answers",
                    crate::limits::cut(&a.rule),
                    match (answers[j].accepted, answers[j].group.is_empty()) {
                        (true, _) => "acceptable: dropped",
                        (false, true) => "not acceptable: confirmed",
                        (false, false) => "not acceptable: one of its group is meant",
                    }
                ),
            });
        }
    }
    Ok(())
}

/// Suspect answers about demonstrations that exist, and every accepted
/// probe at its place in `demos` (one saved in the answers but not yet in
/// the demonstrations is added again).
fn check_demonstrations(answers: &[Answer], demos: &mut Vec<Scene>) -> Result<(), AskError> {
    for (i, a) in answers.iter().enumerate() {
        if let Some(s) = &a.suspect {
            if s.demonstration >= demos.len() {
                return Err(AskError::BadAnswer {
                    index: i,
                    why: format!(
                        "the answer is about demonstration [{}], but demos.json has {} demonstrations",
                        s.demonstration,
                        demos.len()
                    ),
                });
            }
            continue;
        }
        if !a.accepted {
            continue;
        }
        // An accepted probe is a demonstration; one saved in the
        // answers but not yet in the demonstrations (an abort between
        // the two writes) is added again.
        match a.demo {
            Some(d) if demos.get(d) == Some(&a.probe) => {}
            Some(d) if d == demos.len() => demos.push(a.probe.clone()),
            Some(d) if d > demos.len() => {
                return Err(AskError::BadAnswer {
                    index: i,
                    why: format!(
                        "demo: {d} is out of range: demos.json has {} demonstrations (indices 0 to {}), and an accepted probe is at most the next one, [{}]",
                        demos.len(),
                        demos.len().saturating_sub(1),
                        demos.len()
                    ),
                })
            }
            Some(d) => {
                return Err(AskError::BadAnswer {
                    index: i,
                    why: format!(
                        "the accepted probe should be demonstration [{d}], but demos.json has {} demonstrations and [{d}] is a different scene",
                        demos.len()
                    ),
                })
            }
            None => {
                return Err(AskError::BadAnswer {
                    index: i,
                    why: "an accepted answer needs `demo`, its index in demos.json".into(),
                })
            }
        }
    }
    Ok(())
}
