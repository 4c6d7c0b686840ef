// Float64 twin of shaders/raymarch.wesl (physics.md §1.1, §3, §5). Written from
// the integrals: the sample positions of a march are drawn first (consuming the
// PCG stream in the shader's order: one ξ per ray, or one per step), then each
// step contributes the exact integral of a constant source over a constant-σt
// segment, ∫₀^h σa e^{-σt s} Le ds = (σa/σt)(1 - e^{-σt h}) Le, with 1 - e^{-x}
// from Math.expm1 (no series needed in float64).
import { type Medium1D, mediumExtinction, mediumOpticalDepth } from './medium.ts';
import { type RngState, rngNextFloat } from './rng.ts';
import { F32_MAX, FINITE_LIMIT } from './transmittance.ts';

export const MARCH_LEFT = 0;
export const MARCH_MIDPOINT = 1;
export const MARCH_JITTERED_RAY = 2;
export const MARCH_JITTERED_STRATA = 3;

/** Same hard cap as the shader (contract 4). */
export const MARCH_MAX_STEPS = 4096;

/** Where the shader's oneMinusExpOverX switches from its series (float64 needs none). */
export const ONE_MINUS_EXP_SERIES_LIMIT = 1;

/** Same input clamp as the shader's oneMinusExpOverX: 1/x stays a normal f32. */
export const ONE_MINUS_EXP_MAX_X = 1e36;

/** Same clamp of running radiance sums as the shader. */
export const MARCH_MAX_RADIANCE = 1e36;

/** Same fields as the WGSL struct MarchResult. */
export interface MarchResult {
  radiance: number;
  transmittance: number;
  steps: number;
  clampedSteps: number;
}

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);

/** (1 - e^{-x})/x for x ≥ 0 (negative x clamped to 0, where the limit is 1). */
export function oneMinusExpOverX(x: number): number {
  const y = clamp(x, 0, ONE_MINUS_EXP_MAX_X);
  return y === 0 ? 1 : -Math.expm1(-y) / y;
}

/**
 * ∫₀^L e^{−ks} ds = (1 − e^{−kL})/k for k ≥ 0 (1/m) and L ≥ 0 (m), negative inputs counted as 0;
 * L at k = 0. With expm1, so no cancellation and no product that depends on the unit of length;
 * capped at the largest f32 like the shader's saturating quotient.
 */
export function oneMinusExpOverRate(rate: number, length: number): number {
  const k = Math.max(rate, 0);
  const l = Math.max(length, 0);
  if (k === 0) return l;
  return Math.min(-Math.expm1(-k * l) / k, F32_MAX);
}

export function marchStepCount(steps: number): number {
  return clamp(steps >>> 0, 1, MARCH_MAX_STEPS);
}

export function marchRayOffset(scheme: number, state: RngState): number {
  switch (scheme) {
    case MARCH_LEFT:
    case MARCH_JITTERED_STRATA:
      return 0;
    case MARCH_JITTERED_RAY:
      return rngNextFloat(state);
    default:
      return 0.5;
  }
}

export function marchStepOffset(scheme: number, rayOffset: number, state: RngState): number {
  return scheme === MARCH_JITTERED_STRATA ? rngNextFloat(state) : rayOffset;
}

/**
 * clamp(e0 + e1·t, 0, 1e18) with e0 (a radiance) clamped to ±1e18 and t < 0 counting as 0.
 * The slope e1 (per m) and t (m) are never clamped on their own, so L_e is the same in any
 * unit of length; float64 forms e1·t without overflow for any f32 inputs.
 */
export function linearEmission(emission0: number, emissionSlope: number, t: number): number {
  const growth = emissionSlope === 0 ? 0 : emissionSlope * Math.max(t, 0);
  return clamp(clamp(emission0, -FINITE_LIMIT, FINITE_LIMIT) + growth, 0, FINITE_LIMIT);
}

/** The n sample positions t_i = (i + u_i)·h of a march, drawing ξ in the shader's order. */
function samplePositions(n: number, h: number, scheme: number, state: RngState): number[] {
  const rayOffset = marchRayOffset(scheme, state);
  return Array.from({ length: n }, (_, i) => (i + marchStepOffset(scheme, rayOffset, state)) * h);
}

interface MarchSetup {
  n: number;
  positions: number[];
  /** σt·h at each sample (no factor clamped: units do not matter). */
  opticalSteps: number[];
}

function setUpMarch(
  medium: Medium1D,
  d: number,
  steps: number,
  scheme: number,
  state: RngState,
): MarchSetup {
  const n = marchStepCount(steps);
  const h = Math.max(d, 0) / n;
  const positions = samplePositions(n, h, scheme, state);
  const opticalSteps = positions.map((t) => mediumExtinction(medium, t) * h);
  return { n, positions, opticalSteps };
}

export function raymarchEmissionAbsorption(
  medium: Medium1D,
  emission0: number,
  emissionSlope: number,
  albedo: number,
  background: number,
  d: number,
  steps: number,
  scheme: number,
  state: RngState,
): MarchResult {
  const { n, positions, opticalSteps } = setUpMarch(medium, d, steps, scheme, state);
  const absorbedFraction = 1 - clamp(albedo, 0, 1);
  let radiance = 0;
  // T(0, t_i) before step i is exp(-Σ_{j<i} x_j).
  let opticalDepth = 0;
  positions.forEach((t, i) => {
    const x = opticalSteps[i] ?? 0;
    const segmentOpacity = -Math.expm1(-x);
    radiance +=
      Math.exp(-opticalDepth) *
      absorbedFraction *
      segmentOpacity *
      linearEmission(emission0, emissionSlope, t);
    opticalDepth += x;
  });
  const transmittance = Math.exp(-opticalDepth);
  return {
    radiance: radiance + transmittance * clamp(background, 0, FINITE_LIMIT),
    transmittance,
    steps: n,
    clampedSteps: 0,
  };
}

export function raymarchLinearized(
  medium: Medium1D,
  emission0: number,
  emissionSlope: number,
  albedo: number,
  background: number,
  d: number,
  steps: number,
  scheme: number,
  state: RngState,
): MarchResult {
  const { n, positions, opticalSteps } = setUpMarch(medium, d, steps, scheme, state);
  const absorbedFraction = 1 - clamp(albedo, 0, 1);
  let radiance = 0;
  let transmittance = 1;
  let clampedSteps = 0;
  positions.forEach((t, i) => {
    const x = opticalSteps[i] ?? 0;
    // Forward Euler: dT = -σt T ds, dL = T σa Le ds. A step with σt·h > 1 would
    // make T negative; it absorbs everything instead (opacity 1) and is counted.
    const opacity = Math.min(x, 1);
    if (x > 1) clampedSteps += 1;
    radiance +=
      transmittance * absorbedFraction * opacity * linearEmission(emission0, emissionSlope, t);
    transmittance *= 1 - opacity;
  });
  return {
    radiance: radiance + transmittance * clamp(background, 0, FINITE_LIMIT),
    transmittance,
    steps: n,
    clampedSteps,
  };
}

export function raymarchOpticalDepth(
  medium: Medium1D,
  d: number,
  steps: number,
  scheme: number,
  state: RngState,
): number {
  // Capped at the largest f32, the shader's saturation value.
  return Math.min(
    setUpMarch(medium, d, steps, scheme, state).opticalSteps.reduce((a, b) => a + b, 0),
    F32_MAX,
  );
}

export function raymarchEmissionRiemann(
  medium: Medium1D,
  emission0: number,
  emissionSlope: number,
  albedo: number,
  background: number,
  d: number,
  steps: number,
  scheme: number,
  state: RngState,
): MarchResult {
  const n = marchStepCount(steps);
  const length = Math.max(d, 0);
  const h = length / n;
  const absorbedFraction = 1 - clamp(albedo, 0, 1);
  // τ(0, t_i) accumulated segment by segment (the shader calls τ(0, t_i) directly).
  let opticalDepth = 0;
  let previous = 0;
  let radiance = 0;
  for (const t of samplePositions(n, h, scheme, state)) {
    opticalDepth += mediumOpticalDepth(medium, previous, t);
    previous = t;
    const sigmaA = absorbedFraction * mediumExtinction(medium, t);
    const weight = Math.min(Math.exp(-opticalDepth) * sigmaA * h, FINITE_LIMIT);
    radiance = Math.min(
      radiance + weight * linearEmission(emission0, emissionSlope, t),
      MARCH_MAX_RADIANCE,
    );
  }
  const transmittance = Math.exp(-(opticalDepth + mediumOpticalDepth(medium, previous, length)));
  return {
    radiance: radiance + transmittance * clamp(background, 0, FINITE_LIMIT),
    transmittance,
    steps: n,
    clampedSteps: 0,
  };
}
