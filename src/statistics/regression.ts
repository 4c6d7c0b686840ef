// Least-squares straight lines in float64, and the log–log slope the convergence
// sweeps report (error ∝ n^slope: −½ for Monte Carlo, −1 or −2 for quadrature).

export interface LineFit {
  slope: number;
  intercept: number;
  /** Points used (finite x and y). */
  n: number;
}

/**
 * Ordinary least squares y ≈ intercept + slope·x in closed form: with the means x̄, ȳ,
 * slope = Σ(x − x̄)(y − ȳ) / Σ(x − x̄)² and intercept = ȳ − slope·x̄ (centring first
 * avoids the cancellation of the textbook Σxy − n·x̄ȳ form). Pairs with a non-finite
 * x or y are left out. null when fewer than two points remain or all their x are
 * equal (the slope is then undefined).
 */
export function fitLine(x: ArrayLike<number>, y: ArrayLike<number>): LineFit | null {
  const xs: number[] = [];
  const ys: number[] = [];
  const length = Math.min(x.length, y.length);
  for (let i = 0; i < length; i++) {
    if (Number.isFinite(x[i]) && Number.isFinite(y[i])) {
      xs.push(x[i]!);
      ys.push(y[i]!);
    }
  }
  const n = xs.length;
  if (n < 2) return null;
  const meanX = xs.reduce((s, v) => s + v, 0) / n;
  const meanY = ys.reduce((s, v) => s + v, 0) / n;
  let sxy = 0;
  let sxx = 0;
  for (let i = 0; i < n; i++) {
    sxy += (xs[i]! - meanX) * (ys[i]! - meanY);
    sxx += (xs[i]! - meanX) ** 2;
  }
  if (!(sxx > 0)) return null;
  const slope = sxy / sxx;
  return { slope, intercept: meanY - slope * meanX, n };
}

/**
 * Least-squares slope of log y against log x, so y ∝ x^slope. Points where either
 * logarithm is not finite (a zero error, a non-positive or NaN value) are left out;
 * null with fewer than two usable points or when all usable x are equal.
 */
export function logLogSlope(x: readonly number[], y: readonly number[]): number | null {
  return fitLine(x.map(Math.log), y.map(Math.log))?.slope ?? null;
}
