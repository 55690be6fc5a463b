"""`rccpack.strategies` for Hypothesis: every value valid, and a planted
planner bug found and shrunk to the simplest failing layout of the pool."""

from __future__ import annotations

import sys
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import rccpack
from rccpack import strategies

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import planner_property as pp  # noqa: E402

FAST = settings(max_examples=40, database=None, deadline=None, suppress_health_check=list(HealthCheck))


@FAST
@given(strategies.rule_sets(classes=("R", "G"), landmarks=("w1",)))
def test_rule_sets_parse_and_print_back(rules: rccpack.RuleSet) -> None:
    again = rccpack.RuleSet.parse(str(rules))
    assert again == rules
    assert all(r.name == f"r{i}" for i, r in enumerate(rules))


@FAST
@given(st.data())
def test_scenes_keep_the_rules(data: st.DataObject) -> None:
    example = pp.TASK
    demos = rccpack.load_scenes(example / "demos.json")
    pilot = rccpack.load_rules(example / "pilot.rcc")
    scene = data.draw(strategies.scenes(demos, keep=pilot))
    assert scene.complete
    ev = rccpack.evaluate(scene, pilot)
    assert all(r.satisfied == r.subjects for r in ev.rules)
    plain = data.draw(strategies.scenes(demos[0]))
    assert plain.complete and len(plain) <= len(demos[0])


def test_layouts_are_sampled_layouts_simplest_first() -> None:
    problem, rules = pp.task()
    strat = strategies.layouts(problem, rules, all_rules=True, pool=30, seed=24)
    seen: list[rccpack.Scene] = []

    @FAST
    @given(strat)
    def prop(layout: rccpack.Scene) -> None:
        assert layout.complete and rccpack.evaluate(layout, rules).score == 1.0
        seen.append(layout)

    prop()
    assert seen
    # the strategy's shrink target is the simplest layout of the pool
    simplest = rccpack.strategies.layouts(problem, rules, all_rules=True, pool=30, seed=24)
    from hypothesis import find

    first = find(simplest, lambda s: True, settings=settings(database=None))
    g = problem.grid

    def weight(s: rccpack.Scene) -> int:
        return sum((o.x or 0) // g + (o.y or 0) // g for o in s.objects if not o.fixed)

    pool = list(rccpack.sample(problem, rules, n=30, all_rules=True, seed=24))
    assert weight(first) == min(weight(s) for s in pool)


def test_planted_planner_bug_is_found_and_shrunk() -> None:
    # the good planner holds on every accepted layout
    pp.check(pp.plan)
    layout = pp.simplest_failure(pp.plan_with_a_planted_bug)
    assert pp.first_crossing(pp.plan_with_a_planted_bug(layout)) is not None
    # shrunk: no simpler layout of the pool shows the bug
    problem, rules = pp.task()
    pool = list(rccpack.sample(problem, rules, n=200, all_rules=True, seed=24))
    g = problem.grid

    def weight(s: rccpack.Scene) -> int:
        return sum((o.x or 0) // g + (o.y or 0) // g for o in s.objects if not o.fixed)

    failing = [s for s in pool if pp.first_crossing(pp.plan_with_a_planted_bug(s)) is not None]
    assert failing, "the planted bug shows on some accepted layouts"
    assert len(failing) < len(pool), "and not on all of them"
    # Hypothesis shrinks the pool index towards the simplest layout, but the
    # predicate is not monotone in it, so the shrink can stop at a local
    # minimum: the shrunk layout is in the simpler half of the failing ones
    # (an unshrunk, random failing layout is not, half of the time).
    simpler = sum(weight(s) < weight(layout) for s in failing)
    assert simpler <= len(failing) // 2, (weight(layout), sorted(weight(s) for s in failing))


def test_strategies_is_an_attribute_after_a_plain_import() -> None:
    # A fresh interpreter: this file's own `from rccpack import strategies`
    # already imported the submodule here.
    import subprocess

    code = "import rccpack; print(callable(rccpack.strategies.rule_sets))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "True"
    missing = subprocess.run(
        [sys.executable, "-c", "import rccpack; rccpack.no_such_thing"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert "AttributeError" in missing.stderr and "no_such_thing" in missing.stderr
