// <sb-volume-path-tracer>: single versus multiple scattering in a cloud (chapter 10).
// Two images of the same scene are refined progressively by the scene engine
// (src/scene/): one with scatteringOrder 1, one with unlimited order (volumetric path
// tracing: spectral tracking, next-event estimation, Russian roulette). Each frame adds
// `spp` samples per pixel to both, timed on the GPU. A converged reference of each
// (independent seed, many more samples) is accumulated one pass per frame, cached per
// parameter set, with progress and a cancel button; once it is there, the error of
// every snapshot of the progressive images is plotted against accumulated GPU time on
// log–log axes, where an unbiased estimator falls with slope −½. On WebGPU the images
// accumulate on the GPU and are drawn from there (src/scene/accumulationView.ts); a
// frame reads back only reduced statistics. Without WebGPU the float64 CPU twin renders
// a smaller image with fewer samples, and says so.
import type { GpuContext } from '../../gpu/device.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { Accumulation, ImageStatistics } from '../../scene/accumulation.ts';
import { AccumulationView, canvasForContext } from '../../scene/accumulationView.ts';
import { CpuSceneRenderer } from '../../scene/cpuRenderer.ts';
import { GpuAccumulation } from '../../scene/gpuAccumulation.ts';
import { GpuSceneRenderer } from '../../scene/gpuRenderer.ts';
import { toneMapRgba8 } from '../../scene/image.ts';
import { resolveScene } from '../../scene/load.ts';
import { packScene, sceneData } from '../../scene/pack.ts';
import { plan, type Plan } from '../../scene/plan.ts';
import type { PassRenderer, PassTiming } from '../../scene/render.ts';
import { BackendChooser, type Backend, gpuFailureReason } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import { imageCanvas, imageFigure, imagePanel } from '../base/imagePanel.ts';
import { LinePlot } from '../base/plot.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { logLogSlope, mergeSeries, type SweepPoint } from '../base/sweep.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import {
  CPU_BUDGET,
  GPU_BUDGET,
  IMAGE_SEED,
  REFERENCE_SEED,
  buildScene,
  inputsFrom,
  mediumMask,
  sceneKey,
  type Budget,
  type PathTracerInputs,
} from './model.ts';
import { VOLUME_PATH_TRACER } from './schema.ts';

const READOUT_ROWS = [
  ['spp', 'Samples per pixel so far'],
  ['stderr-single', 'Mean standard error, single'],
  ['stderr-multiple', 'Mean standard error, multiple'],
  ['ratio', 'Brightness where τ ≥ 1, multiple ÷ single'],
  ['error-single', 'Error vs reference, single'],
  ['error-multiple', 'Error vs reference, multiple'],
  ['slope', 'Fitted slope, error ∝ time^p (∝ spp^p)'],
  ['frame', 'Time per frame (both images)'],
  ['per-sample', 'Time per path sample, multiple'],
  ['lookups', 'Density lookups per path sample'],
  ['capped', 'Walks stopped at the 1024-vertex cap'],
] as const;

const ORDERS = ['single', 'multiple'] as const;
type Order = (typeof ORDERS)[number];

/** A frozen copy of an image, and its error once the reference is there. */
interface Snapshot {
  samples: number;
  milliseconds: number;
  image: Accumulation | null;
  /** Relative error against the finished reference (NaN: within its noise). */
  error: number | null;
}

/** One image being refined: its renderer (which accumulates), cost so far and snapshots. */
interface Progressive {
  renderer: PassRenderer;
  accumulation: Accumulation;
  milliseconds: number;
  timing: PassTiming;
  lastPassMs: number;
  /** Copies at geometrically spaced spp, for the error plot once the reference exists. */
  snapshots: Snapshot[];
}

/** The reference of one parameter set, complete or in progress. */
interface ReferenceJob {
  /** Null once done: the renderers are freed and only the accumulations kept. */
  renderers: Record<Order, PassRenderer> | null;
  accumulations: Record<Order, Accumulation>;
  done: boolean;
  cancelled: boolean;
  /** Samples per pixel of the next reference pass, sized to REFERENCE_FRAME_MS. */
  passSpp: number;
}

/** Everything of one parameter set on one backend. */
interface Run {
  key: string;
  inputs: PathTracerInputs;
  budget: Budget;
  backend: 'gpu' | 'cpu';
  images: Record<Order, Progressive>;
  plans: Record<Order, Plan>;
  mask: Uint8Array;
  reference: ReferenceJob;
}

const COLOURS: Record<Order, string> = { single: '#d9822b', multiple: '#2b7bb9' };
const MAX_CACHED_REFERENCES = 8;
/**
 * Time one frame's reference pass may take (both orders together): the reference runs
 * beside the progressive images, and a fixed pass of budget.referencePass spp made
 * frames of seconds on a CPU WebGPU. Its size adapts to the measured cost per sample.
 */
const REFERENCE_FRAME_MS = 120;

export class VolumePathTracerElement extends WidgetElement {
  protected readonly entry = VOLUME_PATH_TRACER;
  protected override presets: readonly Preset[] = [
    {
      label: 'white cloud (α = 0.99)',
      values: { scene: 'sphere', albedo: 0.99, g: 0.8, 'optical-thickness': 10 },
    },
    {
      label: 'dark smoke (α = 0.3)',
      values: { scene: 'sphere', albedo: 0.3, g: 0.3, 'optical-thickness': 8 },
    },
    {
      label: 'thin haze (τ = 1)',
      values: { scene: 'sphere', albedo: 0.9, g: 0.6, 'optical-thickness': 1 },
    },
    {
      label: 'puffy grid cloud',
      values: { scene: 'cloud', albedo: 0.98, g: 0.7, 'optical-thickness': 16 },
    },
  ];

  private canvases: Partial<Record<Order, HTMLCanvasElement>> = {};
  /** The WebGPU pictures of the canvases, made for one device. */
  private views: Partial<Record<Order, { device: GPUDevice; view: AccumulationView }>> = {};
  private captions: Partial<Record<Order, HTMLElement>> = {};
  private readouts: ReadoutList | null = null;
  private cost: HTMLElement | null = null;
  private planList: HTMLElement | null = null;
  private plot: LinePlot | null = null;
  private plotHint: HTMLElement | null = null;
  private pauseButton: HTMLButtonElement | null = null;
  private referenceButton: HTMLButtonElement | null = null;
  private referenceProgress: HTMLProgressElement | null = null;
  private referenceStatus: HTMLElement | null = null;
  private paused = false;
  private run: Run | null = null;
  private readonly references = new Map<string, ReferenceJob>();
  private readonly backends = new BackendChooser(
    (gpu: GpuContext) => gpu,
    () => {
      this.discardRun();
      for (const job of this.references.values()) destroyReference(job);
      this.references.clear();
      this.dropViews();
      this.scheduleRender();
    },
  );

  private dropViews(): void {
    for (const order of ORDERS) this.views[order]?.view.destroy();
    this.views = {};
  }

  protected buildStage(stage: HTMLElement): void {
    const panels = ORDERS.map((order) => {
      const canvas = imageCanvas(
        order === 'single' ? 'Single scattering image' : 'Multiple scattering image',
        GPU_BUDGET.width,
        GPU_BUDGET.height,
      );
      this.canvases[order] = canvas;
      const { panel } = imagePanel(
        canvas,
        order === 'single'
          ? 'Single scattering (order 1)'
          : 'Multiple scattering (path tracing, all orders)',
      );
      const caption = panel.querySelector('figcaption');
      if (caption) this.captions[order] = caption;
      panel.dataset['order'] = order;
      return panel;
    });
    stage.appendChild(imageFigure(...panels));

    const bar = document.createElement('div');
    bar.className = 'sb-sweep sb-vpt-bar';
    this.pauseButton = document.createElement('button');
    this.pauseButton.type = 'button';
    this.pauseButton.className = 'sb-button';
    this.pauseButton.dataset['action'] = 'pause';
    this.pauseButton.textContent = 'Pause';
    this.pauseButton.addEventListener('click', () => {
      this.paused = !this.paused;
      this.pauseButton!.textContent = this.paused ? 'Resume' : 'Pause';
      this.pauseButton!.setAttribute('aria-pressed', String(this.paused));
      if (!this.paused) this.scheduleRender();
    });
    const restart = document.createElement('button');
    restart.type = 'button';
    restart.className = 'sb-button';
    restart.dataset['action'] = 'restart';
    restart.textContent = 'Restart';
    restart.addEventListener('click', () => {
      this.discardRun();
      this.scheduleRender();
    });
    this.referenceButton = document.createElement('button');
    this.referenceButton.type = 'button';
    this.referenceButton.className = 'sb-button';
    this.referenceButton.dataset['action'] = 'reference';
    this.referenceButton.textContent = 'Cancel reference';
    this.referenceButton.addEventListener('click', () => this.toggleReference());
    this.referenceProgress = document.createElement('progress');
    this.referenceProgress.max = 1;
    this.referenceProgress.value = 0;
    this.referenceProgress.setAttribute('aria-label', 'Reference progress');
    this.referenceStatus = document.createElement('span');
    this.referenceStatus.className = 'sb-sweep-status sb-vpt-reference-status';
    this.referenceStatus.setAttribute('aria-live', 'polite');
    bar.append(
      this.pauseButton,
      restart,
      this.referenceButton,
      this.referenceProgress,
      this.referenceStatus,
    );
    stage.appendChild(bar);

    this.plotHint = document.createElement('p');
    this.plotHint.className = 'sb-sweep-hint';
    this.plotHint.textContent =
      'The error plot appears when the converged reference is ready: relative RMSE of each image against its reference, against accumulated GPU time, on log–log axes.';
    const plotArea = document.createElement('div');
    plotArea.className = 'sb-plot';
    plotArea.setAttribute('role', 'img');
    plotArea.setAttribute(
      'aria-label',
      'Log–log plot of the relative error of both images against accumulated GPU time',
    );
    stage.append(this.plotHint, plotArea);
    this.plot = new LinePlot(plotArea, {
      xLabel: 'log₁₀ accumulated time (ms)',
      yLabel: 'relative RMSE',
      yLog: true,
      height: 220,
    });
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
    this.cost = this.readouts.cost;
    const plan = document.createElement('dl');
    plan.className = 'sb-vpt-plan';
    plan.setAttribute('aria-label', 'Plan of the two renders');
    readout.appendChild(plan);
    this.planList = plan;
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.readouts?.set(key, text, state);
  }

  private discardRun(): void {
    if (!this.run) return;
    for (const order of ORDERS) {
      const image = this.run.images[order];
      image.renderer.destroy();
      for (const snapshot of image.snapshots) snapshot.image?.destroy();
    }
    // The reference job stays in the cache (with its renderers) only while unfinished
    // work of it may resume; a finished one keeps just its images.
    this.run = null;
  }

  private toggleReference(): void {
    const job = this.run?.reference;
    if (!job || job.done) return;
    job.cancelled = !job.cancelled;
    this.updateReferenceStatus();
    if (!job.cancelled) this.scheduleRender();
  }

  private async makeRenderer(
    backend: Backend<GpuContext>,
    inputs: PathTracerInputs,
    order: Order,
    budget: Budget,
    seed: number,
  ): Promise<{ renderer: PassRenderer; plan: Plan }> {
    const scene = buildScene(
      inputs,
      order === 'single' ? 1 : 'unlimited',
      budget,
      budget.maxSpp,
      seed,
    );
    const scenePlan = plan(scene);
    const packed = packScene(await resolveScene(scene));
    const renderer =
      backend.kind === 'gpu'
        ? await GpuSceneRenderer.create(
            backend.gpu.device,
            STATIC_KERNELS,
            packed,
            scenePlan.conditions,
          )
        : new CpuSceneRenderer(
            sceneData(packed, scenePlan.conditions),
            packed.width,
            packed.height,
            packed.seed,
          );
    return { renderer, plan: scenePlan };
  }

  private async startRun(backend: Backend<GpuContext>, inputs: PathTracerInputs): Promise<Run> {
    const budget = backend.kind === 'gpu' ? GPU_BUDGET : CPU_BUDGET;
    const key = `${backend.kind}|${sceneKey(inputs)}`;
    const made: PassRenderer[] = [];
    try {
      const single = await this.makeRenderer(backend, inputs, 'single', budget, IMAGE_SEED);
      made.push(single.renderer);
      const multiple = await this.makeRenderer(backend, inputs, 'multiple', budget, IMAGE_SEED);
      made.push(multiple.renderer);
      let reference = this.references.get(key);
      if (!reference) {
        const refSingle = await this.makeRenderer(
          backend,
          inputs,
          'single',
          budget,
          REFERENCE_SEED,
        );
        made.push(refSingle.renderer);
        const refMultiple = await this.makeRenderer(
          backend,
          inputs,
          'multiple',
          budget,
          REFERENCE_SEED,
        );
        reference = {
          renderers: { single: refSingle.renderer, multiple: refMultiple.renderer },
          accumulations: {
            single: refSingle.renderer.accumulation,
            multiple: refMultiple.renderer.accumulation,
          },
          done: false,
          cancelled: false,
          passSpp: 1,
        };
        this.references.set(key, reference);
        this.trimReferences();
      }
      const mask = mediumMask(inputs, budget.width, budget.height);
      single.renderer.accumulation.setMask(mask);
      multiple.renderer.accumulation.setMask(mask);
      const progressive = (renderer: PassRenderer): Progressive => ({
        renderer,
        accumulation: renderer.accumulation,
        milliseconds: 0,
        timing: renderer.timing,
        lastPassMs: 0,
        snapshots: [],
      });
      for (const order of ORDERS) {
        const canvas = this.canvases[order];
        if (canvas) {
          canvas.width = budget.width;
          canvas.height = budget.height;
        }
      }
      return {
        key,
        inputs,
        budget,
        backend: backend.kind,
        images: { single: progressive(single.renderer), multiple: progressive(multiple.renderer) },
        plans: { single: single.plan, multiple: multiple.plan },
        mask,
        reference,
      };
    } catch (error) {
      for (const r of made) r.destroy();
      throw error;
    }
  }

  /** Keeps the most recent references; unfinished ones beyond that are dropped. */
  private trimReferences(): void {
    while (this.references.size > MAX_CACHED_REFERENCES) {
      const [oldest, job] = this.references.entries().next().value!;
      destroyReference(job);
      this.references.delete(oldest);
    }
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    const key = `${backend.kind}|${sceneKey(inputs)}`;
    try {
      if (this.run?.key !== key) {
        this.discardRun();
        this.run = await this.startRun(backend, inputs);
      }
      await this.frame(this.run, inputs.spp);
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.backends.useCpu(gpuFailureReason(error));
      this.discardRun();
      this.scheduleRender();
      return;
    }
    if (backend.kind === 'gpu') {
      this.clearNotice('backend');
    } else {
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU twin of the same path tracer: ${CPU_BUDGET.width}×${CPU_BUDGET.height} pixels, at most ${CPU_BUDGET.maxSpp} samples per pixel and ${CPU_BUDGET.maxFrameSpp} per frame, reference ${CPU_BUDGET.referenceSpp}.`,
      );
    }
    const run = this.run;
    await this.show(run);
    if (this.run === run && !this.paused && this.hasWork(run)) this.scheduleRender();
  }

  private hasWork(run: Run): boolean {
    const job = run.reference;
    return (
      run.images.multiple.accumulation.samples < run.budget.maxSpp || (!job.done && !job.cancelled)
    );
  }

  /** One frame: spp more samples per pixel in both images, and one reference pass. */
  private async frame(run: Run, sppPerFrame: number): Promise<void> {
    const { budget } = run;
    if (this.paused) return;
    let frameMs = 0;
    let timing: PassTiming | null = null;
    for (const order of ORDERS) {
      const image = run.images[order];
      const have = image.accumulation.samples;
      const samples = Math.min(sppPerFrame, budget.maxFrameSpp, budget.maxSpp - have);
      if (samples <= 0) continue;
      const output = await image.renderer.renderPass(have, samples);
      if (this.run !== run) return;
      image.milliseconds += output.milliseconds;
      image.lastPassMs = output.milliseconds;
      image.timing = output.timing ?? image.renderer.timing;
      timing = image.timing;
      frameMs += output.milliseconds;
      // Snapshots at spp growing by ≥ 25 %: even spacing on the log–log plot. A copy
      // of the moments in the same store (a GPU buffer copy, nothing read back).
      const last = image.snapshots.at(-1);
      const total = image.accumulation.samples;
      if (!last || total >= last.samples * 1.25 || total === budget.maxSpp)
        image.snapshots.push({
          samples: total,
          milliseconds: image.milliseconds,
          image: image.accumulation.snapshot(),
          error: null,
        });
    }
    if (timing) this.recordFrameCost(frameMs, timingLabel(timing));
    await this.referencePass(run);
  }

  private async referencePass(run: Run): Promise<void> {
    const job = run.reference;
    if (job.done || job.cancelled || !job.renderers) return;
    const { budget } = run;
    let spent = 0;
    let rendered = 0;
    for (const order of ORDERS) {
      const accumulation = job.accumulations[order];
      const passSpp = Math.min(job.passSpp, budget.referencePass);
      const samples = Math.min(passSpp, budget.referenceSpp - accumulation.samples);
      if (samples <= 0) continue;
      const output = await job.renderers[order].renderPass(accumulation.samples, samples);
      spent += output.milliseconds;
      rendered += samples;
    }
    if (rendered > 0 && spent > 0) {
      const perSample = spent / rendered; // ms per spp of one order's image
      job.passSpp = Math.max(
        1,
        Math.min(
          budget.referencePass,
          Math.floor(REFERENCE_FRAME_MS / (ORDERS.length * perSample)),
        ),
      );
    }
    if (ORDERS.every((order) => job.accumulations[order].samples >= budget.referenceSpp)) {
      // Keep the moments (on the GPU for a GPU run), free the scene and its kernels.
      const renderers = job.renderers;
      job.accumulations = {
        single: renderers.single.release(),
        multiple: renderers.multiple.release(),
      };
      job.done = true;
      job.renderers = null;
    }
  }

  private updateReferenceStatus(): void {
    const run = this.run;
    if (!run || !this.referenceStatus || !this.referenceProgress || !this.referenceButton) return;
    const job = run.reference;
    const target = run.budget.referenceSpp;
    const have = Math.min(job.accumulations.single.samples, job.accumulations.multiple.samples);
    this.referenceProgress.max = target;
    this.referenceProgress.value = job.done ? target : have;
    this.referenceButton.disabled = job.done;
    this.referenceButton.textContent = job.cancelled ? 'Compute reference' : 'Cancel reference';
    this.referenceStatus.textContent = job.done
      ? `Reference ready: ${target} spp per pixel per image (independent seed), cached for these parameters.`
      : job.cancelled
        ? `Reference cancelled at ${have} of ${target} spp: no error against it.`
        : `Computing the reference: ${have} of ${target} spp per pixel…`;
  }

  /**
   * Draws an image: on WebGPU straight from its moments on the GPU (a render pass, no
   * read-back); for the CPU twin, its float64 mean tone-mapped on the host.
   */
  private async paint(order: Order, run: Run, accumulation: Accumulation): Promise<void> {
    const current = this.canvases[order];
    if (!current) return;
    if (accumulation instanceof GpuAccumulation) {
      const canvas = canvasForContext(current, 'webgpu');
      this.canvases[order] = canvas;
      const { device } = accumulation;
      let entry = this.views[order];
      if (!entry || entry.device !== device) {
        entry?.view.destroy();
        entry = { device, view: await AccumulationView.create(device, STATIC_KERNELS, canvas) };
        this.views[order] = entry;
      }
      await entry.view.draw(accumulation, { kind: 'radiance', exposure: 0 });
      return;
    }
    const canvas = canvasForContext(current, '2d');
    this.canvases[order] = canvas;
    const context = canvas.getContext('2d');
    if (!context) return;
    const { width, height } = run.budget;
    const mean = (await accumulation.readImage()).mean();
    const rgba = toneMapRgba8(width, height, mean, 0);
    context.putImageData(new ImageData(new Uint8ClampedArray(rgba), width, height), 0, 0);
  }

  private async show(run: Run): Promise<void> {
    const { budget, images, reference } = run;
    const stats: Record<Order, ImageStatistics> = {
      single: await images.single.accumulation.statistics(),
      multiple: await images.multiple.accumulation.statistics(),
    };
    if (this.run !== run) return;
    const spp = images.multiple.accumulation.samples;
    const pixelPaths = budget.width * budget.height;
    for (const order of ORDERS) {
      const image = images[order];
      await this.paint(order, run, image.accumulation);
      if (this.run !== run) return;
      const error = stats[order].meanStandardError;
      const relative = error / stats[order].meanRadiance;
      this.set(
        `stderr-${order}`,
        Number.isFinite(error)
          ? `${formatNumber(error, 3)} W/(m²·sr) (${formatNumber(100 * relative, 3)} % of mean L)`
          : 'needs 2 samples',
      );
      const caption = this.captions[order];
      if (caption)
        caption.textContent = `${order === 'single' ? 'Single scattering (order 1)' : 'Multiple scattering (all orders)'}: ${image.accumulation.samples} spp`;
      this.canvases[order]?.setAttribute(
        'aria-label',
        `${order === 'single' ? 'Single' : 'Multiple'} scattering image, ${image.accumulation.samples} samples per pixel`,
      );
    }
    this.set(
      'spp',
      `${spp} of ${budget.maxSpp}${spp >= budget.maxSpp ? ' (done)' : this.paused ? ' (paused)' : ''}`,
    );
    const single = stats.single.maskedLuminance;
    const multiple = stats.multiple.maskedLuminance;
    this.set(
      'ratio',
      single > 0
        ? `${formatNumber(multiple / single, 3)} (single scattering keeps ${formatNumber((100 * single) / multiple, 3)} %)`
        : 'single scattering is black',
    );

    const multi = images.multiple;
    const timing = timingLabel(multi.timing);
    const frameMs = images.single.lastPassMs + multi.lastPassMs;
    this.set('frame', `${formatMilliseconds(frameMs)} (${timing})`);
    const perSample = spp > 0 ? (multi.milliseconds * 1e6) / (spp * pixelPaths) : NaN;
    this.set(
      'per-sample',
      Number.isFinite(perSample) ? `${formatNumber(perSample, 3)} ns per path` : '—',
    );
    const lookups = (order: Order): string =>
      formatNumber(stats[order].lookups / Math.max(1, stats[order].samples * pixelPaths), 3);
    this.set(
      'lookups',
      run.inputs.scene === 'cloud'
        ? `single ${lookups('single')}, multiple ${lookups('multiple')}`
        : 'none counted (homogeneous medium, no grid)',
    );
    const capped = stats.single.capped + stats.multiple.capped;
    this.set('capped', String(capped), capped > 0 ? 'bad' : 'ok');
    if (capped > 0)
      this.showNotice(
        'capped',
        'warning',
        `${capped} walks reached the hard cap of 1024 vertices and were cut short: the multiple-scattering image is slightly too dark.`,
      );
    else this.clearNotice('capped');

    await this.showErrors(run);
    if (this.run !== run) return;
    this.updateReferenceStatus();
    this.showPlan(run);
    if (this.cost) {
      const where =
        run.backend === 'gpu'
          ? `WebGPU: ${budget.width}×${budget.height} pixels`
          : `CPU fallback (float64 twin): ${budget.width}×${budget.height} pixels`;
      this.cost.textContent = `${where}, ${spp} spp each; accumulated time single ${formatMilliseconds(images.single.milliseconds)}, multiple ${formatMilliseconds(multi.milliseconds)} (${timing}). Reference: ${budget.referenceSpp} spp, independent seed, cached per parameter set.${reference.done ? '' : ' Not ready yet.'}`;
    }
  }

  private async showErrors(run: Run): Promise<void> {
    const job = run.reference;
    if (!job.done) {
      for (const order of ORDERS)
        this.set(
          `error-${order}`,
          run.reference.cancelled ? 'no reference' : 'waiting for the reference',
        );
      this.set('slope', '—');
      return;
    }
    const points: Record<Order, SweepPoint[]> = { single: [], multiple: [] };
    for (const order of ORDERS) {
      const image = run.images[order];
      for (const snapshot of image.snapshots) {
        // Once per snapshot: against the finished reference (one reduction on the GPU),
        // after which the copy is no longer needed.
        if (snapshot.error === null && snapshot.image) {
          snapshot.error = (
            await snapshot.image.statistics(job.accumulations[order])
          ).relativeError;
          snapshot.image.destroy();
          snapshot.image = null;
          if (this.run !== run) return;
        }
        const error = snapshot.error ?? NaN;
        if (Number.isFinite(error))
          points[order].push({
            n: snapshot.samples,
            rmse: error,
            milliseconds: snapshot.milliseconds,
          });
      }
      const latest = points[order].at(-1);
      this.set(
        `error-${order}`,
        latest
          ? `${formatNumber(100 * latest.rmse, 3)} % at ${latest.n} spp`
          : 'within the reference noise',
      );
    }
    // The first frames pay the fixed cost of a dispatch; fit from 4 spp on. The slope
    // against spp isolates the estimator (−½ for any unbiased Monte Carlo estimate);
    // against time it also shows whether the cost per sample stayed constant.
    const slope = (order: Order, against: 'time' | 'spp'): number | null => {
      const usable = points[order].filter((p) => p.n >= 4);
      return logLogSlope(
        usable.map((p) => (against === 'time' ? p.milliseconds : p.n)),
        usable.map((p) => p.rmse),
      );
    };
    const fits = { single: slope('single', 'time'), multiple: slope('multiple', 'time') };
    const text = (v: number | null): string => (v === null ? 'no fit yet' : formatNumber(v, 3));
    this.set(
      'slope',
      ORDERS.map(
        (order) => `${order} ${text(fits[order])} (vs spp ${text(slope(order, 'spp'))})`,
      ).join(', ') + '; expected −½',
    );
    if (points.single.length + points.multiple.length === 0) return;
    this.plotHint?.remove();
    this.plotHint = null;
    const merged = mergeSeries([points.single, points.multiple]);
    // A guide of slope −½ through the multiple-scattering curve's first fitted point.
    const anchor = points.multiple.find((p) => p.n >= 4) ?? points.multiple[0];
    const guide = merged.x.map((x) =>
      anchor
        ? anchor.rmse * 10 ** (-0.5 * (x - Math.log10(Math.max(anchor.milliseconds, 1e-4))))
        : NaN,
    );
    this.plot?.update(merged.x, [
      {
        label: `single scattering, p = ${text(fits.single)}`,
        color: COLOURS.single,
        spanGaps: true,
        values: merged.values[0]!,
      },
      {
        label: `multiple scattering, p = ${text(fits.multiple)}`,
        color: COLOURS.multiple,
        spanGaps: true,
        values: merged.values[1]!,
      },
      { label: 'slope −½', color: '#888888', dash: [6, 4], values: guide },
    ]);
  }

  private showPlan(run: Run): void {
    const list = this.planList;
    if (!list || list.dataset['key'] === run.key) return;
    list.dataset['key'] = run.key;
    list.replaceChildren();
    for (const order of ORDERS) {
      const p = run.plans[order];
      const method = (effect: string): string | null =>
        p.effects.find((e) => e.effect === effect && e.enabled)?.method ?? null;
      const term = document.createElement('dt');
      term.textContent = `Plan, ${order === 'single' ? 'single' : 'multiple'} (${p.integrator})`;
      const value = document.createElement('dd');
      value.dataset['readout'] = `plan-${order}`;
      value.textContent = [
        method('integrator'),
        method('in-scattering'),
        method('view transmittance'),
      ]
        .filter((m): m is string => m !== null)
        .join('; ');
      list.append(term, value);
    }
  }
}

/** Frees a cached reference: its renderers while unfinished, else its moments. */
function destroyReference(job: ReferenceJob): void {
  if (job.renderers) for (const order of ORDERS) job.renderers[order].destroy();
  else for (const order of ORDERS) job.accumulations[order].destroy();
}

export function defineVolumePathTracer(): void {
  if (!customElements.get('sb-volume-path-tracer'))
    customElements.define('sb-volume-path-tracer', VolumePathTracerElement);
}
