// The view of <sb-inverse-render>: the training views (target over current fit), the
// held-out view with its error image, the run bar (Start/Pause, Reset, progress,
// status) and the loss curve. Rendering sets up a trainer for the current problem
// (GPU, or the float64 twin in a Web Worker); Start runs the training as a long job,
// one batch of iterations per animation frame so that the page stays live and
// Pause/Reset act at once, and each batch reports a frame to the readouts.
import type { Backend } from '../base/backend.ts';
import type { FrameBackend, FrameCost } from '../base/definition.ts';
import { formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import { gradientCss, imageCanvas, imageFigure, imagePanel } from '../base/imagePanel.ts';
import { LinePlot, createPlotArea } from '../base/plot.ts';
import { SLICE_MS } from '../base/refinement.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { CpuTrainer, errorColour, paintError, paintView } from './cpuBackend.ts';
import { InverseTrainerGpu, KERNEL } from './gpuBackend.ts';
import {
  CPU_IMAGE_SIZE,
  CPU_MAX_RESOLUTION,
  CPU_MAX_TABLE_LOG2,
  NOVEL_ELEVATION,
  PREVIEW_TARGET_STEPS,
  TARGET_STEPS,
  effectiveBatch,
  hyperFrom,
  problemFrom,
  problemKey,
  viewError,
  type ModelKind,
  type Problem,
  type Trainer,
} from './model.ts';
import { NEURAL_KERNEL, NeuralTrainerGpu } from './neuralGpuBackend.ts';
import { neuralParameterCount } from '../../reference/neural.ts';
import type { InverseRenderFrame } from './widget.ts';

/**
 * Wall time one batch of iterations should take: long enough to amortize a submit,
 * short enough that a batch never holds the page (or, on the GPU, the queue other
 * widgets share) past the long-task threshold (issue 23: steps of at most SLICE_MS).
 */
const BATCH_TARGET_MS = 0.8 * SLICE_MS;
/** How often the views are re-rendered and read back during a run, at the most. */
const REDRAW_MS = 700;
/**
 * The largest share of a run's wall time that the redraws (render of every view and
 * read-back) may take. A redraw marches every pixel of every view, training and
 * held-out: for the neural field on SwiftShader it measured as long as 3–4 iterations
 * (bench/neural.ts: 9 views of 32² pixels × 32 samples, 7.3 s against 2.0 s per
 * iteration of 512 rays), so redrawing every REDRAW_MS took most of the minute.
 * The interval therefore grows to (1 − share)/share times the last redraw's wall time.
 */
const REDRAW_SHARE = 0.2;
/** Window of the iteration-rate readout. */
const RATE_WINDOW_MS = 4000;
/** Scale of the error image: |C − C*| of this size is the brightest colour. */
const ERROR_SCALE_TOP = 0.25;

const REGULARIZER_NAMES: Readonly<Record<string, string>> = {
  none: 'no regularizer',
  tv: 'total variation',
  sparsity: 'sparsity prior',
};

/** The GPU renderer: the page's device (the trainer is built per problem). */
interface GpuKernel {
  gpu: GpuContext;
}

/** A finished or running fit, kept so that the other model's curve can be drawn beside it. */
interface ModelRun {
  /** What both models share: backend, training views, image size, samples per ray, seed. */
  key: string;
  /** Wall time of training (ms) at the end of each iteration, and that iteration's loss. */
  times: number[];
  losses: number[];
  /** Held-out MSE at the redraws: [wall time (ms), MSE]. */
  novel: [number, number][];
}

/** The fit's parameters and the model's name for the readouts. */
export function modelParameters(problem: Problem): number {
  return problem.model === 'neural'
    ? neuralParameterCount(problem.tableSize)
    : 4 * problem.resolution ** 3;
}

const MODEL_NAMES: Readonly<Record<ModelKind, string>> = {
  grid: 'voxel grid',
  neural: 'neural field',
};

interface RateSample {
  at: number;
  iteration: number;
  /** Time spent in iterations so far (GPU timestamps, else wall or CPU time), ms. */
  spent: number;
}

export function createView(
  context: ViewContext<GpuKernel>,
): WidgetView<InverseRenderFrame, GpuKernel> {
  let viewStrip: HTMLElement | null = null;
  let viewCanvases: { target: HTMLCanvasElement; fit: HTMLCanvasElement }[] = [];
  let novelTarget: HTMLCanvasElement | null = null;
  let novelFit: HTMLCanvasElement | null = null;
  let novelError: HTMLCanvasElement | null = null;
  let novelCaption: HTMLElement | null = null;
  let plot: LinePlot | null = null;
  let plotArea: HTMLElement | null = null;
  let plotHint: HTMLElement | null = null;
  let startButton: HTMLButtonElement | null = null;
  let resetButton: HTMLButtonElement | null = null;
  let progress: HTMLProgressElement | null = null;
  let status: HTMLElement | null = null;

  let trainer: Trainer | null = null;
  let trainerKey = '';
  let frameBackend: FrameBackend = { kind: 'cpu', reason: '' };
  let novelAzimuth = NaN;
  let targets: ArrayLike<number> = [];
  /** Loss of every iteration so far (before its update). */
  let losses: number[] = [];
  /** Wall time of training (ms) at the end of each iteration of this run. */
  let times: number[] = [];
  /** The latest run of each model (the current one included), for the comparison. */
  const runs = new Map<ModelKind, ModelRun>();
  /** Held-out MSE measured after n updates, by n. */
  let novelErrors = new Map<number, number>();
  let initialTrainMse = NaN;
  let trainMse = NaN;
  let tenfoldAt: number | null = null;
  let iteration = 0;
  let dropped = 0;
  let timing = '';
  let spent = 0;
  let rateSamples: RateSample[] = [];
  /** The render of every view at set-up, then the time per iteration of the last batch. */
  let cost: FrameCost = { milliseconds: NaN, timing: 'cpu' };
  /** Wall time of the set-up of the current problem: targets and the first render of every view (ms). */
  let setupMs = NaN;
  /** The last batch: its iterations and wall time (ms); null before the first. */
  let lastBatch: { iterations: number; milliseconds: number } | null = null;
  /** Wall time of the last redraw (render of every view and read-back), ms, and its iteration. */
  let redrawMs = 0;
  let drawnIteration = -1;
  let running = false;
  /** Bumped whenever the run must stop (reset, new problem, device loss, destroy). */
  let token = 0;
  let setupToken = 0;

  const setStatus = (text: string): void => {
    if (status) status.textContent = text;
  };

  const budget = (): number => Math.round(Number(context.values['iterations']));

  function syncButtons(): void {
    if (startButton) {
      startButton.textContent = running ? 'Pause' : iteration > 0 ? 'Resume' : 'Start';
      startButton.setAttribute('aria-pressed', String(running));
      startButton.disabled = !trainer;
    }
    if (resetButton) resetButton.disabled = !trainer;
    context.host.toggleAttribute('data-running', running);
  }

  /** Stops a run after its current batch; the fit is kept. */
  function stop(message: string): void {
    const wasRunning = running;
    running = false;
    token += 1;
    if (wasRunning && message) setStatus(`Run ${message}.`);
    syncButtons();
  }

  /** Discards the fit and starts from the initial grid (same problem). */
  function reset(): void {
    stop('');
    trainerKey = '';
    context.scheduleRender();
  }

  function frame(): InverseRenderFrame | null {
    if (!trainer) return null;
    const problem = trainer.problem;
    const hyper = hyperFrom(context.values);
    const first = rateSamples[0];
    const latest = rateSamples[rateSamples.length - 1];
    const rate =
      first && latest && latest.at > first.at
        ? ((latest.iteration - first.iteration) * 1000) / (latest.at - first.at)
        : NaN;
    const iterations = first && latest ? latest.iteration - first.iteration : 0;
    const other = otherRun(problem);
    return {
      model: problem.model,
      parameters: modelParameters(problem),
      tableSize: problem.tableSize,
      trainSeconds: (times[times.length - 1] ?? 0) / 1000,
      comparison: other ? summarize(other) : null,
      iteration,
      budget: budget(),
      lastLoss: losses[losses.length - 1] ?? null,
      trainMse,
      initialTrainMse,
      tenfoldAt,
      novelMse: novelErrors.get(iteration) ?? [...novelErrors.values()].pop() ?? null,
      rate,
      iterationMs:
        first && latest && iterations > 0 ? (latest.spent - first.spent) / iterations : null,
      timing,
      dropped,
      cost,
      setupMs,
      lastBatch,
      resolution: problem.resolution,
      trainViews: problem.trainViews,
      size: problem.size,
      steps: problem.steps,
      rays: effectiveBatch(hyper, problem.trainViews * problem.size * problem.size),
      learningRate: hyper.learningRate,
      // The priors act on voxels; the neural field is fitted by the data term alone.
      regularizer:
        problem.model === 'neural'
          ? 'no regularizer: the priors act on voxels'
          : (REGULARIZER_NAMES[String(context.values['regularizer'])] ?? ''),
    };
  }

  /** The shared part of a problem, under which the two models' runs are compared. */
  function comparisonKey(problem: Problem): string {
    const shared = {
      views: problem.views.slice(0, problem.trainViews),
      size: problem.size,
      steps: problem.steps,
      seed: problem.seed,
    };
    return `${frameBackend.kind}:${JSON.stringify(shared)}`;
  }

  /** The other model's latest run on the same views, if any. */
  function otherRun(problem: Problem): ModelRun | null {
    const other: ModelKind = problem.model === 'neural' ? 'grid' : 'neural';
    const run = runs.get(other);
    return run && run.key === comparisonKey(problem) && run.losses.length > 0 ? run : null;
  }

  function summarize(run: ModelRun): NonNullable<InverseRenderFrame['comparison']> {
    const recent = run.losses.slice(-10);
    const novel = run.novel[run.novel.length - 1];
    return {
      model: runs.get('grid') === run ? 'grid' : 'neural',
      iterations: run.losses.length,
      seconds: (run.times[run.times.length - 1] ?? 0) / 1000,
      loss: recent.reduce((a, b) => a + b, 0) / recent.length,
      novelMse: novel ? novel[1] : null,
    };
  }

  function buildViewCells(problem: Problem): void {
    if (!viewStrip) return;
    viewStrip.replaceChildren();
    viewStrip.style.setProperty('--sb-ir-columns', String(Math.min(problem.trainViews, 8)));
    viewCanvases = [];
    for (let view = 0; view < problem.trainViews; view++) {
      const cell = document.createElement('figure');
      cell.className = 'sb-ir-view';
      const target = imageCanvas(`Training view ${view + 1}: target`, problem.size, problem.size);
      const fit = imageCanvas(`Training view ${view + 1}: current fit`, problem.size, problem.size);
      target.classList.add('sb-ir-thumb');
      fit.classList.add('sb-ir-thumb');
      const caption = document.createElement('figcaption');
      const degrees = Math.round((problem.views[view]!.azimuth * 180) / Math.PI) % 360;
      caption.textContent = `${degrees}°`;
      cell.append(target, fit, caption);
      viewStrip.appendChild(cell);
      viewCanvases.push({ target, fit });
    }
  }

  /** Renders the current grid from every view, paints it and measures the errors. */
  async function drawFit(): Promise<void> {
    const current = trainer;
    if (!current) return;
    const problem = current.problem;
    const started = performance.now();
    drawnIteration = iteration;
    const { image, gpuMs } = await current.render();
    redrawMs = performance.now() - started;
    if (current !== trainer) return;
    if (iteration === 0) {
      // Before any iteration the frame's cost is this render of every view.
      cost =
        frameBackend.kind === 'cpu'
          ? { milliseconds: performance.now() - started, timing: 'cpu' }
          : gpuMs === null
            ? { milliseconds: performance.now() - started, timing: 'gpu-wall' }
            : { milliseconds: gpuMs, timing: 'gpu-timestamp' };
    }
    const pixels = problem.size * problem.size;
    for (const [view, canvases] of viewCanvases.entries())
      paintView(canvases.fit, image, view, problem.size);
    let sum = 0;
    for (let view = 0; view < problem.trainViews; view++)
      sum += viewError(image, targets, view, pixels);
    trainMse = sum / problem.trainViews;
    const novel = viewError(image, targets, problem.trainViews, pixels);
    novelErrors.set(iteration, novel);
    const run = runs.get(problem.model);
    if (run && run.key === comparisonKey(problem))
      run.novel.push([times[iteration - 1] ?? 0, novel]);
    if (novelFit) paintView(novelFit, image, problem.trainViews, problem.size);
    if (novelError)
      paintError(novelError, image, targets, problem.trainViews, problem.size, ERROR_SCALE_TOP);
    if (novelCaption) {
      const degrees = Math.round((problem.views[problem.trainViews]!.azimuth * 180) / Math.PI);
      novelCaption.textContent = `Held-out view (azimuth ${degrees}°, ${Math.round((NOVEL_ELEVATION * 180) / Math.PI)}° above): MSE ${formatNumber(novel, 3)}`;
    }
    novelFit?.setAttribute(
      'aria-label',
      `Held-out view, current fit after ${iteration} iterations: MSE ${formatNumber(novel, 3)}`,
    );
  }

  /** Builds a trainer for a new problem: targets, initial grid, its first render. */
  async function restart(create: () => Promise<Trainer>, key: string): Promise<void> {
    stop('');
    const setup = ++setupToken;
    trainer?.destroy();
    trainer = null;
    trainerKey = '';
    setStatus('Preparing the target images…');
    const started = performance.now();
    const created = await create();
    if (setup !== setupToken || context.signal.aborted) {
      created.destroy();
      return;
    }
    trainer = created;
    const problem = created.problem;
    losses = [];
    times = [];
    runs.set(problem.model, { key: comparisonKey(problem), times, losses, novel: [] });
    novelErrors = new Map();
    tenfoldAt = null;
    iteration = 0;
    dropped = 0;
    timing = '';
    spent = 0;
    rateSamples = [];
    novelAzimuth = problem.views[problem.views.length - 1]!.azimuth;
    lastBatch = null;
    trainMse = NaN;
    initialTrainMse = NaN;
    /** Draws `images` as the targets and reports a frame of the set-up saying what it is. */
    let cellsBuilt = false;
    const showTargets = (images: ArrayLike<number>, status: string, label: string): void => {
      if (!cellsBuilt) buildViewCells(problem);
      cellsBuilt = true;
      for (const [view, canvases] of viewCanvases.entries())
        paintView(canvases.target, images, view, problem.size);
      if (novelTarget) paintView(novelTarget, images, problem.trainViews, problem.size);
      cost = {
        milliseconds: performance.now() - started,
        timing: frameBackend.kind === 'cpu' ? 'cpu' : 'gpu-wall',
      };
      const shown = frame();
      if (!shown) return;
      setStatus(status);
      context.report({ ...shown, refinement: { label, pending: 'job' } }, frameBackend);
    };
    // Issue 23: a preview of the targets (fewer samples per ray, GPU only) comes back while
    // the GPU renders the exact ones, and is drawn at once.
    const early = created.readPreviewTargets ? await created.readPreviewTargets() : null;
    if (setup !== setupToken || context.signal.aborted) return;
    if (early)
      showTargets(
        early,
        'Preparing the target images: a preview is drawn…',
        `Preview: target views with ${PREVIEW_TARGET_STEPS} of ${TARGET_STEPS} samples per ray; the exact targets follow`,
      );
    targets = await created.readTargets();
    if (setup !== setupToken || context.signal.aborted) return;
    // The exact targets are a picture of the new problem already; show them with the stage
    // line saying that set-up goes on, instead of nothing until the first render of the fit
    // (seconds of pipeline builds on a CPU WebGPU). The render's own frame follows.
    showTargets(
      targets,
      'Setting up: the target views are drawn; rendering the initial fit…',
      'Setting up: target views drawn; the first render of the fit follows',
    );
    await drawFit();
    if (setup !== setupToken || context.signal.aborted) return;
    setupMs = performance.now() - started;
    initialTrainMse = trainMse;
    trainerKey = key;
    plotLosses();
    setStatus(`Ready: press Start to fit the ${MODEL_NAMES[problem.model]}.`);
    syncButtons();
  }

  async function moveNovelView(problem: Problem): Promise<void> {
    const current = trainer;
    if (!current) return;
    const view = problem.views[problem.views.length - 1]!;
    await current.setNovelView(view);
    novelAzimuth = view.azimuth;
    targets = await current.readTargets();
    if (novelTarget) paintView(novelTarget, targets, problem.trainViews, problem.size);
    // While running, the loop's next redraw shows the fit from there.
    if (!running) await drawFit();
  }

  /** The trainer for the current values (a new one when the problem changed), then a frame. */
  async function sync(
    kind: 'gpu' | 'cpu',
    create: (problem: Problem) => Promise<Trainer>,
  ): Promise<InverseRenderFrame | null> {
    const problem = problemFrom(context.values, kind);
    const key = `${kind}:${problemKey(problem)}`;
    if (key !== trainerKey || !trainer) await restart(() => create(problem), key);
    else if (problem.views[problem.views.length - 1]!.azimuth !== novelAzimuth)
      await moveNovelView(problem);
    return frame();
  }

  function toggleRun(): void {
    if (running) {
      stop('paused');
      // The loop redraws only every few redraws' time (REDRAW_SHARE): show the fit
      // where the run paused.
      if (drawnIteration !== iteration)
        void drawFit()
          .then(report)
          .catch((error: unknown) =>
            setStatus(`Redraw failed: ${error instanceof Error ? error.message : String(error)}`),
          );
      return;
    }
    if (!trainer) return;
    if (iteration >= budget()) {
      setStatus('The iteration budget is spent: Reset, or raise the budget.');
      return;
    }
    running = true;
    syncButtons();
    void loop(token);
  }

  function report(): void {
    const current = frame();
    if (current) context.report(current, frameBackend);
  }

  /** The training job: one batch per animation frame until paused, done or stopped. */
  async function loop(runToken: number): Promise<void> {
    let count = 1;
    let lastDraw = performance.now();
    const live = (): boolean => runToken === token && !context.signal.aborted;
    rateSamples = [{ at: performance.now(), iteration, spent }];
    try {
      while (running && live() && trainer) {
        const current = trainer;
        const remaining = budget() - iteration;
        if (remaining <= 0) break;
        const batchStart = performance.now();
        const result = await current.train(Math.min(count, remaining), hyperFrom(context.values));
        lastBatch = {
          iterations: result.losses.length,
          milliseconds: performance.now() - batchStart,
        };
        if (!live() || current !== trainer) return;
        const done = result.losses.length;
        losses.push(...Array.from(result.losses));
        // Wall time per iteration within the batch: its share of the batch's wall time.
        const before = times[times.length - 1] ?? 0;
        for (let j = 1; j <= done; j++) times.push(before + (lastBatch.milliseconds * j) / done);
        iteration = result.iteration;
        dropped = result.dropped;
        if (done > 0) {
          const perIteration = (result.gpuMs ?? result.wallMs) / done;
          spent += result.gpuMs ?? result.wallMs;
          const measured =
            frameBackend.kind === 'cpu'
              ? 'cpu'
              : result.gpuMs === null
                ? 'gpu-wall'
                : 'gpu-timestamp';
          timing = measured === 'cpu' ? 'float64, CPU' : timingLabel(measured);
          cost = { milliseconds: perIteration, timing: measured };
          // Aim each batch at BATCH_TARGET_MS, by the longer of wall and GPU time.
          const wallPerIteration = Math.max(result.wallMs / done, perIteration, 0.05);
          count = Math.min(Math.max(Math.round(BATCH_TARGET_MS / wallPerIteration), 1), 32);
        }
        noteTenfold();
        const now = performance.now();
        rateSamples.push({ at: now, iteration, spent });
        while (rateSamples.length > 2 && now - rateSamples[1]!.at > RATE_WINDOW_MS)
          rateSamples.shift();
        const redrawEvery = Math.max(REDRAW_MS, ((1 - REDRAW_SHARE) / REDRAW_SHARE) * redrawMs);
        if (now - lastDraw > redrawEvery || iteration >= budget() || done === 0) {
          await drawFit();
          if (!live()) return;
          lastDraw = performance.now();
        }
        plotLosses();
        report();
        setStatus(`Running: iteration ${iteration} of ${budget()}.`);
        if (done === 0) break;
        // One batch per animation frame: painting and input stay live.
        await new Promise((resolve) => requestAnimationFrame(() => resolve(null)));
      }
    } catch (error) {
      if (!live()) return;
      stop('');
      const message = error instanceof Error ? error.message : String(error);
      setStatus(`Run failed: ${message}`);
      // The base then stops the run (onCpuFallback) and draws again on the CPU.
      if (frameBackend.kind === 'gpu') context.useCpu(`the GPU path failed: ${message}`);
      return;
    }
    if (!live()) return;
    const finished = iteration >= budget();
    running = false;
    syncButtons();
    if (finished) setStatus(`Done: ${iteration} iterations (the budget).`);
    report();
  }

  /** The first iteration where the mean of the last 10 losses is a tenth of the start. */
  function noteTenfold(): void {
    if (tenfoldAt !== null || !(initialTrainMse > 0)) return;
    for (let k = Math.max(losses.length - 64, 10); k <= losses.length; k++) {
      const recent = losses.slice(k - 10, k);
      const mean = recent.reduce((a, b) => a + b, 0) / recent.length;
      if (mean <= initialTrainMse / 10) {
        tenfoldAt = k;
        return;
      }
    }
  }

  /**
   * Loss against training time (wall seconds): this run's batch loss per iteration and
   * its held-out error at the redraws, and, when the other model has run on the same
   * views, its curves too, so that the two models compare per second rather than per
   * iteration (an iteration of the neural field costs more than one of the grid). The
   * curves share one x axis (the union of their times); each is drawn across the times
   * where it has no value.
   */
  function plotLosses(): void {
    if (!plot || !plotArea || !plotHint || !trainer) return;
    // Before the first iteration there is no curve: the hint stands in for the plot.
    const empty = losses.length === 0;
    plotHint.hidden = !empty;
    plotArea.hidden = empty;
    if (empty) return;
    const problem = trainer.problem;
    const other = otherRun(problem);
    const log = (value: number): number => Math.log10(Math.max(value, 1e-30));
    const curves: { label: string; color: string; dash?: number[]; points: [number, number][] }[] =
      [];
    const add = (run: ModelRun, name: string, colors: [string, string], dash: number[]): void => {
      curves.push({
        label: `${name}: training loss`,
        color: colors[0],
        ...(dash.length ? { dash } : {}),
        points: run.losses.map((loss, k) => [run.times[k]!, loss]),
      });
      curves.push({
        label: `${name}: held-out view`,
        color: colors[1],
        dash: [6, 4],
        points: run.novel,
      });
    };
    const current = runs.get(problem.model)!;
    add(current, MODEL_NAMES[problem.model], ['#3b7dd8', '#d8793b'], []);
    if (other) {
      const name = MODEL_NAMES[problem.model === 'neural' ? 'grid' : 'neural'];
      add(other, `${name} (last run)`, ['#2a9d6f', '#a05bc4'], [2, 3]);
    }
    const x = [...new Set(curves.flatMap((c) => c.points.map(([t]) => t)))].sort((a, b) => a - b);
    const index = new Map(x.map((t, i) => [t, i]));
    plot.update(
      x.map((t) => t / 1000),
      curves.map((curve) => {
        const values = new Array<number>(x.length).fill(NaN);
        for (const [t, value] of curve.points) values[index.get(t)!] = log(value);
        return {
          label: curve.label,
          color: curve.color,
          ...(curve.dash ? { dash: curve.dash } : {}),
          spanGaps: true,
          values,
        };
      }),
    );
  }

  /** The CPU notice: where the twin runs and at which size. */
  function cpuNotice(): string {
    const problem = problemFrom(context.values, 'cpu');
    const inWorker = trainer instanceof CpuTrainer && trainer.inWorker;
    const where = `Fitting with the float64 CPU twin instead${inWorker ? ', in a Web Worker' : ''}`;
    if (problem.model === 'neural') {
      const requested = Math.round(Number(context.values['table']) || 12);
      return `${where}, a neural field with 2^${Math.log2(problem.tableSize)} table entries per level${requested > CPU_MAX_TABLE_LOG2 ? ` (not 2^${requested})` : ''} and ${CPU_IMAGE_SIZE}×${CPU_IMAGE_SIZE} pixels per view.`;
    }
    const requested = Number(context.values['grid']);
    return `${where}, at ${problem.resolution}³ voxels${requested > CPU_MAX_RESOLUTION ? ` (not ${requested}³)` : ''} and ${CPU_IMAGE_SIZE}×${CPU_IMAGE_SIZE} pixels per view.`;
  }

  return {
    build(stage) {
      const views = document.createElement('div');
      views.className = 'sb-ir-views-block';
      const viewsLabel = document.createElement('p');
      viewsLabel.className = 'sb-ir-label';
      viewsLabel.textContent = 'Training views: target (top) and current fit (bottom)';
      viewStrip = document.createElement('div');
      viewStrip.className = 'sb-ir-views';
      views.append(viewsLabel, viewStrip);

      novelTarget = imageCanvas('Held-out view: target', CPU_IMAGE_SIZE, CPU_IMAGE_SIZE);
      novelFit = imageCanvas('Held-out view: current fit', CPU_IMAGE_SIZE, CPU_IMAGE_SIZE);
      novelError = imageCanvas('Held-out view: error', CPU_IMAGE_SIZE, CPU_IMAGE_SIZE);
      novelCaption = document.createElement('p');
      novelCaption.className = 'sb-ir-label';
      const novel = imageFigure(
        imagePanel(novelTarget, 'Target').panel,
        imagePanel(novelFit, 'Current fit').panel,
        imagePanel(novelError, '|fit − target|', {
          gradient: gradientCss(errorColour),
          low: '0',
          top: { text: String(ERROR_SCALE_TOP) },
        }).panel,
      );
      novel.classList.add('sb-ir-novel');

      plotHint = document.createElement('p');
      plotHint.className = 'sb-sweep-hint';
      plotHint.textContent =
        'Press Start: the loss of every iteration (its batch of rays) and the held-out view’s error appear here against training time, on a logarithmic scale; the other model’s last run on the same views stays beside them.';
      plotArea = createPlotArea(
        'Base-10 logarithm of the loss against training time: training loss and held-out view error of this model and of the other model’s last run on the same views',
      );
      plotArea.hidden = true;
      // log₁₀ of the error on a linear axis: short tick labels (−1 … −8) over eight decades.
      plot = new LinePlot(plotArea, {
        xLabel: 'training time (s, wall)',
        yLabel: 'log₁₀ MSE',
        height: 300,
      });

      const bar = document.createElement('div');
      bar.className = 'sb-sweep sb-ir-run';
      startButton = document.createElement('button');
      startButton.type = 'button';
      startButton.className = 'sb-button';
      startButton.textContent = 'Start';
      startButton.dataset['action'] = 'start';
      startButton.addEventListener('click', toggleRun);
      resetButton = document.createElement('button');
      resetButton.type = 'button';
      resetButton.className = 'sb-button';
      resetButton.textContent = 'Reset';
      resetButton.dataset['action'] = 'reset';
      resetButton.addEventListener('click', reset);
      progress = document.createElement('progress');
      progress.setAttribute('aria-label', 'Iterations done of the budget');
      progress.max = 1;
      progress.value = 0;
      status = document.createElement('span');
      status.className = 'sb-sweep-status sb-ir-status';
      status.setAttribute('aria-live', 'polite');
      status.textContent = 'Preparing the target images…';
      bar.append(startButton, resetButton, progress, status);

      stage.append(views, novelCaption, novel, bar, plotHint, plotArea);
    },

    createRenderer: (gpu) => ({ gpu }),
    refinement: (shown) => shown.refinement,

    async renderGpu(_renderer, gpu) {
      frameBackend = { kind: 'gpu', adapterDescription: gpu.adapterDescription };
      return sync('gpu', async (problem) => {
        const gridCode = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
        if (problem.model !== 'neural')
          return InverseTrainerGpu.create(gpu.device, gridCode, problem, {
            previewSteps: PREVIEW_TARGET_STEPS,
          });
        // The neural field's targets come from the grid's kernel: the same images.
        const code = await linkLibraryKernel(STATIC_KERNELS, NEURAL_KERNEL);
        return NeuralTrainerGpu.create(gpu.device, code, gridCode, problem);
      });
    },

    async renderCpu() {
      const backend: Backend<GpuKernel> = await context.backend();
      const reason = backend.kind === 'cpu' ? backend.reason : 'this figure draws on the CPU';
      frameBackend = { kind: 'cpu', reason };
      const result = await sync('cpu', (problem) => CpuTrainer.create(problem));
      // Only now is it known whether the twin runs in a Web Worker: say so.
      context.cpuFallbackNotice(reason, cpuNotice());
      return result;
    },

    get cpuNotice() {
      return cpuNotice();
    },

    show(current) {
      if (progress) {
        progress.max = current.budget;
        progress.value = Math.min(current.iteration, current.budget);
      }
    },

    onCpuFallback() {
      stop('stopped: the GPU was lost or failed');
      trainerKey = '';
    },

    destroy() {
      stop('');
      setupToken += 1;
      trainer?.destroy();
      trainer = null;
      trainerKey = '';
    },
  };
}
