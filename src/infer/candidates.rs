//! Candidates (SPEC §7.1): the statements every demonstration satisfies, and
//! for every other statement the first demonstration and object that break
//! it.

use crate::eval::CompiledFormula;
use crate::relations::{ClassAtoms, ClassIndex, Contact};
use crate::scene::Scene;
use serde::Serialize;

/// Where a statement is first broken: demonstrations in order, objects in
/// file order.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Provenance {
    /// Index of the demonstration (0-based).
    pub demo: usize,
    /// Id of the object that does not satisfy the statement.
    pub object: String,
}

/// For each formula, `None` when every demonstration satisfies it (a
/// candidate), else the first object that breaks it.
///
/// `subjects[k]` is formula `k`'s subject class index in `classes`, which
/// must cover every class of the demonstrations.
pub fn find_candidates(
    demos: &[Scene],
    classes: &ClassIndex,
    formulas: &[CompiledFormula],
    subjects: &[usize],
    contact: Contact,
) -> Vec<Option<Provenance>> {
    let mut out: Vec<Option<Provenance>> = vec![None; formulas.len()];
    for (d, scene) in demos.iter().enumerate() {
        let atoms = ClassAtoms::new(scene, classes, contact);
        for (k, f) in formulas.iter().enumerate() {
            if out[k].is_some() {
                continue;
            }
            let broken = scene.objects.iter().enumerate().find(|(i, o)| {
                o.is_placed() && atoms.class_of(*i) == subjects[k] && !f.eval(&atoms, *i)
            });
            if let Some((_, o)) = broken {
                out[k] = Some(Provenance {
                    demo: d,
                    object: o.id.clone(),
                });
            }
        }
    }
    out
}
