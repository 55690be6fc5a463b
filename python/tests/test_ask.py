"""`ask` with a Python oracle asks the same questions as
`rccpack ask --oracle` and leaves the same rules."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
from conftest import Oracle

import rccpack


def test_ask_matches_cli_oracle(example: Path, tmp_path: Path, pilot_oracle: Oracle,
                                cli_session: tuple[dict[str, bytes], str]) -> None:
    task = tmp_path / "task"
    shutil.copytree(example, task)
    result = rccpack.ask(task, pilot_oracle, question_seconds=600)
    # nothing written to the folder
    assert sorted(p.name for p in task.iterdir()) == sorted(p.name for p in example.iterdir())
    files, stdout = cli_session
    # "question 3: `RULE` (reading) -> …" or, for a group, "question 1: 2
    # rules (RULE, OTHER) -> …": the first rule is the question's
    asked = [
        (single or first, verdict)
        for single, first, verdict in re.findall(
            r"^question \d+: (?:`([^`]+)` .*|\d+ rules \(([^,)]+)[^)]*\)) -> (acceptable|not acceptable)", stdout, re.M
        )
    ]
    assert [(q.rule, q.accepted) for q in result.questions] == [(r, a == "acceptable") for r, a in asked]
    assert result.learned_rcc.encode() == files["learned.rcc"]
    assert result.answers_json.encode() == files["answers.json"]
    assert rccpack.scenes_to_json(result.demos).encode() == files["demos.json"]
    progress = result.progress
    assert progress["asked"] == len(result.questions) == len(asked) > 0
    # an accepted probe drops every rule it asked about (a group: all of
    # them); a rejected single rule is confirmed, a rejected group is not,
    # and the one left of a rejected group is confirmed without a question
    assert progress["dropped"] == sum(len(q.group) or 1 for q in result.questions if q.accepted)
    assert progress["dropped_in_groups"] == sum(len(q.group) for q in result.questions if q.accepted)
    assert progress["confirmed"] == progress["deduced"] + sum(
        1 for q in result.questions if q.accepted is False and not q.group
    )
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
