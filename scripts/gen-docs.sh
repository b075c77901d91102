#!/usr/bin/env bash
# Writes the generated documentation after a change to the flags or the Python API: the
# command-line reference (docs/src/reference/cli/, one Markdown page per command) and the
# man pages (docs/man/) from the clap definitions, the scene file's JSON Schema and key
# reference (docs/src/reference/scene-file*) from its serde types, and the Python API reference
# (docs/src/reference/python.md) from the package's docstrings. The tests fail while a
# checked-in page differs from what the code generates.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/build-env.sh
cargo build --quiet --workspace --all-targets --profile test
GONIOLIGHT_BLESS=1 cargo test --quiet --workspace --profile test --test cli -- \
  --test-threads=1 docs::reference:: docs::scene_file::
GONIOLIGHT_BLESS=1 scripts/test-python.sh --from-build -k api_reference
