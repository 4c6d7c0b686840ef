// What the page's long tasks during a slider drag are made of (issue 23: the bench's
// "longest main-thread task" names a duration, not a cause). The widget's embed page is
// loaded and left to settle (data-settled held 300 ms), then the interaction bench's
// scripted drag (20 `input` events 50 ms apart across the first slider's range) is
// given with Chromium's sampling profiler running (CDP Profiler, 0.5 ms interval)
// until the widget has settled again. Every run of consecutive busy samples (anything
// but "(idle)") longer than --over ms is a main-thread task; for each, the functions
// with the most inclusive time (a function counted once per sample) and the most
// self time are printed. "(program)" is the browser's own work in the renderer
// (layout, paint, canvas rasterisation), "(garbage collector)" V8's.
//   npx tsx bench/dragProfile.ts --dist=DIR --widget=NAME [--backend=gpu|cpu] [--over=40] [--page=PATH]
import { chromium } from 'playwright-core';
import { fileURLToPath } from 'node:url';
import { CHROMIUM_PATH, WEBGPU_ARGS } from '../scripts/chromium.mjs';
import { dragValues } from './interactionJudge.ts';
import { servePreview, markFirstSlider } from './previewPage.ts';

const ROOT = fileURLToPath(new URL('..', import.meta.url));

function option(name: string, fallback?: string): string {
  const found = process.argv.find((arg) => arg.startsWith(`--${name}=`));
  const value = found?.slice(name.length + 3) ?? fallback;
  if (value === undefined) throw new Error(`--${name}=… is required`);
  return value;
}

interface ProfileNode {
  id: number;
  callFrame: { functionName: string; url: string; lineNumber: number; columnNumber: number };
  children?: number[];
}
interface Profile {
  nodes: ProfileNode[];
  startTime: number;
  endTime: number;
  samples: number[];
  timeDeltas: number[];
}

const dist = option('dist');
const widget = option('widget');
const backend = option('backend', 'gpu');
const overMs = Number(option('over', '40'));
/** With --page=PATH (e.g. chapters/03-….html), the widget is dragged on that book page, not its embed page. */
const pagePath = process.argv.find((arg) => arg.startsWith('--page='))?.slice(7);
/** With --trace=FILE, a Chromium trace of the drag (the browser's own work, by event) is written too. */
const traceFile = process.argv.find((arg) => arg.startsWith('--trace='))?.slice(8);

/** A frame's name: the function and where it is (file name and line, 1-based). */
function frameName(node: ProfileNode): string {
  const { functionName, url, lineNumber, columnNumber } = node.callFrame;
  const file = url.split('/').at(-1) ?? '';
  return file
    ? `${functionName || '(anonymous)'} ${file}:${lineNumber + 1}:${columnNumber + 1}`
    : functionName || '(anonymous)';
}

const { server, base } = await servePreview(ROOT, dist);
const browser = await chromium.launch({ executablePath: CHROMIUM_PATH, args: WEBGPU_ARGS });
try {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  const query = backend === 'cpu' ? '?backend=cpu' : '';
  await page.goto(`${base}/${pagePath ?? `embed/${widget}.html`}${query}`);
  const tag = `sb-${widget}`;
  await page.locator(tag).first().scrollIntoViewIfNeeded();
  const settled = async (): Promise<void> => {
    const start = Date.now();
    let since = Date.now();
    while (Date.now() - start < 60_000) {
      const state = await page.evaluate(
        (t) => document.querySelector<HTMLElement>(t)?.dataset['settled'] ?? null,
        tag,
      );
      if (state !== 'true') since = Date.now();
      else if (Date.now() - since >= 300) return;
      await page.waitForTimeout(50);
    }
    console.log('not settled after 60 s');
  };
  await settled();
  const slider = await markFirstSlider(page, tag);
  const values = dragValues(slider, 20);
  const cdp = await context.newCDPSession(page);
  await cdp.send('Profiler.enable');
  await cdp.send('Profiler.setSamplingInterval', { interval: 500 });
  await cdp.send('Profiler.start');
  if (traceFile)
    await browser.startTracing(page, {
      path: traceFile,
      categories: [
        'devtools.timeline',
        'disabled-by-default-devtools.timeline',
        'blink',
        'cc',
        'toplevel',
      ],
    });
  await page.evaluate(
    `(async ({ tag, values }) => {
      const control = document.querySelector(tag).querySelector('input[data-probe]');
      for (const v of values) {
        control.value = String(v);
        control.dispatchEvent(new Event('input', { bubbles: true }));
        await new Promise((resolve) => setTimeout(resolve, 50));
      }
    })(${JSON.stringify({ tag, values })})`,
  );
  await page.waitForTimeout(200);
  await settled();
  if (traceFile) await browser.stopTracing();
  const { profile } = (await cdp.send('Profiler.stop')) as unknown as { profile: Profile };
  const byId = new Map(profile.nodes.map((n) => [n.id, n]));
  const parent = new Map<number, number>();
  for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
  // Runs of busy samples.
  let t = profile.startTime;
  interface BusyRun {
    start: number;
    end: number;
    samples: { id: number; dt: number }[];
  }
  let run: BusyRun | null = null;
  const runs: BusyRun[] = [];
  for (let k = 0; k < profile.samples.length; k++) {
    const dt = profile.timeDeltas[k + 1] ?? 0;
    const id = profile.samples[k] as number;
    const name = byId.get(id)?.callFrame.functionName;
    if (name === '(idle)') {
      if (run) runs.push(run);
      run = null;
    } else {
      run ??= { start: t, end: t, samples: [] };
      run.samples.push({ id, dt });
      run.end = t + dt;
    }
    t += profile.timeDeltas[k] ?? 0;
  }
  if (run !== null) runs.push(run as BusyRun);
  const long = runs.filter((r) => (r.end - r.start) / 1000 > overMs);
  console.log(
    `${widget} (${backend}): ${runs.length} busy runs, ${long.length} over ${overMs} ms; longest ${(Math.max(0, ...runs.map((r) => r.end - r.start)) / 1000).toFixed(0)} ms`,
  );
  for (const r of long) {
    const inclusive = new Map<string, number>();
    const self = new Map<string, number>();
    for (const { id, dt } of r.samples) {
      const seen = new Set<string>();
      let node: number | undefined = id;
      const leaf = byId.get(id);
      if (leaf) self.set(frameName(leaf), (self.get(frameName(leaf)) ?? 0) + dt);
      while (node !== undefined) {
        const n = byId.get(node);
        if (!n) break;
        const name = frameName(n);
        if (!seen.has(name)) {
          seen.add(name);
          inclusive.set(name, (inclusive.get(name) ?? 0) + dt);
        }
        node = parent.get(node);
      }
    }
    const top = (m: Map<string, number>, count: number): string =>
      [...m.entries()]
        .filter(([name]) => name !== '(root)')
        .sort((a, b) => b[1] - a[1])
        .slice(0, count)
        .map(([name, us]) => `      ${(us / 1000).toFixed(1).padStart(7)} ms  ${name}`)
        .join('\n');
    console.log(
      `  task at ${((r.start - profile.startTime) / 1000).toFixed(0)} ms, ${((r.end - r.start) / 1000).toFixed(0)} ms\n    inclusive:\n${top(inclusive, 14)}\n    self:\n${top(self, 6)}`,
    );
  }
} finally {
  await browser.close();
  await server.close();
}
