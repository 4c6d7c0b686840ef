// The drawing of <sb-single-scatter>: the progressive image and its per-pixel standard
// error (on WebGPU drawn from the moments on the GPU, src/scene/accumulationView.ts; on
// the CPU on the host), the plan table, the restart / re-time bar with the reference's
// progress, and the RMSE-against-time plot with its slope −½ guide. The view keeps the
// run, the references cached per scene and the kernel timings; each render adds one
// pass to the image or the reference and asks for the next while either has work.
// Readouts, cost line, backend choice and fallback: widget.ts and the base element.
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { GpuContext } from '../../gpu/device.ts';
import type { Accumulation, ImageAccumulator } from '../../scene/accumulation.ts';
import {
  AccumulationView,
  canvasForContext,
  type AccumulationPicture,
} from '../../scene/accumulationView.ts';
import { WorkerSceneRenderer } from '../../scene/workerRenderer.ts';
import { GpuAccumulation } from '../../scene/gpuAccumulation.ts';
import { GpuSceneRenderer } from '../../scene/gpuRenderer.ts';
import { toneMapRgba8 } from '../../scene/image.ts';
import { resolveScene, type ResolvedScene } from '../../scene/load.ts';
import { packScene, sceneData } from '../../scene/pack.ts';
import { GENERAL_CONDITIONS, plan, type Conditions, type Plan } from '../../scene/plan.ts';
import type { PassRenderer, PassTiming } from '../../scene/render.ts';
import { parseScene } from '../../scene/validate.ts';
import type { Backend } from '../base/backend.ts';
import type { FrameRequest, Refinement } from '../base/refinement.ts';
import { formatNumber } from '../base/format.ts';
import {
  gradientCss,
  imageCanvas,
  imageFigure,
  imagePanel,
  niceScale,
} from '../base/imagePanel.ts';
import { LinePlot, createPlotArea } from '../base/plot.ts';
import { siteUrl } from '../base/siteUrl.ts';
import { logLogSlope } from '../base/sweep.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { workerJobs } from '../../workers/compute.ts';
import type { jobs } from './jobs.ts';
import {
  CPU_HEIGHT,
  CPU_SPP_CAP,
  CPU_WIDTH,
  DISPLAY_EXPOSURE,
  GPU_HEIGHT,
  GPU_WIDTH,
  IMAGE_SEED,
  REFERENCE_FACTOR,
  REFERENCE_SEED,
  buildScene,
  inputsFrom,
  sceneKey,
  type SingleScatterInputs,
} from './model.ts';
import { TIMING_REPEATS, type KernelTimes, type SingleScatterFrame } from './widget.ts';
import { context2d } from '../base/canvas2d.ts';

/** Time to spend per animation frame (ms): the pass size adapts to it. */
const GPU_FRAME_BUDGET_MS = 12;
const CPU_FRAME_BUDGET_MS = 30;
const MAX_SAMPLES_PER_PASS = 64;
/** Samples per pixel of each timed pass on the GPU (at least; the CPU twin takes 2). */
const TIMING_SAMPLES = 4;

/** Error of the standard-error image's false colour (dark blue → yellow). */
const ERROR_STOPS: readonly [number, number, number][] = [
  [13, 8, 135],
  [126, 3, 168],
  [204, 71, 120],
  [248, 149, 64],
  [240, 249, 33],
];
function errorColour(x: number): [number, number, number] {
  const t = Math.min(Math.max(x, 0), 1) * (ERROR_STOPS.length - 1);
  const i = Math.min(Math.floor(t), ERROR_STOPS.length - 2);
  const f = t - i;
  const a = ERROR_STOPS[i]!;
  const b = ERROR_STOPS[i + 1]!;
  return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])];
}

/** A progressive render of one scene: its renderer (which accumulates) and pass size. */
interface Progressive {
  renderer: PassRenderer;
  perPass: number;
  /** Sum of the passes' measured times (ms). */
  elapsedMs: number;
  timing: PassTiming;
}

/** The image's state at a number of samples: for the error-against-time plot. */
interface Snapshot {
  samples: number;
  elapsedMs: number;
  /** A frozen copy of the moments (a GPU buffer copy on WebGPU). */
  image: Accumulation;
  /** RMSE against the reference, and the reference's sample count it was measured at. */
  error: { rmse: number; referenceSamples: number } | null;
}

/** Mean over pixels and channels of the variance of one sample, s² = n·SE². */
async function meanSampleVariance(accumulation: Accumulation): Promise<number> {
  const stats = await accumulation.statistics();
  return stats.rmsStandardError ** 2 * stats.samples;
}

interface Run {
  key: string;
  width: number;
  height: number;
  plan: Plan;
  main: Progressive;
  snapshots: Snapshot[];
  nextSnapshot: number;
  lastFrameMs: number;
}

const median = (values: number[]): number => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)]!;
};

/** The CPU twin's passes run in the compute worker (jobs.ts), off the page's thread. */
const cpuJobs = workerJobs<typeof jobs>('single-scatter');

async function makeRenderer(
  backend: Backend<GpuContext>,
  resolved: ResolvedScene,
  conditions: Conditions,
  /** The signal a CPU pass listens to: the input signal of the moment it is asked for. */
  inputSignal: () => AbortSignal,
): Promise<PassRenderer> {
  const packed = packScene(resolved);
  if (backend.kind === 'gpu')
    return GpuSceneRenderer.create(backend.gpu.device, STATIC_KERNELS, packed, conditions);
  return new WorkerSceneRenderer(
    cpuJobs,
    sceneData(packed, conditions),
    packed.width,
    packed.height,
    packed.seed,
    inputSignal,
  );
}

/** One pass of an accumulation, sized to the frame budget from the last pass's cost. */
async function step(accumulation: Progressive, target: number, budgetMs: number): Promise<number> {
  const have = accumulation.renderer.accumulation.samples;
  const samples = Math.min(accumulation.perPass, target - have);
  if (samples <= 0) return 0;
  const output = await accumulation.renderer.renderPass(have, samples);
  accumulation.elapsedMs += output.milliseconds;
  accumulation.timing = output.timing ?? accumulation.renderer.timing;
  const perSample = output.milliseconds / samples;
  accumulation.perPass = Math.max(
    1,
    Math.min(MAX_SAMPLES_PER_PASS, Math.floor(budgetMs / Math.max(perSample, 1e-3))),
  );
  return output.milliseconds;
}

/** What show() draws besides the readouts, kept from the frame's run. */
interface Drawn {
  scale: number;
  errors: number[];
  snapshots: readonly Snapshot[];
  integrator: string;
}

export function createView(
  context: ViewContext<GpuContext>,
): WidgetView<SingleScatterFrame, GpuContext> {
  // Canvases swap themselves between a WebGPU and a 2D context (canvasForContext), so
  // they are the view's, not the base's managed ones; always read them from here.
  let imageElement = imageCanvas('Single-scattering image', GPU_WIDTH, GPU_HEIGHT);
  let errorElement = imageCanvas('Per-pixel standard error', GPU_WIDTH, GPU_HEIGHT);
  let errorScale: HTMLElement | null = null;
  let planBody: HTMLTableSectionElement | null = null;
  let planCaption: HTMLElement | null = null;
  let plot: LinePlot | null = null;
  let progress: HTMLProgressElement | null = null;
  let measureButton: HTMLButtonElement | null = null;
  let run: Run | null = null;
  let generation = 0;
  let drawn: Drawn | null = null;
  /** References per backend and scene: their accumulations go on as the target grows. */
  const references = new Map<string, Progressive>();
  /** The WebGPU pictures of the two canvases, made for one device. */
  let views: { device: GPUDevice; image: AccumulationView; error: AccumulationView } | null = null;
  const kernelTimes = new Map<string, KernelTimes>();
  let remeasure = false;
  const resolvedCache = new Map<string, Promise<ResolvedScene>>();
  /** The signal a CPU pass listens to: that of the frame being drawn (ViewContext.frameSignal). */
  const inputSignal = (): AbortSignal => context.frameSignal;

  const disposeRun = (): void => {
    run?.main.renderer.destroy();
    for (const snapshot of run?.snapshots ?? []) snapshot.image.destroy();
    run = null;
    generation++;
  };

  /** Everything GPU-side and cached per backend (device loss, a failed GPU frame, destroy). */
  const resetAll = (): void => {
    disposeRun();
    for (const reference of references.values()) reference.renderer.destroy();
    references.clear();
    kernelTimes.clear();
    views?.image.destroy();
    views?.error.destroy();
    views = null;
  };

  /** Reads a grid file under public/ (the smoke) once per page. */
  const resolve = (
    inputs: SingleScatterInputs,
    seed: number,
    width: number,
    height: number,
  ): Promise<ResolvedScene> => {
    const scene = parseScene(buildScene(inputs, { width, height, spp: inputs.spp, seed }));
    const cacheKey = `${sceneKey(inputs)}|${seed}|${width}`;
    let resolved = resolvedCache.get(cacheKey);
    if (!resolved) {
      resolved = resolveScene(scene, async (path) => {
        const response = await fetch(siteUrl(path));
        if (!response.ok) throw new Error(`HTTP ${response.status}`);
        return new Uint8Array(await response.arrayBuffer());
      });
      resolved.catch(() => resolvedCache.delete(cacheKey));
      resolvedCache.set(cacheKey, resolved);
    }
    return resolved;
  };

  /**
   * Median time per sample per pixel of the plan's kernel and of the general kernel on
   * the same scene, pass size and seed, alternating so that both see the same load. It
   * runs in a background frame: an input stops it between passes (`signal`), so the
   * new picture does not wait for the remaining repeats.
   */
  const timeKernels = async (
    inputs: SingleScatterInputs,
    backend: Backend<GpuContext>,
    width: number,
    height: number,
    signal: AbortSignal,
  ): Promise<KernelTimes> => {
    const resolved = await resolve(inputs, IMAGE_SEED, width, height);
    const specialized = await makeRenderer(
      backend,
      resolved,
      plan(resolved.scene).conditions,
      inputSignal,
    );
    let general: PassRenderer | null = null;
    const samples = backend.kind === 'gpu' ? Math.max(TIMING_SAMPLES, run?.main.perPass ?? 1) : 2;
    const planTimes: number[] = [];
    const generalTimes: number[] = [];
    let timing: PassTiming = specialized.timing;
    try {
      signal.throwIfAborted();
      // The general kernel compiles here, in the background, on first use (it used to be
      // compiled ahead at the first preview, where the compile held up the next input's
      // picture: bench/firstPictureProbe.ts).
      general = await makeRenderer(backend, resolved, GENERAL_CONDITIONS, inputSignal);
      for (let i = 0; i < TIMING_REPEATS; i++) {
        signal.throwIfAborted();
        // Different samples in each repeat, the same ones for both kernels.
        const a = await specialized.renderPass(i * samples, samples);
        const b = await general.renderPass(i * samples, samples);
        planTimes.push(a.milliseconds / samples);
        generalTimes.push(b.milliseconds / samples);
        timing = a.timing ?? specialized.timing;
      }
      return {
        planMs: median(planTimes),
        generalMs: median(generalTimes),
        planVariance: await meanSampleVariance(specialized.accumulation),
        generalVariance: await meanSampleVariance(general.accumulation),
        timing,
        samples,
      };
    } finally {
      specialized.destroy();
      general?.destroy();
    }
  };

  const showPlan = (scenePlan: Plan): void => {
    if (!planBody) return;
    planBody.replaceChildren();
    for (const effect of scenePlan.effects) {
      const row = planBody.insertRow();
      row.dataset['effect'] = effect.effect;
      row.dataset['enabled'] = String(effect.enabled);
      row.className = effect.enabled ? 'sb-ss-on' : 'sb-ss-off';
      const name = document.createElement('th');
      name.scope = 'row';
      name.textContent = effect.effect;
      row.appendChild(name);
      row.insertCell().textContent = effect.enabled ? 'compiled' : 'skipped';
      row.insertCell().textContent = effect.method ?? '—';
      row.insertCell().textContent = effect.reason;
    }
    const compiled = scenePlan.effects.filter((e) => e.enabled).length;
    if (planCaption)
      planCaption.textContent = `The plan: ${scenePlan.integrator}, ${compiled} of ${scenePlan.effects.length} effects compiled`;
  };

  /**
   * Draws the radiance and the per-pixel standard error: on WebGPU straight from the
   * moments on the GPU (render passes, no read-back); for the CPU twin, on the host.
   */
  const paint = async (current: Run, scale: number): Promise<void> => {
    const accumulation = current.main.renderer.accumulation;
    const radiance: AccumulationPicture = { kind: 'radiance', exposure: DISPLAY_EXPOSURE };
    const error: AccumulationPicture = { kind: 'standard-error', scale };
    if (accumulation instanceof GpuAccumulation) {
      imageElement = canvasForContext(imageElement, 'webgpu');
      errorElement = canvasForContext(errorElement, 'webgpu');
      const { device } = accumulation;
      if (views?.device !== device) {
        views?.image.destroy();
        views?.error.destroy();
        views = {
          device,
          image: await AccumulationView.create(device, STATIC_KERNELS, imageElement),
          error: await AccumulationView.create(device, STATIC_KERNELS, errorElement),
        };
      }
      await views.image.draw(accumulation, radiance);
      await views.error.draw(accumulation, error);
      return;
    }
    imageElement = canvasForContext(imageElement, '2d');
    errorElement = canvasForContext(errorElement, '2d');
    const { width, height } = current;
    const image: ImageAccumulator = await accumulation.readImage();
    const rgba = toneMapRgba8(width, height, image.mean(), DISPLAY_EXPOSURE);
    context2d(imageElement)?.putImageData(
      new ImageData(new Uint8ClampedArray(rgba), width, height),
      0,
      0,
    );
    // Standard error per pixel: the mean over the three channels, on a rounded scale.
    const standardError = image.standardError();
    const errorImage = new ImageData(width, height);
    for (let i = 0; i < width * height; i++) {
      const e = (standardError[3 * i]! + standardError[3 * i + 1]! + standardError[3 * i + 2]!) / 3;
      const [r, g, b] = errorColour((Number.isFinite(e) ? e : 0) / scale);
      errorImage.data.set([r, g, b, 255], 4 * i);
    }
    context2d(errorElement)?.putImageData(errorImage, 0, 0);
  };

  /** Paints the run and gathers the frame (null: the run was replaced meanwhile). */
  const collect = async (
    current: Run,
    reference: Progressive | null,
    target: number,
    referenceTarget: number,
    times: KernelTimes | null,
    stage: Refinement,
  ): Promise<SingleScatterFrame | null> => {
    const accumulation = current.main.renderer.accumulation;
    // Null in a preview whose scene has no reference yet (it is made after the preview).
    const referenceAccumulation = reference?.renderer.accumulation ?? null;
    const referenceSamples = referenceAccumulation?.samples ?? 0;
    const referenceDone = referenceAccumulation !== null && referenceSamples >= referenceTarget;
    const started = generation;
    // One reduction: the readouts' numbers, and the RMSE against the finished reference.
    const stats = await accumulation.statistics(
      referenceDone && referenceAccumulation ? referenceAccumulation : undefined,
    );
    if (started !== generation) return null;
    // The error map's top colour: the largest channel-averaged standard error, rounded.
    const largest = stats.maxPixelStandardError;
    const scale = largest > 0 ? niceScale(largest) : 1;
    await paint(current, scale);
    if (started !== generation) return null;
    // Each snapshot against the reference once (again only if the reference grew).
    if (referenceDone && referenceAccumulation)
      for (const snapshot of current.snapshots) {
        if (snapshot.error?.referenceSamples === referenceSamples) continue;
        const against = await snapshot.image.statistics(referenceAccumulation);
        if (started !== generation) return null;
        snapshot.error = { rmse: against.rmse, referenceSamples };
      }
    const fitted = current.snapshots.filter((s) => s.samples >= 4);
    const slope =
      referenceDone && fitted.length >= 3
        ? logLogSlope(
            fitted.map((s) => s.samples),
            fitted.map((s) => s.error?.rmse ?? NaN),
          )
        : null;
    drawn = {
      scale,
      errors: referenceDone ? current.snapshots.map((s) => s.error?.rmse ?? NaN) : [],
      snapshots: current.snapshots,
      integrator: current.plan.integrator,
    };
    return {
      width: current.width,
      height: current.height,
      samples: accumulation.samples,
      target,
      rmsStandardError: stats.rmsStandardError,
      reference: { samples: referenceSamples, target: referenceTarget, done: referenceDone },
      rmse: referenceDone ? stats.rmse : NaN,
      slope,
      lastFrameMs: current.lastFrameMs,
      perPass: current.main.perPass,
      elapsedMs: current.main.elapsedMs,
      timing: current.main.timing,
      times,
      stage,
    };
  };

  /**
   * One frame on a backend: a pass of the image, a pass of the reference, the kernel
   * timing once the reference is done; null when the run was replaced meanwhile.
   */
  const frame = async (
    inputs: SingleScatterInputs,
    backend: Backend<GpuContext>,
    request: Pick<FrameRequest, 'signal'>,
  ): Promise<SingleScatterFrame | null> => {
    const gpu = backend.kind === 'gpu';
    const width = gpu ? GPU_WIDTH : CPU_WIDTH;
    const height = gpu ? GPU_HEIGHT : CPU_HEIGHT;
    const target = gpu ? inputs.spp : Math.min(inputs.spp, CPU_SPP_CAP);
    const budget = gpu ? GPU_FRAME_BUDGET_MS : CPU_FRAME_BUDGET_MS;
    const key = `${backend.kind}|${sceneKey(inputs)}`;

    if (!run || run.key !== key) {
      disposeRun();
      const started = generation;
      const resolved = await resolve(inputs, IMAGE_SEED, width, height);
      const scenePlan = plan(resolved.scene);
      const renderer = await makeRenderer(backend, resolved, scenePlan.conditions, inputSignal);
      if (started !== generation) {
        renderer.destroy();
        context.scheduleRender();
        return null;
      }
      run = {
        key,
        width,
        height,
        plan: scenePlan,
        main: { renderer, perPass: 1, elapsedMs: 0, timing: renderer.timing },
        snapshots: [],
        nextSnapshot: 1,
        lastFrameMs: 0,
      };
      showPlan(scenePlan);
      for (const canvas of [imageElement, errorElement]) {
        canvas.width = width;
        canvas.height = height;
      }
    }
    const current = run;
    const started = generation;
    let busy = false;
    // The first frame of a run is its preview: one pass of the image and nothing else
    // (no reference renderer to make, no reference pass, no kernel timing), so a new
    // scene is on screen as soon as its kernel is compiled.
    const preview = current.main.renderer.accumulation.samples === 0;

    // 1. The progressive image: one pass sized to the frame budget.
    if (current.main.renderer.accumulation.samples < target) {
      current.lastFrameMs = await step(current.main, target, budget);
      if (started !== generation) return null;
      const samples = current.main.renderer.accumulation.samples;
      if (samples >= current.nextSnapshot || samples >= target) {
        current.snapshots.push({
          samples,
          elapsedMs: current.main.elapsedMs,
          image: current.main.renderer.accumulation.snapshot(),
          error: null,
        });
        while (current.nextSnapshot <= samples) current.nextSnapshot *= 2;
      }
      busy = true;
    }

    // A new input stops the old scene here (its frame is dropped; the next draws the new one).
    if (request.signal.aborted) return null;

    // 2. The reference (cached per scene): REFERENCE_FACTOR × the target, another seed.
    const referenceTarget = REFERENCE_FACTOR * target;
    let reference = references.get(key);
    if (preview) {
      const result = await collect(current, reference ?? null, target, referenceTarget, null, {
        label: `Preview: ${current.main.renderer.accumulation.samples} of ${target} spp`,
        pending: 'frame',
      });
      return started === generation ? result : null;
    }
    if (!reference) {
      const resolved = await resolve(inputs, REFERENCE_SEED, width, height);
      const renderer = await makeRenderer(
        backend,
        resolved,
        plan(resolved.scene).conditions,
        inputSignal,
      );
      if (started !== generation) {
        renderer.destroy();
        context.scheduleRender();
        return null;
      }
      reference = { renderer, perPass: 1, elapsedMs: 0, timing: renderer.timing };
      references.set(key, reference);
    }
    if (reference.renderer.accumulation.samples < referenceTarget && !request.signal.aborted) {
      await step(reference, referenceTarget, busy ? budget : 2 * budget);
      if (started !== generation) return null;
      busy = true;
    }
    // An input meanwhile: the rest (timing, statistics, drawing) is for a stale picture, and
    // the input's first picture would wait for it.
    if (request.signal.aborted) return null;
    const referenceDone = reference.renderer.accumulation.samples >= referenceTarget;

    // 3. Specialized against general kernel, once per scene (or on request), after the reference.
    if (referenceDone && (remeasure || !kernelTimes.has(key)) && !request.signal.aborted) {
      remeasure = false;
      context.setReadout('saved', 'timing both kernels…');
      const times = await timeKernels(inputs, backend, width, height, request.signal);
      if (started !== generation) return null;
      kernelTimes.set(key, times);
    }
    if (request.signal.aborted) return null;

    const result = await collect(
      current,
      reference,
      target,
      referenceTarget,
      kernelTimes.get(key) ?? null,
      {
        label: `${current.main.renderer.accumulation.samples} of ${target} spp${
          reference.renderer.accumulation.samples >= referenceTarget
            ? ''
            : `, reference ${reference.renderer.accumulation.samples} of ${referenceTarget}`
        }`,
        // Complete: while this frame had work (image, reference or timing), the next
        // frames go on with it as background refinement of a settled picture.
        pending: busy ? 'background' : null,
      },
    );
    if (started !== generation || request.signal.aborted) return null;
    return result;
  };

  const renderOn = async (
    backend: Backend<GpuContext>,
    request: FrameRequest,
  ): Promise<SingleScatterFrame | null> => {
    // Captured: the context's signal is a fresh one once the widget is destroyed.
    const signal = context.signal;
    try {
      return await frame(inputsFrom(context.values), backend, request);
    } catch (error) {
      // Destroyed mid-frame (its renderers released under it), or a stale frame given up.
      if (signal.aborted || request.signal.aborted) return null;
      throw error;
    }
  };

  return {
    cpuNotice: `Showing the float64 CPU twin of the same kernel at ${CPU_WIDTH}×${CPU_HEIGHT} pixels, up to ${CPU_SPP_CAP} samples per pixel.`,
    build(stage) {
      const error = imagePanel(errorElement, 'Standard error of each pixel', {
        gradient: gradientCss(errorColour),
        low: '0',
        top: { readout: 'error-scale' },
      });
      errorScale = error.top;
      stage.appendChild(
        imageFigure(
          imagePanel(imageElement, `Radiance (exposure +${DISPLAY_EXPOSURE} EV)`).panel,
          error.panel,
        ),
      );

      const planTable = document.createElement('table');
      planTable.className = 'sb-ss-plan';
      planCaption = document.createElement('caption');
      planTable.appendChild(planCaption);
      const head = planTable.createTHead().insertRow();
      for (const title of ['Effect', 'Compiled?', 'Method', 'Why']) {
        const th = document.createElement('th');
        th.scope = 'col';
        th.textContent = title;
        head.appendChild(th);
      }
      planBody = planTable.createTBody();
      const planWrap = document.createElement('div');
      planWrap.className = 'sb-ss-plan-wrap';
      planWrap.appendChild(planTable);
      stage.appendChild(planWrap);

      const bar = document.createElement('div');
      bar.className = 'sb-sweep';
      const restart = document.createElement('button');
      restart.type = 'button';
      restart.className = 'sb-button';
      restart.textContent = 'Restart accumulation';
      restart.addEventListener('click', () => {
        disposeRun();
        context.scheduleRender();
      });
      const measure = document.createElement('button');
      measure.type = 'button';
      measure.className = 'sb-button';
      measure.textContent = 'Time the kernels again';
      measure.addEventListener('click', () => {
        remeasure = true;
        context.scheduleRender();
      });
      measureButton = measure;
      progress = document.createElement('progress');
      progress.max = 1;
      progress.value = 0;
      progress.setAttribute('aria-label', 'Reference progress');
      const progressLabel = document.createElement('span');
      progressLabel.className = 'sb-sweep-status';
      progressLabel.textContent = 'reference';
      bar.append(restart, measure, progressLabel, progress);
      stage.appendChild(bar);

      const hint = document.createElement('p');
      hint.className = 'sb-sweep-hint';
      hint.textContent =
        'RMSE of the progressive image against the reference, against the accumulated time, on log–log axes; Monte Carlo error falls as time^−½ (dashed).';
      const plotArea = createPlotArea('Log–log plot of RMSE against accumulated time');
      stage.append(hint, plotArea);
      plot = new LinePlot(plotArea, {
        xLabel: 'log₁₀ accumulated time (ms)',
        yLabel: 'RMSE',
        yLog: true,
        height: 200,
      });
    },
    // The scene renderers take the device; they are made per run and per reference.
    createRenderer: (gpu: GpuContext) => gpu,
    renderGpu: (renderer, gpu, request) => renderOn({ kind: 'gpu', gpu, renderer }, request),
    renderCpu: (request) => renderOn({ kind: 'cpu', reason: '' }, request),
    refinement: (shown) => shown.stage,
    onCpuFallback: resetAll,
    destroy: resetAll,
    show(shown) {
      const host = context.host;
      if (drawn && errorScale) errorScale.textContent = formatNumber(drawn.scale, 2);
      host.dataset['referenceDone'] = String(shown.reference.done);
      if (progress) {
        progress.max = shown.reference.target;
        progress.value = shown.reference.samples;
      }
      if (shown.reference.done) host.dataset['error'] = String(shown.rmse);
      else delete host.dataset['error'];
      host.dataset['spp'] = String(shown.samples);
      const { times } = shown;
      if (times) {
        host.dataset['planMs'] = String(times.planMs);
        host.dataset['generalMs'] = String(times.generalMs);
        host.dataset['planVariance'] = String(times.planVariance);
        host.dataset['generalVariance'] = String(times.generalVariance);
      }
      if (measureButton) measureButton.disabled = !times;
      if (drawn && plot && drawn.errors.length > 0) {
        const { errors, snapshots } = drawn;
        const x = snapshots.map((s) => Math.log10(Math.max(s.elapsedMs, 1e-4)));
        const first = snapshots[0]!;
        const slopeLine = snapshots.map(
          (s) => errors[0]! * Math.sqrt(first.elapsedMs / Math.max(s.elapsedMs, 1e-9)),
        );
        plot.update(x, [
          { label: 'RMSE', color: '#d9822b', values: errors },
          { label: 'slope −½', color: '#888888', dash: [6, 4], values: slopeLine },
        ]);
      }
      imageElement.setAttribute(
        'aria-label',
        `Single-scattering image, ${shown.samples} samples per pixel, ${drawn?.integrator ?? ''}`,
      );
    },
  };
}
