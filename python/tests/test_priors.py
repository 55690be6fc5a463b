"""Priors learned across tasks: `priors=` of the learning calls against the
CLI's `--priors`, the plain-data steps `task_counts` / `combine_priors`,
and the Dask recipe (`examples/dask_priors.py`) against `rccpack priors`,
byte for byte."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

import rccpack

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import dask_priors  # noqa: E402

BOX = ROOT / "examples" / "box-packing"
SHELF = ROOT / "examples" / "shelf"


def make_task(dst: Path, src: Path, learned: str, keep: int | None = None,
              drop_rule: str | None = None, confirm: str | None = None) -> Path:
    """A finished task folder: `src`'s demonstrations (the first `keep`),
    and `learned` as learned.rcc (`drop_rule` left out, `confirm` marked
    `# confirmed`)."""
    dst.mkdir(parents=True)
    demos = json.loads((src / "demos.json").read_text())
    if keep is not None:
        demos = demos[:keep]
    (dst / "demos.json").write_text(json.dumps(demos, indent=2) + "\n")
    text = (src / learned).read_text()
    if drop_rule is not None:
        lines = text.splitlines(keepends=True)
        start = next(i for i, l in enumerate(lines) if l.startswith(f"rule {drop_rule}:"))
        end = start + 1
        while end < len(lines) and lines[end].startswith(" "):
            end += 1
        assert end > start
        text = "".join(lines[:start] + lines[end:])
    if confirm is not None:
        assert f"rule {confirm}:" in text
        text = text.replace(f"rule {confirm}:", f"# confirmed\nrule {confirm}:")
    (dst / "learned.rcc").write_text(text)
    return dst


@pytest.fixture(scope="module")
def library(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    """Six task folders: the two bundled examples with their intended rules
    as learned.rcc, varied (fewer demonstrations, a rule dropped, a rule
    confirmed)."""
    d = tmp_path_factory.mktemp("library")
    return [
        make_task(d / "box0", BOX, "pilot.rcc"),
        make_task(d / "box1", BOX, "pilot.rcc", keep=5, drop_rule="green_east_of_blue"),
        make_task(d / "box2", BOX, "pilot.rcc", keep=6, confirm="blue_north_of_red"),
        make_task(d / "shelf0", SHELF, "intended.rcc"),
        make_task(d / "shelf1", SHELF, "intended.rcc", keep=4),
        make_task(d / "shelf2", SHELF, "intended.rcc", keep=6, confirm="red_on_floor"),
    ]


def cli_priors(cli: Path, folders: list[Path], out: Path, *flags: str) -> str:
    p = subprocess.run([str(cli), "priors", *map(str, folders), "-o", str(out), *flags],
                       capture_output=True, text=True, check=False)
    assert p.returncode == 0, p.stderr
    return out.read_text()


@pytest.fixture(scope="module")
def priors_file(cli: Path, library: list[Path], tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("priors") / "priors.json"
    cli_priors(cli, library, out)
    return out


def test_dask_recipe_is_the_cli_byte_for_byte(cli: Path, library: list[Path], tmp_path: Path) -> None:
    from dask.distributed import Client, LocalCluster

    expected = cli_priors(cli, library, tmp_path / "cli.json")
    low = cli_priors(cli, library, tmp_path / "cli-low.json", "--rule-out-after", "2", "--strength", "1")
    assert expected != low
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        assert dask_priors.priors_on_cluster(library, client) == expected
        counts = dask_priors.gather_counts(list(reversed(library)), client)
        # Both workers took part.
        who = client.run(lambda: True)
        assert len(who) == 2
        # A folder that cannot be read: the worker's exception, on the client.
        with pytest.raises(FileNotFoundError):
            dask_priors.gather_counts([library[0], tmp_path / "nowhere"], client)
    assert rccpack.combine_priors(counts) == expected
    assert rccpack.combine_priors(counts, strength=1, rule_out_after=2) == low
    assert '"ruled_out": true' in low


def test_plain_counts_combine_in_any_order(cli: Path, library: list[Path], tmp_path: Path) -> None:
    expected = cli_priors(cli, library, tmp_path / "cli.json")
    counts = [rccpack.task_counts(f) for f in library]
    c0 = counts[0]
    assert c0["version"] == "rccpack-task-counts/1"
    assert (c0["templates"], c0["contact"]) == ("third", "point")
    assert c0["hash"].startswith("fnv1a64:")
    assert all(set(v) == {"candidates", "kept", "confirmed"} for v in c0["kinds"].values())
    # plain data: through JSON and back
    again = json.loads(json.dumps(counts))
    assert rccpack.combine_priors(again) == expected
    assert rccpack.combine_priors(counts[::-1]) == expected
    assert rccpack.combine_priors(tuple(counts[2:] + counts[:2])) == expected
    assert rccpack.combine_priors(counts[1:]) != expected
    # a confirmed rule is counted
    assert sum(v["confirmed"] for v in counts[2]["kinds"].values()) == 1
    # no tasks: the uniform priors file (every kind 1/2)
    empty = json.loads(rccpack.combine_priors([]))
    assert empty["library"]["tasks"] == 0 and [k["prior"] for k in empty["kinds"]] == [0.5]


def test_counts_errors_name_the_field(library: list[Path]) -> None:
    good = rccpack.task_counts(library[0])

    def err(counts: list[dict[str, Any]], **kw: Any) -> rccpack.PriorsError:
        with pytest.raises(rccpack.PriorsError) as e:
            rccpack.combine_priors(counts, **kw)
        return e.value

    e = err([good, rccpack.task_counts(library[3], templates="second")])
    assert e.field == "counts[1].templates" and "second" in str(e)
    assert err([good], contact="edge").field == "counts[0].contact"
    key = next(iter(good["kinds"]))
    bad = json.loads(json.dumps(good))
    bad["kinds"][key]["kept"] = bad["kinds"][key]["candidates"] + 1
    assert err([good, bad]).field == f"counts[1].kinds.{key}.kept"
    bad = json.loads(json.dumps(good))
    bad["kinds"]["{A}_nope/any"] = {"candidates": 1, "kept": 0, "confirmed": 0}
    assert err([bad]).field == "counts[0].kinds.{A}_nope/any"
    bad = json.loads(json.dumps(good))
    bad["kinds"][key]["extra"] = 1
    e = err([bad])
    assert e.field.startswith(f"counts[0].kinds.{key}") and "extra" in str(e)
    bad = dict(good, version="rccpack-task-counts/9")
    assert err([bad]).field == "counts[0].version"
    bad = dict(good, hash="12")
    assert err([bad]).field == "counts[0].hash"
    with pytest.raises(TypeError):
        rccpack.combine_priors(good)  # type: ignore[arg-type]
    with pytest.raises(rccpack.Error, match="strength"):
        rccpack.combine_priors([good], strength=0)
    with pytest.raises(FileNotFoundError):
        rccpack.task_counts(library[0] / "nowhere")


def run_cli(cli: Path, *args: str) -> None:
    p = subprocess.run([str(cli), *args], capture_output=True, text=True, check=False)
    assert p.returncode == 0, p.stderr


def test_learn_with_priors_is_the_cli_byte_for_byte(cli: Path, priors_file: Path, tmp_path: Path) -> None:
    demos_path = BOX / "demos.json"
    run_cli(cli, "learn", str(demos_path), "--priors", str(priors_file),
            "-o", str(tmp_path / "l.rcc"), "--report", str(tmp_path / "r.json"))
    rcc, report = (tmp_path / "l.rcc").read_text(), (tmp_path / "r.json").read_text()
    assert "\n# priors fnv1a64:" in rcc  # the priors changed something
    demos = rccpack.load_scenes(demos_path)
    for p in (priors_file, str(priors_file)):
        got = rccpack.learn(demos, priors=p)
        assert got.to_rcc() == rcc and got.report_json() == report
    plain = rccpack.learn(demos)
    assert plain.to_rcc() != rcc and "# priors" not in plain.to_rcc()
    task = rccpack.Task.load(BOX)
    assert task.learn(priors=priors_file).to_rcc() == rcc


def test_run_with_priors_is_the_cli(cli: Path, priors_file: Path, tmp_path: Path) -> None:
    task = tmp_path / "task"
    shutil.copytree(BOX, task)
    cli_out, py_out = tmp_path / "cli", tmp_path / "py"
    run_cli(cli, "run", str(task), "--out", str(cli_out), "--seed", "2", "--priors", str(priors_file))
    outcome = rccpack.Task.load(task).run(out=py_out, seed=2, priors=priors_file)
    assert outcome.exit_code == 0
    for name in ("learned.rcc", "learn-report.json", "solution.json"):
        assert (py_out / name).read_bytes() == (cli_out / name).read_bytes(), name
    assert "# priors fnv1a64:" in (py_out / "learned.rcc").read_text()


def test_ask_takes_priors(priors_file: Path, tmp_path: Path) -> None:
    with rccpack.AskSession(BOX, save=False, max_questions=0, priors=priors_file) as s:
        assert "# priors fnv1a64:" in s.learned_rcc
    with rccpack.AskSession(BOX, save=False, max_questions=0) as s:
        assert "# priors" not in s.learned_rcc
    r = rccpack.ask(BOX, lambda _probe: False, max_questions=0, priors=priors_file)
    assert "# priors fnv1a64:" in r.learned_rcc


def test_a_bad_priors_file_names_the_field(priors_file: Path, tmp_path: Path) -> None:
    good = json.loads(priors_file.read_text())

    def field_of(doc: Any, call: str = "learn") -> rccpack.PriorsError:
        p = tmp_path / "bad.json"
        p.write_text(json.dumps(doc, indent=2) + "\n")
        with pytest.raises(rccpack.PriorsError) as e:
            if call == "learn":
                rccpack.learn(rccpack.load_scenes(BOX / "demos.json"), priors=p)
            elif call == "task":
                rccpack.Task.load(BOX).learn(priors=p)
            else:
                rccpack.AskSession(BOX, save=False, priors=p)
        assert e.value.file == str(p) and str(p) in str(e.value)
        return e.value

    e = field_of(dict(good, version="rccpack-priors/0"))
    assert e.field == "version" and "rccpack-priors/0" in str(e)
    doc = json.loads(json.dumps(good))
    doc["kinds"][3]["prior"] = 0.123
    assert field_of(doc, "task").field == "kinds[3].prior"
    doc = json.loads(json.dumps(good))
    doc["kinds"][2]["candidates"] += 1
    assert field_of(doc, "ask").field == "hash"
    doc = json.loads(json.dumps(good))
    doc["kinds"][1]["kind"] = "{A}_nope"
    assert field_of(doc).field == "kinds[1].kind"
    with pytest.raises(FileNotFoundError):
        rccpack.learn(rccpack.load_scenes(BOX / "demos.json"), priors=tmp_path / "none.json")
