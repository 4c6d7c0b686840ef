// The peers bench's agreement statistic (bench/peerStatistics.ts): the standard error of an
// RGB image's mean, with the channels' errors added as fully correlated.
import { describe, expect, it } from 'vitest';
import { imageMeanStandardError } from '../../bench/peerStatistics.ts';

describe('imageMeanStandardError', () => {
  it('a gray image (equal channels): the standard error of one channel’s mean, not √3 less', () => {
    // Four pixels of variance 1 in every channel: √4 / 4 = 0.5. Treating the 12 values as
    // independent would give √12 / 12 ≈ 0.29.
    expect(imageMeanStandardError(new Array(12).fill(1))).toBeCloseTo(0.5, 15);
  });

  it('channels of different variance: the mean of the channels’ standard errors', () => {
    // Two pixels; channel variances (1, 4, 9) per pixel: per channel √(2v)/2.
    const v = [1, 4, 9, 1, 4, 9];
    const expected = (Math.sqrt(2) / 2 + Math.sqrt(8) / 2 + Math.sqrt(18) / 2) / 3;
    expect(imageMeanStandardError(v)).toBeCloseTo(expected, 15);
  });

  it('matches the spread of simulated gray image means (fixed seed)', () => {
    // 400 images of 64 gray pixels with per-pixel standard deviation 0.1..0.8: the sample
    // standard deviation of their means agrees with the formula within its own error
    // (about 1/√(2·399) ≈ 3.5 % relative; the bound is 5 standard errors of that).
    let seed = 12345;
    const uniform = () => ((seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0) + 0.5) / 2 ** 32;
    const normal = () => Math.sqrt(-2 * Math.log(uniform())) * Math.cos(2 * Math.PI * uniform());
    const sd = Array.from({ length: 64 }, (_, p) => 0.1 + (0.7 * p) / 63);
    const means = Array.from({ length: 400 }, () => {
      let sum = 0;
      for (const s of sd) sum += 3 * s * normal(); // three equal channels
      return sum / (3 * sd.length);
    });
    const m = means.reduce((a, b) => a + b, 0) / means.length;
    const spread = Math.sqrt(means.reduce((a, b) => a + (b - m) ** 2, 0) / (means.length - 1));
    const predicted = imageMeanStandardError(sd.flatMap((s) => [s * s, s * s, s * s]));
    expect(Math.abs(spread / predicted - 1)).toBeLessThan(5 / Math.sqrt(2 * 399));
  });

  it('an image without pixels has no standard error', () => {
    expect(imageMeanStandardError([])).toBeNaN();
  });
});
