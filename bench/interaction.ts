// What a student feels when moving a slider (issue 23, item 3), widget by widget, on
// the production build (`vite build` → DIR, served by `vite preview`) in Debian's
// Chromium with WebGPU on this machine's adapter (SwiftShader where there is no GPU),
// and again with the CPU fallback (`?backend=cpu`). Each widget's embed page
// (/embed/<name>.html, the widget alone at 1280×900) is loaded in a fresh context and,
// once the widget has settled:
// - input to first picture: the first slider of its controls is set to another value
//   and an `input` event dispatched (t0 = performance.now() just before); the first
//   picture is the next increment of the frame counter (data-frames, or data-rendered
//   in builds without it), seen by a MutationObserver in the page; it is on screen with
//   the next animation frame the page produces after that (a requestAnimationFrame);
// - time to full quality: from t0 until the widget says it is settled (data-settled
//   = "true"), or, in builds without data-settled, until the counter has moved and then
//   stayed still for 1 s (full quality = its last move); capped at 120 s (a widget
//   not settled a minute after loading is measured with a 10 s wait, and says so);
// - a scripted drag: 20 `input` events 50 ms apart across the slider's range (a reader
//   dragging for one second), with a PerformanceObserver on long tasks: the longest
//   main-thread task and the total blocking time (Σ duration − 50 ms) from the first
//   input until settled, and the frames shown during the drag's second;
// - the frame cost the widget reports (data-frame-ms, removed before each change so
//   that a stale value does not count).
// The change alternates between 60 % of the slider's range and its initial value;
// medians over `repeats` changes (fewer where a widget's changes take long; the row
// says how many). A widget that fails or times out gets a row saying so.
// With --chromium-arg=FLAG (repeatable), Chromium gets FLAG besides DESIGN.md's WebGPU flags:
// a diagnostic (e.g. --chromium-arg=--disable-gpu-rasterization shows how much of a first
// picture is Chromium rasterising the page in its GPU process beside WebGPU), never the
// bench's numbers. With --samples, each widget's first-picture times are also printed one by one (in order,
// to stderr): on a shared 2-core machine a median of 9 moves by ±15 ms from run to run.
// With --in-chapter, each widget is measured on its chapter page (the first widget of its
// kind there, at 1280×900, scrolled into view) instead of its embed page: where a student
// reads it, with the chapter's text, formulas and table of contents around it.
//   npx tsx bench/interaction.ts --dist=DIR [--repeats=N] [--backend=gpu|cpu|both]
//     [--only-widgets=a,b] [--samples] [--in-chapter] [--chromium-arg=FLAG ...]  (or npm run bench -- --only=interaction --dist=DIR)
import { existsSync } from 'node:fs';
import { loadavg } from 'node:os';
import { fileURLToPath } from 'node:url';
import { chromium, type Browser, type Page } from 'playwright-core';
import { CHROMIUM_PATH, WEBGPU_ARGS } from '../scripts/chromium.mjs';
import { WIDGET_CATALOG } from '../src/widgets/catalog.ts';
import {
  changeValues,
  dragValues,
  firstShown,
  judgeChange,
  longestTask,
  observation,
  tasksWithin,
  totalBlockingTime,
  type ChangeOutcome,
  type LongTask,
  type Observation,
  type RawObservation,
  type ShownFrame,
} from './interactionJudge.ts';
import { median, printTable, type BenchTable } from './table.ts';
import { servePreview } from './previewPage.ts';

/** DESIGN.md's flags, and the diagnostic extras of --chromium-arg (the header says so). */
const EXTRA_ARGS = process.argv
  .filter((arg) => arg.startsWith('--chromium-arg='))
  .map((arg) => arg.slice('--chromium-arg='.length));
const LAUNCH_ARGS = [...WEBGPU_ARGS, ...EXTRA_ARGS];

const ROOT = fileURLToPath(new URL('..', import.meta.url));

export type BackendName = 'gpu' | 'cpu';

export interface InteractionOptions {
  dist?: string;
  repeats: number;
  backends: readonly BackendName[];
  /** Widget names to measure; every catalog widget but `exercise` when absent. */
  widgets?: readonly string[];
  /** Measure each widget on its chapter page (where a student reads it), not its embed page. */
  inChapter?: boolean;
}

/** Longest wait for full quality after an input (and for the first settle after loading). */
const SETTLE_CAP_MS = 120_000;
/** Quiet time that counts as settled in builds without data-settled. */
const QUIET_MS = 1000;
/** After loading, a longer quiet: a slow accumulation can pause for more than 1 s. */
const LOAD_QUIET_MS = 2000;
/** Longest wait for the widget to settle after loading; past it, see UNSETTLED_WAIT_MS. */
const LOAD_CAP_MS = 60_000;
/**
 * A widget that has not settled a minute after loading (one that accumulates without
 * end, or not within a minute on this machine) is still measured: each change waits
 * for its first picture and then this long for full quality, and says so.
 */
const UNSETTLED_WAIT_MS = 10_000;
/** Once a widget's changes have taken this long (and two are measured), stop repeating. */
const CHANGE_BUDGET_MS = 20_000;
const DRAG_INPUTS = 20;
const DRAG_INTERVAL_MS = 50;
/** A widget's whole measurement (load, changes, drag) is abandoned after this long. */
const RUN_TIMEOUT_MS = 330_000;
const POLL_MS = 100;
/** How long data-settled = "true" must hold (with no new frame) before it counts. */
const CONFIRM_MS = 300;

/**
 * Installed in the page once it has loaded (a string, not a function: tsx keeps
 * function names with a helper that does not exist in the page). Records every change
 * of the widget's frame attributes with its time, and every long task.
 */
const RECORDER = `(tag) => {
  const el = document.querySelector(tag);
  if (!el) return false;
  const names = ['data-frames', 'data-rendered', 'data-settled', 'data-stage', 'data-frame-ms', 'data-frame-timer'];
  const snap = () => ({
    t: performance.now(),
    frames: el.getAttribute('data-frames'),
    rendered: el.getAttribute('data-rendered'),
    settled: el.getAttribute('data-settled'),
    stage: el.getAttribute('data-stage'),
    frameMs: el.getAttribute('data-frame-ms'),
    timer: el.getAttribute('data-frame-timer'),
  });
  const state = { el, log: [snap()], tasks: [], shown: [], taskObserver: null, control: null };
  window.__sbBench = state;
  // The page's next animation frame after each move of the frame counter: when that
  // picture reached the screen.
  let lastCount = el.getAttribute('data-frames') ?? el.getAttribute('data-rendered');
  new MutationObserver(() => {
    const now = snap();
    state.log.push(now);
    const count = now.frames ?? now.rendered;
    if (count === lastCount) return;
    lastCount = count;
    requestAnimationFrame(() => state.shown.push({ frames: Number(count) || 0, t: performance.now() }));
  }).observe(el, { attributes: true, attributeFilter: names });
  try {
    state.taskObserver = new PerformanceObserver((list) => {
      for (const e of list.getEntries()) state.tasks.push({ startTime: e.startTime, duration: e.duration });
    });
    state.taskObserver.observe({ type: 'longtask', buffered: false });
  } catch (error) {
    state.taskObserver = null;
  }
  return true;
}`;

/** The control a change moves: the first visible, enabled slider of the controls, else a select. */
const FIND_CONTROL = `() => {
  const state = window.__sbBench;
  const usable = (c) => !c.disabled && c.checkVisibility();
  const ranges = [
    ...state.el.querySelectorAll('.sb-controls input[type=range]'),
    ...state.el.querySelectorAll('input[type=range]'),
  ].filter(usable);
  const selects = [
    ...state.el.querySelectorAll('.sb-controls select'),
    ...state.el.querySelectorAll('select'),
  ].filter(usable);
  const control = ranges[0] ?? selects[0] ?? null;
  state.control = control;
  if (!control) return null;
  if (control.localName === 'select')
    return { kind: 'select', name: control.name, value: control.value,
      options: [...control.options].map((o) => o.value), min: 0, max: 0, step: 1 };
  return { kind: 'range', name: control.name, value: control.value, options: [],
    min: Number(control.min), max: Number(control.max), step: Number(control.step) || 1 };
}`;

interface ControlInfo {
  kind: 'range' | 'select';
  name: string;
  value: string;
  options: string[];
  min: number;
  max: number;
  step: number;
}

/** What the page has recorded, fetched incrementally. */
class Recording {
  readonly log: Observation[] = [];
  readonly tasks: LongTask[] = [];
  readonly shown: ShownFrame[] = [];
  now = 0;
  constructor(private readonly page: Page) {}

  async fetch(): Promise<void> {
    const fresh = await this.page.evaluate(
      ([fromLog, fromTasks, fromShown]) => {
        const state = (window as unknown as { __sbBench: BenchState }).__sbBench;
        for (const entry of state.taskObserver?.takeRecords() ?? [])
          state.tasks.push({ startTime: entry.startTime, duration: entry.duration });
        return {
          log: state.log.slice(fromLog),
          tasks: state.tasks.slice(fromTasks),
          shown: state.shown.slice(fromShown),
          now: performance.now(),
        };
      },
      [this.log.length, this.tasks.length, this.shown.length] as const,
    );
    this.log.push(...fresh.log.map(observation));
    this.tasks.push(...fresh.tasks);
    this.shown.push(...fresh.shown);
    this.now = fresh.now;
  }

  /**
   * Polls until the change given at t0 is settled, or `capMs` has passed and its first
   * picture came (the first picture is waited for up to SETTLE_CAP_MS).
   */
  async waitSettled(
    t0: number,
    frames0: number,
    quietMs: number,
    capMs = SETTLE_CAP_MS,
  ): Promise<ChangeOutcome> {
    for (;;) {
      await this.fetch();
      const outcome = judgeChange(this.log, t0, frames0, this.now, quietMs);
      // A frame for stale inputs (one that was in flight when a drag's last input came)
      // can say settled until the next frame starts: data-settled must hold a moment.
      const confirmed =
        outcome.settled !== null &&
        (outcome.settledBy === 'quiet' || this.now - outcome.settled.t >= CONFIRM_MS);
      const waited = this.now - t0;
      if (confirmed || (waited > capMs && (outcome.firstPicture || waited > SETTLE_CAP_MS)))
        return outcome;
      await new Promise((resolve) => setTimeout(resolve, POLL_MS));
    }
  }
}

/** The page-side state RECORDER installs (typed for the evaluate callbacks). */
interface BenchState {
  el: HTMLElement;
  log: RawObservation[];
  tasks: LongTask[];
  shown: ShownFrame[];
  taskObserver: PerformanceObserver | null;
  control: HTMLInputElement | HTMLSelectElement | null;
}

/** Sets the control to `value` and dispatches the event a reader's input gives; returns t0. */
async function giveInput(page: Page, value: string): Promise<{ t0: number; frames0: number }> {
  return page.evaluate((next) => {
    const state = (window as unknown as { __sbBench: BenchState }).__sbBench;
    const control = state.control;
    if (!control) throw new Error('no control');
    // A stale cost must not count as reported for this change.
    delete state.el.dataset['frameMs'];
    delete state.el.dataset['frameTimer'];
    const frames0 = Number(state.el.dataset['frames'] ?? state.el.dataset['rendered'] ?? 0);
    const t0 = performance.now();
    control.value = next;
    control.dispatchEvent(
      new Event(control.localName === 'select' ? 'change' : 'input', { bubbles: true }),
    );
    return { t0, frames0 };
  }, value);
}

/** The scripted drag: `values` as inputs `interval` ms apart, on schedule (late when blocked). */
async function drag(
  page: Page,
  values: readonly string[],
  interval: number,
): Promise<{ times: number[]; frames0: number; framesAtLast: number; shown: number }> {
  return page.evaluate(
    async ({ values, interval }) => {
      const state = (window as unknown as { __sbBench: BenchState }).__sbBench;
      const control = state.control;
      if (!control) throw new Error('no control');
      const el = state.el;
      const frames0 = Number(el.dataset['frames'] ?? el.dataset['rendered'] ?? 0);
      // Every frame shown: the current inputs' and a drag's earlier inputs' (data-stale-frames).
      // Written out, not a named helper: tsx names functions with an __name() call that the
      // page does not have.
      const shown0 = frames0 + Number(el.dataset['staleFrames'] ?? 0);
      const times: number[] = [];
      let framesAtLast = frames0;
      const start = performance.now();
      for (const [i, value] of values.entries()) {
        const wait = start + i * interval - performance.now();
        if (wait > 0) await new Promise((resolve) => setTimeout(resolve, wait));
        framesAtLast = Number(el.dataset['frames'] ?? el.dataset['rendered'] ?? 0);
        times.push(performance.now());
        control.value = value;
        control.dispatchEvent(
          new Event(control.localName === 'select' ? 'change' : 'input', { bubbles: true }),
        );
      }
      await new Promise((resolve) => setTimeout(resolve, interval));
      const shown =
        Number(el.dataset['frames'] ?? el.dataset['rendered'] ?? 0) +
        Number(el.dataset['staleFrames'] ?? 0) -
        shown0;
      return { times, frames0, framesAtLast, shown };
    },
    { values, interval },
  );
}

/** Iterations of the load probe's fixed loop. */
const PROBE_ITERATIONS = 2_000_000;

/**
 * Milliseconds the page takes for a fixed arithmetic loop, once the widget has settled:
 * how much of a core the page gets on this shared machine while the row was measured
 * (compare rows and runs by it: it does not correct the times).
 */
async function loadProbe(page: Page): Promise<number> {
  return page.evaluate((iterations) => {
    const start = performance.now();
    let sum = 0;
    for (let i = 0; i < iterations; i++) sum += Math.sqrt(i);
    const elapsed = performance.now() - start;
    return sum > 0 ? elapsed : -1;
  }, PROBE_ITERATIONS);
}

/** A wait that ran out: "> 120 s". */
function beyond(capMs: number): string {
  return `> ${capMs / 1000} s`;
}

interface ChangeSample {
  firstMs: number;
  /** To the page's next animation frame after the first picture; null when none was logged. */
  shownMs: number | null;
  fullMs: number | null;
  stage: string | null;
  frameMs: number | null;
  timer: string | null;
}

type Row = BenchTable['rows'][number];

/** One widget on one backend: load, settle, `repeats` changes, the drag. */
async function measureWidget(
  browser: Browser,
  base: string,
  name: string,
  backend: BackendName,
  repeats: number,
  inChapter = false,
): Promise<{ row: Row; adapter: string | null; settledBy: string }> {
  const context = await browser.newContext({
    viewport: { width: 1280, height: 900 },
    serviceWorkers: 'block',
  });
  const errors: string[] = [];
  try {
    const page = await context.newPage();
    page.on('pageerror', (error) => errors.push(error.message));
    page.on('console', (message) => {
      if (message.type() === 'error') errors.push(message.text());
    });
    const query = backend === 'cpu' ? '?backend=cpu' : '';
    await page.goto(`${base}/embed/${name}.html${query}`, { waitUntil: 'domcontentloaded' });
    if (inChapter) {
      // The chapter the embed page's "Open in the book" link names; its first such widget.
      const chapter = await page.locator('a.embed-chapter-link').getAttribute('href');
      if (!chapter) throw new Error('no chapter link on the embed page');
      const url = new URL(chapter, page.url());
      url.search = query;
      url.hash = '';
      await page.goto(url.href, { waitUntil: 'domcontentloaded' });
    }
    const tag = `sb-${name}`;
    if (!(await page.evaluate(`(${RECORDER})(${JSON.stringify(tag)})`)))
      throw new Error(`no <${tag}> on the ${inChapter ? 'chapter' : 'embed'} page`);
    await page.locator(tag).first().scrollIntoViewIfNeeded();
    const recording = new Recording(page);
    const loaded = await recording.waitSettled(0, 0, LOAD_QUIET_MS, LOAD_CAP_MS);
    if (!loaded.firstPicture) throw new Error(`no frame ${SETTLE_CAP_MS / 1000} s after loading`);
    // Not settled a minute after loading: measured all the same, with a short wait.
    const unsettled = loaded.settled === null;
    const capMs = unsettled ? UNSETTLED_WAIT_MS : SETTLE_CAP_MS;
    const capLabel = unsettled ? ' (never settled after loading)' : '';
    const probe = await loadProbe(page);
    const adapter =
      backend === 'gpu'
        ? await page.evaluate(async () => {
            const gpu = (navigator as Navigator & { gpu?: GPU }).gpu;
            const found = await gpu?.requestAdapter();
            return found
              ? `${found.info.vendor} ${found.info.architecture} ${found.info.description}`.trim()
              : 'none';
          })
        : null;
    const control = (await page.evaluate(`(${FIND_CONTROL})()`)) as ControlInfo | null;
    if (!control) throw new Error('no slider or select in the controls');
    let pair: [string, string];
    let dragged: string[];
    if (control.kind === 'range') {
      const [a, b] = changeValues(control, Number(control.value));
      pair = [String(a), String(b)];
      dragged = dragValues(control, DRAG_INPUTS).map(String);
    } else {
      const other = control.options.find((option) => option !== control.value);
      if (other === undefined) throw new Error(`select ${control.name} has one option`);
      pair = [other, control.value];
      dragged = Array.from(
        { length: DRAG_INPUTS },
        (_, i) => control.options[(i + 1) % control.options.length] ?? control.value,
      );
    }

    // Single changes, alternating between the two values.
    const samples: ChangeSample[] = [];
    const started = Date.now();
    let capped = false;
    for (let i = 0; i < repeats; i++) {
      if (samples.length >= 2 && Date.now() - started > CHANGE_BUDGET_MS) break;
      const { t0, frames0 } = await giveInput(page, pair[i % 2] ?? pair[0]);
      const outcome = await recording.waitSettled(t0, frames0, QUIET_MS, capMs);
      if (!outcome.firstPicture)
        throw new Error(`no new frame ${SETTLE_CAP_MS / 1000} s after an input`);
      const shown = firstShown(recording.shown, t0, frames0);
      // The cost at full quality, or the latest one where the widget never settled.
      const costAt = outcome.settled ?? recording.log[recording.log.length - 1] ?? null;
      samples.push({
        firstMs: outcome.firstPicture.t - t0,
        shownMs: shown ? shown.t - t0 : null,
        fullMs: outcome.settled ? outcome.settled.t - t0 : null,
        stage: outcome.firstPicture.stage,
        frameMs: costAt?.frameMs ?? null,
        timer: costAt?.timer ?? null,
      });
      if (!outcome.settled && !unsettled) {
        capped = true;
        break;
      }
    }

    // The drag, unless the widget never settled after a change.
    let dragCells: Row = {
      'longest task during drag ms': 'not measured',
      'total blocking ms': 'not measured',
      'frames during drag': 'not measured',
      'full quality after drag ms': 'not measured',
    };
    if (!capped) {
      const { times, framesAtLast, shown } = await drag(page, dragged, DRAG_INTERVAL_MS);
      const first = times[0] ?? 0;
      const last = times[times.length - 1] ?? first;
      const outcome = await recording.waitSettled(last, framesAtLast, QUIET_MS, capMs);
      const end = outcome.settled?.t ?? recording.now;
      // Long tasks are delivered after they end: one more look once the page is idle.
      await new Promise((resolve) => setTimeout(resolve, 200));
      await recording.fetch();
      const tasks = tasksWithin(recording.tasks, first, end);
      dragCells = {
        'longest task during drag ms': longestTask(tasks) ?? 'none',
        'total blocking ms': totalBlockingTime(tasks),
        'frames during drag': shown,
        'full quality after drag ms': outcome.settled
          ? outcome.settled.t - last
          : `${beyond(capMs)}${capLabel}`,
      };
    }

    const full = samples.map((s) => s.fullMs);
    const stages = [...new Set(samples.map((s) => s.stage ?? '—'))];
    const costs = samples.map((s) => s.frameMs).filter((ms): ms is number => ms !== null);
    const timer = samples.find((s) => s.timer)?.timer ?? '';
    const shownTimes = samples.map((s) => s.shownMs).filter((ms): ms is number => ms !== null);
    const fellBack =
      backend === 'gpu' &&
      (await page.evaluate(() =>
        (document.querySelector('.sb-notices')?.textContent ?? '').includes(
          'WebGPU is not available',
        ),
      ));
    if (process.argv.includes('--samples'))
      console.error(
        `${name}: first picture ms ${samples.map((s) => s.firstMs.toFixed(0)).join(' ')}`,
      );
    return {
      adapter,
      settledBy: loaded.settledBy,
      row: {
        widget: fellBack ? `${name} (fell back to the CPU)` : name,
        slider:
          control.kind === 'range'
            ? `${control.name} ${pair[1]}→${pair[0]}`
            : `${control.name} (select) ${pair[1]}→${pair[0]}`,
        'first picture ms (median)': median(samples.map((s) => s.firstMs)),
        'on screen ms (median)': shownTimes.length > 0 ? median(shownTimes) : 'not logged',
        'stage at first picture': stages.join(' / '),
        'full quality ms (median)': full.includes(null)
          ? `${beyond(capMs)}${capLabel}`
          : median(full.filter((ms): ms is number => ms !== null)),
        ...dragCells,
        'frame cost reported':
          costs.length === samples.length
            ? `yes: ${Number(median(costs).toPrecision(4))} ms${timer ? ` (${timer})` : ''}`
            : costs.length > 0
              ? `after ${costs.length} of ${samples.length} changes`
              : 'no',
        changes: samples.length,
        'load probe ms': probe,
        'settled by': `${loaded.settledBy === 'data-settled' ? 'data-settled' : 'quiet 1 s'}${unsettled ? `, not within ${LOAD_CAP_MS / 1000} s of loading` : ''}`,
      },
    };
  } catch (error) {
    const why = error instanceof Error ? (error.message.split('\n')[0] ?? '') : String(error);
    const pageErrors = errors.length > 0 ? `; page errors: ${errors.slice(0, 3).join(' | ')}` : '';
    console.error(`bench: ${name} (${backend}) failed: ${why}${pageErrors}`);
    return {
      adapter: null,
      settledBy: '',
      row: { widget: name, 'first picture ms (median)': `failed: ${why}` },
    };
  } finally {
    await context.close().catch(() => undefined);
  }
}

/** Every catalog widget that draws frames (an exercise's cost is grading: bench/grading.ts). */
export function interactionWidgets(): string[] {
  return Object.keys(WIDGET_CATALOG).filter((name) => name !== 'exercise');
}

async function withTimeout<T>(work: Promise<T>, ms: number, onTimeout: () => T): Promise<T> {
  let timer: ReturnType<typeof setTimeout> | undefined;
  const timeout = new Promise<T>((resolve) => {
    timer = setTimeout(() => resolve(onTimeout()), ms);
  });
  try {
    return await Promise.race([work, timeout]);
  } finally {
    clearTimeout(timer);
  }
}

export async function benchInteraction(options: InteractionOptions): Promise<BenchTable[]> {
  const dist = options.dist ?? `${ROOT}dist`;
  const widgets = options.widgets ?? interactionWidgets();
  const loadAtStart = loadavg();
  const { server, base } = await servePreview(ROOT, dist);
  let browser = await chromium.launch({ executablePath: CHROMIUM_PATH, args: LAUNCH_ARGS });
  const tables: BenchTable[] = [];
  const started = Date.now();
  try {
    for (const backend of options.backends) {
      const rows: Row[] = [];
      const quietJudged: string[] = [];
      let adapter = backend === 'gpu' ? 'unknown' : 'none (CPU fallback)';
      for (const name of widgets) {
        if (!existsSync(`${dist}/embed/${name}.html`)) {
          rows.push({ widget: name, 'first picture ms (median)': 'no embed page in the build' });
          continue;
        }
        // A crashed browser (GPU process lost) is started again for the next widget.
        if (!browser.isConnected())
          browser = await chromium.launch({ executablePath: CHROMIUM_PATH, args: LAUNCH_ARGS });
        const current = browser;
        const run = measureWidget(current, base, name, backend, options.repeats, options.inChapter);
        let timedOut = false;
        const result = await withTimeout(run, RUN_TIMEOUT_MS, () => {
          timedOut = true;
          return {
            adapter: null,
            settledBy: '',
            row: {
              widget: name,
              'first picture ms (median)': `timed out after ${RUN_TIMEOUT_MS / 1000} s`,
            },
          };
        });
        if (timedOut) {
          // The measurement still holds its context: close the browser to end it.
          await current.close().catch(() => undefined);
          await run.catch(() => undefined);
        }
        rows.push(result.row);
        if (result.adapter) adapter = result.adapter;
        if (result.settledBy === 'quiet') quietJudged.push(name);
        console.error(
          `bench: ${name} (${backend}) done at ${((Date.now() - started) / 1000).toFixed(0)} s`,
        );
      }
      tables.push({
        title: `Slider input to picture, ${backend === 'gpu' ? 'WebGPU' : 'CPU fallback (?backend=cpu)'} (Chromium, ${options.inChapter ? 'each widget on its chapter page (the first of its kind there)' : 'embed pages'}, ${dist})`,
        notes: [
          `Adapter: ${adapter}.`,
          ...(EXTRA_ARGS.length > 0
            ? [
                `Diagnostic run: Chromium also got ${EXTRA_ARGS.join(' ')} (not the bench's setting).`,
              ]
            : []),
          `Medians of up to ${options.repeats} changes of the first slider (60 % of its range ↔ its initial value), after the widget settled; ` +
            `a widget stops repeating once its changes took ${CHANGE_BUDGET_MS / 1000} s (the "changes" column).`,
          'first picture: t0 = performance.now() before the input event, to the next increment of data-frames (data-rendered where the build has no data-frames).',
          'on screen: t0 to the first animation frame the page produced after that increment (the drawing reaches the screen with that frame; on SwiftShader under load frames can come hundreds of ms apart).',
          quietJudged.length > 0
            ? `settled: data-settled = "true"; where the build has no data-settled (${quietJudged.join(', ')}), the frame counter moved and then stayed still for ${QUIET_MS / 1000} s (full quality = its last move).`
            : 'settled: data-settled = "true" after the input\'s first frame.',
          `settled counts once data-settled = "true" has held ${CONFIRM_MS} ms; a widget not settled ${LOAD_CAP_MS / 1000} s after loading is measured all the same, waiting ${UNSETTLED_WAIT_MS / 1000} s for full quality after each input (the row says so).`,
          `drag: ${DRAG_INPUTS} input events ${DRAG_INTERVAL_MS} ms apart from the slider's min to max; long tasks (PerformanceObserver "longtask", ≥ 50 ms) from the first input until settled; total blocking = Σ (duration − 50 ms); frames during drag = frames shown from the first input to one interval after the last (data-frames and data-stale-frames: a first picture of earlier inputs is shown too); full quality after drag is from the last input.`,
          'frame cost reported: data-frame-ms (removed before each change) at full quality (the latest, where a change never settled), median, with data-frame-timer.',
          `load probe: ms for a fixed loop of ${PROBE_ITERATIONS.toExponential(0)} square roots in the page after loading: larger means the machine was busier while that row was measured (compare rows and runs by it; it does not correct the times).`,
        ],
        rows,
      });
    }
  } finally {
    await browser.close().catch(() => undefined);
    await new Promise<void>((resolve) => server.httpServer.close(() => resolve()));
  }
  const loadAtEnd = loadavg();
  const load = (values: number[]): string => values.map((v) => v.toFixed(2)).join(', ');
  for (const table of tables)
    table.notes.push(
      `Load averages (1, 5, 15 min): ${load(loadAtStart)} at start, ${load(loadAtEnd)} at end; whole run ${((Date.now() - started) / 1000).toFixed(0)} s.`,
    );
  return tables;
}

/** Options from the command line: --dist=DIR --repeats=N --backend=gpu|cpu|both --only-widgets=a,b. */
export function interactionOptionsFromArgs(
  argv: readonly string[],
  defaultRepeats: number,
): InteractionOptions {
  const value = (key: string): string | undefined =>
    argv.find((a) => a.startsWith(`--${key}=`))?.slice(`--${key}=`.length);
  const backend = value('backend') ?? 'both';
  if (!['gpu', 'cpu', 'both'].includes(backend))
    throw new Error(`--backend must be gpu, cpu or both, not ${backend}`);
  const widgets = value('only-widgets')?.split(',').filter(Boolean);
  const known = interactionWidgets();
  for (const name of widgets ?? [])
    if (!known.includes(name))
      throw new Error(`unknown widget ${name}: one of ${known.join(', ')}`);
  const repeats = Number(value('repeats') ?? defaultRepeats);
  if (!Number.isInteger(repeats) || repeats < 1)
    throw new Error('--repeats must be a positive integer');
  return {
    dist: value('dist'),
    repeats,
    backends: backend === 'both' ? ['gpu', 'cpu'] : [backend as BackendName],
    widgets,
    inChapter: argv.includes('--in-chapter'),
  };
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const tables = await benchInteraction(interactionOptionsFromArgs(process.argv, 5));
  for (const table of tables) printTable(table);
}
