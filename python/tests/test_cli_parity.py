"""The README's example through Python, compared with the CLI byte for byte:
the same learned `.rcc` and report, the same layout for the same seed and
node limit, the same `score --json`."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

import rccpack


def run(cli: Path, *args: object) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, check=False)


def test_learn_matches_cli(cli: Path, example: Path, tmp_path: Path, learned: rccpack.Learned) -> None:
    out, report = tmp_path / "learned.rcc", tmp_path / "report.json"
    p = run(cli, "learn", example / "demos.json", "-o", out, "--report", report)
    assert p.returncode == 0, p.stderr
    assert learned.to_rcc() == out.read_text()
    assert learned.report_json() == report.read_text()
    assert learned.rules == rccpack.RuleSet.parse(out.read_text())
    assert len(learned) == len(learned.rules) == 57
    assert learned.demonstrations == 8 and learned.candidates == 83
    assert len(learned.statements) == 366
    # The third edition's group statements are learned and read as such.
    assert "B_one_group" in learned.rules
    top = learned.rules[0]
    assert top.posterior is not None and top.posterior < 0.01 and top.reading


@pytest.mark.parametrize("seed", [0, 7])
def test_learn_seed_and_samples_match_cli(cli: Path, example: Path, demos: list[rccpack.Scene], seed: int) -> None:
    p = run(cli, "learn", example / "demos.json", "--seed", seed, "--samples", 300, "--templates", "first")
    assert p.returncode == 0, p.stderr
    assert rccpack.learn(demos, seed=seed, samples=300, templates="first").to_rcc() == p.stdout


@pytest.mark.parametrize(("node_limit", "like"), [(300, True), (100000, True), (200, False)])
def test_synthesize_matches_cli(
    cli: Path,
    example: Path,
    tmp_path: Path,
    demos: list[rccpack.Scene],
    problem: rccpack.Scene,
    learned: rccpack.Learned,
    node_limit: int,
    like: bool,
) -> None:
    rules_path = tmp_path / "learned.rcc"
    rules_path.write_text(learned.to_rcc())
    sol = tmp_path / "solution.json"
    args: list[object] = ["synth", example / "problem.json", "--rules", rules_path, "--seed", 3,
                          "--node-limit", node_limit, "-o", sol, "--quiet"]
    if like:
        args += ["--like", example / "demos.json"]
    p = run(cli, *args)
    assert p.returncode == 0, p.stderr
    r = rccpack.synthesize(problem, learned.rules, like=demos if like else None, node_limit=node_limit, seed=3)
    assert r.status in (rccpack.Status.OPTIMAL, rccpack.Status.FEASIBLE)
    assert r.scene is not None
    assert r.scene.to_json() == sol.read_text()
    # the score is the evaluator's, and score --json agrees byte for byte
    score = run(cli, "score", sol, "--rules", rules_path, "--json")
    assert score.returncode == 0, score.stderr
    ev = rccpack.evaluate(r.scene, learned.rules)
    assert ev.to_json() + "\n" == score.stdout
    assert r.score == ev.score


def test_pipeline_result(demos: list[rccpack.Scene], problem: rccpack.Scene, learned: rccpack.Learned) -> None:
    r = rccpack.synthesize(problem, learned.rules, like=demos)
    assert r.status is rccpack.Status.OPTIMAL
    assert r.score == 1.0 and not r.interrupted
    assert r.resemblance is not None and r.resemblance.cost == 0 and r.resemblance.proven
    assert r.resemblance.bound == r.resemblance.cost
    assert r.conflict is None
    assert r.stats.nodes > 0 and r.stats.time_ms > 0
    assert r.scene is not None and r.scene.complete
    placed = [o for o in r.scene.objects if not o.fixed]
    assert len(placed) == 9
    # same seed, same output
    again = rccpack.synthesize(problem, learned.rules, like=demos)
    assert again.scene == r.scene


def test_render(problem: rccpack.Scene, learned: rccpack.Learned, demos: list[rccpack.Scene]) -> None:
    svg = rccpack.render(problem, learned.rules, like=demos, title="problem")
    assert svg.startswith("<svg") or svg.startswith("<?xml")
    assert "problem" in svg
    png = rccpack.render_png(problem, learned.rules)
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(rccpack.Error, match="scale"):
        rccpack.render(problem, scale=0.0)


@pytest.mark.parametrize("node_limit", [200, 100000])
def test_report_json_matches_synth_report(cli: Path, example: Path, tmp_path: Path, demos: list[rccpack.Scene],
                                          problem: rccpack.Scene, learned: rccpack.Learned, node_limit: int) -> None:
    import json

    rules_path = tmp_path / "learned.rcc"
    rules_path.write_text(learned.to_rcc())
    report = tmp_path / "report.json"
    p = run(cli, "synth", example / "problem.json", "--rules", rules_path, "--like", example / "demos.json",
            "--node-limit", node_limit, "--seed", 1, "-o", tmp_path / "sol.json", "--report", report, "--quiet")
    assert p.returncode == 0, p.stderr
    r = rccpack.synthesize(problem, learned.rules, like=demos, node_limit=node_limit, seed=1)
    timed = ("time_ms", "time_to_first_ms", "time_to_best_ms")

    def untimed(text: str) -> str:
        d = json.loads(text)
        for k in timed:
            if d.get(k) is not None:
                d[k] = 0
        return json.dumps(d, indent=2)

    mine, theirs = r.report_json(), report.read_text()
    # the same fields in the same order, the same values but the clock's
    assert [line.split(":")[0] for line in mine.splitlines()] == [line.split(":")[0] for line in theirs.splitlines()]
    assert untimed(mine) == untimed(theirs)
    assert mine.endswith("}\n")
