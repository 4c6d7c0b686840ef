// How this project launches Debian's Chromium with WebGPU on SwiftShader
// (DESIGN.md "Platform facts"). Shared by the Playwright config and the
// screenshot script. CHROMIUM_PATH overrides the executable.
export const CHROMIUM_PATH = process.env.CHROMIUM_PATH || '/usr/bin/chromium';

const COMMON = [
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
  ...(process.getuid && process.getuid() === 0 ? ['--no-sandbox'] : []),
];

export const WEBGPU_ARGS = [
  ...COMMON,
  '--enable-unsafe-webgpu',
  '--enable-features=Vulkan',
  '--use-vulkan=swiftshader',
  '--use-angle=swiftshader',
];

/** Chromium with WebGPU switched off, for testing the CPU fallback. */
export const NO_WEBGPU_ARGS = [...COMMON, '--disable-features=WebGPU,Vulkan'];
