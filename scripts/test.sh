#!/usr/bin/env bash
# Formatting, lints and every test — what CI runs. Ends with the time of each stage, so
# the next slow one is visible.
#
# One build serves the lints, the tests and the Python package:
# - it runs under clippy's driver (what `cargo clippy` itself does, with `check` in place
#   of a build), so the dependencies are compiled once, not once to check and once to link;
# - it builds the whole workspace in one invocation (the library, binary, tests, benches,
#   examples and the Python extension), so every crate is built with one set of features;
#   the test runs below name the workspace too and find it all built, and the Python tests
#   load the extension from it (a `pip install ./python` builds the GPU stack again with
#   the package's own features: scripts/test-python.sh without --from-build does that);
# - the development and test profiles are the same (Cargo.toml).
#
# GONIOLIGHT_FUZZ_SECONDS: each stable-Rust fuzz target's budget in the gate (default 10;
# scripts/fuzz.sh runs them for longer).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# The build settings every cargo call of the test command shares (clippy's driver, no
# incremental cache, the Python extension's linking).
. scripts/build-env.sh

started=$SECONDS
times=()
failed=()
current=""
# stage NAME COMMAND…: runs COMMAND and records its time; a failure stops the run.
stage() {
  current=$1
  shift
  local t0=$SECONDS
  echo "==> $current" >&2
  "$@"
  times+=("$(printf '%6d s  %s' $((SECONDS - t0)) "$current")")
}
# test_stage NAME COMMAND…: as stage, but a failing test binary does not stop the others.
test_stage() {
  current=$1
  shift
  local t0=$SECONDS mark=""
  echo "==> $current" >&2
  "$@" || { mark="  FAILED"; failed+=("$current"); }
  times+=("$(printf '%6d s  %s%s' $((SECONDS - t0)) "$current" "$mark")")
}
report() {
  local rc=$?
  echo
  echo "Stage times (scripts/test.sh, $((SECONDS - started)) s in all):"
  printf '%s\n' "${times[@]}"
  if [ "$rc" -ne 0 ] && [ ${#failed[@]} -eq 0 ]; then
    echo "stopped in: $current (exit $rc)"
  fi
}
trap report EXIT

stage "fmt" cargo fmt --all --check
stage "build and clippy: the workspace, every target" \
  cargo build --workspace --all-targets --profile test --quiet
test_stage "test: library unit tests" cargo test --workspace --lib --quiet
test_stage "test: binary unit tests" cargo test --workspace --bins --quiet
for main in tests/*.rs tests/*/main.rs; do
  name=$(basename "$main" .rs)
  [ "$name" = main ] && name=$(basename "$(dirname "$main")")
  test_stage "test: tests/$name" cargo test --workspace --test "$name" --quiet
done
test_stage "test: doc tests" cargo test --workspace --doc --quiet
# The library without its GPU/GUI stack (photometry, sun, geometry, silhouettes, scene
# files): linted with its unit tests (the same tests run above with every feature; none is
# written for the feature-less build alone), and its documentation built.
stage "clippy: library without default features, with its unit tests" \
  cargo clippy --lib --no-default-features --profile test --quiet -- -D warnings
stage "docs: library without default features" \
  env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib --no-default-features --quiet
# The library with the GPU stack but no command line or viewer, as the Python package
# depends on it, and the package's crate: linted as before.
stage "clippy: the Python package's crate and the library as it uses it" \
  cargo clippy -p goniolight-python --quiet -- -D warnings
stage "package" cargo package -p goniolight --allow-dirty --no-verify --quiet
test_stage "python: pytest on the built extension" scripts/test-python.sh --from-build

if [ ${#failed[@]} -gt 0 ]; then
  echo "failed: ${failed[*]}" >&2
  exit 1
fi
