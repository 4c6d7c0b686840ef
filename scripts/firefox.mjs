// How this project launches Firefox with WebGPU (README "Browser support"):
// Debian's firefox-esr driven by puppeteer-core over WebDriver BiDi (Playwright's
// Firefox is a patched build that cannot be installed from Debian), headless, with
// WebGPU switched on by prefs (without them `navigator.gpu` is absent on Linux),
// drawing on Mesa's lavapipe Vulkan driver (a CPU rasterizer; Firefox finds no
// adapter on SwiftShader). Shared by the Firefox end-to-end tests and the
// screenshot script. FIREFOX_PATH and FIREFOX_VK_ICD override the defaults.
export const FIREFOX_PATH = process.env.FIREFOX_PATH || '/usr/bin/firefox-esr';
export const LAVAPIPE_ICD =
  process.env.FIREFOX_VK_ICD || '/usr/share/vulkan/icd.d/lvp_icd.x86_64.json';

/** Firefox prefs that switch WebGPU on where the release build keeps it off. */
export const WEBGPU_PREFS = {
  'dom.webgpu.enabled': true,
  'gfx.webgpu.ignore-blocklist': true,
  'gfx.webgpu.force-enabled': true,
};

/** Options for puppeteer-core's `launch` (headless Firefox with WebGPU on lavapipe). */
export function firefoxLaunchOptions() {
  return {
    browser: 'firefox',
    protocol: 'webDriverBiDi',
    executablePath: FIREFOX_PATH,
    headless: true,
    extraPrefsFirefox: WEBGPU_PREFS,
    env: { ...process.env, VK_ICD_FILENAMES: LAVAPIPE_ICD },
  };
}
