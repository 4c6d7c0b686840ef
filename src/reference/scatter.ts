// Float64 twin of shaders/scatter.wesl (physics.md §5). Written from the
// formulas: the slab closed form as printed in §5 with Math.expm1, the marched
// form from the per-step integral ∫₀^h σs e^{-σt s} ds = α(1 - e^{-σt h}), and the
// equiangular pdf as h/((θb - θa)(h² + t²)) directly (float64 has the range).
import { type Medium1D, mediumExtinction } from './medium.ts';
import { type MarchResult, marchRayOffset, marchStepCount, marchStepOffset } from './raymarch.ts';
import type { RngState } from './rng.ts';
import { FINITE_LIMIT, transmittanceHomogeneous } from './transmittance.ts';

/** Same angle clamp as the shader: the largest f32 below π/2. */
export const EQUIANGULAR_MAX_ANGLE = Math.fround(1.5707962513);
export const EQUIANGULAR_MIN_EXTENT = 1e-30;
export const EQUIANGULAR_MAX_T = 1e36;

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);

export function shadowTransmittanceExact(sigmaT: number, a: number, b: number, t: number): number {
  const lightPath =
    clamp(a, 0, FINITE_LIMIT) + clamp(b, 0, FINITE_LIMIT) * clamp(t, 0, FINITE_LIMIT);
  return transmittanceHomogeneous(sigmaT, lightPath);
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
  const s = clamp(sigmaS, 0, FINITE_LIMIT);
  const sigmaT = s + clamp(sigmaA, 0, FINITE_LIMIT);
  if (sigmaT === 0) return 0;
  const growth = 1 + clamp(b, 0, FINITE_LIMIT);
  // x is capped as in the shader (the cap never changes e^{-x} = 0 beyond it).
  const x = Math.min(sigmaT * growth, FINITE_LIMIT) * clamp(length, 0, FINITE_LIMIT);
  return (
    (s *
      clamp(phase, 0, FINITE_LIMIT) *
      clamp(irradiance, 0, FINITE_LIMIT) *
      transmittanceHomogeneous(sigmaT, a) *
      -Math.expm1(-x)) /
    (sigmaT * growth)
  );
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
  const h = clamp(length, 0, FINITE_LIMIT) / n;
  const scatteringAlbedo = clamp(albedo, 0, 1);
  const lightSource = clamp(phase, 0, FINITE_LIMIT) * clamp(irradiance, 0, FINITE_LIMIT);
  const rayOffset = marchRayOffset(scheme, state);
  let opticalDepth = 0;
  let radiance = 0;
  for (let i = 0; i < n; i++) {
    const t = (i + marchStepOffset(scheme, rayOffset, state)) * h;
    const sigmaT = Math.min(mediumExtinction(medium, t), FINITE_LIMIT);
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
  const t = clamp(h, 0, FINITE_LIMIT) * Math.tan(theta);
  return [t, equiangularPdf(h, thetaA, thetaB, t)];
}

export function equiangularPdf(h: number, thetaA: number, thetaB: number, t: number): number {
  const distance = clamp(h, 0, FINITE_LIMIT);
  const angle =
    clamp(thetaB, -EQUIANGULAR_MAX_ANGLE, EQUIANGULAR_MAX_ANGLE) -
    clamp(thetaA, -EQUIANGULAR_MAX_ANGLE, EQUIANGULAR_MAX_ANGLE);
  if (distance * angle < EQUIANGULAR_MIN_EXTENT) return 0;
  const along = clamp(t, -EQUIANGULAR_MAX_T, EQUIANGULAR_MAX_T);
  return distance / (angle * (distance * distance + along * along));
}
