# Sourced by scripts/test.sh and scripts/gen-docs.sh: the settings of the one build that
# serves the lints, the tests and the Python package. A cargo call with other settings
# builds the workspace again.
#
# A one-shot build gains nothing from the incremental cache, which costs gigabytes of disk.
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"
export GONIOLIGHT_FUZZ_SECONDS="${GONIOLIGHT_FUZZ_SECONDS:-10}"

# Clippy's driver compiles the workspace's crates in every build below, denying warnings
# (`cargo clippy` hands its arguments to the driver the same way). Every cargo call keeps
# it: the wrapper is part of what cargo fingerprints, so a call without it builds again.
clippy_driver="$(rustc --print sysroot)/bin/clippy-driver"
if [ ! -x "$clippy_driver" ]; then
  echo "error: $clippy_driver not found: install clippy (rustup component add clippy)" >&2
  exit 1
fi
export RUSTC_WORKSPACE_WRAPPER="$clippy_driver"
export CLIPPY_ARGS="-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__"
# The Python extension links no libpython (as maturin builds it).
export PYO3_BUILD_EXTENSION_MODULE=1
