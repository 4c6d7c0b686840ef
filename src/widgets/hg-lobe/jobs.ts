// The float64 work of <sb-hg-lobe> that would otherwise hold the page: the twin's
// replay of the kernel's PCG streams (the whole histogram on the CPU fallback, the
// first 2¹⁶ samples beside the GPU) and the CPU fallback's polar picture. They run in
// the compute worker (src/workers/compute.ts), cached by arguments. No DOM, no GPU.
import { polarPixels, sampleHistogramCpu } from './cpuBackend.ts';
import type { HgHistogram, HgLobeInputs } from './model.ts';

/** The polar picture's RGBA bytes at width × height and the float64 time it took (ms). */
export interface PolarImage {
  pixels: Uint8ClampedArray<ArrayBuffer>;
  width: number;
  height: number;
  milliseconds: number;
}

/** A replay shorter than this is timed again over repeats: the worker's clock has 5–100 µs steps. */
export const MIN_TIMED_MS = 5;

export const jobs = {
  /**
   * The histogram of samples 0 … count − 1 of the streams of `seed` (the kernel's
   * sampling pass), with the time of one replay: when one is under MIN_TIMED_MS it
   * is repeated until the repeats take that long, and the mean is kept, so a small N
   * never reads 0 ms.
   */
  histogram(g: number, count: number, seed: number): HgHistogram {
    const histogram = sampleHistogramCpu(g, count, seed);
    if (histogram.milliseconds >= MIN_TIMED_MS) return histogram;
    let repeats = 0;
    const start = performance.now();
    let elapsed = 0;
    do {
      sampleHistogramCpu(g, count, seed);
      repeats += 1;
      elapsed = performance.now() - start;
    } while (elapsed < MIN_TIMED_MS);
    return { ...histogram, milliseconds: elapsed / repeats };
  },
  /** The picture of lobeFragment for a canvas of canvasWidth × canvasHeight, at 1/scale resolution. */
  polar(
    inputs: HgLobeInputs,
    canvasWidth: number,
    canvasHeight: number,
    scale: number,
  ): PolarImage {
    const start = performance.now();
    const image = polarPixels(inputs, canvasWidth, canvasHeight, scale);
    return { ...image, milliseconds: performance.now() - start };
  },
};
