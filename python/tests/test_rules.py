"""Rule sets: parsing, printing, attributes, located errors."""

from __future__ import annotations

from pathlib import Path

import pytest

import rccpack

TEXT = """\
# blue blocks go north of red ones
rule blue_north_of_red: DR_N(B, R)
rule red_touches_red weight 2: EC_E(R, R) | EC_W(R, R)
rule green_east p 1.0e-8: DR_E(G, R)
rule red_inside hard: !DR_N(R, W) & !DR_S(R, W) & !DR_E(R, W) & !DR_W(R, W)
rule one_red_west: some R: EC_E(R, @w_west)
"""


def test_parse_and_attributes() -> None:
    rules = rccpack.RuleSet.parse(TEXT)
    assert len(rules) == 5
    assert rules.names == ["blue_north_of_red", "red_touches_red", "green_east", "red_inside", "one_red_west"]
    b = rules["blue_north_of_red"]
    assert (b.name, b.weight, b.hard, b.posterior, b.subject) == ("blue_north_of_red", 1.0, False, None, "B")
    assert b.reading == "every B is north of every R"
    assert b.text == "rule blue_north_of_red: DR_N(B, R)"
    assert rules[1].weight == 2.0
    g = rules[2]
    assert g.posterior == pytest.approx(1e-8)
    assert g.weight == pytest.approx(18.420680743952367)
    assert rules[-2].hard and rules[-2].weight == 0.0
    assert rules[4].scene_level and rules[4].formula.startswith("some R: ")
    assert "red_inside" in rules and "nope" not in rules
    assert [r.name for r in rules] == rules.names
    with pytest.raises(KeyError):
        rules["nope"]
    with pytest.raises(IndexError):
        rules[5]


def test_str_prints_rcc_that_parses_back() -> None:
    rules = rccpack.RuleSet.parse(TEXT)
    again = rccpack.RuleSet.parse(str(rules))
    assert again == rules
    assert str(again) == str(rules)


@pytest.mark.parametrize(
    ("text", "line", "column", "words"),
    [
        ("rule a: DR_N(B, R)\nrule b: XX_N(B, R)\n", 2, 9, "unknown relation `XX_N`"),
        ("rule a: DR_N(B, R)\nrule a: DR_S(B, R)\n", 2, 6, "a"),
        ("rule a: DR_N(B, R) & DR_N(G, R)\n", 1, 22, "subject"),
        ("rule a weight -1: DR_N(B, R)\n", 1, 15, "weight"),
        ("rule a: DR_N(B, R\n", 1, 18, "expected"),
        ("rule a: " + "(" * 300 + "DR_N(B, R)" + ")" * 300 + "\n", 1, None, "nest"),
    ],
)
def test_rules_error_is_located(text: str, line: int, column: int | None, words: str) -> None:
    with pytest.raises(rccpack.RulesError) as e:
        rccpack.RuleSet.parse(text, file="t.rcc")
    err = e.value
    assert err.line == line
    if column is not None:
        assert err.column == column
    assert words in err.message
    assert err.kind.islower() and err.kind
    assert str(err).startswith(f"t.rcc:{err.line}:{err.column}: ")
    # the caret text: the offending source line with a marker under it
    assert f"t.rcc:{err.line}:{err.column}" in err.report
    assert "│" in err.report or "^" in err.report
    assert err.diagnostics[0] == (err.line, err.column, err.message)
    assert isinstance(err, rccpack.Error)


def test_load_rules(tmp_path: Path, example: Path) -> None:
    pilot = rccpack.load_rules(example / "pilot.rcc")
    assert len(pilot) > 0
    bad = tmp_path / "bad.rcc"
    bad.write_text("rule a: DR_N(B, R)\n\nrule b: DR_Q(B, R)\n")
    with pytest.raises(rccpack.RulesError) as e:
        rccpack.load_rules(bad)
    assert (e.value.line, e.value.file) == (3, str(bad))
    assert str(e.value).startswith(f"{bad}:3:9: ")
    with pytest.raises(FileNotFoundError):
        rccpack.load_rules(tmp_path / "missing.rcc")
    latin = tmp_path / "latin.rcc"
    latin.write_bytes(b"rule caf\xe9: DR_N(B, R)\n")
    with pytest.raises(rccpack.Error, match="byte"):
        rccpack.load_rules(latin)


def test_check_against_a_scene(problem: rccpack.Scene) -> None:
    rules = rccpack.RuleSet.parse("rule a: DR_N(B, R)\nrule b: DR_N(Q, R)\n")
    with pytest.raises(rccpack.RulesError) as e:
        rules.check(problem)
    assert e.value.line == 2 and "Q" in e.value.message
    assert e.value.kind == "unknown_class"
    lm = rccpack.RuleSet.parse("rule a: EC_E(B, @nowhere)\n")
    with pytest.raises(rccpack.RulesError, match="nowhere"):
        lm.check(problem)
    # evaluating a rule whose landmark is absent is bad input (docs/language.md#landmarks)
    with pytest.raises(rccpack.RulesError, match="nowhere") as e2:
        rccpack.evaluate(problem, lm)
    assert (e2.value.line, e2.value.column) == (1, 9)


def test_evaluate() -> None:
    scene = rccpack.Scene.from_json(
        """{"space": {"width": 100, "height": 100}, "objects": [
        {"id": "b1", "class": "B", "x": 0,  "y": 20, "width": 20, "height": 20},
        {"id": "r1", "class": "R", "x": 0,  "y": 0,  "width": 20, "height": 20},
        {"id": "r2", "class": "R", "x": 60, "y": 0,  "width": 20, "height": 20}]}"""
    )
    rules = rccpack.RuleSet.parse(
        "rule blue_north_of_red: DR_N(B, R)\nrule red_touches_red weight 2: EC_E(R, R) | EC_W(R, R)\n"
    )
    ev = rccpack.evaluate(scene, rules)
    assert (ev.satisfied_weight, ev.total_weight) == (1.0, 5.0)
    assert ev.score == pytest.approx(0.2)
    assert ev.rules[1].violators == ["r1", "r2"]
    assert (ev.rules[0].subjects, ev.rules[0].satisfied) == (1, 1)
    assert rccpack.evaluate(scene, rules, contact="edge").score == pytest.approx(0.2)
    with pytest.raises(rccpack.Error, match="unknown contact mode `corner`"):
        rccpack.evaluate(scene, rules, contact="corner")
