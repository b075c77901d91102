#!/usr/bin/env bash
# The Python package: `pip install ./python` into a virtual environment under target/,
# then its pytest suite (which compares every function with the command line's output).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/python-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet pytest numpy "eulumdat-ugr==1.0.2"
# A development-profile build shares the compiled dependencies of `cargo test`.
MATURIN_PEP517_ARGS="--profile dev" "$venv/bin/python" -m pip install --quiet ./python
cargo build --quiet --bin goniolight
GONIOLIGHT_BIN="$PWD/target/debug/goniolight" "$venv/bin/python" -m pytest -q python/tests
