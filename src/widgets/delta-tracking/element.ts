// <sb-delta-tracking>: unbiased and biased transmittance estimators (chapter 6).
// Averages spp estimates per pixel on the GPU, shows the mean transmittance
// next to the per-pixel variance (false colour, labelled scale), the RMSE and
// mean bias against the exact T, the lookups per estimate and the GPU time; a
// cancellable sweep over spp = 1, 2, 4, …, 256 plots RMSE against GPU time.
import { BackendChooser, type Backend } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/imageKernel.ts';
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
import { DELTA_TRACKING } from './schema.ts';
import { CPU_HEIGHT, CPU_WIDTH, paintImages, renderCpu } from './cpuBackend.ts';
import { DeltaTrackingGpu } from './gpuBackend.ts';
import {
  ESTIMATOR_NAMES,
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  exactImage,
  imageStatistics,
  inputsFrom,
  sampleVariance,
  transmittanceColour,
  varianceColour,
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
  private readouts: ReadoutList | null = null;
  private cost: HTMLElement | null = null;
  private sweep: SweepControls | null = null;
  private readonly backends = new BackendChooser(
    (gpu) => new DeltaTrackingGpu(gpu),
    () => {
      this.sweep?.cancel('stopped: the GPU was lost');
      this.scheduleRender();
    },
  );

  protected buildStage(stage: HTMLElement): void {
    this.imageCanvas = imageCanvas('Estimated transmittance image', IMAGE_WIDTH, IMAGE_HEIGHT);
    this.varianceCanvas = imageCanvas('Per-pixel variance image', IMAGE_WIDTH, IMAGE_HEIGHT);
    const variance = imagePanel(this.varianceCanvas, 'Variance of one estimate, per pixel', {
      gradient: gradientCss((x) => varianceColour(x, 1)),
      low: '0',
      top: { readout: 'variance-scale' },
    });
    this.scaleTop = variance.top;
    stage.appendChild(
      imageFigure(
        imagePanel(this.imageCanvas, 'Estimated T (mean of spp samples)', {
          gradient: gradientCss(transmittanceColour),
          low: '0',
          top: { text: '1' },
        }).panel,
        variance.panel,
      ),
    );
    this.sweep = new SweepControls(
      stage,
      this,
      {
        name: 'spp',
        buttonText: 'Run sweep spp = 1 … 256',
        hint: 'Run the sweep to plot RMSE against the time per render for spp = 1, 2, 4, …, 256. An unbiased estimator falls as spp^(−½); a biased one levels off at its bias.',
        color: '#3b7dd8',
        statusClass: 'sb-dt-sweep-status',
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
      this.sweep?.cancel('stopped: the GPU path failed');
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
    const scale = niceScale(stats.largestVariance);
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

  /** Renders spp = 1, 2, 4, …, 256 and fits the slope of log RMSE against log spp. */
  private runSweep(): Promise<void> {
    return this.sweep!.run(async () => {
      const inputs = inputsFrom(this.values);
      const backend = await this.backends.choose();
      this.set('slope', 'sweeping…');
      const label = `${ESTIMATOR_NAMES[inputs.estimator] ?? inputs.estimator}, ${MAJORANT_NAMES[inputs.majorant] ?? inputs.majorant}`;
      return {
        label,
        measure: async (n) => {
          const frame = await this.frame(backend, inputs, n);
          const stats = imageStatistics(frame.image, frame.exact, sampleVariance(frame.image));
          return { rmse: stats.rmse, milliseconds: frame.milliseconds };
        },
        finish: (points) => {
          const slope = logLogSlope(
            points.map((p) => p.n),
            points.map((p) => p.rmse),
          );
          this.set(
            'slope',
            slope === null ? 'no fit' : `p = ${formatNumber(slope, 3)} (unbiased: −0.5)`,
          );
          return `${label}, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}`;
        },
        failed: () => this.set('slope', 'failed', 'bad'),
      };
    });
  }
}

export function defineDeltaTracking(): void {
  if (!customElements.get('sb-delta-tracking'))
    customElements.define('sb-delta-tracking', DeltaTrackingElement);
}
