// The built book works under any URL path (issue 18): the site built for `/` and a
// copy built for a deep sub-path are each served under their path by a tiny static
// server that answers 404 everywhere else, so a link or fetch that escapes the base
// fails here as it would on a course's web space.
//   - A link checker reads every built HTML file: each internal href/src/srcset (a,
//     area, link, script, img, source, iframe, …) and each url() of the built CSS
//     (the KaTeX fonts) must be served, and a fragment must name an id on its page.
//   - A browser pass opens the pages of the sub-path build that tests/e2e/offline.spec.ts
//     does not (offline.spec.ts opens the home page, every chapter, the appendix and the
//     deck of this same build offline, draws every figure and fails on any request that
//     escapes the base path, being absent from the precache, and on console errors):
//     the answers page and the embed pages, and the figure states that fetch data files.
//     It scrolls the figures that fetch files into view (they fetch when they first
//     draw) and records failed requests (status ≥ 400 or network failures) and console
//     errors.
// The sub-path build (about 20–40 s) is made once, into a temporary folder; set
// E2E_SUB_DIST to a build made with `--base /courses/cmsc740/book/` to reuse one
// (scripts/test.mjs does: support.ts, subPathBuild).
import { existsSync, readFileSync, readdirSync, rmSync, statSync } from 'node:fs';
import { createServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { extname, join, relative, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test, type Page } from '@playwright/test';
import { bookPages, SUB_PATH, subPathBuild, waitForPicture } from './support.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const ROOT_DIST = resolve(ROOT, process.env['E2E_DIST'] ?? 'dist');

const TYPES: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript',
  '.mjs': 'text/javascript',
  '.css': 'text/css',
  '.json': 'application/json',
  '.webmanifest': 'application/manifest+json',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.woff2': 'font/woff2',
  '.woff': 'font/woff',
  '.ttf': 'font/ttf',
  '.wasm': 'application/wasm',
};

interface Site {
  server: Server;
  /** e.g. http://127.0.0.1:41234/courses/cmsc740/book/ */
  base: string;
  dist: string;
}

/** Serves `dist` under `prefix` only: any path outside it is a 404, as on a shared host. */
async function serve(dist: string, prefix: string): Promise<Site> {
  const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url ?? '/', 'http://x').pathname);
    let file = '';
    if (path.startsWith(prefix)) {
      const inside = path.slice(prefix.length);
      file = resolve(dist, inside === '' || inside.endsWith('/') ? `${inside}index.html` : inside);
    }
    if (!file || !file.startsWith(dist + sep) || !existsSync(file) || !statSync(file).isFile()) {
      response.writeHead(404, { 'content-type': 'text/plain' }).end(`not found: ${path}`);
      return;
    }
    response.writeHead(200, {
      'content-type': TYPES[extname(file)] ?? 'application/octet-stream',
      'cache-control': 'no-cache',
    });
    response.end(readFileSync(file));
  });
  await new Promise<void>((done) => server.listen(0, '127.0.0.1', done));
  const { port } = server.address() as AddressInfo;
  return { server, base: `http://127.0.0.1:${port}${prefix}`, dist };
}

function filesUnder(dir: string, extension: string): string[] {
  const out: string[] = [];
  for (const entry of readdirSync(dir, { withFileTypes: true })) {
    const path = join(dir, entry.name);
    if (entry.isDirectory()) out.push(...filesUnder(path, extension));
    else if (entry.name.endsWith(extension)) out.push(path);
  }
  return out.sort();
}

const REFERENCE_TAG =
  /<(a|area|link|script|img|source|iframe|video|audio|track|embed|image|use)\b[^>]*>/gi;
const REFERENCE_ATTRIBUTE = /\s(href|src|srcset|poster|xlink:href)\s*=\s*(?:"([^"]*)"|'([^']*)')/gi;

/** Every URL an HTML file references through an element attribute. */
function htmlReferences(html: string): string[] {
  const urls: string[] = [];
  // Listings in <pre>/<code> are text, not markup; KaTeX and Markdown escape them anyway.
  for (const tag of html.matchAll(REFERENCE_TAG)) {
    for (const attribute of tag[0].matchAll(REFERENCE_ATTRIBUTE)) {
      const value = (attribute[2] ?? attribute[3] ?? '').replace(/&amp;/g, '&').trim();
      if (attribute[1]?.toLowerCase() === 'srcset') {
        for (const candidate of value.split(',')) urls.push(candidate.trim().split(/\s+/)[0] ?? '');
      } else urls.push(value);
    }
  }
  return urls.filter((url) => url !== '');
}

/** Every url() of a stylesheet that is a file (not data:, not a fragment). */
function cssReferences(css: string): string[] {
  return [...css.matchAll(/url\(\s*(?:"([^"]*)"|'([^']*)'|([^)'"\s]*))\s*\)/g)]
    .map((m) => m[1] ?? m[2] ?? m[3] ?? '')
    .filter((url) => url !== '' && !url.startsWith('data:') && !url.startsWith('#'));
}

const EXTERNAL = /^(?:[a-z][a-z0-9+.-]*:|\/\/)/i;

/**
 * Checks every internal reference of a served build. Returns the problems as
 * readable lines ("page → url: why") and the number of distinct URLs checked.
 */
async function checkLinks(site: Site): Promise<{ problems: string[]; checked: number }> {
  const problems: string[] = [];
  const status = new Map<string, Promise<number>>();
  const ids = new Map<string, Set<string>>();
  const fetchStatus = (url: string): Promise<number> => {
    let known = status.get(url);
    if (!known) {
      known = fetch(url).then(async (response) => {
        if (response.ok && url.endsWith('.html')) {
          const body = await response.text();
          ids.set(url, new Set([...body.matchAll(/\s(?:id|name)="([^"]*)"/g)].map((m) => m[1]!)));
        } else await response.arrayBuffer();
        return response.status;
      });
      status.set(url, known);
    }
    return known;
  };
  const check = async (from: string, reference: string): Promise<void> => {
    // Other sites are not checked (no network here); a same-page `#id` is, below.
    if (EXTERNAL.test(reference) && !reference.startsWith(new URL(site.base).origin)) return;
    const url = new URL(reference, from);
    if (!url.pathname.startsWith(new URL(site.base).pathname)) {
      problems.push(`${from} → ${reference}: escapes the base path (${url.pathname})`);
      return;
    }
    const target = `${url.origin}${url.pathname}`;
    const code = await fetchStatus(target);
    if (code !== 200) {
      problems.push(`${from} → ${reference}: HTTP ${code}`);
      return;
    }
    const fragment = decodeURIComponent(url.hash.slice(1));
    if (fragment && target.endsWith('.html') && !fragment.includes('=')) {
      // `#slide=2`, `#beer-law-1.sigma-a=…` are widget state, not element ids.
      if (!ids.get(target)?.has(fragment))
        problems.push(`${from} → ${reference}: no element with id "${fragment}"`);
    }
  };
  const pending: Promise<void>[] = [];
  for (const file of filesUnder(site.dist, '.html')) {
    const page = new URL(relative(site.dist, file).split(sep).join('/'), site.base).href;
    for (const reference of htmlReferences(readFileSync(file, 'utf8')))
      pending.push(check(page, reference));
  }
  for (const file of filesUnder(site.dist, '.css')) {
    const sheet = new URL(relative(site.dist, file).split(sep).join('/'), site.base).href;
    for (const reference of cssReferences(readFileSync(file, 'utf8')))
      pending.push(check(sheet, reference));
  }
  await Promise.all(pending);
  return { problems: [...new Set(problems)].sort(), checked: status.size };
}

let subDist = '';
let madeSubDist = false;

test.describe.configure({ mode: 'serial' });

test.beforeAll(() => {
  test.setTimeout(240_000);
  const made = subPathBuild();
  subDist = made.dist;
  madeSubDist = made.made;
});

test.afterAll(() => {
  if (madeSubDist) rmSync(subDist, { recursive: true, force: true });
});

for (const [label, prefix] of [
  ['the root', '/'],
  ['a deep sub-path', SUB_PATH],
] as const) {
  test(`link checker: every internal href, src and font of the build for ${label} is served under its path`, async () => {
    const dist = prefix === '/' ? ROOT_DIST : subDist;
    expect(existsSync(join(dist, 'index.html')), `${dist} holds a build`).toBe(true);
    const site = await serve(dist, prefix);
    try {
      const { problems, checked } = await checkLinks(site);
      expect(problems).toEqual([]);
      // Pages, scripts, stylesheets, fonts: a build that references next to nothing
      // would pass vacuously.
      expect(checked).toBeGreaterThan(40);
    } finally {
      site.server.close();
    }
  });
}

test('the link checker catches a link that escapes the base path and a missing file', async () => {
  const site = await serve(subDist, SUB_PATH);
  try {
    const from = new URL('chapters/02-extinction-and-transmittance.html', site.base).href;
    expect((await fetch(new URL('/index.html', site.base))).status).toBe(404);
    expect(htmlReferences('<a href="/index.html">x</a><img srcset="a.png 1x, b.png 2x">')).toEqual([
      '/index.html',
      'a.png',
      'b.png',
    ]);
    expect((await fetch(new URL('../index.html', from))).status).toBe(200);
  } finally {
    site.server.close();
  }
});

/**
 * The figures that fetch files of the site at run time: those whose code calls siteUrl
 * (src/widgets/base/siteUrl.ts: data sets, scenes) and every figure that draws with a
 * kernel from the build's static WGSL files (src/gpu/staticKernels.ts, fetched through
 * siteUrl). They fetch when they first draw, so the browser pass scrolls them into
 * view; an exercise fetches nothing until its checks run.
 */
const FETCHING_WIDGETS = readdirSync(join(ROOT, 'src/widgets'), { withFileTypes: true })
  .filter((entry) => {
    const folder = join(ROOT, 'src/widgets', entry.name);
    if (!entry.isDirectory() || !existsSync(join(folder, 'widget.ts'))) return false;
    return readdirSync(folder)
      .filter((name) => name.endsWith('.ts'))
      .some((name) =>
        /siteUrl\(|staticKernels|prelinked/.test(readFileSync(join(folder, name), 'utf8')),
      );
  })
  .map((entry) => `sb-${entry.name}`);

/**
 * Opens a page and waits until everything it loads by itself has arrived: every
 * figure's module (each sb-* element is defined), the fonts, and the data files of
 * the figures that fetch some (each has drawn its first frame).
 */
async function visit(page: Page, url: string, figures = true): Promise<void> {
  await page.goto(url, { waitUntil: figures ? 'load' : 'networkidle' });
  await page.waitForFunction(
    () =>
      [...document.querySelectorAll('*')]
        .filter((element) => element.localName.startsWith('sb-'))
        .every((element) => customElements.get(element.localName) !== undefined),
    null,
    { timeout: 30_000 },
  );
  await page.evaluate(() => document.fonts.ready.then(() => undefined));
  if (!figures || FETCHING_WIDGETS.length === 0) return;
  // A figure fetches before it draws: its first data response, or its first picture
  // where its state needs no file (the single-scatter fog, figures whose only fetch is
  // their kernel's WGSL), is enough; waiting for full refinement would not fetch more.
  for (const widget of await page.locator(`:is(${FETCHING_WIDGETS.join(', ')}):visible`).all()) {
    const fetched = page.waitForResponse((response) => /\.(?:bin|f32)$/.test(response.url()), {
      timeout: 60_000,
    });
    await Promise.race([fetched, waitForPicture(widget)]);
    fetched.catch(() => undefined);
  }
}

/**
 * The pages of the sub-path build that tests/e2e/offline.spec.ts opens, draws and checks
 * for failed requests and console errors, offline from that same build: the home page,
 * every chapter, the appendix and the deck.
 */
const OPENED_OFFLINE = new Set([
  'index.html',
  'deck.html',
  ...bookPages().map((page) => page.path.replace(/^\//, '')),
]);

test('browser pass: the pages of the sub-path build that offline.spec.ts does not open load with no failed request and no console error', async ({
  page,
}) => {
  // About 20 pages, the embed pages without drawing, and two figures' first pictures on
  // SwiftShader: about a minute on a loaded two-core machine, so the allowance leaves room.
  test.setTimeout(240_000);
  const site = await serve(subDist, SUB_PATH);
  const problems: string[] = [];
  let current = '';
  let recording = false;
  const record = (line: string): void => {
    if (recording) problems.push(`${current}: ${line}`);
  };
  page.on('response', (response) => {
    if (response.status() >= 400) record(`HTTP ${response.status()} ${response.url()}`);
  });
  page.on('requestfailed', (request) =>
    record(`request failed ${request.url()} (${request.failure()?.errorText ?? ''})`),
  );
  page.on('console', (message) => {
    if (message.type() === 'error') record(`console: ${message.text()}`);
  });
  page.on('pageerror', (error) => record(`pageerror: ${error.message}`));
  // Served by the network or by the service worker's precache, once it controls the page.
  const dataFiles = new Set<string>();
  page.on('response', (response) => {
    const path = new URL(response.url()).pathname;
    if (response.ok() && /\.(?:bin|f32)$/.test(path)) dataFiles.add(path);
  });
  try {
    const built = filesUnder(subDist, '.html').map((file) =>
      relative(subDist, file).split(sep).join('/'),
    );
    expect(built.length).toBeGreaterThan(12);
    // Every page offline.spec.ts relies on is in the build (else neither spec opens it).
    expect([...OPENED_OFFLINE].filter((path) => !built.includes(path))).toEqual([]);
    const pages = built.filter((path) => !OPENED_OFFLINE.has(path));
    expect(pages).toContain('embed/photon-map.html');
    // Figures whose data files are fetched, drawn here too (offline.spec.ts draws them
    // offline, where a fetch is answered by the precache): the smoke volume, fetched only
    // in that state, and the photon map's reference, on its embed page (its chapter's
    // path tracer would add nothing here).
    const states = ['chapters/09-single-scattering.html#single-scatter-1.medium=smoke'];
    const drawn = new Set(['embed/photon-map.html', ...states]);
    for (const path of [...pages, ...states]) {
      current = path;
      recording = true;
      const started = Date.now();
      // An embed page holds one figure of a chapter, with the same module one folder
      // deep (embed/ as chapters/), so it fetches what that figure fetches from its
      // chapter, which is checked there: its own page, modules and fonts are loaded here
      // (until the network is idle), without waiting for a picture on SwiftShader.
      await visit(
        page,
        new URL(path, site.base).href,
        drawn.has(path) || !path.startsWith('embed/'),
      );
      if (process.env['E2E_PUBLISH_TIMES']) console.warn(`${path}: ${Date.now() - started} ms`);
      recording = false;
      // Pending work of the page may be cancelled by leaving it: that is not a failure.
      await page.goto('about:blank');
    }
    expect(problems).toEqual([]);
    // The data files behind the figures were fetched, and under the base path.
    expect(FETCHING_WIDGETS).toEqual(
      expect.arrayContaining(['sb-photon-map', 'sb-single-scatter']),
    );
    for (const file of ['volumes/smoke-24.f32', 'photon-map/reference.bin'])
      expect([...dataFiles], file).toContain(`${SUB_PATH}${file}`);
  } finally {
    site.server.close();
  }
});
