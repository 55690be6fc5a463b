//! Relations lifted to classes: class names and landmark ids interned for
//! one evaluation, and per placed object and target how many target
//! objects stand in each relation with it (docs/language.md#class-rules, docs/language.md#quantifiers).

use super::{relation_bits, Contact, Quant, RelBits, Relation};
use crate::scene::{Rect, Scene};

/// Class names (and landmark ids) interned to dense indices for one
/// evaluation.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ClassIndex {
    names: Vec<String>,
    landmarks: Vec<String>,
}

impl ClassIndex {
    /// The classes of a scene, in order of first appearance.
    pub fn of_scene(scene: &Scene) -> Self {
        ClassIndex {
            names: scene.classes().into_iter().map(String::from).collect(),
            landmarks: Vec::new(),
        }
    }
    /// Intern a name (adds it when new) and return its index.
    pub(crate) fn intern(&mut self, name: &str) -> usize {
        match self.get(name) {
            Some(i) => i,
            None => {
                self.names.push(name.to_string());
                self.names.len() - 1
            }
        }
    }
    /// Intern a landmark id (adds it when new) and return its index.
    pub fn intern_landmark(&mut self, id: &str) -> usize {
        match self.landmarks.iter().position(|n| n == id) {
            Some(i) => i,
            None => {
                self.landmarks.push(id.to_string());
                self.landmarks.len() - 1
            }
        }
    }
    /// Index of a class name.
    pub fn get(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }
    /// Number of classes.
    pub fn len(&self) -> usize {
        self.names.len()
    }
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }
    /// Name of class `i`.
    pub fn name(&self, i: usize) -> &str {
        &self.names[i]
    }
    /// All names.
    pub fn names(&self) -> &[String] {
        &self.names
    }
    /// Interned landmark ids.
    pub fn landmarks(&self) -> &[String] {
        &self.landmarks
    }
}

/// For one object and one target: how many target objects there are and,
/// per relation, how many of them the object stands in it with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TargetCount {
    /// `m`: the other placed objects of the target.
    pub total: u32,
    /// `c` per relation (index `Relation::index()`).
    pub hits: [u32; 16],
}

impl TargetCount {
    /// Whether `rel(o, Q target)` holds.
    #[inline]
    pub fn holds(&self, rel: Relation, quant: Quant) -> bool {
        quant.holds(self.hits[rel.index()], self.total)
    }
    /// The mask of relations whose default lifting holds (the first
    /// edition's class-atom byte, widened).
    pub(crate) fn default_bits(&self) -> RelBits {
        Relation::ALL
            .iter()
            .filter(|r| self.holds(**r, r.default_quant()))
            .fold(0, |acc, r| acc | r.bit())
    }
    fn add(&mut self, bits: RelBits) {
        self.total += 1;
        let mut b = bits;
        while b != 0 {
            let i = b.trailing_zeros() as usize;
            self.hits[i] += 1;
            b &= b - 1;
        }
    }
}

/// The count of a target with no objects.
const EMPTY_TARGET: TargetCount = TargetCount {
    total: 0,
    hits: [0; 16],
};

/// Per placed object and per target (every class, then `*`), the
/// [`TargetCount`] of docs/language.md#class-rules and docs/language.md#quantifiers; plus the scene's landmarks.
///
/// Object indices are indices into `scene.objects`; unplaced objects have no
/// row (they take no part in evaluation).
#[derive(Debug, Clone)]
pub struct ClassAtoms {
    /// Number of targets per row = classes + 1 (the last is `*`).
    stride: usize,
    /// `row[i]`: row start of object `i` in `counts`, or `usize::MAX` if unplaced.
    row: Vec<usize>,
    /// Class index of each object.
    class_of: Vec<usize>,
    counts: Vec<TargetCount>,
    rects: Vec<Option<Rect>>,
    /// Per object: placed, turned and not square.
    turned: Vec<bool>,
    /// Per interned landmark id: the fixed, placed object with that id.
    landmarks: Vec<Option<usize>>,
    contact: Contact,
}

impl ClassAtoms {
    /// Build the table for `scene` with the given class index (every class of
    /// the scene must be in it; extra classes simply have no objects).
    /// Landmark ids interned in `classes` are resolved to this scene's fixed
    /// objects.
    pub fn new(scene: &Scene, classes: &ClassIndex, contact: Contact) -> Self {
        let n = scene.objects.len();
        let stride = classes.len() + 1;
        let class_of: Vec<usize> = scene
            .objects
            .iter()
            .map(|o| classes.get(&o.class).unwrap_or(usize::MAX))
            .collect();
        let rects: Vec<Option<Rect>> = scene.objects.iter().map(|o| o.rect()).collect();
        let mut row = vec![usize::MAX; n];
        let mut next = 0;
        for i in 0..n {
            if rects[i].is_some() {
                row[i] = next;
                next += stride;
            }
        }
        let mut counts = vec![EMPTY_TARGET; next];
        for i in 0..n {
            let Some(a) = rects[i] else { continue };
            let base = row[i];
            for j in 0..n {
                if i == j {
                    continue;
                }
                let Some(b) = rects[j] else { continue };
                let bits = relation_bits(&a, &b, contact);
                if class_of[j] < stride - 1 {
                    counts[base + class_of[j]].add(bits);
                }
                counts[base + stride - 1].add(bits);
            }
        }
        let landmarks = classes
            .landmarks()
            .iter()
            .map(|id| {
                scene
                    .objects
                    .iter()
                    .position(|o| o.fixed && o.is_placed() && &o.id == id)
            })
            .collect();
        ClassAtoms {
            stride,
            row,
            class_of,
            counts,
            rects,
            turned: scene
                .objects
                .iter()
                .map(|o| o.is_placed() && o.turned && o.is_oblong())
                .collect(),
            landmarks,
            contact,
        }
    }

    /// The counts of object `obj` against `target` (`None` = `*`), or
    /// `None` when the object is unplaced.
    #[inline]
    pub fn count(&self, obj: usize, target: Option<usize>) -> Option<&TargetCount> {
        let r = *self.row.get(obj)?;
        if r == usize::MAX {
            return None;
        }
        let t = match target {
            None => self.stride - 1,
            Some(t) if t < self.stride - 1 => t,
            // A class the table does not know has no objects.
            Some(_) => return Some(&EMPTY_TARGET),
        };
        Some(&self.counts[r + t])
    }

    /// The counts of object `obj` against landmark `lm` (an index of
    /// [`ClassIndex::landmarks`]): one target object, or none when the
    /// landmark is missing from the scene or is `obj` itself. `None` when
    /// `obj` is unplaced.
    pub(crate) fn landmark_count(&self, obj: usize, lm: usize) -> Option<TargetCount> {
        let a = (*self.rects.get(obj)?)?;
        let mut c = EMPTY_TARGET;
        if let Some(Some(l)) = self.landmarks.get(lm) {
            if *l != obj {
                if let Some(b) = self.rects[*l] {
                    c.add(relation_bits(&a, &b, self.contact));
                }
            }
        }
        Some(c)
    }

    /// The default-lifted bits of `obj` against `target` (docs/language.md#class-rules: `DR` every,
    /// the others some), or `None` when unplaced.
    pub fn bits(&self, obj: usize, target: Option<usize>) -> Option<RelBits> {
        self.count(obj, target).map(TargetCount::default_bits)
    }

    /// Whether the class atom `rel(obj's class, target)` with its default
    /// quantifier holds for `obj`. Unplaced objects satisfy nothing.
    #[inline]
    pub fn holds(&self, obj: usize, rel: Relation, target: Option<usize>) -> bool {
        self.count(obj, target)
            .is_some_and(|c| c.holds(rel, rel.default_quant()))
    }

    /// Class index of object `obj` (`usize::MAX` for a class the index does
    /// not know).
    pub(crate) fn class_of(&self, obj: usize) -> usize {
        self.class_of[obj]
    }

    /// Whether object `obj` is placed.
    pub fn is_placed(&self, obj: usize) -> bool {
        self.row.get(obj).is_some_and(|&r| r != usize::MAX)
    }

    /// The rectangle of object `obj` (`None` when unplaced).
    pub fn rect(&self, obj: usize) -> Option<Rect> {
        self.rects.get(obj).copied().flatten()
    }

    /// Whether object `obj` lies turned (placed, `turned`, not square;
    /// docs/language.md#orientation).
    pub fn lies_turned(&self, obj: usize) -> bool {
        self.turned.get(obj).copied().unwrap_or(false)
    }

    /// The contact mode the table was built with.
    pub fn contact(&self) -> Contact {
        self.contact
    }
}
