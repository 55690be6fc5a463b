//! Scene validation (docs/scenes.md#geometry): each rule a named check, run in a fixed
//! order so the first error reported is always the same.

use super::{Object, Rect, Scene, SceneError, SceneErrorKind};
use crate::limits::{cut, MAX_OBJECTS, MAX_SCENE_COORD};
use std::collections::HashSet;

impl Scene {
    /// Check docs/scenes.md#geometry: coordinates, sizes and grid within
    /// [`crate::limits::MAX_SCENE_COORD`], sizes ≥ 1, grid ≥ 1, unique ids, class
    /// names that are identifiers, fixed objects placed, `x` and `y` given
    /// together, `turned` only on placed objects and `turnable` only on
    /// movable ones, placed objects (their footprints) inside the space,
    /// no two interiors overlapping.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.validate_with(false)
    }

    /// [`Scene::validate`], except that an unplaced object may carry
    /// `turned` (a `turnable` one): synthesis' own problems with an
    /// orientation chosen for each turnable object.
    pub(crate) fn validate_oriented(&self) -> Result<(), SceneError> {
        self.validate_with(true)
    }

    fn validate_with(&self, oriented: bool) -> Result<(), SceneError> {
        self.check_count()?;
        // Range first: after these checks every edge and every difference
        // of edges fits easily in i64 (see `crate::limits`).
        self.check_ranges()?;
        self.check_space()?;
        let mut ids = HashSet::new();
        for (i, o) in self.objects.iter().enumerate() {
            self.check_object(i, o, &mut ids, oriented)?;
        }
        self.check_overlaps()
    }

    /// At most [`MAX_OBJECTS`] objects.
    fn check_count(&self) -> Result<(), SceneError> {
        if self.objects.len() > MAX_OBJECTS {
            return Err(SceneError::invalid(
                SceneErrorKind::TooManyObjects,
                "objects",
                format!(
                    "{} objects is too many; expected at most {MAX_OBJECTS}",
                    self.objects.len()
                ),
            ));
        }
        Ok(())
    }

    /// Every coordinate within ±[`MAX_SCENE_COORD`], every size and the grid
    /// step at most [`MAX_SCENE_COORD`].
    fn check_ranges(&self) -> Result<(), SceneError> {
        let coord = |path: &str, what: &str, v: i64| -> Result<(), SceneError> {
            if (-MAX_SCENE_COORD..=MAX_SCENE_COORD).contains(&v) {
                Ok(())
            } else {
                Err(SceneError::invalid(
                    SceneErrorKind::OutOfRange,
                    path,
                    format!("{what} {v} is out of range; expected an integer from -{MAX_SCENE_COORD} to {MAX_SCENE_COORD}"),
                ))
            }
        };
        let size = |path: &str, what: &str, v: i64| -> Result<(), SceneError> {
            if v > MAX_SCENE_COORD {
                Err(SceneError::invalid(
                    SceneErrorKind::OutOfRange,
                    path,
                    format!(
                        "{what} {v} is too large; expected an integer from 1 to {MAX_SCENE_COORD}"
                    ),
                ))
            } else {
                Ok(())
            }
        };
        coord("space.x", "space x", self.space.x)?;
        coord("space.y", "space y", self.space.y)?;
        size("space.width", "space width", self.space.width)?;
        size("space.height", "space height", self.space.height)?;
        size("grid", "grid step", self.grid)?;
        for (i, o) in self.objects.iter().enumerate() {
            size(&format!("objects[{i}].width"), "width", o.width)?;
            size(&format!("objects[{i}].height"), "height", o.height)?;
            if let Some(x) = o.x {
                coord(&format!("objects[{i}].x"), "x", x)?;
            }
            if let Some(y) = o.y {
                coord(&format!("objects[{i}].y"), "y", y)?;
            }
        }
        Ok(())
    }

    /// The space at least 1×1 and the grid step at least 1.
    fn check_space(&self) -> Result<(), SceneError> {
        if self.space.width < 1 || self.space.height < 1 {
            return Err(SceneError::invalid(
                SceneErrorKind::BadSize,
                "space",
                format!(
                    "space size {}x{} is invalid; width and height must be at least 1",
                    self.space.width, self.space.height
                ),
            ));
        }
        if self.grid < 1 {
            return Err(SceneError::invalid(
                SceneErrorKind::BadGrid,
                "grid",
                format!(
                    "grid step {} is invalid; expected an integer of at least 1",
                    self.grid
                ),
            ));
        }
        Ok(())
    }

    /// Object `i` on its own: an identifier for a class, a non-empty id
    /// not in `ids` (then added), a size of at least 1×1, both coordinates
    /// or neither, placed when fixed, inside the space when placed.
    fn check_object<'s>(
        &self,
        i: usize,
        o: &'s Object,
        ids: &mut HashSet<&'s str>,
        oriented: bool,
    ) -> Result<(), SceneError> {
        let path = format!("objects[{i}]");
        if !super::is_identifier(&o.class) {
            return Err(SceneError::invalid(
                SceneErrorKind::BadClass,
                format!("{path}.class"),
                format!(
                    "class `{}` is not an identifier; expected letters, digits and `_`, not starting with a digit",
                    cut(&o.class)
                ),
            ));
        }
        if o.id.is_empty() {
            return Err(SceneError::invalid(
                SceneErrorKind::EmptyId,
                format!("{path}.id"),
                "object id is empty",
            ));
        }
        if !ids.insert(o.id.as_str()) {
            let first = self.objects.iter().position(|p| p.id == o.id).unwrap_or(0);
            return Err(SceneError::invalid(
                SceneErrorKind::DuplicateId,
                format!("{path}.id"),
                format!(
                    "duplicate object id `{}` (also objects[{first}])",
                    cut(&o.id)
                ),
            ));
        }
        if o.width < 1 || o.height < 1 {
            return Err(SceneError::invalid(
                SceneErrorKind::BadSize,
                path,
                format!(
                    "object `{}` has size {}x{}; width and height must be at least 1",
                    cut(&o.id),
                    o.width,
                    o.height
                ),
            ));
        }
        Self::check_placement(&path, o)?;
        Self::check_turn(&path, o, oriented)?;
        self.check_inside(path, o)
    }

    /// Both coordinates or neither, and a fixed object placed.
    fn check_placement(path: &str, o: &Object) -> Result<(), SceneError> {
        if o.x.is_some() != o.y.is_some() {
            let missing = if o.x.is_none() { "x" } else { "y" };
            return Err(SceneError::invalid(
                SceneErrorKind::HalfPlaced,
                format!("{path}.{missing}"),
                format!(
                    "object `{}` has only one coordinate; give both x and y or neither",
                    cut(&o.id)
                ),
            ));
        }
        if o.fixed && !o.is_placed() {
            return Err(SceneError::invalid(
                SceneErrorKind::FixedUnplaced,
                path,
                format!(
                    "fixed object `{}` has no position; fixed objects must be placed",
                    cut(&o.id)
                ),
            ));
        }
        Ok(())
    }

    /// `turned` only on a placed object (an unplaced one has no
    /// orientation yet: `turnable` says it may get one), `turnable` only
    /// on a movable one (a fixed object stands as it is given, turned or
    /// not).
    fn check_turn(path: &str, o: &Object, oriented: bool) -> Result<(), SceneError> {
        if o.turned && !o.is_placed() && !(oriented && o.turnable) {
            return Err(SceneError::invalid(
                SceneErrorKind::BadTurn,
                format!("{path}.turned"),
                format!(
                    "object `{}` is turned but has no position; `turned` describes a placed object \
                     (to let synthesis turn it, write \"turnable\": true)",
                    cut(&o.id)
                ),
            ));
        }
        if o.turnable && o.fixed {
            return Err(SceneError::invalid(
                SceneErrorKind::BadTurn,
                format!("{path}.turnable"),
                format!(
                    "fixed object `{}` is turnable; a fixed object never moves nor turns \
                     (give its footprint, or \"turned\": true, instead)",
                    cut(&o.id)
                ),
            ));
        }
        Ok(())
    }

    /// A placed object inside the space.
    fn check_inside(&self, path: String, o: &Object) -> Result<(), SceneError> {
        let space = self.space.rect();
        let Some(r) = o.rect() else {
            return Ok(());
        };
        if r.inside(&space) {
            return Ok(());
        }
        Err(SceneError::invalid(
            SceneErrorKind::Outside,
            path,
            format!(
                "object `{}` at [{}, {}]x[{}, {}] lies outside the space [{}, {}]x[{}, {}]",
                cut(&o.id),
                r.x,
                r.x2(),
                r.y,
                r.y2(),
                space.x,
                space.x2(),
                space.y,
                space.y2()
            ),
        ))
    }

    /// No two placed objects' interiors overlap (a sweep over x, to stay
    /// fast on large scenes); the pair reported is the first in that sweep.
    fn check_overlaps(&self) -> Result<(), SceneError> {
        let mut placed: Vec<(usize, Rect)> = self
            .objects
            .iter()
            .enumerate()
            .filter_map(|(i, o)| o.rect().map(|r| (i, r)))
            .collect();
        placed.sort_by_key(|(i, r)| (r.x, *i));
        for a in 0..placed.len() {
            let (i, ra) = placed[a];
            for &(j, rb) in &placed[a + 1..] {
                if rb.x >= ra.x2() {
                    break;
                }
                if ra.interiors_overlap(&rb) {
                    let (i, j) = (i.min(j), i.max(j));
                    return Err(SceneError::invalid(
                        SceneErrorKind::Overlap,
                        format!("objects[{j}]"),
                        format!(
                            "objects `{}` (objects[{i}]) and `{}` (objects[{j}]) overlap",
                            cut(&self.objects[i].id),
                            cut(&self.objects[j].id)
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}
