// The statistics the grader needs, in float64: Pearson's chi-square test against
// equiprobable bins, z-tests, and the distributions' quantiles (regularised incomplete
// gamma by series / continued fraction, Numerical Recipes 3rd ed. §6.2; the normal
// tail by erfc, §6.2.2), plus a small seeded generator for the stratification jitter.

const LOG_GAMMA_COEFFICIENTS = [
  57.15623566586292, -59.59796035547549, 14.136097974741746, -0.4919138160976202,
  3.399464998481189e-5, 4.652362892704858e-5, -9.837447530487956e-5, 0.0001580887032249125,
  -0.00021026444172410488, 0.00021743961811521265, -0.0001643181065367639, 8.441822398385275e-5,
  -2.6190838401581408e-5, 3.6899182659531625e-6,
];

/** ln Γ(x) for x > 0 (Lanczos, Numerical Recipes 3rd ed. §6.1, |error| < 1e-15). */
export function logGamma(x: number): number {
  let y = x;
  const tmp = x + 5.2421875;
  const t = (x + 0.5) * Math.log(tmp) - tmp;
  let ser = 0.9999999999999971;
  for (const c of LOG_GAMMA_COEFFICIENTS) ser += c / ++y;
  return t + Math.log((2.5066282746310007 * ser) / x);
}

/** Regularised upper incomplete gamma Q(a, x) = Γ(a, x)/Γ(a). */
export function gammaQ(a: number, x: number): number {
  if (x <= 0) return 1;
  const gln = logGamma(a);
  if (x < a + 1) {
    // Series for P(a, x).
    let sum = 1 / a;
    let del = sum;
    let ap = a;
    for (let n = 0; n < 1000; n++) {
      ap += 1;
      del *= x / ap;
      sum += del;
      if (Math.abs(del) < Math.abs(sum) * 1e-16) break;
    }
    return 1 - sum * Math.exp(-x + a * Math.log(x) - gln);
  }
  // Continued fraction for Q(a, x) (modified Lentz).
  const tiny = 1e-300;
  let b = x + 1 - a;
  let c = 1 / tiny;
  let d = 1 / b;
  let h = d;
  for (let i = 1; i < 1000; i++) {
    const an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (Math.abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (Math.abs(c) < tiny) c = tiny;
    d = 1 / d;
    const del = d * c;
    h *= del;
    if (Math.abs(del - 1) < 1e-16) break;
  }
  return Math.exp(-x + a * Math.log(x) - gln) * h;
}

/** P(χ²_k > x). */
export function chiSquareSurvival(x: number, k: number): number {
  return gammaQ(k / 2, x / 2);
}

/** The x with P(χ²_k > x) = alpha, by bisection (monotone survival function). */
export function chiSquareCritical(alpha: number, k: number): number {
  let lo = 0;
  let hi = k + 20 * Math.sqrt(2 * k) + 100;
  for (let i = 0; i < 200; i++) {
    const mid = 0.5 * (lo + hi);
    if (chiSquareSurvival(mid, k) > alpha) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

/** erfc(x) (Numerical Recipes 2nd ed. §6.2 Chebyshev fit, relative error < 1.2e-07). */
export function erfc(x: number): number {
  const z = Math.abs(x);
  const t = 1 / (1 + 0.5 * z);
  const r =
    t *
    Math.exp(
      -z * z -
        1.26551223 +
        t *
          (1.00002368 +
            t *
              (0.37409196 +
                t *
                  (0.09678418 +
                    t *
                      (-0.18628806 +
                        t *
                          (0.27886807 +
                            t *
                              (-1.13520398 +
                                t * (1.48851587 + t * (-0.82215223 + t * 0.17087277)))))))),
    );
  return x >= 0 ? r : 2 - r;
}

/** P(|Z| > z) for a standard normal Z. */
export function twoSidedNormalTail(z: number): number {
  return erfc(Math.abs(z) / Math.SQRT2);
}

/** The z with P(|Z| > z) = alpha. */
export function normalCritical(alpha: number): number {
  let lo = 0;
  let hi = 40;
  for (let i = 0; i < 200; i++) {
    const mid = 0.5 * (lo + hi);
    if (twoSidedNormalTail(mid) > alpha) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

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

export function sampleMoments(values: readonly number[]): Moments {
  const n = values.length;
  let mean = 0;
  for (const v of values) mean += v;
  mean /= n;
  let squares = 0;
  for (const v of values) squares += (v - mean) * (v - mean);
  return { n, mean, variance: n > 1 ? squares / (n - 1) : 0 };
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
