// What a reader downloads and waits for, page by page, from the production build
// (`vite build` → dist/, served by `vite preview`) in Debian's Chromium with WebGPU on
// this machine's adapter:
// - the JavaScript and WGSL the page fetches (every script, module and shader
//   response), as gzip -9 bytes of the built files, so the figure does not depend on
//   the preview server's compression;
// - each widget's first-frame time: a fresh page, the widget scrolled into view at
//   once, and the time from navigation start until the widget reports its first
//   rendered frame (`data-rendered` > 0). That covers module loading, the device,
//   shader linking and compilation, and the first frame itself.
// Widgets are found in the built pages' DOM (every `sb-*` element but exercises, which
// draw no frame), so the same bench measures any checkout:
//   npx tsx bench/pages.ts [--dist=DIR] [--repeats=N]   (or npm run bench -- --only=pages)
import { readFileSync, readdirSync, statSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';
import { chromium, type Browser } from 'playwright-core';
import { CHROMIUM_PATH, WEBGPU_ARGS } from '../scripts/chromium.mjs';
import { median, printTable, type BenchTable } from './table.ts';
import { servePreview } from './previewPage.ts';

const ROOT = fileURLToPath(new URL('..', import.meta.url));

/** Every built page worth measuring: the chapters, the appendix, the deck, the home page. */
function builtPages(dist: string): string[] {
  const pages = ['/index.html', '/deck.html'];
  for (const folder of ['chapters', 'appendix']) {
    let names: string[] = [];
    try {
      names = readdirSync(`${dist}/${folder}`);
    } catch {
      continue;
    }
    for (const name of names.sort()) if (name.endsWith('.html')) pages.push(`/${folder}/${name}`);
  }
  return pages;
}

const gzipCache = new Map<string, number>();
/** gzip -9 size of a built file, or 0 when the URL is not a file in dist/. */
function gzipBytes(dist: string, pathname: string): number {
  const file = `${dist}${decodeURIComponent(pathname)}`;
  let size = gzipCache.get(file);
  if (size === undefined) {
    try {
      size = statSync(file).isFile() ? gzipSync(readFileSync(file), { level: 9 }).length : 0;
    } catch {
      size = 0;
    }
    gzipCache.set(file, size);
  }
  return size;
}

interface PageLoad {
  jsBytes: number;
  wgslBytes: number;
  widgets: string[];
}

async function loadPage(browser: Browser, base: string, dist: string, path: string) {
  const context = await browser.newContext({
    viewport: { width: 1280, height: 900 },
    serviceWorkers: 'block',
  });
  const page = await context.newPage();
  const fetched = new Set<string>();
  page.on('response', (response) => fetched.add(new URL(response.url()).pathname));
  await page.goto(`${base}${path}`, { waitUntil: 'networkidle' });
  // Scroll through the page so every widget loads its modules and shaders.
  const widgets = await page.evaluate(() =>
    [...document.querySelectorAll('*')]
      .map((el) => el.localName)
      .filter((name) => name.startsWith('sb-') && name !== 'sb-exercise'),
  );
  // Each widget fetches its modules, data and kernels when it first draws: scroll it into
  // view and wait for its first frame (the deck shows one slide: the others are skipped).
  for (const [index] of widgets.entries()) {
    const handle = await page.evaluateHandle((i) => {
      const all = [...document.querySelectorAll('*')].filter(
        (el) => el.localName.startsWith('sb-') && el.localName !== 'sb-exercise',
      );
      all[i]?.scrollIntoView();
      // A widget the page does not show (the deck's other slides) never draws.
      const shown = all[i]?.checkVisibility() ?? false;
      return shown ? (all[i] ?? null) : null;
    }, index);
    if ((await handle.jsonValue().catch(() => 'element')) === null) continue;
    await page
      .waitForFunction(
        (el) => el !== null && Number((el as HTMLElement).dataset['rendered'] ?? 0) > 0,
        handle,
        { timeout: 120_000 },
      )
      .catch(() => console.error(`bench: widget ${index} on ${path} never drew`));
  }
  await page.waitForLoadState('networkidle');
  await context.close();
  const load: PageLoad = { jsBytes: 0, wgslBytes: 0, widgets };
  for (const pathname of fetched) {
    if (/\.(m?js)$/.test(pathname)) load.jsBytes += gzipBytes(dist, pathname);
    else if (/\.wgsl$/.test(pathname)) load.wgslBytes += gzipBytes(dist, pathname);
  }
  return load;
}

/** Milliseconds from navigation start to the first rendered frame of the `index`-th `tag`. */
async function firstFrame(
  browser: Browser,
  base: string,
  path: string,
  tag: string,
  index: number,
): Promise<number> {
  const context = await browser.newContext({
    viewport: { width: 1280, height: 900 },
    serviceWorkers: 'block',
  });
  try {
    const page = await context.newPage();
    await page.goto(`${base}${path}`, { waitUntil: 'domcontentloaded' });
    const widget = page.locator(tag).nth(index);
    await widget.scrollIntoViewIfNeeded();
    const handle = await widget.elementHandle();
    await page.waitForFunction(
      (el) => el !== null && Number((el as HTMLElement).dataset['rendered'] ?? 0) > 0,
      handle,
      { timeout: 120_000, polling: 5 },
    );
    return await page.evaluate(() => performance.now());
  } finally {
    await context.close();
  }
}

export async function benchPages(options: {
  dist?: string;
  repeats: number;
}): Promise<BenchTable[]> {
  const dist = options.dist ?? `${ROOT}dist`;
  const { server, base } = await servePreview(ROOT, dist);
  const browser = await chromium.launch({ executablePath: CHROMIUM_PATH, args: WEBGPU_ARGS });
  const bytes: BenchTable['rows'] = [];
  const frames: BenchTable['rows'] = [];
  try {
    const firstPage = new Map<string, string>();
    for (const path of builtPages(dist)) {
      const load = await loadPage(browser, base, dist, path);
      bytes.push({
        page: path,
        widgets: load.widgets.length,
        'JS gzip KB': load.jsBytes / 1024,
        'WGSL gzip KB': load.wgslBytes / 1024,
      });
      if (path !== '/deck.html')
        for (const tag of load.widgets) if (!firstPage.has(tag)) firstPage.set(tag, path);
    }
    for (const [tag, path] of firstPage) {
      const samples: number[] = [];
      try {
        for (let i = 0; i < options.repeats; i++)
          samples.push(await firstFrame(browser, base, path, tag, 0));
        frames.push({
          widget: tag.slice('sb-'.length),
          page: path,
          'first frame ms (median)': median(samples),
          'min ms': Math.min(...samples),
          loads: samples.length,
        });
      } catch (error) {
        const why = error instanceof Error ? error.message.split('\n')[0] : String(error);
        frames.push({
          widget: tag.slice('sb-'.length),
          page: path,
          'first frame ms (median)': `failed: ${why ?? ''}`,
        });
      }
    }
  } finally {
    await browser.close();
    await new Promise<void>((resolve) => server.httpServer.close(() => resolve()));
  }
  return [
    {
      title: `JavaScript and WGSL each page fetches (gzip -9 of the built files, ${dist})`,
      notes: [
        'Every script and shader response while the page loads and every widget is scrolled into view.',
        'WGSL linked in the page from WESL sources bundled into JS counts as JS.',
      ],
      rows: bytes,
    },
    {
      title: 'Widget first-frame time (Chromium, WebGPU, fresh page per load)',
      notes: [
        'From navigation start to the first rendered frame, the widget scrolled into view at once.',
        `Medians of ${options.repeats} cold page loads (same browser, new context each).`,
      ],
      rows: frames,
    },
  ];
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const dist = process.argv.find((a) => a.startsWith('--dist='))?.slice('--dist='.length);
  const repeats = Number(
    process.argv.find((a) => a.startsWith('--repeats='))?.slice('--repeats='.length) ?? 3,
  );
  for (const table of await benchPages({ dist, repeats })) printTable(table);
}
