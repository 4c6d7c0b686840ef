// Frame time of every widget at its default settings, in Debian's Chromium with
// WebGPU on this machine's adapter (SwiftShader where there is no GPU): each widget
// records the cost of its main work as data-frame-ms (GPU timestamp query where the
// adapter has one, wall time otherwise, in data-frame-timer); the whole frame —
// dispatch, readback, drawing and readouts — is timed around `redraw()`. Medians of
// `repeats` frames after one warm-up frame; widgets are found through the catalog and
// the chapter that embeds each.
import { readdirSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { createServer } from 'vite';
import { CHROMIUM_PATH, WEBGPU_ARGS } from '../scripts/chromium.mjs';
import { WIDGET_CATALOG } from '../src/widgets/catalog.ts';
import { median, type BenchTable } from './table.ts';

const ROOT = fileURLToPath(new URL('..', import.meta.url));

/** The first chapter page that embeds each widget, from the chapter sources. */
function pagesByWidget(): Map<string, string> {
  const pages = new Map<string, string>();
  const chapters = readdirSync(`${ROOT}/chapters`)
    .filter((name) => name.endsWith('.md'))
    .sort();
  for (const file of chapters) {
    const text = readFileSync(`${ROOT}/chapters/${file}`, 'utf8');
    for (const name of Object.keys(WIDGET_CATALOG)) {
      // An exercise draws no frame: its cost is grading, timed in bench/grading.ts.
      if (name === 'exercise') continue;
      if (!pages.has(name) && text.includes(`<sb-${name}`))
        pages.set(name, `/chapters/${file.replace(/\.md$/, '.html')}`);
    }
  }
  return pages;
}

interface FrameSample {
  work: number;
  timer: string;
  frame: number;
}

export async function benchWidgets(options: {
  repeats: number;
  /** Only these widgets (names without sb-), e.g. from --only-widgets=a,b. */
  only?: readonly string[];
}): Promise<BenchTable> {
  const server = await createServer({
    root: ROOT,
    configFile: `${ROOT}/vite.config.ts`,
    server: { port: 0, strictPort: false },
    logLevel: 'error',
  });
  await server.listen();
  const address = server.httpServer?.address();
  const port = typeof address === 'object' && address ? address.port : 5173;
  const browser = await chromium.launch({ executablePath: CHROMIUM_PATH, args: WEBGPU_ARGS });
  const rows: BenchTable['rows'] = [];
  let adapter = 'unknown';
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
    const errors: string[] = [];
    page.on('pageerror', (error) => errors.push(error.message));
    page.on('console', (message) => {
      if (message.type() === 'error') errors.push(message.text());
    });
    for (const [name, path] of pagesByWidget()) {
      if (options.only && !options.only.includes(name)) continue;
      errors.length = 0;
      try {
        rows.push(await measure(name, path));
      } catch (error) {
        const why = error instanceof Error ? error.message.split('\n')[0] : String(error);
        console.error(
          `bench: ${name} on ${path} failed: ${why}; page errors: ${errors.join(' | ')}`,
        );
        rows.push({ widget: name, page: path, 'timed by': `failed: ${why}` });
      }
    }
    async function measure(name: string, path: string): Promise<BenchTable['rows'][number]> {
      // A chapter edited during the run makes the dev server regenerate its page and
      // abort the navigation: try once more.
      await page
        .goto(`http://localhost:${port}${path}`)
        .catch(() => page.goto(`http://localhost:${port}${path}`));
      const widget = page.locator(`sb-${name}`).first();
      await widget.scrollIntoViewIfNeeded();
      await page.waitForFunction(
        (el) => el !== null && Number((el as HTMLElement).dataset['rendered'] ?? 0) > 0,
        await widget.elementHandle(),
        { timeout: 60_000 },
      );
      adapter = await page.evaluate(async () => {
        const gpu = (navigator as Navigator & { gpu?: GPU }).gpu;
        const found = await gpu?.requestAdapter();
        return found
          ? `${found.info.vendor} ${found.info.architecture} ${found.info.description}`.trim()
          : 'none';
      });
      const samples: FrameSample[] = [];
      for (let i = 0; i <= options.repeats; i++) {
        const sample = await widget.evaluate(async (el) => {
          const element = el as HTMLElement & { redraw(): Promise<void> };
          const start = performance.now();
          await element.redraw();
          return {
            frame: performance.now() - start,
            work: Number(element.dataset['frameMs'] ?? NaN),
            timer: element.dataset['frameTimer'] ?? '',
          };
        });
        if (i > 0) samples.push(sample); // the first frame warms caches and pipelines
      }
      return {
        widget: name,
        page: path,
        'main work ms (median)': samples.some((s) => Number.isNaN(s.work))
          ? null
          : median(samples.map((s) => s.work)),
        'timed by': samples[0]?.timer || 'not reported',
        'whole frame ms (median)': median(samples.map((s) => s.frame)),
        frames: samples.length,
      };
    }
  } finally {
    await browser.close();
    await server.close();
  }
  return {
    title: 'Widget frame time at default settings (Chromium, WebGPU)',
    notes: [
      `Adapter: ${adapter}.`,
      'main work: what the widget reports next to its error (GPU timestamp query, else wall time).',
      'whole frame: around redraw(), including readback, CPU reference where recomputed, drawing and readouts.',
      `Medians of ${options.repeats} frames after one warm-up frame.`,
    ],
    rows,
  };
}
