// The drawing of <sb-volume-path-tracer>: the two progressive images (on WebGPU drawn
// from the moments on the GPU, src/scene/accumulationView.ts; on the CPU tone-mapped on
// the host), the pause / restart / reference bar, the log–log error plot with its
// slope −½ guide, and the plan of each render. The view keeps the run (renderers,
// accumulations, snapshots) and the cache of references; each render adds one frame of
// samples and one reference pass, and asks for the next while there is work left.
// Readouts, cost line, backend choice and fallback: widget.ts and the base element.
import type { GpuContext } from '../../gpu/device.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { Accumulation, ImageStatistics } from '../../scene/accumulation.ts';
import { AccumulationView, canvasForContext } from '../../scene/accumulationView.ts';
import { WorkerSceneRenderer } from '../../scene/workerRenderer.ts';
import { GpuAccumulation } from '../../scene/gpuAccumulation.ts';
import { GpuSceneRenderer } from '../../scene/gpuRenderer.ts';
import { toneMapRgba8 } from '../../scene/image.ts';
import { resolveScene } from '../../scene/load.ts';
import { packScene, sceneData } from '../../scene/pack.ts';
import { plan, type Plan } from '../../scene/plan.ts';
import type { PassRenderer, PassTiming } from '../../scene/render.ts';
import type { Backend } from '../base/backend.ts';
import {
  PREVIEW_WORK_SHARE,
  firstPictureBudget,
  type FrameRequest,
  type Refinement,
} from '../base/refinement.ts';
import { imageCanvas, imageFigure, imagePanel } from '../base/imagePanel.ts';
import { LinePlot, createPlotArea } from '../base/plot.ts';
import { logLogSlope, mergeSeries, type SweepPoint } from '../base/sweep.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { workerJobs } from '../../workers/compute.ts';
import type { jobs } from './jobs.ts';
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
  type SceneChoice,
} from './model.ts';
import {
  ORDERS,
  slopeText,
  type Order,
  type ReferenceErrors,
  type VolumePathTracerFrame,
} from './widget.ts';
import { context2d } from '../base/canvas2d.ts';

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
  /** Samples per pixel of the next reference pass, sized to REFERENCE_STEP_MS. */
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
  /** Made after the first picture (its kernels are the images' own, already compiled). */
  reference: ReferenceJob | null;
  /** False once the reader cancelled the reference before it was made. */
  referenceWanted: boolean;
}

const COLOURS: Record<Order, string> = { single: '#d9822b', multiple: '#2b7bb9' };
const MAX_CACHED_REFERENCES = 8;
/**
 * Time one frame's reference pass may take (both orders together): the reference runs
 * beside the progressive images, and a fixed pass of budget.referencePass spp made
 * frames of seconds on a CPU WebGPU. Its size adapts to the measured cost per sample.
 */
const REFERENCE_FRAME_MS = 120;
/**
 * One reference pass (one order's image) of that time: what an input may wait behind. At
 * 20 ms (GPU timestamps; wall time on SwiftShader is longer under load) a pass in flight
 * held an input's first picture back by up to 60 ms (bench/firstPictureProbe.ts).
 */
const REFERENCE_STEP_MS = 10;
/**
 * Time the image passes of one background frame may take (both orders together, GPU ms):
 * an input's first picture waits for them. At 40 the two passes in flight took up to 130
 * ms of wall time on SwiftShader (firstPictureProbe).
 */
const BACKGROUND_FRAME_MS = 20;

/** Frees a cached reference: its renderers while unfinished, else its moments. */
function destroyReference(job: ReferenceJob): void {
  if (job.renderers) for (const order of ORDERS) job.renderers[order].destroy();
  else for (const order of ORDERS) job.accumulations[order].destroy();
}

/** The CPU twin's passes run in the compute worker (jobs.ts), off the page's thread. */
const cpuJobs = workerJobs<typeof jobs>('volume-path-tracer');

async function makeRenderer(
  backend: Backend<GpuContext>,
  inputs: PathTracerInputs,
  order: Order,
  budget: Budget,
  seed: number,
  /** The signal a CPU pass listens to: the input signal of the moment it is asked for. */
  inputSignal: () => AbortSignal,
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
      : new WorkerSceneRenderer(
          cpuJobs,
          sceneData(packed, scenePlan.conditions),
          packed.width,
          packed.height,
          packed.seed,
          inputSignal,
        );
  return { renderer, plan: scenePlan };
}

export function createView(
  context: ViewContext<GpuContext>,
): WidgetView<VolumePathTracerFrame, GpuContext> {
  // Canvases swap themselves between a WebGPU and a 2D context (canvasForContext), so
  // they are the view's, not the base's managed ones; always read them from here.
  const canvases: Partial<Record<Order, HTMLCanvasElement>> = {};
  /** The WebGPU pictures of the canvases, made for one device. */
  let views: Partial<Record<Order, { device: GPUDevice; view: AccumulationView }>> = {};
  const captions: Partial<Record<Order, HTMLElement>> = {};
  let planList: HTMLElement | null = null;
  let plot: LinePlot | null = null;
  let plotHint: HTMLElement | null = null;
  let referenceButton: HTMLButtonElement | null = null;
  let referenceProgress: HTMLProgressElement | null = null;
  let referenceStatus: HTMLElement | null = null;
  let paused = false;
  let run: Run | null = null;
  const references = new Map<string, ReferenceJob>();
  /** The signal a CPU pass listens to: that of the frame being drawn (ViewContext.frameSignal). */
  const inputSignal = (): AbortSignal => context.frameSignal;

  const dropViews = (): void => {
    for (const order of ORDERS) views[order]?.view.destroy();
    views = {};
  };

  const discardRun = (): void => {
    if (!run) return;
    for (const order of ORDERS) {
      const image = run.images[order];
      image.renderer.destroy();
      for (const snapshot of image.snapshots) snapshot.image?.destroy();
    }
    // The reference job stays in the cache (with its renderers) only while unfinished
    // work of it may resume; a finished one keeps just its images.
    run = null;
  };

  /** Everything GPU-side: the run, the cached references and the pictures (device loss, destroy). */
  const releaseAll = (): void => {
    discardRun();
    for (const job of references.values()) destroyReference(job);
    references.clear();
    dropViews();
  };

  const updateReferenceStatus = (): void => {
    if (!run || !referenceStatus || !referenceProgress || !referenceButton) return;
    const target = run.budget.referenceSpp;
    const job = run.reference ?? {
      accumulations: { single: { samples: 0 }, multiple: { samples: 0 } },
      done: false,
      cancelled: !run.referenceWanted,
    };
    const have = Math.min(job.accumulations.single.samples, job.accumulations.multiple.samples);
    referenceProgress.max = target;
    referenceProgress.value = job.done ? target : have;
    referenceButton.disabled = job.done;
    referenceButton.textContent = job.cancelled ? 'Compute reference' : 'Cancel reference';
    referenceStatus.textContent = job.done
      ? `Reference ready: ${target} spp per pixel per image (independent seed), cached for these parameters.`
      : job.cancelled
        ? `Reference cancelled at ${have} of ${target} spp: no error against it.`
        : `Computing the reference: ${have} of ${target} spp per pixel…`;
  };

  const toggleReference = (): void => {
    if (run && !run.reference) {
      run.referenceWanted = !run.referenceWanted;
      updateReferenceStatus();
      if (run.referenceWanted) context.scheduleRender();
      return;
    }
    const job = run?.reference;
    if (!job || job.done) return;
    job.cancelled = !job.cancelled;
    updateReferenceStatus();
    if (!job.cancelled) context.scheduleRender();
  };

  /** Keeps the most recent references; unfinished ones beyond that are dropped. */
  const trimReferences = (): void => {
    while (references.size > MAX_CACHED_REFERENCES) {
      const [oldest, job] = references.entries().next().value!;
      destroyReference(job);
      references.delete(oldest);
    }
  };

  const startRun = async (backend: Backend<GpuContext>, inputs: PathTracerInputs): Promise<Run> => {
    const budget = backend.kind === 'gpu' ? GPU_BUDGET : CPU_BUDGET;
    const key = `${backend.kind}|${sceneKey(inputs)}`;
    // Both images' kernels link and compile side by side; the reference waits until the
    // first picture is up (referenceFor), so a new scene shows something at once.
    const made = await Promise.allSettled([
      makeRenderer(backend, inputs, 'single', budget, IMAGE_SEED, inputSignal),
      makeRenderer(backend, inputs, 'multiple', budget, IMAGE_SEED, inputSignal),
    ]);
    const failed = made.find((m) => m.status === 'rejected');
    if (failed) {
      for (const m of made) if (m.status === 'fulfilled') m.value.renderer.destroy();
      throw failed.reason;
    }
    const [single, multiple] = made.map(
      (m) => (m as PromiseFulfilledResult<{ renderer: PassRenderer; plan: Plan }>).value,
    ) as [{ renderer: PassRenderer; plan: Plan }, { renderer: PassRenderer; plan: Plan }];
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
      const canvas = canvases[order];
      // Only on a change of size: setting it clears the canvas, and the old picture stays
      // up until the new scene's first picture replaces it.
      if (canvas && (canvas.width !== budget.width || canvas.height !== budget.height)) {
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
      reference: references.get(key) ?? null,
      referenceWanted: true,
    };
  };

  /** The run's reference job: the cached one, or a new one (two more renderers). */
  const referenceFor = async (
    backend: Backend<GpuContext>,
    current: Run,
  ): Promise<ReferenceJob | null> => {
    if (current.reference || !current.referenceWanted) return current.reference;
    const { inputs, budget, key } = current;
    const made = await Promise.allSettled([
      makeRenderer(backend, inputs, 'single', budget, REFERENCE_SEED, inputSignal),
      makeRenderer(backend, inputs, 'multiple', budget, REFERENCE_SEED, inputSignal),
    ]);
    const failed = made.find((m) => m.status === 'rejected');
    if (failed || run !== current) {
      for (const m of made) if (m.status === 'fulfilled') m.value.renderer.destroy();
      if (failed) throw failed.reason;
      return null;
    }
    const [refSingle, refMultiple] = made.map(
      (m) => (m as PromiseFulfilledResult<{ renderer: PassRenderer }>).value.renderer,
    ) as [PassRenderer, PassRenderer];
    const reference: ReferenceJob = {
      renderers: { single: refSingle, multiple: refMultiple },
      accumulations: { single: refSingle.accumulation, multiple: refMultiple.accumulation },
      done: false,
      cancelled: false,
      passSpp: 1,
    };
    references.set(key, reference);
    trimReferences();
    current.reference = reference;
    return reference;
  };

  const hasWork = (current: Run): boolean => {
    const job = current.reference;
    return (
      current.images.multiple.accumulation.samples < current.budget.maxSpp ||
      !job ||
      (!job.done && !job.cancelled)
    );
  };

  const referencePass = async (current: Run, signal: AbortSignal): Promise<void> => {
    const job = current.reference;
    if (!job || job.done || job.cancelled || !job.renderers) return;
    const { budget } = current;
    // Steps of about REFERENCE_STEP_MS each, one order at a time, until the frame's
    // REFERENCE_FRAME_MS are spent: an input waits for at most the step in flight (the GPU
    // runs a submitted pass to its end; a 60-ms pass made first pictures 130 ms late).
    let spent = 0;
    for (let step = 0; step < REFERENCE_FRAME_MS / REFERENCE_STEP_MS; step++) {
      let rendered = 0;
      let stepMs = 0;
      for (const order of ORDERS) {
        const accumulation = job.accumulations[order];
        const samples = Math.min(job.passSpp, budget.referenceSpp - accumulation.samples);
        if (samples <= 0 || signal.aborted || !job.renderers || run !== current) continue;
        const output = await job.renderers[order].renderPass(accumulation.samples, samples);
        stepMs += output.milliseconds;
        rendered += samples;
      }
      if (rendered === 0) break;
      spent += stepMs;
      if (stepMs > 0) {
        const perSample = stepMs / rendered; // ms per spp of one order's image
        job.passSpp = Math.max(
          1,
          Math.min(budget.referencePass, Math.floor(REFERENCE_STEP_MS / perSample)),
        );
      }
      if (spent >= REFERENCE_FRAME_MS || signal.aborted || run !== current) break;
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
  };

  /**
   * One frame's passes: `count` more samples per pixel in both images. Both passes are
   * submitted before either is awaited: their read-backs (the GPU timestamps) come back
   * in one round trip instead of two.
   */
  const frame = async (current: Run, count: number, signal: AbortSignal): Promise<void> => {
    const { budget } = current;
    if (paused) return;
    const passes = ORDERS.map((order) => {
      const image = current.images[order];
      const have = image.accumulation.samples;
      const samples = Math.min(count, budget.maxSpp - have);
      // A new input stops the old scene between frames (its frame is dropped).
      if (samples <= 0 || signal.aborted) return null;
      return image.renderer.renderPass(have, samples);
    });
    const outputs = await Promise.all(passes);
    if (run !== current) return;
    for (const [i, order] of ORDERS.entries()) {
      const output = outputs[i];
      if (!output) continue;
      const image = current.images[order];
      image.milliseconds += output.milliseconds;
      image.lastPassMs = output.milliseconds;
      image.timing = output.timing ?? image.renderer.timing;
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
  };

  /**
   * Draws an image: on WebGPU straight from its moments on the GPU (a render pass, no
   * read-back); for the CPU twin, its float64 mean tone-mapped on the host.
   */
  const paint = async (order: Order, current: Run, accumulation: Accumulation): Promise<void> => {
    const existing = canvases[order];
    if (!existing) return;
    if (accumulation instanceof GpuAccumulation) {
      const canvas = canvasForContext(existing, 'webgpu');
      canvases[order] = canvas;
      const { device } = accumulation;
      let entry = views[order];
      if (!entry || entry.device !== device) {
        entry?.view.destroy();
        entry = { device, view: await AccumulationView.create(device, STATIC_KERNELS, canvas) };
        views[order] = entry;
      }
      await entry.view.draw(accumulation, { kind: 'radiance', exposure: 0 });
      return;
    }
    const canvas = canvasForContext(existing, '2d');
    canvases[order] = canvas;
    const drawing = context2d(canvas);
    if (!drawing) return;
    const { width, height } = current.budget;
    const mean = (await accumulation.readImage()).mean();
    const rgba = toneMapRgba8(width, height, mean, 0);
    drawing.putImageData(new ImageData(new Uint8ClampedArray(rgba), width, height), 0, 0);
  };

  /**
   * Each snapshot's error against the finished reference (one reduction each, once;
   * then the copy is freed), and the fitted slopes. Null while the reference is not done
   * or when the run was replaced meanwhile.
   */
  const referenceErrors = async (current: Run): Promise<ReferenceErrors | null> => {
    const job = current.reference;
    if (!job?.done) return null;
    const points: Record<Order, SweepPoint[]> = { single: [], multiple: [] };
    for (const order of ORDERS) {
      for (const snapshot of current.images[order].snapshots) {
        if (snapshot.error === null && snapshot.image) {
          snapshot.error = (
            await snapshot.image.statistics(job.accumulations[order])
          ).relativeError;
          snapshot.image.destroy();
          snapshot.image = null;
          if (run !== current) return null;
        }
        const error = snapshot.error ?? NaN;
        if (Number.isFinite(error))
          points[order].push({
            n: snapshot.samples,
            rmse: error,
            milliseconds: snapshot.milliseconds,
          });
      }
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
    return {
      points,
      slopes: {
        single: { time: slope('single', 'time'), spp: slope('single', 'spp') },
        multiple: { time: slope('multiple', 'time'), spp: slope('multiple', 'spp') },
      },
    };
  };

  const plotErrors = ({ points, slopes }: ReferenceErrors): void => {
    if (points.single.length + points.multiple.length === 0) return;
    plotHint?.remove();
    plotHint = null;
    const merged = mergeSeries([points.single, points.multiple]);
    // A guide of slope −½ through the multiple-scattering curve's first fitted point.
    const anchor = points.multiple.find((p) => p.n >= 4) ?? points.multiple[0];
    const guide = merged.x.map((x) =>
      anchor
        ? anchor.rmse * 10 ** (-0.5 * (x - Math.log10(Math.max(anchor.milliseconds, 1e-4))))
        : NaN,
    );
    plot?.update(merged.x, [
      {
        label: `single scattering, p = ${slopeText(slopes.single.time)}`,
        color: COLOURS.single,
        spanGaps: true,
        values: merged.values[0]!,
      },
      {
        label: `multiple scattering, p = ${slopeText(slopes.multiple.time)}`,
        color: COLOURS.multiple,
        spanGaps: true,
        values: merged.values[1]!,
      },
      { label: 'slope −½', color: '#888888', dash: [6, 4], values: guide },
    ]);
  };

  const showPlan = (current: Run): void => {
    const list = planList;
    if (!list || list.dataset['key'] === current.key) return;
    list.dataset['key'] = current.key;
    list.replaceChildren();
    for (const order of ORDERS) {
      const p = current.plans[order];
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
  };

  /**
   * Paints both images and gathers the frame's numbers (null: the run was replaced
   * meanwhile). The pictures go first; a refinement frame then adds one reference pass
   * (never the first picture after an input: it waits for that).
   */
  const collect = async (
    current: Run,
    backend: Backend<GpuContext>,
    withReference: boolean,
    signal: AbortSignal,
    stage: (samples: number) => Refinement,
  ): Promise<VolumePathTracerFrame | null> => {
    const { images } = current;
    // Both pictures and both reductions (64 bytes each: the readouts' numbers) at once: the
    // draws' error scopes and the read-backs come back in one round trip, not four in a row.
    const painted = Promise.all(
      ORDERS.map((order) => paint(order, current, images[order].accumulation)),
    );
    const reduced = Promise.all([
      images.single.accumulation.statistics(),
      images.multiple.accumulation.statistics(),
    ]);
    const [, [single, multiple]] = await Promise.all([painted, reduced]);
    if (run !== current) return null;
    for (const order of ORDERS) {
      const image = images[order];
      const caption = captions[order];
      if (caption)
        caption.textContent = `${order === 'single' ? 'Single scattering (order 1)' : 'Multiple scattering (all orders)'}: ${image.accumulation.samples} spp`;
      canvases[order]?.setAttribute(
        'aria-label',
        `${order === 'single' ? 'Single' : 'Multiple'} scattering image, ${image.accumulation.samples} samples per pixel`,
      );
    }
    const stats: Record<Order, ImageStatistics> = { single, multiple };
    if (run !== current) return null;
    if (withReference && !paused && !signal.aborted) {
      await referenceFor(backend, current);
      if (run !== current) return null;
      await referencePass(current, signal);
      if (run !== current) return null;
    }
    const errors = await referenceErrors(current);
    if (run !== current) return null;
    const numbers = (order: Order) => ({
      samples: images[order].accumulation.samples,
      milliseconds: images[order].milliseconds,
      lastPassMs: images[order].lastPassMs,
      stats: stats[order],
    });
    const job = current.reference;
    return {
      inputs: current.inputs,
      budget: current.budget,
      paused,
      images: { single: numbers('single'), multiple: numbers('multiple') },
      timing: images.multiple.timing,
      reference: {
        done: job?.done ?? false,
        cancelled: job ? job.cancelled : !current.referenceWanted,
      },
      errors,
      stage: stage(images.multiple.accumulation.samples),
    };
  };

  /** Measured pass time per sample per pixel of both images together, per backend (ms). */
  const msPerSpp: Partial<Record<'gpu' | 'cpu', number>> = {};

  /**
   * Samples per pixel of the first picture after an input: as many of the frame's
   * samples as the measured cost says fit the first-picture budget (one before anything
   * was measured, and at least one).
   */
  const previewSpp = (kind: 'gpu' | 'cpu', perFrame: number): number => {
    const cost = msPerSpp[kind];
    if (cost === undefined) return 1;
    // The CPU twin's passes queue in the compute worker behind the background pass it may
    // be running when the input comes (a running job is not stopped): the preview leaves
    // room for one (firstPictureProbe: a 200 ms background pass ahead of the preview's).
    const room = kind === 'cpu' ? BACKGROUND_FRAME_MS : 0;
    const fits = Math.floor((PREVIEW_WORK_SHARE * firstPictureBudget(kind) - room) / cost);
    return Math.max(1, Math.min(perFrame, fits));
  };

  /**
   * Samples per pixel of a background frame (the picture is complete; it goes on
   * accumulating): as many as the measured cost fits BACKGROUND_FRAME_MS, at most a
   * whole frame's. An input waits for the background frame in flight (its GPU work is
   * queued before the new picture's), so a frame of the reader's spp, ~0.9 s on
   * SwiftShader, made the first picture after an input slower than before previews
   * existed (bench/interaction.ts: 1.5 s → 2.5 s).
   */
  const backgroundSpp = (kind: 'gpu' | 'cpu', perFrame: number): number => {
    const cost = msPerSpp[kind];
    if (cost === undefined) return 1;
    return Math.max(1, Math.min(perFrame, Math.floor(BACKGROUND_FRAME_MS / cost)));
  };

  /** Kernel variants compiled ahead for the other medium, once per device. */
  const warmed = new WeakSet<GPUDevice>();
  /**
   * Once the run has nothing more to do (accumulation and reference done, or paused),
   * links and compiles the kernels of the other medium (grid or homogeneous): switching
   * to it then draws its preview at once instead of waiting seconds for a compile (the
   * pipelines are cached per device). Not earlier: a compile in flight holds up every
   * later GPU call of the page (measured with bench/firstPictureProbe.ts on SwiftShader:
   * the two kernels started 0.4 s before an albedo change delayed its first GPU call by
   * 1.5 s, first picture 2.9 s), and a reader usually moves a slider first.
   */
  const warmOtherScene = (gpu: GpuContext, inputs: PathTracerInputs): void => {
    if (warmed.has(gpu.device)) return;
    warmed.add(gpu.device);
    const other: SceneChoice = inputs.scene === 'cloud' ? 'sphere' : 'cloud';
    const size = { width: 8, height: 8 };
    for (const order of [1, 'unlimited'] as const) {
      const conditions = plan(
        buildScene({ ...inputs, scene: other }, order, size, 1, 1),
      ).conditions;
      void GpuSceneRenderer.prepare(gpu.device, STATIC_KERNELS, conditions).catch(() => undefined);
    }
  };

  /**
   * One frame on a backend: start a run for new parameters (its first frame a preview
   * within the first-picture budget), add samples, draw, then a reference pass.
   */
  const renderOn = async (
    backend: Backend<GpuContext>,
    request: FrameRequest,
  ): Promise<VolumePathTracerFrame | null> => {
    // Captured: the context's signal is a fresh one once the widget is destroyed.
    const signal = context.signal;
    const inputs = inputsFrom(context.values);
    const key = `${backend.kind}|${sceneKey(inputs)}`;
    try {
      if (run?.key !== key) {
        discardRun();
        run = await startRun(backend, inputs);
        if (signal.aborted || request.signal.aborted) {
          discardRun();
          return null;
        }
      }
      const current = run;
      const result = await advance(backend, current, request.signal, request.background ?? false);
      if (!result || request.signal.aborted) return null;
      if (result.stage.pending === null && backend.kind === 'gpu')
        warmOtherScene(backend.gpu, inputs);
      return result;
    } catch (error) {
      // Destroyed mid-frame (its renderers released under it), or a stale frame given up.
      if (signal.aborted || request.signal.aborted) return null;
      throw error;
    }
  };

  /**
   * One frame of a run: its first is the preview (as many samples as fit the
   * first-picture budget); the next tops it up to a whole frame of `spp` samples (what
   * one frame drew before previews existed: full quality), and from there each frame
   * adds `spp` as the reader asked, with a reference pass after the pictures.
   */
  const advance = async (
    backend: Backend<GpuContext>,
    current: Run,
    stale: AbortSignal,
    background: boolean,
  ): Promise<VolumePathTracerFrame | null> => {
    const { budget, inputs } = current;
    const perFrame = Math.min(inputs.spp, budget.maxFrameSpp);
    const have = current.images.multiple.accumulation.samples;
    const preview = have === 0;
    const count = preview
      ? previewSpp(backend.kind, perFrame)
      : background
        ? backgroundSpp(backend.kind, perFrame)
        : perFrame - (have % perFrame);
    await frame(current, count, stale);
    if (stale.aborted || run !== current) return null;
    const added = current.images.multiple.accumulation.samples - have;
    const passMs = current.images.single.lastPassMs + current.images.multiple.lastPassMs;
    if (added > 0 && passMs > 0) {
      const measured = passMs / added;
      const before = msPerSpp[backend.kind];
      msPerSpp[backend.kind] = before === undefined ? measured : 0.5 * (before + measured);
    }
    const stage = (samples: number): Refinement => {
      if (samples < perFrame && !paused)
        return { label: `Preview: ${samples} of ${perFrame} spp`, pending: 'frame' };
      // Complete for the reader's spp: the images (and the reference) go on refining as
      // background frames, settled, until both are done or the reader pauses.
      const more = !paused && hasWork(current);
      const done = samples >= budget.maxSpp;
      return {
        label: done
          ? `${samples} spp, done`
          : `${samples} of ${budget.maxSpp} spp${paused ? ', paused' : ''}`,
        pending: more ? 'background' : null,
      };
    };
    return collect(current, backend, !preview, stale, stage);
  };

  return {
    cpuNotice: `Showing the float64 CPU twin of the same path tracer: ${CPU_BUDGET.width}×${CPU_BUDGET.height} pixels, at most ${CPU_BUDGET.maxSpp} samples per pixel and ${CPU_BUDGET.maxFrameSpp} per frame, reference ${CPU_BUDGET.referenceSpp}.`,
    build(stage) {
      const panels = ORDERS.map((order) => {
        const canvas = imageCanvas(
          order === 'single' ? 'Single scattering image' : 'Multiple scattering image',
          GPU_BUDGET.width,
          GPU_BUDGET.height,
        );
        canvases[order] = canvas;
        const { panel } = imagePanel(
          canvas,
          order === 'single'
            ? 'Single scattering (order 1)'
            : 'Multiple scattering (path tracing, all orders)',
        );
        const caption = panel.querySelector('figcaption');
        if (caption) captions[order] = caption;
        panel.dataset['order'] = order;
        return panel;
      });
      stage.appendChild(imageFigure(...panels));

      const bar = document.createElement('div');
      bar.className = 'sb-sweep sb-vpt-bar';
      const pauseButton = document.createElement('button');
      pauseButton.type = 'button';
      pauseButton.className = 'sb-button';
      pauseButton.dataset['action'] = 'pause';
      pauseButton.textContent = 'Pause';
      pauseButton.addEventListener('click', () => {
        paused = !paused;
        pauseButton.textContent = paused ? 'Resume' : 'Pause';
        pauseButton.setAttribute('aria-pressed', String(paused));
        if (!paused) context.scheduleRender();
      });
      const restart = document.createElement('button');
      restart.type = 'button';
      restart.className = 'sb-button';
      restart.dataset['action'] = 'restart';
      restart.textContent = 'Restart';
      restart.addEventListener('click', () => {
        discardRun();
        context.scheduleRender();
      });
      referenceButton = document.createElement('button');
      referenceButton.type = 'button';
      referenceButton.className = 'sb-button';
      referenceButton.dataset['action'] = 'reference';
      referenceButton.textContent = 'Cancel reference';
      referenceButton.addEventListener('click', toggleReference);
      referenceProgress = document.createElement('progress');
      referenceProgress.max = 1;
      referenceProgress.value = 0;
      referenceProgress.setAttribute('aria-label', 'Reference progress');
      referenceStatus = document.createElement('span');
      referenceStatus.className = 'sb-sweep-status sb-vpt-reference-status';
      referenceStatus.setAttribute('aria-live', 'polite');
      bar.append(pauseButton, restart, referenceButton, referenceProgress, referenceStatus);
      stage.appendChild(bar);

      plotHint = document.createElement('p');
      plotHint.className = 'sb-sweep-hint';
      plotHint.textContent =
        'The error plot appears when the converged reference is ready: relative RMSE of each image against its reference, against accumulated GPU time, on log–log axes.';
      const plotArea = createPlotArea(
        'Log–log plot of the relative error of both images against accumulated GPU time',
      );
      stage.append(plotHint, plotArea);
      plot = new LinePlot(plotArea, {
        xLabel: 'log₁₀ accumulated time (ms)',
        yLabel: 'relative RMSE',
        yLog: true,
        height: 220,
      });
    },
    buildReadoutExtras(area) {
      const list = document.createElement('dl');
      list.className = 'sb-vpt-plan';
      list.setAttribute('aria-label', 'Plan of the two renders');
      area.appendChild(list);
      planList = list;
    },
    // The scene renderers take the device; they are made per run (startRun).
    createRenderer: (gpu: GpuContext) => gpu,
    renderGpu: (renderer, gpu, request) => renderOn({ kind: 'gpu', gpu, renderer }, request),
    renderCpu: (request) => renderOn({ kind: 'cpu', reason: '' }, request),
    refinement: (shown) => shown.stage,
    // A device loss or a failed GPU frame: the GPU run, references and pictures go.
    onCpuFallback: releaseAll,
    destroy: releaseAll,
    show(shown) {
      if (!run) return;
      const capped = shown.images.single.stats.capped + shown.images.multiple.stats.capped;
      if (capped > 0)
        context.showNotice(
          'capped',
          'warning',
          `${capped} walks reached the hard cap of 1024 vertices and were cut short: the multiple-scattering image is slightly too dark.`,
        );
      else context.clearNotice('capped');
      if (shown.errors) plotErrors(shown.errors);
      updateReferenceStatus();
      showPlan(run);
    },
  };
}
