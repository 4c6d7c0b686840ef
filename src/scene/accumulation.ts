// Progressive accumulation of a render (GPU or CPU): per pixel and channel the running
// sums of the samples and of their squares (float64 on the host; each pass's partial
// sums come from the kernel in f32), from which the image (the mean, i.e. the box-filtered
// pixel radiance) and the per-pixel standard error sqrt(s²/n) follow.

/** Words per pixel in a pass's output: sums of R, G, B, of their squares, lookups, capped. */
export const PASS_WORDS_PER_PIXEL = 8;

export class ImageAccumulator {
  readonly sum: Float64Array;
  readonly sumSquares: Float64Array;
  samples = 0;
  lookups = 0;
  capped = 0;

  constructor(
    readonly width: number,
    readonly height: number,
  ) {
    this.sum = new Float64Array(3 * width * height);
    this.sumSquares = new Float64Array(3 * width * height);
  }

  /** Adds one pass: `floats`/`words` are the same PASS_WORDS_PER_PIXEL words per pixel. */
  addPass(floats: ArrayLike<number>, words: ArrayLike<number>, samples: number): void {
    const pixels = this.width * this.height;
    for (let i = 0; i < pixels; i++) {
      const o = PASS_WORDS_PER_PIXEL * i;
      for (let c = 0; c < 3; c++) {
        this.sum[3 * i + c]! += floats[o + c]!;
        this.sumSquares[3 * i + c]! += floats[o + 3 + c]!;
      }
      this.lookups += words[o + 6]!;
      this.capped += words[o + 7]!;
    }
    this.samples += samples;
  }

  /** The image: mean radiance per pixel and channel, RGB interleaved, row 0 at the top. */
  mean(): Float64Array {
    const n = Math.max(this.samples, 1);
    return this.sum.map((s) => s / n);
  }

  /**
   * Standard error of each pixel's mean, sqrt(s²/n) with the unbiased sample variance s²;
   * NaN with fewer than two samples (no variance estimate).
   */
  standardError(): Float64Array {
    const n = this.samples;
    if (n < 2) return new Float64Array(this.sum.length).fill(NaN);
    return this.sum.map((s, k) => {
      const mean = s / n;
      const variance = Math.max((this.sumSquares[k]! - n * mean * mean) / (n - 1), 0);
      return Math.sqrt(variance / n);
    });
  }
}
