// Drawing of <sb-raymarch-steps> and its CPU backend. Both backends hand the
// widget an image of radiances (the GPU path reads its storage buffer back, as
// it needs the numbers for the RMSE anyway); these functions colour the image
// and the error image into 2D canvases. Without WebGPU, the float64 twin in
// model.ts marches the image at 1/CPU_SCALE resolution.
import {
  CPU_SCALE,
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  errorColour,
  radianceColour,
  referenceImageCpu,
  renderImageCpu,
  type MarchImage,
  type MarchInputs,
} from './model.ts';
import { context2d } from '../base/canvas2d.ts';

/** Paints width × height colours into a canvas, scaled to the canvas's size. */
export function paintImage(
  canvas: HTMLCanvasElement,
  width: number,
  height: number,
  colourAt: (index: number) => [number, number, number],
): void {
  const context = context2d(canvas);
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const image = context.createImageData(width, height);
  for (let index = 0; index < width * height; index++) {
    const rgb = colourAt(index);
    for (let c = 0; c < 3; c++) image.data[4 * index + c] = Math.round(rgb[c]!);
    image.data[4 * index + 3] = 255;
  }
  if (width === canvas.width && height === canvas.height) {
    context.putImageData(image, 0, 0);
    return;
  }
  const small = new OffscreenCanvas(width, height);
  context2d(small)?.putImageData(image, 0, 0);
  // Nearest neighbour: the fallback's pixels stay visible as pixels.
  context.imageSmoothingEnabled = false;
  context.drawImage(small, 0, 0, canvas.width, canvas.height);
}

/** Paints the radiance image and |image − reference| on the given error scale. */
export function paintImages(
  imageCanvas: HTMLCanvasElement,
  errorCanvas: HTMLCanvasElement,
  image: MarchImage,
  reference: ArrayLike<number>,
  scale: number,
): void {
  paintImage(imageCanvas, image.width, image.height, (i) => radianceColour(image.radiance[i]!));
  paintImage(errorCanvas, image.width, image.height, (i) =>
    errorColour(image.radiance[i]! - reference[i]!, scale),
  );
}

export const CPU_WIDTH = IMAGE_WIDTH / CPU_SCALE;
export const CPU_HEIGHT = IMAGE_HEIGHT / CPU_SCALE;

/** The float64 image at reduced resolution and the time it took (ms, CPU wall time). */
export function renderCpu(
  inputs: MarchInputs,
  steps = inputs.steps,
): { image: MarchImage; milliseconds: number } {
  const start = performance.now();
  const image = renderImageCpu(CPU_WIDTH, CPU_HEIGHT, inputs, steps);
  return { image, milliseconds: performance.now() - start };
}

export function referenceCpu(density: number): Float64Array {
  return referenceImageCpu(CPU_WIDTH, CPU_HEIGHT, density);
}
