// What <sb-dipole-profile> computes, independent of the backend: the medium of each
// channel (a Jensen et al. 2001 preset or coefficients set by hand, per mm), the three
// diffusion profiles on a log-spaced grid with their totals (the float64 twin of
// evaluateProfiles in shaders/kernels/dipole-profile.wesl), the colour of the lit disc
// (the twin of discFragment), the Monte Carlo run of the same half-space
// (shaders/kernels/slab.wesl through src/subsurface/slabKernel.ts) and the comparison
// of every model's total with the Monte Carlo's.
import {
  betterDipoleParameters,
  betterDipoleProfile,
  betterDipoleTotalReflectance,
  burleyProfile,
  burleyShapeSearchlight,
  dipoleParameters,
  dipoleProfile,
  dipoleTotalReflectance,
} from '../../reference/dipole.ts';
import { findMaterial, type Rgb } from '../../subsurface/materials.ts';
import { planBatches, type ChannelEstimate, type SlabRun } from '../../subsurface/slabKernel.ts';
import type { ParameterValues } from '../parameters.ts';

/** The plot's radii: log-spaced from GRID_R_MIN to GRID_R_MAX mm. */
export const GRID_COUNT = 160;
export const GRID_R_MIN = 0.01;
export const GRID_R_MAX = 100;
/** Monte Carlo radial bins: [0, 0.01) mm, then 40 log-spaced bins to 100 mm (10 per decade). */
export const MC_BINS = 41;
/** Cap on free flights per Monte Carlo walk, reported when reached (see slab.wesl). */
export const MC_MAX_COLLISIONS = 16384;
/** The disc's exposure at 0 EV, in mm²: 1 − exp(−200 mm²·R_d) is 0.5 where R_d = 3.5e-3 mm⁻². */
export const EXPOSURE_AT_ZERO_EV = 200;
/** As AMBIENT and DISC_FRACTION in the kernel. */
export const DISC_AMBIENT = 0.05;
export const DISC_FRACTION = 0.94;
/** Monte Carlo collisions a first run may spend per channel (it runs on every change). */
export const FIRST_RUN_COLLISIONS = 2 ** 17;

export const CHANNEL_NAMES = ['R', 'G', 'B'] as const;

export interface ProfileInputs {
  material: string;
  /** σs′ per channel (1/mm). */
  sigmaSPrime: Rgb;
  /** σa per channel (1/mm). */
  sigmaA: Rgb;
  eta: number;
  /** HG g of the Monte Carlo. */
  g: number;
  /** Photons per channel that "More photons" runs up to. */
  photonTarget: number;
  /** mm² (EXPOSURE_AT_ZERO_EV · 2^EV). */
  exposure: number;
  /** Half-width of the disc picture (mm). */
  view: number;
  seed: number;
}

// The material presets' slider values live in materialValues.ts (free of GPU code, so
// that widget.ts can build the presets from them); re-exported for model's callers.
export { MATERIAL_PARAMETERS, materialValues } from './materialValues.ts';

export function inputsFrom(values: ParameterValues): ProfileInputs {
  const material = String(values['material']);
  const preset = findMaterial(material);
  const n = (key: string): number => Number(values[key]);
  return {
    material,
    sigmaSPrime: preset?.sigmaSPrime ?? [n('sigma-s-r'), n('sigma-s-g'), n('sigma-s-b')],
    sigmaA: preset?.sigmaA ?? [n('sigma-a-r'), n('sigma-a-g'), n('sigma-a-b')],
    eta: preset?.eta ?? n('eta'),
    g: n('g'),
    photonTarget: 2 ** Math.round(n('photons')),
    exposure: EXPOSURE_AT_ZERO_EV * 2 ** n('exposure'),
    view: n('view'),
    seed: Math.round(n('seed')),
  };
}

/** What a Monte Carlo run depends on: when it changes, the accumulated photons are dropped. */
export function monteCarloKey(inputs: ProfileInputs): string {
  return JSON.stringify([inputs.sigmaSPrime, inputs.sigmaA, inputs.eta, inputs.g, inputs.seed]);
}

export function gridRadius(i: number): number {
  return GRID_R_MIN * (GRID_R_MAX / GRID_R_MIN) ** (i / (GRID_COUNT - 1));
}

/** The three profiles per channel on the grid, and their totals. */
export interface ProfileCurves {
  radii: Float64Array;
  /** [channel] → values on the grid (1/mm²). */
  dipole: Float64Array[];
  better: Float64Array[];
  burley: Float64Array[];
  dipoleTotal: number[];
  betterTotal: number[];
  /** Christensen–Burley shape length d per channel (mm); its albedo is dipoleTotal. */
  burleyLength: number[];
  dipoleAtZero: number[];
  betterAtZero: number[];
}

/** The Burley comparison's d = ℓ/s(A), ℓ = 1/σt′, A = the dipole's total (as the kernel). */
export function burleyLength(sigmaTPrime: number, albedo: number): number {
  // No medium has no spread (d = 0, where burleyProfile is 0), as in the kernel.
  if (!(sigmaTPrime > 0)) return 0;
  return 1 / (sigmaTPrime * burleyShapeSearchlight(albedo));
}

/** Twin of evaluateProfiles: the same radii and formulas in float64, on f32-rounded inputs. */
/** What the three profiles depend on (a cache key of the worker job holds nothing else). */
export type CurveInputs = Pick<ProfileInputs, 'sigmaSPrime' | 'sigmaA' | 'eta'>;

export function evaluateProfilesCpu(inputs: CurveInputs): ProfileCurves {
  const radii = Float64Array.from({ length: GRID_COUNT }, (_, i) => gridRadius(i));
  const curves: ProfileCurves = {
    radii,
    dipole: [],
    better: [],
    burley: [],
    dipoleTotal: [],
    betterTotal: [],
    burleyLength: [],
    dipoleAtZero: [],
    betterAtZero: [],
  };
  const eta = Math.fround(inputs.eta);
  for (let c = 0; c < 3; c++) {
    const sp = Math.fround(inputs.sigmaSPrime[c]!);
    const sa = Math.fround(inputs.sigmaA[c]!);
    const p = dipoleParameters(sp, sa, eta);
    const q = betterDipoleParameters(sp, sa, eta);
    const albedo = dipoleTotalReflectance(p);
    const d = burleyLength(p.sigmaTPrime, albedo);
    curves.dipole.push(radii.map((r) => dipoleProfile(p, r)));
    curves.better.push(radii.map((r) => betterDipoleProfile(q, r)));
    curves.burley.push(radii.map((r) => burleyProfile(albedo, d, r)));
    curves.dipoleTotal.push(albedo);
    curves.betterTotal.push(betterDipoleTotalReflectance(q));
    curves.burleyLength.push(d);
    curves.dipoleAtZero.push(dipoleProfile(p, 0));
    curves.betterAtZero.push(betterDipoleProfile(q, 0));
  }
  return curves;
}

/** Unpacks the kernel's output (layout in shaders/kernels/dipole-profile.wesl). */
export function unpackProfiles(output: Float32Array): ProfileCurves {
  const n = GRID_COUNT;
  const slice = (k: number): Float64Array => Float64Array.from(output.subarray(k * n, (k + 1) * n));
  const totals = 9 * n;
  const three = (offset: number): number[] =>
    [0, 1, 2].map((c) => output[totals + offset + c] ?? NaN);
  return {
    radii: Float64Array.from({ length: n }, (_, i) => gridRadius(i)),
    dipole: [0, 1, 2].map((c) => slice(c)),
    better: [0, 1, 2].map((c) => slice(3 + c)),
    burley: [0, 1, 2].map((c) => slice(6 + c)),
    dipoleTotal: three(0),
    betterTotal: three(3),
    burleyLength: three(6),
    dipoleAtZero: three(9),
    betterAtZero: three(12),
  };
}

/**
 * Twin of discFragment: the display colour (gamma 2.2, in [0, 1]) of a point at distance r
 * (mm) from the beam, inside the disc: 1 − exp(−exposure·R_d(r)) + AMBIENT·R_d,total per channel.
 */
export function discColour(
  inputs: Pick<ProfileInputs, 'sigmaSPrime' | 'sigmaA' | 'eta' | 'exposure'>,
  r: number,
): [number, number, number] {
  const colour: [number, number, number] = [0, 0, 0];
  for (let c = 0; c < 3; c++) {
    const p = dipoleParameters(inputs.sigmaSPrime[c]!, inputs.sigmaA[c]!, inputs.eta);
    const light =
      1 -
      Math.exp(-inputs.exposure * dipoleProfile(p, r)) +
      DISC_AMBIENT * dipoleTotalReflectance(p);
    colour[c] = Math.min(light, 1) ** (1 / 2.2);
  }
  return colour;
}

/**
 * A first guess of the collisions per walk in a half-space, from the reduced albedo: the
 * diffusion length grows as 1/√(1 − α′), and ≈ 20/√(1 − α′) matches the measured walks
 * (marble R: 640, skin1 B: ≈ 30), capped at MC_MAX_COLLISIONS. Used only to size runs.
 */
export function expectedCollisions(inputs: ProfileInputs): number {
  let worst = 1;
  for (let c = 0; c < 3; c++) {
    const sp = inputs.sigmaSPrime[c]!;
    const sa = inputs.sigmaA[c]!;
    const absorbed = sa / Math.max(sp + sa, 1e-12);
    const guess = 20 / Math.sqrt(Math.max(absorbed, 1e-9)) / (1 - inputs.g);
    worst = Math.max(worst, Math.min(guess, MC_MAX_COLLISIONS));
  }
  return worst;
}

/**
 * Photons per channel of the first run: FIRST_RUN_COLLISIONS worth, a power of two in
 * [1024, 4096]. At least 1024 makes 16 batches of 64, enough for a first standard error
 * (its own relative error is about 1/√(2·15) ≈ 18%).
 */
export function firstRunPhotons(inputs: ProfileInputs): number {
  const photons = FIRST_RUN_COLLISIONS / expectedCollisions(inputs);
  return 2 ** Math.min(Math.max(Math.round(Math.log2(photons)), 10), 12);
}

/** A Monte Carlo run of the half-space (all three channels), continuing at threadOffset. */
export function slabRunFor(inputs: ProfileInputs, photons: number, threadOffset: number): SlabRun {
  const g = Math.min(Math.max(inputs.g, 0), 0.95);
  return {
    channels: [0, 1, 2].map((c) => ({
      sigmaA: inputs.sigmaA[c]!,
      // Similarity: σs = σs′/(1 − g) keeps σs′ = σs(1 − g), the diffusion models' input.
      sigmaS: inputs.sigmaSPrime[c]! / (1 - g),
    })),
    g,
    thickness: Infinity,
    eta: inputs.eta,
    incidenceCos: 1,
    maxCollisions: MC_MAX_COLLISIONS,
    seed: inputs.seed,
    threadOffset,
    profile: { bins: MC_BINS, rMin: GRID_R_MIN, rMax: GRID_R_MAX },
    ...planBatches(photons),
  };
}

/** One model's total against the Monte Carlo's, per channel. */
export interface TotalComparison {
  /** Model − MC. */
  difference: number;
  /** (Model − MC)/MC. */
  relative: number;
  /** Difference in MC standard errors. */
  z: number;
}

export function compareTotal(model: number, mc: ChannelEstimate): TotalComparison {
  const reference = mc.diffuseReflectance.mean;
  const difference = model - reference;
  return {
    difference,
    relative: reference > 0 ? difference / reference : 0,
    z: mc.diffuseReflectance.se > 0 ? difference / mc.diffuseReflectance.se : 0,
  };
}

/** The mean over channels of |value|. */
export function meanAbsolute(values: readonly number[]): number {
  return values.reduce((sum, v) => sum + Math.abs(v), 0) / Math.max(values.length, 1);
}
