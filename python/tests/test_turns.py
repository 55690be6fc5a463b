"""Objects that turn through Python: the fields, the footprint, the
dictionary form, a box that fits only turned (docs/scenes.md#objects-that-turn)."""

from __future__ import annotations

import pytest

import rccpack


def pinwheel(turnable: bool) -> rccpack.Scene:
    blocks = [rccpack.Object(f"l{i}", "L", 20, 10, turnable=turnable) for i in range(4)]
    return rccpack.Scene(rccpack.Space(30, 30), blocks + [rccpack.Object("s", "S", 10, 10)])


def test_fields_footprint_and_dict_round_trip() -> None:
    o = rccpack.Object("a", "A", 20, 10, x=0, y=0, turned=True)
    assert (o.width, o.height, o.turned, o.turnable) == (20, 10, True, False)
    assert o.footprint == (10, 20)
    s = rccpack.Scene(rccpack.Space(40, 40), [o])
    d = s.to_dict()
    assert d["objects"][0]["turned"] is True
    assert "turnable" not in d["objects"][0]
    assert rccpack.Scene.from_dict(d).to_json() == s.to_json()


def test_bad_turns_name_the_field() -> None:
    with pytest.raises(rccpack.SceneError) as e:
        rccpack.Scene.from_json(
            '{"space":{"width":40,"height":40},"objects":[{"class":"A","width":10,"height":20,"turned":true}]}'
        )
    assert e.value.path == "objects[0].turned"
    with pytest.raises(rccpack.SceneError) as e:
        rccpack.Scene.from_dict(
            {"space": {"width": 40, "height": 40}, "objects": [{"class": "A", "width": 10, "height": 20, "turnable": 1}]}
        )
    assert e.value.path == "objects[0].turnable"


def test_a_box_that_fits_only_turned() -> None:
    none = rccpack.RuleSet.parse("")
    assert rccpack.synthesize(pinwheel(False), none).status == rccpack.Status.INFEASIBLE
    r = rccpack.synthesize(pinwheel(True), none)
    assert r.status == rccpack.Status.OPTIMAL
    assert r.scene is not None
    assert any(o.turned for o in r.scene.objects)
