// The one statistics module (src/statistics/): exact answers on small data, a known
// slope recovered, and degenerate input (empty, one value, all x equal, NaN, zero
// errors) answered with NaN or null rather than a made-up number.
import { describe, expect, it } from 'vitest';
import { maxAbsoluteError, relativeRmse, rmse } from '../../src/statistics/errors.ts';
import { fitLine, logLogSlope } from '../../src/statistics/regression.ts';
import { mean, moments, standardError, variance } from '../../src/statistics/summary.ts';

describe('summary', () => {
  it('mean, unbiased variance and standard error of a small sample', () => {
    // 2, 4, 4, 4, 5, 5, 7, 9: mean 5, Σ(x − 5)² = 32, s² = 32/7.
    const values = [2, 4, 4, 4, 5, 5, 7, 9];
    expect(mean(values)).toBe(5);
    expect(variance(values)).toBeCloseTo(32 / 7, 14);
    expect(standardError(values)).toBeCloseTo(Math.sqrt(32 / 7 / 8), 14);
    expect(moments(new Float32Array(values)).n).toBe(8);
  });

  it('keeps precision for a large offset (two passes, no cancellation)', () => {
    expect(variance([1e9 + 1, 1e9 + 2, 1e9 + 3])).toBe(1);
  });

  it('degenerate samples give NaN', () => {
    expect(mean([])).toBeNaN();
    expect(moments([])).toEqual({ n: 0, mean: NaN, variance: NaN, standardError: NaN });
    expect(moments([3])).toEqual({ n: 1, mean: 3, variance: NaN, standardError: NaN });
    expect(mean([1, NaN, 3])).toBeNaN();
  });
});

describe('errors', () => {
  it('rmse, relative rmse and largest error on small data', () => {
    // Differences 1, −1, 3, −3: squares 1, 1, 9, 9, mean 5.
    const reference = [1, 2, 3, 4];
    const estimate = [2, 1, 6, 1];
    expect(rmse(estimate, reference)).toBeCloseTo(Math.sqrt(5), 14);
    expect(relativeRmse(estimate, reference)).toBeCloseTo(Math.sqrt(5) / 2.5, 14);
    expect(maxAbsoluteError(estimate, reference)).toBe(3);
    expect(rmse(reference, reference)).toBe(0);
  });

  it('degenerate input: empty is NaN, a dark reference has no relative error, lengths must agree', () => {
    expect(rmse([], [])).toBeNaN();
    expect(relativeRmse([], [])).toBeNaN();
    expect(maxAbsoluteError([], [])).toBeNaN();
    expect(relativeRmse([1, 1], [0, 0])).toBeNaN();
    expect(rmse([1, NaN], [1, 1])).toBeNaN();
    expect(() => rmse([1, 2, 3], [1, 2])).toThrow(RangeError);
  });
});

describe('regression', () => {
  it('recovers an exact line', () => {
    const x = [0, 1, 2, 3, 4];
    const fit = fitLine(
      x,
      x.map((v) => 3 - 2 * v),
    );
    expect(fit?.slope).toBeCloseTo(-2, 14);
    expect(fit?.intercept).toBeCloseTo(3, 14);
    expect(fit?.n).toBe(5);
  });

  it('least squares of noisy points: the closed form on a hand-worked case', () => {
    // x = 0, 1, 2; y = 1, 3, 2: x̄ = 1, ȳ = 2, Sxy = (−1)(−1) + 0 + (1)(0) = 1, Sxx = 2.
    expect(fitLine([0, 1, 2], [1, 3, 2])).toEqual({ slope: 0.5, intercept: 1.5, n: 3 });
  });

  it('recovers the Monte Carlo slope −½ on a log–log plot', () => {
    const n = [1, 2, 4, 8, 16, 32, 64, 128, 256];
    const errors = n.map((k) => 0.3 / Math.sqrt(k));
    expect(logLogSlope(n, errors)).toBeCloseTo(-0.5, 12);
  });

  it('leaves out zero errors and non-finite values', () => {
    const n = [1, 2, 4, 8];
    expect(logLogSlope(n, [1, 0.25, 0, 1 / 64])).toBeCloseTo(-2, 12);
    expect(fitLine([0, 1, NaN, 2], [0, 1, 5, 2])?.slope).toBeCloseTo(1, 14);
  });

  it('degenerate input gives null', () => {
    expect(fitLine([], [])).toBeNull();
    expect(fitLine([1], [2])).toBeNull();
    expect(fitLine([2, 2, 2], [1, 2, 3])).toBeNull();
    expect(fitLine([NaN, NaN], [1, 2])).toBeNull();
    expect(logLogSlope([4, 4], [1, 2])).toBeNull();
    expect(logLogSlope([1, 2], [0, 0])).toBeNull();
  });
});
