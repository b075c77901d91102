#!/usr/bin/env bash
# The main job on the bundled data: writes out/polar.png and out/check.json.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cargo run --release --quiet -- demo --out-dir out "$@"
