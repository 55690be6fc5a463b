//! Candidates (docs/guide.md#learning): the statements every demonstration
//! satisfies, and for every other statement where it is first broken.
//!
//! A per-object statement is broken by an object of its subject class that
//! does not satisfy it. A scene-level statement (`Q A: φ`) is broken by a
//! demonstration in which the number of `A` objects satisfying `φ` does not
//! meet `Q`; the object named then is the one `score` names as a violator
//! (docs/language.md#scene-rules): for `no` and `at most`, the first object (in file order) that
//! satisfies `φ`; for `some` and `at least`, none — no single object is to
//! blame for a missing one.

use crate::eval::CompiledRule;
use crate::relations::{ClassAtoms, ClassIndex, Contact, Quant};
use crate::rules::Scope;
use crate::scene::Scene;
use serde::Serialize;

/// Where a statement is first broken: demonstrations in order, objects in
/// file order.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Provenance {
    /// Index of the demonstration (0-based).
    pub demo: usize,
    /// Id of the object that does not satisfy a per-object statement, or
    /// that satisfies the formula of a broken `no` / `at most` scene-level
    /// statement; `None` (not serialised) for a broken `some` / `at least`
    /// scene-level statement.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub object: Option<String>,
}

/// For each statement, `None` when every demonstration satisfies it (a
/// candidate), else where it is first broken.
///
/// `classes` must cover every class of the demonstrations and every
/// landmark of the statements.
pub(crate) fn find_candidates(
    demos: &[Scene],
    classes: &ClassIndex,
    rules: &[CompiledRule],
    contact: Contact,
) -> Vec<Option<Provenance>> {
    let mut out: Vec<Option<Provenance>> = vec![None; rules.len()];
    for (d, scene) in demos.iter().enumerate() {
        let atoms = ClassAtoms::new(scene, classes, contact);
        for (k, r) in rules.iter().enumerate() {
            if out[k].is_some() {
                continue;
            }
            let mut of_class = (0..scene.objects.len())
                .filter(|&i| atoms.is_placed(i) && atoms.class_of(i) == r.subject);
            match r.scope {
                Scope::Each => {
                    if let Some(i) = of_class.find(|&i| !r.formula.eval(&atoms, i)) {
                        out[k] = Some(Provenance {
                            demo: d,
                            object: Some(scene.objects[i].id.clone()),
                        });
                    }
                }
                Scope::Group => {
                    if !r.scene_holds(&atoms, scene.objects.len()) {
                        // The first object off the largest group, if any.
                        let object = r
                            .group_check(&atoms, scene.objects.len())
                            .and_then(|(c, neg)| (!neg).then(|| c.off_main()))
                            .and_then(|off| off.first().map(|&i| scene.objects[i].id.clone()));
                        out[k] = Some(Provenance { demo: d, object });
                    }
                }
                Scope::Scene(q) => {
                    let (c, m) = r.count(&atoms, scene.objects.len());
                    if !q.holds(c, m) {
                        let object = match q {
                            Quant::No | Quant::AtMost(_) => of_class
                                .find(|&i| r.formula.eval(&atoms, i))
                                .map(|i| scene.objects[i].id.clone()),
                            _ => None,
                        };
                        out[k] = Some(Provenance { demo: d, object });
                    }
                }
            }
        }
    }
    out
}

/// A statement broken in one demonstration only: by a slip, perhaps
/// (docs/guide.md#slips). In a learning result, the slip that repairs it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Exception {
    /// The demonstration that breaks it (0-based).
    pub demo: usize,
    /// The objects that break it there: for a per-object statement every
    /// subject object that does not satisfy it; for a scene-level or group
    /// statement the object first named as breaking it, if any. In a
    /// learning result ([`crate::infer::StatementResult::exception`]): the
    /// one slip that repairs it.
    pub objects: Vec<String>,
}

/// For each statement broken in exactly one of at least three
/// demonstrations (`broken` from [`find_candidates`]), that
/// demonstration; `None` for every other statement.
pub(crate) fn find_exceptions(
    demos: &[Scene],
    classes: &ClassIndex,
    rules: &[CompiledRule],
    contact: Contact,
    broken: &[Option<Provenance>],
) -> Vec<Option<usize>> {
    if demos.len() < 3 {
        return vec![None; rules.len()];
    }
    let atoms: Vec<ClassAtoms> = demos
        .iter()
        .map(|s| ClassAtoms::new(s, classes, contact))
        .collect();
    rules
        .iter()
        .zip(broken)
        .map(|(r, first)| {
            let d = first.as_ref()?.demo;
            (d + 1..demos.len())
                .all(|e| holds_in(r, &demos[e], &atoms[e]))
                .then_some(d)
        })
        .collect()
}

/// Whether `r` holds in `scene` (`atoms` its atom table): every subject
/// object satisfies a per-object statement, a group or scene-level
/// statement holds.
pub(crate) fn holds_in(r: &CompiledRule, scene: &Scene, atoms: &ClassAtoms) -> bool {
    match r.scope {
        Scope::Each => (0..scene.objects.len())
            .filter(|&i| atoms.is_placed(i) && atoms.class_of(i) == r.subject)
            .all(|i| r.formula.eval(atoms, i)),
        Scope::Group => r.scene_holds(atoms, scene.objects.len()),
        Scope::Scene(q) => {
            let (c, m) = r.count(atoms, scene.objects.len());
            q.holds(c, m)
        }
    }
}
