"""`Task`: the task folder and `rccpack run`, byte for byte against the CLI."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

import rccpack


def files_of(d: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(d.iterdir()) if p.is_file()}


def masked(summary: str, out: Path) -> str:
    return re.sub(r"in [0-9.]+ ms", "in T ms", summary.replace(str(out), "OUT"))


def test_run_matches_cli(cli: Path, example: Path, tmp_path: Path) -> None:
    task = tmp_path / "task"
    shutil.copytree(example, task)
    cli_out, py_out = tmp_path / "cli", tmp_path / "py"
    p = subprocess.run(
        [str(cli), "run", str(task), "--out", str(cli_out), "--seed", "2"],
        capture_output=True, text=True, check=False,
    )
    assert p.returncode == 0, p.stderr
    t = rccpack.Task.load(task)
    outcome = t.run(out=py_out, seed=2)
    assert outcome.exit_code == 0 and outcome.message is None
    cli_files, py_files = files_of(cli_out), files_of(py_out)
    assert sorted(py_files) == sorted(cli_files) == sorted(
        [".rccpack.lock", "learn-report.json", "learned.rcc", "solution.json", "solution.png"]
    )
    for name in cli_files:
        assert py_files[name] == cli_files[name], name
    assert masked(outcome.summary, py_out) == masked(p.stdout, cli_out)
    assert outcome.files == [str(py_out / f) for f in ("learned.rcc", "learn-report.json", "solution.json", "solution.png")]
    # what it returns is what it wrote
    assert outcome.learned.to_rcc() == (py_out / "learned.rcc").read_text()
    assert outcome.scene is not None
    assert outcome.scene.to_json() == (py_out / "solution.json").read_text()
    assert outcome.result.status is rccpack.Status.OPTIMAL and outcome.missing_classes == []
    assert len(outcome.rules) == len(outcome.learned) > 0
    # the task folder itself is untouched when OUT is elsewhere
    assert sorted(p.name for p in task.iterdir()) == sorted(p.name for p in example.iterdir())


def test_run_into_the_task_folder(example: Path, tmp_path: Path) -> None:
    task = tmp_path / "task"
    shutil.copytree(example, task)
    outcome = rccpack.Task.load(task).run()
    assert outcome.exit_code == 0
    for f in ("learned.rcc", "learn-report.json", "solution.json", "solution.png"):
        assert (task / f).exists(), f
    assert not [p for p in task.iterdir() if ".tmp-" in p.name]


def test_learn_and_place_are_the_pipeline_steps(example: Path, demos: list[rccpack.Scene],
                                               problem: rccpack.Scene, learned: rccpack.Learned) -> None:
    t = rccpack.Task.load(example)
    assert t.dir == str(example) and t.statements is None
    assert t.demos == demos and t.problem == problem
    got = t.learn()
    assert got.to_rcc() == learned.to_rcc() and got.report_json() == learned.report_json()
    placed = t.place(got.rules, node_limit=3000, seed=1)
    direct = rccpack.synthesize(problem, got.rules, like=demos, node_limit=3000, seed=1)
    assert placed.scene == direct.scene and placed.status == direct.status
    off = t.place(got.rules, like=None, node_limit=3000)
    assert off.resemblance is None
    assert repr(t).startswith("<Task ")


def test_task_errors_and_lock(example: Path, tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        rccpack.Task.load(tmp_path / "nowhere")
    bad = tmp_path / "bad"
    shutil.copytree(example, bad)
    (bad / "problem.json").write_text('{"space": {"width": 10, "height": 10}, "objects": [{"id": 1}]}')
    with pytest.raises(rccpack.SceneError) as e:
        rccpack.Task.load(bad)
    assert e.value.file is not None and e.value.file.endswith("problem.json")
    (bad / "problem.json").write_text((example / "problem.json").read_text())
    (bad / "statements.rcc").write_text("rule a: DR_N(B, \n")
    with pytest.raises(rccpack.RulesError) as r:
        rccpack.Task.load(bad)
    assert r.value.line == 1 and "statements.rcc" in r.value.file
    (bad / "statements.rcc").unlink()
    t = rccpack.Task.load(bad)
    with pytest.raises(rccpack.Error, match="like"):
        t.run(like="demonstrations")  # type: ignore[arg-type]
    with rccpack.AskSession(bad, samples=200):
        with pytest.raises(rccpack.Error, match="another `rccpack ask`"):
            t.run(samples=200)
    assert t.run(samples=200, node_limit=500).exit_code == 0


def test_infeasible_run_is_an_outcome(tmp_path: Path, demos: list[rccpack.Scene]) -> None:
    task = tmp_path / "t"
    task.mkdir()
    (task / "demos.json").write_text(rccpack.scenes_to_json(demos))
    crowded = rccpack.Scene(rccpack.Space(20, 20), [rccpack.Object(f"a{i}", "B", 20, 20) for i in range(2)])
    (task / "problem.json").write_text(crowded.to_json())
    (task / "statements.rcc").write_text("rule b: DR_N(B, R) | !DR_N(B, R)\n")
    out = rccpack.Task.load(task).run(samples=100)
    assert out.exit_code == 2 and out.scene is None
    assert out.message is not None and out.message.startswith("infeasible: ")
    assert not (task / "solution.json").exists()
