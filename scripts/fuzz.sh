#!/usr/bin/env bash
# The stable-Rust fuzzers (tests/cpu/fuzz_parsers.rs) for longer than the gate's short run:
# every reader and the scene file for GONIOLIGHT_FUZZ_SECONDS each (default 600), in an
# optimised build. For a nightly job:
#   scripts/fuzz.sh                              # 10 minutes a target
#   GONIOLIGHT_FUZZ_SECONDS=3600 scripts/fuzz.sh # an hour a target
#   GONIOLIGHT_FUZZ_SEED=42 scripts/fuzz.sh      # other mutations than the fixed seed's
# A case that fails is written to target/fuzz-found/ (see the test file's header).
# The coverage-guided fuzzers (cargo-fuzz, nightly Rust) are in fuzz/.
set -euo pipefail
cd "$(dirname "$0")/.."
export GONIOLIGHT_FUZZ_SECONDS="${GONIOLIGHT_FUZZ_SECONDS:-600}"
exec cargo test --release --test cpu fuzz_parsers:: -- --test-threads "$(nproc)" "$@"
