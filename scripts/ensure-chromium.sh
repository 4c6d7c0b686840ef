#!/bin/sh
# Makes sure Debian's Chromium is present: it runs the end-to-end tests, and its
# SwiftShader Vulkan driver lets Dawn (Node) run WebGPU without a GPU.
# Installs it with apt when running as root; otherwise says exactly what to do.
set -eu
CHROMIUM="${CHROMIUM_PATH:-/usr/bin/chromium}"
if [ -x "$CHROMIUM" ] && [ -f /usr/lib/chromium/vk_swiftshader_icd.json ]; then
  exit 0
fi
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then
  echo "Installing Debian's chromium (browser tests and SwiftShader WebGPU)..."
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq chromium >/dev/null
  exit 0
fi
echo "Debian's chromium is missing. Install it with:  sudo apt-get install -y chromium" >&2
echo "(or point CHROMIUM_PATH at a Chromium with SwiftShader)." >&2
exit 1
