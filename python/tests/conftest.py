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
