// The float64 work of <sb-transfer-function> that would otherwise hold the page
// (issue 23): the CPU twin's rows of the picture, of the termination timings and of
// the fine-step reference's bands. They run in the compute worker
// (src/workers/compute.ts), cached by arguments. No DOM, no GPU.
import {
  buildTransferFunction,
  emptyImage,
  renderRowsCpu,
  type ControlPoint,
  type FrameInputs,
} from './model.ts';

/** What the rows depend on of FrameInputs: the transfer function is rebuilt from it in the worker. */
export interface RowsScene {
  points: ControlPoint[];
  colormap: string;
  azimuth: number;
  elevation: number;
}

/** Rows [rowStart, rowEnd) of a size² image: planes of `rows × size` values, and their statistics. */
export interface RowsBand {
  rows: number;
  rgb: Float64Array<ArrayBuffer>;
  stepsPerPixel: Uint32Array<ArrayBuffer>;
  plannedPerPixel: Uint32Array<ArrayBuffer>;
  steps: number;
  plannedSteps: number;
  terminatedRays: number;
  cappedRays: number;
  /** The float64 march's time in the worker (ms). */
  milliseconds: number;
}

/** The scene part of `inputs`, the only part the rows read besides the step and threshold. */
export function rowsScene(inputs: FrameInputs): RowsScene {
  const { points, colormap, azimuth, elevation } = inputs;
  return { points, colormap, azimuth, elevation };
}

export const jobs = {
  /** renderRowsCpu for rows [rowStart, rowEnd) of a size² image, as a band. */
  rows(
    scene: RowsScene,
    size: number,
    stepVoxels: number,
    threshold: number,
    rowStart: number,
    rowEnd: number,
  ): RowsBand {
    const start = performance.now();
    const end = Math.min(rowEnd, size);
    const inputs: FrameInputs = {
      ...scene,
      tf: buildTransferFunction(scene.points, scene.colormap),
      step: stepVoxels,
      termination: threshold > 0,
      epsilon: threshold,
      panel: 'error',
    };
    const image = emptyImage(size, new Float64Array(3 * size * size));
    renderRowsCpu(image, inputs, stepVoxels, threshold, rowStart, end);
    const pixels = size * size;
    const from = rowStart * size;
    const to = end * size;
    const bandPixels = to - from;
    const rgb = new Float64Array(3 * bandPixels);
    for (let c = 0; c < 3; c++)
      rgb.set(image.rgb.subarray(c * pixels + from, c * pixels + to), c * bandPixels);
    return {
      rows: end - rowStart,
      rgb,
      stepsPerPixel: image.stepsPerPixel.slice(from, to),
      plannedPerPixel: image.plannedPerPixel.slice(from, to),
      steps: image.steps,
      plannedSteps: image.plannedSteps,
      terminatedRays: image.terminatedRays,
      cappedRays: image.cappedRays,
      milliseconds: performance.now() - start,
    };
  },
};
