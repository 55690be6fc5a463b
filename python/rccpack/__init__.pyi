"""Type stubs of rccpack (the native module `rccpack._rccpack` and the
pure-Python `Status`)."""

import enum
import os
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from typing import Any, Literal, Optional, Union, final

__version__: str

_Path = Union[str, "os.PathLike[str]"]
_Scenes = Union["Scene", Sequence["Scene"]]

# ---- errors ------------------------------------------------------------------

class Error(ValueError):
    """Base class of every rccpack error (the input is at fault)."""

class SceneError(Error):
    """A scene breaks docs/scenes.md; `path` names the field (`objects[3].x`)."""

    path: str
    message: str
    kind: str
    """`json`, `overlap`, `outside`, `duplicate_id`, `out_of_range`, …"""
    file: Optional[str]

class RulesError(Error):
    """Invalid `.rcc` text, located: `line`, `column`, `report` (caret)."""

    line: int
    column: int
    message: str
    kind: str
    """`syntax`, `unknown_relation`, `duplicate_name`, `unknown_class`, …"""
    report: str
    file: str
    diagnostics: list[tuple[int, int, str]]

class SynthError(Error):
    """A problem that cannot be used for synthesis."""

class LearnError(Error):
    """Learning cannot run (parameters, demonstrations, statements)."""

class AskError(Error):
    """The question loop cannot go on."""

class SampleError(Error):
    """Sampling found no layout of the quality asked for."""

    kind: str
    """`infeasible`, `no_layout`, `synth`, …"""

class PriorsError(Error):
    """A priors file or task counts are damaged or do not fit; `field` names
    the field (`version`, `kinds[3].prior`, `hash`, `counts[2].templates`)."""

    field: str
    file: Optional[str]

class InternalError(Error):
    """A bug in rccpack (a Rust panic caught at the boundary)."""

# ---- scenes ------------------------------------------------------------------

@final
class Space:
    def __new__(cls, width: int, height: int, x: int = 0, y: int = 0) -> Space: ...
    @property
    def x(self) -> int: ...
    @property
    def y(self) -> int: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...

@final
class Object:
    def __new__(
        klass,
        id: str,
        cls: str,
        width: int,
        height: int,
        x: Optional[int] = None,
        y: Optional[int] = None,
        fixed: bool = False,
        turnable: bool = False,
        turned: bool = False,
    ) -> Object: ...
    @property
    def id(self) -> str: ...
    @property
    def cls(self) -> str: ...
    @property
    def x(self) -> Optional[int]: ...
    @property
    def y(self) -> Optional[int]: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def fixed(self) -> bool: ...
    @property
    def turnable(self) -> bool: ...
    @property
    def turned(self) -> bool: ...
    @property
    def footprint(self) -> tuple[int, int]: ...
    @property
    def placed(self) -> bool: ...
    def at(self, x: Optional[int], y: Optional[int]) -> Object:
        """The same object at another position."""

@final
class Scene:
    def __new__(cls, space: Space, objects: Sequence[Object], grid: int = 10) -> Scene: ...
    @staticmethod
    def from_json(text: str) -> Scene: ...
    @staticmethod
    def from_dict(d: Any) -> Scene: ...
    def to_dict(self) -> dict[str, Any]: ...
    def to_json(self) -> str: ...
    @property
    def space(self) -> Space: ...
    @property
    def grid(self) -> int: ...
    @property
    def objects(self) -> tuple[Object, ...]: ...
    @property
    def classes(self) -> list[str]: ...
    @property
    def complete(self) -> bool: ...
    def get(self, id: str) -> Optional[Object]: ...
    def __len__(self) -> int: ...

def load_scene(path: _Path) -> Scene: ...
def load_scenes(path: _Path) -> list[Scene]: ...

@final
class Measured:
    @property
    def scenes(self) -> list[Scene]: ...
    @property
    def moves(self) -> list[dict[str, Any]]: ...

def load_measured(path: _Path, tolerance: Optional[float] = None) -> Measured: ...
def measured(demos: Union[str, Sequence[Any]], tolerance: Optional[float] = None) -> Measured: ...
def scenes_to_json(scenes: _Scenes) -> str: ...

# ---- rules -------------------------------------------------------------------

@final
class Rule:
    @property
    def name(self) -> str: ...
    @property
    def weight(self) -> float: ...
    @property
    def hard(self) -> bool: ...
    @property
    def posterior(self) -> Optional[float]: ...
    @property
    def reading(self) -> str: ...
    @property
    def subject(self) -> str: ...
    @property
    def scene_level(self) -> bool: ...
    @property
    def formula(self) -> str: ...
    @property
    def comments(self) -> list[str]: ...
    @property
    def text(self) -> str: ...

@final
class RuleSet:
    @staticmethod
    def parse(text: str, file: str = "<rules>") -> RuleSet: ...
    def check(self, scene: Scene) -> None: ...
    @property
    def rules(self) -> tuple[Rule, ...]: ...
    @property
    def names(self) -> list[str]: ...
    @property
    def classes(self) -> list[str]: ...
    def __len__(self) -> int: ...
    def __getitem__(self, key: Union[int, str], /) -> Rule: ...
    def __contains__(self, name: object, /) -> bool: ...
    def __iter__(self) -> Iterator[Rule]: ...

def load_rules(path: _Path) -> RuleSet: ...

# ---- evaluate ----------------------------------------------------------------

@final
class RuleReport:
    @property
    def name(self) -> str: ...
    @property
    def weight(self) -> float: ...
    @property
    def hard(self) -> bool: ...
    @property
    def subjects(self) -> int: ...
    @property
    def satisfied(self) -> int: ...
    @property
    def violators(self) -> list[str]: ...
    @property
    def quantifier(self) -> Optional[str]: ...

@final
class Evaluation:
    @property
    def score(self) -> float: ...
    @property
    def satisfied_weight(self) -> float: ...
    @property
    def total_weight(self) -> float: ...
    @property
    def hard_violations(self) -> int: ...
    @property
    def off_grid(self) -> list[str]: ...
    @property
    def rules(self) -> tuple[RuleReport, ...]: ...
    def to_json(self) -> str: ...

def evaluate(scene: Scene, rules: RuleSet, contact: str = "point") -> Evaluation: ...

# ---- learn -------------------------------------------------------------------

@final
class Statement:
    @property
    def name(self) -> str: ...
    @property
    def formula(self) -> str: ...
    @property
    def subject(self) -> str: ...
    @property
    def english(self) -> str: ...
    @property
    def candidate(self) -> bool: ...
    @property
    def n(self) -> int: ...
    @property
    def satisfied(self) -> Optional[int]: ...
    @property
    def q(self) -> Optional[float]: ...
    @property
    def p(self) -> Optional[float]: ...
    @property
    def log10_likelihood(self) -> Optional[float]: ...
    @property
    def log10_posterior(self) -> Optional[float]: ...
    @property
    def posterior(self) -> Optional[float]: ...
    @property
    def learned(self) -> bool: ...
    @property
    def rank(self) -> Optional[int]: ...
    @property
    def implied_by(self) -> Optional[str]: ...

@final
class Learned:
    @property
    def rules(self) -> RuleSet: ...
    def to_rcc(self) -> str: ...
    def report_json(self) -> str: ...
    def report(self) -> dict[str, Any]: ...
    @property
    def statements(self) -> tuple[Statement, ...]: ...
    @property
    def demonstrations(self) -> int: ...
    @property
    def candidates(self) -> int: ...
    def __len__(self) -> int: ...

def learn(
    demos: _Scenes,
    samples: int = 1000,
    cutoff: float = 0.01,
    seed: int = 0,
    templates: str = "third",
    statements: Optional[RuleSet] = None,
    prior: float = 0.5,
    epsilon: Optional[float] = None,
    contact: str = "point",
    priors: Optional[_Path] = None,
    slip_rate: float = 0.0,
) -> Learned: ...

# ---- priors learned across tasks -----------------------------------------------

def task_counts(
    folder: _Path, templates: str = "third", contact: str = "point"
) -> dict[str, Any]: ...
def combine_priors(
    counts: Iterable[Mapping[str, Any]],
    strength: int = 4,
    rule_out_after: int = 10,
    templates: str = "third",
    contact: str = "point",
) -> str: ...

# ---- synthesize --------------------------------------------------------------

class Status(enum.Enum):
    OPTIMAL = "optimal"
    FEASIBLE = "feasible"
    INFEASIBLE = "infeasible"
    UNKNOWN = "unknown"

@final
class Resemblance:
    @property
    def cost(self) -> int: ...
    @property
    def proven(self) -> bool: ...
    @property
    def bound(self) -> int: ...

@final
class Conflict:
    @property
    def objects_cannot_fit(self) -> bool: ...
    @property
    def hard_rules(self) -> list[str]: ...
    @property
    def limit_struck(self) -> bool: ...

@final
class SolveStats:
    @property
    def nodes(self) -> int: ...
    @property
    def conflicts(self) -> int: ...
    @property
    def time_ms(self) -> float: ...
    @property
    def time_to_first_ms(self) -> Optional[float]: ...
    @property
    def time_to_best_ms(self) -> Optional[float]: ...

@final
class SynthResult:
    @property
    def status(self) -> Status: ...
    @property
    def scene(self) -> Optional[Scene]: ...
    @property
    def evaluation(self) -> Optional[Evaluation]: ...
    @property
    def score(self) -> Optional[float]: ...
    @property
    def score_bound(self) -> Optional[float]: ...
    @property
    def resemblance(self) -> Optional[Resemblance]: ...
    @property
    def conflict(self) -> Optional[Conflict]: ...
    @property
    def stats(self) -> SolveStats: ...
    @property
    def interrupted(self) -> bool: ...
    def report_json(self) -> str:
        """The JSON `rccpack synth --report` writes."""

def synthesize(
    problem: Scene,
    rules: RuleSet,
    like: Optional[_Scenes] = None,
    time_limit: Optional[float] = None,
    node_limit: Optional[int] = None,
    seed: int = 0,
    contact: str = "point",
    warm_start: Optional[_Scenes] = None,
    progress: Optional[Callable[[float, float], object]] = None,
) -> SynthResult: ...

# ---- render ------------------------------------------------------------------

def render(
    scene: Scene,
    rules: Optional[RuleSet] = None,
    like: Optional[_Scenes] = None,
    contact: str = "point",
    scale: float = 1.0,
    title: Optional[str] = None,
) -> str: ...
def render_png(
    scene: Scene,
    rules: Optional[RuleSet] = None,
    like: Optional[_Scenes] = None,
    contact: str = "point",
    scale: float = 1.0,
    title: Optional[str] = None,
) -> bytes: ...

# ---- ask ---------------------------------------------------------------------

@final
class Question:
    @property
    def number(self) -> int: ...
    @property
    def rule(self) -> str: ...
    @property
    def statement(self) -> str: ...
    @property
    def english(self) -> str: ...
    @property
    def probe(self) -> Scene: ...
    @property
    def broken(self) -> list[str]: ...
    @property
    def also_broken(self) -> list[str]: ...
    @property
    def group(self) -> list[str]:
        """For a group question, every rule the probe breaks on purpose; empty for one rule."""
    @property
    def suspect(self) -> Optional[int]:
        """The demonstration asked about as a possible slip; `None` for a probe."""
    @property
    def accepted(self) -> Optional[bool]:
        """`None` while the question is open."""
    @property
    def probe_file(self) -> Optional[str]: ...
    @property
    def picture_file(self) -> Optional[str]: ...

@final
class AskResult:
    @property
    def questions(self) -> tuple[Question, ...]: ...
    @property
    def rules(self) -> RuleSet: ...
    @property
    def learned_rcc(self) -> str: ...
    @property
    def demos(self) -> list[Scene]: ...
    @property
    def answers_json(self) -> str: ...
    @property
    def progress(self) -> dict[str, int]: ...
    @property
    def stopped_at_budget(self) -> bool: ...

@final
class AskSession:
    def __new__(
        cls,
        task_dir: _Path,
        max_questions: Optional[int] = None,
        save: bool = True,
        samples: int = 1000,
        cutoff: float = 0.01,
        seed: int = 0,
        time_limit: Optional[float] = 10.0,
        node_limit: int = ...,
        check_nodes: int = ...,
        contact: str = "point",
        templates: str = "third",
        question_nodes: int = ...,
        question_seconds: Optional[float] = 3.0,
        edits: bool = True,
        priors: Optional[_Path] = None,
        slip_rate: float = 0.0,
        groups: bool = True,
    ) -> AskSession: ...
    def next_question(self) -> Optional[Question]: ...
    def answer(self, question: Question, accepted: bool) -> Question: ...
    def undo(self) -> Optional[str]: ...
    @property
    def progress(self) -> dict[str, int]: ...
    @property
    def questions(self) -> tuple[Question, ...]: ...
    @property
    def resumed(self) -> int: ...
    @property
    def stopped_at_budget(self) -> bool: ...
    @property
    def backup_written(self) -> bool: ...
    @property
    def rules(self) -> RuleSet: ...
    @property
    def learned_rcc(self) -> str: ...
    @property
    def demos(self) -> list[Scene]: ...
    @property
    def answers_json(self) -> str: ...
    @property
    def dir(self) -> str: ...
    @property
    def closed(self) -> bool: ...
    def result(self) -> AskResult: ...
    def close(self) -> None: ...
    def __enter__(self) -> AskSession: ...
    def __exit__(self, *_args: object) -> bool: ...

def ask(
    task_dir: _Path,
    oracle: Callable[[Scene], object],
    max_questions: Optional[int] = None,
    save: bool = False,
    samples: int = 1000,
    cutoff: float = 0.01,
    seed: int = 0,
    time_limit: Optional[float] = 10.0,
    node_limit: int = ...,
    check_nodes: int = ...,
    contact: str = "point",
    templates: str = "third",
    question_nodes: int = ...,
    question_seconds: Optional[float] = 3.0,
    edits: bool = True,
    priors: Optional[_Path] = None,
    slip_rate: float = 0.0,
    groups: bool = True,
) -> AskResult: ...

# ---- task folders ------------------------------------------------------------

_Like = Union[Literal["demos"], "Scene", Sequence["Scene"], None]

@final
class RunOutcome:
    @property
    def learned(self) -> Learned: ...
    @property
    def rules(self) -> RuleSet: ...
    @property
    def result(self) -> SynthResult: ...
    @property
    def scene(self) -> Optional[Scene]: ...
    @property
    def missing_classes(self) -> list[str]: ...
    @property
    def summary(self) -> str: ...
    @property
    def message(self) -> Optional[str]: ...
    @property
    def exit_code(self) -> int: ...
    @property
    def files(self) -> list[str]: ...

@final
class Task:
    @staticmethod
    def load(dir: _Path) -> Task: ...
    @property
    def dir(self) -> str: ...
    @property
    def demos(self) -> list[Scene]: ...
    @property
    def problem(self) -> Scene: ...
    @property
    def statements(self) -> Optional[RuleSet]: ...
    def learn(
        self,
        samples: int = 1000,
        cutoff: float = 0.01,
        seed: int = 0,
        templates: str = "third",
        prior: float = 0.5,
        epsilon: Optional[float] = None,
        contact: str = "point",
        time_limit: Optional[float] = None,
        priors: Optional[_Path] = None,
    ) -> Learned: ...
    def place(
        self,
        rules: RuleSet,
        like: _Like = ...,
        time_limit: Optional[float] = None,
        node_limit: Optional[int] = None,
        seed: int = 0,
        contact: str = "point",
    ) -> SynthResult: ...
    def run(
        self,
        out: Optional[_Path] = None,
        samples: int = 1000,
        cutoff: float = 0.01,
        seed: int = 0,
        time_limit: Optional[float] = 60.0,
        contact: str = "point",
        like: _Like = ...,
        templates: str = "third",
        node_limit: Optional[int] = None,
        priors: Optional[_Path] = None,
    ) -> RunOutcome: ...

# ---- sample ------------------------------------------------------------------

@final
class Sampler:
    def __iter__(self) -> Sampler: ...
    def __next__(self) -> Scene: ...
    def close(self) -> None: ...
    @property
    def state(self) -> str: ...
    @property
    def found(self) -> int: ...
    @property
    def skipped(self) -> int: ...
    @property
    def limit_reached(self) -> bool: ...
    @property
    def target_proven(self) -> Optional[bool]: ...

def sample(
    problem: Scene,
    rules: RuleSet,
    n: Optional[int] = None,
    seed: int = 0,
    all_rules: bool = False,
    min_score: Optional[float] = None,
    like: Optional[_Scenes] = None,
    repair: str = "random",
    time_limit: Optional[float] = None,
    layout_node_limit: Optional[int] = None,
    layout_time_limit: Optional[float] = None,
    contact: str = "point",
) -> Sampler: ...
def _null_scene(demos: _Scenes, seed: int, index: int) -> Scene: ...

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
