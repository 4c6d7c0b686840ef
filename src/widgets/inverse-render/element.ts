// <sb-inverse-render>: inverse volume rendering (chapter 8). The target images of a
// hidden volume, from N training views and one held-out view, are rendered once by
// the book's ray marcher; Start fits a grid of raw density and emission to the
// training images with Adam, on the GPU (shaders/kernels/inverse-render.wesl) or,
// without WebGPU, with the float64 twin in a Web Worker. Iterations run in batches,
// one per animation frame, so the page stays live and Pause/Reset act at once. The
// widget shows targets against the current fit, the held-out view with its error
// image, the loss curve, the iteration rate and the GPU time per iteration.
import { BackendChooser, type Backend, gpuFailureReason } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/imageKernel.ts';
import { gradientCss, imageCanvas, imageFigure, imagePanel } from '../base/imagePanel.ts';
import { LinePlot } from '../base/plot.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { INVERSE_RENDER } from './schema.ts';
import { CpuTrainer, errorColour, paintError, paintView } from './cpuBackend.ts';
import { InverseTrainerGpu, KERNEL } from './gpuBackend.ts';
import {
  CPU_IMAGE_SIZE,
  CPU_MAX_RESOLUTION,
  NOVEL_ELEVATION,
  effectiveBatch,
  hyperFrom,
  problemFrom,
  problemKey,
  viewError,
  type Problem,
  type Trainer,
} from './model.ts';

const READOUT_ROWS = [
  ['iteration', 'Iteration'],
  ['loss', 'Training loss (last batch, MSE)'],
  ['train-mse', 'Training MSE, all pixels'],
  ['reduction', 'Reduction from the start'],
  ['novel-mse', 'Held-out view MSE (PSNR)'],
  ['rate', 'Iterations per second'],
  ['time', 'Time per iteration'],
  ['dropped', 'Dropped gradient adds'],
] as const;

/** Wall time one batch of iterations should take: long enough to amortize a submit, short enough to stay responsive. */
const BATCH_TARGET_MS = 120;
/** How often the views are re-rendered and read back during a run. */
const REDRAW_MS = 700;
/** Window of the iteration-rate readout. */
const RATE_WINDOW_MS = 4000;
/** Scale of the error image: |C − C*| of this size is the brightest colour. */
const ERROR_SCALE_TOP = 0.25;

const REGULARIZER_NAMES: Readonly<Record<string, string>> = {
  none: 'no regularizer',
  tv: 'total variation',
  sparsity: 'sparsity prior',
};

/** The GPU renderer handed out by BackendChooser: the linked kernel source. */
interface GpuKernel {
  gpu: GpuContext;
}

interface RateSample {
  at: number;
  iteration: number;
  /** Time spent in iterations so far (GPU timestamps, else wall or CPU time), ms. */
  spent: number;
}

export class InverseRenderElement extends WidgetElement {
  protected readonly entry = INVERSE_RENDER;
  protected override presets: readonly Preset[] = [
    { label: '8 views, 32³', values: { views: 8, grid: '32', regularizer: 'none' } },
    { label: '3 views: ambiguity', values: { views: 3, regularizer: 'none' } },
    { label: '1 view: no depth', values: { views: 1, regularizer: 'none' } },
    { label: '8 views, 16³: fewer unknowns', values: { views: 8, grid: '16' } },
    {
      label: '8 views + smoothness prior',
      values: { views: 8, regularizer: 'tv', weight: 0.001 },
    },
    {
      label: '8 views + sparsity prior',
      values: { views: 8, regularizer: 'sparsity', weight: 0.003 },
    },
  ];

  private viewStrip: HTMLElement | null = null;
  private viewCanvases: { target: HTMLCanvasElement; fit: HTMLCanvasElement }[] = [];
  private novelTarget: HTMLCanvasElement | null = null;
  private novelFit: HTMLCanvasElement | null = null;
  private novelError: HTMLCanvasElement | null = null;
  private novelCaption: HTMLElement | null = null;
  private plot: LinePlot | null = null;
  private plotArea: HTMLElement | null = null;
  private plotHint: HTMLElement | null = null;
  private startButton: HTMLButtonElement | null = null;
  private resetButton: HTMLButtonElement | null = null;
  private progress: HTMLProgressElement | null = null;
  private status: HTMLElement | null = null;
  private readouts: ReadoutList | null = null;

  private trainer: Trainer | null = null;
  private trainerKey = '';
  private backendKind: 'gpu' | 'cpu' = 'gpu';
  private backendText = '';
  private novelAzimuth = NaN;
  private targets: ArrayLike<number> = [];
  private image: ArrayLike<number> | null = null;
  /** Loss of every iteration so far (before its update). */
  private losses: number[] = [];
  /** Held-out MSE measured after n updates, by n. */
  private novelErrors = new Map<number, number>();
  private initialTrainMse = NaN;
  private trainMse = NaN;
  private tenfoldAt: number | null = null;
  private iteration = 0;
  private dropped = 0;
  private timing = '';
  private spent = 0;
  private rateSamples: RateSample[] = [];
  private running = false;
  /** Bumped whenever the run must stop (reset, new problem, device loss). */
  private token = 0;
  private setupToken = 0;

  private readonly backends = new BackendChooser<GpuKernel>(
    (gpu) => ({ gpu }),
    () => {
      this.stop('stopped: the GPU was lost');
      this.trainerKey = '';
      this.scheduleRender();
    },
  );

  protected buildStage(stage: HTMLElement): void {
    const views = document.createElement('div');
    views.className = 'sb-ir-views-block';
    const viewsLabel = document.createElement('p');
    viewsLabel.className = 'sb-ir-label';
    viewsLabel.textContent = 'Training views: target (top) and current fit (bottom)';
    this.viewStrip = document.createElement('div');
    this.viewStrip.className = 'sb-ir-views';
    views.append(viewsLabel, this.viewStrip);

    this.novelTarget = imageCanvas('Held-out view: target', CPU_IMAGE_SIZE, CPU_IMAGE_SIZE);
    this.novelFit = imageCanvas('Held-out view: current fit', CPU_IMAGE_SIZE, CPU_IMAGE_SIZE);
    this.novelError = imageCanvas('Held-out view: error', CPU_IMAGE_SIZE, CPU_IMAGE_SIZE);
    const novelLabel = document.createElement('p');
    novelLabel.className = 'sb-ir-label';
    this.novelCaption = novelLabel;
    const novel = imageFigure(
      imagePanel(this.novelTarget, 'Target').panel,
      imagePanel(this.novelFit, 'Current fit').panel,
      imagePanel(this.novelError, '|fit − target|', {
        gradient: gradientCss(errorColour),
        low: '0',
        top: { text: String(ERROR_SCALE_TOP) },
      }).panel,
    );
    novel.classList.add('sb-ir-novel');

    this.plotHint = document.createElement('p');
    this.plotHint.className = 'sb-sweep-hint';
    this.plotHint.textContent =
      'Press Start: the loss of every iteration (its batch of rays) and the held-out view’s error appear here, on a logarithmic scale.';
    this.plotArea = document.createElement('div');
    this.plotArea.className = 'sb-plot';
    this.plotArea.hidden = true;
    this.plotArea.setAttribute('role', 'img');
    this.plotArea.setAttribute(
      'aria-label',
      'Base-10 logarithm of the loss against iteration: training loss and held-out view error',
    );
    // log₁₀ of the error on a linear axis: short tick labels (−1 … −8) over eight decades.
    this.plot = new LinePlot(this.plotArea, {
      xLabel: 'iteration',
      yLabel: 'log₁₀ MSE',
      height: 300,
    });

    const bar = document.createElement('div');
    bar.className = 'sb-sweep sb-ir-run';
    this.startButton = document.createElement('button');
    this.startButton.type = 'button';
    this.startButton.className = 'sb-button';
    this.startButton.textContent = 'Start';
    this.startButton.dataset['action'] = 'start';
    this.startButton.addEventListener('click', () => this.toggleRun());
    this.resetButton = document.createElement('button');
    this.resetButton.type = 'button';
    this.resetButton.className = 'sb-button';
    this.resetButton.textContent = 'Reset';
    this.resetButton.dataset['action'] = 'reset';
    this.resetButton.addEventListener('click', () => this.reset());
    this.progress = document.createElement('progress');
    this.progress.setAttribute('aria-label', 'Iterations done of the budget');
    this.progress.max = 1;
    this.progress.value = 0;
    this.status = document.createElement('span');
    this.status.className = 'sb-sweep-status sb-ir-status';
    this.status.setAttribute('aria-live', 'polite');
    this.status.textContent = 'Preparing the target images…';
    bar.append(this.startButton, this.resetButton, this.progress, this.status);

    stage.append(views, novelLabel, novel, bar, this.plotHint, this.plotArea);
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.readouts?.set(key, text, state);
  }

  protected async render(): Promise<void> {
    const backend = await this.backends.choose();
    const problem = problemFrom(this.values, backend.kind);
    const key = `${backend.kind}:${problemKey(problem)}`;
    try {
      if (key !== this.trainerKey || !this.trainer) {
        await this.restart(backend, problem, key);
      } else {
        const azimuth = problem.views[problem.views.length - 1]!.azimuth;
        if (azimuth !== this.novelAzimuth) await this.moveNovelView(problem);
      }
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.backends.useCpu(gpuFailureReason(error));
      this.stop('stopped: the GPU path failed');
      this.trainerKey = '';
      this.scheduleRender();
      return;
    }
    this.showBackend(backend, problem);
    this.updateReadouts();
  }

  /** Builds a trainer for a new problem: targets, initial grid, its first render. */
  private async restart(backend: Backend<GpuKernel>, problem: Problem, key: string): Promise<void> {
    this.stop('');
    const setup = ++this.setupToken;
    this.trainer?.destroy();
    this.trainer = null;
    this.trainerKey = '';
    if (this.status) this.status.textContent = 'Preparing the target images…';
    let trainer: Trainer;
    if (backend.kind === 'gpu') {
      const code = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
      trainer = await InverseTrainerGpu.create(backend.renderer.gpu.device, code, problem);
    } else {
      trainer = await CpuTrainer.create(problem);
    }
    if (setup !== this.setupToken) {
      trainer.destroy();
      return;
    }
    this.trainer = trainer;
    this.backendKind = backend.kind;
    this.targets = await trainer.readTargets();
    this.losses = [];
    this.novelErrors = new Map();
    this.tenfoldAt = null;
    this.iteration = 0;
    this.dropped = 0;
    this.timing = '';
    this.spent = 0;
    this.rateSamples = [];
    this.novelAzimuth = problem.views[problem.views.length - 1]!.azimuth;
    this.buildViewCells(problem);
    for (const [view, canvases] of this.viewCanvases.entries())
      paintView(canvases.target, this.targets, view, problem.size);
    if (this.novelTarget)
      paintView(this.novelTarget, this.targets, problem.trainViews, problem.size);
    await this.drawFit();
    this.initialTrainMse = this.trainMse;
    this.trainerKey = key;
    this.plotLosses();
    if (this.status) this.status.textContent = 'Ready: press Start to fit the grid.';
    this.syncButtons();
  }

  private async moveNovelView(problem: Problem): Promise<void> {
    const trainer = this.trainer;
    if (!trainer) return;
    const view = problem.views[problem.views.length - 1]!;
    await trainer.setNovelView(view);
    this.novelAzimuth = view.azimuth;
    this.targets = await trainer.readTargets();
    if (this.novelTarget)
      paintView(this.novelTarget, this.targets, problem.trainViews, problem.size);
    // While running, the loop's next redraw shows the fit from there.
    if (!this.running) await this.drawFit();
  }

  private buildViewCells(problem: Problem): void {
    if (!this.viewStrip) return;
    this.viewStrip.replaceChildren();
    this.viewStrip.style.setProperty('--sb-ir-columns', String(Math.min(problem.trainViews, 8)));
    this.viewCanvases = [];
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
      this.viewStrip.appendChild(cell);
      this.viewCanvases.push({ target, fit });
    }
  }

  /** Renders the current grid from every view, paints it and measures the errors. */
  private async drawFit(): Promise<void> {
    const trainer = this.trainer;
    if (!trainer) return;
    const problem = trainer.problem;
    const { image } = await trainer.render();
    if (trainer !== this.trainer) return;
    this.image = image;
    const pixels = problem.size * problem.size;
    for (const [view, canvases] of this.viewCanvases.entries())
      paintView(canvases.fit, image, view, problem.size);
    let sum = 0;
    for (let view = 0; view < problem.trainViews; view++)
      sum += viewError(image, this.targets, view, pixels);
    this.trainMse = sum / problem.trainViews;
    const novel = viewError(image, this.targets, problem.trainViews, pixels);
    this.novelErrors.set(this.iteration, novel);
    if (this.novelFit) paintView(this.novelFit, image, problem.trainViews, problem.size);
    if (this.novelError)
      paintError(
        this.novelError,
        image,
        this.targets,
        problem.trainViews,
        problem.size,
        ERROR_SCALE_TOP,
      );
    if (this.novelCaption) {
      const degrees = Math.round((problem.views[problem.trainViews]!.azimuth * 180) / Math.PI);
      this.novelCaption.textContent = `Held-out view (azimuth ${degrees}°, ${Math.round((NOVEL_ELEVATION * 180) / Math.PI)}° above): MSE ${formatNumber(novel, 3)}`;
    }
    this.novelFit?.setAttribute(
      'aria-label',
      `Held-out view, current fit after ${this.iteration} iterations: MSE ${formatNumber(novel, 3)}`,
    );
  }

  private toggleRun(): void {
    if (this.running) {
      this.stop('paused');
      return;
    }
    if (!this.trainer) return;
    if (this.iteration >= this.budget()) {
      if (this.status)
        this.status.textContent = 'The iteration budget is spent: Reset, or raise the budget.';
      return;
    }
    this.running = true;
    this.syncButtons();
    void this.loop(this.token);
  }

  private budget(): number {
    return Math.round(Number(this.values['iterations']));
  }

  /** Stops a run after its current batch; the fit is kept. */
  private stop(message: string): void {
    const wasRunning = this.running;
    this.running = false;
    this.token += 1;
    if (wasRunning && message && this.status) this.status.textContent = `Run ${message}.`;
    this.syncButtons();
  }

  /** Discards the fit and starts from the initial grid (same problem). */
  private reset(): void {
    this.stop('');
    this.trainerKey = '';
    this.scheduleRender();
  }

  private syncButtons(): void {
    if (this.startButton) {
      this.startButton.textContent = this.running
        ? 'Pause'
        : this.iteration > 0
          ? 'Resume'
          : 'Start';
      this.startButton.setAttribute('aria-pressed', String(this.running));
      this.startButton.disabled = !this.trainer;
    }
    if (this.resetButton) this.resetButton.disabled = !this.trainer;
    this.toggleAttribute('data-running', this.running);
  }

  private async loop(token: number): Promise<void> {
    let count = 1;
    let lastDraw = performance.now();
    this.rateSamples = [{ at: performance.now(), iteration: this.iteration, spent: this.spent }];
    try {
      while (this.running && token === this.token && this.trainer) {
        const trainer = this.trainer;
        const remaining = this.budget() - this.iteration;
        if (remaining <= 0) break;
        const hyper = hyperFrom(this.values);
        const report = await trainer.train(Math.min(count, remaining), hyper);
        if (token !== this.token || trainer !== this.trainer) return;
        const done = report.losses.length;
        this.losses.push(...Array.from(report.losses));
        this.iteration = report.iteration;
        this.dropped = report.dropped;
        if (done > 0) {
          const perIteration = (report.gpuMs ?? report.wallMs) / done;
          this.spent += report.gpuMs ?? report.wallMs;
          this.timing =
            this.backendKind === 'cpu'
              ? 'float64, CPU'
              : timingLabel(report.gpuMs === null ? 'gpu-wall' : 'gpu-timestamp');
          this.recordFrameCost(perIteration, `per iteration, ${this.timing}`);
          // Aim each batch at BATCH_TARGET_MS, by the longer of wall and GPU time.
          const wallPerIteration = Math.max(report.wallMs / done, perIteration, 0.05);
          count = Math.min(Math.max(Math.round(BATCH_TARGET_MS / wallPerIteration), 1), 32);
        }
        this.noteTenfold();
        const now = performance.now();
        this.rateSamples.push({ at: now, iteration: this.iteration, spent: this.spent });
        while (this.rateSamples.length > 2 && now - this.rateSamples[1]!.at > RATE_WINDOW_MS)
          this.rateSamples.shift();
        if (now - lastDraw > REDRAW_MS || this.iteration >= this.budget() || done === 0) {
          await this.drawFit();
          if (token !== this.token) return;
          lastDraw = performance.now();
        }
        this.plotLosses();
        this.updateReadouts();
        if (this.status)
          this.status.textContent = `Running: iteration ${this.iteration} of ${this.budget()}.`;
        if (done === 0) break;
        // One batch per animation frame: painting and input stay live.
        await new Promise((resolve) => requestAnimationFrame(() => resolve(null)));
      }
    } catch (error) {
      if (token !== this.token) return;
      this.stop('');
      const message = error instanceof Error ? error.message : String(error);
      if (this.status) this.status.textContent = `Run failed: ${message}`;
      if (this.backendKind === 'gpu') {
        this.backends.useCpu(`the GPU path failed: ${message}`);
        this.trainerKey = '';
        this.scheduleRender();
      }
      return;
    }
    if (token !== this.token) return;
    const finished = this.iteration >= this.budget();
    this.running = false;
    this.syncButtons();
    if (finished && this.status)
      this.status.textContent = `Done: ${this.iteration} iterations (the budget).`;
    this.updateReadouts();
  }

  /** The first iteration where the mean of the last 10 losses is a tenth of the start. */
  private noteTenfold(): void {
    if (this.tenfoldAt !== null || !(this.initialTrainMse > 0)) return;
    for (let k = Math.max(this.losses.length - 64, 10); k <= this.losses.length; k++) {
      const recent = this.losses.slice(k - 10, k);
      const mean = recent.reduce((a, b) => a + b, 0) / recent.length;
      if (mean <= this.initialTrainMse / 10) {
        this.tenfoldAt = k;
        return;
      }
    }
  }

  /**
   * Loss curve: at x = k the batch loss of iteration k + 1 (the parameters after k
   * updates) and the held-out error last measured at or before k updates.
   */
  private plotLosses(): void {
    if (!this.plot || !this.plotArea || !this.plotHint) return;
    // Before the first iteration there is no curve: the hint stands in for the plot.
    const empty = this.losses.length === 0;
    this.plotHint.hidden = !empty;
    this.plotArea.hidden = empty;
    if (empty) return;
    const log = (value: number): number => Math.log10(Math.max(value, 1e-30));
    const x = this.losses.map((_, k) => k);
    let last = this.novelErrors.get(0) ?? this.trainMse;
    const novel = x.map((k) => {
      last = this.novelErrors.get(k) ?? last;
      return log(last);
    });
    this.plot.update(x, [
      { label: 'training loss (batch)', color: '#3b7dd8', values: this.losses.map(log) },
      { label: 'held-out view', color: '#d8793b', dash: [6, 4], values: novel },
    ]);
  }

  private showBackend(backend: Backend<GpuKernel>, problem: Problem): void {
    if (backend.kind === 'gpu') {
      this.clearNotice('backend');
      this.backendText = `WebGPU (${backend.gpu.adapterDescription})`;
      return;
    }
    const requested = Number(this.values['grid']);
    this.showNotice(
      'backend',
      'warning',
      `WebGPU is not available (${backend.reason}). Fitting with the float64 CPU twin instead${
        this.trainer instanceof CpuTrainer && this.trainer.inWorker ? ', in a Web Worker' : ''
      }, at ${problem.resolution}³ voxels${requested > CPU_MAX_RESOLUTION ? ` (not ${requested}³)` : ''} and ${CPU_IMAGE_SIZE}×${CPU_IMAGE_SIZE} pixels per view.`,
    );
    this.backendText = 'CPU fallback (float64 twin)';
  }

  private updateReadouts(): void {
    const trainer = this.trainer;
    if (!trainer) return;
    const problem = trainer.problem;
    const budget = this.budget();
    this.set('iteration', `${this.iteration} of ${budget}`);
    if (this.progress) {
      this.progress.max = budget;
      this.progress.value = Math.min(this.iteration, budget);
    }
    const last = this.losses[this.losses.length - 1];
    this.set('loss', last === undefined ? 'press Start' : formatNumber(last, 3));
    this.set('train-mse', `${formatNumber(this.trainMse, 3)} (at the last redraw)`);
    const reduction = this.initialTrainMse / this.trainMse;
    this.set(
      'reduction',
      this.iteration === 0
        ? `start: ${formatNumber(this.initialTrainMse, 3)}`
        : `${formatNumber(reduction, 3)}×${this.tenfoldAt !== null ? `; 10× by iteration ${this.tenfoldAt}` : ''}`,
      this.tenfoldAt !== null ? 'ok' : undefined,
    );
    const novel = this.novelErrors.get(this.iteration) ?? [...this.novelErrors.values()].pop();
    if (novel !== undefined)
      this.set(
        'novel-mse',
        `${formatNumber(novel, 3)} (${formatNumber(10 * Math.log10(1 / novel), 3)} dB)`,
      );
    const first = this.rateSamples[0];
    const latest = this.rateSamples[this.rateSamples.length - 1];
    const rate =
      first && latest && latest.at > first.at
        ? ((latest.iteration - first.iteration) * 1000) / (latest.at - first.at)
        : NaN;
    this.set('rate', Number.isFinite(rate) && rate > 0 ? `${formatNumber(rate, 3)} it/s` : '—');
    // Both over the same window of the last few seconds: iterations per wall second, and
    // the time the iterations themselves took (GPU timestamps where available).
    const iterations = first && latest ? latest.iteration - first.iteration : 0;
    this.set(
      'time',
      first && latest && iterations > 0
        ? `${formatMilliseconds((latest.spent - first.spent) / iterations)} (${this.timing})`
        : '—',
    );
    if (this.backendKind === 'cpu') this.set('dropped', 'none: float64 sums, no atomics');
    else this.set('dropped', String(this.dropped), this.dropped > 0 ? 'bad' : 'ok');
    const hyper = hyperFrom(this.values);
    const rays = effectiveBatch(hyper, problem.trainViews * problem.size * problem.size);
    const regularizer = REGULARIZER_NAMES[String(this.values['regularizer'])] ?? '';
    if (this.readouts)
      this.readouts.cost.textContent = `${this.backendText}: a ${problem.resolution}³ grid (${(4 * problem.resolution ** 3).toLocaleString('en')} parameters), ${problem.trainViews} training view${problem.trainViews === 1 ? '' : 's'} of ${problem.size}×${problem.size} pixels; each iteration marches ${rays} rays × ${problem.steps} samples forward and backward, then Adam (η = ${hyper.learningRate}, ${regularizer}). ${
        Number.isFinite(rate) && rate > 0 ? `${formatNumber(rate, 3)} iterations/s. ` : ''
      }Targets: the hidden volume, 192 samples per ray.`;
  }
}

export function defineInverseRender(): void {
  if (!customElements.get('sb-inverse-render'))
    customElements.define('sb-inverse-render', InverseRenderElement);
}
