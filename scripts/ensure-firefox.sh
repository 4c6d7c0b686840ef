#!/bin/sh
# Makes sure Debian's Firefox ESR and Mesa's Vulkan drivers are present: the Firefox
# end-to-end tests (tests/firefox) run the book in firefox-esr with WebGPU drawing on
# lavapipe, the CPU Vulkan driver in mesa-vulkan-drivers. Installs them with apt when
# running as root; otherwise says exactly what to do.
set -eu
FIREFOX="${FIREFOX_PATH:-/usr/bin/firefox-esr}"
ICD="${FIREFOX_VK_ICD:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}"
if [ -x "$FIREFOX" ] && [ -f "$ICD" ]; then
  exit 0
fi
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then
  echo "Installing Debian's firefox-esr and mesa-vulkan-drivers (Firefox tests on lavapipe)..."
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq firefox-esr mesa-vulkan-drivers >/dev/null
  exit 0
fi
echo "Firefox ESR or Mesa's lavapipe Vulkan driver is missing. Install them with:" >&2
echo "  sudo apt-get install -y firefox-esr mesa-vulkan-drivers" >&2
echo "(or point FIREFOX_PATH at a Firefox with WebGPU and FIREFOX_VK_ICD at a Vulkan ICD file)." >&2
exit 1
