"""Overhead of the Python binding (a bench, not a timed test).

    python python/bench.py [--repeat N] [--cli PATH]

1. `synthesize` on the bundled example through Python against the same
   solve timed inside Rust (`SynthResult.stats.time_ms`, the core's own
   wall clock around the whole solve): the difference is the binding
   (argument conversion, the worker thread, the result objects).
2. `learn` on the bundled example through Python against `rccpack learn`
   (the CLI, in Rust) minus the CLI's start-up (`rccpack --version`) and
   file I/O.
3. A 1 000-object scene converted to and from Python objects: `from_dict`,
   `to_dict`, `objects`, `Scene(...)`.

Medians over the repeats; install a wheel first and run with `python -P` (the
source tree off `sys.path`). Also: `sample` against `rccpack sample`, `Task.run`
against `rccpack run`, and a whole `AskSession`.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import time
from pathlib import Path
from typing import Any, Callable

import rccpack

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "box-packing"


def median_ms(f: Callable[[], object], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append((time.perf_counter() - t) * 1000)
    return statistics.median(times)


def big_scene(n: int = 1000) -> dict[str, Any]:
    side = 40
    objects: list[dict[str, Any]] = []
    for i in range(n):
        o: dict[str, Any] = {"id": f"o{i}", "class": "RGB"[i % 3], "width": 10, "height": 10}
        if i % 2 == 0:
            o["x"], o["y"] = (i // 2 % side) * 10, (i // 2 // side) * 10
        objects.append(o)
    return {"space": {"width": side * 10, "height": side * 10}, "grid": 10, "objects": objects}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=20)
    ap.add_argument("--cli", default=os.environ.get("RCCPACK_BIN", str(ROOT / "target" / "release" / "rccpack")))
    a = ap.parse_args()
    demos = rccpack.load_scenes(EXAMPLE / "demos.json")
    problem = rccpack.load_scene(EXAMPLE / "problem.json")
    rules = rccpack.learn(demos).rules

    wall, inner = [], []
    for _ in range(a.repeat):
        t = time.perf_counter()
        r = rccpack.synthesize(problem, rules, like=demos, node_limit=100_000)
        wall.append((time.perf_counter() - t) * 1000)
        inner.append(r.stats.time_ms)
    w, i = statistics.median(wall), statistics.median(inner)
    print(f"synthesize: python {w:.2f} ms, rust (stats.time_ms) {i:.2f} ms, overhead {w - i:.2f} ms ({(w - i) / i * 100:.1f} %)")

    py_learn = median_ms(lambda: rccpack.learn(demos), a.repeat)
    cli = Path(a.cli)
    if cli.exists():
        def run(*args: str) -> None:
            subprocess.run([str(cli), *args], check=True, stdout=subprocess.DEVNULL)

        cli_learn = median_ms(lambda: run("learn", str(EXAMPLE / "demos.json"), "-o", os.devnull), a.repeat)
        start = median_ms(lambda: run("--version"), a.repeat)
        rust = cli_learn - start
        print(f"learn: python {py_learn:.2f} ms, rust (CLI {cli_learn:.2f} - start-up {start:.2f}) {rust:.2f} ms, "
              f"difference {py_learn - rust:.2f} ms")
    else:
        print(f"learn: python {py_learn:.2f} ms (no CLI at {cli} to compare with)")

    # sample: 50 layouts of score 1 through Python against `rccpack sample`
    # minus its start-up (reading the two files is a few hundred µs).
    py_sample = median_ms(lambda: list(rccpack.sample(problem, rules, n=50, seed=1, all_rules=True)), max(3, a.repeat // 4))
    if cli.exists():
        import tempfile

        with tempfile.TemporaryDirectory() as tmp:
            rules_path = Path(tmp) / "learned.rcc"
            rules_path.write_text(rccpack.learn(demos).to_rcc())
            cli_sample = median_ms(lambda: run("sample", str(EXAMPLE / "problem.json"), "--rules", str(rules_path),
                                               "-n", "50", "--seed", "1", "--all-rules", "--quiet"),
                                   max(3, a.repeat // 4))
        print(f"sample 50: python {py_sample:.2f} ms, rust (CLI - start-up) {cli_sample - start:.2f} ms, "
              f"difference {py_sample - (cli_sample - start):.2f} ms")

        # Task.run against `rccpack run` (learn + place + four files)
        with tempfile.TemporaryDirectory() as tmp:
            task = rccpack.Task.load(EXAMPLE)
            py_run = median_ms(lambda: task.run(out=Path(tmp) / "py"), max(3, a.repeat // 4))
            cli_run = median_ms(lambda: run("run", str(EXAMPLE), "--out", str(Path(tmp) / "cli")), max(3, a.repeat // 4))
        print(f"Task.run: python {py_run:.2f} ms, rust (CLI - start-up) {cli_run - start:.2f} ms, "
              f"difference {py_run - (cli_run - start):.2f} ms")

    # AskSession: one question (next_question + answer, files written)
    # against the session's own work; the whole session against ask().
    import shutil
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        task_dir = Path(tmp) / "task"
        shutil.copytree(EXAMPLE, task_dir, ignore=shutil.ignore_patterns("answers.json", "probes", "learned.rcc*"))
        t0 = time.perf_counter()
        with rccpack.AskSession(task_dir) as session:
            opened = (time.perf_counter() - t0) * 1000
            per_q = []
            while True:
                t1 = time.perf_counter()
                q = session.next_question()
                if q is None:
                    break
                session.answer(q, False)
                per_q.append((time.perf_counter() - t1) * 1000)
        total = (time.perf_counter() - t0) * 1000
    print(f"AskSession: open {opened:.1f} ms, {len(per_q)} questions, median {statistics.median(per_q):.1f} ms "
          f"per question (next_question + answer + files), whole session {total:.0f} ms")

    d = big_scene()
    scene = rccpack.Scene.from_dict(d)
    objs = scene.objects
    space = scene.space
    rows = [
        ("Scene.from_dict", lambda: rccpack.Scene.from_dict(d)),
        ("Scene.to_dict", lambda: scene.to_dict()),
        ("Scene.objects", lambda: scene.objects),
        ("Scene(space, objects)", lambda: rccpack.Scene(space, objs, 10)),
        ("Scene.from_json", lambda: rccpack.Scene.from_json(scene.to_json())),
    ]
    for name, f in rows:
        print(f"1000 objects: {name:<22} {median_ms(f, a.repeat):.3f} ms")
    rt = median_ms(lambda: rccpack.Scene.from_dict(scene.to_dict()), a.repeat)
    print(f"1000 objects: to_dict + from_dict round trip {rt:.3f} ms")


if __name__ == "__main__":
    main()
