// Drawing of <sb-delta-tracking> and its CPU backend. Both backends hand the
// widget per-pixel means and second moments (the GPU path reads its storage
// buffer back); these functions colour the transmittance image and the variance
// image into 2D canvases. Without WebGPU, the float64 twin in model.ts renders
// the image at 1/CPU_SCALE resolution.
import { paintImage } from '../raymarch-steps/cpuBackend.ts';
import {
  CPU_SCALE,
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  renderImageCpu,
  transmittanceColour,
  varianceColour,
  type TrackingImage,
  type TrackingInputs,
} from './model.ts';

/** Paints the mean transmittance and the per-pixel variance on the given scale. */
export function paintImages(
  imageCanvas: HTMLCanvasElement,
  varianceCanvas: HTMLCanvasElement,
  image: TrackingImage,
  variance: ArrayLike<number>,
  scale: number,
): void {
  paintImage(imageCanvas, image.width, image.height, (i) => transmittanceColour(image.mean[i]!));
  paintImage(varianceCanvas, image.width, image.height, (i) => varianceColour(variance[i]!, scale));
}

export const CPU_WIDTH = IMAGE_WIDTH / CPU_SCALE;
export const CPU_HEIGHT = IMAGE_HEIGHT / CPU_SCALE;

/** The float64 image at reduced resolution and the time it took (ms, CPU wall time). */
export function renderCpu(
  inputs: TrackingInputs,
  spp = inputs.spp,
): { image: TrackingImage; milliseconds: number } {
  const start = performance.now();
  const image = renderImageCpu(CPU_WIDTH, CPU_HEIGHT, inputs, spp);
  return { image, milliseconds: performance.now() - start };
}
