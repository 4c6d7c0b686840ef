// Offline reading: the options of vite-plugin-pwa (Workbox, generateSW strategy).
// The service worker precaches the whole built book — every page, script, style
// sheet, math font and data file the widgets fetch — so that after one visit every
// chapter opens and draws without a network. Updates never take over silently
// (registerType 'prompt'): the page registers the worker itself
// (src/book/offline.ts) and offers a Reload button once a new version is waiting.
import type { VitePWAOptions } from 'vite-plugin-pwa';
import { SITE_SUBTITLE, SITE_TITLE } from './pages.ts';

/**
 * What is precached, by file type, so that pages added later (embeds, appendices)
 * and new data files under public/ are covered without a list to keep up to date.
 * Fonts: only WOFF2. KaTeX's style sheet lists each face as woff2, then woff, then
 * ttf, and a browser takes the first format it supports; every browser that runs
 * service workers supports WOFF2, so the WOFF and TTF copies (two thirds of the
 * font bytes) would never be read from the cache.
 */
export const PRECACHE_PATTERNS = [
  // (The web app manifest is added by vite-plugin-pwa itself, and so would appear twice.)
  '**/*.{html,js,mjs,css,woff2,svg,png,webp}',
  // Data the widgets fetch at run time: scenes, volume grids, reference images,
  // and shader sources should a widget ever fetch them instead of bundling them.
  '**/*.{json,f32,bin,wgsl,wesl}',
];

/**
 * Largest file precached. The biggest built file is the shader-library appendix
 * page (about 1.7 MB of typeset math); Workbox's default of 2 MiB would leave no
 * margin, and a page silently left out would be missing offline.
 */
export const PRECACHE_MAX_FILE_BYTES = 8 * 1024 * 1024;

export function offlineReading(): Partial<VitePWAOptions> {
  return {
    strategies: 'generateSW',
    registerType: 'prompt',
    // src/book/offline.ts registers the worker with workbox-window, so that it can
    // say when a new version is waiting and when the page is a saved copy.
    injectRegister: false,
    filename: 'sw.js',
    manifestFilename: 'manifest.webmanifest',
    // The icons are in public/ and matched by the patterns above; listing them again
    // would put each in the precache twice.
    includeManifestIcons: false,
    // The book works in `vite` (npm start) without a worker: no precache in development.
    devOptions: { enabled: false },
    manifest: {
      name: `${SITE_TITLE} — ${SITE_SUBTITLE}`,
      short_name: SITE_TITLE,
      description: SITE_SUBTITLE,
      lang: 'en',
      display: 'standalone',
      // start_url and scope default to Vite's base, so the installed book opens at
      // its own sub-path. Icon URLs are relative to the manifest, which sits at the
      // base. The maskable icon keeps its drawing inside the central safe circle
      // (radius 40 % of the size) that launchers may crop to.
      background_color: '#fbfaf7',
      theme_color: '#1d2a44',
      icons: [
        { src: 'favicon.svg', sizes: 'any', type: 'image/svg+xml', purpose: 'any' },
        { src: 'icon-maskable.svg', sizes: 'any', type: 'image/svg+xml', purpose: 'maskable' },
      ],
    },
    workbox: {
      globPatterns: PRECACHE_PATTERNS,
      maximumFileSizeToCacheInBytes: PRECACHE_MAX_FILE_BYTES,
      // A multi-page book: an address that was never built must not open the home
      // page in its place (vite-plugin-pwa's default fallback is index.html).
      navigateFallback: null,
      // Every query is the page's own business (?backend=cpu, deep-link states live
      // in the hash anyway): the same precached file answers with or without it.
      ignoreURLParametersMatching: [/.*/],
      // The first installation controls the open page at once, so the reader's first
      // visit is enough to read offline. Later versions wait for the Reload button.
      clientsClaim: true,
      skipWaiting: false,
      cleanupOutdatedCaches: true,
    },
  };
}
