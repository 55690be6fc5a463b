"""`ask` with a Python oracle asks the same questions as
`rccpack ask --oracle` and leaves the same rules."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

import rccpack


def test_ask_matches_cli_oracle(cli: Path, example: Path, tmp_path: Path) -> None:
    pilot = rccpack.load_rules(example / "pilot.rcc")

    def oracle(probe: rccpack.Scene) -> bool:
        # what `rccpack score --rules pilot.rcc --require` answers
        return all(r.satisfied >= r.subjects for r in rccpack.evaluate(probe, pilot).rules)

    task = tmp_path / "task"
    shutil.copytree(example, task)
    result = rccpack.ask(task, oracle)
    # nothing written to the folder
    assert sorted(p.name for p in task.iterdir()) == sorted(p.name for p in example.iterdir())

    cli_task = tmp_path / "cli"
    shutil.copytree(example, cli_task)
    p = subprocess.run(
        [str(cli), "ask", str(cli_task), "--oracle", f"{cli} score --rules {example / 'pilot.rcc'} --require"],
        capture_output=True, text=True, check=False,
    )
    assert p.returncode == 0, p.stderr
    asked = re.findall(r"^question \d+: `([^`]+)` .* -> (acceptable|not acceptable)", p.stdout, re.M)
    assert [(q.rule, q.accepted) for q in result.questions] == [(r, a == "acceptable") for r, a in asked]
    assert result.learned_rcc == (cli_task / "learned.rcc").read_text()
    assert result.answers_json == (cli_task / "answers.json").read_text()
    assert rccpack.scenes_to_json(result.demos) == (cli_task / "demos.json").read_text()
    progress = result.progress
    assert progress["asked"] == len(result.questions) == len(asked) > 0
    assert progress["dropped"] + progress["confirmed"] == progress["asked"]
    q = result.questions[0]
    assert q.probe.complete and q.english and q.statement


def test_ask_budget_and_oracle_errors(example: Path) -> None:
    r = rccpack.ask(example, lambda probe: False, max_questions=2)
    assert len(r.questions) == 2 and r.stopped_at_budget
    assert all(not q.accepted for q in r.questions)

    def broken(probe: rccpack.Scene) -> bool:
        raise RuntimeError("the person left")

    with pytest.raises(RuntimeError, match="the person left"):
        rccpack.ask(example, broken)
    with pytest.raises(FileNotFoundError):
        rccpack.ask(example / "nowhere", lambda probe: True)
