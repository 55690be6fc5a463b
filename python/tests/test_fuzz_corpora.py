"""No input reaches a Rust panic: every committed fuzz corpus and regression
file (`fuzz/corpus/*`, `fuzz/regressions/*`) goes through the Python entry
points; each either works or raises an `rccpack.Error` (never
`InternalError`, never a crash of the interpreter)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

import rccpack

ROOT = Path(__file__).resolve().parents[2]
FILES = sorted(p for d in ("corpus", "regressions") for p in (ROOT / "fuzz" / d).glob("*/*") if p.is_file())

SMALL = rccpack.Scene.from_json(
    """{"space":{"width":60,"height":60},"grid":10,"objects":[
    {"id":"w","class":"W","x":0,"y":0,"width":60,"height":10,"fixed":true},
    {"id":"r1","class":"R","x":0,"y":10,"width":10,"height":10},
    {"id":"g1","class":"G","x":30,"y":10,"width":20,"height":10},
    {"id":"b1","class":"B","x":0,"y":20,"width":10,"height":10},
    {"id":"b2","class":"B","width":10,"height":10}]}"""
)
RULES = rccpack.RuleSet.parse(
    "rule a: DR_N(B, R) | EC_E(B, *)\nrule b weight 2: FL_S(R, some G)\nrule c: some G: AL_S(G, R)\n"
)


def scenes_in(text: str) -> list[Any]:
    try:
        value = json.loads(text)
    except (ValueError, RecursionError):
        return []
    return value if isinstance(value, list) else [value]


def exercise(text: str) -> None:
    try:
        rules = rccpack.RuleSet.parse(text)
    except rccpack.RulesError as e:
        assert e.line >= 1 and e.column >= 1 and e.report
    else:
        assert rccpack.RuleSet.parse(str(rules)) == rules
        try:
            rccpack.evaluate(SMALL, rules)
        except rccpack.RulesError:
            pass  # a landmark the small scene lacks
    candidates: list[rccpack.Scene] = []
    try:
        candidates.append(rccpack.Scene.from_json(text))
    except rccpack.SceneError as e:
        assert isinstance(e.path, str)
    for value in scenes_in(text)[:20]:
        try:
            candidates.append(rccpack.Scene.from_dict(value))
        except rccpack.SceneError as e:
            assert isinstance(e.path, str)
    for s in candidates:
        assert rccpack.Scene.from_dict(s.to_dict()) == s
        rccpack.evaluate(s, RULES)
        rccpack.render(s, RULES)
        if not s.complete and len(s) <= 30:
            try:
                rccpack.synthesize(s, RULES, node_limit=300, time_limit=2.0)
            except rccpack.SynthError:
                pass


def test_corpora_exist() -> None:
    assert len(FILES) > 1000


@pytest.mark.parametrize("kind", ["scene", "rules", "learn", "synth", "studio"])
def test_no_panic_on_corpus(kind: str) -> None:
    files = [p for p in FILES if p.parent.name == kind]
    for p in files:
        text = p.read_bytes().decode("utf-8", errors="replace")
        try:
            exercise(text)
        except rccpack.InternalError as e:  # pragma: no cover - the failure
            pytest.fail(f"{p}: {e}")
