// The statistics the grader needs, in float64: Pearson's chi-square test against
// equiprobable bins and z-tests (the distributions' tails and quantiles are in
// src/statistics/distributions.ts), plus a small seeded generator for the
// stratification jitter.

import { chiSquareCritical, chiSquareSurvival } from '../statistics/distributions.ts';
import { moments } from '../statistics/summary.ts';

export interface ChiSquareResult {
  statistic: number;
  critical: number;
  degreesOfFreedom: number;
  pValue: number;
  observed: number[];
  expected: number[];
}

/**
 * Pearson's chi-square of `values` against `bins` equiprobable bins of the CDF
 * (bin j holds cdf(x) ∈ [j/bins, (j+1)/bins)); bins − 1 degrees of freedom.
 */
export function chiSquareEquiprobable(
  values: readonly number[],
  cdf: (x: number) => number,
  bins: number,
  alpha: number,
): ChiSquareResult {
  const observed = new Array<number>(bins).fill(0);
  for (const value of values) {
    const p = cdf(value);
    const bin = Math.min(bins - 1, Math.max(0, Math.floor(p * bins)));
    observed[bin] = (observed[bin] ?? 0) + 1;
  }
  const each = values.length / bins;
  const expected = new Array<number>(bins).fill(each);
  const statistic = observed.reduce((sum, o) => sum + ((o - each) * (o - each)) / each, 0);
  const degreesOfFreedom = bins - 1;
  return {
    statistic,
    critical: chiSquareCritical(alpha, degreesOfFreedom),
    degreesOfFreedom,
    pValue: chiSquareSurvival(statistic, degreesOfFreedom),
    observed,
    expected,
  };
}

export interface Moments {
  n: number;
  mean: number;
  /** Unbiased sample variance. */
  variance: number;
}

/**
 * Mean and unbiased variance (src/statistics/summary.ts). A single value's variance
 * is taken as 0 here, not NaN: the checks draw thousands of values, and a variance
 * check of one value then fails on its z rather than on a NaN.
 */
export function sampleMoments(values: readonly number[]): Moments {
  const { n, mean, variance } = moments(values);
  return { n, mean, variance: n > 1 ? variance : 0 };
}

/**
 * z of the sample mean of n Bernoulli(T) draws against T: (m − T)/√(T(1 − T)/n).
 * Exact variance, so under the null z is asymptotically standard normal.
 */
export function bernoulliMeanZ(m: Moments, expected: number): number {
  const sd = Math.sqrt((expected * (1 - expected)) / m.n);
  return ratioZ(m.mean - expected, sd);
}

/**
 * z of the sample variance s² against T(1 − T). By the delta method
 * Var(s²) ≈ (μ₄ − σ⁴)/n, and for a Bernoulli(T) variable μ₄ − σ⁴ = T(1 − T)(1 − 2T)².
 * That vanishes at T = ½ (s² = m(1 − m) is then flat in m), so the checks use T away
 * from ½; a floor of T(1 − T)/n² keeps the division finite.
 */
export function bernoulliVarianceZ(m: Moments, expected: number): number {
  const pq = expected * (1 - expected);
  const sd = Math.sqrt((pq * (1 - 2 * expected) ** 2) / m.n + pq / (m.n * m.n));
  return ratioZ(m.variance - pq, sd);
}

/**
 * difference/sd, where a zero sd (T = 0 or 1: the estimator must be exactly
 * constant) makes any difference infinitely significant and none insignificant.
 */
function ratioZ(difference: number, sd: number): number {
  if (sd > 0) return difference / sd;
  return difference === 0 ? 0 : difference > 0 ? Infinity : -Infinity;
}

/** SplitMix32-style generator: deterministic uniforms in [0, 1) from a seed. */
export function seededUniforms(seed: number): () => number {
  let state = seed >>> 0;
  return () => {
    state = (state + 0x9e3779b9) >>> 0;
    let z = state;
    z = Math.imul(z ^ (z >>> 16), 0x85ebca6b) >>> 0;
    z = Math.imul(z ^ (z >>> 13), 0xc2b2ae35) >>> 0;
    z = (z ^ (z >>> 16)) >>> 0;
    return z / 4294967296;
  };
}

/** A 32-bit mix of two words, for deriving per-check seeds. */
export function mixSeed(a: number, b: number): number {
  let z = (Math.imul(a >>> 0, 0x9e3779b1) ^ (b >>> 0)) >>> 0;
  z = Math.imul(z ^ (z >>> 15), 0x85ebca6b) >>> 0;
  z = Math.imul(z ^ (z >>> 13), 0xc2b2ae35) >>> 0;
  return (z ^ (z >>> 16)) >>> 0;
}
