// <sb-delta-tracking>: unbiased and biased transmittance estimators (chapter 6).
// Averages spp estimates per pixel on the GPU, shows the mean transmittance
// next to the per-pixel variance (false colour, labelled scale), the RMSE and
// mean bias against the exact T, the lookups per estimate and the GPU time; a
// cancellable sweep over spp = 1, 2, 4, …, 256 plots RMSE against GPU time.
import { BackendChooser, type Backend } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { LinePlot } from '../base/plot.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { DELTA_TRACKING } from './schema.ts';
import { CPU_HEIGHT, CPU_WIDTH, paintImages, renderCpu } from './cpuBackend.ts';
import { DeltaTrackingGpu } from './gpuBackend.ts';
import {
  ESTIMATOR_NAMES,
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  SWEEP_SPP,
  convergenceSlope,
  exactImage,
  gradientCss,
  imageStatistics,
  inputsFrom,
  sampleVariance,
  transmittanceColour,
  varianceColour,
  varianceScale,
  type TrackingImage,
  type TrackingInputs,
} from './model.ts';

const READOUT_ROWS = [
  ['rmse', 'RMSE against the exact T'],
  ['bias', 'Mean bias (± 1 SE)'],
  ['lookups', 'Density lookups per estimate'],
  ['time', 'Time per render'],
  ['capped', 'Capped estimates'],
  ['slope', 'Sweep: fitted RMSE ∝ spp^p'],
] as const;

const MAJORANT_NAMES: Readonly<Record<string, string>> = {
  tight: 'tight majorant',
  loose: 'loose majorant (×3)',
  low: 'majorant too low (×0.5)',
};

/** One frame's image on the backend in use, with its cost. */
interface Frame {
  image: TrackingImage;
  exact: Float64Array;
  milliseconds: number;
  how: string;
}

function timingLabel(timing: 'gpu-timestamp' | 'gpu-wall' | 'cpu'): string {
  if (timing === 'gpu-timestamp') return 'GPU timestamp query';
  if (timing === 'gpu-wall') return 'wall time; this GPU has no timestamp queries';
  return 'CPU wall time';
}

export class DeltaTrackingElement extends WidgetElement {
  protected readonly entry = DELTA_TRACKING;
  protected override presets: readonly Preset[] = [
    { label: 'delta tracking, tight', values: { estimator: 'delta', majorant: 'tight' } },
    { label: 'ratio tracking', values: { estimator: 'ratio', majorant: 'tight' } },
    { label: 'biased exp(−τ̂)', values: { estimator: 'biased', majorant: 'tight' } },
    { label: 'majorant too low', values: { estimator: 'delta', majorant: 'low' } },
  ];

  private imageCanvas: HTMLCanvasElement | null = null;
  private varianceCanvas: HTMLCanvasElement | null = null;
  private scaleTop: HTMLElement | null = null;
  private plot: LinePlot | null = null;
  private readouts = new Map<string, HTMLElement>();
  private cost: HTMLElement | null = null;
  private sweepButton: HTMLButtonElement | null = null;
  private cancelButton: HTMLButtonElement | null = null;
  private progress: HTMLProgressElement | null = null;
  private sweepStatus: HTMLElement | null = null;
  private plotHint: HTMLElement | null = null;
  private readonly backends = new BackendChooser(
    (gpu) => new DeltaTrackingGpu(gpu),
    () => {
      this.cancelSweep('stopped: the GPU was lost');
      this.scheduleRender();
    },
  );
  private sweepToken = 0;

  protected buildStage(stage: HTMLElement): void {
    const figure = document.createElement('div');
    figure.className = 'sb-dt-figure';
    this.imageCanvas = this.createCanvas('Estimated transmittance image');
    this.varianceCanvas = this.createCanvas('Per-pixel variance image');
    figure.append(
      this.panel(
        this.imageCanvas,
        'Estimated T (mean of spp samples)',
        gradientCss(transmittanceColour),
        '0',
        '1',
      ),
      this.panel(
        this.varianceCanvas,
        'Variance of one estimate, per pixel',
        gradientCss((x) => varianceColour(x, 1)),
        '0',
        null,
      ),
    );
    stage.appendChild(figure);

    const plotArea = document.createElement('div');
    plotArea.className = 'sb-plot';
    plotArea.setAttribute('role', 'img');
    plotArea.setAttribute('aria-label', 'Log–log plot of RMSE against time per render');
    this.plotHint = document.createElement('p');
    this.plotHint.className = 'sb-dt-plot-hint';
    this.plotHint.textContent =
      'Run the sweep to plot RMSE against the time per render for spp = 1, 2, 4, …, 256. An unbiased estimator falls as spp^(−½); a biased one levels off at its bias.';
    stage.append(this.plotHint, plotArea);
    this.plot = new LinePlot(plotArea, {
      xLabel: 'log₁₀ time per render (ms)',
      yLabel: 'RMSE',
      yLog: true,
      height: 240,
    });

    const sweep = document.createElement('div');
    sweep.className = 'sb-dt-sweep';
    this.sweepButton = document.createElement('button');
    this.sweepButton.type = 'button';
    this.sweepButton.className = 'sb-button';
    this.sweepButton.textContent = 'Run sweep spp = 1 … 256';
    this.sweepButton.addEventListener('click', () => void this.runSweep());
    this.cancelButton = document.createElement('button');
    this.cancelButton.type = 'button';
    this.cancelButton.className = 'sb-button';
    this.cancelButton.textContent = 'Cancel';
    this.cancelButton.disabled = true;
    this.cancelButton.addEventListener('click', () => this.cancelSweep('cancelled'));
    this.progress = document.createElement('progress');
    this.progress.max = SWEEP_SPP.length;
    this.progress.value = 0;
    this.progress.setAttribute('aria-label', 'Sweep progress');
    this.sweepStatus = document.createElement('span');
    this.sweepStatus.className = 'sb-dt-sweep-status';
    this.sweepStatus.setAttribute('aria-live', 'polite');
    this.sweepStatus.textContent = 'No sweep yet.';
    sweep.append(this.sweepButton, this.cancelButton, this.progress, this.sweepStatus);
    stage.appendChild(sweep);
  }

  private createCanvas(label: string): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.className = 'sb-canvas';
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', label);
    canvas.width = IMAGE_WIDTH;
    canvas.height = IMAGE_HEIGHT;
    return canvas;
  }

  /** A canvas with its caption and a colour-scale legend; a null top is a live readout. */
  private panel(
    canvas: HTMLCanvasElement,
    caption: string,
    gradient: string,
    low: string,
    top: string | null,
  ): HTMLElement {
    const panel = document.createElement('figure');
    panel.className = 'sb-dt-panel';
    const text = document.createElement('figcaption');
    text.textContent = caption;
    const legend = document.createElement('div');
    legend.className = 'sb-dt-scale';
    const bar = document.createElement('span');
    bar.className = 'sb-dt-scale-bar';
    bar.style.background = gradient;
    bar.setAttribute('aria-hidden', 'true');
    const lowLabel = document.createElement('span');
    lowLabel.textContent = low;
    const topLabel = document.createElement('span');
    if (top === null) {
      topLabel.dataset['readout'] = 'variance-scale';
      this.scaleTop = topLabel;
    } else {
      topLabel.textContent = top;
    }
    legend.append(lowLabel, bar, topLabel);
    panel.append(canvas, text, legend);
    return panel;
  }

  protected buildReadout(readout: HTMLElement): void {
    const list = document.createElement('dl');
    list.className = 'sb-readout';
    for (const [key, label] of READOUT_ROWS) {
      const row = document.createElement('div');
      const term = document.createElement('dt');
      term.textContent = label;
      const value = document.createElement('dd');
      value.dataset['readout'] = key;
      row.append(term, value);
      list.appendChild(row);
      this.readouts.set(key, value);
    }
    this.cost = document.createElement('p');
    this.cost.className = 'sb-cost';
    this.cost.setAttribute('aria-live', 'polite');
    readout.append(list, this.cost);
    this.set('slope', 'run the sweep');
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    const element = this.readouts.get(key);
    if (!element) return;
    element.textContent = text;
    element.classList.toggle('sb-ok', state === 'ok');
    element.classList.toggle('sb-bad', state === 'bad');
  }

  /** One image with spp samples on the backend in use, and the exact T to compare it with. */
  private async frame(
    backend: Backend<DeltaTrackingGpu>,
    inputs: TrackingInputs,
    spp: number,
  ): Promise<Frame> {
    if (backend.kind === 'gpu') {
      const image = await backend.renderer.render(inputs, spp);
      return {
        image,
        exact: exactImage(IMAGE_WIDTH, IMAGE_HEIGHT),
        milliseconds: image.milliseconds,
        how: timingLabel(image.timing),
      };
    }
    const { image, milliseconds } = renderCpu(inputs, spp);
    return {
      image,
      exact: exactImage(CPU_WIDTH, CPU_HEIGHT),
      milliseconds,
      how: timingLabel('cpu'),
    };
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    let frame: Frame;
    try {
      frame = await this.frame(backend, inputs, inputs.spp);
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.backends.useCpu(
        `the GPU path failed: ${error instanceof Error ? error.message : String(error)}`,
      );
      this.cancelSweep('stopped: the GPU path failed');
      this.scheduleRender();
      return;
    }
    if (backend.kind === 'gpu') {
      this.clearNotice('backend');
    } else {
      this.showNotice(
        'backend',
        'warning',
        `WebGPU is not available (${backend.reason}). Showing the float64 CPU twin: the same rays and estimators, at ${CPU_WIDTH}×${CPU_HEIGHT} pixels.`,
      );
    }
    this.showFrame(inputs, frame, backend);
  }

  private showFrame(
    inputs: TrackingInputs,
    frame: Frame,
    backend: Backend<DeltaTrackingGpu>,
  ): void {
    const { image, exact } = frame;
    const variance = sampleVariance(image);
    const stats = imageStatistics(image, exact, variance);
    const scale = varianceScale(stats.largestVariance);
    if (this.imageCanvas && this.varianceCanvas)
      paintImages(this.imageCanvas, this.varianceCanvas, image, variance, scale);
    if (this.scaleTop)
      this.scaleTop.textContent = image.spp < 2 ? 'needs spp ≥ 2' : formatNumber(scale, 2);
    this.set('rmse', formatNumber(stats.rmse, 3));
    // Significant at 5 SE (the book's threshold for "biased", physics.md §4.5).
    const significant = image.spp >= 2 && Math.abs(stats.bias) > 5 * stats.biasError;
    this.set(
      'bias',
      image.spp < 2
        ? `${formatNumber(stats.bias, 3)} (SE needs spp ≥ 2)`
        : `${formatNumber(stats.bias, 3)} ± ${formatNumber(stats.biasError, 2)}${significant ? ' (biased)' : ''}`,
      significant ? 'bad' : undefined,
    );
    this.set('lookups', formatNumber(stats.lookupsPerEstimate, 3));
    this.set('time', `${formatMilliseconds(frame.milliseconds)} (${frame.how})`);
    this.set('capped', String(image.capped), image.capped > 0 ? 'bad' : 'ok');
    if (image.capped > 0) {
      this.showNotice(
        'capped',
        'warning',
        `${image.capped} estimates reached their cap and were cut short; the image is biased there.`,
      );
    } else {
      this.clearNotice('capped');
    }
    const where =
      backend.kind === 'gpu'
        ? `WebGPU (${backend.gpu.adapterDescription}): ${IMAGE_WIDTH}×${IMAGE_HEIGHT} rays`
        : `CPU fallback (float64 twin): ${CPU_WIDTH}×${CPU_HEIGHT} rays`;
    const name = ESTIMATOR_NAMES[inputs.estimator] ?? inputs.estimator;
    if (this.cost) {
      this.cost.textContent = `${where} × spp = ${image.spp} estimates (${name}, ${MAJORANT_NAMES[inputs.majorant] ?? inputs.majorant}) in ${formatMilliseconds(frame.milliseconds)} (${frame.how}). Reference: the exact T = e^(−τ) from the closed-form optical depth.`;
    }
    if (this.imageCanvas)
      this.imageCanvas.setAttribute(
        'aria-label',
        `Estimated transmittance, ${name}, spp = ${image.spp}, RMSE ${formatNumber(stats.rmse, 3)}`,
      );
  }

  private cancelSweep(message: string): void {
    if (!this.cancelButton?.disabled) {
      this.sweepToken += 1;
      if (this.sweepStatus) this.sweepStatus.textContent = `Sweep ${message}.`;
      this.setSweeping(false);
    }
  }

  private setSweeping(on: boolean): void {
    if (this.sweepButton) this.sweepButton.disabled = on;
    if (this.cancelButton) this.cancelButton.disabled = !on;
    this.toggleAttribute('data-sweeping', on);
  }

  /** Renders spp = 1, 2, 4, …, 256, yielding to the page between steps; Cancel stops it. */
  private async runSweep(): Promise<void> {
    const token = ++this.sweepToken;
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    this.setSweeping(true);
    this.set('slope', 'sweeping…');
    const spps: number[] = [];
    const errors: number[] = [];
    const times: number[] = [];
    const label = `${ESTIMATOR_NAMES[inputs.estimator] ?? inputs.estimator}, ${MAJORANT_NAMES[inputs.majorant] ?? inputs.majorant}`;
    try {
      for (const [k, n] of SWEEP_SPP.entries()) {
        if (token !== this.sweepToken) return;
        if (this.sweepStatus)
          this.sweepStatus.textContent = `spp = ${n} (${k + 1} of ${SWEEP_SPP.length})…`;
        const frame = await this.frame(backend, inputs, n);
        if (token !== this.sweepToken) return;
        const stats = imageStatistics(frame.image, frame.exact, sampleVariance(frame.image));
        spps.push(n);
        errors.push(stats.rmse);
        times.push(frame.milliseconds);
        if (this.progress) this.progress.value = k + 1;
        this.plotSweep(errors, times, label);
        // Let the page breathe between renders: input, painting and Cancel stay live.
        await new Promise((resolve) => setTimeout(resolve, 0));
      }
    } catch (error) {
      if (token === this.sweepToken) {
        this.set('slope', 'failed', 'bad');
        if (this.sweepStatus)
          this.sweepStatus.textContent = `Sweep failed: ${error instanceof Error ? error.message : String(error)}`;
        this.setSweeping(false);
      }
      return;
    }
    const slope = convergenceSlope(spps, errors);
    this.set('slope', slope === null ? 'no fit' : `p = ${formatNumber(slope, 3)} (unbiased: −0.5)`);
    if (this.sweepStatus)
      this.sweepStatus.textContent = `Sweep done: ${label}, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}.`;
    this.setSweeping(false);
  }

  private plotSweep(errors: number[], times: number[], label: string): void {
    // uPlot wants ascending x: sort the points by time (small spp costs about the
    // same fixed dispatch time, so time is not monotone in spp).
    const order = errors.map((_, i) => i).sort((a, b) => times[a]! - times[b]!);
    const x = order.map((i) => Math.log10(Math.max(times[i]!, 1e-4)));
    this.plotHint?.remove();
    this.plotHint = null;
    this.plot?.update(x, [
      { label: `RMSE, ${label}`, color: '#3b7dd8', values: order.map((i) => errors[i]!) },
    ]);
  }
}

export function defineDeltaTracking(): void {
  if (!customElements.get('sb-delta-tracking'))
    customElements.define('sb-delta-tracking', DeltaTrackingElement);
}
