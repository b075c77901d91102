#!/usr/bin/env bash
# The checks a machine with a real GPU is for (the "On a real GPU" figures of
# docs/src/measurements/radiosity.md and renderer.md), as one short run,
# the most wanted first:
#  1. the view-driven radiosity benchmark on the large scene seen in part: the generated
#     CAD office seen at a desk, three rounds (issue #20's goal: perspective-driven >= 5x
#     faster than global to 5 % in view);
#  2. the same on eight furnished rooms with both map rasterizers;
#  3. the viewer's frame times while it solves (headless: the same UI pass, render and
#     painting as in a window; goal >= 10 frames/s), the furnished room and the office;
#  4. the radiosity modules of the GPU test binary (tests/gpu/), one test at a time
#     (several at once on one GPU crashed a driver).
#
# Build first, where the toolchain is (the GPU machine needs neither Rust nor the network):
#   cargo build --release --bin goniolight --example make_scenes && cargo test --release --no-run
# then run this beside those builds, in a checkout at the same path (the test binaries read
# the bundled scenes from the folder they were built in; elsewhere, link that path to the
# checkout first). Each step's output (.txt, the JSON ones .json) and log (.log) and
# summary.txt (one line a step) go to out/gpu-check (GPU_CHECK_DIR); when $OUT is set
# (the device machine's folder that comes back, at most 8 files) they are packed after
# every step into $OUT/gpu-check.tar.gz, with summary.txt beside it, so a run stopped at
# its limit still brings back what it did. Each step has its own time limit, so one that
# hangs does not spend the machine's time; GPU_CHECK_MAX_S caps every limit (to try the
# script where the GPU is slow).
set -uo pipefail
cd "$(dirname "$0")/.."
out="${GPU_CHECK_DIR:-out/gpu-check}"
mkdir -p "$out"
summary="$out/summary.txt"
: >"$summary"
bin=target/release/goniolight
scenes=target/release/examples/make_scenes
for exe in "$bin" "$scenes"; do
  if [ ! -x "$exe" ]; then
    echo "error: $exe is missing: run cargo build --release --bin goniolight --example make_scenes first" >&2
    exit 2
  fi
done

pack() { # what is done so far, into $OUT
  if [ -n "${OUT:-}" ]; then
    tar -C "$out" -czf "$OUT/gpu-check.tar.gz" . && cp "$summary" "$OUT/summary.txt"
  fi
}

step() { # NAME LIMIT_S FILE COMMAND… — runs COMMAND with a limit into FILE (.log beside)
  local name=$1 limit=$2 file=$3
  shift 3
  if [ -n "${GPU_CHECK_MAX_S:-}" ] && [ "$GPU_CHECK_MAX_S" -lt "$limit" ]; then
    limit=$GPU_CHECK_MAX_S
  fi
  local start=$SECONDS
  timeout "$limit" "$@" >"$out/$file" 2>"$out/${file%.*}.log"
  local code=$?
  echo "$name: exit $code in $((SECONDS - start)) s (limit $limit s)" | tee -a "$summary"
  pack
}

# The office, generated (13 MB: not bundled) with its luminaires read from this checkout.
office="$(mktemp -d)"
trap 'rm -rf "$office"' EXIT
step "make_scenes cad-office" 60 make-scenes.txt "$scenes" cad-office "$office"
sed -i "s#^file = \".*/luminaires/#file = \"$PWD/luminaires/#" "$office/cad_office.toml"

step "bench radiosity-view: CAD office at a desk, 3 rounds" 300 bench-radiosity-view-cad-desk.json \
  "$bin" bench radiosity-view --scene "$office/cad_office.toml" --texel-density 5 \
  --eye 2.3,1.0,1.5 --look-at 2.3,2.4,0.75 --fov 40 --repeat 3 --json
for raster in hardware compute; do
  step "bench radiosity-view --rooms 8 --raster $raster" 240 \
    "bench-radiosity-view-rooms8-$raster.json" \
    "$bin" bench radiosity-view --rooms 8 --raster "$raster" --json
done
step "view --headless --indirect radiosity --drive perspective: furnished room" 120 \
  view-furnished-room.txt \
  "$bin" view --headless --indirect radiosity --drive perspective --frames 2000
step "view --headless --indirect radiosity --drive perspective: CAD office" 180 \
  view-cad-office.txt \
  "$bin" view "$office/cad_office.toml" --headless --indirect radiosity --drive perspective \
  --frames 2000
gpu_tests=$(find target/release/deps -maxdepth 1 -type f -executable -name "gpu-*" \
  -printf '%T@ %p\n' 2>/dev/null | sort -rn | head -n 1 | cut -d' ' -f2-)
for test in radiosity_view radiosity radiosity_restart; do
  if [ -z "$gpu_tests" ]; then
    echo "test $test: no release test binary (cargo test --release --no-run)" | tee -a "$summary"
    continue
  fi
  # tests/gpu/ is one binary; each file is a module there.
  step "test $test" 180 "test-$test.txt" "$gpu_tests" "$test::" --test-threads 1
done
pack
