#!/usr/bin/env bash
# Installs what a fresh Debian machine lacks to build and test goniolight.
set -euo pipefail

need_apt=()
command -v cc >/dev/null 2>&1 || need_apt+=(gcc libc6-dev)
# The image tests' FLIP metric (nv-flip-sys) compiles C++.
command -v c++ >/dev/null 2>&1 || need_apt+=(g++)
# GPU code runs on any Vulkan driver; without one, the software driver lavapipe.
if ! compgen -G "/usr/share/vulkan/icd.d/*.json" >/dev/null && ! compgen -G "/etc/vulkan/icd.d/*.json" >/dev/null; then
  need_apt+=(mesa-vulkan-drivers libvulkan1)
fi
command -v python3 >/dev/null 2>&1 || need_apt+=(python3)
# The Python package's tests run in a virtual environment.
python3 -c "import venv, ensurepip" >/dev/null 2>&1 || need_apt+=(python3-venv python3-pip)
# The viewer's window tests run under a virtual X server; winit loads these X libraries.
command -v xvfb-run >/dev/null 2>&1 || need_apt+=(xvfb xauth)
# The calc report is checked in a real browser (headless Chromium renders it to a PNG).
command -v chromium >/dev/null 2>&1 || need_apt+=(chromium)
for lib in libxkbcommon-x11.so.0 libXcursor.so.1 libXi.so.6 libXrandr.so.2 libX11-xcb.so.1; do
  if ! ldconfig -p 2>/dev/null | grep -q "$lib"; then
    need_apt+=(libxkbcommon-x11-0 libxcursor1 libxi6 libxrandr2 libx11-xcb1)
    break
  fi
done
if [ ${#need_apt[@]} -gt 0 ]; then
  echo "installing: ${need_apt[*]}" >&2
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need_apt[@]}" >/dev/null
fi

if ! command -v cargo >/dev/null 2>&1; then
  echo "error: cargo not found. goniolight needs Rust 1.95 or newer: install it with rustup" >&2
  echo "       (https://rustup.rs), then run this command again." >&2
  exit 1
fi
if command -v rustup >/dev/null 2>&1; then
  for comp in rustfmt clippy; do
    rustup component list --installed 2>/dev/null | grep -q "^$comp" || rustup component add "$comp"
  done
fi
