// The error readouts of <sb-translucent-render> against a young, noisy path-traced reference:
// errorAgainstNoisyReference subtracts the reference's noise variance from the MSE
// (E[(a − r̂)²] = (a − r)² + Var r̂). A synthetic reference whose samples are mostly 0 and
// occasionally large (like path-traced walks) is built from a fixed PCG stream, with the mean
// and standard error computed as PathAccumulator does; bounds come from the estimator's spread.
import { describe, expect, it } from 'vitest';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { errorAgainstNoisyReference } from '../../src/widgets/translucent-render/model.ts';

const PIXELS = 3000;
/** Each sample is r/q with probability q, else 0: mean r, variance r²(1/q − 1). */
const HIT = 0.3;

interface Synthetic {
  truth: Float64Array;
  image: Float64Array;
  mean: Float64Array;
  se: Float64Array;
  mask: Uint8Array;
  trueRelativeRmse: number;
}

/** A true image, an image off by a known ±`offset` pattern, and an n-sample reference of the truth. */
function synthetic(samples: number, offset: number, seed: number): Synthetic {
  const truth = new Float64Array(3 * PIXELS);
  const image = new Float64Array(3 * PIXELS);
  const mean = new Float64Array(3 * PIXELS);
  const se = new Float64Array(3 * PIXELS);
  let squares = 0;
  let sum = 0;
  for (let k = 0; k < 3 * PIXELS; k++) {
    const r = 0.5 + 0.3 * Math.sin(0.37 * k);
    truth[k] = r;
    image[k] = r * (1 + offset * (k % 2 === 0 ? 1 : -1));
    squares += (image[k]! - r) ** 2;
    sum += r;
    const state = { value: rngSeed(k, seed) };
    let s1 = 0;
    let s2 = 0;
    for (let i = 0; i < samples; i++) {
      const x = rngNextFloat(state) < HIT ? r / HIT : 0;
      s1 += x;
      s2 += x * x;
    }
    // As PathAccumulator.mean and .standardError: s² with n − 1, SE = s/√n.
    const m = s1 / samples;
    mean[k] = m;
    se[k] =
      samples < 2
        ? NaN
        : Math.sqrt((Math.max(0, s2 / samples - m * m) * (samples / (samples - 1))) / samples);
  }
  const mask = new Uint8Array(PIXELS).fill(1);
  const trueRelativeRmse = Math.sqrt(squares / (3 * PIXELS)) / (sum / (3 * PIXELS));
  return { truth, image, mean, se, mask, trueRelativeRmse };
}

describe('errorAgainstNoisyReference', () => {
  it('recovers the true error from a 3-sample reference whose noise is twice the error', () => {
    const s = synthetic(3, 0.4, 1);
    const e = errorAgainstNoisyReference(s.image, s.mean, s.se, s.mask);
    // Relative SE of one value is √((1/q − 1)/3) ≈ 0.88; the RMS over the image is near that.
    expect(e.referenceNoise).toBeGreaterThan(0.6);
    expect(e.referenceNoise).toBeLessThan(1.1);
    // The plain RMSE is dominated by the noise: more than twice the true ~43 %.
    expect(s.trueRelativeRmse).toBeGreaterThan(0.4);
    expect(e.rawRelativeRmse).toBeGreaterThan(2 * s.trueRelativeRmse);
    // Over 200 other seeds the estimate averaged 0.433 (true 0.4345) with a standard deviation
    // of 0.028; 0.12 is over 4 of them.
    expect(Math.abs(e.relativeRmse - s.trueRelativeRmse)).toBeLessThan(0.12);
    expect(e.belowNoise).toBe(false);
  });

  it('shows almost no error for the true image itself, where the plain RMSE shows the noise', () => {
    const s = synthetic(3, 0, 2);
    const e = errorAgainstNoisyReference(s.truth, s.mean, s.se, s.mask);
    expect(e.rawRelativeRmse).toBeGreaterThan(0.6);
    // The subtracted MSE estimate has a standard deviation of about 0.018 (relative², from 200
    // seeds; it is clamped at 0 half the time); 0.3² = 0.09 is about 5 of them.
    expect(e.relativeRmse).toBeLessThan(0.3);
    expect(e.relativeRmse).toBeLessThan(e.rawRelativeRmse / 3);
  });

  it('agrees with the plain RMSE once the reference is converged', () => {
    const s = synthetic(400, 0.4, 3);
    const e = errorAgainstNoisyReference(s.image, s.mean, s.se, s.mask);
    expect(e.referenceNoise).toBeLessThan(0.1);
    expect(e.relativeRmse).toBeLessThan(e.rawRelativeRmse);
    expect(Math.abs(e.relativeRmse - s.trueRelativeRmse)).toBeLessThan(0.03);
    expect(Math.abs(e.meanError)).toBeLessThan(0.03);
  });

  it('counts values without a standard error (one sample) as noise-free', () => {
    const s = synthetic(1, 0.4, 4);
    const e = errorAgainstNoisyReference(s.image, s.mean, s.se, s.mask);
    expect(e.referenceNoise).toBe(0);
    expect(e.relativeRmse).toBe(e.rawRelativeRmse);
  });

  it('returns NaN when no pixel is inside the mask', () => {
    const s = synthetic(3, 0.4, 5);
    const e = errorAgainstNoisyReference(s.image, s.mean, s.se, new Uint8Array(PIXELS));
    expect(e.relativeRmse).toBeNaN();
    expect(e.belowNoise).toBe(false);
  });
});
