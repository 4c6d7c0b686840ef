// Float64 twin of shaders/transmittance.wesl (physics.md §1). Written from the
// integrals, not from the shader: the smooth profile integrates the cosine
// directly, the grid walks the covered cells by index, and exp needs no
// underflow guard in float64 (it reaches 0 smoothly at τ ≈ 745).
//
// Units do not matter (σ → kσ, lengths → ·/k leave τ and T unchanged), so no coefficient
// or length is clamped on its own; float64 forms σ·d exactly enough for any f32 inputs, and
// the result is then capped at the largest finite f32, the shader's saturation value.

export const GRID1D_MAX_CELLS = 16;

/** The largest finite f32; the shader's products and sums saturate here (WGSL assumes no Inf). */
export const F32_MAX = 3.4028234663852886e38;

/**
 * The shader's bound on coordinates (ray parameters, grid bounds) in other modules. It is
 * never applied to a coefficient or a length before a product.
 */
export const FINITE_LIMIT = 1e18;

/** Non-negative part; NaN counts as 0 like a negative value. */
const nonNegative = (x: number): number => (x > 0 ? x : 0);

/** x·y of non-negative factors (negative ones count as 0), capped at F32_MAX; 0·∞ is 0. */
export function saturatingProduct(x: number, y: number): number {
  const a = nonNegative(x);
  const b = nonNegative(y);
  if (a === 0 || b === 0) return 0;
  return Math.min(a * b, F32_MAX);
}

/** x + y of non-negative terms, capped at F32_MAX. */
export function saturatingSum(x: number, y: number): number {
  return Math.min(nonNegative(x) + nonNegative(y), F32_MAX);
}

/** x/y of a non-negative x (negative counts as 0), capped at F32_MAX; 0/0 is 0, x/0 is F32_MAX. */
export function saturatingQuotient(x: number, y: number): number {
  const a = nonNegative(x);
  if (a === 0) return 0;
  if (!(y > 0)) return F32_MAX;
  return Math.min(a / y, F32_MAX);
}

/** s1 − s0 when positive, else 0, capped at F32_MAX. */
export function segmentLength(s0: number, s1: number): number {
  return s1 > s0 ? Math.min(s1 - s0, F32_MAX) : 0;
}

export function transmittanceFromOpticalThickness(tau: number): number {
  return Math.exp(-Math.max(tau, 0));
}

/** τ = σt·d; a negative factor is no medium (τ = 0); capped at F32_MAX. */
export function opticalThicknessHomogeneous(sigmaT: number, distance: number): number {
  return saturatingProduct(sigmaT, distance);
}

export function transmittanceHomogeneous(sigmaT: number, distance: number): number {
  return Math.exp(-opticalThicknessHomogeneous(sigmaT, distance));
}

/** ∫_{s0}^{s1} σ0 (1 + a sin(k s + φ)) ds with a clamped to [0, 1], capped at F32_MAX. */
export function opticalThicknessSine(
  sigma0: number,
  amplitude: number,
  frequency: number,
  phase: number,
  s0: number,
  s1: number,
): number {
  const sigma = nonNegative(sigma0);
  const a = Math.min(Math.max(amplitude, 0), 1);
  if (!(s1 > s0) || sigma === 0) return 0;
  if (frequency <= 0) return saturatingProduct(sigma * (1 + a * Math.sin(phase)), s1 - s0);
  // The antiderivative in units of the phase: u = k s, ∫ = (1/k)[u − a cos(u + φ)], so the
  // integral is σ0/k times a dimensionless difference (scale-free for any k).
  const dimensionless =
    frequency * (s1 - s0) -
    a * (Math.cos(frequency * s1 + phase) - Math.cos(frequency * s0 + phase));
  return saturatingProduct(sigma, dimensionless / frequency);
}

/** ∫ of a piecewise-constant profile: cell i covers [i h, (i+1) h); capped at F32_MAX. */
export function opticalThicknessGrid1D(
  sigma: readonly number[],
  cellCount: number,
  cellSize: number,
  s0: number,
  s1: number,
): number {
  const count = Math.min(cellCount, GRID1D_MAX_CELLS, sigma.length);
  if (cellSize <= 0 || s1 <= s0 || count <= 0) return 0;
  const first = Math.max(0, Math.floor(s0 / cellSize));
  const last = Math.min(count - 1, Math.floor(s1 / cellSize));
  let tau = 0;
  for (let i = first; i <= last; i++) {
    const overlap = Math.min(s1, (i + 1) * cellSize) - Math.max(s0, i * cellSize);
    if (overlap > 0) tau += nonNegative(sigma[i] ?? 0) * overlap;
  }
  return Math.min(tau, F32_MAX);
}
