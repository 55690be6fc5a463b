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
    AskSession,
    Conflict,
    Error,
    Evaluation,
    InternalError,
    Learned,
    LearnError,
    Measured,
    Object,
    PriorsError,
    Question,
    Resemblance,
    Rule,
    RuleReport,
    RulesError,
    RuleSet,
    RunOutcome,
    SampleError,
    Sampler,
    Scene,
    SceneError,
    SolveStats,
    Space,
    Statement,
    SynthError,
    SynthResult,
    Task,
    __version__,
    _null_scene,
    ask,
    combine_priors,
    evaluate,
    learn,
    load_measured,
    load_rules,
    load_scene,
    load_scenes,
    measured,
    render,
    render_png,
    sample,
    scenes_to_json,
    synthesize,
    task_counts,
)


class Status(enum.Enum):
    """How a solve ended (docs/guide.md#synthesis)."""

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
    "AskSession",
    "Conflict",
    "Error",
    "Evaluation",
    "InternalError",
    "Learned",
    "LearnError",
    "Measured",
    "Object",
    "PriorsError",
    "Question",
    "Resemblance",
    "Rule",
    "RuleReport",
    "RulesError",
    "RuleSet",
    "RunOutcome",
    "SampleError",
    "Sampler",
    "Scene",
    "SceneError",
    "SolveStats",
    "Space",
    "Statement",
    "Status",
    "SynthError",
    "SynthResult",
    "Task",
    "__version__",
    "ask",
    "combine_priors",
    "evaluate",
    "learn",
    "load_measured",
    "load_rules",
    "load_scene",
    "load_scenes",
    "measured",
    "render",
    "render_png",
    "sample",
    "scenes_to_json",
    "synthesize",
    "task_counts",
]


def __getattr__(name: str) -> object:
    """`rccpack.strategies` after a plain `import rccpack`: the submodule
    (it needs Hypothesis) is imported on first use, not with the package."""
    if name == "strategies":
        import importlib

        return importlib.import_module(".strategies", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
