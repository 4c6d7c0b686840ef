// The one way a widget takes a 2D context: rasterised on the CPU, in the page or worker
// that draws (willReadFrequently; the first getContext of a canvas fixes its attributes
// for the canvas's life, so every call site asks the same).
//
// Accelerated, Chromium rasterises a 2D canvas in its GPU process, which also runs
// WebGPU. On a software adapter (SwiftShader) that raster competed with the widgets'
// compute passes: a plot's redraw held chromatic-media's next pass back by up to 430 ms,
// hg-lobe's wireframe took 0.6–2.7 s (issue 23, bench/firstPictureProbe.ts). The pictures
// a widget puts on a 2D canvas are small (putImageData of its own pixels, a plot's few
// hundred segments), a millisecond or two on the CPU. ESLint allows getContext('2d')
// nowhere else (eslint.config.js).

export type Context2D = CanvasRenderingContext2D | OffscreenCanvasRenderingContext2D;

/** The context attributes that ask for a canvas rasterised on the CPU. */
export const CPU_RASTERISED = { willReadFrequently: true } as const;

/** The CPU-rasterised 2D context of `canvas`; null where the canvas has another kind. */
export function context2d(canvas: HTMLCanvasElement): CanvasRenderingContext2D | null;
export function context2d(canvas: OffscreenCanvas): OffscreenCanvasRenderingContext2D | null;
export function context2d(canvas: HTMLCanvasElement | OffscreenCanvas): Context2D | null;
export function context2d(canvas: HTMLCanvasElement | OffscreenCanvas): Context2D | null {
  // eslint-disable-next-line no-restricted-syntax -- the one place that asks.
  return canvas.getContext('2d', CPU_RASTERISED) as Context2D | null;
}
