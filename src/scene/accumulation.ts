// Progressive accumulation of a render: per pixel and channel the running mean of the
// samples and M2, the sum of squared deviations from it (Chan, Golub & LeVeque's
// pairwise update, one pass at a time), from which the image (the mean, i.e. the
// box-filtered pixel radiance) and the per-pixel standard error sqrt(s²/n) follow.
//
// Two stores share one interface, Accumulation: ImageAccumulator here (float64, on the
// host: the CPU renderer's, and the full read-back of a GPU render) and GpuAccumulation
// (src/scene/gpuAccumulation.ts: the same moments in f32 storage buffers that stay on the
// GPU, with a reduction kernel for the statistics below). imageStatistics is the float64
// twin of that kernel (shaders/kernels/scene-statistics.wesl).

/** Words per pixel in a pass's output: sums of R, G, B, of their squares, lookups, capped. */
export const PASS_WORDS_PER_PIXEL = 8;

/** Whole-image numbers for readouts, from one reduction (a few words read back). */
export interface ImageStatistics {
  samples: number;
  pixels: number;
  /** Mean radiance over pixels and channels. */
  meanRadiance: number;
  /** Mean of the per-pixel standard errors over pixels and channels (NaN below 2 samples). */
  meanStandardError: number;
  /** Root mean square of the per-pixel standard errors (NaN below 2 samples). */
  rmsStandardError: number;
  /** Largest channel-averaged per-pixel standard error (0 below 2 samples). */
  maxPixelStandardError: number;
  /** Mean luminance of the mean over the mask's pixels (NaN without a mask or when empty). */
  maskedLuminance: number;
  lookups: number;
  capped: number;
  /** Against a reference (NaN without one): RMSE of the means over pixels and channels. */
  rmse: number;
  /**
   * Relative RMSE with the reference's own noise removed: sqrt(mean (I − R)² − mean SE_R²)
   * / mean R, NaN when the difference is within the reference's noise (the
   * volume-path-tracer's relativeError).
   */
  relativeError: number;
}

/** A progressive image's accumulated samples, wherever they are kept. */
export interface Accumulation {
  readonly width: number;
  readonly height: number;
  /** Samples per pixel accumulated so far. */
  readonly samples: number;
  /** Per-pixel weights for ImageStatistics.maskedLuminance (1 = counted); null clears. */
  setMask(mask: Uint8Array | null): void;
  /** The statistics, optionally against a reference of the same size on the same store. */
  statistics(reference?: Accumulation): Promise<ImageStatistics>;
  /** A frozen copy of the current state (same store), e.g. for error-against-time plots. */
  snapshot(): Accumulation;
  /** The whole image on the host (a full read-back for a GPU store): CLI and tests. */
  readImage(): Promise<ImageAccumulator>;
  /** Forgets every sample (the next pass overwrites the moments; nothing is cleared). */
  reset(): void;
  destroy(): void;
}

const LUMA = [0.2126, 0.7152, 0.0722] as const;

/** The float64 accumulation: the CPU renderer's store and a GPU render's read-back. */
export class ImageAccumulator implements Accumulation {
  /** Running mean per pixel and channel, RGB interleaved, row 0 at the top. */
  readonly meanValues: Float64Array;
  /** Sum of squared deviations from the mean, per pixel and channel. */
  readonly m2: Float64Array;
  samples = 0;
  lookups = 0;
  capped = 0;
  private mask: Uint8Array | null = null;

  constructor(
    readonly width: number,
    readonly height: number,
  ) {
    this.meanValues = new Float64Array(3 * width * height);
    this.m2 = new Float64Array(3 * width * height);
  }

  /** An accumulator holding given moments (a GPU read-back). */
  static fromMoments(
    width: number,
    height: number,
    moments: { samples: number; mean: ArrayLike<number>; m2: ArrayLike<number> },
    lookups: number,
    capped: number,
  ): ImageAccumulator {
    const image = new ImageAccumulator(width, height);
    image.meanValues.set(moments.mean);
    image.m2.set(moments.m2);
    image.samples = moments.samples;
    image.lookups = lookups;
    image.capped = capped;
    return image;
  }

  /**
   * Adds one pass: `floats`/`words` are the same PASS_WORDS_PER_PIXEL words per pixel
   * (the pass's sums per pixel over `samples` samples), combined with the moments so far
   * by the pairwise update (the same formulas as shaders/kernels/scene-accumulate.wesl).
   */
  addPass(floats: ArrayLike<number>, words: ArrayLike<number>, samples: number): void {
    if (samples <= 0) return;
    const pixels = this.width * this.height;
    const nA = this.samples;
    const nB = samples;
    const weight = nB / (nA + nB);
    for (let i = 0; i < pixels; i++) {
      const o = PASS_WORDS_PER_PIXEL * i;
      for (let c = 0; c < 3; c++) {
        const k = 3 * i + c;
        const sum = floats[o + c]!;
        const meanB = sum / nB;
        const m2B = Math.max(floats[o + 3 + c]! - sum * meanB, 0);
        if (nA === 0) {
          this.meanValues[k] = meanB;
          this.m2[k] = m2B;
        } else {
          const delta = meanB - this.meanValues[k]!;
          this.meanValues[k]! += delta * weight;
          this.m2[k]! += m2B + delta * delta * nA * weight;
        }
      }
      this.lookups += words[o + 6]!;
      this.capped += words[o + 7]!;
    }
    this.samples += samples;
  }

  /** The image: mean radiance per pixel and channel, RGB interleaved, row 0 at the top. */
  mean(): Float64Array {
    return this.meanValues.slice();
  }

  /**
   * Standard error of each pixel's mean, sqrt(s²/n) with the unbiased sample variance
   * s² = M2/(n − 1); NaN with fewer than two samples (no variance estimate).
   */
  standardError(): Float64Array {
    const n = this.samples;
    if (n < 2) return new Float64Array(this.m2.length).fill(NaN);
    return this.m2.map((m2) => Math.sqrt(Math.max(m2, 0) / (n * (n - 1))));
  }

  setMask(mask: Uint8Array | null): void {
    this.mask = mask;
  }

  statistics(reference?: Accumulation): Promise<ImageStatistics> {
    if (reference !== undefined && !(reference instanceof ImageAccumulator))
      return Promise.reject(new Error('a CPU accumulation compares only with a CPU one'));
    return Promise.resolve(imageStatistics(this, reference, this.mask));
  }

  snapshot(): ImageAccumulator {
    const copy = ImageAccumulator.fromMoments(
      this.width,
      this.height,
      { samples: this.samples, mean: this.meanValues, m2: this.m2 },
      this.lookups,
      this.capped,
    );
    copy.mask = this.mask;
    return copy;
  }

  readImage(): Promise<ImageAccumulator> {
    return Promise.resolve(this.snapshot());
  }

  reset(): void {
    this.samples = 0;
    this.lookups = 0;
    this.capped = 0;
    this.meanValues.fill(0);
    this.m2.fill(0);
  }

  destroy(): void {}
}

/**
 * The statistics of an image (and against a reference), in float64: the twin of the
 * reduction kernel shaders/kernels/scene-statistics.wesl.
 */
export function imageStatistics(
  image: ImageAccumulator,
  reference?: ImageAccumulator,
  mask: Uint8Array | null = null,
): ImageStatistics {
  const values = 3 * image.width * image.height;
  if (reference && reference.meanValues.length !== values)
    throw new Error('the reference has another size');
  const n = image.samples;
  const se = image.standardError();
  const referenceSe = reference?.standardError();
  let radiance = 0;
  let seSum = 0;
  let seSquares = 0;
  let largest = 0;
  let difference = 0;
  let noise = 0;
  let referenceRadiance = 0;
  for (let k = 0; k < values; k++) {
    radiance += image.meanValues[k]!;
    if (n >= 2) {
      seSum += se[k]!;
      seSquares += se[k]! ** 2;
    }
    if (reference && referenceSe) {
      difference += (image.meanValues[k]! - reference.meanValues[k]!) ** 2;
      if (reference.samples >= 2) noise += referenceSe[k]! ** 2;
      referenceRadiance += reference.meanValues[k]!;
    }
  }
  if (n >= 2)
    for (let k = 0; k < values; k += 3)
      largest = Math.max(largest, (se[k]! + se[k + 1]! + se[k + 2]!) / 3);
  let masked = 0;
  let count = 0;
  if (mask)
    for (let i = 0; i < mask.length; i++) {
      if (!mask[i]) continue;
      for (let c = 0; c < 3; c++) masked += LUMA[c]! * image.meanValues[3 * i + c]!;
      count++;
    }
  return finishStatistics(image.width * image.height, n, {
    radiance,
    standardError: seSum,
    standardErrorSq: seSquares,
    maxPixelError: largest,
    maskedLuminance: masked,
    maskCount: count,
    squaredDifference: difference,
    referenceNoise: noise,
    referenceRadiance,
    lookups: image.lookups,
    capped: image.capped,
    hasReference: reference !== undefined,
  });
}

/** The sums of a reduction (GPU or CPU), before they are divided into statistics. */
export interface StatisticsSums {
  radiance: number;
  standardError: number;
  standardErrorSq: number;
  maxPixelError: number;
  maskedLuminance: number;
  maskCount: number;
  squaredDifference: number;
  referenceNoise: number;
  referenceRadiance: number;
  lookups: number;
  capped: number;
  hasReference: boolean;
}

/** Divides a reduction's sums into ImageStatistics (shared by both stores). */
export function finishStatistics(
  pixels: number,
  samples: number,
  sums: StatisticsSums,
): ImageStatistics {
  const values = 3 * pixels;
  const withError = samples >= 2;
  const mse = (sums.squaredDifference - sums.referenceNoise) / values;
  const referenceMean = sums.referenceRadiance / values;
  return {
    samples,
    pixels,
    meanRadiance: sums.radiance / values,
    meanStandardError: withError ? sums.standardError / values : NaN,
    rmsStandardError: withError ? Math.sqrt(sums.standardErrorSq / values) : NaN,
    maxPixelStandardError: withError ? sums.maxPixelError : 0,
    maskedLuminance: sums.maskCount > 0 ? sums.maskedLuminance / sums.maskCount : NaN,
    lookups: sums.lookups,
    capped: sums.capped,
    rmse: sums.hasReference ? Math.sqrt(sums.squaredDifference / values) : NaN,
    relativeError:
      sums.hasReference && mse > 0 && referenceMean > 0 ? Math.sqrt(mse) / referenceMean : NaN,
  };
}
