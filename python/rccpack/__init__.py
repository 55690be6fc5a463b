"""rccpack: learn spatial placement rules from demonstrations, lay out new
objects that keep them. Python bindings of the rccpack Rust library.

>>> import rccpack
>>> demos = rccpack.load_scenes("examples/box-packing/demos.json")
>>> learned = rccpack.learn(demos)
>>> result = rccpack.synthesize(rccpack.load_scene("examples/box-packing/problem.json"),
...                             learned.rules, like=demos)
>>> result.status
<Status.OPTIMAL: 'optimal'>
"""

from __future__ import annotations

import enum

from ._rccpack import (
    AskError,
    AskResult,
    Conflict,
    Error,
    Evaluation,
    InternalError,
    Learned,
    LearnError,
    Object,
    Question,
    Resemblance,
    Rule,
    RuleReport,
    RulesError,
    RuleSet,
    Scene,
    SceneError,
    SolveStats,
    Space,
    Statement,
    SynthError,
    SynthResult,
    __version__,
    ask,
    evaluate,
    learn,
    load_rules,
    load_scene,
    load_scenes,
    render,
    render_png,
    scenes_to_json,
    synthesize,
)


class Status(enum.Enum):
    """How a solve ended (SPEC §9)."""

    OPTIMAL = "optimal"
    """Proved optimal."""
    FEASIBLE = "feasible"
    """A limit (or Ctrl-C) stopped the search; the layout is the best found."""
    INFEASIBLE = "infeasible"
    """No placement meets the hard requirements (see `SynthResult.conflict`)."""
    UNKNOWN = "unknown"
    """A limit stopped the search before any layout was found."""


__all__ = [
    "AskError",
    "AskResult",
    "Conflict",
    "Error",
    "Evaluation",
    "InternalError",
    "Learned",
    "LearnError",
    "Object",
    "Question",
    "Resemblance",
    "Rule",
    "RuleReport",
    "RulesError",
    "RuleSet",
    "Scene",
    "SceneError",
    "SolveStats",
    "Space",
    "Statement",
    "Status",
    "SynthError",
    "SynthResult",
    "__version__",
    "ask",
    "evaluate",
    "learn",
    "load_rules",
    "load_scene",
    "load_scenes",
    "render",
    "render_png",
    "scenes_to_json",
    "synthesize",
]
