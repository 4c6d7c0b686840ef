// Shared helpers of the end-to-end tests.
import AxeBuilder from '@axe-core/playwright';
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, type Locator, type Page } from '@playwright/test';
import { PNG } from 'pngjs';
import { WIDGET_CATALOG } from '../../src/widgets/catalog.ts';

/** A CSS selector matching every widget element in the catalog. */
export const WIDGET_SELECTOR = Object.keys(WIDGET_CATALOG)
  .map((name) => `sb-${name}`)
  .join(', ');

const CHAPTERS = fileURLToPath(new URL('../../chapters', import.meta.url));

/** The generated appendix documenting the shader library. */
export const APPENDIX_PAGE = {
  slug: 'appendix-shader-library',
  path: '/appendix/shader-library.html',
  hasMath: true,
};

/** Every chapter page, then the appendix: the reading order of the pager links. */
export function bookPages(): { slug: string; path: string; hasMath: boolean }[] {
  return [...chapterPages(), APPENDIX_PAGE];
}

/** Every chapter page, from the Markdown sources (the build makes one page each). */
export function chapterPages(): { slug: string; path: string; hasMath: boolean }[] {
  return readdirSync(CHAPTERS)
    .filter((name) => /^\d{2}-.*\.md$/.test(name))
    .sort()
    .map((name) => {
      const slug = name.replace(/\.md$/, '');
      const source = readFileSync(`${CHAPTERS}/${name}`, 'utf8');
      // Math inside a quiz block is shown only once the quiz is answered (it is
      // encoded in the page: src/book/quizCode.ts), so it does not count.
      const shown = source.replace(/^```quiz\n[\s\S]*?^```$/gm, '');
      return { slug, path: `/chapters/${slug}.html`, hasMath: shown.includes('$') };
    });
}

/** The deep sub-path a course's web space may serve the book under (issue 18). */
export const SUB_PATH = '/courses/cmsc740/book/';

/**
 * The book built for SUB_PATH: E2E_SUB_DIST when set (scripts/test.mjs builds it once for
 * publish.spec.ts and offline.spec.ts), else built now (20–40 s) into a temporary folder
 * that the caller removes (`made`). Call it from a beforeAll with a timeout of minutes.
 * Two workers may ask at once: the build writes the generated pages into the checkout
 * (src/book/build/generate.ts, writeBook), so builds of one checkout take turns, by a
 * lock folder (mkdir is atomic); a lock left by a killed run is taken after 5 minutes.
 */
export function subPathBuild(): { dist: string; made: boolean } {
  const root = fileURLToPath(new URL('../..', import.meta.url));
  const given = process.env['E2E_SUB_DIST'];
  if (given) return { dist: resolve(root, given), made: false };
  const checkout = createHash('sha256').update(root).digest('hex').slice(0, 16);
  const lock = join(tmpdir(), `scatterbook-subpath-build-${checkout}.lock`);
  const wait = new Int32Array(new SharedArrayBuffer(4));
  for (;;) {
    try {
      mkdirSync(lock);
      break;
    } catch {
      let age = 0;
      try {
        age = Date.now() - statSync(lock).mtimeMs;
      } catch {
        continue; // released meanwhile
      }
      if (age > 300_000) rmSync(lock, { recursive: true, force: true });
      else Atomics.wait(wait, 0, 0, 1000);
    }
  }
  try {
    const dist = mkdtempSync(join(tmpdir(), 'scatterbook-subpath-'));
    execFileSync(
      'npx',
      [
        'vite',
        'build',
        '--base',
        SUB_PATH,
        '--outDir',
        dist,
        '--emptyOutDir',
        '--logLevel',
        'warn',
      ],
      { cwd: root, stdio: ['ignore', 'ignore', 'inherit'], timeout: 220_000 },
    );
    return { dist, made: true };
  } finally {
    rmSync(lock, { recursive: true, force: true });
  }
}

/** Collects console errors and uncaught exceptions of a page from now on. */
export function trackErrors(page: Page): string[] {
  const errors: string[] = [];
  page.on('console', (message) => {
    if (message.type() === 'error') errors.push(`console: ${message.text()}`);
  });
  page.on('pageerror', (error) => errors.push(`pageerror: ${error.message}`));
  return errors;
}

/**
 * A function that opens `chapter` with a widget's state in the URL hash
 * (`id.key=value&…`, plus an optional query such as `?backend=cpu`) and waits for the
 * widget's first frame.
 */
export function widgetOpener(
  chapter: string,
  tag: string,
  id: string,
  waitFor: (widget: Locator) => Promise<void> = waitForRender,
): (page: Page, state?: Record<string, string>, query?: string) => Promise<Locator> {
  return async (page, state = {}, query = '') => {
    const hash = Object.entries(state)
      .map(([k, v]) => `${id}.${k}=${v}`)
      .join('&');
    await page.goto(`${chapter}${query}${hash ? `#${hash}` : ''}`);
    const widget = page.locator(tag).first();
    await waitFor(widget);
    return widget;
  };
}

/** The text of a widget's readout `key` (`data-readout`). */
export async function readout(widget: Locator, key: string): Promise<string> {
  return (await widget.locator(`[data-readout="${key}"]`).textContent()) ?? '';
}

/**
 * Scrolls a widget into view and waits until it has drawn at least `count` times and
 * its progressive refinement has settled at full quality (data-settled, set by the base
 * element: src/widgets/base/definedElement.ts), so readouts are the final numbers.
 */
export async function waitForRender(widget: Locator, count = 1): Promise<void> {
  await widget.scrollIntoViewIfNeeded();
  await expect
    .poll(async () => Number((await widget.getAttribute('data-rendered')) ?? '0'), {
      timeout: 30_000,
    })
    .toBeGreaterThanOrEqual(count);
  await waitForSettled(widget);
}

/**
 * Scrolls a widget into view and waits for its first picture only (a preview may still
 * be refining): for checks of the page around it (accessibility, layout) that do not read
 * its final numbers, and should not pay for its full refinement on a software GPU.
 */
export async function waitForPicture(widget: Locator): Promise<void> {
  await widget.scrollIntoViewIfNeeded();
  await expect
    .poll(async () => Number((await widget.getAttribute('data-rendered')) ?? '0'), {
      timeout: 30_000,
      // Every 250 ms at most: the default back-off (to 1 s) adds about half a second to
      // each of the many figures the page sweeps wait for one after the other.
      intervals: [100, 250],
    })
    .toBeGreaterThanOrEqual(1);
}

/** Waits until the widget shows full quality for its current inputs (no preview, no job pending). */
export async function waitForSettled(widget: Locator, timeout = 45_000): Promise<void> {
  await expect
    .poll(async () => await widget.getAttribute('data-settled'), { timeout })
    .not.toBe('false');
}

/** The number of frames the widget has shown (each refinement stage and job step counts). */
export async function framesShown(widget: Locator): Promise<number> {
  return Number((await widget.getAttribute('data-frames')) ?? '0');
}

/**
 * Starts recording the stage (data-stage) of every frame `widget` shows from the next
 * input on `control` on (the event the widget takes its value on), and returns the reader
 * of that list. Recording starts with the input itself, in the page: a widget still refining
 * its old picture in the background may show such a frame between this call and the
 * test's input, and that frame is not the input's first picture.
 */
export async function recordStagesFromNextInput(
  widget: Locator,
  control: Locator,
): Promise<() => Promise<string[]>> {
  const host = await widget.elementHandle();
  await control.evaluate((input, element) => {
    const seen: string[] = [];
    (window as unknown as { sbStages: string[] }).sbStages = seen;
    let armed = false;
    const arm = (): void => {
      armed = true;
    };
    // The event the widget takes the value on (widgetElement.ts): a slider's `input`, a
    // number box's or a select's `change` (typing into a number box is not an input yet).
    const range = input instanceof HTMLInputElement && input.type === 'range';
    input.addEventListener(range ? 'input' : 'change', arm);
    new MutationObserver(() => {
      if (armed && element) seen.push(element.getAttribute('data-stage') ?? '');
    }).observe(element ?? input, { attributeFilter: ['data-frames'] });
  }, host);
  return () =>
    widget.page().evaluate(() => [...(window as unknown as { sbStages: string[] }).sbStages]);
}

export interface CanvasStats {
  /** Standard deviation of luminance over the pixels (0–255). */
  luminanceDeviation: number;
  /** Number of distinct colours after quantizing to 5 bits per channel. */
  distinctColours: number;
  png: Buffer;
}

/** Screenshots an element and measures whether it shows a picture rather than a flat fill. */
export async function canvasStats(canvas: Locator): Promise<CanvasStats> {
  const png = await canvas.screenshot();
  const image = PNG.sync.read(png);
  let sum = 0;
  let sumSquares = 0;
  const colours = new Set<number>();
  const pixels = image.width * image.height;
  for (let i = 0; i < pixels; i++) {
    const r = image.data[4 * i] ?? 0;
    const g = image.data[4 * i + 1] ?? 0;
    const b = image.data[4 * i + 2] ?? 0;
    const luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    sum += luminance;
    sumSquares += luminance * luminance;
    colours.add(((r >> 3) << 10) | ((g >> 3) << 5) | (b >> 3));
  }
  const mean = sum / pixels;
  return {
    luminanceDeviation: Math.sqrt(Math.max(sumSquares / pixels - mean * mean, 0)),
    distinctColours: colours.size,
    png,
  };
}

/** Reads a number as the widgets print it (plain, or mantissa×10ⁿ). */
export function parseDisplayed(text: string): number {
  const superscripts = '⁰¹²³⁴⁵⁶⁷⁸⁹';
  const match = /(-?[\d.]+)(?:×10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+))?/.exec(text);
  if (!match) throw new Error(`no number in "${text}"`);
  const mantissa = Number(match[1]);
  if (!match[2]) return mantissa;
  const exponent = Number(
    [...match[2]].map((c) => (c === '⁻' ? '-' : String(superscripts.indexOf(c)))).join(''),
  );
  return mantissa * 10 ** exponent;
}

/** Number of significant digits shown in a printed number, for "equal to the displayed digits". */
export function displayedDigits(text: string): number {
  const match = /(-?[\d.]+)/.exec(text);
  const digits = (match?.[1] ?? '').replace('-', '').replace('.', '').replace(/^0+/, '');
  return Math.max(digits.length, 1);
}

/**
 * axe-core's WCAG 2.1 A/AA violations on the page as it is now, one line each. KaTeX's
 * HTML rendering (`.katex-html`) is left out: it is the aria-hidden visual copy of the
 * MathML beside it, which axe does check, and it has no colour of its own (the book sets
 * none; it inherits the prose's, which is checked). It is removed from the page, not
 * only excluded: axe builds its tree over the whole document, and on a math-heavy page
 * these spans are most of the nodes (30,000 of 46,000 in the appendix), which halves
 * axe's time. Call it after every other check of the page.
 *
 * `colourOnly`: the rules a theme can change (contrast, links told apart by colour), for
 * the second theme; the rest of WCAG does not depend on colours and ran in the first.
 */
export async function axeViolations(page: Page, colourOnly = false): Promise<string[]> {
  // Layout is final once the math fonts have loaded.
  await page.evaluate(() => document.fonts.ready.then(() => undefined));
  await page.evaluate(() => {
    for (const copy of document.querySelectorAll('.katex-html')) copy.remove();
  });
  const builder = new AxeBuilder({ page });
  const results = await (
    colourOnly
      ? builder.withRules(['color-contrast', 'link-in-text-block'])
      : builder.withTags(['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'])
  ).analyze();
  return results.violations.map(
    (violation) =>
      `${violation.id}: ${violation.nodes.map((node) => node.target.join(' ')).join(', ')}`,
  );
}

/**
 * axe-core violations inside one widget (`include`, a CSS selector), as `rule: targets`.
 * The first theme gets the full rule set (`tags`: only those tag sets, e.g. WCAG 2.1 AA;
 * none: every rule axe runs by default); the second theme needs only the colour rules
 * (`colourOnly`), since names, roles and labels do not change with the theme: the same
 * split as book.spec.ts's page checks.
 */
export async function widgetAxeViolations(
  page: Page,
  include: string,
  { colourOnly = false, tags }: { colourOnly?: boolean; tags?: string[] } = {},
): Promise<string[]> {
  const builder = new AxeBuilder({ page }).include(include);
  if (colourOnly) builder.withRules(['color-contrast', 'link-in-text-block']);
  else if (tags) builder.withTags(tags);
  const results = await builder.analyze();
  return results.violations.map(
    (violation) =>
      `${violation.id}: ${violation.help} (${violation.nodes.map((node) => node.target.join(' ')).join(', ')})`,
  );
}

/**
 * Switches the page to the other theme with its own button (as a reader does, without a
 * reload: the tokens follow html[data-theme]) and waits until it applies.
 */
export async function toggleTheme(page: Page, to: 'light' | 'dark'): Promise<void> {
  await page.locator('.theme-toggle').click();
  await expect(page.locator('html')).toHaveAttribute('data-theme', to);
}

/**
 * Opens `chapter` like widgetOpener, but waits for the widget's first picture only
 * (waitForPicture): for checks of controls, notices, the cost line and readouts that
 * every refinement stage shows, without paying for full refinement on a software GPU.
 */
export function widgetPictureOpener(
  chapter: string,
  tag: string,
  id: string,
): (page: Page, state?: Record<string, string>, query?: string) => Promise<Locator> {
  return widgetOpener(chapter, tag, id, waitForPicture);
}
