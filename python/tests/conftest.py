"""Shared fixtures: the repository's bundled example and the `rccpack` CLI.

The CLI binary is `$RCCPACK_BIN` when set (python/ci.sh sets it), else
`target/{release,debug}/rccpack` of the repository (or of
`$CARGO_TARGET_DIR`), else it is built with `cargo build --bin rccpack`.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path
from typing import Callable

import pytest

import rccpack

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "box-packing"


def _find_cli() -> Path:
    env = os.environ.get("RCCPACK_BIN")
    if env:
        return Path(env)
    targets = [Path(os.environ["CARGO_TARGET_DIR"])] if "CARGO_TARGET_DIR" in os.environ else []
    targets.append(ROOT / "target")
    for t in targets:
        for profile in ("release", "debug"):
            p = t / profile / "rccpack"
            if p.exists():
                return p
    cargo = shutil.which("cargo")
    if cargo is None:
        pytest.skip("no rccpack binary and no cargo to build one")
    subprocess.run([cargo, "build", "--quiet", "--bin", "rccpack"], cwd=ROOT, check=True)
    return targets[0] / "debug" / "rccpack"


@pytest.fixture(scope="session")
def cli() -> Path:
    return _find_cli()


@pytest.fixture(scope="session")
def example() -> Path:
    return EXAMPLE


@pytest.fixture(scope="session")
def demos() -> list[rccpack.Scene]:
    return rccpack.load_scenes(EXAMPLE / "demos.json")


@pytest.fixture(scope="session")
def problem() -> rccpack.Scene:
    return rccpack.load_scene(EXAMPLE / "problem.json")


@pytest.fixture(scope="session")
def learned(demos: list[rccpack.Scene]) -> rccpack.Learned:
    return rccpack.learn(demos)


Oracle = Callable[[rccpack.Scene], bool]


def tree(d: Path) -> dict[str, bytes]:
    """Every file under `d` (relative path -> bytes)."""
    return {str(p.relative_to(d)): p.read_bytes() for p in sorted(d.rglob("*")) if p.is_file()}


@pytest.fixture(scope="session")
def pilot_oracle() -> Oracle:
    pilot = rccpack.load_rules(EXAMPLE / "pilot.rcc")

    def oracle(probe: rccpack.Scene) -> bool:
        # what `rccpack score --rules pilot.rcc --require` answers
        return all(r.satisfied >= r.subjects for r in rccpack.evaluate(probe, pilot).rules)

    return oracle


@pytest.fixture(scope="session")
def cli_session(cli: Path, tmp_path_factory: pytest.TempPathFactory) -> tuple[dict[str, bytes], str]:
    """The files an uninterrupted `rccpack ask --oracle` leaves on the
    bundled example, and what it prints."""
    d = tmp_path_factory.mktemp("cli") / "task"
    shutil.copytree(EXAMPLE, d)
    p = subprocess.run(
        [str(cli), "ask", str(d), "--question-seconds", "600", "--oracle", f"{cli} score --rules {EXAMPLE / 'pilot.rcc'} --require"],
        capture_output=True, text=True, check=False,
    )
    assert p.returncode == 0, p.stderr
    return tree(d), p.stdout
