// End-to-end tests in Debian's Chromium: WebGPU through SwiftShader for the main
// project, and WebGPU switched off for the CPU-fallback project. The book is
// served from the production build (`vite build`, then `vite preview`).
import { defineConfig } from '@playwright/test';
import { CHROMIUM_PATH, NO_WEBGPU_ARGS, WEBGPU_ARGS } from './scripts/chromium.mjs';

const PORT = Number(process.env['E2E_PORT'] ?? 4173);
// Several checkouts or developers can test side by side: E2E_DIST names the
// build to serve (default dist/) and E2E_RESULTS where Playwright writes.
const DIST = process.env['E2E_DIST'] ?? 'dist';
const RESULTS = process.env['E2E_RESULTS'] ?? 'test-results';

export default defineConfig({
  testDir: 'tests/e2e',
  timeout: 60_000,
  expect: { timeout: 15_000 },
  fullyParallel: false,
  // Two browsers at once on the two cores CI has: much of a test is waiting (page loads,
  // polls for a settled picture, animation frames) rather than SwiftShader's drawing,
  // so two workers shorten the run; files still run their tests in order. E2E_WORKERS=1
  // runs one at a time (a loaded machine, or a spec being debugged).
  workers: Number(process.env['E2E_WORKERS'] ?? 2),
  retries: 0,
  outputDir: RESULTS,
  reporter: [['list'], ['json', { outputFile: `${RESULTS}/playwright.json` }]],
  use: {
    baseURL: `http://localhost:${PORT}`,
    viewport: { width: 1280, height: 900 },
    // The book registers a service worker that precaches ~6 MB on first load. Every test
    // gets a fresh context, so it would install and download again in the background of
    // every test; only tests/e2e/offline.spec.ts, which is about it, allows it.
    serviceWorkers: 'block',
  },
  projects: [
    {
      name: 'webgpu',
      testIgnore: /fallback\.spec\.ts/,
      use: { launchOptions: { executablePath: CHROMIUM_PATH, args: WEBGPU_ARGS } },
    },
    {
      name: 'no-webgpu',
      testMatch: /fallback\.spec\.ts/,
      use: { launchOptions: { executablePath: CHROMIUM_PATH, args: NO_WEBGPU_ARGS } },
    },
  ],
  webServer: {
    command: `npx vite preview --port ${PORT} --strictPort --outDir ${DIST}`,
    url: `http://localhost:${PORT}/index.html`,
    reuseExistingServer: !process.env['CI'],
    timeout: 60_000,
  },
});
