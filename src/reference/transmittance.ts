// Float64 twin of shaders/transmittance.wesl (physics.md §1). Written from the
// integrals, not from the shader: the smooth profile integrates the cosine
// directly, the grid walks the covered cells by index, and exp needs no
// underflow guard in float64 (it reaches 0 smoothly at τ ≈ 745).

export const GRID1D_MAX_CELLS = 16;

/** Same clamp as the shader: keeps τ finite in f32 without changing any T (τ ≤ 1e36). */
export const FINITE_LIMIT = 1e18;

const clampFinite = (x: number): number => Math.min(Math.max(x, 0), FINITE_LIMIT);

export function transmittanceFromOpticalThickness(tau: number): number {
  return Math.exp(-Math.max(tau, 0));
}

export function opticalThicknessHomogeneous(sigmaT: number, distance: number): number {
  return clampFinite(sigmaT) * clampFinite(distance);
}

export function transmittanceHomogeneous(sigmaT: number, distance: number): number {
  return Math.exp(-opticalThicknessHomogeneous(sigmaT, distance));
}

/** ∫_{s0}^{s1} σ0 (1 + a sin(k s + φ)) ds with a clamped to [0, 1]. */
export function opticalThicknessSine(
  sigma0: number,
  amplitude: number,
  frequency: number,
  phase: number,
  s0: number,
  s1: number,
): number {
  const sigma = clampFinite(sigma0);
  const a = Math.min(Math.max(amplitude, 0), 1);
  if (s1 <= s0) return 0;
  if (frequency <= 0) return sigma * (1 + a * Math.sin(phase)) * clampFinite(s1 - s0);
  const antiderivative = (s: number): number =>
    s - (a / frequency) * Math.cos(frequency * s + phase);
  return Math.max(sigma * (antiderivative(s1) - antiderivative(s0)), 0);
}

/** ∫ of a piecewise-constant profile: cell i covers [i h, (i+1) h). */
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
    if (overlap > 0) tau += Math.max(sigma[i] ?? 0, 0) * overlap;
  }
  return tau;
}
