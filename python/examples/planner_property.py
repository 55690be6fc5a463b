"""A property test of a pick-order planner with Hypothesis, over layouts
that keep the rules learned from the bundled example (the Python twin of
`examples/pick_order.rs`).

The planner decides in which order a gripper puts the blocks of a layout
into the box. A block comes down from the north (+y) along its own column
and must not sweep through a block already in place. The property: for
every layout a person would accept -- here, every layout that keeps every
rule learned from `examples/box-packing/demos.json` -- every block can be
placed in the planned order without crossing an already-placed one.

    python python/examples/planner_property.py      # the good planner holds,
                                                    # the buggy one is caught
    pytest python/examples/planner_property.py      # the same, as tests
"""

from __future__ import annotations

import sys
from functools import lru_cache
from pathlib import Path
from typing import Callable, Optional

from hypothesis import HealthCheck, find, given, settings
from hypothesis import strategies as st

import rccpack
from rccpack import strategies

TASK = Path(__file__).resolve().parents[2] / "examples" / "box-packing"
Planner = Callable[[rccpack.Scene], list[rccpack.Object]]


def plan(scene: rccpack.Scene) -> list[rccpack.Object]:
    """The planner under test: south to north, then west to east."""
    return sorted((o for o in scene.objects if not o.fixed), key=lambda o: (o.y or 0, o.x or 0))


def plan_with_a_planted_bug(scene: rccpack.Scene) -> list[rccpack.Object]:
    """A planner with a bug that only some layouts show: it orders rows by
    a coarse 50-unit band (a "quantised height map"), west to east within a
    band, so a block stacked on another one in the same band can come
    first."""
    return sorted((o for o in scene.objects if not o.fixed), key=lambda o: ((o.y or 0) // 50, o.x or 0))


def first_crossing(order: list[rccpack.Object]) -> Optional[tuple[str, str]]:
    """The first block whose way down from the north crosses a block placed
    before it, if any."""
    for k, a in enumerate(order):
        assert a.x is not None and a.y is not None
        for b in order[:k]:
            assert b.x is not None and b.y is not None
            same_column = b.x < a.x + a.width and a.x < b.x + b.width
            if same_column and b.y + b.height > a.y + a.height:
                return (a.id, b.id)
    return None


@lru_cache(maxsize=1)
def task() -> tuple[rccpack.Scene, rccpack.RuleSet]:
    t = rccpack.Task.load(TASK)
    return t.problem, t.learn().rules


@lru_cache(maxsize=1)
def accepted_layouts() -> st.SearchStrategy[rccpack.Scene]:
    problem, rules = task()
    return strategies.layouts(problem, rules, all_rules=True, pool=200, seed=24)


def check(planner: Planner) -> None:
    @settings(max_examples=64, database=None, suppress_health_check=list(HealthCheck))
    @given(accepted_layouts())
    def prop(layout: rccpack.Scene) -> None:
        assert first_crossing(planner(layout)) is None

    prop()


def simplest_failure(planner: Planner) -> rccpack.Scene:
    """The simplest accepted layout the planner fails on (Hypothesis
    finds one and shrinks it)."""
    return find(
        accepted_layouts(),
        lambda layout: first_crossing(planner(layout)) is not None,
        settings=settings(max_examples=500, database=None, derandomize=True, suppress_health_check=list(HealthCheck)),
    )


def test_the_planner_packs_every_accepted_layout() -> None:
    check(plan)


def test_the_planted_bug_is_found() -> None:
    layout = simplest_failure(plan_with_a_planted_bug)
    assert first_crossing(plan_with_a_planted_bug(layout)) is not None


def main() -> int:
    check(plan)
    print("planner: every sampled layout can be packed in the planned order")
    layout = simplest_failure(plan_with_a_planted_bug)
    crossing = first_crossing(plan_with_a_planted_bug(layout))
    placed = [f"{o.id}@({o.x},{o.y})" for o in layout.objects if not o.fixed]
    print(f"planted bug found: {crossing[0]} crosses {crossing[1]} (simplest failing layout: {placed})"
          if crossing else "planted bug: not found")
    return 0


if __name__ == "__main__":
    sys.exit(main())
