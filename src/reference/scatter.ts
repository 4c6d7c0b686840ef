// Float64 twin of shaders/scatter.wesl (physics.md §5). Written from the
// formulas: the slab closed form as printed in §5 with Math.expm1, the marched
// form from the per-step integral ∫₀^h σs e^{-σt s} ds = α(1 - e^{-σt h}), and the
// equiangular pdf as h/((θb - θa)(h² + t²)) directly (float64 has the range).
import { type Medium1D, mediumExtinction } from './medium.ts';
import { type MarchResult, marchRayOffset, marchStepCount, marchStepOffset } from './raymarch.ts';
import type { RngState } from './rng.ts';
import { F32_MAX, transmittanceHomogeneous } from './transmittance.ts';

// Units do not matter: σ → kσ with lengths → ·/k leaves every transmittance and radiance
// here unchanged (pdfs in 1/m scale by k). No coefficient or length is clamped before a
// product; optical thicknesses are formed in float64 and exp(−τ) needs no cap.

/** Same angle clamp as the shader: the largest f32 below π/2. */
export const EQUIANGULAR_MAX_ANGLE = Math.fround(1.5707962513);
/** The smallest normal f32, 2^-126: a smaller extent h(θb − θa) has an f32-infinite pdf. */
export const EQUIANGULAR_MIN_EXTENT = 2 ** -126;
/** The domain of h and |t| in the equiangular functions (length units). */
export const EQUIANGULAR_MAX_T = 1e36;

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);
const nonNegative = (x: number): number => (x > 0 ? x : 0);

/** e^{−σt(a + b t)}, negative inputs counting as 0. */
export function shadowTransmittanceExact(sigmaT: number, a: number, b: number, t: number): number {
  const sigma = nonNegative(sigmaT);
  if (sigma === 0) return 1;
  return Math.exp(-(sigma * nonNegative(a) + sigma * nonNegative(b) * nonNegative(t)));
}

/** 1 − e^{−x} (negative x counts as 0). */
export function oneMinusExpOfThickness(x: number): number {
  return -Math.expm1(-nonNegative(x));
}

export function singleScatterHomogeneousSlab(
  sigmaS: number,
  sigmaA: number,
  phase: number,
  irradiance: number,
  a: number,
  b: number,
  length: number,
): number {
  const s = nonNegative(sigmaS);
  const sigmaT = s + nonNegative(sigmaA);
  if (sigmaT === 0) return 0;
  const growth = 1 + nonNegative(b);
  // Written as σs/(σt(1+b))·(1 − e^{−σt(1+b)L}): the first factor is a ratio of
  // coefficients and the second depends on the dimensionless σt·L only (float64 has the
  // range for any f32 inputs); p·E is capped at the largest f32, as in the shader.
  const x = sigmaT * growth * nonNegative(length);
  const source = Math.min(nonNegative(phase) * nonNegative(irradiance), F32_MAX);
  return (s / sigmaT / growth) * source * transmittanceHomogeneous(sigmaT, a) * -Math.expm1(-x);
}

export function singleScatterMarched(
  medium: Medium1D,
  albedo: number,
  phase: number,
  irradiance: number,
  a: number,
  b: number,
  length: number,
  steps: number,
  scheme: number,
  state: RngState,
): MarchResult {
  const n = marchStepCount(steps);
  const h = nonNegative(length) / n;
  const scatteringAlbedo = clamp(albedo, 0, 1);
  const lightSource = Math.min(nonNegative(phase) * nonNegative(irradiance), F32_MAX);
  const rayOffset = marchRayOffset(scheme, state);
  let opticalDepth = 0;
  let radiance = 0;
  for (let i = 0; i < n; i++) {
    const t = (i + marchStepOffset(scheme, rayOffset, state)) * h;
    const sigmaT = mediumExtinction(medium, t);
    // ∫ over the step of e^{-σt s} σs ds with σt, σs and the shadow held at t_i.
    const inScattered =
      scatteringAlbedo * -Math.expm1(-sigmaT * h) * shadowTransmittanceExact(sigmaT, a, b, t);
    radiance += Math.exp(-opticalDepth) * inScattered * lightSource;
    opticalDepth += sigmaT * h;
  }
  return { radiance, transmittance: Math.exp(-opticalDepth), steps: n, clampedSteps: 0 };
}

/** [t, pdf] for the equiangular sample ξ (Kulla & Fajardo 2012). */
export function equiangularSample(
  h: number,
  thetaA: number,
  thetaB: number,
  xi: number,
): [number, number] {
  const lo = clamp(thetaA, -EQUIANGULAR_MAX_ANGLE, EQUIANGULAR_MAX_ANGLE);
  const hi = clamp(thetaB, lo, EQUIANGULAR_MAX_ANGLE);
  const theta = lo + clamp(xi, 0, 1) * (hi - lo);
  const t = clamp(h, 0, EQUIANGULAR_MAX_T) * Math.tan(theta);
  return [t, equiangularPdf(h, thetaA, thetaB, t)];
}

export function equiangularPdf(h: number, thetaA: number, thetaB: number, t: number): number {
  const distance = clamp(h, 0, EQUIANGULAR_MAX_T);
  const angle =
    clamp(thetaB, -EQUIANGULAR_MAX_ANGLE, EQUIANGULAR_MAX_ANGLE) -
    clamp(thetaA, -EQUIANGULAR_MAX_ANGLE, EQUIANGULAR_MAX_ANGLE);
  if (distance * angle < EQUIANGULAR_MIN_EXTENT) return 0;
  const along = clamp(t, -EQUIANGULAR_MAX_T, EQUIANGULAR_MAX_T);
  return distance / (angle * (distance * distance + along * along));
}
