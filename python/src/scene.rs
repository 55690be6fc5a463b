//! `Space`, `Object`, `Scene`: the docs/scenes.md scene as Python objects, and
//! the conversions to and from plain Python dicts (the JSON form).

use crate::errors::{guard, scene_error};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use rccpack_core::{Object as CoreObject, Scene as CoreScene, SceneError, Space as CoreSpace};

/// The table: min corner and size.
#[pyclass(module = "rccpack", name = "Space", frozen, eq)]
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct PySpace {
    pub(crate) inner: CoreSpace,
}

#[pymethods]
impl PySpace {
    #[new]
    #[pyo3(signature = (width, height, x = 0, y = 0))]
    fn new(width: i64, height: i64, x: i64, y: i64) -> Self {
        PySpace {
            inner: CoreSpace {
                x,
                y,
                width,
                height,
            },
        }
    }
    #[getter]
    fn x(&self) -> i64 {
        self.inner.x
    }
    #[getter]
    fn y(&self) -> i64 {
        self.inner.y
    }
    #[getter]
    fn width(&self) -> i64 {
        self.inner.width
    }
    #[getter]
    fn height(&self) -> i64 {
        self.inner.height
    }
    fn __repr__(&self) -> String {
        let s = self.inner;
        format!(
            "Space(width={}, height={}, x={}, y={})",
            s.width, s.height, s.x, s.y
        )
    }
}

/// One rectangle: id, class, position (when placed), size, fixed.
#[pyclass(module = "rccpack", name = "Object", frozen, eq)]
#[derive(Clone, PartialEq, Eq)]
pub struct PyObject {
    pub(crate) inner: CoreObject,
}

#[pymethods]
impl PyObject {
    #[new]
    #[pyo3(signature = (id, cls, width, height, x = None, y = None, fixed = false, turnable = false, turned = false))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        id: String,
        cls: String,
        width: i64,
        height: i64,
        x: Option<i64>,
        y: Option<i64>,
        fixed: bool,
        turnable: bool,
        turned: bool,
    ) -> Self {
        PyObject {
            inner: CoreObject {
                id,
                class: cls,
                x,
                y,
                width,
                height,
                fixed,
                turnable,
                turned,
            },
        }
    }
    #[getter]
    fn id(&self) -> &str {
        &self.inner.id
    }
    #[getter]
    fn cls(&self) -> &str {
        &self.inner.class
    }
    #[getter]
    fn x(&self) -> Option<i64> {
        self.inner.x
    }
    #[getter]
    fn y(&self) -> Option<i64> {
        self.inner.y
    }
    #[getter]
    fn width(&self) -> i64 {
        self.inner.width
    }
    #[getter]
    fn height(&self) -> i64 {
        self.inner.height
    }
    #[getter]
    fn fixed(&self) -> bool {
        self.inner.fixed
    }
    /// Whether the object may be placed turned by 90°.
    #[getter]
    fn turnable(&self) -> bool {
        self.inner.turnable
    }
    /// Whether the (placed) object lies turned: its footprint is
    /// `height × width`.
    #[getter]
    fn turned(&self) -> bool {
        self.inner.turned
    }
    /// The `(width, height)` it occupies: its size, swapped when turned.
    #[getter]
    fn footprint(&self) -> (i64, i64) {
        self.inner.footprint()
    }
    /// Whether the object has a position.
    #[getter]
    fn placed(&self) -> bool {
        self.inner.is_placed()
    }
    /// The same object at another position (`None`, `None`: unplaced).
    #[pyo3(signature = (x, y))]
    fn at(&self, x: Option<i64>, y: Option<i64>) -> Self {
        let mut o = self.inner.clone();
        o.x = x;
        o.y = y;
        PyObject { inner: o }
    }
    fn __repr__(&self) -> String {
        let o = &self.inner;
        let pos = match (o.x, o.y) {
            (Some(x), Some(y)) => format!(", x={x}, y={y}"),
            _ => String::new(),
        };
        format!(
            "Object(id={:?}, cls={:?}, width={}, height={}{pos}{}{}{})",
            o.id,
            o.class,
            o.width,
            o.height,
            if o.fixed { ", fixed=True" } else { "" },
            if o.turnable { ", turnable=True" } else { "" },
            if o.turned { ", turned=True" } else { "" }
        )
    }
}

/// A scene: space, grid step and objects (validated on construction).
#[pyclass(module = "rccpack", name = "Scene", frozen, eq)]
#[derive(Clone, PartialEq, Eq)]
pub struct PyScene {
    pub(crate) inner: CoreScene,
}

impl PyScene {
    pub(crate) fn wrap(inner: CoreScene) -> Self {
        PyScene { inner }
    }
}

/// One scene or a sequence of scenes (the `like=` and `demos` arguments).
pub(crate) fn scenes_arg(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<CoreScene>> {
    if let Ok(s) = obj.cast::<PyScene>() {
        return Ok(vec![s.get().inner.clone()]);
    }
    if obj.is_instance_of::<PyString>() || obj.is_instance_of::<PyDict>() {
        return Err(PyTypeError::new_err(format!(
            "{what}: expected a Scene or a sequence of Scenes, found {}",
            type_name(obj)
        )));
    }
    let mut out = Vec::new();
    for (i, item) in obj.try_iter()?.enumerate() {
        let item = item?;
        match item.cast::<PyScene>() {
            Ok(s) => out.push(s.get().inner.clone()),
            Err(_) => {
                return Err(PyTypeError::new_err(format!(
                    "{what}[{i}]: expected a Scene, found {}",
                    type_name(&item)
                )))
            }
        }
    }
    Ok(out)
}

pub(crate) fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "an object".into())
}

fn json_err(path: &str, message: String) -> SceneError {
    SceneError::Json {
        path: if path.is_empty() {
            ".".into()
        } else {
            path.into()
        },
        message,
    }
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// What a Python value is, in serde's words (`floating point `2.5``).
fn unexpected(v: &Bound<'_, PyAny>) -> String {
    if v.is_none() {
        "null".into()
    } else if let Ok(b) = v.cast::<PyBool>() {
        format!("boolean `{}`", b.is_true())
    } else if let Ok(f) = v.cast::<PyFloat>() {
        format!("floating point `{}`", f.value())
    } else if let Ok(s) = v.cast::<PyString>() {
        format!(
            "string {:?}",
            rccpack_core::limits::cut(&s.to_string_lossy())
        )
    } else if v.is_instance_of::<PyInt>() {
        "integer".into()
    } else if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        "sequence".into()
    } else if v.is_instance_of::<PyDict>() {
        "map".into()
    } else {
        type_name(v)
    }
}

fn int(v: &Bound<'_, PyAny>, path: &str) -> Result<i64, SceneError> {
    if v.is_instance_of::<PyInt>() && !v.is_instance_of::<PyBool>() {
        return v.extract::<i64>().map_err(|_| {
            let text = v.str().map(|s| s.to_string()).unwrap_or_default();
            json_err(
                path,
                format!(
                    "integer {} is out of range; expected at most 10^15 in absolute value",
                    rccpack_core::limits::cut(&text)
                ),
            )
        });
    }
    Err(json_err(
        path,
        format!("invalid type: {}, expected an integer", unexpected(v)),
    ))
}

fn opt_int(v: &Bound<'_, PyAny>, path: &str) -> Result<Option<i64>, SceneError> {
    if v.is_none() {
        Ok(None)
    } else {
        int(v, path).map(Some)
    }
}

fn string(v: &Bound<'_, PyAny>, path: &str) -> Result<String, SceneError> {
    match v.cast::<PyString>() {
        Ok(s) => s
            .to_cow()
            .map(|c| c.into_owned())
            .map_err(|_| json_err(path, "invalid string: not valid unicode".into())),
        Err(_) => Err(json_err(
            path,
            format!("invalid type: {}, expected a string", unexpected(v)),
        )),
    }
}

fn dict<'a, 'py>(
    v: &'a Bound<'py, PyAny>,
    path: &str,
) -> Result<&'a Bound<'py, PyDict>, SceneError> {
    v.cast::<PyDict>().map_err(|_| {
        json_err(
            path,
            format!("invalid type: {}, expected a dict", unexpected(v)),
        )
    })
}

fn key_str(k: &Bound<'_, PyAny>, path: &str) -> Result<String, SceneError> {
    match k.cast::<PyString>() {
        Ok(s) => Ok(s.to_string_lossy().into_owned()),
        Err(_) => Err(json_err(
            path,
            format!("invalid key: {}, expected a string", unexpected(k)),
        )),
    }
}

fn unknown(path: &str, key: &str, expected: &[&str]) -> SceneError {
    let list: Vec<String> = expected.iter().map(|e| format!("`{e}`")).collect();
    json_err(
        path,
        format!(
            "unknown field `{}`, expected one of {}",
            rccpack_core::limits::cut(key),
            list.join(", ")
        ),
    )
}

fn missing(path: &str, key: &str) -> SceneError {
    json_err(path, format!("missing field `{key}`"))
}

fn space_from(v: &Bound<'_, PyAny>, path: &str) -> Result<CoreSpace, SceneError> {
    let d = dict(v, path)?;
    let (mut x, mut y, mut w, mut h) = (0, 0, None, None);
    for (k, v) in d.iter() {
        let key = key_str(&k, path)?;
        let p = join(path, &key);
        match key.as_str() {
            "x" => x = int(&v, &p)?,
            "y" => y = int(&v, &p)?,
            "width" => w = Some(int(&v, &p)?),
            "height" => h = Some(int(&v, &p)?),
            _ => return Err(unknown(&p, &key, &["x", "y", "width", "height"])),
        }
    }
    Ok(CoreSpace {
        x,
        y,
        width: w.ok_or_else(|| missing(path, "width"))?,
        height: h.ok_or_else(|| missing(path, "height"))?,
    })
}

fn object_from(v: &Bound<'_, PyAny>, path: &str, index: usize) -> Result<CoreObject, SceneError> {
    let d = dict(v, path)?;
    let (mut id, mut class, mut x, mut y, mut w, mut h) = (None, None, None, None, None, None);
    let (mut fixed, mut turnable, mut turned) = (false, false, false);
    let boolean = |v: &Bound<'_, PyAny>, p: &str| match v.cast::<PyBool>() {
        Ok(b) => Ok(b.is_true()),
        Err(_) => Err(json_err(
            p,
            format!("invalid type: {}, expected a boolean", unexpected(v)),
        )),
    };
    for (k, v) in d.iter() {
        let key = key_str(&k, path)?;
        let p = join(path, &key);
        match key.as_str() {
            "id" => id = Some(string(&v, &p)?),
            "class" => class = Some(string(&v, &p)?),
            "x" => x = opt_int(&v, &p)?,
            "y" => y = opt_int(&v, &p)?,
            "width" => w = Some(int(&v, &p)?),
            "height" => h = Some(int(&v, &p)?),
            "fixed" => fixed = boolean(&v, &p)?,
            "turnable" => turnable = boolean(&v, &p)?,
            "turned" => turned = boolean(&v, &p)?,
            _ => {
                return Err(unknown(
                    &p,
                    &key,
                    &[
                        "id", "class", "x", "y", "width", "height", "fixed", "turnable", "turned",
                    ],
                ))
            }
        }
    }
    let class = class.ok_or_else(|| missing(path, "class"))?;
    Ok(CoreObject {
        id: id.unwrap_or_else(|| format!("{class}{index}")),
        x,
        y,
        width: w.ok_or_else(|| missing(path, "width"))?,
        height: h.ok_or_else(|| missing(path, "height"))?,
        fixed,
        turnable,
        turned,
        class,
    })
}

/// A scene from a dict in the docs/scenes.md#fields JSON form, validated; errors carry
/// the field path (`objects[3].x`).
pub(crate) fn scene_from_dict(v: &Bound<'_, PyAny>) -> Result<CoreScene, SceneError> {
    let d = dict(v, "")?;
    let (mut space, mut grid, mut objects) = (None, 10, None);
    for (k, v) in d.iter() {
        let key = key_str(&k, "")?;
        match key.as_str() {
            "space" => space = Some(space_from(&v, "space")?),
            "grid" => grid = int(&v, "grid")?,
            "objects" => {
                let items: Vec<Bound<'_, PyAny>> = if let Ok(list) = v.cast::<PyList>() {
                    list.iter().collect()
                } else if let Ok(tuple) = v.cast::<PyTuple>() {
                    tuple.iter().collect()
                } else {
                    return Err(json_err(
                        "objects",
                        format!("invalid type: {}, expected a list", unexpected(&v)),
                    ));
                };
                let mut out = Vec::with_capacity(items.len());
                for (i, o) in items.iter().enumerate() {
                    out.push(object_from(o, &format!("objects[{i}]"), i)?);
                }
                objects = Some(out);
            }
            _ => return Err(unknown(&key, &key, &["space", "grid", "objects"])),
        }
    }
    let scene = CoreScene {
        space: space.ok_or_else(|| missing("", "space"))?,
        grid,
        objects: objects.ok_or_else(|| missing("", "objects"))?,
    };
    scene.validate()?;
    Ok(scene)
}

pub(crate) fn scene_to_dict<'py>(py: Python<'py>, s: &CoreScene) -> PyResult<Bound<'py, PyDict>> {
    let space = PyDict::new(py);
    space.set_item("x", s.space.x)?;
    space.set_item("y", s.space.y)?;
    space.set_item("width", s.space.width)?;
    space.set_item("height", s.space.height)?;
    let mut objects = Vec::with_capacity(s.objects.len());
    for o in &s.objects {
        let d = PyDict::new(py);
        d.set_item("id", &o.id)?;
        d.set_item("class", &o.class)?;
        if let Some(x) = o.x {
            d.set_item("x", x)?;
        }
        if let Some(y) = o.y {
            d.set_item("y", y)?;
        }
        d.set_item("width", o.width)?;
        d.set_item("height", o.height)?;
        if o.fixed {
            d.set_item("fixed", true)?;
        }
        if o.turnable {
            d.set_item("turnable", true)?;
        }
        if o.turned {
            d.set_item("turned", true)?;
        }
        objects.push(d);
    }
    let out = PyDict::new(py);
    out.set_item("space", space)?;
    out.set_item("grid", s.grid)?;
    out.set_item("objects", PyList::new(py, objects)?)?;
    Ok(out)
}

#[pymethods]
impl PyScene {
    #[new]
    #[pyo3(signature = (space, objects, grid = 10))]
    fn new(space: PySpace, objects: &Bound<'_, PyAny>, grid: i64) -> PyResult<Self> {
        let mut objs = Vec::new();
        for (i, item) in objects.try_iter()?.enumerate() {
            let item = item?;
            match item.cast::<PyObject>() {
                Ok(o) => objs.push(o.get().inner.clone()),
                Err(_) => {
                    return Err(PyTypeError::new_err(format!(
                        "objects[{i}]: expected an Object, found {}",
                        type_name(&item)
                    )))
                }
            }
        }
        let scene = CoreScene {
            space: space.inner,
            grid,
            objects: objs,
        };
        guard(|| scene.validate())?.map_err(|e| scene_error(e, None))?;
        Ok(PyScene { inner: scene })
    }

    /// Parse and validate one scene from JSON text (docs/scenes.md#fields).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        guard(|| CoreScene::from_json(text))?
            .map(PyScene::wrap)
            .map_err(|e| scene_error(e, None))
    }

    /// A scene from a dict in the JSON form (`"class"`, not `cls`).
    #[staticmethod]
    fn from_dict(d: &Bound<'_, PyAny>) -> PyResult<Self> {
        guard(|| scene_from_dict(d))?
            .map(PyScene::wrap)
            .map_err(|e| scene_error(e, None))
    }

    /// The JSON form as a dict (what `from_dict` reads).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        scene_to_dict(py, &self.inner)
    }

    /// Pretty JSON, byte for byte what the command line writes.
    fn to_json(&self) -> String {
        self.inner.to_json()
    }

    #[getter]
    fn space(&self) -> PySpace {
        PySpace {
            inner: self.inner.space,
        }
    }
    #[getter]
    fn grid(&self) -> i64 {
        self.inner.grid
    }
    /// The objects, in file order (a new tuple of immutable objects).
    #[getter]
    fn objects<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let items: Vec<Bound<'py, PyObject>> = self
            .inner
            .objects
            .iter()
            .map(|o| Bound::new(py, PyObject { inner: o.clone() }))
            .collect::<PyResult<_>>()?;
        PyTuple::new(py, items)
    }
    /// The distinct classes, in order of first appearance.
    #[getter]
    fn classes(&self) -> Vec<String> {
        self.inner.classes().into_iter().map(String::from).collect()
    }
    /// Whether every object is placed.
    #[getter]
    fn complete(&self) -> bool {
        self.inner.is_complete()
    }
    /// The object with this id, or `None`.
    fn get(&self, id: &str) -> Option<PyObject> {
        self.inner
            .objects
            .iter()
            .find(|o| o.id == id)
            .map(|o| PyObject { inner: o.clone() })
    }
    fn __len__(&self) -> usize {
        self.inner.objects.len()
    }
    fn __repr__(&self) -> String {
        let s = &self.inner;
        format!(
            "<Scene {}x{} grid {}: {} objects, {} placed>",
            s.space.width,
            s.space.height,
            s.grid,
            s.objects.len(),
            s.objects.iter().filter(|o| o.is_placed()).count()
        )
    }
    fn __str__(&self) -> String {
        self.inner.to_json()
    }
}
