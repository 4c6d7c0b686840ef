// What the vre-ray widget computes, independent of the backend: the inputs of a
// frame, the numbers it reports, and the exact integral form they are checked against.
import { mediumOpticalDepth, sineMedium, type Medium1D } from '../../reference/medium.ts';
import { transmittanceFromOpticalThickness } from '../../reference/transmittance.ts';
import type { ParameterValues } from '../parameters.ts';

/** Midpoint steps of the march, on the GPU and in the float64 twin alike. */
export const MARCH_STEPS = 1024;
/** The profile σt(s) = σ0(1 + a sin(k s)) of chapter 2's worked example. */
export const PROFILE_AMPLITUDE = 0.8;
export const PROFILE_FREQUENCY = 3;

export interface VreRayInputs {
  /** σ0 (1/m). */
  sigma: number;
  albedo: number;
  /** Le, L_in, L_bg in radiance units. */
  emission: number;
  inscatter: number;
  background: number;
  /** d (m). */
  length: number;
}

export interface VreRayResult {
  /** Step boundaries s_j = j·d/n, j = 0..n (m). */
  depths: Float64Array;
  /** Radiance reaching the eye from [0, s_j]: the emission and in-scattering parts. */
  emitted: Float64Array;
  inscattered: Float64Array;
  /** T(0→s_j). */
  transmittance: Float64Array;
  /** L(0) = emission part + in-scattering part + T(0→d)·L_bg. */
  total: number;
  /** Time of the march: GPU timestamp, GPU wall time, or CPU time (ms). */
  milliseconds: number;
  timing: 'gpu-timestamp' | 'gpu-wall' | 'cpu';
}

export function inputsFrom(values: ParameterValues): VreRayInputs {
  return {
    sigma: Number(values['sigma']),
    albedo: Number(values['albedo']),
    emission: Number(values['emission']),
    inscatter: Number(values['inscatter']),
    background: Number(values['background']),
    length: Number(values['length']),
  };
}

export function mediumFor(inputs: VreRayInputs): Medium1D {
  return sineMedium(inputs.sigma, PROFILE_AMPLITUDE, PROFILE_FREQUENCY);
}

export function depthsFor(length: number, steps = MARCH_STEPS): Float64Array {
  return Float64Array.from({ length: steps + 1 }, (_, j) => (length * j) / steps);
}

/** The three terms of the integral form, exactly. */
export interface ExactRadiance {
  emitted: number;
  inscattered: number;
  background: number;
  total: number;
  /** T(0→d) and τ(0→d). */
  transmittance: number;
  opticalDepth: number;
}

/**
 * The integral form of the VRE (chapter 4) for constant Le and L_in and constant
 * albedo: σa = (1 − α)σt and σs = ασt, and ∫₀^d σt(s) e^{−τ(0,s)} ds = 1 − T(0→d)
 * for any σt, so
 * L = (1 − α) Le (1 − T) + α L_in (1 − T) + T L_bg, with τ from the closed form
 * of the sine profile. No quadrature: this is the float64 reference.
 */
export function exactRadiance(inputs: VreRayInputs): ExactRadiance {
  const tau = mediumOpticalDepth(mediumFor(inputs), 0, inputs.length);
  const T = transmittanceFromOpticalThickness(tau);
  const emitted = (1 - inputs.albedo) * inputs.emission * (1 - T);
  const inscattered = inputs.albedo * inputs.inscatter * (1 - T);
  const background = T * inputs.background;
  return {
    emitted,
    inscattered,
    background,
    total: emitted + inscattered + background,
    transmittance: T,
    opticalDepth: tau,
  };
}

/** Depth range of the picture: the eye's margin on the left, the background's on the right. */
export function viewRange(length: number): [number, number] {
  return [-0.12 * length, 1.12 * length];
}
