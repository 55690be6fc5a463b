"""Every Python example of the documentation runs.

The `python` blocks of each page (`README.md`, `docs/python.md`,
`python/README.md`) run in order in one namespace, as a reader pasting
them into one session would, from a scratch folder holding a copy of the
repository's `examples/`. A block whose info string says `ignore` is shown
only. The Rust and shell examples are tested by `cargo test` (doctests and
`tests/docs.rs`)."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = ["README.md", "docs/python.md", "python/README.md"]


def python_blocks(text: str) -> list[tuple[int, str]]:
    """The `python` blocks of a page: `(line, source)`."""
    blocks: list[tuple[int, str]] = []
    body: list[str] | None = None
    start = 0
    in_other = False
    for n, line in enumerate(text.splitlines(), 1):
        fence = line.strip().startswith("```")
        if body is not None:
            if fence:
                blocks.append((start, "\n".join(body) + "\n"))
                body = None
            else:
                body.append(line)
        elif in_other:
            in_other = not fence
        elif fence:
            info = line.strip()[3:].split()
            if info[:1] == ["python"] and "ignore" not in info:
                body, start = [], n + 1
            else:
                in_other = True
    return blocks


def test_the_scanner_finds_blocks() -> None:
    text = "a\n```python\nx = 1\n```\n```console\n$ b\n```\n```python ignore\ny\n```\n"
    assert python_blocks(text) == [(3, "x = 1\n")]


@pytest.mark.parametrize("page", PAGES)
def test_every_python_example_runs(page: str, tmp_path: Path) -> None:
    blocks = python_blocks((ROOT / page).read_text())
    assert blocks, f"{page} has no python block: is the scanner broken?"
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        namespace: dict[str, object] = {"__name__": f"docs_{Path(page).stem}"}
        for line, source in blocks:
            code = compile(source, f"{page}:{line}", "exec")
            exec(code, namespace)  # noqa: S102 - the documentation's own examples
    finally:
        os.chdir(here)
