// Offline reading (issue 18): one visit saves the whole book, and then, with the
// web server shut down and the browser offline, every page opens and every figure
// draws from the service worker's precache. Each chapter and the appendix, once its
// figures have drawn, also gets the book's page checks (typeset math, table of
// contents, chapter links, no console errors, axe-core in both themes; formerly one
// test per page in book.spec.ts, which loaded and drew every page a second time).
// And the update flow: a new version is downloaded while a saved copy is shown, the
// page says so, Reload switches to it, and another open tab says it is now the older
// version.
//
// These tests serve the build themselves (not through Playwright's shared
// webServer) so that they can stop the server — a page that still reached the
// network would fail — and serve a changed next version. They serve it under the
// base path it was built for (the manifest's scope), so a sub-path build
// (`vite build --base /courses/cmsc740/book/`) is checked the same way.
import { createServer, type Server } from 'node:http';
import { existsSync, readdirSync, readFileSync, rmSync, statSync } from 'node:fs';
import { extname, join, normalize, relative, resolve } from 'node:path';
import type { AddressInfo } from 'node:net';
import AxeBuilder from '@axe-core/playwright';
import {
  expect,
  test,
  type Browser,
  type BrowserContext,
  type Page,
  type TestInfo,
} from '@playwright/test';
import {
  APPENDIX_PAGE,
  axeViolations,
  bookPages,
  canvasStats,
  chapterPages,
  SUB_PATH,
  subPathBuild,
  trackErrors,
  waitForPicture,
  WIDGET_SELECTOR,
} from './support.ts';

/** A build to serve: its folder, and the base path it was made for. */
interface Build {
  dist: string;
  base: string;
}

/** The build in `dist`, with the base path it was made for: the web app manifest's scope. */
function buildIn(dist: string): Build {
  const folder = resolve(dist);
  const manifest = JSON.parse(readFileSync(join(folder, 'manifest.webmanifest'), 'utf8')) as {
    scope?: string;
  };
  const scope = manifest.scope ?? '/';
  return { dist: folder, base: scope.endsWith('/') ? scope : `${scope}/` };
}

/** The build the other specs serve (at the root, by default). */
const ROOT_BUILD = buildIn(process.env['E2E_DIST'] ?? 'dist');

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
  { dist, base }: Build,
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
    const file = join(dist, relativePath);
    if (!file.startsWith(dist) || !existsSync(file) || !statSync(file).isFile()) {
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

/** Every built file under `dir`, relative to the build folder `dist`. */
function builtFiles(dist: string, dir = dist): string[] {
  return readdirSync(dir).flatMap((name) => {
    const path = join(dir, name);
    return statSync(path).isDirectory() ? builtFiles(dist, path) : [relative(dist, path)];
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

/**
 * The build this spec reads offline, page by page: the one for a deep sub-path
 * (support.ts, subPathBuild), the stricter case: its service worker's scope, its
 * precache and every URL a page or figure fetches must stay under the base path (a URL
 * that escaped it is not in the precache, so it fails offline). tests/e2e/publish.spec.ts
 * leaves its browser pass over the chapters and the deck to this spec. The root build
 * gets the saving and scope checks, and one chapter offline (the last describe below).
 */
let build: Build = ROOT_BUILD;
let madeSubPathBuild = false;

test.beforeAll(() => {
  test.setTimeout(240_000);
  const made = subPathBuild();
  madeSubPathBuild = made.made;
  build = buildIn(made.dist);
  expect(build.base, 'the sub-path build is made for its path').toBe(SUB_PATH);
});

test.afterAll(() => {
  if (madeSubPathBuild) rmSync(build.dist, { recursive: true, force: true });
});

/**
 * The shader-library appendix has one entry per library function (328), each written by
 * the same template (src/book/build/appendix.ts: heading, signature, prose with math,
 * twin note). axe checks the page with the first two entries of each module (about 50):
 * every part the template writes, in every module, at a twentieth of the cost. The
 * table of contents and every entry's id were checked on the whole page before.
 */
async function sampleAppendixEntries(page: Page): Promise<void> {
  const kept = await page.evaluate(() => {
    const perModule = new Map<string, number>();
    let count = 0;
    for (const entry of document.querySelectorAll('section.api-entry')) {
      const module = entry.id.split('-')[0] ?? '';
      const seen = (perModule.get(module) ?? 0) + 1;
      perModule.set(module, seen);
      if (seen > 2) entry.remove();
      else count += 1;
    }
    return count;
  });
  expect(kept).toBeGreaterThan(20);
}

/** The book's pages (chapters, then the appendix): the reading order of the pager links. */
const BOOK_PAGES = bookPages();

/**
 * The book's checks of one page (chapter or appendix), once its figures have drawn their
 * first pictures (each widget's own spec checks its final numbers): typeset math, a table
 * of contents whose entries each lead to one element, the pager links, and axe-core in
 * the light theme (the full WCAG 2.1 AA set), then in the dark theme switched with the
 * page's own button, as a reader does (the colour rules only: axeViolations). The page is
 * the saved copy the service worker serves, which is the built file (the precache holds
 * every built file, checked by the first test here), so the raw HTML is read from it.
 */
async function expectBookPage(page: Page, index: number): Promise<void> {
  const chapter = BOOK_PAGES[index]!;
  await expect(page.locator('nav.toc a').first()).toBeVisible();
  // KaTeX ran at build time: the HTML already holds typeset math.
  const raw = readFileSync(join(build.dist, chapter.path), 'utf8');
  if (chapter.hasMath) expect(raw, 'typeset math').toContain('class="katex');
  expect(raw, 'no raw TeX').not.toMatch(/\$\$|\\label\{/);
  // Every entry leads to exactly one element of the page (one evaluation: the appendix's
  // table of contents has over 200 entries, each a round trip as a locator check).
  const tocTargets = await page.evaluate(() =>
    [...document.querySelectorAll('nav.toc a')].map((link) => {
      const id = (link.getAttribute('href') ?? '').slice(1);
      return { id, count: document.querySelectorAll(`[id="${CSS.escape(id)}"]`).length };
    }),
  );
  expect(tocTargets.length, 'table of contents').toBeGreaterThan(0);
  expect(
    tocTargets.filter((target) => target.count !== 1),
    'table of contents entries without exactly one target',
  ).toEqual([]);
  // Links are relative to their page: under the build's base they lead to its pages.
  const pathOf = (link: string): Promise<string> =>
    page.locator(link).evaluate((a) => (a as HTMLAnchorElement).pathname);
  const previous = BOOK_PAGES[index - 1];
  const next = BOOK_PAGES[index + 1];
  if (previous)
    expect(await pathOf('a[rel="prev"]'), 'previous link').toBe(
      `${build.base}${previous.path.slice(1)}`,
    );
  if (next)
    expect(await pathOf('a[rel="next"]'), 'next link').toBe(`${build.base}${next.path.slice(1)}`);
  if (chapter.slug === APPENDIX_PAGE.slug) await sampleAppendixEntries(page);
  expect(await axeViolations(page), 'light theme').toEqual([]);
  await page.locator('.theme-toggle').click();
  await expect(page.locator('html')).toHaveAttribute('data-theme', 'dark');
  expect(await axeViolations(page, true), 'dark theme').toEqual([]);
  // The choice is stored for the whole context: the pages after this one start light.
  await page.evaluate(() => localStorage.removeItem('scatterbook:theme'));
}

/**
 * Serves `served`, opens its home page in a new context, and checks that one visit saves
 * every built file (but NOT_PRECACHED) under the base path, in a worker whose scope is the
 * base path; then stops the server and takes the context offline, where the page says it
 * shows the saved copy. Returns that context (the caller closes it); on a failed check the
 * server and the context are closed here.
 */
async function saveThenGoOffline(
  browser: Browser,
  served: Build,
  info: TestInfo,
): Promise<BrowserContext> {
  const { server, origin } = await serveBuild(served);
  const context = await newContext(browser, origin);
  try {
    await saveAndCheck(context, served, info);
  } catch (error) {
    await context.close();
    await closeServer(server);
    throw error;
  }
  // Now the network goes away entirely: the server stops, the browser is offline.
  await closeServer(server);
  await context.setOffline(true);
  return context;
}

async function saveAndCheck(
  context: BrowserContext,
  { base, dist }: Build,
  info: TestInfo,
): Promise<void> {
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
  const expected = builtFiles(dist)
    .filter((file) => !NOT_PRECACHED.test(file.split('/').pop() ?? ''))
    .map((file) => `${base}${file}`);
  expect(cached.length).toBeGreaterThan(0);
  expect(expected.filter((url) => !cached.includes(url))).toEqual([]);
  const bytes = expected.reduce(
    (sum, url) => sum + statSync(join(dist, url.slice(base.length))).size,
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
  await page.close();
}

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

  test.afterAll(async () => {
    await context?.close();
  });

  test('one visit saves every page, script, style, font and data file of the build', async ({
    browser,
  }, info) => {
    context = await saveThenGoOffline(browser, build, info);
    const page = await context.newPage();
    await page.goto(`${build.base}index.html`);
    await expect(page.locator('.sb-offline-message--offline')).toContainText(
      /^Offline — showing the saved copy from .+\.$/,
    );
    await page.close();
  });

  for (const entry of pages) {
    const bookIndex = BOOK_PAGES.findIndex((chapter) => chapter.slug === entry.slug);
    const title =
      bookIndex < 0
        ? `offline: ${entry.slug} opens and its figures draw`
        : `offline: ${entry.slug} opens and its figures draw; typeset math, table of contents, chapter links, no console errors, axe-core in both themes`;
    test(title, async () => {
      // The page checks add two axe-core runs after the figures have drawn (the appendix is long).
      test.setTimeout(bookIndex < 0 ? 180_000 : 300_000);
      const page = await context.newPage();
      // Each page starts in the light theme: the dark-theme check of the page before
      // stored the reader's choice (src/book/theme.ts) in the shared context.
      await page.emulateMedia({ colorScheme: 'light' });
      await page.addInitScript(() => localStorage.removeItem('scatterbook:theme'));
      const errors = trackErrors(page);
      const failed: string[] = [];
      page.on('requestfailed', (request) => failed.push(request.url()));
      await page.goto(`${build.base}${entry.path}`);
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
      if (bookIndex >= 0) {
        await expectBookPage(page, bookIndex);
        expect(failed).toEqual([]);
        expect(errors).toEqual([]);
      }
      await page.close();
    });
  }

  test('offline: the demo deck opens, every slide has its figure code, and slides draw', async () => {
    test.setTimeout(120_000);
    const page = await context.newPage();
    const errors = trackErrors(page);
    await page.goto(`${build.base}deck.html`);
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
    await page.goto(`${build.base}index.html`);
    await expect(page.getByRole('status')).toContainText('Offline — showing the saved copy from');
    expect(await statusLineViolations(page, (name) => info.outputPath(name))).toEqual([]);
    await page.close();
  });

  test('offline: a page with a query and a hash opens from the saved copy', async () => {
    const page = await context.newPage();
    const chapter = pages.find((p) => p.slug.startsWith('02-'));
    // The precache ignores queries (?backend=cpu selects the CPU twin).
    await page.goto(`${build.base}${chapter?.path ?? ''}?backend=cpu#content`);
    await expect(page.locator('main h1')).toBeVisible();
    await expectFiguresDrawn(page);
    await page.close();
  });
});

test.describe('the build the other specs serve', () => {
  // Offline, its saving and scope are checked, and one chapter (every page and figure
  // offline is checked above, under the stricter sub-path): its page, modules, kernels
  // and fonts come from the saved copy.
  test('one visit saves every built file under its base, and a chapter then opens and draws offline', async ({
    browser,
  }, info) => {
    test.setTimeout(180_000);
    const context = await saveThenGoOffline(browser, ROOT_BUILD, info);
    try {
      const page = await context.newPage();
      const errors = trackErrors(page);
      const failed: string[] = [];
      page.on('requestfailed', (request) => failed.push(request.url()));
      const chapter = pages.find((p) => p.slug.startsWith('02-'));
      await page.goto(`${ROOT_BUILD.base}${chapter?.path ?? ''}`);
      await expect(page.getByRole('status').filter({ hasText: 'Offline' })).toContainText(
        /^Offline — showing the saved copy from .+\.$/,
      );
      await expectFiguresDrawn(page);
      expect(failed).toEqual([]);
      expect(errors).toEqual([]);
    } finally {
      await context.close();
    }
  });
});

test.describe('updates', () => {
  test('a new version: the saved page says so, Reload switches to it, another tab says it is older', async ({
    browser,
  }) => {
    test.setTimeout(120_000);
    const overrides: Overrides = new Map();
    const { server, origin } = await serveBuild(build, overrides);
    const context = await newContext(browser, origin);
    try {
      const first = await context.newPage();
      await first.goto(`${build.base}index.html`);
      await waitForControl(first);
      const second = await context.newPage();
      await second.goto(`${build.base}index.html`);
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
          .get('sw.js')?.(readFileSync(join(build.dist, 'sw.js')))
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
      await third.goto(`${build.base}index.html`);
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
