"""`AskSession`: one question at a time, saved after every answer and
resumed from `answers.json` — the same questions, files and bytes as
`rccpack ask`, interrupted or not."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from conftest import Oracle, tree

import rccpack


def answer_all(session: rccpack.AskSession, oracle: Oracle, k: int | None = None) -> int:
    n = 0
    while k is None or n < k:
        q = session.next_question()
        if q is None:
            break
        assert q.accepted is None and q.probe_file is not None and Path(q.probe_file).exists()
        a = session.answer(q, oracle(q.probe))
        assert a.accepted is not None and a.number == q.number
        n += 1
    return n


@pytest.mark.parametrize("k", [3, 7])
def test_interrupted_and_resumed_is_the_uninterrupted_session(
    example: Path, tmp_path: Path, pilot_oracle: Oracle, cli_session: tuple[dict[str, bytes], str], k: int
) -> None:
    d = tmp_path / "task"
    shutil.copytree(example, d)
    with rccpack.AskSession(d, question_seconds=600) as s:
        assert s.resumed == 0 and not s.backup_written
        assert answer_all(s, pilot_oracle, k) == k
        assert s.progress["asked"] == k
    # a fresh session (a new process would do the same) resumes
    s2 = rccpack.AskSession(d, question_seconds=600)
    assert s2.resumed == k
    rest = answer_all(s2, pilot_oracle)
    assert s2.next_question() is None and not s2.stopped_at_budget
    assert s2.progress["asked"] == k + rest == len(s2.questions) + k
    s2.close()
    assert s2.closed
    assert tree(d) == cli_session[0]


def test_cli_interrupted_python_resumes(cli: Path, example: Path, tmp_path: Path, pilot_oracle: Oracle,
                                        cli_session: tuple[dict[str, bytes], str]) -> None:
    d = tmp_path / "task"
    shutil.copytree(example, d)
    p = subprocess.run(
        [str(cli), "ask", str(d), "--max-questions", "4", "--question-seconds", "600",
         "--oracle", f"{cli} score --rules {example / 'pilot.rcc'} --require"],
        capture_output=True, text=True, check=False,
    )
    assert p.returncode == 0, p.stderr
    r = rccpack.ask(d, pilot_oracle, save=True, question_seconds=600)
    assert r.progress["asked"] == len(r.questions) + 4
    assert tree(d) == cli_session[0]


def test_ask_saves_like_the_cli(example: Path, tmp_path: Path, pilot_oracle: Oracle,
                                cli_session: tuple[dict[str, bytes], str]) -> None:
    d = tmp_path / "task"
    shutil.copytree(example, d)
    r = rccpack.ask(d, pilot_oracle, save=True, question_seconds=600)
    assert tree(d) == cli_session[0]
    assert r.answers_json.encode() == cli_session[0]["answers.json"]


def test_budget_lock_stale_answers_and_undo(example: Path, tmp_path: Path) -> None:
    d = tmp_path / "task"
    shutil.copytree(example, d)
    s = rccpack.AskSession(d, max_questions=2)
    with pytest.raises(rccpack.AskError, match="another `rccpack ask`"):
        rccpack.AskSession(d, question_seconds=600)
    q1 = s.next_question()
    assert q1 is not None and q1.number == 1
    again = s.next_question()
    assert again is not None and again.rule == q1.rule and again.number == 1
    s.answer(again, False)
    with pytest.raises(rccpack.AskError, match="not the open question"):
        s.answer(q1, False)
    q2 = s.next_question()
    assert q2 is not None and q2.number == 2
    s.answer(q2, True)
    assert s.next_question() is None and s.stopped_at_budget
    assert not (d / "probes" / "probe-3.json").exists()
    assert len(s.demos) == 9  # the accepted probe joined the demonstrations
    # undo the accepted answer: the probe leaves demos.json again
    assert s.undo() == q2.rule
    original = rccpack.scenes_to_json(rccpack.load_scenes(example / "demos.json"))
    assert len(s.demos) == 8 and (d / "demos.json").read_text() == original
    assert [q.rule for q in s.questions] == [q1.rule]
    q2b = s.next_question()
    assert q2b is not None and q2b.rule == q2.rule and q2b.probe == q2.probe
    assert s.undo() == q1.rule and s.undo() is None
    assert s.answers_json == '{\n  "answers": []\n}\n'
    s.close()
    with pytest.raises(rccpack.AskError, match="closed"):
        s.next_question()
    # the lock is free again
    with rccpack.AskSession(d, save=False) as mem:
        assert mem.resumed == 0


def test_memory_session_writes_nothing(example: Path, tmp_path: Path) -> None:
    d = tmp_path / "task"
    shutil.copytree(example, d)
    with rccpack.AskSession(d, save=False, max_questions=1) as s:
        q = s.next_question()
        assert q is not None and q.probe_file is None and q.picture_file is None
        s.answer(q, False)
        assert s.next_question() is None
        res = s.result()
        assert res.stopped_at_budget and len(res.questions) == 1
    assert tree(d) == tree(example)


def slipped_example(example: Path, d: Path) -> None:
    """The bundled example with block r4 of demonstration 5 put in a wrong
    free place (a slip)."""
    import json

    shutil.copytree(example, d)
    demos = json.loads((d / "demos.json").read_text())
    for o in demos[5]["objects"]:
        if o["id"] == "r4":
            o["x"], o["y"] = 300, 300
    (d / "demos.json").write_text(json.dumps(demos, indent=1))


def test_a_suspect_is_asked_about_first_both_ways(example: Path, tmp_path: Path) -> None:
    import json

    d = tmp_path / "task"
    slipped_example(example, d)
    demos_before = (d / "demos.json").read_text()
    # Without a slip rate: no question about a demonstration.
    with rccpack.AskSession(d, save=False) as s:
        q = s.next_question()
        assert q is not None and q.suspect is None
    # "No": a slip, no longer counted against the rules it breaks; journaled,
    # not asked again after a resume.
    with rccpack.AskSession(d, slip_rate=0.01) as s:
        q = s.next_question()
        assert q is not None and q.suspect == 5 and q.broken[0] == "r4", q
        a = s.answer(q, False)
        assert a.suspect == 5 and a.accepted is False
    answers = json.loads((d / "answers.json").read_text())["answers"]
    assert answers[0]["suspect"]["demonstration"] == 5
    assert "demonstration 5: `r4` answered as a slip" in (d / "learned.rcc").read_text()
    assert (d / "demos.json").read_text() == demos_before
    with rccpack.AskSession(d, slip_rate=0.01) as s:
        assert s.resumed == 1
        q = s.next_question()
        assert q is None or q.suspect != 5
    # "Yes": meant; the rules it breaks are dropped.
    d2 = tmp_path / "task2"
    slipped_example(example, d2)
    r = rccpack.ask(d2, lambda probe: True, max_questions=1, slip_rate=0.01)
    (q,) = r.questions
    assert q.suspect == 5 and q.accepted is True
    held = {rule.name for rule in r.rules}
    assert q.rule not in held and not (set(q.also_broken) & held)


def test_group_questions_and_one_rule_per_question(example: Path, tmp_path: Path) -> None:
    d = tmp_path / "task"
    shutil.copytree(example, d)
    with rccpack.AskSession(d, max_questions=2, question_seconds=600) as s:
        q = s.next_question()
        assert q is not None and len(q.group) >= 2 and q.group[0] == q.rule
        s.answer(q, False)
        # "not acceptable" about a group confirms none of its rules yet
        assert s.progress["grouped"] == 1 and s.progress["confirmed"] == 0
        q2 = s.next_question()
        assert q2 is not None and set(q2.group or [q2.rule]) < set(q.group)
    d2 = tmp_path / "task2"
    shutil.copytree(example, d2)
    with rccpack.AskSession(d2, max_questions=1, groups=False) as s:
        q = s.next_question()
        assert q is not None and q.group == []
