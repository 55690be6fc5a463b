"""Behaviour in a host program: the GIL is released while learning and
solving, Ctrl-C and the progress callback stop a solve, errors are typed."""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import rccpack

# A problem whose optimum takes the engine long to prove: 24 blocks in an
# open 300x300 table with rules that pull against each other.
HARD_RULES = rccpack.RuleSet.parse(
    """\
rule r_touch: FL_E(R, R) | FL_W(R, R)
rule r_north weight 2: DR_N(R, G)
rule g_row: AL_S(G, every G) & (FL_E(G, G) | FL_W(G, G))
rule g_east weight 3: DR_E(G, R)
rule r_col: AL_W(R, every R)
"""
)


def hard_problem() -> rccpack.Scene:
    objects = [rccpack.Object(f"r{i}", "R", 30, 20) for i in range(14)]
    objects += [rccpack.Object(f"g{i}", "G", 20, 30) for i in range(10)]
    return rccpack.Scene(rccpack.Space(300, 300), objects, grid=10)


def counting_thread(stop: threading.Event, counter: list[int]) -> threading.Thread:
    def work() -> None:
        while not stop.is_set():
            counter[0] += 1

    return threading.Thread(target=work)


def test_gil_released_while_solving() -> None:
    """A second Python thread runs while `synthesize` works."""
    problem = hard_problem()
    counter = [0]
    stop = threading.Event()
    t = counting_thread(stop, counter)
    t.start()
    try:
        start = counter[0]
        r = rccpack.synthesize(problem, HARD_RULES, time_limit=1.0, seed=1)
        during = counter[0] - start
    finally:
        stop.set()
        t.join()
    assert r.status in (rccpack.Status.FEASIBLE, rccpack.Status.OPTIMAL)
    # a thread that held the GIL for the whole second would leave ~0 here;
    # a free interpreter counts millions of loop iterations per second
    assert during > 100_000, during


def test_gil_released_while_learning(demos: list[rccpack.Scene]) -> None:
    counter = [0]
    stop = threading.Event()
    t = counting_thread(stop, counter)
    t.start()
    try:
        t0 = time.perf_counter()
        start = counter[0]
        rccpack.learn(demos, samples=20000)
        during, secs = counter[0] - start, time.perf_counter() - t0
    finally:
        stop.set()
        t.join()
    assert during > 50_000 * secs, (during, secs)


def test_two_solves_in_two_threads(demos: list[rccpack.Scene], problem: rccpack.Scene, learned: rccpack.Learned) -> None:
    results: list[Any] = [None, None]

    def solve(i: int) -> None:
        results[i] = rccpack.synthesize(problem, learned.rules, like=demos, node_limit=2000)

    threads = [threading.Thread(target=solve, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results[0].scene == results[1].scene


@pytest.fixture
def sigint_raises() -> Iterator[None]:
    """SIGINT raises KeyboardInterrupt during the test, as in an interactive
    Python: a shell without job control starts background jobs with SIGINT
    ignored, and Python then installs no handler of its own."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)


@pytest.mark.skipif(not hasattr(signal, "SIGINT"), reason="needs SIGINT")
def test_ctrl_c_returns_the_best_layout(sigint_raises: None) -> None:
    """Ctrl-C (SIGINT → KeyboardInterrupt in the main thread) stops the
    search: the best layout found is returned with status FEASIBLE and
    `interrupted` set; no KeyboardInterrupt escapes."""
    problem = hard_problem()
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.perf_counter()
    timer.start()
    try:
        r = rccpack.synthesize(problem, HARD_RULES, time_limit=60.0, seed=1)
    finally:
        timer.cancel()
    secs = time.perf_counter() - t0
    assert secs < 10, secs
    assert r.interrupted
    assert r.status is rccpack.Status.FEASIBLE
    assert r.scene is not None and r.scene.complete


def test_progress_callback_sees_improvements_and_can_stop() -> None:
    seen: list[tuple[float, float]] = []

    def progress(score: float, elapsed: float) -> bool:
        seen.append((score, elapsed))
        return len(seen) < 2  # False: stop after the second improvement

    r = rccpack.synthesize(hard_problem(), HARD_RULES, time_limit=5.0, seed=1, progress=progress)
    assert 1 <= len(seen) <= 2
    assert all(0.0 <= s <= 1.0 and e >= 0.0 for s, e in seen)
    assert [s for s, _ in seen] == sorted(s for s, _ in seen)
    if len(seen) == 2:
        assert r.interrupted and r.status is rccpack.Status.FEASIBLE


def test_progress_callback_exception_propagates() -> None:
    class Stop(Exception):
        pass

    def progress(score: float, elapsed: float) -> None:
        raise Stop("from the callback")

    with pytest.raises(Stop):
        rccpack.synthesize(hard_problem(), HARD_RULES, time_limit=10.0, progress=progress)


def test_synth_errors_and_statuses(problem: rccpack.Scene) -> None:
    big = rccpack.Scene(rccpack.Space(2**29, 10), [rccpack.Object("a", "R", 10, 10)], grid=10)
    with pytest.raises(rccpack.SynthError, match="too large") as e:
        rccpack.synthesize(big, rccpack.RuleSet.parse("rule a: DR_N(R, R)\n"))
    assert isinstance(e.value, rccpack.Error)
    crowded = rccpack.Scene(rccpack.Space(20, 20), [rccpack.Object(f"a{i}", "R", 20, 20) for i in range(2)])
    r = rccpack.synthesize(crowded, rccpack.RuleSet.parse("rule a: DR_N(R, R)\n"))
    assert r.status is rccpack.Status.INFEASIBLE and r.scene is None and r.score is None
    assert r.conflict is not None and r.conflict.objects_cannot_fit
    hard = rccpack.RuleSet.parse("rule a hard: DR_N(R, R)\nrule b hard: DR_S(R, R)\n")
    two = rccpack.Scene(rccpack.Space(100, 100), [rccpack.Object(f"a{i}", "R", 10, 10) for i in range(2)])
    r = rccpack.synthesize(two, hard)
    assert r.status is rccpack.Status.INFEASIBLE
    assert r.conflict is not None and r.conflict.hard_rules and set(r.conflict.hard_rules) <= {"a", "b"}
    with pytest.raises(rccpack.Error, match="time_limit"):
        rccpack.synthesize(problem, hard, time_limit=-1.0)
    with pytest.raises(TypeError):
        rccpack.synthesize(problem, hard, like="demos.json")  # type: ignore[arg-type]
    with pytest.raises(rccpack.RulesError, match="nowhere"):
        rccpack.synthesize(problem, rccpack.RuleSet.parse("rule a: EC_E(R, @nowhere)\n"))


def test_learn_errors(demos: list[rccpack.Scene], problem: rccpack.Scene) -> None:
    with pytest.raises(rccpack.LearnError, match="cutoff") as e:
        rccpack.learn(demos, cutoff=2.0)
    assert isinstance(e.value, rccpack.Error)
    with pytest.raises(rccpack.LearnError, match="no demonstrations"):
        rccpack.learn([])
    with pytest.raises(rccpack.LearnError, match="incomplete"):
        rccpack.learn([problem])
    with pytest.raises(rccpack.Error, match="fourth"):
        rccpack.learn(demos, templates="fourth")
    with pytest.raises(OverflowError):
        rccpack.learn(demos, samples=-1)


@pytest.mark.skipif(not hasattr(signal, "SIGINT"), reason="needs SIGINT")
def test_ctrl_c_stops_learning(demos: list[rccpack.Scene], sigint_raises: None) -> None:
    """Ctrl-C during `learn` stops the null model's draws (the core's
    cancel flag) and raises KeyboardInterrupt at once, not when the
    learning would have ended (1 000 000 samples: about 20 s)."""
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            rccpack.learn(demos, samples=1_000_000)
    finally:
        timer.cancel()
    secs = time.perf_counter() - t0
    assert secs < 5, secs
    # the same through a task folder
    task = rccpack.Task.load(Path(__file__).resolve().parents[2] / "examples" / "box-packing")
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            task.learn(samples=1_000_000)
    finally:
        timer.cancel()
    assert time.perf_counter() - t0 < 5
