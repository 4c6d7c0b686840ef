// The book in Firefox (Debian's firefox-esr, WebGPU by prefs, on Mesa's lavapipe):
// wgpu and its naga shader compiler instead of Chromium's Dawn and Tint. Served from
// the production build (dist/) by `vite preview` on a port of its own, driven by
// puppeteer-core over WebDriver BiDi (scripts/firefox.mjs), one browser for all tests
// and one tab at a time, each page opened in sequence.
//
//   every page (home, each chapter, the appendix pages, each embed, the deck) loads with no console error;
//   every widget draws on WebGPU: no fallback notice, a non-blank canvas;
//   a deep link restores a widget in presentation mode, and F / Esc toggle it;
//   the Beer's-law exercise runs its public checks in the page;
//   Firefox's limits: without timestamp queries the widgets still draw on WebGPU and
//   label their times as wall time; a fallback adapter is named as one.
//
// Run by scripts/test.mjs (`npm test`) with node:test, counted by ./reporter.mjs:
//   node --import tsx --test --test-reporter=spec --test-reporter-destination=stdout \
//     --test-reporter=./tests/firefox/reporter.mjs \
//     --test-reporter-destination=test-results/firefox.json tests/firefox/book.firefox.ts
// The file name keeps it out of Vitest's and Playwright's globs.
import assert from 'node:assert/strict';
import { spawn, type ChildProcess } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { after, before, describe, it, type TestContext } from 'node:test';
import { PNG } from 'pngjs';
import puppeteer, { type Browser, type ElementHandle, type Page } from 'puppeteer-core';
import { firefoxLaunchOptions } from '../../scripts/firefox.mjs';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const PORT = Number(process.env['FIREFOX_E2E_PORT'] ?? 4183);
const DIST = resolve(ROOT, process.env['E2E_DIST'] ?? 'dist');
const RESULTS = resolve(ROOT, process.env['E2E_RESULTS'] ?? 'test-results', 'firefox');
const BASE = `http://localhost:${PORT}`;
const VIEWPORT = { width: 1280, height: 900 };
/** lavapipe rasterizes on the CPU: the heavier widgets take seconds per frame. */
const RENDER_TIMEOUT = 150_000;

interface WidgetSpec {
  /** Custom element name, e.g. `sb-beer-law`. */
  tag: string;
  /** Position among the page's widgets of that tag. */
  nth: number;
  /** The element's id attribute, when the page gives one. */
  id: string | null;
}

interface PageSpec {
  file: string;
  widgets: WidgetSpec[];
}

/** Every page of the build with its widgets, read from the HTML that is served. */
function builtPages(): PageSpec[] {
  const chapters = readdirSync(join(DIST, 'chapters'))
    .filter((name) => name.endsWith('.html'))
    .sort()
    .map((name) => `chapters/${name}`);
  const folder = (name: string): string[] =>
    existsSync(join(DIST, name))
      ? readdirSync(join(DIST, name))
          .filter((file) => file.endsWith('.html'))
          .sort()
          .map((file) => `${name}/${file}`)
      : [];
  // The embeddable figures (embed/<widget>.html) are pages too.
  return ['index.html', ...chapters, ...folder('appendix'), ...folder('embed')].map((file) => {
    // A <template> holds inert copies (an embed's other instances), not live widgets.
    const html = readFileSync(join(DIST, file), 'utf8').replace(
      /<template[\s\S]*?<\/template>/g,
      '',
    );
    const seen = new Map<string, number>();
    const widgets = [...html.matchAll(/<(sb-[a-z-]+)\b([^>]*)>/g)].map((match) => {
      const tag = match[1] ?? '';
      const nth = seen.get(tag) ?? 0;
      seen.set(tag, nth + 1);
      return { tag, nth, id: /\bid="([^"]+)"/.exec(match[2] ?? '')?.[1] ?? null };
    });
    return { file, widgets };
  });
}

/** The deck's widget slides: each widget's id and its slide number (equation slides lie between). */
function deckSlides(): { id: string; slide: number }[] {
  const html = readFileSync(join(DIST, 'deck.html'), 'utf8');
  return [...html.matchAll(/<sb-[a-z-]+ id="(slide-(\d+)-widget)"/g)].map((m) => ({
    id: m[1] ?? '',
    slide: Number(m[2]),
  }));
}

let server: ChildProcess | null = null;
let browser: Browser | null = null;

async function waitForServer(): Promise<void> {
  const deadline = Date.now() + 30_000;
  for (;;) {
    try {
      const response = await fetch(`${BASE}/index.html`);
      if (response.ok) return;
    } catch {
      // not listening yet
    }
    if (server?.exitCode !== null) throw new Error(`vite preview exited (${server?.exitCode})`);
    if (Date.now() > deadline) throw new Error(`vite preview did not answer on ${BASE}`);
    await new Promise((resolve) => setTimeout(resolve, 200));
  }
}

before(async () => {
  mkdirSync(RESULTS, { recursive: true });
  server = spawn(
    process.execPath,
    [
      join(ROOT, 'node_modules/vite/bin/vite.js'),
      'preview',
      '--port',
      String(PORT),
      '--strictPort',
      '--outDir',
      DIST,
    ],
    { cwd: ROOT, stdio: ['ignore', 'ignore', 'inherit'] },
  );
  await waitForServer();
  browser = await puppeteer.launch(firefoxLaunchOptions());
});

after(async () => {
  await browser?.close();
  server?.kill();
});

interface OpenPage {
  page: Page;
  /** Console errors and uncaught exceptions since the page was opened. */
  errors: string[];
}

/** A fresh tab on `path`, with its errors collected from before the first script runs. */
async function open(path: string, prepare?: (page: Page) => Promise<void>): Promise<OpenPage> {
  if (!browser) throw new Error('Firefox did not start');
  const page = await browser.newPage();
  await page.setViewport(VIEWPORT);
  const errors: string[] = [];
  page.on('console', (message) => {
    if (message.type() === 'error') errors.push(`console: ${message.text()}`);
  });
  page.on('pageerror', (error) => errors.push(`pageerror: ${(error as Error).message}`));
  if (prepare) await prepare(page);
  await page.goto(`${BASE}${path}`, { waitUntil: 'load' });
  return { page, errors };
}

async function widgetHandle(page: Page, widget: WidgetSpec): Promise<ElementHandle<Element>> {
  const handles = await page.$$(widget.tag);
  const handle = handles[widget.nth];
  assert.ok(handle, `${widget.tag} #${widget.nth + 1} is on the page`);
  return handle;
}

/** Scrolls a widget into view and waits until it has drawn at least `count` times. */
async function waitForRender(page: Page, handle: ElementHandle<Element>, count = 1): Promise<void> {
  await handle.scrollIntoView();
  await page.waitForFunction(
    (element: Element, n: number) =>
      Number((element as HTMLElement).dataset['rendered'] ?? '0') >= n,
    { timeout: RENDER_TIMEOUT, polling: 100 },
    handle,
    count,
  );
}

interface BackendReport {
  warnings: string[];
  errors: string[];
  cost: string;
  timer: string;
}

async function backendReport(handle: ElementHandle<Element>): Promise<BackendReport> {
  return handle.evaluate((element) => ({
    warnings: [...element.querySelectorAll('.sb-notice--warning')].map((n) => n.textContent ?? ''),
    errors: [...element.querySelectorAll('.sb-notice--error')].map((n) => n.textContent ?? ''),
    cost: element.querySelector('.sb-cost')?.textContent ?? '',
    timer: (element as HTMLElement).dataset['frameTimer'] ?? '',
  }));
}

/** Why a widget is not drawing on WebGPU, or null when it is. */
function fallbackReason(report: BackendReport): string | null {
  const notice = report.warnings.find((text) => text.includes('WebGPU is not available'));
  if (notice) return notice;
  if (report.errors.length) return report.errors.join(' / ');
  if (/CPU fallback/.test(report.cost)) return report.cost;
  return null;
}

/** Standard deviation of the luminance of an element's screenshot (0–255). */
async function luminanceDeviation(handle: ElementHandle<Element>, file: string): Promise<number> {
  const png = Buffer.from(await handle.screenshot({ type: 'png' }));
  writeFileSync(join(RESULTS, file), png);
  const image = PNG.sync.read(png);
  const pixels = image.width * image.height;
  let sum = 0;
  let sumSquares = 0;
  for (let i = 0; i < pixels; i++) {
    const luminance =
      0.2126 * (image.data[4 * i] ?? 0) +
      0.7152 * (image.data[4 * i + 1] ?? 0) +
      0.0722 * (image.data[4 * i + 2] ?? 0);
    sum += luminance;
    sumSquares += luminance * luminance;
  }
  const mean = sum / pixels;
  return Math.sqrt(Math.max(sumSquares / pixels - mean * mean, 0));
}

/**
 * Asserts that a widget drew on WebGPU with a picture on its canvas, and notes the
 * result (the per-widget table of the report).
 */
async function expectDrawsOnWebGpu(
  t: TestContext,
  page: Page,
  handle: ElementHandle<Element>,
  label: string,
  screenshot: string,
): Promise<void> {
  await waitForRender(page, handle);
  const report = await backendReport(handle);
  const reason = fallbackReason(report);
  t.diagnostic(reason ? `${label}: fallback — ${reason}` : `${label}: WebGPU — ${report.cost}`);
  assert.equal(reason, null, `${label} draws on WebGPU`);
  const tag = await handle.evaluate((element) => element.localName);
  if (tag === 'sb-exercise') {
    // An editor, not a figure: on WebGPU its checks run on the page's GPU.
    assert.match(report.cost, /page’s GPU/);
    return;
  }
  const canvas = await handle.$('canvas.sb-canvas');
  assert.ok(canvas, `${label} has a canvas`);
  const deviation = await luminanceDeviation(canvas, screenshot);
  assert.ok(deviation > 10, `${label}'s canvas shows a picture (luminance σ = ${deviation})`);
}

/** A number as the widgets print it: plain, or mantissa×10 with a superscript exponent. */
function parseDisplayed(text: string): number {
  const superscripts = '⁰¹²³⁴⁵⁶⁷⁸⁹';
  const match = /(-?[\d.]+)(?:×10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+))?/.exec(text);
  if (!match) return NaN;
  const exponent = [...(match[2] ?? '⁰')]
    .map((c) => (c === '⁻' ? '-' : String(superscripts.indexOf(c))))
    .join('');
  return Number(match[1]) * 10 ** Number(exponent);
}

const pages = builtPages();

for (const spec of pages) {
  describe(spec.file, () => {
    let current: OpenPage | null = null;
    after(async () => {
      await current?.page.close();
    });

    it('loads, with its MathML laid out once parsed', async () => {
      current = await open(`/${spec.file}`);
      // An embed is the figure alone; every other page has a heading.
      const heading = await current.page.$(spec.file.startsWith('embed/') ? 'main' : 'main h1');
      assert.ok(heading, 'the page has its main content');
      const raw = readFileSync(join(DIST, spec.file), 'utf8');
      if (raw.includes('class="katex')) {
        // The MathML is hidden only while the page is parsed (src/book/build/pages.ts).
        await current.page.waitForFunction(
          () => !document.documentElement.classList.contains('sb-parsing'),
          { timeout: 10_000 },
        );
        const display = await current.page.$eval(
          '.katex-mathml math',
          (math) => getComputedStyle(math).display,
        );
        assert.notEqual(display, 'none', 'the MathML is laid out once the page is parsed');
      }
    });

    for (const widget of spec.widgets) {
      const label = `${widget.tag} #${widget.nth + 1}`;
      it(`${label} draws on WebGPU`, { timeout: RENDER_TIMEOUT + 30_000 }, async (t) => {
        assert.ok(current, 'the page loaded');
        const handle = await widgetHandle(current.page, widget);
        const name = `${spec.file.replace(/[/.]/g, '_')}-${widget.tag}-${widget.nth + 1}.png`;
        await expectDrawsOnWebGpu(t, current.page, handle, label, name);
      });
    }

    it('logs no console errors (MathML included)', async () => {
      assert.ok(current, 'the page loaded');
      // Layout, MathML included, is final once the fonts have loaded.
      await current.page.evaluate(() => document.fonts.ready.then(() => undefined));
      assert.deepEqual(current.errors, []);
    });
  });
}

describe('deck.html', () => {
  const slides = deckSlides();
  let current: OpenPage | null = null;
  after(async () => {
    await current?.page.close();
  });

  it('loads on its first slide', async () => {
    assert.ok(slides.length >= 2, 'the deck has slides');
    current = await open('/deck.html');
    const shown = await current.page.$eval('.deck-jump', (el) => (el as HTMLInputElement).value);
    assert.equal(shown, '1');
  });

  for (const { id, slide } of slides) {
    it(
      `slide ${slide}: → reaches it, and its widget draws on WebGPU`,
      {
        timeout: RENDER_TIMEOUT + 30_000,
      },
      async (t) => {
        assert.ok(current, 'the deck loaded');
        const { page } = current;
        // Each test moves on from the slide before (past the equation slides between
        // widget slides), so one failure does not stall the rest.
        for (let presses = 0; presses < 10; presses++) {
          const shown = await page.$eval('.deck-jump', (el) =>
            Number((el as HTMLInputElement).value),
          );
          if (shown >= slide) break;
          await page.keyboard.press('ArrowRight');
        }
        await page.waitForFunction(
          (n: number) =>
            document.querySelector<HTMLInputElement>('.deck-jump')?.value === String(n),
          { timeout: 10_000 },
          slide,
        );
        assert.ok(page.url().includes(`slide=${slide}`), 'each slide is a deep link');
        const handle = await page.$(`#${id}`);
        assert.ok(handle, `slide ${slide} holds #${id}`);
        await expectDrawsOnWebGpu(t, page, handle, `#${id}`, `deck-slide-${slide}.png`);
      },
    );
  }

  it('logs no console errors', () => {
    assert.ok(current, 'the deck loaded');
    assert.deepEqual(current.errors, []);
  });
});

const CHAPTER_2 = '/chapters/02-extinction-and-transmittance.html';

describe('a widget in presentation mode from a deep link', () => {
  it('opens presenting with the linked state, matches the float64 twin; Esc and F toggle', async () => {
    const { page, errors } = await open(
      `${CHAPTER_2}#beer-law-1.sigma-a=1.5&beer-law-1.thickness=3&beer-law-1.profile=layered&beer-law-1.present=1&v=1`,
    );
    try {
      const handle = await widgetHandle(page, { tag: 'sb-beer-law', nth: 0, id: null });
      await waitForRender(page, handle);
      // No named functions inside page callbacks: tsx would wrap them in a helper
      // (__name) that exists only in Node.
      const state = await handle.evaluate((element) => {
        const shell = element.querySelector('.sb-widget');
        const box = shell?.getBoundingClientRect();
        return {
          presenting: shell?.classList.contains('is-presenting') ?? false,
          box: box && { x: box.x, y: box.y, width: box.width, height: box.height },
          // Presentation asks for fullscreen: where the browser grants it the window is
          // the screen (1366×768 on CI), otherwise the 1280×900 viewport.
          window: { x: 0, y: 0, width: window.innerWidth, height: window.innerHeight },
          controls: ['sigma-a', 'thickness', 'profile'].map(
            (name) => (element.querySelector(`[name="${name}"]`) as HTMLInputElement | null)?.value,
          ),
          exit: element.querySelector('[data-readout="exit"]')?.textContent ?? '',
          reference: element.querySelector('[data-readout="reference"]')?.textContent ?? '',
        };
      });
      assert.equal(state.presenting, true, 'present=1 in the link opens presentation mode');
      assert.deepEqual(state.box, state.window, 'the widget fills the window');
      assert.deepEqual(state.controls, ['1.5', '3', 'layered'], 'the linked state is restored');
      const exit = parseDisplayed(state.exit);
      const reference = parseDisplayed(state.reference);
      assert.ok(Number.isFinite(exit) && Number.isFinite(reference), `${state.exit}`);
      assert.ok(Math.abs(exit - reference) <= 1e-5 * Math.abs(reference) + 1e-12, 'GPU = twin');
      assert.equal(fallbackReason(await backendReport(handle)), null, 'drawn on WebGPU');

      await page.keyboard.press('Escape');
      await page.waitForFunction(
        () =>
          !document.querySelector('sb-beer-law .sb-widget')?.classList.contains('is-presenting'),
        { timeout: 10_000 },
      );
      // The link is written at most every STATE_WRITE_INTERVAL_MS (throttledWriter.ts): a
      // change right after another reaches the URL at the end of the interval.
      const linkSays = (present: boolean) =>
        page
          .waitForFunction(
            (want: boolean) => location.href.includes('present=1') === want,
            { timeout: 5_000 },
            present,
          )
          .then(
            () => true,
            () => false,
          );
      assert.ok(await linkSays(false), 'leaving drops present=1 from the link');
      await handle.$eval('input[type="range"]', (input) => (input as HTMLElement).focus());
      await page.keyboard.press('f');
      await page.waitForFunction(
        () => document.querySelector('sb-beer-law .sb-widget')?.classList.contains('is-presenting'),
        { timeout: 10_000 },
      );
      assert.ok(await linkSays(true), 'F enters presentation mode again, and the link says so');
      assert.deepEqual(errors, []);
    } finally {
      await page.close();
    }
  });
});

const SOLUTION = `fn transmittance(sigmaT: f32, d: f32) -> f32 {
  // Clamp the optical thickness so T stays in [0, 1].
  return exp(-max(sigmaT * d, 0.0));
}
`;

describe("the Beer's-law exercise", () => {
  it('grades a correct solution on the GPU: public checks pass', { timeout: 120_000 }, async () => {
    const { page, errors } = await open(CHAPTER_2);
    try {
      const handle = await page.$('sb-exercise[exercise="beer-law"]');
      assert.ok(handle, 'chapter 2 holds the exercise');
      await waitForRender(page, handle);
      await page.waitForSelector('sb-exercise[exercise="beer-law"] .cm-content', {
        timeout: 30_000,
      });
      // Replace the editor's text as typing would: select all, then insert. (Firefox
      // hides the data of a synthetic paste event from the page, so no paste here.)
      await handle.$eval(
        '.cm-content',
        (content, code) => {
          (content as HTMLElement).focus();
          document.execCommand('selectAll');
          document.execCommand('insertText', false, code);
        },
        SOLUTION,
      );
      const code = await handle.$eval('.cm-content', (content) => content.textContent ?? '');
      assert.ok(code.includes('exp(-max(sigmaT * d, 0.0))'), `the editor holds: ${code}`);
      await handle.$eval('[data-action="run"]', (button) => (button as HTMLButtonElement).click());
      await page.waitForFunction(
        (element: Element) =>
          ['graded', 'compile-error', 'failed'].includes(element.getAttribute('data-state') ?? ''),
        { timeout: 90_000, polling: 200 },
        handle,
      );
      const result = await handle.evaluate((element) => ({
        state: element.getAttribute('data-state'),
        summary: element.querySelector('.sb-exercise-summary')?.textContent ?? '',
        passes: element.querySelectorAll('.sb-exercise-check[data-verdict="pass"]').length,
        row:
          [...element.querySelectorAll('.sb-exercise-samples tr')]
            .map((row) => row.textContent ?? '')
            .find((text) => text.includes('d = 1 m')) ?? '',
      }));
      assert.equal(result.state, 'graded', result.summary);
      assert.match(
        result.summary,
        /Public checks passed \(2 of 2, 6 of 6 points\) — hidden tests run when graded\./,
      );
      assert.equal(result.passes, 2);
      // The student's value next to the reference: exp(−1) at d = 1 m.
      assert.match(result.row, /0\.3678/);
      assert.deepEqual(errors, []);
    } finally {
      await page.close();
    }
  });
});

describe("Firefox's limits", () => {
  it('the adapter is named, and a fallback adapter as one', async () => {
    const { page, errors } = await open(CHAPTER_2);
    try {
      const fallback = await page.evaluate(async () => {
        const adapter = await navigator.gpu.requestAdapter();
        return adapter?.info.isFallbackAdapter ?? null;
      });
      assert.notEqual(fallback, null, 'Firefox gives an adapter');
      const handle = await widgetHandle(page, { tag: 'sb-beer-law', nth: 0, id: null });
      await waitForRender(page, handle);
      const { cost } = await backendReport(handle);
      assert.match(cost, fallback ? /WebGPU \(software fallback adapter\)/ : /WebGPU \([^)]+\)/);
      assert.doesNotMatch(cost, /WebGPU \(WebGPU\)/);
      assert.deepEqual(errors, []);
    } finally {
      await page.close();
    }
  });

  // Timestamp queries are an optional WebGPU feature: older Firefox builds and many
  // adapters lack them. Hide the feature from the page: every widget on these chapters
  // must still draw on WebGPU and label its time as wall time, not a GPU timestamp.
  const hideTimestamps = async (page: Page): Promise<void> => {
    await page.evaluateOnNewDocument(() => {
      // @webgpu/types declares the interface but not its global constructor.
      const features = (
        window as unknown as { GPUSupportedFeatures: { prototype: GPUSupportedFeatures } }
      ).GPUSupportedFeatures.prototype;
      const has = features.has;
      Object.defineProperty(features, 'has', {
        value(this: GPUSupportedFeatures, name: string): boolean {
          return name === 'timestamp-query' ? false : has.call(this, name);
        },
      });
    });
  };
  for (const file of [
    'chapters/02-extinction-and-transmittance.html',
    'chapters/05-emission-absorption-and-ray-marching.html',
    'chapters/09-single-scattering.html',
  ]) {
    const spec = pages.find((p) => p.file === file);
    it(
      `without timestamp queries, ${file} draws on WebGPU and reports wall time`,
      {
        timeout: 240_000,
      },
      async (t) => {
        assert.ok(spec, `${file} is built`);
        const { page, errors } = await open(`/${file}`, hideTimestamps);
        try {
          const features = await page.evaluate(async () => {
            const adapter = await navigator.gpu.requestAdapter();
            return adapter?.features.has('timestamp-query');
          });
          assert.equal(features, false, 'the page sees no timestamp queries');
          for (const widget of spec.widgets.filter((w) => w.tag !== 'sb-exercise')) {
            const label = `${widget.tag} #${widget.nth + 1} (no timestamps)`;
            const handle = await widgetHandle(page, widget);
            await expectDrawsOnWebGpu(t, page, handle, label, `no-timestamps-${widget.tag}.png`);
            const report = await backendReport(handle);
            const shown = `${report.cost} ${report.timer}`;
            assert.doesNotMatch(shown, /GPU timestamp/, shown);
            assert.match(shown, /wall time/, `${label} says its time is wall time: ${shown}`);
          }
          assert.deepEqual(errors, []);
        } finally {
          await page.close();
        }
      },
    );
  }
});
