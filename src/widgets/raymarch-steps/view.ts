// The drawing of <sb-raymarch-steps>: the marched image and its error image (2D
// canvases painted from the radiance, on either backend), the error scale, the
// notices of the linear update and the step cap, and the sweep over N. Readouts,
// backends and fallback: widget.ts and the base element.
import type { GpuContext } from '../../gpu/device.ts';
import { formatNumber } from '../base/format.ts';
import {
  gradientCss,
  imageCanvas,
  imageFigure,
  imagePanel,
  niceScale,
} from '../base/imagePanel.ts';
import { SweepControls } from '../base/sweep.ts';
import { logLogSlope } from '../../statistics/regression.ts';
import type { Backend } from '../base/backend.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { LadderFamily } from '../base/ladderFamily.ts';
import { GPU_FIRST_PICTURE_MS } from '../base/refinement.ts';
import { imageRungs, type ImageSize } from './stages.ts';
import { workerJobs } from '../../workers/compute.ts';
import { CPU_HEIGHT, CPU_WIDTH, paintImages } from './cpuBackend.ts';
import type { jobs as marchJobTable } from './jobs.ts';
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
  type MarchInputs,
} from './model.ts';
import type { RaymarchFrame } from './widget.ts';

const PLACEMENT_NAMES: Readonly<Record<string, string>> = {
  left: 'left',
  midpoint: 'midpoint',
  'jittered-ray': 'jittered per ray',
  'jittered-strata': 'jittered per step',
};

/** The CPU fallback's float64 image and reference, in the compute worker, cached by arguments. */
const cpuJobs = workerJobs<typeof marchJobTable>('raymarch-steps');

/**
 * One image with `steps` steps per ray on the backend, and the reference to compare
 * it with. On the CPU both come from the worker (the page never marches), the
 * reference once per density.
 */
async function march(
  backend: Backend<RaymarchStepsGpu>,
  inputs: MarchInputs,
  steps: number,
  signal?: AbortSignal,
  size: ImageSize = { width: IMAGE_WIDTH, height: IMAGE_HEIGHT },
): Promise<RaymarchFrame> {
  const measured = async (): Promise<Omit<RaymarchFrame, 'rmse' | 'largestError'>> => {
    if (backend.kind === 'gpu') {
      const { width, height } = size;
      const reference = await backend.renderer.reference(inputs.density, width, height);
      const image = await backend.renderer.render(inputs, steps, width, height);
      return {
        inputs,
        image,
        reference,
        referenceSteps: REFERENCE_STEPS,
        milliseconds: image.milliseconds,
        timing: image.timing,
        capped: image.capped,
      };
    }
    const options = signal ? { signal } : {};
    const { image, milliseconds } = await cpuJobs.run('render', [inputs, steps], options);
    const reference = await cpuJobs.run('reference', [inputs.density], options);
    return {
      inputs,
      image,
      reference,
      referenceSteps: REFERENCE_STEPS,
      milliseconds,
      timing: 'cpu',
      capped: false,
    };
  };
  const frame = await measured();
  return {
    ...frame,
    rmse: rmse(frame.image.radiance, frame.reference),
    largestError: maxError(frame.image.radiance, frame.reference),
  };
}

export function createView(
  context: ViewContext<RaymarchStepsGpu>,
): WidgetView<RaymarchFrame, RaymarchStepsGpu> {
  const picture = imageCanvas('Ray-marched image of the volume', IMAGE_WIDTH, IMAGE_HEIGHT);
  const errorImage = imageCanvas('Error image, |image − reference|', IMAGE_WIDTH, IMAGE_HEIGHT);
  let scaleTop: HTMLElement | null = null;
  let sweep: SweepControls | null = null;
  /** The GPU's ladders of image sizes, one per N (stages.ts, ladderFamily.ts). */
  const gpuLadders = new LadderFamily<ImageSize>(GPU_FIRST_PICTURE_MS);

  /** Renders N = 1, 2, 4, …, 256 and fits the order of convergence. */
  const runSweep = (controls: SweepControls): Promise<void> =>
    controls.run(async () => {
      const inputs = inputsFrom(context.values);
      const backend = await context.backend();
      context.setReadout('slope', 'sweeping…');
      const label = `${PLACEMENT_NAMES[inputs.placement] ?? inputs.placement}, ${inputs.linear ? 'linear' : 'exact'} update, σ̄ = ${formatNumber(inputs.density, 3)}`;
      return {
        label,
        measure: async (n) => {
          const frame = await march(backend, inputs, n);
          return { rmse: frame.rmse, milliseconds: frame.milliseconds };
        },
        finish: (points) => {
          const slope = logLogSlope(
            points.map((p) => p.n),
            points.map((p) => p.rmse),
          );
          context.setReadout(
            'slope',
            slope === null
              ? 'no fit'
              : `p = ${formatNumber(slope, 3)} (order ${formatNumber(-slope, 3)})`,
          );
          return `${label}, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}`;
        },
        failed: () => context.setReadout('slope', 'failed', 'bad'),
      };
    });

  return {
    cpuNotice: `Showing the float64 CPU twin: the same rays and marches, at ${CPU_WIDTH}×${CPU_HEIGHT} pixels, computed in a worker.`,
    build(stage) {
      const error = imagePanel(errorImage, 'Error |L − L_ref|', {
        gradient: gradientCss((x) => errorColour(x, 1)),
        low: '0',
        top: { readout: 'error-scale' },
      });
      scaleTop = error.top;
      stage.appendChild(
        imageFigure(
          imagePanel(picture, `Radiance L (colour scale 0 … ${RADIANCE_SCALE})`).panel,
          error.panel,
        ),
      );
      const controls = new SweepControls(
        stage,
        context.host,
        {
          name: 'N',
          buttonText: 'Run sweep N = 1 … 256',
          hint: 'Run the sweep to plot RMSE against the time per render for N = 1, 2, 4, …, 256 and fit the order of convergence.',
          color: '#d9822b',
          statusClass: 'sb-rm-sweep-status',
        },
        () => void runSweep(controls),
      );
      sweep = controls;
    },
    createRenderer: (gpu: GpuContext) => new RaymarchStepsGpu(gpu),
    refinement: (frame) => frame.refinement,
    async renderGpu(renderer, gpu, request) {
      const inputs = inputsFrom(context.values);
      const backend: Backend<RaymarchStepsGpu> = { kind: 'gpu', gpu, renderer };
      const ladder = gpuLadders.get(String(inputs.steps), () => imageRungs(inputs.steps));
      const choice = ladder.pick(request);
      // The reference of this size first (once per density and size), so that the
      // ladder learns what the march and its read-back cost, not the reference's 1024 steps.
      await renderer.reference(inputs.density, choice.rung.value.width, choice.rung.value.height);
      const started = performance.now();
      const frame = await march(backend, inputs, inputs.steps, request.signal, choice.rung.value);
      gpuLadders.record(ladder, choice, performance.now() - started);
      return { ...frame, refinement: ladder.refinement(choice) };
    },
    renderCpu(request) {
      const inputs = inputsFrom(context.values);
      return march({ kind: 'cpu', reason: '' }, inputs, inputs.steps, request.signal);
    },
    onCpuFallback: () => sweep?.cancel('stopped: the GPU was lost'),
    show({ inputs, image, reference, largestError, rmse: error, capped }) {
      const scale = niceScale(largestError);
      paintImages(picture, errorImage, image, reference, scale);
      if (scaleTop) scaleTop.textContent = formatNumber(scale, 2);
      if (inputs.linear && image.clampedSteps > 0) {
        context.showNotice(
          'clamped',
          'warning',
          `The linear update failed: in ${image.clampedSteps} steps σt·h > 1, so 1 − σt·h was negative (a negative transmittance) and was clamped to 0.`,
        );
      } else {
        context.clearNotice('clamped');
      }
      if (capped) {
        context.showNotice(
          'capped',
          'warning',
          'A march reached its step cap; the image is truncated.',
        );
      } else {
        context.clearNotice('capped');
      }
      picture.setAttribute(
        'aria-label',
        `Ray-marched image, ${PLACEMENT_NAMES[inputs.placement] ?? inputs.placement} samples, N = ${inputs.steps}, RMSE ${formatNumber(error, 3)}`,
      );
    },
  };
}
