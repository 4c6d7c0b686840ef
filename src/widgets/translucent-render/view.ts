// The drawing of <sb-translucent-render>: the three pictures (Lambert, BSSRDF with its
// overlay of irradiance samples or the selected pixel's octree cut, path-traced
// reference), the path tracer's own controls (continue, cancel, progress) and the ε
// sweep. The reference runs on its own schedule (steps of about STEP_BUDGET_MS) and
// writes its rows and the error rows itself; the frame's rows are widget.ts's.
import type { GpuContext } from '../../gpu/device.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import {
  dipolesOf,
  gatherCpu,
  imageError,
  interiorMask,
  visiblePoint,
  type Octree,
  type OctreeNode,
  type TranslucentScene,
} from '../../subsurface/translucent.ts';
import {
  BACKGROUND_BAND_BUDGET_MS,
  PathAccumulator,
  TranslucentKernels,
} from '../../subsurface/translucentKernels.ts';
import type { Backend } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { imageFigure, imagePanel } from '../base/imagePanel.ts';
import { SweepControls, type SweepPoint } from '../base/sweep.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import {
  CPU_FIRST_PICTURE_MS,
  GPU_FIRST_PICTURE_MS,
  Ladder,
  type FrameRequest,
  type RungChoice,
} from '../base/refinement.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { workerJobs } from '../../workers/compute.ts';
import { sampleSceneOf, type jobs as translucentJobTable } from './jobs.ts';
import {
  epsilonOf,
  errorAgainstNoisyReference,
  paintImage,
  referenceKey,
  sampleCountOf,
  sceneFromValues,
  type NoisyReferenceError,
} from './model.ts';
import type { TranslucentFrame } from './widget.ts';
import { context2d } from '../base/canvas2d.ts';

/**
 * A progressive step of the path tracer aims at this much GPU time (at least one sample
 * per pixel): an input waits for the step in flight, and steps of 120 ms held the first
 * picture after an input back by up to that much (issue 23).
 */
const STEP_BUDGET_MS = 40;
/** Largest image side the CPU fallback draws. */
const CPU_SIZE = 40;
/**
 * Irradiance samples of a GPU preview's octree when the scene's own is not built yet: the
 * default 4096 took 36–47 ms in the worker, and the first picture after an input waited
 * for it (issue 23, bench/firstPictureProbe.ts). A preview is 16² pixels, where a quarter
 * of the samples (twice their spacing) is still finer than a pixel on the default sphere.
 */
const PREVIEW_OCTREE_SAMPLES = 1024;

/**
 * Pass 1 (samples, octree, packing) on both backends and the CPU fallback's pictures,
 * in the compute worker, cached by arguments (jobs.ts): the page never builds or gathers.
 */
const translucentJobs = workerJobs<typeof translucentJobTable>('translucent-render');

const percent = (x: number): string =>
  Number.isFinite(x) ? `${x >= 0 ? '+' : '−'}${formatNumber(Math.abs(100 * x), 3)}%` : '—';
/**
 * An error against the path-traced reference, its noise variance subtracted (model.ts,
 * errorAgainstNoisyReference). While the subtracted noise is not small next to the error
 * (over ¼ of it) the estimate is itself noisy, so it is marked ≈ and the noise that was
 * subtracted is named; the label says "noise-corrected".
 */
const errorText = (e: NoisyReferenceError | null): string => {
  if (!e) return '— (no reference yet)';
  const noise = `±${formatNumber(100 * e.referenceNoise, 2)}%`;
  if (e.belowNoise) return `below the reference noise (${noise}) · ${percent(e.meanError)}`;
  const young = e.referenceNoise > e.relativeRmse / 4;
  const value = `${formatNumber(100 * e.relativeRmse, 3)}% · ${percent(e.meanError)}`;
  return young ? `≈ ${value} (ref. noise ${noise})` : value;
};

interface OctreeState {
  key: string;
  octree: Octree;
  packed: { nodes: Uint32Array; samples: Uint32Array };
  buildMs: number;
}

interface ReferenceState {
  key: string;
  accumulator: PathAccumulator;
  target: number;
  timing: string;
}

/**
 * The image sides of the progressive refinement (issue 23): a quarter, a half and all of
 * the chosen side (at least 8 pixels), one sixteenth, a quarter and all of the pixels.
 * Rebuilt when the side changes; the ladder starts on the largest rung its measured cost
 * per pixel fits into the first-picture budget.
 */
function sizeLadder(full: number, firstBudgetMs: number): Ladder<number> {
  const sides = [
    ...new Set([Math.max(8, Math.round(full / 4)), Math.max(8, Math.round(full / 2)), full]),
  ]
    .filter((side) => side <= full)
    .sort((a, b) => a - b);
  return new Ladder(
    sides.map((side) => ({
      value: side,
      work: (side * side) / (full * full),
      label: `${side}×${side} pixels`,
    })),
    firstBudgetMs,
  );
}

interface Pictures {
  diffuse: Float32Array;
  gather: { image: Float32Array; visited: Float32Array; exact: Float32Array | null };
}

export function createView(
  context: ViewContext<TranslucentKernels>,
): WidgetView<TranslucentFrame, TranslucentKernels> {
  const canvas = (label: string) => {
    const managed = context.canvas({ width: 64, height: 64 });
    managed.element.setAttribute('aria-label', label);
    return managed;
  };
  const canvases = [
    canvas('The sphere as a Lambertian surface'),
    canvas('The sphere with the dipole BSSRDF, Jensen–Buhler gather'),
    canvas('The sphere by volumetric path tracing (reference)'),
  ] as const;
  const set = (key: string, text: string, state?: 'ok' | 'bad'): void =>
    context.setReadout(key, text, state);

  let overlay: SVGSVGElement | null = null;
  let sweep: SweepControls | null = null;
  let runButton: HTMLButtonElement | null = null;
  let cancelButton: HTMLButtonElement | null = null;
  let progress: HTMLProgressElement | null = null;
  let status: HTMLElement | null = null;
  let octreeState: OctreeState | null = null;
  let reference: ReferenceState | null = null;
  let referenceToken = 0;
  let running = false;
  /** The reader cancelled the path tracer: later frames do not resume it (Run does). */
  let referenceStopped = false;
  /** Whether the last render ran on the CPU twins, where no reference is ever traced. */
  let cpuOnly = false;
  let pictures: Pictures | null = null;
  let scene: TranslucentScene | null = null;
  let exact: { key: string; image: Float32Array; milliseconds: number } | null = null;
  /** The selected pixel (column, row) of the BSSRDF picture. */
  let selected: [number, number] | null = null;
  /** Per backend: the ladder of image sides and the full side it was built for. */
  const ladders: Partial<Record<'gpu' | 'cpu', { full: number; ladder: Ladder<number> }>> = {};
  const ladderFor = (kind: 'gpu' | 'cpu', full: number): Ladder<number> => {
    const known = ladders[kind];
    if (known?.full === full) return known.ladder;
    const ladder = sizeLadder(full, kind === 'gpu' ? GPU_FIRST_PICTURE_MS : CPU_FIRST_PICTURE_MS);
    ladders[kind] = { full, ladder };
    return ladder;
  };

  /** The worker job's arguments for the octree of `count` samples (and its cache key). */
  const octreeArgs = (
    forScene: TranslucentScene,
    count: number,
  ): [ReturnType<typeof sampleSceneOf>, number] => [sampleSceneOf(forScene), count];

  /**
   * The octree of the scene's irradiance samples, from the worker (jobs.ts): it depends
   * on the sphere, its index and the light only, so a change of ε, size or exposure
   * reuses it. `signal`: an input meanwhile drops the job if it has not started.
   */
  const octreeFor = async (
    forScene: TranslucentScene,
    count: number,
    signal?: AbortSignal,
  ): Promise<OctreeState> => {
    const args = octreeArgs(forScene, count);
    const key = JSON.stringify(args);
    if (octreeState?.key === key) return octreeState;
    const built =
      translucentJobs.cached('octree', args) ??
      (await translucentJobs.run('octree', args, signal ? { signal } : {}));
    octreeState = { key, octree: built.octree, packed: built.packed, buildMs: built.buildMs };
    return octreeState;
  };

  const setRunning = (on: boolean): void => {
    if (cancelButton) cancelButton.disabled = !on;
    if (runButton) runButton.disabled = on;
    context.host.toggleAttribute('data-path-tracing', on);
  };

  const cancelReference = (message: string): void => {
    referenceStopped = message === 'cancelled';
    referenceToken += 1;
    if (running && status) status.textContent = `Path tracing ${message}.`;
    running = false;
    setRunning(false);
  };

  /** The selected pixel in the three pictures, with the reference's standard error there. */
  const showPixelValues = (p: number): void => {
    const average = (image: ArrayLike<number> | null | undefined): number =>
      image ? (image[3 * p]! + image[3 * p + 1]! + image[3 * p + 2]!) / 3 : NaN;
    const acc = reference?.accumulator;
    const pixels = (scene?.size ?? 0) ** 2;
    let value = '—';
    if (acc && acc.samples > 1 && acc.pixels === pixels) {
      const se = acc.standardError();
      const seMean = Math.hypot(se[3 * p]!, se[3 * p + 1]!, se[3 * p + 2]!) / 3;
      value = `${formatNumber(average(acc.mean()), 3)} ± ${formatNumber(seMean, 2)}`;
    }
    set(
      'pixel-values',
      `${formatNumber(average(pictures?.diffuse), 3)} · ${formatNumber(average(pictures?.gather.image), 3)} · ${value}`,
    );
  };

  /** Paints the reference and updates every error readout from the current accumulation. */
  const showReference = (): void => {
    if (!scene) return;
    const exposure = Number(context.values['exposure']);
    const mask = interiorMask(scene);
    const target = canvases[2].element;
    if (
      !reference ||
      reference.accumulator.samples === 0 ||
      reference.accumulator.pixels !== scene.size * scene.size
    ) {
      const blank = context2d(target);
      if (blank) {
        target.width = scene.size;
        target.height = scene.size;
        blank.fillStyle = '#000';
        blank.fillRect(0, 0, scene.size, scene.size);
      }
      const missing = cpuOnly ? '— (the reference needs WebGPU)' : errorText(null);
      set('diffuse-error', missing);
      set('gather-error', missing);
      if (!reference) return;
    }
    const acc = reference.accumulator;
    if (acc.samples === 0) return;
    const mean = acc.mean();
    const se = acc.standardError();
    paintImage(target, mean, scene.size, exposure);
    if (acc.samples < 2) {
      // One sample per pixel has no standard error, so its noise can be neither
      // subtracted nor shown: an error against it would be mostly that noise.
      const young = '— (waiting for a second reference sample per pixel)';
      set('diffuse-error', young);
      set('gather-error', young);
    } else if (pictures)
      set('diffuse-error', errorText(errorAgainstNoisyReference(pictures.diffuse, mean, se, mask)));
    if (acc.samples >= 2 && pictures)
      set(
        'gather-error',
        errorText(errorAgainstNoisyReference(pictures.gather.image, mean, se, mask)),
      );
    let squares = 0;
    let sum = 0;
    let n = 0;
    mask.forEach((inside, p) => {
      if (!inside) return;
      for (let c = 0; c < 3; c++) {
        squares += Number.isFinite(se[3 * p + c]!) ? se[3 * p + c]! ** 2 : 0;
        sum += mean[3 * p + c]!;
        n += 1;
      }
    });
    set('path-spp', `${acc.samples} of ${reference.target}`);
    set(
      'path-time',
      `${formatMilliseconds(acc.milliseconds)} (${reference.timing ? timingLabel(reference.timing as GpuTiming) : '…'})`,
    );
    set(
      'path-se',
      acc.samples > 1
        ? `${formatNumber((100 * Math.sqrt(squares / n)) / (sum / n), 3)}% of the mean`
        : '—',
    );
    set('path-capped', String(acc.capped), acc.capped > 0 ? 'bad' : 'ok');
    if (selected) showPixelValues(selected[1] * scene.size + selected[0]);
    if (progress) progress.value = Math.min(acc.samples / reference.target, 1);
  };

  /** Runs the path tracer until the target, in steps of about STEP_BUDGET_MS, yielding between. */
  const continueReference = async (): Promise<void> => {
    const job = reference;
    if (!job || running) return;
    const backend = await context.backend();
    if (backend.kind !== 'gpu') return;
    const token = ++referenceToken;
    // An input pauses the path tracer until the input's full-quality frame (finishFrame
    // resumes it): its steps would run between the preview's dispatches on the GPU and
    // hold the new picture back (issue 23).
    const input = context.inputSignal;
    const alive = (): boolean =>
      token === referenceToken && job === reference && !context.signal.aborted;
    const current = (): boolean => alive() && !input.aborted;
    running = true;
    setRunning(true);
    let perStep = 1;
    try {
      while (job.accumulator.samples < job.target) {
        if (!current()) return;
        if (!scene || scene.size * scene.size !== job.accumulator.pixels) return;
        const samples = Math.min(perStep, job.target - job.accumulator.samples);
        // In bands of rows: an input stops the step between two (the step's samples are
        // drawn again when the reference resumes, from the same offset).
        const batch = await backend.renderer.pathBatch(scene, {
          samples,
          offset: job.accumulator.samples,
          seed: Number(context.values['seed']),
          signal: input,
          bandBudgetMs: BACKGROUND_BAND_BUDGET_MS,
        });
        // A step that an input overtook is still this reference's: kept.
        if (!alive()) return;
        job.accumulator.add(batch);
        job.timing = batch.timing;
        // Aim the next step at the budget from this one's time per sample.
        const perSample = batch.milliseconds / samples;
        perStep = Math.max(
          1,
          Math.min(256, Math.floor(STEP_BUDGET_MS / Math.max(perSample, 1e-3))),
        );
        if (status)
          status.textContent = `Path tracing: ${job.accumulator.samples} of ${job.target} samples per pixel…`;
        showReference();
        await new Promise((resolve) => setTimeout(resolve, 0));
      }
      if (status)
        status.textContent = `Path tracing done: ${job.accumulator.samples} samples per pixel.`;
    } catch (error) {
      // An input stopped the step: the reference resumes after the input's full frame.
      if (error instanceof DOMException && error.name === 'AbortError') return;
      if (status)
        status.textContent = `Path tracing failed: ${error instanceof Error ? error.message : String(error)}`;
    } finally {
      if (token === referenceToken) {
        running = false;
        setRunning(false);
      }
    }
  };

  /** The pixel where the light is strongest on the sphere, half-way to its rim. */
  const defaultPixel = (on: TranslucentScene): [number, number] => {
    const l = on.toLight;
    const planar = Math.hypot(l[0], l[1]) || 1;
    const x = (0.5 * on.radius * l[0]) / planar;
    const y = (0.5 * on.radius * l[1]) / planar;
    return [
      Math.floor(((x / on.view + 1) / 2) * on.size),
      Math.floor(((1 - y / on.view) / 2) * on.size),
    ];
  };

  /** The irradiance samples (coloured by E) or the selected pixel's octree cut, over the BSSRDF picture. */
  const drawOverlay = (): void => {
    const svg = overlay;
    const state = octreeState;
    if (!svg || !scene || !state) return;
    const shown = scene;
    const size = shown.size;
    svg.setAttribute('viewBox', `0 0 ${size} ${size}`);
    svg.replaceChildren();
    const toPixel = (p: readonly number[]): [number, number] => [
      ((p[0]! / shown.view + 1) / 2) * size,
      ((1 - p[1]! / shown.view) / 2) * size,
    ];
    const circle = (x: number, y: number, r: number, cls: string, fill?: string): void => {
      const c = document.createElementNS('http://www.w3.org/2000/svg', 'circle');
      c.setAttribute('cx', x.toFixed(2));
      c.setAttribute('cy', y.toFixed(2));
      c.setAttribute('r', r.toFixed(2));
      c.setAttribute('class', cls);
      if (fill) c.setAttribute('fill', fill);
      svg.appendChild(c);
    };
    const mode = String(context.values['overlay']);
    const { samples } = state.octree;
    if (mode === 'samples') {
      let largest = 0;
      samples.irradiance.forEach((e) => (largest = Math.max(largest, e)));
      for (let k = 0; k < samples.count; k++) {
        const z = samples.positions[3 * k + 2]!;
        if (z <= 0) continue; // the far side is hidden
        const [x, y] = toPixel([samples.positions[3 * k]!, samples.positions[3 * k + 1]!]);
        const e = samples.irradiance[k]! / (largest || 1);
        circle(
          x,
          y,
          Math.max(0.35, size / 220),
          'sb-tr-sample',
          `rgb(${Math.round(40 + 215 * e)}, ${Math.round(60 + 160 * e)}, ${Math.round(200 - 170 * e)})`,
        );
      }
      set('pixel', `${samples.count} samples (dots, colour = E; far side hidden)`);
      return;
    }
    const [i, j] = selected ?? defaultPixel(shown);
    selected = [i, j];
    const x = visiblePoint(shown, i, j);
    if (!x) {
      set('pixel', `(${i}, ${j}) is off the sphere`);
      circle(i + 0.5, j + 0.5, 1.2, 'sb-tr-pixel');
      return;
    }
    const cut: OctreeNode[] = [];
    const result = gatherCpu(state.octree, dipolesOf(shown), x, epsilonOf(context.values), cut);
    const leafTerms = result.terms - cut.length;
    if (mode === 'cut') {
      for (const node of cut) {
        if (node.centroid[2] <= 0) continue;
        const [cx, cy] = toPixel(node.centroid);
        const r = (Math.sqrt(node.area / Math.PI) / (2 * shown.view)) * size;
        circle(cx, cy, r, 'sb-tr-node');
      }
    }
    circle(i + 0.5, j + 0.5, Math.max(1.2, size / 60), 'sb-tr-pixel');
    set(
      'pixel',
      `(${i}, ${j}): ${result.visited} nodes visited · ${cut.length} whole + ${leafTerms} single samples`,
    );
    context.host.dataset['pixelVisited'] = String(result.visited);
    showPixelValues(j * size + i);
  };

  const selectPixel = (i: number, j: number): void => {
    const size = scene?.size ?? 64;
    selected = [Math.min(Math.max(i, 0), size - 1), Math.min(Math.max(j, 0), size - 1)];
    drawOverlay();
  };

  /** Nodes visited per pixel on the sphere, mean. */
  const meanVisitedOf = (shown: TranslucentScene, drawn: Pictures): number => {
    let visitedSum = 0;
    let visitedCount = 0;
    interiorMask(shown).forEach((inside, p) => {
      if (!inside) return;
      visitedSum += drawn.gather.visited[p]!;
      visitedCount += 1;
    });
    return visitedSum / Math.max(visitedCount, 1);
  };

  /**
   * What both backends share after their pictures: paint them, start or extend the
   * reference on the GPU (or say it needs WebGPU), redraw the reference and the overlay.
   */
  const finishFrame = (
    shown: TranslucentScene,
    state: OctreeState,
    drawn: Pictures,
    frame: Omit<TranslucentFrame, 'size' | 'octree' | 'meanVisited' | 'exact'>,
    exactMs: number | null,
    /** Aborted when the inputs changed since this frame's request (FrameRequest.inputsChanged). */
    inputsChanged: AbortSignal,
  ): TranslucentFrame => {
    pictures = drawn;
    const exposure = Number(context.values['exposure']);
    paintImage(canvases[0].element, drawn.diffuse, shown.size, exposure);
    paintImage(canvases[1].element, drawn.gather.image, shown.size, exposure);
    const mask = interiorMask(shown);
    const exactImage = drawn.gather.exact;
    const result: TranslucentFrame = {
      ...frame,
      size: shown.size,
      octree: {
        samples: state.octree.samples.count,
        nodes: state.octree.nodes.length,
        buildMs: state.buildMs,
      },
      meanVisited: meanVisitedOf(shown, drawn),
      exact:
        exactImage && exactMs !== null
          ? {
              milliseconds: exactMs,
              relativeRmse: imageError(drawn.gather.image, exactImage, mask).relativeRmse,
            }
          : null,
    };

    if (cpuOnly) {
      set('path-spp', 'needs WebGPU');
      if (status) status.textContent = 'The path-traced reference needs WebGPU.';
      if (runButton) runButton.disabled = true;
    } else if (!inputsChanged.aborted) {
      // Not from a frame of a drag's earlier inputs (shown, refinement.ts showsWhenStale):
      // it would key the reference by the newest inputs and accumulate this scene in it.
      const key = referenceKey(context.values);
      const target = 2 ** Number(context.values['spp']);
      if (reference?.key !== key) {
        cancelReference('restarted');
        reference = {
          key,
          accumulator: new PathAccumulator(shown.size * shown.size),
          target,
          timing: '',
        };
        void continueReference();
      } else {
        // The same reference: a new target, or a step paused by an input, goes on.
        reference.target = target;
        if (!running && !referenceStopped && reference.accumulator.samples < target)
          void continueReference();
      }
    }
    showReference();
    drawOverlay();
    return result;
  };

  const runSweep = async (): Promise<void> => {
    await sweep?.runSeries(async () => {
      const backend: Backend<TranslucentKernels> = await context.backend();
      const swept = scene ?? sceneFromValues(context.values);
      const count = sampleCountOf(context.values);
      const state = await octreeFor(swept, count);
      const mask = interiorMask(swept);
      // On the CPU the gathers run in the worker; their time is the worker's float64 time.
      const measure = async (
        inverse: number,
      ): Promise<{ image: Float32Array; milliseconds: number }> => {
        const epsilon = inverse === Infinity ? 0 : 1 / inverse;
        if (backend.kind === 'gpu')
          return backend.renderer.gather(swept, state.octree, epsilon, state.packed);
        const drawn = await translucentJobs.run('pictures', [swept, count, epsilon]);
        return { image: drawn.image, milliseconds: drawn.gatherMs };
      };
      const direct = (await measure(Infinity)).image;
      const cache = new Map<number, { image: Float32Array; milliseconds: number }>();
      const run = async (
        inverse: number,
      ): Promise<{ image: Float32Array; milliseconds: number }> => {
        let r = cache.get(inverse);
        if (!r) {
          r = await measure(inverse);
          cache.set(inverse, r);
        }
        return r;
      };
      return {
        series: [
          { label: 'vs direct sum (ε = 0)', color: '#3d6fd6' },
          { label: 'vs path-traced reference', color: '#d9473f', dash: [6, 4] },
        ],
        measure: async (series: number, inverse: number): Promise<Omit<SweepPoint, 'n'>> => {
          const r = await run(inverse);
          if (series === 0)
            return {
              rmse: imageError(r.image, direct, mask).relativeRmse,
              milliseconds: r.milliseconds,
            };
          // Against the reference, as in the readouts: its noise variance subtracted.
          const acc = reference?.accumulator;
          const error =
            acc && acc.samples > 0 && acc.pixels === swept.size ** 2
              ? errorAgainstNoisyReference(r.image, acc.mean(), acc.standardError(), mask)
                  .relativeRmse
              : NaN;
          return { rmse: error, milliseconds: r.milliseconds };
        },
        finish: (points: readonly (readonly SweepPoint[])[]) => {
          const first = points[0]?.[0];
          const last = points[0]?.at(-1);
          return first && last
            ? `ε = 1: ${formatNumber(100 * first.rmse, 3)}% in ${formatMilliseconds(first.milliseconds)}; ε = 1/256: ${formatNumber(100 * last.rmse, 3)}% in ${formatMilliseconds(last.milliseconds)}`
            : 'no points';
        },
        failed: () => undefined,
      };
    });
  };

  /**
   * The scene of this frame and its octree (the CPU draws a smaller image), at the side of
   * this stage's rung. Only a full-quality frame becomes `scene`, which the reference, the
   * overlay and the selected pixel are measured in.
   */
  const prepare = async (
    onCpu: boolean,
    request: FrameRequest,
  ): Promise<{
    shown: TranslucentScene;
    state: OctreeState;
    ladder: Ladder<number>;
    choice: RungChoice<number>;
  }> => {
    const shown = sceneFromValues(context.values);
    cpuOnly = onCpu;
    if (onCpu) shown.size = Math.min(shown.size, CPU_SIZE);
    const ladder = ladderFor(onCpu ? 'cpu' : 'gpu', shown.size);
    const choice = ladder.pick(request);
    shown.size = choice.rung.value;
    const count = sampleCountOf(context.values);
    // A GPU preview of a scene whose octree is still to be built takes a smaller one;
    // one already built (an input of ε, size or exposure) is used as it is.
    const preview =
      !onCpu && !choice.final && count > PREVIEW_OCTREE_SAMPLES && !octreeReady(shown, count);
    const state = await octreeFor(shown, preview ? PREVIEW_OCTREE_SAMPLES : count, request.signal);
    if (choice.final) scene = shown;
    return { shown, state, ladder, choice };
  };

  /** Whether the octree of `count` samples for this scene is built (here or in the worker's cache). */
  const octreeReady = (forScene: TranslucentScene, count: number): boolean => {
    const args = octreeArgs(forScene, count);
    return (
      octreeState?.key === JSON.stringify(args) ||
      translucentJobs.cached('octree', args) !== undefined
    );
  };

  /** A preview's pictures: painted (pixelated), nothing else touched; the readouts say it is one. */
  const finishPreview = (
    shown: TranslucentScene,
    state: OctreeState,
    drawn: Pictures,
    frame: Omit<TranslucentFrame, 'size' | 'octree' | 'meanVisited' | 'exact'>,
    refinement: TranslucentFrame['refinement'],
  ): TranslucentFrame => {
    const exposure = Number(context.values['exposure']);
    paintImage(canvases[0].element, drawn.diffuse, shown.size, exposure);
    paintImage(canvases[1].element, drawn.gather.image, shown.size, exposure);
    for (const key of ['diffuse-error', 'gather-error']) set(key, 'after the preview…');
    // The stage line says when the preview's octree has fewer samples than asked for.
    const asked = sampleCountOf(context.values);
    const used = state.octree.samples.count;
    const stage =
      refinement && used < asked
        ? { ...refinement, label: `${refinement.label}, ${used} of ${asked} irradiance samples` }
        : refinement;
    return {
      ...frame,
      size: shown.size,
      octree: {
        samples: state.octree.samples.count,
        nodes: state.octree.nodes.length,
        buildMs: state.buildMs,
      },
      meanVisited: meanVisitedOf(shown, drawn),
      exact: null,
      ...(stage ? { refinement: stage } : {}),
    };
  };

  return {
    // A getter: the notice names the size the CPU drew at (the base reads it after renderCpu).
    get cpuNotice() {
      return `Showing the float64 twins of the Lambertian and BSSRDF pictures at ${scene?.size ?? CPU_SIZE}² pixels; the path-traced reference needs WebGPU and is not run.`;
    },
    build(stage) {
      const diffuse = imagePanel(canvases[0].element, 'Lambert, albedo = dipole Rd');
      const bssrdf = imagePanel(canvases[1].element, 'Dipole BSSRDF, octree gather');
      const path = imagePanel(canvases[2].element, 'Path tracing (reference)');
      // The BSSRDF picture holds an SVG overlay (samples or cut) and takes clicks and arrow keys.
      const holder = document.createElement('div');
      holder.className = 'sb-tr-holder';
      holder.tabIndex = 0;
      holder.setAttribute('role', 'group');
      holder.setAttribute(
        'aria-label',
        'Dipole BSSRDF picture: click a pixel or use the arrow keys to show the octree cut that pixel uses',
      );
      overlay = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
      overlay.classList.add('sb-tr-overlay');
      overlay.setAttribute('aria-hidden', 'true');
      bssrdf.panel.insertBefore(holder, bssrdf.panel.firstChild);
      holder.append(canvases[1].element, overlay);
      holder.addEventListener('click', (event) => {
        const rect = holder.getBoundingClientRect();
        const size = scene?.size ?? 64;
        const i = Math.floor(((event.clientX - rect.left) / rect.width) * size);
        const j = Math.floor(((event.clientY - rect.top) / rect.height) * size);
        selectPixel(i, j);
      });
      holder.addEventListener('keydown', (event) => {
        const step: Record<string, [number, number]> = {
          ArrowLeft: [-1, 0],
          ArrowRight: [1, 0],
          ArrowUp: [0, -1],
          ArrowDown: [0, 1],
        };
        const move = step[event.key];
        if (!move) return;
        event.preventDefault();
        const size = scene?.size ?? 64;
        const [i, j] = selected ?? [Math.floor(size / 2), Math.floor(size / 2)];
        const stride = event.shiftKey ? 8 : 1;
        selectPixel(i + stride * move[0], j + stride * move[1]);
      });
      stage.appendChild(imageFigure(diffuse.panel, bssrdf.panel, path.panel));

      const controls = document.createElement('div');
      controls.className = 'sb-sweep sb-tr-path';
      runButton = document.createElement('button');
      runButton.type = 'button';
      runButton.className = 'sb-button';
      runButton.textContent = 'Continue path tracing';
      runButton.addEventListener('click', () => {
        referenceStopped = false;
        void continueReference();
      });
      cancelButton = document.createElement('button');
      cancelButton.type = 'button';
      cancelButton.className = 'sb-button';
      cancelButton.textContent = 'Cancel';
      cancelButton.disabled = true;
      cancelButton.addEventListener('click', () => cancelReference('cancelled'));
      progress = document.createElement('progress');
      progress.max = 1;
      progress.value = 0;
      progress.setAttribute('aria-label', 'Path tracing progress');
      status = document.createElement('span');
      status.className = 'sb-tr-status';
      status.setAttribute('role', 'status');
      controls.append(runButton, cancelButton, progress, status);
      stage.appendChild(controls);

      sweep = new SweepControls(
        stage,
        context.host,
        {
          name: '1/ε',
          buttonText: 'Sweep ε',
          hint: 'Sweep ε from 1 to 1/256: the gather’s error against the direct sum (ε = 0) falls as its time grows, while its error against the path-traced reference levels off at the dipole’s own model error.',
          color: '#3d6fd6',
          points: [1, 2, 4, 8, 16, 32, 64, 128, 256],
          errorName: 'relative RMSE',
        },
        () => void runSweep(),
      );
    },
    createRenderer: (gpu: GpuContext) => new TranslucentKernels(gpu.device, STATIC_KERNELS),
    refinement: (frame) => frame.refinement,
    async renderGpu(renderer, _gpu, request) {
      const { shown, state, ladder, choice } = await prepare(false, request);
      const epsilon = epsilonOf(context.values);
      const start = performance.now();
      // Both pictures submitted together (one read-back wait, not two); a preview's gather
      // in one dispatch: its 16² pixels are a few ms of GPU time, and bands would add a
      // read-back round trip each to the first picture (issue 23).
      const [diffuse, gather] = await Promise.all([
        renderer.diffuse(shown),
        renderer.gather(shown, state.octree, epsilon, state.packed, request.signal, !choice.final),
      ]);
      ladder.record(choice.index, performance.now() - start);
      if (!choice.final)
        return finishPreview(
          shown,
          state,
          { diffuse: diffuse.image, gather: { ...gather, exact: null } },
          {
            epsilon,
            diffuse: { milliseconds: diffuse.milliseconds, timing: diffuse.timing as GpuTiming },
            gather: { milliseconds: gather.milliseconds, timing: gather.timing as GpuTiming },
          },
          ladder.refinement(choice),
        );
      // The direct sum does not depend on ε: computed once per octree and image size.
      const exactKey = `${state.key}|${shown.size}`;
      if (exact?.key !== exactKey)
        exact = {
          key: exactKey,
          ...(await renderer.gather(shown, state.octree, 0, state.packed, request.signal)),
        };
      return finishFrame(
        shown,
        state,
        {
          diffuse: diffuse.image,
          gather: { image: gather.image, visited: gather.visited, exact: exact.image },
        },
        {
          epsilon,
          diffuse: { milliseconds: diffuse.milliseconds, timing: diffuse.timing as GpuTiming },
          gather: { milliseconds: gather.milliseconds, timing: gather.timing as GpuTiming },
        },
        exact.milliseconds,
        request.inputsChanged,
      );
    },
    async renderCpu(request) {
      const { shown, state, ladder, choice } = await prepare(true, request);
      const epsilon = epsilonOf(context.values);
      // Both pictures in the worker; the ladder learns their float64 time there.
      const drawn = await translucentJobs.run(
        'pictures',
        [shown, sampleCountOf(context.values), epsilon],
        { signal: request.signal },
      );
      ladder.record(choice.index, drawn.diffuseMs + drawn.gatherMs);
      const pictures = {
        diffuse: drawn.diffuse,
        gather: { image: drawn.image, visited: drawn.visited, exact: null },
      };
      const times = {
        epsilon,
        diffuse: { milliseconds: drawn.diffuseMs, timing: 'cpu' as const },
        gather: { milliseconds: drawn.gatherMs, timing: 'cpu' as const },
      };
      if (!choice.final)
        return finishPreview(shown, state, pictures, times, ladder.refinement(choice));
      return finishFrame(shown, state, pictures, times, null, request.inputsChanged);
    },
    onCpuFallback(reason) {
      cancelReference(`stopped: ${reason}`);
      sweep?.cancel('stopped: the GPU was lost');
    },
    destroy() {
      cancelReference('stopped');
      sweep?.cancel('stopped');
    },
  };
}
