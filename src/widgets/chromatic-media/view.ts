// The drawing of <sb-chromatic-media>: four small pictures side by side (the three
// estimators and the reference), accumulated pass by pass. Each frame runs one pass of
// every estimator (GPU kernel, or the float64 twin in the compute worker), adds it to the
// running sums, and reports the statistics (model.ts); while fewer than `target` samples
// per pixel are in, the frame asks for background refinement, so the pictures keep
// converging while the page stays responsive. Readouts, backend choice and fallback are the
// base element's (widget.ts holds the rows).
import { drawPixels } from '../base/pixels.ts';
import type { ManagedCanvas, ViewContext, WidgetView } from '../base/view.ts';
import type { FrameRequest } from '../base/refinement.ts';
import { workerJobs } from '../../workers/compute.ts';
import type { GpuTiming } from '../base/timing.ts';
import { ChromaticGpu } from './gpuBackend.ts';
import type { jobs } from './jobs.ts';
import {
  CPU_SIZE,
  ESTIMATORS,
  ESTIMATOR_INDEX,
  ESTIMATOR_LABELS,
  GPU_SIZE,
  REFERENCE_FACTOR,
  REFERENCE_FRAME_OFFSET,
  accumulate,
  accumulationKey,
  emptyAccumulation,
  estimatorStats,
  inputsFrom,
  means,
  toPixels,
  type Accumulation,
  type ChromaticInputs,
  type EstimatorName,
  type EstimatorStats,
} from './model.ts';
import type { ChromaticFrame } from './widget.ts';

type Pass = (
  inputs: ChromaticInputs,
  estimator: number,
  size: number,
  spp: number,
  frame: number,
) => Promise<{ sums: ArrayLike<number>; milliseconds: number }>;

interface State {
  key: string;
  size: number;
  estimators: Record<EstimatorName, Accumulation>;
  reference: Accumulation;
  pass: number;
}

export function createView(context: ViewContext): WidgetView<ChromaticFrame, ChromaticGpu> {
  const pictures: Record<EstimatorName | 'reference', ManagedCanvas> = {
    oneChannel: context.canvas({
      width: GPU_SIZE,
      height: GPU_SIZE,
      label: ESTIMATOR_LABELS.oneChannel,
    }),
    hero: context.canvas({ width: GPU_SIZE, height: GPU_SIZE, label: ESTIMATOR_LABELS.hero }),
    spectral: context.canvas({
      width: GPU_SIZE,
      height: GPU_SIZE,
      label: ESTIMATOR_LABELS.spectral,
    }),
    reference: context.canvas({ width: GPU_SIZE, height: GPU_SIZE, label: 'Reference' }),
  };
  const cpuJobs = workerJobs<typeof jobs>('chromatic-media');
  let state: State | null = null;

  function fresh(inputs: ChromaticInputs, size: number): State {
    return {
      key: `${accumulationKey(inputs)}@${size}`,
      size,
      estimators: {
        oneChannel: emptyAccumulation(size),
        hero: emptyAccumulation(size),
        spectral: emptyAccumulation(size),
      },
      reference: emptyAccumulation(size),
      pass: 0,
    };
  }

  async function frame(
    request: FrameRequest,
    size: number,
    run: Pass,
    timing: GpuTiming | 'cpu',
  ): Promise<ChromaticFrame> {
    const inputs = inputsFrom(context.values);
    const key = `${accumulationKey(inputs)}@${size}`;
    if (!state || state.key !== key || (request.stage === 0 && !request.background)) {
      state = fresh(inputs, size);
    }
    const s = state;
    const spp = Math.min(inputs.spp, Math.max(inputs.target - s.estimators.hero.samples, 1));
    let frameMilliseconds = 0;
    for (const name of ESTIMATORS) {
      const pass = await run(inputs, ESTIMATOR_INDEX[name], size, spp, s.pass);
      accumulate(s.estimators[name], pass.sums, spp, pass.milliseconds);
      frameMilliseconds += pass.milliseconds;
    }
    // The reference: one channel at a time, REFERENCE_FACTOR× the samples, its own streams.
    const reference = await run(
      inputs,
      ESTIMATOR_INDEX.oneChannel,
      size,
      REFERENCE_FACTOR * spp,
      REFERENCE_FRAME_OFFSET + s.pass,
    );
    accumulate(s.reference, reference.sums, REFERENCE_FACTOR * spp, reference.milliseconds);
    frameMilliseconds += reference.milliseconds;
    s.pass++;
    const referenceMeans = means(s.reference);
    const stats = {} as Record<EstimatorName, EstimatorStats>;
    const milliseconds = {} as Record<EstimatorName, number>;
    for (const name of ESTIMATORS) {
      stats[name] = estimatorStats(s.estimators[name], referenceMeans);
      milliseconds[name] = s.estimators[name].milliseconds;
      drawPixels(
        pictures[name].element,
        toPixels(means(s.estimators[name]), size, inputs.exposure),
        size,
        size,
      );
    }
    drawPixels(
      pictures.reference.element,
      toPixels(referenceMeans, size, inputs.exposure),
      size,
      size,
    );
    const samples = s.estimators.hero.samples;
    const done = samples >= inputs.target;
    return {
      inputs,
      size,
      samples,
      referenceSamples: s.reference.samples,
      stats,
      milliseconds,
      frameMilliseconds,
      timing,
      refinement: {
        label: done ? 'full' : `Accumulating: ${samples} of ${inputs.target} samples per pixel`,
        pending: done ? null : 'background',
      },
    };
  }

  return {
    cpuNotice: `Showing the float64 twin at ${CPU_SIZE}×${CPU_SIZE} pixels; the GPU draws ${GPU_SIZE}×${GPU_SIZE}.`,
    build(stage) {
      const row = document.createElement('div');
      row.className = 'sb-chromatic-row';
      row.style.display = 'grid';
      // Two by two: each picture gets half the stage's width (64 pixels scaled up, square).
      row.style.gridTemplateColumns = 'repeat(2, minmax(0, 1fr))';
      row.style.gap = '0.5rem';
      for (const [name, picture] of Object.entries(pictures)) {
        const figure = document.createElement('figure');
        figure.style.margin = '0';
        picture.element.style.width = '100%';
        picture.element.style.height = 'auto';
        picture.element.style.aspectRatio = '1 / 1';
        picture.element.style.imageRendering = 'pixelated';
        figure.appendChild(picture.element);
        const caption = document.createElement('figcaption');
        caption.textContent =
          name === 'reference'
            ? `Reference (${REFERENCE_FACTOR}× samples)`
            : ESTIMATOR_LABELS[name as EstimatorName];
        figure.appendChild(caption);
        row.appendChild(figure);
      }
      stage.appendChild(row);
    },
    createRenderer: (gpu) => new ChromaticGpu(gpu),
    async renderGpu(renderer, _gpu, request) {
      let timing: GpuTiming = 'gpu-timestamp';
      const run: Pass = async (...args) => {
        const pass = await renderer.pass(...args);
        if (pass.timing === 'gpu-wall') timing = 'gpu-wall';
        return pass;
      };
      const result = await frame(request, GPU_SIZE, run, 'gpu-timestamp');
      return { ...result, timing };
    },
    async renderCpu(request) {
      const run: Pass = (...args) => cpuJobs.run('pass', args);
      return frame(request, CPU_SIZE, run, 'cpu');
    },
    refinement: (f) => f.refinement,
    show(f) {
      for (const name of ESTIMATORS) {
        const s = f.stats[name];
        pictures[name].element.setAttribute(
          'aria-label',
          `${ESTIMATOR_LABELS[name]}: a sphere of chromatic medium, ${f.samples} samples per pixel, colour noise ${s.colourNoise.toFixed(3)} (×1000).`,
        );
      }
      pictures.reference.element.setAttribute(
        'aria-label',
        `Reference picture, one channel at a time with ${f.referenceSamples} samples per pixel.`,
      );
    },
  };
}
