//! How likely each held rule is meant, for choosing group questions
//! (docs/guide.md#how-a-session-chooses-its-questions).
//!
//! A held rule is true in every demonstration and improbable by chance;
//! whether it is *meant* or a habit only the person can say. Before they
//! say anything, two things hint at it:
//!
//! - **evidence**: a rule just past the cutoff (a few subjects, a likely
//!   pattern) is more often a habit than one whose chance explanation is
//!   astronomically unlikely. With `L = −log10 P` (the rule's posterior
//!   of being a chance pattern), the evidence says `L / (L + H)` with
//!   [`HALF_EVIDENCE`] `= H`: a rule at the default cutoff (`L = 2`) is
//!   meant with 0.17, one at `L = 10` with 0.5, one at `L = 90` with 0.9;
//! - **priors** learned across tasks (`--priors`): the statement's prior
//!   that it is intended; with priors the two are averaged.
//!
//! Then the session learns about *this person*. Every answer settles
//! rules (dropped: habits; confirmed, alone or deduced in a group: meant).
//! First, how much evidence this person's meant rules have: a meant rule
//! with evidence at most `L` says `L` is enough, a habit with evidence at
//! least `L` says it is not, so the evidence estimate becomes
//! `(M≤ + α·e) / (M≤ + H≥ + α)` (`e` the estimate above; monotone in
//! `L`, as it should be). Then the rules are counted per **family** — the statement with its classes and landmarks
//! made anonymous (`!DR_E(B, R)` → `!DR_E(A, B)`), and, when that family has
//! no answer yet, the family with directions made anonymous too
//! (`!DR_d(A, B)`). A family with `m` meant and `h` habits gives
//! `(m + α·base) / (m + h + α)` with [`PRIOR_WEIGHT`] `= α`: after one
//! dropped `!DR_E(B, R)`, every `!DR_d(X, Y)` looks like a habit.

use super::Asker;
use std::collections::{BTreeSet, HashMap};

/// `H`: the evidence `L = −log10 P` at which the evidence alone says "meant
/// or a habit, equally likely".
pub(super) const HALF_EVIDENCE: f64 = 10.0;

/// `α`: how many answers of a family the base estimate counts as.
pub(super) const PRIOR_WEIGHT: f64 = 1.0;

/// A group question breaks rules while the chance that every one of them
/// is a habit stays at least this: near one half, each answer halves the
/// doubt (the group-testing rule of thumb).
pub(super) const GROUP_CHANCE: f64 = 0.5;

/// The family of a statement text: classes (`classes`) and landmarks made
/// anonymous in order of first appearance; with `general`, the directions
/// of relations (`DR_N` …) too.
pub(super) fn family(text: &str, classes: &BTreeSet<String>, general: bool) -> String {
    let mut out = String::with_capacity(text.len());
    let mut names: Vec<&str> = Vec::new();
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        if c.is_alphanumeric() || c == '_' {
            let end = rest
                .find(|ch: char| !(ch.is_alphanumeric() || ch == '_'))
                .unwrap_or(rest.len());
            let word = &rest[..end];
            let landmark = out.ends_with('@');
            if landmark || classes.contains(word) {
                let at = names.iter().position(|n| *n == word).unwrap_or_else(|| {
                    names.push(word);
                    names.len() - 1
                });
                if landmark {
                    out.push('L');
                } else {
                    out.push(char::from(b'A' + (at % 26) as u8));
                }
            } else if general && is_directed(word) {
                out.push_str(&word[..word.len() - 1]);
                out.push('d');
            } else {
                out.push_str(word);
            }
            rest = &rest[end..];
        } else {
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// `DR_N`, `EC_W`, `FL_S` …: a relation with a direction.
fn is_directed(word: &str) -> bool {
    let b = word.as_bytes();
    b.len() >= 4
        && b[b.len() - 2] == b'_'
        && matches!(b[b.len() - 1], b'N' | b'S' | b'E' | b'W')
        && b[..b.len() - 2].iter().all(u8::is_ascii_uppercase)
}

/// What the answers so far say about families, `(meant, habits)` per key,
/// and about evidence (the evidence `L` of every settled rule, meant or
/// not).
#[derive(Debug, Default)]
pub(super) struct Families {
    counts: HashMap<String, (u32, u32)>,
    evidence: Vec<(f64, bool)>,
    /// The classes of the problem and the demonstrations (what a family
    /// makes anonymous).
    classes: BTreeSet<String>,
}

impl Families {
    fn add(&mut self, key: String, meant: bool) {
        let e = self.counts.entry(key).or_default();
        if meant {
            e.0 += 1;
        } else {
            e.1 += 1;
        }
    }
}

impl Asker {
    /// Every class of the problem and the demonstrations.
    fn class_names(&self) -> BTreeSet<String> {
        self.problem
            .objects
            .iter()
            .chain(self.demos.iter().flat_map(|d| d.objects.iter()))
            .map(|o| o.class.clone())
            .collect()
    }

    /// The statement text of the learned statement named `name`.
    fn statement_of(&self, name: &str) -> Option<String> {
        self.learned
            .statements
            .iter()
            .find(|s| s.name == name)
            .map(|s| crate::infer::statement_text(s.scope, &s.formula))
    }

    /// The families of every rule the answers settled.
    pub(super) fn families(&self) -> Families {
        let classes = self.class_names();
        let mut f = Families {
            classes: classes.clone(),
            ..Families::default()
        };
        let mut note = |name: &str, meant: bool| {
            if let Some(text) = self.statement_of(name) {
                f.add(family(&text, &classes, false), meant);
                f.add(family(&text, &classes, true), meant);
            }
            if let Some(l) = self.evidence_of(name) {
                f.evidence.push((l, meant));
            }
        };
        for a in self.answers.iter().filter(|a| a.suspect.is_none()) {
            if a.accepted {
                for name in a.asked() {
                    note(name, false);
                }
            } else if a.group.is_empty() {
                note(&a.rule, true);
            }
        }
        for name in &self.deduced {
            note(name, true);
        }
        for name in &self.also_dropped {
            note(name, false);
        }
        f
    }

    /// The evidence `L = −log10 P` of the learned statement named `name`.
    fn evidence_of(&self, name: &str) -> Option<f64> {
        self.learned
            .statements
            .iter()
            .find(|s| s.name == name)
            .and_then(|s| s.posterior)
            .map(|p| (-p.log10_posterior).max(0.0))
    }

    /// The chance that held rule `k` is meant (see the module's text).
    pub(super) fn p_meant(&self, k: usize, families: &Families) -> f64 {
        let name = &self.held.rules[k].name;
        let stmt = self.learned.statements.iter().find(|s| s.name == *name);
        let l = self.evidence_of(name).unwrap_or(0.0);
        let mut base = l / (l + HALF_EVIDENCE);
        let meant_below = families
            .evidence
            .iter()
            .filter(|&&(e, m)| m && e <= l)
            .count();
        let habits_above = families
            .evidence
            .iter()
            .filter(|&&(e, m)| !m && e >= l)
            .count();
        base = (meant_below as f64 + PRIOR_WEIGHT * base)
            / ((meant_below + habits_above) as f64 + PRIOR_WEIGHT);
        if let Some(prior) = stmt.and_then(|s| s.prior.as_ref()) {
            base = 0.5 * (base + prior.prior.clamp(0.0, 1.0));
        }
        let classes = &families.classes;
        let text = self.text(k);
        let (m, h) = [false, true]
            .iter()
            .map(|&g| {
                families
                    .counts
                    .get(&family(&text, classes, g))
                    .copied()
                    .unwrap_or_default()
            })
            .find(|&(m, h)| m + h > 0)
            .unwrap_or_default();
        (f64::from(m) + PRIOR_WEIGHT * base) / (f64::from(m + h) + PRIOR_WEIGHT)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn families_make_classes_and_directions_anonymous() {
        let classes: BTreeSet<String> = ["B", "R", "W"].iter().map(|s| s.to_string()).collect();
        assert_eq!(family("!DR_E(B, R)", &classes, false), "!DR_E(A, B)");
        assert_eq!(family("!DR_W(R, B)", &classes, false), "!DR_W(A, B)");
        assert_eq!(family("!DR_W(R, B)", &classes, true), "!DR_d(A, B)");
        assert_eq!(family("EC_N(R, *)", &classes, true), "EC_d(A, *)");
        assert_eq!(family("group(B)", &classes, false), "group(A)");
        assert_eq!(
            family("some R: EC_N(R, @w_south)", &classes, false),
            "some A: EC_N(A, @L)"
        );
        assert_eq!(
            family("at least 2 R: DR_N(R, W)", &classes, false),
            "at least 2 A: DR_N(A, B)"
        );
    }
}
