// Distribution functions in float64 shared by the grader (src/grading/stats.ts), the
// hg-lobe widget's chi-square test and the tests: ln Γ, the regularised incomplete gamma
// (series / continued fraction, Numerical Recipes 3rd ed. §6.1–6.2) and with it the
// chi-square tail and its quantile; erfc (Numerical Recipes 2nd ed. §6.2) and with it
// the two-sided normal tail and its quantile.

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
    return Math.max(0, 1 - sum * Math.exp(-x + a * Math.log(x) - gln));
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

/**
 * P(χ'²_k(λ) > x), the noncentral chi-square tail, as the Poisson(λ/2) mixture of
 * central tails Σ_j e^{−λ/2}(λ/2)^j/j! · Q(x; k + 2j) (Johnson, Kotz & Balakrishnan,
 * Continuous Univariate Distributions vol. 2, §29.4): the power of a χ² test whose
 * alternative has noncentrality λ.
 */
export function noncentralChiSquareSurvival(x: number, k: number, lambda: number): number {
  if (lambda <= 0) return chiSquareSurvival(x, k);
  const half = lambda / 2;
  // Sum outwards from the Poisson mode so the terms that matter come first.
  const mode = Math.floor(half);
  const logWeight = (j: number): number => -half + j * Math.log(half) - logGamma(j + 1);
  let sum = 0;
  for (let j = mode; j >= 0; j--) {
    const w = Math.exp(logWeight(j));
    sum += w * chiSquareSurvival(x, k + 2 * j);
    if (w < 1e-18 && j < mode) break;
  }
  for (let j = mode + 1; ; j++) {
    const w = Math.exp(logWeight(j));
    sum += w * chiSquareSurvival(x, k + 2 * j);
    if (w < 1e-18) break;
  }
  return Math.min(1, sum);
}

/**
 * Kolmogorov's limiting tail P(√n·D_n > x) = 2 Σ_{k≥1} (−1)^{k−1} e^{−2k²x²} for the
 * one-sample Kolmogorov–Smirnov statistic D_n of a continuous distribution.
 */
export function kolmogorovSurvival(x: number): number {
  if (x <= 0) return 1;
  if (x < 0.2) return 1;
  let sum = 0;
  for (let k = 1; k <= 100; k++) {
    const term = Math.exp(-2 * k * k * x * x);
    sum += (k % 2 === 1 ? 1 : -1) * term;
    if (term < 1e-17) break;
  }
  return Math.min(1, Math.max(0, 2 * sum));
}

/**
 * The KS statistic scaled for sample size n with Stephens' correction,
 * (√n + 0.12 + 0.11/√n)·D, whose tail is kolmogorovSurvival to within 1 % for n ≥ 5
 * (Stephens 1970, J. R. Stat. Soc. B 32, table 1; D'Agostino & Stephens 1986 §4.4).
 */
export function kolmogorovScaled(d: number, n: number): number {
  const root = Math.sqrt(n);
  return (root + 0.12 + 0.11 / root) * d;
}

/** The x with kolmogorovSurvival(x) = alpha (monotone; bisection). */
export function kolmogorovCritical(alpha: number): number {
  let lo = 0.2;
  let hi = 10;
  for (let i = 0; i < 200; i++) {
    const mid = 0.5 * (lo + hi);
    if (kolmogorovSurvival(mid) > alpha) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

/** Φ(z), the standard normal CDF. */
export function normalCdf(z: number): number {
  return 0.5 * erfc(-z / Math.SQRT2);
}
