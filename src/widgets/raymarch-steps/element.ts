// <sb-raymarch-steps>: ray marching an emissive, absorbing volume (chapter 5).
// Marches one ray per pixel with N steps on the GPU, shows the image next to its
// error against a converged reference (false colour, labelled scale), the RMSE,
// the GPU time and the clamped linear factors; a cancellable sweep over
// N = 1, 2, 4, …, 256 plots RMSE against GPU time and fits the order of convergence.
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
import { ReadoutList } from '../base/readoutList.ts';
import { SweepControls, logLogSlope } from '../base/sweep.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { RAYMARCH_STEPS } from './schema.ts';
import { CPU_HEIGHT, CPU_WIDTH, paintImages, referenceCpu, renderCpu } from './cpuBackend.ts';
import { RaymarchStepsGpu } from './gpuBackend.ts';
import {
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  RADIANCE_SCALE,
  REFERENCE_STEPS,
  errorColour,
  inputsFrom,
  maxError,
  rmse,
  type MarchImage,
  type MarchInputs,
} from './model.ts';

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
  private readouts: ReadoutList | null = null;
  private cost: HTMLElement | null = null;
  private sweep: SweepControls | null = null;
  private readonly backends = new BackendChooser(
    (gpu) => new RaymarchStepsGpu(gpu),
    () => {
      this.sweep?.cancel('stopped: the GPU was lost');
      this.scheduleRender();
    },
  );

  protected buildStage(stage: HTMLElement): void {
    this.imageCanvas = imageCanvas('Ray-marched image of the volume', IMAGE_WIDTH, IMAGE_HEIGHT);
    this.errorCanvas = imageCanvas('Error image, |image − reference|', IMAGE_WIDTH, IMAGE_HEIGHT);
    const error = imagePanel(this.errorCanvas, 'Error |L − L_ref|', {
      gradient: gradientCss((x) => errorColour(x, 1)),
      low: '0',
      top: { readout: 'error-scale' },
    });
    this.scaleTop = error.top;
    stage.appendChild(
      imageFigure(
        imagePanel(this.imageCanvas, `Radiance L (colour scale 0 … ${RADIANCE_SCALE})`).panel,
        error.panel,
      ),
    );
    this.sweep = new SweepControls(
      stage,
      this,
      {
        name: 'N',
        buttonText: 'Run sweep N = 1 … 256',
        hint: 'Run the sweep to plot RMSE against the time per render for N = 1, 2, 4, …, 256 and fit the order of convergence.',
        color: '#d9822b',
        statusClass: 'sb-rm-sweep-status',
      },
      () => void this.runSweep(),
    );
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
    this.cost = this.readouts.cost;
    this.set('slope', 'run the sweep');
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.readouts?.set(key, text, state);
  }

  /** One image with N steps on the backend in use, and the reference to compare it with. */
  private async frame(
    backend: Backend<RaymarchStepsGpu>,
    inputs: MarchInputs,
    steps: number,
  ): Promise<Frame> {
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
    const backend = await this.backends.choose();
    let frame: Frame;
    try {
      frame = await this.frame(backend, inputs, inputs.steps);
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.backends.useCpu(gpuFailureReason(error));
      this.sweep?.cancel('stopped: the GPU was lost');
      this.scheduleRender();
      return;
    }
    if (backend.kind === 'gpu') {
      this.clearNotice('backend');
    } else {
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU twin: the same rays and marches, at ${CPU_WIDTH}×${CPU_HEIGHT} pixels.`,
      );
    }
    this.showFrame(inputs, frame, backend);
  }

  private showFrame(inputs: MarchInputs, frame: Frame, backend: Backend<RaymarchStepsGpu>): void {
    const { image, reference } = frame;
    const error = rmse(image.radiance, reference);
    const largest = maxError(image.radiance, reference);
    const scale = niceScale(largest);
    if (this.imageCanvas && this.errorCanvas)
      paintImages(this.imageCanvas, this.errorCanvas, image, reference, scale);
    if (this.scaleTop) this.scaleTop.textContent = formatNumber(scale, 2);
    this.set('rmse', formatNumber(error, 3));
    this.set('max-error', formatNumber(largest, 3));
    this.set('time', `${formatMilliseconds(frame.milliseconds)} (${frame.how})`);
    this.recordFrameCost(frame.milliseconds, frame.how);
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

  /** Renders N = 1, 2, 4, …, 256 and fits the order of convergence. */
  private runSweep(): Promise<void> {
    return this.sweep!.run(async () => {
      const inputs = inputsFrom(this.values);
      const backend = await this.backends.choose();
      this.set('slope', 'sweeping…');
      const label = `${PLACEMENT_NAMES[inputs.placement] ?? inputs.placement}, ${inputs.linear ? 'linear' : 'exact'} update, σ̄ = ${formatNumber(inputs.density, 3)}`;
      return {
        label,
        measure: async (n) => {
          const frame = await this.frame(backend, inputs, n);
          return {
            rmse: rmse(frame.image.radiance, frame.reference),
            milliseconds: frame.milliseconds,
          };
        },
        finish: (points) => {
          const slope = logLogSlope(
            points.map((p) => p.n),
            points.map((p) => p.rmse),
          );
          this.set(
            'slope',
            slope === null
              ? 'no fit'
              : `p = ${formatNumber(slope, 3)} (order ${formatNumber(-slope, 3)})`,
          );
          return `${label}, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}`;
        },
        failed: () => this.set('slope', 'failed', 'bad'),
      };
    });
  }
}

export function defineRaymarchSteps(): void {
  if (!customElements.get('sb-raymarch-steps'))
    customElements.define('sb-raymarch-steps', RaymarchStepsElement);
}
