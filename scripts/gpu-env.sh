#!/bin/sh
# Runs a command with WebGPU available to Node on a machine without a GPU: Dawn
# (the `webgpu` package) uses SwiftShader through the Vulkan ICD that Debian's
# chromium ships, and the Vulkan loader chromium ships if the system has none.
ICD=/usr/lib/chromium/vk_swiftshader_icd.json
if [ -z "${VK_ICD_FILENAMES:-}" ] && [ -f "$ICD" ]; then
  export VK_ICD_FILENAMES="$ICD"
fi
if ! ldconfig -p 2>/dev/null | grep -q 'libvulkan.so.1 ' && [ -f /usr/lib/chromium/libvulkan.so.1 ]; then
  export LD_LIBRARY_PATH="/usr/lib/chromium${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
# Vulkan's window-system layers read XDG_RUNTIME_DIR and print an error line per device
# when it is unset (CI, root shells); a private empty folder silences them.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)" && export XDG_RUNTIME_DIR
fi
exec "$@"
