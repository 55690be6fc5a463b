"""Scenes: construction, JSON and dict forms, errors with field paths."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

import rccpack

SMALL: dict[str, Any] = {
    "space": {"width": 100, "height": 100},
    "objects": [
        {"id": "b1", "class": "B", "x": 0, "y": 20, "width": 20, "height": 20},
        {"id": "r1", "class": "R", "x": 0, "y": 0, "width": 20, "height": 20},
        {"class": "R", "width": 20, "height": 20},
    ],
}


def test_objects_are_attributes() -> None:
    s = rccpack.Scene.from_dict(SMALL)
    assert len(s) == 3
    assert s.grid == 10
    assert (s.space.x, s.space.y, s.space.width, s.space.height) == (0, 0, 100, 100)
    b1 = s.objects[0]
    assert (b1.id, b1.cls, b1.x, b1.y, b1.width, b1.height, b1.fixed) == ("b1", "B", 0, 20, 20, 20, False)
    assert b1.placed
    r2 = s.objects[2]
    assert r2.id == "R2"  # docs/scenes.md#fields: <class><index>
    assert r2.x is None and r2.y is None and not r2.placed
    assert s.classes == ["B", "R"]
    assert not s.complete
    assert s.get("r1") == s.objects[1]
    assert s.get("nope") is None


def test_dict_and_json_round_trip(problem: rccpack.Scene, example: Path) -> None:
    again = rccpack.Scene.from_dict(problem.to_dict())
    assert again == problem
    assert rccpack.Scene.from_json(problem.to_json()) == problem
    assert json.loads(problem.to_json()) == problem.to_dict()
    assert problem.to_dict() == json.loads(
        rccpack.Scene.from_json((example / "problem.json").read_text()).to_json()
    )


def test_constructor_validates() -> None:
    space = rccpack.Space(100, 100)
    a = rccpack.Object("a", "R", 20, 20, x=0, y=0)
    b = rccpack.Object("b", "R", 20, 20, x=10, y=10)
    assert len(rccpack.Scene(space, [a, b.at(20, 0)])) == 2
    with pytest.raises(rccpack.SceneError) as e:
        rccpack.Scene(space, [a, b])
    assert e.value.path.startswith("objects[")
    assert "overlap" in str(e.value)
    assert e.value.kind == "overlap"
    with pytest.raises(TypeError):
        rccpack.Scene(space, [a, "b"])  # type: ignore[list-item]


@pytest.mark.parametrize(
    ("patch", "path", "words"),
    [
        ({"x": 12.5}, "objects[0].x", "floating point `12.5`"),
        ({"x": True}, "objects[0].x", "boolean"),
        ({"x": "3"}, "objects[0].x", "string"),
        ({"x": 2**70}, "objects[0].x", "out of range"),
        ({"colour": "red"}, "objects[0].colour", "unknown field `colour`"),
        ({"width": -1}, "objects[0]", "width"),
        ({"class": 3}, "objects[0].class", "expected a string"),
        ({"fixed": 1}, "objects[0].fixed", "expected a boolean"),
    ],
)
def test_dict_errors_name_the_field(patch: dict[str, Any], path: str, words: str) -> None:
    d = json.loads(json.dumps(SMALL))
    d["objects"][0].update(patch)
    with pytest.raises(rccpack.SceneError) as e:
        rccpack.Scene.from_dict(d)
    assert e.value.path.startswith(path), e.value.path
    assert words in str(e.value)
    assert isinstance(e.value, rccpack.Error)
    assert isinstance(e.value, ValueError)


def test_dict_accepts_a_tuple_of_objects() -> None:
    d = dict(SMALL)
    d["objects"] = tuple(SMALL["objects"])
    assert rccpack.Scene.from_dict(d) == rccpack.Scene.from_dict(SMALL)


def test_dict_missing_fields() -> None:
    with pytest.raises(rccpack.SceneError, match="missing field `space`"):
        rccpack.Scene.from_dict({"objects": []})
    with pytest.raises(rccpack.SceneError, match="missing field `height`") as e:
        rccpack.Scene.from_dict({"space": {"width": 1}, "objects": []})
    assert e.value.path == "space"
    with pytest.raises(rccpack.SceneError, match="expected a dict"):
        rccpack.Scene.from_dict([])


def test_json_errors_name_the_field() -> None:
    text = json.dumps(SMALL).replace('"x": 0, "y": 20', '"x": 0.5, "y": 20')
    with pytest.raises(rccpack.SceneError) as e:
        rccpack.Scene.from_json(text)
    assert e.value.path == "objects[0].x"
    assert "line 1 column" in e.value.message
    with pytest.raises(rccpack.SceneError, match="found an array"):
        rccpack.Scene.from_json("[]")


def test_load_scene_errors(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        rccpack.load_scene(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"space": {"width": 10, "height": 10}, "objects": [{"class": "R", "width": 1.0, "height": 1}]}')
    with pytest.raises(rccpack.SceneError) as e:
        rccpack.load_scene(bad)
    assert e.value.file == str(bad)
    assert str(e.value).startswith(f"{bad}: objects[0].width:")
    demos = tmp_path / "demos.json"
    demos.write_text(json.dumps([SMALL, {"space": {"width": 5, "height": 5}, "objects": [], "grid": 0}]))
    with pytest.raises(rccpack.SceneError) as e:
        rccpack.load_scenes(demos)
    assert e.value.path.startswith("[1]")


def test_scenes_to_json_round_trip(demos: list[rccpack.Scene], example: Path) -> None:
    text = rccpack.scenes_to_json(demos)
    assert len(json.loads(text)) == len(json.loads((example / "demos.json").read_text()))
    assert [rccpack.Scene.from_dict(d) for d in json.loads(text)] == demos


def test_measured_demonstrations_take_float_coordinates(tmp_path: Path) -> None:
    """Demonstrations as a camera records them: fractions and a 2-px
    overlap go to the grid, as `rccpack learn` reads them."""
    import json

    space = {"x": 0, "y": 0, "width": 100, "height": 100}
    demo = {
        "space": space,
        "grid": 10,
        "objects": [
            {"id": "a", "class": "A", "x": 14.9, "y": 20.0, "width": 10, "height": 10},
            {"id": "b", "class": "A", "x": 22.9, "y": 20.0, "width": 10, "height": 10},
        ],
    }
    m = rccpack.measured([demo])
    (scene,) = m.scenes
    xs = {o.id: o.x for o in scene.objects}
    assert xs == {"a": 10, "b": 20}, xs
    assert [(mv["object"], mv["to"]) for mv in m.moves] == [("a", (10, 20)), ("b", (20, 20))]
    assert max(mv["distance"] for mv in m.moves) < 5
    # The same from a file, and from JSON text.
    f = tmp_path / "demos.json"
    f.write_text(json.dumps([demo]))
    same = [s.to_json() for s in m.scenes]
    assert [s.to_json() for s in rccpack.load_measured(f).scenes] == same
    assert [s.to_json() for s in rccpack.measured(json.dumps([demo])).scenes] == same
    # Exact reading refuses the fractions; a tolerance at half a step or more is refused.
    with pytest.raises(rccpack.SceneError):
        rccpack.measured([demo], tolerance=0)
    with pytest.raises(rccpack.Error, match="tolerance"):
        rccpack.measured([demo], tolerance=5)
    # Learning takes the snapped scenes.
    assert len(rccpack.learn(m.scenes * 3, samples=50).statements) > 0
