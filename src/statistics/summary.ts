// Summaries of a sample in float64: mean, unbiased variance and the standard error
// of the mean, shared by the grader's Monte Carlo checks, the widgets and the bench.
// Degenerate input gives NaN, never a made-up number: the mean of nothing, and the
// variance of fewer than two values, are undefined.

export interface Moments {
  n: number;
  /** NaN for an empty sample. */
  mean: number;
  /** Unbiased sample variance Σ(x − mean)²/(n − 1); NaN for n < 2. */
  variance: number;
  /** Standard error of the mean, √(variance/n); NaN for n < 2. */
  standardError: number;
}

/** Arithmetic mean; NaN for an empty sample (and NaN when a value is NaN). */
export function mean(values: ArrayLike<number>): number {
  if (values.length === 0) return NaN;
  let sum = 0;
  for (let i = 0; i < values.length; i++) sum += values[i]!;
  return sum / values.length;
}

/** Mean, unbiased variance (two passes, so no cancellation) and standard error. */
export function moments(values: ArrayLike<number>): Moments {
  const n = values.length;
  const m = mean(values);
  if (n < 2) return { n, mean: m, variance: NaN, standardError: NaN };
  let squares = 0;
  for (let i = 0; i < n; i++) squares += (values[i]! - m) ** 2;
  const variance = squares / (n - 1);
  return { n, mean: m, variance, standardError: Math.sqrt(variance / n) };
}

/** Unbiased sample variance; NaN for fewer than two values. */
export function variance(values: ArrayLike<number>): number {
  return moments(values).variance;
}

/** Standard error of the mean, √(s²/n); NaN for fewer than two values. */
export function standardError(values: ArrayLike<number>): number {
  return moments(values).standardError;
}
