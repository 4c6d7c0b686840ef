// <sb-single-scatter>: single scattering through fog or smoke (chapter 9), rendered by
// the scene engine (src/scene/) from a scene the widget builds (model.ts). The image
// accumulates progressively, a few samples per pixel per animation frame, with its
// per-pixel standard error; a reference of the same scene with eight times the samples
// and another seed (cached per scene) gives the error, plotted against the accumulated
// GPU time on log–log axes next to the slope −½ of Monte Carlo. The plan of the scene
// (src/scene/plan.ts) is listed effect by effect, and the specialized kernel's time per
// sample is measured against the general kernel's (DESIGN.md contract 3). On WebGPU the
// image accumulates on the GPU and both pictures are drawn from there
// (src/scene/accumulationView.ts); a frame reads back only reduced statistics.
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { GpuContext } from '../../gpu/device.ts';
import type { Accumulation, ImageAccumulator } from '../../scene/accumulation.ts';
import {
  AccumulationView,
  canvasForContext,
  type AccumulationPicture,
} from '../../scene/accumulationView.ts';
import { CpuSceneRenderer } from '../../scene/cpuRenderer.ts';
import { GpuAccumulation } from '../../scene/gpuAccumulation.ts';
import { GpuSceneRenderer } from '../../scene/gpuRenderer.ts';
import { toneMapRgba8 } from '../../scene/image.ts';
import { resolveScene, type ResolvedScene } from '../../scene/load.ts';
import { packScene, sceneData } from '../../scene/pack.ts';
import { GENERAL_CONDITIONS, plan, type Conditions, type Plan } from '../../scene/plan.ts';
import type { PassRenderer, PassTiming } from '../../scene/render.ts';
import { parseScene } from '../../scene/validate.ts';
import { BackendChooser, type Backend, gpuFailureReason } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import {
  gradientCss,
  imageCanvas,
  imageFigure,
  imagePanel,
  niceScale,
} from '../base/imagePanel.ts';
import { LinePlot } from '../base/plot.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { logLogSlope } from '../base/sweep.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
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
import { SINGLE_SCATTER } from './schema.ts';
import { siteUrl } from '../base/siteUrl.ts';

const READOUT_ROWS = [
  ['spp', 'Samples per pixel so far'],
  ['std-error', 'Per-pixel standard error (RMS)'],
  ['error', 'RMSE against the reference'],
  ['reference', 'Reference'],
  ['slope', 'Fitted slope, log RMSE vs log spp'],
  ['frame', 'Last frame (GPU time)'],
  ['time-plan', 'Time per sample, specialized kernel'],
  ['time-general', 'Time per sample, general kernel'],
  ['saved', 'Time the plan saves'],
] as const;

/** Time to spend per animation frame (ms): the pass size adapts to it. */
const GPU_FRAME_BUDGET_MS = 12;
const CPU_FRAME_BUDGET_MS = 30;
const MAX_SAMPLES_PER_PASS = 64;
/** Timed passes per kernel for the specialized-versus-general comparison (median). */
const TIMING_REPEATS = 3;
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

type Renderer = GpuContext;

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

/**
 * The two kernels on the same scene: time per sample per pixel and the variance of one
 * sample (mean over pixels and channels). Time per sample alone is not the cost of an
 * image: the specialized estimator may spend more per sample (an equiangular point and
 * its shadow ray per spot light) to get less variance. The time to reach a given error
 * is proportional to variance × time per sample (the inverse of the efficiency).
 */
interface KernelTimes {
  planMs: number;
  generalMs: number;
  planVariance: number;
  generalVariance: number;
  timing: PassTiming;
  samples: number;
}

/** Mean over pixels and channels of the variance of one sample, s² = n·SE². */
async function meanSampleVariance(accumulation: Accumulation): Promise<number> {
  const stats = await accumulation.statistics();
  return stats.rmsStandardError ** 2 * stats.samples;
}

interface Run {
  key: string;
  backend: 'gpu' | 'cpu';
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

export class SingleScatterElement extends WidgetElement {
  protected readonly entry = SINGLE_SCATTER;
  protected override presets: readonly Preset[] = [
    {
      label: 'spot light, fog, sphere',
      values: { light: 'spot', medium: 'fog', occluder: 'sphere', scattering: 'on' },
    },
    {
      label: 'sun through fog, box',
      values: { light: 'directional', medium: 'fog', occluder: 'box', scattering: 'on' },
    },
    {
      label: 'smoke grid in the spot',
      values: { light: 'spot', medium: 'smoke', occluder: 'sphere', scattering: 'on' },
    },
    {
      label: 'no scattering, glowing fog',
      values: { scattering: 'off', emission: 'on', albedo: 0.5, floor: 'off', occluder: 'none' },
    },
  ];

  private imageCanvas: HTMLCanvasElement | null = null;
  private errorCanvas: HTMLCanvasElement | null = null;
  private errorScale: HTMLElement | null = null;
  private planBody: HTMLTableSectionElement | null = null;
  private planCaption: HTMLElement | null = null;
  private plot: LinePlot | null = null;
  private progress: HTMLProgressElement | null = null;
  private measureButton: HTMLButtonElement | null = null;
  private readouts: ReadoutList | null = null;
  private run: Run | null = null;
  private generation = 0;
  /** References per backend and scene: their accumulations go on as the target grows. */
  private readonly references = new Map<string, Progressive>();
  /** The WebGPU pictures of the two canvases, made for one device. */
  private views: { device: GPUDevice; image: AccumulationView; error: AccumulationView } | null =
    null;
  private readonly kernelTimes = new Map<string, KernelTimes>();
  private remeasure = false;
  private readonly resolvedCache = new Map<string, Promise<ResolvedScene>>();
  private readonly backends = new BackendChooser<Renderer>(
    (gpu) => gpu,
    () => {
      this.resetAll();
      this.scheduleRender();
    },
  );

  protected buildStage(stage: HTMLElement): void {
    this.imageCanvas = imageCanvas('Single-scattering image', GPU_WIDTH, GPU_HEIGHT);
    this.errorCanvas = imageCanvas('Per-pixel standard error', GPU_WIDTH, GPU_HEIGHT);
    const error = imagePanel(this.errorCanvas, 'Standard error of each pixel', {
      gradient: gradientCss(errorColour),
      low: '0',
      top: { readout: 'error-scale' },
    });
    this.errorScale = error.top;
    stage.appendChild(
      imageFigure(
        imagePanel(this.imageCanvas, `Radiance (exposure +${DISPLAY_EXPOSURE} EV)`).panel,
        error.panel,
      ),
    );

    const planTable = document.createElement('table');
    planTable.className = 'sb-ss-plan';
    this.planCaption = document.createElement('caption');
    planTable.appendChild(this.planCaption);
    const head = planTable.createTHead().insertRow();
    for (const title of ['Effect', 'Compiled?', 'Method', 'Why']) {
      const th = document.createElement('th');
      th.scope = 'col';
      th.textContent = title;
      head.appendChild(th);
    }
    this.planBody = planTable.createTBody();
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
      this.disposeRun();
      this.scheduleRender();
    });
    this.measureButton = document.createElement('button');
    this.measureButton.type = 'button';
    this.measureButton.className = 'sb-button';
    this.measureButton.textContent = 'Time the kernels again';
    this.measureButton.addEventListener('click', () => {
      this.remeasure = true;
      this.scheduleRender();
    });
    this.progress = document.createElement('progress');
    this.progress.max = 1;
    this.progress.value = 0;
    this.progress.setAttribute('aria-label', 'Reference progress');
    const progressLabel = document.createElement('span');
    progressLabel.className = 'sb-sweep-status';
    progressLabel.textContent = 'reference';
    bar.append(restart, this.measureButton, progressLabel, this.progress);
    stage.appendChild(bar);

    const hint = document.createElement('p');
    hint.className = 'sb-sweep-hint';
    hint.textContent =
      'RMSE of the progressive image against the reference, against the accumulated time, on log–log axes; Monte Carlo error falls as time^−½ (dashed).';
    const plotArea = document.createElement('div');
    plotArea.className = 'sb-plot';
    plotArea.setAttribute('role', 'img');
    plotArea.setAttribute('aria-label', 'Log–log plot of RMSE against accumulated time');
    stage.append(hint, plotArea);
    this.plot = new LinePlot(plotArea, {
      xLabel: 'log₁₀ accumulated time (ms)',
      yLabel: 'RMSE',
      yLog: true,
      height: 200,
    });
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.readouts?.set(key, text, state);
  }

  private resetAll(): void {
    this.disposeRun();
    for (const reference of this.references.values()) reference.renderer.destroy();
    this.references.clear();
    this.kernelTimes.clear();
    this.views?.image.destroy();
    this.views?.error.destroy();
    this.views = null;
  }

  private disposeRun(): void {
    this.run?.main.renderer.destroy();
    for (const snapshot of this.run?.snapshots ?? []) snapshot.image.destroy();
    this.run = null;
    this.generation++;
  }

  override disconnectedCallback(): void {
    super.disconnectedCallback();
    this.resetAll();
  }

  /** Reads a grid file under public/ (the smoke) once per page. */
  private resolve(inputs: SingleScatterInputs, seed: number, width: number, height: number) {
    const scene = parseScene(buildScene(inputs, { width, height, spp: inputs.spp, seed }));
    const cacheKey = `${sceneKey(inputs)}|${seed}|${width}`;
    let resolved = this.resolvedCache.get(cacheKey);
    if (!resolved) {
      resolved = resolveScene(scene, async (path) => {
        const response = await fetch(siteUrl(path));
        if (!response.ok) throw new Error(`HTTP ${response.status}`);
        return new Uint8Array(await response.arrayBuffer());
      });
      resolved.catch(() => this.resolvedCache.delete(cacheKey));
      this.resolvedCache.set(cacheKey, resolved);
    }
    return resolved;
  }

  private async makeRenderer(
    backend: Backend<Renderer>,
    resolved: ResolvedScene,
    conditions: Conditions,
  ): Promise<PassRenderer> {
    const packed = packScene(resolved);
    if (backend.kind === 'gpu')
      return GpuSceneRenderer.create(backend.gpu.device, STATIC_KERNELS, packed, conditions);
    return new CpuSceneRenderer(
      sceneData(packed, conditions),
      packed.width,
      packed.height,
      packed.seed,
    );
  }

  /** One pass of an accumulation, sized to the frame budget from the last pass's cost. */
  private async step(accumulation: Progressive, target: number, budgetMs: number): Promise<number> {
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

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    try {
      await this.frame(inputs, backend);
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.backends.useCpu(gpuFailureReason(error));
      this.resetAll();
      this.scheduleRender();
    }
  }

  private async frame(inputs: SingleScatterInputs, backend: Backend<Renderer>): Promise<void> {
    const gpu = backend.kind === 'gpu';
    const width = gpu ? GPU_WIDTH : CPU_WIDTH;
    const height = gpu ? GPU_HEIGHT : CPU_HEIGHT;
    const target = gpu ? inputs.spp : Math.min(inputs.spp, CPU_SPP_CAP);
    const budget = gpu ? GPU_FRAME_BUDGET_MS : CPU_FRAME_BUDGET_MS;
    const key = `${backend.kind}|${sceneKey(inputs)}`;
    if (gpu) this.clearNotice('backend');
    else
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU twin of the same kernel at ${CPU_WIDTH}×${CPU_HEIGHT} pixels, up to ${CPU_SPP_CAP} samples per pixel.`,
      );

    if (!this.run || this.run.key !== key) {
      this.disposeRun();
      const generation = this.generation;
      const resolved = await this.resolve(inputs, IMAGE_SEED, width, height);
      const scenePlan = plan(resolved.scene);
      const renderer = await this.makeRenderer(backend, resolved, scenePlan.conditions);
      if (generation !== this.generation) {
        renderer.destroy();
        this.scheduleRender();
        return;
      }
      this.run = {
        key,
        backend: backend.kind,
        width,
        height,
        plan: scenePlan,
        main: {
          renderer,
          perPass: 1,
          elapsedMs: 0,
          timing: renderer.timing,
        },
        snapshots: [],
        nextSnapshot: 1,
        lastFrameMs: 0,
      };
      this.showPlan(scenePlan);
      if (this.imageCanvas && this.errorCanvas) {
        for (const canvas of [this.imageCanvas, this.errorCanvas]) {
          canvas.width = width;
          canvas.height = height;
        }
      }
    }
    const run = this.run;
    const generation = this.generation;
    let busy = false;

    // 1. The progressive image: one pass sized to the frame budget.
    if (run.main.renderer.accumulation.samples < target) {
      run.lastFrameMs = await this.step(run.main, target, budget);
      if (generation !== this.generation) return;
      this.recordFrameCost(run.lastFrameMs, timingLabel(run.main.timing));
      const samples = run.main.renderer.accumulation.samples;
      if (samples >= run.nextSnapshot || samples >= target) {
        run.snapshots.push({
          samples,
          elapsedMs: run.main.elapsedMs,
          image: run.main.renderer.accumulation.snapshot(),
          error: null,
        });
        while (run.nextSnapshot <= samples) run.nextSnapshot *= 2;
      }
      busy = true;
    }

    // 2. The reference (cached per scene): REFERENCE_FACTOR × the target, another seed.
    const referenceTarget = REFERENCE_FACTOR * target;
    let reference = this.references.get(key);
    if (!reference) {
      const resolved = await this.resolve(inputs, REFERENCE_SEED, width, height);
      const renderer = await this.makeRenderer(backend, resolved, plan(resolved.scene).conditions);
      if (generation !== this.generation) {
        renderer.destroy();
        this.scheduleRender();
        return;
      }
      reference = {
        renderer,
        perPass: 1,
        elapsedMs: 0,
        timing: renderer.timing,
      };
      this.references.set(key, reference);
    }
    if (reference.renderer.accumulation.samples < referenceTarget) {
      await this.step(reference, referenceTarget, busy ? budget : 2 * budget);
      if (generation !== this.generation) return;
      busy = true;
    }
    const referenceDone = reference.renderer.accumulation.samples >= referenceTarget;

    // 3. Specialized against general kernel, once per scene (or on request), after the reference.
    if (referenceDone && (this.remeasure || !this.kernelTimes.has(key))) {
      this.remeasure = false;
      this.set('saved', 'timing both kernels…');
      const times = await this.timeKernels(inputs, backend, width, height);
      if (generation !== this.generation) return;
      this.kernelTimes.set(key, times);
    }

    await this.show(run, reference, target, referenceTarget, this.kernelTimes.get(key) ?? null);
    if (generation !== this.generation) return;
    if (busy) this.scheduleRender();
  }

  /**
   * Median time per sample per pixel of the plan's kernel and of the general kernel on
   * the same scene, pass size and seed, alternating so that both see the same load.
   */
  private async timeKernels(
    inputs: SingleScatterInputs,
    backend: Backend<Renderer>,
    width: number,
    height: number,
  ): Promise<KernelTimes> {
    const resolved = await this.resolve(inputs, IMAGE_SEED, width, height);
    const specialized = await this.makeRenderer(backend, resolved, plan(resolved.scene).conditions);
    const general = await this.makeRenderer(backend, resolved, GENERAL_CONDITIONS);
    const samples =
      backend.kind === 'gpu' ? Math.max(TIMING_SAMPLES, this.run?.main.perPass ?? 1) : 2;
    const planTimes: number[] = [];
    const generalTimes: number[] = [];
    let timing: PassTiming = specialized.timing;
    try {
      for (let i = 0; i < TIMING_REPEATS; i++) {
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
      general.destroy();
    }
  }

  private showPlan(scenePlan: Plan): void {
    if (!this.planBody) return;
    this.planBody.replaceChildren();
    for (const effect of scenePlan.effects) {
      const row = this.planBody.insertRow();
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
    if (this.planCaption)
      this.planCaption.textContent = `The plan: ${scenePlan.integrator}, ${compiled} of ${scenePlan.effects.length} effects compiled`;
  }

  /**
   * Draws the radiance and the per-pixel standard error: on WebGPU straight from the
   * moments on the GPU (render passes, no read-back); for the CPU twin, on the host.
   */
  private async paint(run: Run, scale: number): Promise<void> {
    const accumulation = run.main.renderer.accumulation;
    const radiance: AccumulationPicture = { kind: 'radiance', exposure: DISPLAY_EXPOSURE };
    const error: AccumulationPicture = { kind: 'standard-error', scale };
    if (!this.imageCanvas || !this.errorCanvas) return;
    if (accumulation instanceof GpuAccumulation) {
      this.imageCanvas = canvasForContext(this.imageCanvas, 'webgpu');
      this.errorCanvas = canvasForContext(this.errorCanvas, 'webgpu');
      const { device } = accumulation;
      if (this.views?.device !== device) {
        this.views?.image.destroy();
        this.views?.error.destroy();
        this.views = {
          device,
          image: await AccumulationView.create(device, STATIC_KERNELS, this.imageCanvas),
          error: await AccumulationView.create(device, STATIC_KERNELS, this.errorCanvas),
        };
      }
      await this.views.image.draw(accumulation, radiance);
      await this.views.error.draw(accumulation, error);
      return;
    }
    this.imageCanvas = canvasForContext(this.imageCanvas, '2d');
    this.errorCanvas = canvasForContext(this.errorCanvas, '2d');
    const { width, height } = run;
    const image: ImageAccumulator = await accumulation.readImage();
    const rgba = toneMapRgba8(width, height, image.mean(), DISPLAY_EXPOSURE);
    this.imageCanvas
      .getContext('2d')
      ?.putImageData(new ImageData(new Uint8ClampedArray(rgba), width, height), 0, 0);
    // Standard error per pixel: the mean over the three channels, on a rounded scale.
    const standardError = image.standardError();
    const errorImage = new ImageData(width, height);
    for (let i = 0; i < width * height; i++) {
      const e = (standardError[3 * i]! + standardError[3 * i + 1]! + standardError[3 * i + 2]!) / 3;
      const [r, g, b] = errorColour((Number.isFinite(e) ? e : 0) / scale);
      errorImage.data.set([r, g, b, 255], 4 * i);
    }
    this.errorCanvas.getContext('2d')?.putImageData(errorImage, 0, 0);
  }

  private async show(
    run: Run,
    reference: Progressive,
    target: number,
    referenceTarget: number,
    times: KernelTimes | null,
  ): Promise<void> {
    const accumulation = run.main.renderer.accumulation;
    const referenceAccumulation = reference.renderer.accumulation;
    const referenceSamples = referenceAccumulation.samples;
    const referenceDone = referenceSamples >= referenceTarget;
    const generation = this.generation;
    // One reduction: the readouts' numbers, and the RMSE against the finished reference.
    const stats = await accumulation.statistics(referenceDone ? referenceAccumulation : undefined);
    if (generation !== this.generation) return;
    // The error map's top colour: the largest channel-averaged standard error, rounded.
    const largest = stats.maxPixelStandardError;
    const scale = largest > 0 ? niceScale(largest) : 1;
    await this.paint(run, scale);
    if (generation !== this.generation) return;
    if (this.errorScale) this.errorScale.textContent = formatNumber(scale, 2);
    // Each snapshot against the reference once (again only if the reference grew).
    if (referenceDone)
      for (const snapshot of run.snapshots) {
        if (snapshot.error?.referenceSamples === referenceSamples) continue;
        const against = await snapshot.image.statistics(referenceAccumulation);
        if (generation !== this.generation) return;
        snapshot.error = { rmse: against.rmse, referenceSamples };
      }

    const { width, height } = run;
    const samples = accumulation.samples;
    this.set('spp', `${samples} of ${target}`, samples >= target ? 'ok' : undefined);
    // One sample has no sample variance (the accumulator returns NaN): say so.
    this.set(
      'std-error',
      samples < 2 ? 'needs ≥ 2 samples' : formatNumber(stats.rmsStandardError, 3),
    );
    this.dataset['referenceDone'] = String(referenceDone);
    if (this.progress) {
      this.progress.max = referenceTarget;
      this.progress.value = referenceSamples;
    }
    this.set(
      'reference',
      referenceDone
        ? `${referenceTarget} spp, another seed (cached)`
        : `computing: ${referenceSamples} of ${referenceTarget} spp`,
    );

    const errors = referenceDone ? run.snapshots.map((s) => s.error?.rmse ?? NaN) : [];
    if (referenceDone) {
      const current = stats.rmse;
      this.set('error', formatNumber(current, 3));
      this.dataset['error'] = String(current);
    } else {
      this.set('error', 'waiting for the reference');
      delete this.dataset['error'];
    }
    this.dataset['spp'] = String(samples);
    const fitted = run.snapshots.filter((s) => s.samples >= 4);
    const slope =
      referenceDone && fitted.length >= 3
        ? logLogSlope(
            fitted.map((s) => s.samples),
            fitted.map((s) => s.error?.rmse ?? NaN),
          )
        : null;
    this.set(
      'slope',
      slope === null
        ? 'needs the reference and 16 spp'
        : `${formatNumber(slope, 2)} (expected −0.5)`,
    );
    this.set(
      'frame',
      `${formatMilliseconds(run.lastFrameMs)}, ${run.main.perPass} spp per pass (${timingLabel(run.main.timing)})`,
    );

    if (times) {
      const label = times.timing === 'cpu' ? 'CPU wall time' : timingLabel(times.timing);
      this.set(
        'time-plan',
        `${formatMilliseconds(times.planMs)} per spp, variance ${formatNumber(times.planVariance, 3)} (${label})`,
      );
      this.set(
        'time-general',
        `${formatMilliseconds(times.generalMs)} per spp, variance ${formatNumber(times.generalVariance, 3)}`,
      );
      // Time to a given error ∝ variance × time per sample.
      const planCost = times.planVariance * times.planMs;
      const generalCost = times.generalVariance * times.generalMs;
      const perSample = 1 - times.planMs / times.generalMs;
      const equalError = 1 - planCost / generalCost;
      this.set(
        'saved',
        `${formatNumber(100 * equalError, 2)} % of the time to the same error (${formatNumber(100 * perSample, 2)} % per sample)`,
        equalError > 0 ? 'ok' : 'bad',
      );
      this.dataset['planMs'] = String(times.planMs);
      this.dataset['generalMs'] = String(times.generalMs);
      this.dataset['planVariance'] = String(times.planVariance);
      this.dataset['generalVariance'] = String(times.generalVariance);
    } else {
      this.set('time-plan', 'after the reference');
      this.set('time-general', 'after the reference');
      if (!referenceDone) this.set('saved', 'after the reference');
    }
    if (this.measureButton) this.measureButton.disabled = !times;

    if (this.plot && errors.length > 0) {
      const x = run.snapshots.map((s) => Math.log10(Math.max(s.elapsedMs, 1e-4)));
      const first = run.snapshots[0]!;
      const slopeLine = run.snapshots.map(
        (s) => errors[0]! * Math.sqrt(first.elapsedMs / Math.max(s.elapsedMs, 1e-9)),
      );
      this.plot.update(x, [
        { label: 'RMSE', color: '#d9822b', values: errors },
        { label: 'slope −½', color: '#888888', dash: [6, 4], values: slopeLine },
      ]);
    }

    const where =
      run.backend === 'gpu'
        ? `WebGPU: ${width}×${height} pixels`
        : `CPU fallback (float64 twin): ${width}×${height} pixels`;
    if (this.readouts)
      this.readouts.cost.textContent = `${where}, ${samples} spp in ${formatMilliseconds(run.main.elapsedMs)} of ${run.main.timing === 'cpu' ? 'CPU' : 'GPU'} time (${timingLabel(run.main.timing)}). Reference: ${REFERENCE_FACTOR}× the target samples with an independent seed, computed once per scene${times ? `; kernels timed over ${TIMING_REPEATS} passes of ${times.samples} spp each, median` : ''}.`;
    if (this.imageCanvas)
      this.imageCanvas.setAttribute(
        'aria-label',
        `Single-scattering image, ${samples} samples per pixel, ${run.plan.integrator}`,
      );
  }
}

export function defineSingleScatter(): void {
  if (!customElements.get('sb-single-scatter'))
    customElements.define('sb-single-scatter', SingleScatterElement);
}
