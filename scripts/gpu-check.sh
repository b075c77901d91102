#!/usr/bin/env bash
# The checks a machine with a real GPU is for (README, "On a real GPU"), as one short run:
# the view-driven radiosity benchmark on eight rooms with both map rasterizers (issue #20's
# goal: perspective-driven >= 5x faster than global to 5 % in view), then the GPU test
# binaries that are there, one at a time (several at once on one GPU crashed a driver).
#
# Build first, where the toolchain is (the GPU machine needs neither Rust nor the network):
#   cargo build --release && cargo test --release --no-run
# then run this beside those builds, in a checkout at the same path (the test binaries read
# the bundled scenes from the folder they were built in). Results go to $OUT (or
# out/gpu-check): the benchmark's JSON (with the GPU's name) and log per rasterizer, each
# test binary's output (.txt) and log (.log), and summary.txt, one line a step.
# Each step has its own time limit, so one that hangs does not spend the machine's time.
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/gpu-check}"
mkdir -p "$out"
summary="$out/summary.txt"
: >"$summary"
bin=target/release/goniolight
if [ ! -x "$bin" ]; then
  echo "error: $bin is missing: run cargo build --release first" >&2
  exit 2
fi

step() { # NAME LIMIT_S STDOUT STDERR COMMAND… — runs COMMAND with a limit, logs its exit
  local name=$1 limit=$2 stdout=$3 stderr=$4
  shift 4
  local start=$SECONDS
  timeout "$limit" "$@" >"$stdout" 2>"$stderr"
  local code=$?
  echo "$name: exit $code in $((SECONDS - start)) s" | tee -a "$summary"
}

for raster in hardware compute; do
  step "bench radiosity-view --rooms 8 --raster $raster" 240 \
    "$out/bench-radiosity-view-$raster.json" "$out/bench-radiosity-view-$raster.log" \
    "$bin" bench radiosity-view --rooms 8 --raster "$raster" --json
done
for test in radiosity_view radiosity radiosity_restart; do
  exe=$(find target/release/deps -maxdepth 1 -type f -executable -name "$test-*" \
    -printf '%T@ %p\n' 2>/dev/null | sort -rn | head -n 1 | cut -d' ' -f2-)
  if [ -z "$exe" ]; then
    echo "test $test: no release test binary (cargo test --release --no-run)" | tee -a "$summary"
    continue
  fi
  step "test $test" 180 "$out/test-$test.txt" "$out/test-$test.log" "$exe" --test-threads 1
done
