//! Semantic checks that need a scene (classes named by rules exist in it).

use super::{RuleSet, RulesError};
use crate::scene::Scene;

/// Check that every class named by `rules` exists in `scene`.
pub fn check_classes(_rules: &RuleSet, _scene: &Scene) -> Result<(), RulesError> {
    todo!("parser helper")
}
