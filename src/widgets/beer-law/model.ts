// What the beer-law widget computes, independent of the backend: the inputs of a
// frame and the numbers it reports.
import type { ParameterValues } from '../parameters.ts';
import type { ProfileName } from './profiles.ts';

export const CURVE_SAMPLES = 256;

export interface BeerLawInputs {
  sigmaA: number;
  sigmaS: number;
  sigmaT: number;
  thickness: number;
  /** Split point clamped to [0, d]. */
  split: number;
  profile: ProfileName;
}

export interface BeerLawResult {
  /** Depths s_i (m) and T(0→s_i). */
  depths: Float64Array;
  transmittance: Float64Array;
  opticalDepth: Float64Array;
  exit: number;
  beforeSplit: number;
  afterSplit: number;
  /** Time to compute the curve: GPU timestamp, GPU wall time, or CPU time (ms). */
  milliseconds: number;
  timing: 'gpu-timestamp' | 'gpu-wall' | 'cpu';
}

export function inputsFrom(values: ParameterValues): BeerLawInputs {
  const sigmaA = Number(values['sigma-a']);
  const sigmaS = Number(values['sigma-s']);
  const thickness = Number(values['thickness']);
  return {
    sigmaA,
    sigmaS,
    sigmaT: sigmaA + sigmaS,
    thickness,
    split: Math.min(Math.max(Number(values['split']), 0), thickness),
    profile: values['profile'] as ProfileName,
  };
}

export function depthsFor(thickness: number, samples = CURVE_SAMPLES): Float64Array {
  return Float64Array.from({ length: samples }, (_, i) => (thickness * i) / (samples - 1));
}

/** Depth range of the picture: the slab plus a margin on each side for the incident and exiting beam. */
export function viewRange(thickness: number): [number, number] {
  const span = Math.max(thickness, 0.5);
  return [-0.08 * span, thickness + 0.08 * span];
}
