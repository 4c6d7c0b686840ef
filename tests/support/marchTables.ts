// Harness tables for the marched functions that take a Medium1D and an RNG state
// (shaders/raymarch.wesl and singleScatterMarched of shaders/scatter.wesl), shared by
// tests/shaders and tests/stability: the medium crosses as its eight fields
// (medium1d.ts), the seed as a u32 that the wrapper turns into `var state`, and the
// twin consumes the identical PCG stream from { value: seed }. A march returns
// (radiance, transmittance, steps, clampedSteps) as a vec4f.
import {
  raymarchEmissionAbsorption,
  raymarchOpticalDepth,
  type MarchResult,
} from '../../src/reference/raymarch.ts';
import { singleScatterMarched } from '../../src/reference/scatter.ts';
import { MEDIUM_SINE, type Medium1D } from '../../src/reference/medium.ts';
import {
  MEDIUM_ARGUMENTS,
  MEDIUM_PARAMETERS,
  MEDIUM_VALUE,
  mediumArguments,
  mediumFromArguments,
} from './medium1d.ts';
import type { Argument, ShaderFunctionTable } from './shaderHarness.ts';

type Cases = ShaderFunctionTable['cases'];
type Tolerance = ShaderFunctionTable['tolerance'];

/** WGSL sin's absolute error 2^-11 (spec, "Floating Point Accuracy"; bounded on [-π, π]). */
export const SIN_ERROR = 2 ** -11;

/** An upper bound on σt along the ray: the largest coefficient (≤ 1e18) times 1 + amplitude. */
export const sigmaUpperBound = (medium: Medium1D): number =>
  Math.min(Math.max(medium.sigma0, ...medium.cells, 0), 1e18) * (1 + medium.amplitude);

/** δσ: how far WGSL sin may move σt of a sinusoidal medium (σ0·a·2^-11); 0 for the others. */
export const sinErrorInSigma = (medium: Medium1D): number =>
  medium.kind === MEDIUM_SINE ? medium.sigma0 * medium.amplitude * SIN_ERROR : 0;

const asVector = (r: MarchResult): number[] => [
  r.radiance,
  r.transmittance,
  r.steps,
  r.clampedSteps,
];

/** The signature shared by the four march functions of raymarch.ts. */
export type March = typeof raymarchEmissionAbsorption;

/** Harness arguments of a march: medium, e0, slope, albedo, L_bg, d, steps, scheme, seed. */
export const marchArgs = (
  medium: Medium1D,
  e0: number,
  slope: number,
  albedo: number,
  background: number,
  d: number,
  steps: number,
  scheme: number,
  seed = 0,
): Argument[] => [
  ...mediumArguments(medium),
  e0,
  slope,
  albedo,
  background,
  d,
  steps,
  scheme,
  seed,
];

/** A harness table for one of the four march functions of raymarch.wesl. */
export function marchTable(
  fn: string,
  twin: March,
  cases: Cases,
  tolerance: Tolerance,
): ShaderFunctionTable {
  return {
    module: 'raymarch',
    fn,
    args: [...MEDIUM_ARGUMENTS, 'f32', 'f32', 'f32', 'f32', 'f32', 'u32', 'u32', 'u32'],
    result: 'vec4f',
    wrapper: {
      imports: [fn],
      wgsl: `fn caseUnderTest(${MEDIUM_PARAMETERS}, emission0: f32, emissionSlope: f32, albedo: f32, background: f32, d: f32, steps: u32, scheme: u32, seed: u32) -> vec4f {
  var state = seed;
  let r = ${fn}(${MEDIUM_VALUE}, emission0, emissionSlope, albedo, background, d, steps, scheme, &state);
  return vec4f(r.radiance, r.transmittance, f32(r.steps), f32(r.clampedSteps));
}`,
    },
    twin: ((...args: Argument[]) => {
      const [e0, slope, albedo, background, d, steps, scheme, seed] = args.slice(8) as number[];
      return asVector(
        twin(
          mediumFromArguments(args),
          e0 ?? 0,
          slope ?? 0,
          albedo ?? 0,
          background ?? 0,
          d ?? 0,
          steps ?? 0,
          scheme ?? 0,
          { value: seed ?? 0 },
        ),
      );
    }) as never,
    tolerance,
    cases,
  };
}

/** Harness arguments of raymarchOpticalDepth: medium, d, steps, scheme, seed. */
export const opticalDepthArgs = (
  medium: Medium1D,
  d: number,
  steps: number,
  scheme: number,
  seed: number,
): Argument[] => [...mediumArguments(medium), d, steps, scheme, seed];

/**
 * A harness table for raymarchOpticalDepth (arguments: opticalDepthArgs). With
 * `transmittance`, both sides return exp(−τ̂) instead of τ̂.
 */
export function opticalDepthTable(
  cases: Cases,
  tolerance: Tolerance,
  output: 'opticalDepth' | 'transmittance' = 'opticalDepth',
): ShaderFunctionTable {
  const call = `raymarchOpticalDepth(${MEDIUM_VALUE}, d, steps, scheme, &state)`;
  return {
    module: 'raymarch',
    fn: 'raymarchOpticalDepth',
    args: [...MEDIUM_ARGUMENTS, 'f32', 'u32', 'u32', 'u32'],
    result: 'f32',
    wrapper: {
      imports: ['raymarchOpticalDepth'],
      wgsl: `fn caseUnderTest(${MEDIUM_PARAMETERS}, d: f32, steps: u32, scheme: u32, seed: u32) -> f32 {
  var state = seed;
  return ${output === 'transmittance' ? `exp(-${call})` : call};
}`,
    },
    twin: ((...args: Argument[]) => {
      const [d, steps, scheme, seed] = args.slice(8) as number[];
      const tau = raymarchOpticalDepth(mediumFromArguments(args), d ?? 0, steps ?? 0, scheme ?? 0, {
        value: seed ?? 0,
      });
      return output === 'transmittance' ? Math.exp(-tau) : tau;
    }) as never,
    tolerance,
    cases,
  };
}

/**
 * Harness arguments of singleScatterMarched: medium, albedo, phase value, irradiance,
 * shadow lengths a and b, view length, steps, scheme, seed.
 */
export const singleScatterArgs = (
  medium: Medium1D,
  albedo: number,
  phase: number,
  irradiance: number,
  a: number,
  b: number,
  length: number,
  steps: number,
  scheme: number,
  seed: number,
): Argument[] => [
  ...mediumArguments(medium),
  albedo,
  phase,
  irradiance,
  a,
  b,
  length,
  steps,
  scheme,
  seed,
];

/** A harness table for singleScatterMarched of scatter.wesl (arguments: singleScatterArgs). */
export function singleScatterTable(cases: Cases, tolerance: Tolerance): ShaderFunctionTable {
  return {
    module: 'scatter',
    fn: 'singleScatterMarched',
    args: [...MEDIUM_ARGUMENTS, 'f32', 'f32', 'f32', 'f32', 'f32', 'f32', 'u32', 'u32', 'u32'],
    result: 'vec4f',
    wrapper: {
      imports: ['singleScatterMarched'],
      wgsl: `fn caseUnderTest(${MEDIUM_PARAMETERS}, albedo: f32, phaseValue: f32, irradiance: f32, a: f32, b: f32, viewLength: f32, steps: u32, scheme: u32, seed: u32) -> vec4f {
  var state = seed;
  let r = singleScatterMarched(${MEDIUM_VALUE}, albedo, phaseValue, irradiance, a, b, viewLength, steps, scheme, &state);
  return vec4f(r.radiance, r.transmittance, f32(r.steps), f32(r.clampedSteps));
}`,
    },
    twin: ((...args: Argument[]) => {
      const [albedo, phase, irradiance, a, b, length, steps, scheme, seed] = args.slice(
        8,
      ) as number[];
      return asVector(
        singleScatterMarched(
          mediumFromArguments(args),
          albedo ?? 0,
          phase ?? 0,
          irradiance ?? 0,
          a ?? 0,
          b ?? 0,
          length ?? 0,
          steps ?? 0,
          scheme ?? 0,
          { value: seed ?? 0 },
        ),
      );
    }) as never,
    tolerance,
    cases,
  };
}
