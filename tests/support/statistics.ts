// Sample statistics for the estimator tests (physics.md §4): mean, unbiased variance
// and the standard error of that variance, and the 5-standard-error checks built on
// them. Each check has two-sided p ≈ 5.7e-7 under the null hypothesis, so a file's
// few dozen checks stay far below α = 0.01 together (Bonferroni).
import { expect } from 'vitest';

export interface Moments {
  n: number;
  mean: number;
  /** Unbiased sample variance. */
  variance: number;
  /** Standard error of the sample variance: SE² = (μ4 − σ⁴(N−3)/(N−1))/N. */
  varianceError: number;
  min: number;
  max: number;
}

export function moments(values: readonly number[]): Moments {
  const n = values.length;
  let sum = 0;
  let min = Infinity;
  let max = -Infinity;
  for (const x of values) {
    sum += x;
    min = Math.min(min, x);
    max = Math.max(max, x);
  }
  const mean = sum / n;
  let m2 = 0;
  let m4 = 0;
  for (const x of values) {
    const d2 = (x - mean) ** 2;
    m2 += d2;
    m4 += d2 * d2;
  }
  const variance = m2 / (n - 1);
  m4 /= n;
  const varianceError = Math.sqrt(Math.max(m4 - (variance * variance * (n - 3)) / (n - 1), 0) / n);
  return { n, mean, variance, varianceError, min, max };
}

/**
 * |mean − exact| < 5·sqrt(Var/N) + systematic: Var is the predicted variance where
 * one is known (the sample variance otherwise); `systematic` is an f32 allowance
 * that the caller states.
 */
export function expectMean(m: Moments, exact: number, variance = m.variance, systematic = 0): void {
  const bound = 5 * Math.sqrt(variance / m.n) + systematic;
  expect(Math.abs(m.mean - exact), `mean ${m.mean} vs ${exact} (bound ${bound})`).toBeLessThan(
    bound,
  );
}

/** |sample variance − predicted| < 5·SE of the sample variance. */
export function expectVariance(m: Moments, predicted: number): void {
  const bound = 5 * m.varianceError;
  expect(
    Math.abs(m.variance - predicted),
    `variance ${m.variance} vs ${predicted} (5 SE = ${bound})`,
  ).toBeLessThan(bound);
}
