// Drawing of <sb-delta-tracking> and its CPU backend. Both backends hand the
// widget per-pixel means and second moments (the GPU path reads its storage
// buffer back); these functions colour the transmittance image and the variance
// image into 2D canvases. Without WebGPU, the float64 twin in model.ts renders
// the image at 1/CPU_SCALE resolution, a few rows at a time, yielding to the page
// between slices so that a long render (unbiased ray marching at high spp, the
// comparison's equal-time row, a sweep) never freezes it.
import { paintImage } from '../raymarch-steps/cpuBackend.ts';
import {
  CPU_SCALE,
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  emptyImageCpu,
  renderRowsCpu,
  transmittanceColour,
  varianceColour,
  type TrackingImage,
  type TrackingInputs,
} from './model.ts';

/** Paints the mean transmittance of an image into a canvas. */
export function paintEstimate(canvas: HTMLCanvasElement, image: TrackingImage): void {
  paintImage(canvas, image.width, image.height, (i) => transmittanceColour(image.mean[i]!));
}

/** Paints a per-pixel variance on the given scale (the colour scale's top). */
export function paintVariance(
  canvas: HTMLCanvasElement,
  image: TrackingImage,
  variance: ArrayLike<number>,
  scale: number,
): void {
  paintImage(canvas, image.width, image.height, (i) => varianceColour(variance[i]!, scale));
}

/** Paints the mean transmittance and the per-pixel variance on the given scale. */
export function paintImages(
  imageCanvas: HTMLCanvasElement,
  varianceCanvas: HTMLCanvasElement,
  image: TrackingImage,
  variance: ArrayLike<number>,
  scale: number,
): void {
  paintEstimate(imageCanvas, image);
  paintVariance(varianceCanvas, image, variance, scale);
}

export const CPU_WIDTH = IMAGE_WIDTH / CPU_SCALE;
export const CPU_HEIGHT = IMAGE_HEIGHT / CPU_SCALE;

/** Longest stretch (ms) the fallback computes before it lets the page paint and take input. */
const SLICE_MS = 12;

/**
 * The float64 image at reduced resolution and the time it took: CPU wall time
 * spent computing, without the pauses in which the page ran. Each slice of rows
 * is timed as a whole, so the coarse clock of a browser (0.1 ms without
 * cross-origin isolation) errs once per slice, not once per row.
 */
export async function renderCpu(
  inputs: TrackingInputs,
  spp = inputs.spp,
): Promise<{ image: TrackingImage; milliseconds: number }> {
  const image = emptyImageCpu(CPU_WIDTH, CPU_HEIGHT, spp);
  let busy = 0;
  let row = 0;
  while (row < CPU_HEIGHT) {
    const start = performance.now();
    do {
      renderRowsCpu(image, inputs, row, row + 1);
      row += 1;
    } while (row < CPU_HEIGHT && performance.now() - start < SLICE_MS);
    busy += performance.now() - start;
    if (row < CPU_HEIGHT) await new Promise((resolve) => setTimeout(resolve, 0));
  }
  return { image, milliseconds: busy };
}
