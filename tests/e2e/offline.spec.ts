// Offline reading (issue 18): one visit saves the whole book, and then, with the
// web server shut down and the browser offline, every page opens and every figure
// draws from the service worker's precache. And the update flow: a new version is
// downloaded while a saved copy is shown, the page says so, Reload switches to it,
// and another open tab says it is now the older version.
//
// These tests serve the build themselves (not through Playwright's shared
// webServer) so that they can stop the server — a page that still reached the
// network would fail — and serve a changed next version. They serve it under the
// base path it was built for (the manifest's scope), so a sub-path build
// (`vite build --base /courses/cmsc740/book/`) is checked the same way.
import { createServer, type Server } from 'node:http';
import { existsSync, readdirSync, readFileSync, statSync } from 'node:fs';
import { extname, join, normalize, relative, resolve } from 'node:path';
import type { AddressInfo } from 'node:net';
import AxeBuilder from '@axe-core/playwright';
import { expect, test, type Browser, type BrowserContext, type Page } from '@playwright/test';
import {
  APPENDIX_PAGE,
  canvasStats,
  chapterPages,
  trackErrors,
  waitForPicture,
  WIDGET_SELECTOR,
} from './support.ts';

const DIST = resolve(process.env['E2E_DIST'] ?? 'dist');

/** The base path the build was made for: the web app manifest's scope. */
function buildBase(): string {
  const manifest = JSON.parse(readFileSync(join(DIST, 'manifest.webmanifest'), 'utf8')) as {
    scope?: string;
  };
  const scope = manifest.scope ?? '/';
  return scope.endsWith('/') ? scope : `${scope}/`;
}

const TYPES: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.webmanifest': 'application/manifest+json',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.woff2': 'font/woff2',
  '.woff': 'font/woff',
  '.ttf': 'font/ttf',
  '.wgsl': 'text/plain; charset=utf-8',
  '.wesl': 'text/plain; charset=utf-8',
};

/** Changes to the served files, standing in for a newly deployed version. */
type Overrides = Map<string, (body: Buffer) => Buffer>;

/**
 * A static server for the build under `base` on an ephemeral localhost port (a
 * secure context, so service workers run). Node's server sends a Date header, which
 * the page shows as the date of its saved copy.
 */
async function serveBuild(
  base: string,
  overrides: Overrides = new Map(),
): Promise<{ server: Server; origin: string }> {
  const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url ?? '/', 'http://localhost').pathname);
    if (!path.startsWith(base)) {
      response.writeHead(404).end();
      return;
    }
    let relativePath = normalize(path.slice(base.length)).replace(/^(\.\.[/\\])+/, '');
    if (relativePath === '' || relativePath.endsWith('/')) relativePath += 'index.html';
    const file = join(DIST, relativePath);
    if (!file.startsWith(DIST) || !existsSync(file) || !statSync(file).isFile()) {
      response.writeHead(404).end();
      return;
    }
    const original = readFileSync(file);
    const body = overrides.get(relativePath)?.(original) ?? original;
    response.writeHead(200, {
      'Content-Type': TYPES[extname(file)] ?? 'application/octet-stream',
      'Cache-Control': 'no-cache',
    });
    response.end(body);
  });
  await new Promise<void>((done) => server.listen(0, 'localhost', done));
  const { port } = server.address() as AddressInfo;
  return { server, origin: `http://localhost:${port}` };
}

function closeServer(server: Server): Promise<void> {
  server.closeAllConnections();
  return new Promise((done) => server.close(() => done()));
}

/** Waits until the book's service worker is active and controls the page. */
async function waitForControl(page: Page): Promise<void> {
  await page.waitForFunction(
    () => navigator.serviceWorker.controller?.state === 'activated',
    undefined,
    { timeout: 60_000 },
  );
}

/** Every built file, relative to the build folder. */
function builtFiles(dir = DIST): string[] {
  return readdirSync(dir).flatMap((name) => {
    const path = join(dir, name);
    return statSync(path).isDirectory() ? builtFiles(path) : [relative(DIST, path)];
  });
}

/**
 * Built files the precache leaves out on purpose: the worker itself and its Workbox
 * runtime (the browser keeps those), and the WOFF/TTF copies of the KaTeX fonts
 * (every browser with service workers takes the WOFF2 copy; src/book/build/pwa.ts).
 */
const NOT_PRECACHED = /^(sw\.js|workbox-[\w-]+\.js)$|\.(woff|ttf|map)$/;

async function newContext(browser: Browser, origin: string): Promise<BrowserContext> {
  return browser.newContext({
    baseURL: origin,
    viewport: { width: 1280, height: 900 },
    serviceWorkers: 'allow',
  });
}

/**
 * axe-core's WCAG 2.1 AA findings for the status line, in both themes (with
 * screenshots kept when `shotPath` is given: a screenshot of a page that is not the
 * front tab waits for a frame that may never come).
 */
async function statusLineViolations(page: Page, shotPath?: (name: string) => string) {
  const found: string[] = [];
  for (const theme of ['light', 'dark'] as const) {
    // What the theme button does (src/book/theme.ts): pin the theme on <html>.
    await page.evaluate((value) => (document.documentElement.dataset['theme'] = value), theme);
    const line = page.locator('.sb-offline-message').first();
    await expect(line).toBeVisible();
    if (shotPath) await page.screenshot({ path: shotPath(`status-line-${theme}.png`) });
    const results = await new AxeBuilder({ page })
      .include('.sb-offline-status')
      .withTags(['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'])
      .analyze();
    for (const violation of results.violations) found.push(`${theme}: ${violation.id}`);
  }
  return found;
}

/**
 * Checks that every widget on the page has drawn, without error notices, and not blank.
 * The first picture is enough: it proves the widget's modules, kernels and data came from
 * the cache; its full refinement (tens of seconds per widget on SwiftShader) is its own
 * spec's business.
 */
async function expectFiguresDrawn(page: Page, widgets = page.locator(WIDGET_SELECTOR)) {
  for (const widget of await widgets.all()) {
    await waitForPicture(widget);
    await expect(widget.locator('.sb-notice--error')).toHaveCount(0);
    const canvas = widget.locator('canvas.sb-canvas').first();
    if ((await widget.locator('canvas.sb-canvas').count()) > 0) {
      const stats = await canvasStats(canvas);
      expect(
        stats.luminanceDeviation,
        `${await widget.evaluate((e) => e.tagName.toLowerCase())} draws a picture`,
      ).toBeGreaterThan(2);
    }
  }
  // A widget module that failed to load replaces its element with an alert.
  await expect(page.locator('.sb-notice--error')).toHaveCount(0);
}

const base = buildBase();
const pages = [
  { slug: 'home', path: 'index.html' },
  ...[...chapterPages(), APPENDIX_PAGE].map((chapter) => ({
    slug: chapter.slug,
    path: chapter.path.replace(/^\//, ''),
  })),
];

test.describe('offline reading', () => {
  test.describe.configure({ mode: 'serial' });
  let context: BrowserContext;
  let server: Server | null = null;

  test.afterAll(async () => {
    await context?.close();
    if (server) await closeServer(server);
  });

  test('one visit saves every page, script, style, font and data file of the build', async ({
    browser,
  }, info) => {
    const served = await serveBuild(base);
    server = served.server;
    context = await newContext(browser, served.origin);
    const page = await context.newPage();
    const errors = trackErrors(page);
    const started = Date.now();
    await page.goto(`${base}index.html`);
    await waitForControl(page);
    const cached = await page.evaluate(async () => {
      const urls: string[] = [];
      for (const name of await caches.keys()) {
        for (const request of await (await caches.open(name)).keys()) {
          const url = new URL(request.url);
          url.searchParams.delete('__WB_REVISION__');
          urls.push(url.pathname);
        }
      }
      return urls;
    });
    const expected = builtFiles()
      .filter((file) => !NOT_PRECACHED.test(file.split('/').pop() ?? ''))
      .map((file) => `${base}${file}`);
    expect(cached.length).toBeGreaterThan(0);
    expect(expected.filter((url) => !cached.includes(url))).toEqual([]);
    const bytes = expected.reduce(
      (sum, url) => sum + statSync(join(DIST, url.slice(base.length))).size,
      0,
    );
    info.annotations.push({
      type: 'precache',
      description: `${expected.length} files, ${(bytes / 2 ** 20).toFixed(2)} MiB, saved in ${Date.now() - started} ms under ${base}`,
    });
    // The worker scope is the base path, so a book under a sub-path leaves the
    // rest of its host alone.
    const scope = await page.evaluate(async () => {
      const registration = await navigator.serviceWorker.getRegistration();
      return registration ? new URL(registration.scope).pathname : null;
    });
    expect(scope).toBe(base);
    // Online, with nothing newer: the status line says nothing.
    await expect(page.locator('.sb-offline-status')).toBeEmpty();
    expect(errors).toEqual([]);
    // Now the network goes away entirely: the server stops, the browser is offline.
    await closeServer(served.server);
    server = null;
    await context.setOffline(true);
    await expect(page.locator('.sb-offline-message--offline')).toContainText(
      /^Offline — showing the saved copy from .+\.$/,
    );
  });

  for (const entry of pages) {
    test(`offline: ${entry.slug} opens and its figures draw`, async () => {
      test.setTimeout(180_000);
      const page = await context.newPage();
      const errors = trackErrors(page);
      const failed: string[] = [];
      page.on('requestfailed', (request) => failed.push(request.url()));
      await page.goto(`${base}${entry.path}`);
      await expect(page.locator('main h1')).toBeVisible();
      const status = page.getByRole('status').filter({ hasText: 'Offline' });
      await expect(status).toContainText(/^Offline — showing the saved copy from .+\.$/);
      await expectFiguresDrawn(page);
      // The math fonts come from the cache too: loading KaTeX's main faces succeeds,
      // and no face on the page failed.
      const fonts = await page.evaluate(async () => {
        const loaded = await document.fonts.load('16px KaTeX_Main');
        const italic = await document.fonts.load('italic 16px KaTeX_Math');
        await document.fonts.ready;
        return {
          loaded: [...loaded, ...italic].filter((face) => face.status === 'loaded').length,
          failed: [...document.fonts]
            .filter((face) => face.status === 'error')
            .map((face) => face.family),
        };
      });
      expect(fonts.failed).toEqual([]);
      expect(fonts.loaded).toBeGreaterThanOrEqual(2);
      expect(failed).toEqual([]);
      expect(errors).toEqual([]);
      await page.close();
    });
  }

  test('offline: the demo deck opens, every slide has its figure code, and slides draw', async () => {
    test.setTimeout(120_000);
    const page = await context.newPage();
    const errors = trackErrors(page);
    await page.goto(`${base}deck.html`);
    const slides = page.locator('.deck-slide');
    const count = await slides.count();
    expect(count).toBeGreaterThanOrEqual(2);
    // Every widget slide's module came from the cache: its element is defined
    // (drawing each figure is checked on its chapter page above).
    const widgetSlides = page.locator('.deck-slide--widget');
    await expect(slides.locator(WIDGET_SELECTOR)).toHaveCount(await widgetSlides.count());
    await expect
      .poll(() =>
        page.evaluate(() => document.querySelectorAll('.deck-slide *:not(:defined)').length),
      )
      .toBe(0);
    // The first widget slide and the last slide draw.
    const first = (await widgetSlides.first().getAttribute('id')) ?? '';
    await page.evaluate((n) => (location.hash = `slide=${n}`), first.replace('slide-', ''));
    await expectFiguresDrawn(page, page.locator(`#${first}`).locator(WIDGET_SELECTOR));
    await page.keyboard.press('End');
    await expect(page.locator(`#slide-${count}`)).toBeVisible();
    await expectFiguresDrawn(page, page.locator(`#slide-${count}`).locator(WIDGET_SELECTOR));
    expect(errors).toEqual([]);
    await page.close();
  });

  test('offline: the status line passes the accessibility check in both themes', async () => {
    const info = test.info();
    const page = await context.newPage();
    await page.goto(`${base}index.html`);
    await expect(page.getByRole('status')).toContainText('Offline — showing the saved copy from');
    expect(await statusLineViolations(page, (name) => info.outputPath(name))).toEqual([]);
    await page.close();
  });

  test('offline: a page with a query and a hash opens from the saved copy', async () => {
    const page = await context.newPage();
    const chapter = pages.find((p) => p.slug.startsWith('02-'));
    // The precache ignores queries (?backend=cpu selects the CPU twin).
    await page.goto(`${base}${chapter?.path ?? ''}?backend=cpu#content`);
    await expect(page.locator('main h1')).toBeVisible();
    await expectFiguresDrawn(page);
    await page.close();
  });
});

test.describe('updates', () => {
  test('a new version: the saved page says so, Reload switches to it, another tab says it is older', async ({
    browser,
  }) => {
    test.setTimeout(120_000);
    const overrides: Overrides = new Map();
    const { server, origin } = await serveBuild(base, overrides);
    const context = await newContext(browser, origin);
    try {
      const first = await context.newPage();
      await first.goto(`${base}index.html`);
      await waitForControl(first);
      const second = await context.newPage();
      await second.goto(`${base}index.html`);
      await expect(second.locator('.sb-offline-status')).toBeEmpty();

      // Deploy a next version: a changed home page, and a worker whose precache
      // list names the new revision of it.
      overrides.set('index.html', (body) =>
        Buffer.from(
          body.toString().replace('</head>', '<meta name="sb-version" content="next"></head>'),
        ),
      );
      overrides.set('sw.js', (body) =>
        Buffer.from(
          body
            .toString()
            .replace(
              /(\{url:"index\.html",revision:")[0-9a-f]+"/,
              (_match, head: string) => `${head}next-version"`,
            ),
        ),
      );
      expect(
        overrides
          .get('sw.js')?.(readFileSync(join(DIST, 'sw.js')))
          .toString(),
      ).toContain('next-version');
      // The browser looks for a new worker on navigations and on the page's hourly check.
      await first.evaluate(async () => {
        await (await navigator.serviceWorker.getRegistration())?.update();
      });
      const notice = first.getByRole('status').filter({ hasText: 'A new version' });
      await expect(notice).toContainText(
        'A new version of the book is available — this page is the saved copy from ',
      );
      // The page on screen is still the saved, older copy — and says so.
      await expect(first.locator('meta[name="sb-version"]')).toHaveCount(0);
      // A page opened now is still served from the saved copy, and says so as well.
      const third = await context.newPage();
      await third.goto(`${base}index.html`);
      await expect(third.locator('meta[name="sb-version"]')).toHaveCount(0);
      await expect(third.getByRole('status')).toContainText(
        'A new version of the book is available',
      );

      expect(await statusLineViolations(first)).toEqual([]);
      // Reload by keyboard: the waiting worker takes over and the page reloads from it.
      const button = notice.getByRole('button', { name: 'Reload' });
      await button.focus();
      await Promise.all([first.waitForEvent('load'), first.keyboard.press('Enter')]);
      await expect(first.locator('meta[name="sb-version"]')).toHaveCount(1);
      await expect(first.locator('.sb-offline-status')).toBeEmpty();
      // The tabs that stayed on the old copy now say that they are older.
      for (const other of [second, third]) {
        await expect(other.getByRole('status')).toContainText(
          'The book was updated in another tab; this page is still the older version.',
        );
        await expect(other.locator('meta[name="sb-version"]')).toHaveCount(0);
      }
      await Promise.all([
        second.waitForEvent('load'),
        second.getByRole('button', { name: 'Reload' }).click(),
      ]);
      await expect(second.locator('meta[name="sb-version"]')).toHaveCount(1);
    } finally {
      await context.close();
      await closeServer(server);
    }
  });
});
