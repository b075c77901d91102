#!/usr/bin/env bash
# Writes the generated documentation after a change to the flags or the Python API: the
# command-line reference (docs/src/reference/cli/, one Markdown page per command) and the
# man pages (docs/man/) from the clap definitions, and the Python API reference
# (docs/src/reference/python.md) from the package's docstrings. The tests fail while a
# checked-in page differs from what the code generates.
set -euo pipefail
cd "$(dirname "$0")/.."
GONIOLIGHT_BLESS=1 cargo test --quiet --test cli docs::reference::
GONIOLIGHT_BLESS=1 scripts/test-python.sh -k api_reference
