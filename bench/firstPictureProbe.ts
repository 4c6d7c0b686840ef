// Where the time between an input and the first picture goes, for one widget on one
// build (issue 23's first-picture regressions): the page's WebGPU calls are wrapped
// before any script runs, so every pipeline compile (createComputePipelineAsync,
// createRenderPipelineAsync), every read-back (mapAsync) and every
// onSubmittedWorkDone is logged with its start and end, together with the long tasks,
// the compute worker's jobs (request to answer), the animation frames that came more
// than 20 ms after they were requested, and the widget's frame attributes. The
// widget is loaded, left to settle as the interaction bench does (data-settled held
// 300 ms, or a quiet 2 s in builds without it), given the bench's input (its first
// slider to 60 % of the range), and the log from 3 s before the input to the first
// picture after it is printed: what was still compiling, reading back or computing in
// the worker when the input came, and what the first picture waited for; then when the
// page's next animation frame came (the picture is on screen with that frame).
// With --stacks, each submit and read-back names its callers (build with --minify false).
// With --profile, the page's main thread is sampled (CDP Profiler, 0.2 ms) from just before
// the input to the first picture, and the functions that took the most time are printed.
// With --trace, a Chromium trace is recorded around the input, and the busy time of the GPU
// process's main thread (where Dawn runs WebGPU beside the raster of the page, under
// DESIGN.md's flags) from the input to the first picture is printed by task, with the
// tasks that ran longest; --trace=FILE also keeps the trace (chrome://tracing, Perfetto).
// --chromium-arg=FLAG (repeatable) adds a diagnostic Chromium flag, as in interaction.ts.
//   npx tsx bench/firstPictureProbe.ts --dist=DIR --widget=NAME [--backend=gpu|cpu] [--after-settle-ms=N] [--stacks] [--profile] [--trace[=FILE]] [--page=chapters/NAME.html] [--chromium-arg=FLAG]
import { chromium } from 'playwright-core';
import { writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { CHROMIUM_PATH, WEBGPU_ARGS } from '../scripts/chromium.mjs';
import { changeValues } from './interactionJudge.ts';
import { servePreview, markFirstSlider } from './previewPage.ts';

const ROOT = fileURLToPath(new URL('..', import.meta.url));

/** Installed before the page's scripts: wraps the GPU calls that can stall a frame. */
const WRAP = `((stacks) => {
  const log = [];
  // With --stacks: the calling functions of each entry (readable in an unminified build),
  // deep enough to reach the widget's own function (V8 keeps 10 frames by default).
  if (stacks) Error.stackTraceLimit = 40;
  const caller = () => stacks
    ? (new Error().stack || '').split("\\n").slice(3, 30)
        .map((line) => line.trim().replace(/^at /, '').replace(/ \\(.*\\)$/, '')).join(' < ')
    : '';
  window.__probe = log;
  const wrapAsync = (proto, name, what) => {
    if (!proto || !proto[name]) return;
    const original = proto[name];
    proto[name] = function (...args) {
      const entry = { what, start: performance.now(), end: null,
        label: (args[0] && args[0].label) || (this && this.label) || caller() };
      log.push(entry);
      const result = original.apply(this, args);
      Promise.resolve(result).then(
        () => { entry.end = performance.now(); },
        () => { entry.end = performance.now(); entry.failed = true; });
      return result;
    };
  };
  const wrapSync = (proto, name, what) => {
    if (!proto || !proto[name]) return;
    const original = proto[name];
    proto[name] = function (...args) {
      const start = performance.now();
      const result = original.apply(this, args);
      const end = performance.now();
      if (end - start > 2) log.push({ what, start, end, label: '' });
      return result;
    };
  };
  if (typeof GPUDevice !== 'undefined') {
    wrapAsync(GPUDevice.prototype, 'createComputePipelineAsync', 'compute pipeline (async)');
    wrapAsync(GPUDevice.prototype, 'createRenderPipelineAsync', 'render pipeline (async)');
    wrapSync(GPUDevice.prototype, 'createComputePipeline', 'compute pipeline (sync)');
    wrapSync(GPUDevice.prototype, 'createShaderModule', 'shader module');
    wrapAsync(GPUBuffer.prototype, 'mapAsync', 'mapAsync');
    wrapAsync(GPUQueue.prototype, 'onSubmittedWorkDone', 'onSubmittedWorkDone');
    wrapAsync(GPUDevice.prototype, 'popErrorScope', 'popErrorScope');
    const submit = GPUQueue.prototype.submit;
    GPUQueue.prototype.submit = function (...args) {
      log.push({ what: 'submit', start: performance.now(), end: performance.now(), label: caller() });
      return submit.apply(this, args);
    };
  }
  // Jobs of the compute worker (src/workers/compute.ts): each request from its
  // postMessage to the answer with the same id, named widget.job.
  if (typeof Worker !== 'undefined') {
    const Original = Worker;
    window.Worker = class extends Original {
      constructor(...args) {
        super(...args);
        const pending = new Map();
        this.addEventListener('message', (event) => {
          const entry = pending.get(event.data && event.data.id);
          if (!entry) return;
          entry.end = performance.now();
          pending.delete(event.data.id);
        });
        const post = this.postMessage.bind(this);
        this.postMessage = (message, transfer) => {
          if (message && typeof message.name === 'string') {
            const entry = { what: 'worker job', start: performance.now(), end: null,
              label: message.widget + '.' + message.name };
            log.push(entry);
            pending.set(message.id, entry);
          }
          return transfer === undefined ? post(message) : post(message, transfer);
        };
      }
    };
  }
  // Animation frames that came late: request to callback, when over 20 ms (the
  // render of a widget waits for one; issue 23 found them seconds late on some pages).
  const raf = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (callback) => {
    const start = performance.now();
    return raf((time) => {
      const end = performance.now();
      if (end - start > 20) log.push({ what: 'late animation frame', start, end, label: '' });
      callback(time);
    });
  };
  try {
    new PerformanceObserver((list) => {
      for (const e of list.getEntries())
        log.push({ what: 'long task', start: e.startTime, end: e.startTime + e.duration, label: '' });
    }).observe({ type: 'longtask', buffered: true });
  } catch (error) { /* no long-task timing */ }
})`;

interface CpuProfile {
  nodes: {
    id: number;
    callFrame: { functionName: string; url: string; lineNumber: number };
    children?: number[];
  }[];
  samples?: number[];
  timeDeltas?: number[];
}

/**
 * The main thread's time from the input to the first picture (plus the 300 ms the page
 * waits after it), by function (self time, ms), idle and garbage collection included, so
 * that what the page did while the picture waited shows.
 */
function printProfile(profile: CpuProfile): void {
  const byId = new Map(profile.nodes.map((node) => [node.id, node]));
  const self = new Map<string, number>();
  const samples = profile.samples ?? [];
  const deltas = profile.timeDeltas ?? [];
  samples.forEach((id, i) => {
    const frame = byId.get(id)?.callFrame;
    const name = frame
      ? `${frame.functionName || '(anonymous)'} ${frame.url.replace(/^.*\//, '')}:${frame.lineNumber + 1}`
      : '?';
    self.set(name, (self.get(name) ?? 0) + (deltas[i + 1] ?? 0) / 1000);
  });
  console.log('  main thread, self time (ms), input to 300 ms after the first picture:');
  for (const [name, ms] of [...self.entries()].sort((a, b) => b[1] - a[1]).slice(0, 25))
    console.log(`    ${ms.toFixed(1).padStart(7)}  ${name}`);
}

interface TraceEvent {
  name: string;
  cat: string;
  ph: string;
  ts: number;
  dur?: number;
  pid: number;
  tid: number;
  args?: Record<string, unknown>;
}

/**
 * What the GPU process's main thread did between the input and the first picture: its
 * top-level tasks (complete events that no other event of that thread encloses), summed
 * by name, and the longest ones. The page marks the input and the picture with
 * console.timeStamp, which puts both on the trace's clock.
 */
function printGpuThread(events: TraceEvent[]): void {
  const mark = (name: string): number | undefined =>
    events.find(
      (e) =>
        e.name === 'TimeStamp' &&
        (e.args?.['data'] as { message?: string } | undefined)?.message === name,
    )?.ts;
  const input = mark('probe-input');
  const picture = mark('probe-picture');
  if (input === undefined || picture === undefined) {
    console.log('  trace: the input or picture mark is missing');
    return;
  }
  const threadName = new Map<string, string>();
  const processName = new Map<number, string>();
  for (const e of events) {
    if (e.ph !== 'M') continue;
    const name = (e.args?.['name'] as string | undefined) ?? '';
    if (e.name === 'thread_name') threadName.set(`${e.pid}:${e.tid}`, name);
    if (e.name === 'process_name') processName.set(e.pid, name);
  }
  const gpuPid = [...processName.entries()].find(([, name]) => /GPU/i.test(name))?.[0];
  const gpuMain = [...threadName.entries()].find(
    ([key, name]) => key.startsWith(`${gpuPid}:`) && name === 'CrGpuMain',
  )?.[0];
  if (gpuMain === undefined) {
    console.log('  trace: no GPU process main thread (CrGpuMain) in the trace');
    return;
  }
  const tasks = events
    .filter((e) => e.ph === 'X' && `${e.pid}:${e.tid}` === gpuMain && e.dur !== undefined)
    .sort((a, b) => a.ts - b.ts || b.dur! - a.dur!);
  // Top level: not inside the previous top-level task.
  const top: TraceEvent[] = [];
  for (const e of tasks) {
    const last = top.at(-1);
    if (last && e.ts < last.ts + last.dur!) continue;
    top.push(e);
  }
  const inWindow = top.filter((e) => e.ts + e.dur! > input && e.ts < picture);
  // A task is named by what it ran: the nested events that took most of it, past the
  // scheduler's wrappers (e.g. "SkiaOutputSurfaceImplOnGpu::SwapBuffers", the page's
  // composited frame, or "WebGPU", the page's WebGPU commands).
  const WRAPPERS = new Set([
    'RunTask',
    'ThreadControllerImpl::RunTask',
    'Scheduler::RunTask',
    'GpuChannel::ExecuteDeferredRequest',
    'GPUTask',
    'CommandBuffer::Flush',
    'CommandBufferStub::OnAsyncFlush',
  ]);
  const childName = (task: TraceEvent): string => {
    const inside = tasks.filter(
      (e) =>
        e.ts >= task.ts &&
        e.ts + e.dur! <= task.ts + task.dur! &&
        !WRAPPERS.has(e.name) &&
        e.dur! > 0.3 * task.dur!,
    );
    return inside.length > 0
      ? inside
          .slice(0, 3)
          .map((e) => e.name)
          .join(' > ')
      : task.name;
  };
  const byName = new Map<string, number>();
  let busy = 0;
  for (const e of inWindow) {
    const overlap = (Math.min(e.ts + e.dur!, picture) - Math.max(e.ts, input)) / 1000;
    busy += overlap;
    const name = childName(e);
    byName.set(name, (byName.get(name) ?? 0) + overlap);
  }
  console.log(
    `  GPU process main thread, input to first picture (${((picture - input) / 1000).toFixed(0)} ms): busy ${busy.toFixed(1)} ms`,
  );
  for (const [name, ms] of [...byName.entries()].sort((a, b) => b[1] - a[1]).slice(0, 12))
    console.log(`    ${ms.toFixed(1).padStart(7)}  ${name}`);
  console.log('  its longest tasks (start after the input, ms):');
  for (const e of [...inWindow].sort((a, b) => b.dur! - a.dur!).slice(0, 8))
    console.log(
      `    ${((e.ts - input) / 1000).toFixed(0).padStart(5)}  ${(e.dur! / 1000).toFixed(1).padStart(6)}  ${childName(e)}`,
    );
}

function option(name: string, fallback?: string): string {
  const found = process.argv.find((arg) => arg.startsWith(`--${name}=`));
  const value = found?.slice(name.length + 3) ?? fallback;
  if (value === undefined) throw new Error(`--${name}=… is required`);
  return value;
}

const dist = option('dist');
const widget = option('widget');
const backend = option('backend', 'gpu');
const afterSettleMs = Number(option('after-settle-ms', '0'));

const { server, base } = await servePreview(ROOT, dist);
const extraArgs = process.argv
  .filter((arg) => arg.startsWith('--chromium-arg='))
  .map((arg) => arg.slice('--chromium-arg='.length));
const browser = await chromium.launch({
  executablePath: CHROMIUM_PATH,
  args: [...WEBGPU_ARGS, ...extraArgs],
});
try {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  await context.addInitScript(`${WRAP}(${process.argv.includes('--stacks')})`);
  const page = await context.newPage();
  const query = backend === 'cpu' ? '?backend=cpu' : '';
  // The widget's embed page, or with --page=PATH the first such widget of a book page.
  const pagePath = process.argv.find((arg) => arg.startsWith('--page='))?.slice('--page='.length);
  await page.goto(`${base}/${pagePath ?? `embed/${widget}.html`}${query}`);
  const tag = `sb-${widget}`;
  await page.locator(tag).first().scrollIntoViewIfNeeded();
  // Settled as the bench judges it.
  const loadStart = Date.now();
  let quietSince = Date.now();
  let lastCount = '';
  for (;;) {
    const state = await page.evaluate((t) => {
      const el = document.querySelector(t) as HTMLElement | null;
      return {
        settled: el?.dataset['settled'] ?? null,
        count: `${el?.dataset['frames'] ?? ''}/${el?.dataset['rendered'] ?? ''}`,
      };
    }, tag);
    // data-settled "true" held 300 ms counts whatever frames come (a widget that goes on
    // accumulating draws every few hundred ms), as in interaction.ts; without it, no
    // new frame for 2 s.
    if ((state.settled === null && state.count !== lastCount) || state.settled === 'false') {
      lastCount = state.count;
      quietSince = Date.now();
    }
    const quiet = Date.now() - quietSince;
    if (state.settled === 'true' ? quiet >= 300 : state.settled === null && quiet >= 2000) break;
    if (Date.now() - loadStart > 60_000) {
      console.log('not settled after 60 s: input anyway');
      break;
    }
    await page.waitForTimeout(100);
  }
  if (afterSettleMs > 0) await page.waitForTimeout(afterSettleMs);
  const slider = await markFirstSlider(page, tag);
  const [next] = changeValues(slider, slider.value);
  // A string, not a function: tsx names arrow functions with a helper the page lacks.
  const INPUT = `async ({ tag, next }) => {
    const el = document.querySelector(tag);
    const control = el.querySelector('input[data-probe]');
    const count = () => Number(el.dataset.frames ?? el.dataset.rendered ?? 0);
    const before = count();
    console.timeStamp('probe-input');
    const t0 = performance.now();
    control.value = String(next);
    control.dispatchEvent(new Event('input', { bubbles: true }));
    // The stage of the first picture, read when it comes (later frames replace it).
    let stage = null;
    await new Promise((resolve) => {
      const observer = new MutationObserver(() => {
        if (count() > before) { stage = el.dataset.stage ?? null; observer.disconnect(); resolve(); }
      });
      observer.observe(el, { attributes: true });
    });
    const t1 = performance.now();
    console.timeStamp('probe-picture');
    // The picture reaches the screen with the next frame the page produces: a render
    // that starts early does not help while frame production is stalled.
    await new Promise((resolve) => requestAnimationFrame(resolve));
    const t2 = performance.now();
    await new Promise((resolve) => setTimeout(resolve, 300));
    const log = window.__probe.filter(
      (e) => (e.end === null || e.end >= t0 - 3000) && e.start <= t1);
    return { control: control.name, value: next, t0, firstMs: t1 - t0, frameMs: t2 - t0,
      stage, log };
  }`;
  const profiling = process.argv.includes('--profile');
  const cdp = profiling ? await context.newCDPSession(page) : null;
  if (cdp) {
    await cdp.send('Profiler.enable');
    await cdp.send('Profiler.setSamplingInterval', { interval: 200 });
    await cdp.send('Profiler.start');
  }
  const traceArg = process.argv.find((arg) => arg === '--trace' || arg.startsWith('--trace='));
  if (traceArg)
    await browser.startTracing(page, {
      categories: [
        'devtools.timeline',
        'toplevel',
        'gpu',
        'cc',
        'viz',
        'skia',
        'disabled-by-default-devtools.timeline',
      ],
    });
  // A second of the settled page before the input, so the trace shows what was running.
  if (traceArg) await page.waitForTimeout(1000);
  const result = (await page.evaluate(`(${INPUT})(${JSON.stringify({ tag, next })})`)) as {
    control: string;
    value: number;
    t0: number;
    firstMs: number;
    frameMs: number;
    stage: string | null;
    log: Record<string, unknown>[];
  };
  console.log(
    `${widget} (${backend}): ${result.control} → ${result.value}: first picture ${result.firstMs.toFixed(0)} ms (${result.stage}), next animation frame at ${result.frameMs.toFixed(0)} ms`,
  );
  if (cdp) printProfile((await cdp.send('Profiler.stop')).profile);
  if (traceArg) {
    const trace = await browser.stopTracing();
    const file = traceArg.startsWith('--trace=') ? traceArg.slice('--trace='.length) : null;
    if (file) writeFileSync(file, trace);
    printGpuThread(
      (JSON.parse(trace.toString('utf8')) as { traceEvents: TraceEvent[] }).traceEvents,
    );
  }
  for (const entry of result.log) {
    const start = (entry['start'] as number) - result.t0;
    const end = entry['end'] === null ? null : (entry['end'] as number) - result.t0;
    console.log(
      `  ${String(entry['what']).padEnd(26)} ${start.toFixed(0).padStart(7)} → ${end === null ? 'pending' : end.toFixed(0).padStart(7)} ms  ${end === null ? '' : `(${(end - start).toFixed(0)} ms)`} ${entry['label'] ?? ''}`,
    );
  }
} finally {
  await browser.close();
  await server.close();
}
