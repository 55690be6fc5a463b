#!/usr/bin/env bash
# CI for the Python package: from a clean clone on a fresh machine, build
# the wheel, install it (not the source tree) into a fresh virtual
# environment and run the tests against it.
#
#   bash python/ci.sh
#
# python/.venv (gitignored) holds the build tool (maturin); the wheel is
# built with `maturin build` (the dev profile: the core and every
# dependency optimised at opt-level 2, see Cargo.toml — the same build as
# `maturin develop`, and the same artifacts the root `cargo test` makes,
# so CI compiles nothing twice; `maturin build --release` makes the
# distribution wheel, see the README), then installed into a new
# python/.venv-wheel with pytest, Hypothesis, mypy and Dask. The tests run from
# outside the source tree, so `import rccpack` is the installed wheel:
# pytest, `mypy --strict` on the tests, the examples and the bench, and
# stubtest of the stubs against the installed module. Last, the sdist is
# built (`maturin sdist`) and its contents checked.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
# One target folder with the root crate: the dependencies built for
# `cargo test` are reused.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
venv="$here/.venv"
wvenv="$here/.venv-wheel"
wheels="$CARGO_TARGET_DIR/wheels"
pip_quiet=(--quiet --disable-pip-version-check)

echo "== python: build tools in $venv"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install "${pip_quiet[@]}" --upgrade maturin

echo "== python: cargo fmt --check, cargo clippy -D warnings (python/)"
cargo fmt --manifest-path "$here/Cargo.toml" -- --check
cargo clippy --quiet --manifest-path "$here/Cargo.toml" -- -D warnings

echo "== python: the rccpack CLI (the parity tests compare with it)"
# The library part optimised as in the extension, so that the CLI side of
# `ask` and `synth` runs at the same speed.
(cd "$root" && cargo build --quiet --bin rccpack --config 'profile.dev.package.rccpack.opt-level=2')
export RCCPACK_BIN="$CARGO_TARGET_DIR/debug/rccpack"

echo "== python: maturin build (abi3 wheel)"
t0=$(date +%s)
rm -f "$wheels"/rccpack-*.whl
# A `maturin develop` of an earlier checkout leaves the extension in the
# source tree; the tests must not see it.
rm -f "$here"/rccpack/_rccpack*.so "$here"/rccpack/_rccpack*.pyd
(cd "$here" && "$venv/bin/maturin" build --quiet --out "$wheels")
wheel="$(ls "$wheels"/rccpack-*.whl)"
echo "   $(basename "$wheel") in $(( $(date +%s) - t0 )) s"
case "$(basename "$wheel")" in
  *-abi3-*) ;;
  *) echo "error: $wheel is not an abi3 wheel" >&2; exit 1 ;;
esac

echo "== python: a fresh virtual environment with the wheel ($wvenv)"
rm -rf "$wvenv"
python3 -m venv "$wvenv"
"$wvenv/bin/python" -m pip install "${pip_quiet[@]}" "$wheel" pytest hypothesis mypy \
  "dask[distributed]"  # the cluster recipe's test (examples/dask_priors.py)
# From outside the source tree: the installed package, not python/rccpack.
cd /
"$wvenv/bin/python" - "$wvenv" <<'EOF'
import sys, rccpack, rccpack._rccpack as ext
assert rccpack.__file__.startswith(sys.argv[1]), rccpack.__file__
assert ext.__file__.startswith(sys.argv[1]), ext.__file__
print("   rccpack", rccpack.__version__, "from", rccpack.__file__)
EOF

echo "== python: pytest (the installed wheel)"
"$wvenv/bin/python" -m pytest -q -p no:cacheprovider "$here/tests" "$here/examples/planner_property.py"

echo "== python: mypy --strict, stubtest (the stubs against the installed module)"
(cd "$here" && "$wvenv/bin/python" -m mypy --strict --no-incremental tests examples bench.py rccpack)
"$wvenv/bin/python" -m mypy.stubtest rccpack

echo "== python: sdist"
rm -f "$wheels"/rccpack-*.tar.gz
(cd "$here" && "$venv/bin/maturin" sdist --out "$wheels" >/dev/null)
sdist="$(ls "$wheels"/rccpack-*.tar.gz)"
tar tzf "$sdist" > "$wheels/sdist.txt"
for f in pyproject.toml rccpack/__init__.pyi rccpack/strategies.py src/lib.rs; do
  grep -q "/python/$f\$\|/$f\$" "$wheels/sdist.txt" || { echo "error: $sdist lacks $f" >&2; exit 1; }
done
echo "   $(basename "$sdist"): $(wc -l < "$wheels/sdist.txt") files"
echo "== python ok"
