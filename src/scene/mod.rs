//! Scenes: the space, the grid and the objects (docs/scenes.md).
//!
//! A [`Scene`] is parsed from JSON with [`Scene::from_json`] (one scene) or
//! [`scenes_from_json`] (a demonstrations array), both of which validate the
//! result. Errors are typed ([`SceneError`]) and name the JSON field path
//! (`objects[3].x`) or the objects involved. This module does no file I/O:
//! callers read the text and pass it in.

use serde::{Deserialize, Serialize};
use std::fmt;

mod geometry;
pub mod measured;
mod object;
mod validate;

pub use geometry::{Rect, Space};
pub use object::Object;

/// A scene: space, grid step and objects (docs/scenes.md#geometry).
///
/// Serde reads and writes the docs/scenes.md#fields form (defaults filled in, the scene
/// validated), so a scene can be a field of other JSON files
/// (`answers.json`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "SceneJson", into = "SceneJson")]
pub struct Scene {
    /// The table.
    pub space: Space,
    /// Grid step (≥ 1); positions of synthesised objects are multiples of it
    /// from the space's min corner.
    pub grid: i64,
    /// The objects, in file order.
    pub objects: Vec<Object>,
}

/// What rule of docs/scenes.md a scene breaks ([`SceneError::kind`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SceneErrorKind {
    /// The JSON text does not match the scene format (syntax, a missing
    /// or unknown field, a wrong type, a float where an integer belongs).
    Json,
    /// More objects than [`crate::limits::MAX_OBJECTS`].
    TooManyObjects,
    /// A coordinate or size beyond [`crate::limits::MAX_SCENE_COORD`].
    OutOfRange,
    /// A width or height below 1 (the space's or an object's).
    BadSize,
    /// A grid step below 1.
    BadGrid,
    /// A class name that is not an identifier.
    BadClass,
    /// An empty object id.
    EmptyId,
    /// Two objects with one id.
    DuplicateId,
    /// An object with `x` or `y` but not both.
    HalfPlaced,
    /// A fixed object without a position.
    FixedUnplaced,
    /// A placed object outside the space.
    Outside,
    /// Two placed objects whose interiors overlap.
    Overlap,
    /// `turned` on an object without a position, or `turnable` on a
    /// fixed object (docs/scenes.md#turns).
    BadTurn,
}

/// Why a scene (or a demonstrations file) is invalid.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The JSON text does not match the scene format.
    #[error("{path}: {message}")]
    Json {
        /// Field path such as `objects[3].x` (`.` for the document root).
        path: String,
        /// What is wrong, with line and column.
        message: String,
    },
    /// The scene parsed but breaks a rule of docs/scenes.md#geometry.
    #[error("{path}: {message}")]
    Invalid {
        /// Which rule.
        kind: SceneErrorKind,
        /// Field path of the first object involved, e.g. `objects[2]`.
        path: String,
        /// What is wrong, naming the objects.
        message: String,
    },
}

impl SceneError {
    /// The field path the error points at.
    pub fn path(&self) -> &str {
        match self {
            SceneError::Json { path, .. } | SceneError::Invalid { path, .. } => path,
        }
    }
    /// What kind of problem.
    pub fn kind(&self) -> SceneErrorKind {
        match self {
            SceneError::Json { .. } => SceneErrorKind::Json,
            SceneError::Invalid { kind, .. } => *kind,
        }
    }
    fn invalid(kind: SceneErrorKind, path: impl Into<String>, message: impl Into<String>) -> Self {
        SceneError::Invalid {
            kind,
            path: path.into(),
            message: message.into(),
        }
    }
    fn prefixed(self, prefix: &str) -> Self {
        let join = |p: String| {
            if p == "." {
                prefix.to_string()
            } else if p.starts_with('[') {
                format!("{prefix}{p}")
            } else {
                format!("{prefix}.{p}")
            }
        };
        match self {
            SceneError::Json { path, message } => SceneError::Json {
                path: join(path),
                message,
            },
            SceneError::Invalid {
                kind,
                path,
                message,
            } => SceneError::Invalid {
                kind,
                path: join(path),
                message,
            },
        }
    }
}

// ---- JSON form -------------------------------------------------------------

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneJson {
    space: Space,
    #[serde(default = "default_grid", deserialize_with = "int")]
    grid: i64,
    objects: Vec<ObjectJson>,
}

fn default_grid() -> i64 {
    10
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectJson {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    id: Option<String>,
    class: String,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "opt_int"
    )]
    x: Option<i64>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "opt_int"
    )]
    y: Option<i64>,
    #[serde(deserialize_with = "int")]
    width: i64,
    #[serde(deserialize_with = "int")]
    height: i64,
    #[serde(default, skip_serializing_if = "is_false")]
    fixed: bool,
    #[serde(default, skip_serializing_if = "is_false")]
    turnable: bool,
    #[serde(default, skip_serializing_if = "is_false")]
    turned: bool,
}

/// A JSON integer as `i64`: `-0` (which JSON readers hand over as a
/// floating-point zero) is 0, and a whole number past 64 bits (`2^64`,
/// handed over as floating point too) is out of range, not "floating
/// point"; a fraction stays an invalid type.
struct IntVisitor;

impl serde::de::Visitor<'_> for IntVisitor {
    type Value = i64;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("i64")
    }
    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<i64, E> {
        Ok(v)
    }
    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<i64, E> {
        i64::try_from(v).map_err(|_| out_of_range(&v.to_string()))
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<i64, E> {
        if v == 0.0 && v.is_sign_negative() {
            return Ok(0);
        }
        if v.is_finite() && v.fract() == 0.0 && v.abs() >= 9.0e18 {
            return Err(out_of_range(&format!("{v:e}")));
        }
        Err(E::invalid_type(serde::de::Unexpected::Float(v), &self))
    }
}

fn out_of_range<E: serde::de::Error>(v: &str) -> E {
    E::custom(format!(
        "integer {} is out of range; expected at most 10^15 in absolute value",
        crate::limits::cut(v)
    ))
}

fn int<'de, D: serde::Deserializer<'de>>(d: D) -> Result<i64, D::Error> {
    d.deserialize_i64(IntVisitor)
}

fn opt_int<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<i64>, D::Error> {
    struct Int(i64);
    impl<'de> Deserialize<'de> for Int {
        fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
            int(d).map(Int)
        }
    }
    Ok(Option::<Int>::deserialize(d)?.map(|i| i.0))
}

/// `text` without a leading UTF-8 byte-order mark (accepted everywhere).
pub fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// JSON text with every lone `\r` (an old Mac line end) made a `\n`, so
/// the parser's "line L column C" counts lines as an editor does. JSON
/// allows a raw `\r` only as whitespace between tokens, so the meaning is
/// the same.
fn lone_cr_as_lf(text: &str) -> std::borrow::Cow<'_, str> {
    let b = text.as_bytes();
    if !b
        .iter()
        .enumerate()
        .any(|(i, &c)| c == b'\r' && b.get(i + 1) != Some(&b'\n'))
    {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\r' && chars.peek() != Some(&'\n') {
            out.push('\n');
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}

fn is_false(b: &bool) -> bool {
    !*b
}

fn json_error(e: serde_path_to_error::Error<serde_json::Error>) -> SceneError {
    let path = e.path().to_string();
    SceneError::Json {
        path,
        message: e.into_inner().to_string(),
    }
}

impl SceneJson {
    fn into_scene(self) -> Scene {
        let objects = self
            .objects
            .into_iter()
            .enumerate()
            .map(|(i, o)| Object {
                id: o.id.unwrap_or_else(|| format!("{}{}", o.class, i)),
                class: o.class,
                x: o.x,
                y: o.y,
                width: o.width,
                height: o.height,
                fixed: o.fixed,
                turnable: o.turnable,
                turned: o.turned,
            })
            .collect();
        Scene {
            space: self.space,
            grid: self.grid,
            objects,
        }
    }

    fn from_scene(s: &Scene) -> Self {
        SceneJson {
            space: s.space,
            grid: s.grid,
            objects: s
                .objects
                .iter()
                .map(|o| ObjectJson {
                    id: Some(o.id.clone()),
                    class: o.class.clone(),
                    x: o.x,
                    y: o.y,
                    width: o.width,
                    height: o.height,
                    fixed: o.fixed,
                    turnable: o.turnable,
                    turned: o.turned,
                })
                .collect(),
        }
    }
}

impl From<Scene> for SceneJson {
    fn from(s: Scene) -> Self {
        SceneJson::from_scene(&s)
    }
}

impl TryFrom<SceneJson> for Scene {
    type Error = SceneError;
    fn try_from(raw: SceneJson) -> Result<Self, SceneError> {
        let scene = raw.into_scene();
        scene.validate()?;
        Ok(scene)
    }
}

fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

impl Scene {
    /// Parse and validate one scene from JSON text.
    pub fn from_json(text: &str) -> Result<Scene, SceneError> {
        let text = lone_cr_as_lf(strip_bom(text));
        let text = text.as_ref();
        if text.trim_start().starts_with('[') {
            return Err(SceneError::Json {
                path: ".".into(),
                message: "expected one scene (a JSON object), found an array; \
                          a demonstrations file holds several scenes"
                    .into(),
            });
        }
        let de = &mut serde_json::Deserializer::from_str(text);
        let raw: SceneJson = serde_path_to_error::deserialize(&mut *de).map_err(json_error)?;
        de.end().map_err(|e| SceneError::Json {
            path: ".".into(),
            message: e.to_string(),
        })?;
        let scene = raw.into_scene();
        scene.validate()?;
        Ok(scene)
    }

    /// A scene from its parts, validated ([`Scene::validate`]).
    pub fn new(space: Space, grid: i64, objects: Vec<Object>) -> Result<Scene, SceneError> {
        let scene = Scene {
            space,
            grid,
            objects,
        };
        scene.validate()?;
        Ok(scene)
    }

    /// Serialise as pretty JSON (ids always written; `fixed` only when true).
    pub fn to_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(&SceneJson::from_scene(self))
            .expect("scene serialisation cannot fail");
        s.push('\n');
        s
    }

    /// Whether every object is placed.
    pub fn is_complete(&self) -> bool {
        self.objects.iter().all(Object::is_placed)
    }

    /// The distinct class names in order of first appearance.
    pub fn classes(&self) -> Vec<&str> {
        let mut out: Vec<&str> = Vec::new();
        for o in &self.objects {
            if !out.contains(&o.class.as_str()) {
                out.push(&o.class);
            }
        }
        out
    }

    /// Whether `o` sits on the grid: `(x − space.x) % grid == 0`, same for y.
    pub fn on_grid(&self, o: &Object) -> bool {
        match (o.x, o.y) {
            // In i128 and with a guard on the step, so that a scene built in
            // code (not validated) cannot overflow or divide by zero here.
            (Some(x), Some(y)) if self.grid >= 1 => {
                let g = i128::from(self.grid);
                (i128::from(x) - i128::from(self.space.x)).rem_euclid(g) == 0
                    && (i128::from(y) - i128::from(self.space.y)).rem_euclid(g) == 0
            }
            (Some(_), Some(_)) => false,
            _ => true,
        }
    }
}

impl fmt::Display for Scene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_json())
    }
}

/// Parse and validate a JSON array of scenes (a demonstrations file).
///
/// Error paths are prefixed with the scene index: `[2].objects[3].x`.
/// A single scene object (not an array) is accepted as a one-element list.
pub fn scenes_from_json(text: &str) -> Result<Vec<Scene>, SceneError> {
    let text = lone_cr_as_lf(strip_bom(text));
    let text = text.as_ref();
    if !text.trim_start().starts_with('[') {
        return Ok(vec![Scene::from_json(text)?]);
    }
    // Straight from the text (not through a JSON value, which would keep
    // only the last of two equal keys): a key given twice is refused in a
    // demonstrations array as in a single scene.
    let de = &mut serde_json::Deserializer::from_str(text);
    let raws: Vec<SceneJson> = serde_path_to_error::deserialize(&mut *de).map_err(json_error)?;
    de.end().map_err(|e| SceneError::Json {
        path: ".".into(),
        message: e.to_string(),
    })?;
    let mut out = Vec::with_capacity(raws.len());
    for (i, raw) in raws.into_iter().enumerate() {
        let scene = raw.into_scene();
        scene
            .validate()
            .map_err(|e| e.prefixed(&format!("[{i}]")))?;
        out.push(scene);
    }
    Ok(out)
}

/// Serialise scenes as a pretty JSON array.
pub fn scenes_to_json(scenes: &[Scene]) -> String {
    let raw: Vec<SceneJson> = scenes.iter().map(SceneJson::from_scene).collect();
    let mut s = serde_json::to_string_pretty(&raw).expect("scene serialisation cannot fail");
    s.push('\n');
    s
}
