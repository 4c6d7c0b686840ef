// Pictures computed off the canvas (the CPU twins' RGBA pixels, often in the compute
// worker) drawn onto a widget's canvas: put at their own size, then scaled up to the
// canvas with smoothing, so a coarse preview and the finer stages fill the same area.

/** Draws width × height RGBA pixels scaled to fill `canvas`. */
export function drawPixels(
  canvas: HTMLCanvasElement,
  pixels: Uint8ClampedArray<ArrayBuffer>,
  width: number,
  height: number,
): void {
  // Rasterised on the CPU (willReadFrequently; the first getContext fixes it): drawn in
  // Chromium's GPU process, the picture waited behind WebGPU's work there on a software
  // adapter, and the widget's next pass behind it (see plot.ts, withCpuCanvases).
  const context = canvas.getContext('2d', { willReadFrequently: true });
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const small = new OffscreenCanvas(width, height);
  small.getContext('2d')?.putImageData(new ImageData(pixels, width, height), 0, 0);
  context.imageSmoothingEnabled = true;
  context.drawImage(small, 0, 0, canvas.width, canvas.height);
}
