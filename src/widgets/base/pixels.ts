// Pictures computed off the canvas (the CPU twins' RGBA pixels, often in the compute
// worker) drawn onto a widget's canvas: put at their own size, then scaled up to the
// canvas with smoothing, so a coarse preview and the finer stages fill the same area.
import { context2d } from './canvas2d.ts';

/** Draws width × height RGBA pixels scaled to fill `canvas`. */
export function drawPixels(
  canvas: HTMLCanvasElement,
  pixels: Uint8ClampedArray<ArrayBuffer>,
  width: number,
  height: number,
): void {
  const context = context2d(canvas);
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const small = new OffscreenCanvas(width, height);
  context2d(small)?.putImageData(new ImageData(pixels, width, height), 0, 0);
  context.imageSmoothingEnabled = true;
  context.drawImage(small, 0, 0, canvas.width, canvas.height);
}
