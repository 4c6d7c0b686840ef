// <sb-raymarch-steps>: ray marching an emissive, absorbing volume (chapter 5).
// Marches one ray per pixel with N steps on the GPU, shows the image next to its
// error against a converged reference (false colour, labelled scale), the RMSE,
// the GPU time and the clamped linear factors; a cancellable sweep over
// N = 1, 2, 4, …, 256 plots RMSE against GPU time and fits the order of convergence.
import { acquireGpu, onDeviceLost, type GpuContext } from '../../gpu/device.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { LinePlot } from '../base/plot.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { RAYMARCH_STEPS } from './schema.ts';
import { CPU_HEIGHT, CPU_WIDTH, paintImages, referenceCpu, renderCpu } from './cpuBackend.ts';
import { RaymarchStepsGpu } from './gpuBackend.ts';
import {
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  RADIANCE_SCALE,
  REFERENCE_STEPS,
  SWEEP_STEPS,
  convergenceSlope,
  errorGradientCss,
  errorScale,
  inputsFrom,
  maxError,
  rmse,
  type MarchImage,
  type MarchInputs,
} from './model.ts';

type Backend =
  { kind: 'gpu'; gpu: GpuContext; renderer: RaymarchStepsGpu } | { kind: 'cpu'; reason: string };

const READOUT_ROWS = [
  ['rmse', 'RMSE against the reference'],
  ['max-error', 'Largest pixel error'],
  ['time', 'Time per render'],
  ['clamped', 'Clamped steps (1 − σt·h < 0)'],
  ['slope', 'Sweep: fitted order, RMSE ∝ N^p'],
] as const;

const PLACEMENT_NAMES: Readonly<Record<string, string>> = {
  left: 'left',
  midpoint: 'midpoint',
  'jittered-ray': 'jittered per ray',
  'jittered-strata': 'jittered per step',
};

/** One frame's image on the backend in use, with its cost. */
interface Frame {
  image: MarchImage;
  reference: ArrayLike<number>;
  milliseconds: number;
  how: string;
  capped: boolean;
}

function timingLabel(timing: 'gpu-timestamp' | 'gpu-wall' | 'cpu'): string {
  if (timing === 'gpu-timestamp') return 'GPU timestamp query';
  if (timing === 'gpu-wall') return 'wall time; this GPU has no timestamp queries';
  return 'CPU wall time';
}

export class RaymarchStepsElement extends WidgetElement {
  protected readonly entry = RAYMARCH_STEPS;
  protected override presets: readonly Preset[] = [
    { label: 'left, N = 8', values: { placement: 'left', steps: 8, update: 'exact' } },
    { label: 'midpoint, N = 8', values: { placement: 'midpoint', steps: 8, update: 'exact' } },
    {
      label: 'jittered strata, N = 8',
      values: { placement: 'jittered-strata', steps: 8, update: 'exact' },
    },
    {
      label: 'linear update, N = 4 (fails)',
      values: { placement: 'left', steps: 4, update: 'linear' },
    },
  ];

  private imageCanvas: HTMLCanvasElement | null = null;
  private errorCanvas: HTMLCanvasElement | null = null;
  private scaleTop: HTMLElement | null = null;
  private plot: LinePlot | null = null;
  private readouts = new Map<string, HTMLElement>();
  private cost: HTMLElement | null = null;
  private sweepButton: HTMLButtonElement | null = null;
  private cancelButton: HTMLButtonElement | null = null;
  private progress: HTMLProgressElement | null = null;
  private sweepStatus: HTMLElement | null = null;
  private plotHint: HTMLElement | null = null;
  private backend: Promise<Backend> | null = null;
  private sweepToken = 0;

  protected buildStage(stage: HTMLElement): void {
    const figure = document.createElement('div');
    figure.className = 'sb-rm-figure';
    this.imageCanvas = this.createCanvas('Ray-marched image of the volume');
    this.errorCanvas = this.createCanvas('Error image, |image − reference|');
    figure.append(
      this.panel(this.imageCanvas, `Radiance L (colour scale 0 … ${RADIANCE_SCALE})`),
      this.panel(this.errorCanvas, 'Error |L − L_ref|', true),
    );
    stage.appendChild(figure);

    const plotArea = document.createElement('div');
    plotArea.className = 'sb-plot';
    plotArea.setAttribute('role', 'img');
    plotArea.setAttribute('aria-label', 'Log–log plot of RMSE against time per render');
    this.plotHint = document.createElement('p');
    this.plotHint.className = 'sb-rm-plot-hint';
    this.plotHint.textContent =
      'Run the sweep to plot RMSE against the time per render for N = 1, 2, 4, …, 256 and fit the order of convergence.';
    stage.append(this.plotHint, plotArea);
    this.plot = new LinePlot(plotArea, {
      xLabel: 'log₁₀ time per render (ms)',
      yLabel: 'RMSE',
      yLog: true,
      height: 240,
    });

    const sweep = document.createElement('div');
    sweep.className = 'sb-rm-sweep';
    this.sweepButton = document.createElement('button');
    this.sweepButton.type = 'button';
    this.sweepButton.className = 'sb-button';
    this.sweepButton.textContent = 'Run sweep N = 1 … 256';
    this.sweepButton.addEventListener('click', () => void this.runSweep());
    this.cancelButton = document.createElement('button');
    this.cancelButton.type = 'button';
    this.cancelButton.className = 'sb-button';
    this.cancelButton.textContent = 'Cancel';
    this.cancelButton.disabled = true;
    this.cancelButton.addEventListener('click', () => this.cancelSweep('cancelled'));
    this.progress = document.createElement('progress');
    this.progress.max = SWEEP_STEPS.length;
    this.progress.value = 0;
    this.progress.setAttribute('aria-label', 'Sweep progress');
    this.sweepStatus = document.createElement('span');
    this.sweepStatus.className = 'sb-rm-sweep-status';
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

  private panel(canvas: HTMLCanvasElement, caption: string, withScale = false): HTMLElement {
    const panel = document.createElement('figure');
    panel.className = 'sb-rm-panel';
    const text = document.createElement('figcaption');
    text.textContent = caption;
    panel.append(canvas, text);
    if (withScale) {
      const legend = document.createElement('div');
      legend.className = 'sb-rm-scale';
      const bar = document.createElement('span');
      bar.className = 'sb-rm-scale-bar';
      bar.style.background = errorGradientCss();
      bar.setAttribute('aria-hidden', 'true');
      const low = document.createElement('span');
      low.textContent = '0';
      this.scaleTop = document.createElement('span');
      this.scaleTop.dataset['readout'] = 'error-scale';
      legend.append(low, bar, this.scaleTop);
      panel.appendChild(legend);
    }
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

  private chooseBackend(): Promise<Backend> {
    this.backend ??= (async (): Promise<Backend> => {
      if (new URLSearchParams(location.search).get('backend') === 'cpu') {
        return { kind: 'cpu', reason: 'the page was opened with ?backend=cpu' };
      }
      try {
        const gpu = await acquireGpu();
        onDeviceLost((reason) => this.fallBackToCpu(reason));
        return { kind: 'gpu', gpu, renderer: new RaymarchStepsGpu(gpu) };
      } catch (error) {
        return { kind: 'cpu', reason: error instanceof Error ? error.message : String(error) };
      }
    })();
    return this.backend;
  }

  /** After a device loss: the CPU path (the canvases are 2D on both paths). */
  private fallBackToCpu(reason: string): void {
    this.cancelSweep('stopped: the GPU was lost');
    this.backend = Promise.resolve({ kind: 'cpu', reason });
    this.scheduleRender();
  }

  /** One image with N steps on the backend in use, and the reference to compare it with. */
  private async frame(backend: Backend, inputs: MarchInputs, steps: number): Promise<Frame> {
    if (backend.kind === 'gpu') {
      const reference = await backend.renderer.reference(inputs.density);
      const image = await backend.renderer.render(inputs, steps);
      return {
        image,
        reference,
        milliseconds: image.milliseconds,
        how: timingLabel(image.timing),
        capped: image.capped,
      };
    }
    const reference = referenceCpu(inputs.density);
    const { image, milliseconds } = renderCpu(inputs, steps);
    return { image, reference, milliseconds, how: timingLabel('cpu'), capped: false };
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.chooseBackend();
    let frame: Frame;
    try {
      frame = await this.frame(backend, inputs, inputs.steps);
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.fallBackToCpu(
        `the GPU path failed: ${error instanceof Error ? error.message : String(error)}`,
      );
      return;
    }
    if (backend.kind === 'gpu') {
      this.clearNotice('backend');
    } else {
      this.showNotice(
        'backend',
        'warning',
        `WebGPU is not available (${backend.reason}). Showing the float64 CPU twin: the same rays and marches, at ${CPU_WIDTH}×${CPU_HEIGHT} pixels.`,
      );
    }
    this.showFrame(inputs, frame, backend);
  }

  private showFrame(inputs: MarchInputs, frame: Frame, backend: Backend): void {
    const { image, reference } = frame;
    const error = rmse(image.radiance, reference);
    const largest = maxError(image.radiance, reference);
    const scale = errorScale(largest);
    if (this.imageCanvas && this.errorCanvas)
      paintImages(this.imageCanvas, this.errorCanvas, image, reference, scale);
    if (this.scaleTop) this.scaleTop.textContent = formatNumber(scale, 2);
    this.set('rmse', formatNumber(error, 3));
    this.set('max-error', formatNumber(largest, 3));
    this.set('time', `${formatMilliseconds(frame.milliseconds)} (${frame.how})`);
    if (!inputs.linear) {
      this.set('clamped', '0 (exact update)', 'ok');
      this.clearNotice('clamped');
    } else if (image.clampedSteps > 0) {
      this.set(
        'clamped',
        `${image.clampedSteps} steps in ${image.clampedPixels} of ${image.width * image.height} rays`,
        'bad',
      );
      this.showNotice(
        'clamped',
        'warning',
        `The linear update failed: in ${image.clampedSteps} steps σt·h > 1, so 1 − σt·h was negative (a negative transmittance) and was clamped to 0.`,
      );
    } else {
      this.set('clamped', '0 (σt·h ≤ 1 on every step)', 'ok');
      this.clearNotice('clamped');
    }
    if (frame.capped) {
      this.showNotice('capped', 'warning', 'A march reached its step cap; the image is truncated.');
    } else {
      this.clearNotice('capped');
    }
    const where =
      backend.kind === 'gpu'
        ? `WebGPU (${backend.gpu.adapterDescription}): ${IMAGE_WIDTH}×${IMAGE_HEIGHT} rays`
        : `CPU fallback (float64 twin): ${CPU_WIDTH}×${CPU_HEIGHT} rays`;
    if (this.cost) {
      this.cost.textContent = `${where} × N = ${inputs.steps} steps in ${formatMilliseconds(frame.milliseconds)} (${frame.how}). Reference: midpoint, exact update, N = ${REFERENCE_STEPS}, computed once per density scale.`;
    }
    if (this.imageCanvas)
      this.imageCanvas.setAttribute(
        'aria-label',
        `Ray-marched image, ${PLACEMENT_NAMES[inputs.placement] ?? inputs.placement} samples, N = ${inputs.steps}, RMSE ${formatNumber(error, 3)}`,
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

  /** Renders N = 1, 2, 4, …, 256, yielding to the page between steps; Cancel stops it. */
  private async runSweep(): Promise<void> {
    const token = ++this.sweepToken;
    const inputs = inputsFrom(this.values);
    const backend = await this.chooseBackend();
    this.setSweeping(true);
    this.set('slope', 'sweeping…');
    const steps: number[] = [];
    const errors: number[] = [];
    const times: number[] = [];
    const label = `${PLACEMENT_NAMES[inputs.placement] ?? inputs.placement}, ${inputs.linear ? 'linear' : 'exact'} update, σ̄ = ${formatNumber(inputs.density, 3)}`;
    try {
      for (const [k, n] of SWEEP_STEPS.entries()) {
        if (token !== this.sweepToken) return;
        if (this.sweepStatus)
          this.sweepStatus.textContent = `N = ${n} (${k + 1} of ${SWEEP_STEPS.length})…`;
        const frame = await this.frame(backend, inputs, n);
        if (token !== this.sweepToken) return;
        steps.push(n);
        errors.push(rmse(frame.image.radiance, frame.reference));
        times.push(frame.milliseconds);
        if (this.progress) this.progress.value = k + 1;
        this.plotSweep(steps, errors, times, label);
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
    const slope = convergenceSlope(steps, errors);
    this.set(
      'slope',
      slope === null
        ? 'no fit'
        : `p = ${formatNumber(slope, 3)} (order ${formatNumber(-slope, 3)})`,
    );
    if (this.sweepStatus)
      this.sweepStatus.textContent = `Sweep done: ${label}, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}.`;
    this.setSweeping(false);
  }

  private plotSweep(steps: number[], errors: number[], times: number[], label: string): void {
    // uPlot wants ascending x: sort the points by time. At small N the fixed cost
    // of a dispatch dominates, so time is not monotone in N.
    const order = steps.map((_, i) => i).sort((a, b) => times[a]! - times[b]!);
    const x = order.map((i) => Math.log10(Math.max(times[i]!, 1e-4)));
    this.plotHint?.remove();
    this.plotHint = null;
    this.plot?.update(x, [
      { label: `RMSE, ${label}`, color: '#d9822b', values: order.map((i) => errors[i]!) },
    ]);
  }
}

export function defineRaymarchSteps(): void {
  if (!customElements.get('sb-raymarch-steps'))
    customElements.define('sb-raymarch-steps', RaymarchStepsElement);
}
