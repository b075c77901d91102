#!/usr/bin/env bash
# The Python package's pytest suite (which compares every function with the command line's
# output), in a virtual environment under target/.
#
#   scripts/test-python.sh               builds and installs the package as a user would
#                                        (`pip install ./python`: maturin, its own build)
#   scripts/test-python.sh --from-build  tests the extension module that
#                                        `cargo build --workspace --all-targets --profile test`
#                                        built (scripts/test.sh does), laid out as maturin
#                                        lays it out (pyproject.toml's module-name beside
#                                        the package's Python files): no second build of
#                                        the GPU stack with the package's own features
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/python-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet pytest numpy "eulumdat-ugr==1.0.2" "ezdxf==1.4.5" "trimesh==4.5.3"

from_build=""
if [ "${1:-}" = "--from-build" ]; then
  from_build=1
  shift
fi
if [ -n "$from_build" ]; then
  # The built module and the package, at the paths that pyproject.toml's [tool.maturin]
  # gives (module-name "goniolight._native", python-packages ["goniolight"]).
  staged=target/python-from-build
  rm -rf "$staged"
  mkdir -p "$staged"
  "$venv/bin/python" - "$staged" <<'EOF'
import pathlib, shutil, sys, tomllib
staged = pathlib.Path(sys.argv[1])
maturin = tomllib.loads(pathlib.Path("python/pyproject.toml").read_text())["tool"]["maturin"]
for package in maturin["python-packages"]:
    shutil.copytree(pathlib.Path("python") / package, staged / package)
crate = tomllib.loads(pathlib.Path("python/Cargo.toml").read_text())["lib"]["name"]
built = pathlib.Path("target/debug") / f"lib{crate}.so"
if not built.exists():
    sys.exit(f"error: {built} is missing: build it first with "
             "`cargo build --workspace --all-targets --profile test`")
*package, module = maturin["module-name"].split(".")
shutil.copy2(built, staged.joinpath(*package) / f"{module}.abi3.so")
EOF
  export PYTHONPATH="$PWD/$staged"
  # The same build made the command line (a `cargo build --bin` here would resolve the
  # features of the root crate alone and build the GPU stack again).
  if [ ! -x target/debug/goniolight ]; then
    echo "error: target/debug/goniolight is missing: build it first with" \
      "\`cargo build --workspace --all-targets --profile test\`" >&2
    exit 1
  fi
else
  # A development-profile build shares the compiled dependencies of `cargo test`.
  MATURIN_PEP517_ARGS="--profile dev" "$venv/bin/python" -m pip install --quiet ./python
  cargo build --quiet --bin goniolight
fi
GONIOLIGHT_BIN="$PWD/target/debug/goniolight" "$venv/bin/python" -m pytest -q python/tests "$@"
