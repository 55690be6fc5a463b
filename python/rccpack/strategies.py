"""Hypothesis strategies over rccpack: layouts that keep rules, scenes like
the demonstrations, and rule sets of the ``.rcc`` language.

Needs Hypothesis (``pip install hypothesis``, or the ``hypothesis`` extra of
the wheel); ``import rccpack`` alone does not.

>>> from hypothesis import given
>>> from rccpack import strategies
>>> @given(strategies.layouts(problem, rules, all_rules=True))
... def test_planner(layout): ...

Shrinking (every shrunk value is as valid as the first):

* :func:`layouts` draws a pool of distinct layouts with
  :func:`rccpack.sample` when the strategy is made, sorts it simplest first
  (the sum of the placed objects' grid coordinates: objects towards the
  space's origin) and shrinks towards the simplest failing layout of the
  pool, as the Rust strategy ``rccpack::sample::strategy::layouts`` does;
* :func:`scenes` shrinks by dropping movable objects and towards the first
  demonstration;
* :func:`rule_sets` shrinks to fewer rules and smaller formulas.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Optional, Union

from hypothesis import assume
from hypothesis import strategies as st

import rccpack

__all__ = ["layouts", "scenes", "rule_sets", "formulas", "RELATIONS"]

_Scenes = Union[rccpack.Scene, Sequence[rccpack.Scene]]

RELATIONS: tuple[str, ...] = tuple(f"{k}_{d}" for k in ("DR", "EC", "FL", "AL") for d in "NSEW")
"""The sixteen relations of the language (docs/language.md#relations)."""


def _scene_list(scenes: _Scenes) -> list[rccpack.Scene]:
    return [scenes] if isinstance(scenes, rccpack.Scene) else list(scenes)


def layouts(
    problem: rccpack.Scene,
    rules: rccpack.RuleSet,
    *,
    pool: int = 100,
    seed: int = 0,
    all_rules: bool = False,
    min_score: Optional[float] = None,
    like: Optional[_Scenes] = None,
    layout_node_limit: Optional[int] = None,
    time_limit: Optional[float] = None,
    contact: str = "point",
) -> st.SearchStrategy[rccpack.Scene]:
    """Complete layouts of `problem` that keep `rules` at the quality asked
    for (the optimum score by default; `all_rules`: score 1; `min_score`).

    Up to `pool` distinct layouts are drawn by :func:`rccpack.sample` (with
    `seed`) now, sorted simplest first; the strategy picks one and shrinks
    towards the simplest. Raises :class:`rccpack.SampleError` when no layout
    of that quality exists, :class:`rccpack.Error` when a limit struck
    before any.
    """
    found = list(
        rccpack.sample(
            problem,
            rules,
            n=pool,
            seed=seed,
            all_rules=all_rules,
            min_score=min_score,
            like=like,
            layout_node_limit=layout_node_limit,
            time_limit=time_limit,
            contact=contact,
        )
    )
    if not found:
        raise rccpack.Error("no layout: a limit stopped the sampler before any layout")
    g = max(problem.grid, 1)
    sx, sy = problem.space.x, problem.space.y
    movable = {o.id for o in problem.objects if not o.placed}

    def weight(s: rccpack.Scene) -> int:
        return sum(
            ((o.x or 0) - sx) // g + ((o.y or 0) - sy) // g for o in s.objects if o.id in movable
        )

    found.sort(key=weight)
    return st.sampled_from(found)


def _keep(scene: rccpack.Scene, rules: rccpack.RuleSet, contact: str) -> Optional[rccpack.Scene]:
    """Drop movable objects that break a rule until none does; None when a
    scene-level rule fails or a fixed object breaks a rule."""
    while True:
        ev = rccpack.evaluate(scene, rules, contact=contact)
        bad = {v for r in ev.rules for v in r.violators}
        scene_fails = any(
            r.quantifier is not None and r.satisfied < r.subjects and not r.violators for r in ev.rules
        )
        if not bad and not scene_fails:
            return scene
        if scene_fails or any(o.fixed and o.id in bad for o in scene.objects):
            return None
        scene = rccpack.Scene(scene.space, [o for o in scene.objects if o.id not in bad], grid=scene.grid)


def scenes(
    demos: _Scenes,
    keep: Optional[rccpack.RuleSet] = None,
    contact: str = "point",
) -> st.SearchStrategy[rccpack.Scene]:
    """Scenes from the demonstrations' distribution: the learner's null
    model (docs/guide.md#learning) re-places the movable objects of a demonstration at
    random, each kept with probability about 9/10 (shrinking drops them).
    With `keep`, objects that break those rules are dropped too (and
    scenes whose scene-level rules fail are rejected), so every scene keeps
    them.
    """
    demos = _scene_list(demos)
    if not demos:
        raise rccpack.Error("scenes() needs at least one demonstration")
    most = max(len(d.objects) for d in demos)

    @st.composite
    def draw(draw: st.DrawFn) -> rccpack.Scene:
        index = draw(st.integers(0, len(demos) - 1))
        seed = draw(st.integers(0, 2**64 - 1))
        mask = draw(st.lists(st.integers(0, 9).map(lambda k: k != 0), min_size=most, max_size=most))
        scene = rccpack._null_scene(demos, seed, index)
        objects = [o for o, m in zip(scene.objects, mask) if o.fixed or m]
        kept = rccpack.Scene(scene.space, objects, grid=scene.grid)
        if keep is None:
            return kept
        held = _keep(kept, keep, contact)
        assume(held is not None)
        assert held is not None
        return held

    return draw()


def formulas(
    subject: str,
    classes: Sequence[str],
    landmarks: Sequence[str] = (),
    max_leaves: int = 6,
    quantifiers: bool = True,
) -> st.SearchStrategy[str]:
    """Formulas over `subject` as `.rcc` text: atoms `REL(subject, target)`
    (a class of `classes`, `*` or `@landmark`, optionally quantified), `!`,
    `&` and `|`, fully parenthesised."""
    targets: list[st.SearchStrategy[str]] = [st.sampled_from(list(classes)), st.just("*")]
    quant = st.sampled_from(["", "every ", "some ", "no "]) | st.integers(0, 3).flatmap(
        lambda k: st.sampled_from([f"at least {k} ", f"at most {k} "])
    )
    target = st.one_of(*targets)
    if quantifiers:
        target = st.tuples(quant, target).map("".join)
    if landmarks:
        target = target | st.sampled_from([f"@{x}" for x in landmarks])
    atom = st.tuples(st.sampled_from(RELATIONS), target).map(lambda a: f"{a[0]}({subject}, {a[1]})")

    def extend(inner: st.SearchStrategy[str]) -> st.SearchStrategy[str]:
        return (
            inner.map(lambda f: f"!({f})")
            | st.tuples(inner, inner).map(lambda p: f"({p[0]}) & ({p[1]})")
            | st.tuples(inner, inner).map(lambda p: f"({p[0]}) | ({p[1]})")
        )

    return st.recursive(atom, extend, max_leaves=max_leaves)


def rule_sets(
    classes: Sequence[str] = ("R", "G", "B"),
    landmarks: Sequence[str] = (),
    *,
    min_rules: int = 0,
    max_rules: int = 5,
    max_leaves: int = 6,
    hard: bool = True,
    quantifiers: bool = True,
) -> st.SearchStrategy[rccpack.RuleSet]:
    """Rule sets of the `.rcc` language over `classes` (and `@landmarks`):
    unique names `r0`, `r1`, …, a subject class each, a weight or `hard`
    (when `hard`), random formulas. Parsed with :meth:`rccpack.RuleSet.parse`,
    so every value is a valid rule set; shrinks to fewer rules, smaller
    formulas, weight 1."""
    classes = list(classes)
    if not classes:
        raise rccpack.Error("rule_sets() needs at least one class")
    strengths = [st.just(""), st.integers(2, 5).map(lambda w: f" weight {w}")]
    if hard:
        strengths.append(st.just(" hard"))
    rule = st.tuples(
        st.sampled_from(classes).flatmap(
            lambda s: formulas(s, classes, landmarks, max_leaves, quantifiers)
        ),
        st.one_of(*strengths),
    )

    def build(rules: list[tuple[str, str]]) -> rccpack.RuleSet:
        text = "".join(f"rule r{i}{strength}: {f}\n" for i, (f, strength) in enumerate(rules))
        return rccpack.RuleSet.parse(text)

    return st.lists(rule, min_size=min_rules, max_size=max_rules).map(build)
