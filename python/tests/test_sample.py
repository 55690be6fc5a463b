"""`sample`: the same layouts as `rccpack sample` for the same seed; an
iterator that releases the GIL and stops."""

from __future__ import annotations

import threading
from pathlib import Path
import subprocess

import pytest

import rccpack


def cli_sample(cli: Path, problem: Path, rules: Path, *args: object) -> str:
    p = subprocess.run([str(cli), "sample", str(problem), "--rules", str(rules), *map(str, args), "--quiet"],
                       capture_output=True, text=True, check=False)
    assert p.returncode == 0, p.stderr
    return p.stdout


@pytest.mark.parametrize(("n", "seed", "extra"), [(6, 3, ["--all-rules"]), (4, 0, []),
                                                  (5, 11, ["--min-score", "0.99", "--repair", "activity"])])
def test_sample_matches_cli(cli: Path, example: Path, tmp_path: Path, problem: rccpack.Scene,
                            learned: rccpack.Learned, n: int, seed: int, extra: list[str]) -> None:
    rules_path = tmp_path / "learned.rcc"
    rules_path.write_text(learned.to_rcc())
    want = cli_sample(cli, example / "problem.json", rules_path, "-n", n, "--seed", seed, *extra)
    kw: dict[str, object] = {}
    if "--all-rules" in extra:
        kw["all_rules"] = True
    if "--min-score" in extra:
        kw["min_score"] = 0.99
    if "--repair" in extra:
        kw["repair"] = "activity"
    got = list(rccpack.sample(problem, learned.rules, n=n, seed=seed, **kw))  # type: ignore[arg-type]
    assert rccpack.scenes_to_json(got) == want
    assert len(got) == n and len({s.to_json() for s in got}) == n
    for s in got:
        assert s.complete
        if "--all-rules" in extra:
            assert rccpack.evaluate(s, learned.rules).score == 1.0


def test_like_matches_cli(cli: Path, example: Path, tmp_path: Path, problem: rccpack.Scene,
                          learned: rccpack.Learned, demos: list[rccpack.Scene]) -> None:
    rules_path = tmp_path / "learned.rcc"
    rules_path.write_text(learned.to_rcc())
    want = cli_sample(cli, example / "problem.json", rules_path, "-n", 3, "--seed", 5, "--all-rules",
                      "--like", example / "demos.json")
    got = rccpack.sample(problem, learned.rules, n=3, seed=5, all_rules=True, like=demos)
    assert rccpack.scenes_to_json(list(got)) == want


TINY = rccpack.Scene(rccpack.Space(30, 10), [rccpack.Object(f"a{i}", "R", 10, 10) for i in range(2)])


def test_iterator_ends_exhausted_and_is_fused() -> None:
    rules = rccpack.RuleSet.parse("rule touch: EC_E(R, R) | EC_W(R, R)\n")
    s = rccpack.sample(TINY, rules, all_rules=True)
    assert s.state == "running"
    got = list(s)
    # two interchangeable blocks side by side in a 3x1 strip: 2 layouts
    assert len(got) == 2 and s.state == "exhausted" and not s.limit_reached
    assert list(s) == [] and s.found == 2
    with pytest.raises(StopIteration):
        next(s)
    assert "Sampler" in repr(s)


def test_errors() -> None:
    rules = rccpack.RuleSet.parse("rule a hard: DR_N(R, R)\nrule b hard: DR_S(R, R)\n")
    s = rccpack.sample(TINY, rules)
    with pytest.raises(rccpack.SampleError, match="infeasible") as e:
        next(s)
    assert e.value.kind == "infeasible" and isinstance(e.value, rccpack.Error)
    never = rccpack.RuleSet.parse("rule n: DR_N(R, R)\n")
    with pytest.raises(rccpack.SampleError) as e2:
        next(rccpack.sample(TINY, never, all_rules=True))
    assert e2.value.kind == "no_layout"
    with pytest.raises(rccpack.Error, match="min_score"):
        rccpack.sample(TINY, never, min_score=2.0)
    with pytest.raises(rccpack.Error, match="together"):
        rccpack.sample(TINY, never, all_rules=True, min_score=0.5)
    with pytest.raises(rccpack.Error, match="repair"):
        rccpack.sample(TINY, never, repair="greedy")
    with pytest.raises(rccpack.RulesError, match="nowhere"):
        rccpack.sample(TINY, rccpack.RuleSet.parse("rule a: EC_E(R, @nowhere)\n"))


def test_limit_and_close(problem: rccpack.Scene, learned: rccpack.Learned) -> None:
    s = rccpack.sample(problem, learned.rules, all_rules=True, layout_node_limit=1, seed=1)
    got = list(s)
    assert s.limit_reached and s.state == "stopped"
    assert len(got) < 50
    s2 = rccpack.sample(problem, learned.rules, all_rules=True, seed=1)
    first = next(s2)
    s2.close()
    assert list(s2) == [] and first.complete


def test_gil_released_while_drawing(problem: rccpack.Scene, learned: rccpack.Learned) -> None:
    counter = [0]
    stop = threading.Event()

    def work() -> None:
        while not stop.is_set():
            counter[0] += 1

    t = threading.Thread(target=work)
    t.start()
    try:
        start = counter[0]
        got = list(rccpack.sample(problem, learned.rules, n=30, all_rules=True, seed=2))
        during = counter[0] - start
    finally:
        stop.set()
        t.join()
    assert len(got) == 30
    assert during > 10_000, during
