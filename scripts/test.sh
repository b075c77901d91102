#!/usr/bin/env bash
# Formatting, lints and every test — what CI runs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# A one-shot build gains nothing from the incremental cache, which costs gigabytes of disk.
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"
cargo fmt --all --check
cargo clippy --all-targets -- -D warnings
# The library without its GPU/GUI stack (photometry, sun, geometry, silhouettes, scene files).
cargo clippy --lib --no-default-features -- -D warnings
cargo clippy -p goniolight-python -- -D warnings
# The stable-Rust fuzzers (tests/fuzz_parsers.rs) run 90 s per reader in CI.
GONIOLIGHT_FUZZ_SECONDS="${GONIOLIGHT_FUZZ_SECONDS:-90}" cargo test
cargo test --lib --no-default-features
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib --no-default-features --quiet
cargo package -p goniolight --allow-dirty --no-verify --quiet
scripts/test-python.sh
