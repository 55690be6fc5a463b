#!/usr/bin/env bash
# CI for the Python package: from a clean clone on a fresh machine, build
# the extension into a virtual environment and run its tests.
#
#   bash python/ci.sh
#
# Creates python/.venv (gitignored), installs maturin, pytest and mypy from
# PyPI, builds the CLI the parity tests compare with, builds and installs
# the extension (`maturin develop`, dev profile; the core and every
# dependency are optimised, see Cargo.toml), then runs pytest and
# `mypy --strict` on the tests, the example and the bench, and stubtest.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
# One target folder with the root crate: the dependencies built for
# `cargo test` are reused.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
venv="$here/.venv"

echo "== python: virtual environment $venv"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade maturin pytest mypy

echo "== python: cargo fmt --check, cargo clippy -D warnings (python/)"
cargo fmt --manifest-path "$here/Cargo.toml" -- --check
cargo clippy --quiet --manifest-path "$here/Cargo.toml" -- -D warnings

echo "== python: the rccpack CLI (the parity tests compare with it)"
# The library part optimised as in the extension, so that the CLI side of
# `ask` and `synth` runs at the same speed.
(cd "$root" && cargo build --quiet --bin rccpack --config 'profile.dev.package.rccpack.opt-level=2')
export RCCPACK_BIN="$CARGO_TARGET_DIR/debug/rccpack"

echo "== python: maturin develop"
(cd "$here" && VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" "$venv/bin/maturin" develop --quiet)

echo "== python: pytest"
cd "$here"
"$venv/bin/python" -m pytest -q tests

echo "== python: mypy --strict, stubtest (the stubs against the built module)"
"$venv/bin/python" -m mypy --strict tests examples bench.py
"$venv/bin/python" -m mypy.stubtest rccpack
echo "== python ok"
