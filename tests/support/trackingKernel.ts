// One walk of a transmittance estimator of shaders/tracking.wesl, chosen by index, in
// WGSL for the custom kernels of tests/shaders/tracking.test.ts (many walks of one
// setup) and tests/stability/tracking.test.ts (a few walks of many setups), and in
// TypeScript for the twin's replay of the same walks: given the same seed, both draw
// the identical PCG stream (physics.md §4; DESIGN.md contract 1).
import type { Medium1D } from '../../src/reference/medium.ts';
import { rngNextFloat, type RngState } from '../../src/reference/rng.ts';
import {
  TRACKING_MAX_STEPS,
  transmittanceDeltaTracking,
  transmittanceRatioTracking,
  transmittanceResidualRatioTracking,
  transmittanceNullScattering,
  transmittanceTrackLength,
  transmittanceUnbiasedRayMarching,
  type TransmittanceEstimate,
} from '../../src/reference/tracking.ts';
import { MEDIUM_WORDS, mediumAsF32, packMedium } from './medium1d.ts';

/** The estimators in the order of their WGSL index. */
export const ESTIMATORS = [
  'delta',
  'ratio',
  'residual',
  'unbiasedRayMarching',
  'trackLength',
  'nullScattering',
] as const;
export type EstimatorName = (typeof ESTIMATORS)[number];

/** What one walk needs: the estimator and its inputs. */
export interface WalkSetup {
  estimator: EstimatorName;
  medium: Medium1D;
  d: number;
  /** σ̄ (the residual majorant σ̄r for residual ratio tracking). */
  sigmaMaj: number;
  /** σc of residual ratio tracking (0 when absent). */
  sigmaControl?: number;
  /** The loop cap (TRACKING_MAX_STEPS when absent). */
  maxSteps?: number;
  /** β of null-scattering tracking (0 when absent: delta tracking's P_n). */
  nullBlend?: number;
}

/**
 * WGSL: the struct WalkSetup (the fields of the interface, in that order) and
 * `estimateTransmittance(setup, &state)`, one walk from the stream in `state`. Library
 * names are written in full, so that a kernel can place this after its own imports.
 */
export const WALK_WGSL = `
struct WalkSetup {
  estimator: u32,
  medium: package::medium::Medium1D,
  d: f32,
  sigmaMaj: f32,
  sigmaControl: f32,
  maxSteps: u32,
  nullBlend: f32,
}

fn estimateTransmittance(setup: WalkSetup, state: ptr<function, u32>) -> package::tracking::TransmittanceEstimate {
  let m = setup.medium;
  var r = package::tracking::TransmittanceEstimate(1.0, 0u, 0u);
  switch setup.estimator {
    case 0u: { r = package::tracking::transmittanceDeltaTracking(m, setup.d, setup.sigmaMaj, state, setup.maxSteps); }
    case 1u: { r = package::tracking::transmittanceRatioTracking(m, setup.d, setup.sigmaMaj, state, setup.maxSteps); }
    case 2u: { r = package::tracking::transmittanceResidualRatioTracking(m, setup.d, setup.sigmaControl, setup.sigmaMaj, state, setup.maxSteps); }
    case 3u: { r = package::tracking::transmittanceUnbiasedRayMarching(m, setup.d, setup.sigmaMaj, state, setup.maxSteps); }
    case 5u: { r = package::tracking::transmittanceNullScattering(m, setup.d, setup.sigmaMaj, setup.nullBlend, state, setup.maxSteps); }
    case 4u: { r.estimate = package::tracking::transmittanceTrackLength(m.sigma0, setup.d, package::rng::rngNextFloat(state)); }
    default: {}
  }
  return r;
}
`;

/** 32-bit words of a WalkSetup in a storage buffer. */
export const WALK_SETUP_WORDS = MEDIUM_WORDS + 6;

/** Writes `setup` into `words` from word `offset` on, in the layout of WALK_WGSL's struct. */
export function packWalkSetup(words: Uint32Array, offset: number, setup: WalkSetup): void {
  const floats = new Float32Array(words.buffer, words.byteOffset, words.length);
  const o = offset + 1 + MEDIUM_WORDS;
  words[offset] = ESTIMATORS.indexOf(setup.estimator);
  packMedium(words, offset + 1, setup.medium);
  floats[o] = setup.d;
  floats[o + 1] = setup.sigmaMaj;
  floats[o + 2] = setup.sigmaControl ?? 0;
  words[o + 3] = setup.maxSteps ?? TRACKING_MAX_STEPS;
  floats[o + 4] = setup.nullBlend ?? 0;
}

/**
 * The twin of estimateTransmittance for `setup`, with every input rounded to f32 as
 * the GPU sees it: each call is one walk from the stream in `state`.
 */
export function twinWalker(setup: WalkSetup): (state: RngState) => TransmittanceEstimate {
  const medium = mediumAsF32(setup.medium);
  const d = Math.fround(setup.d);
  const sigmaMaj = Math.fround(setup.sigmaMaj);
  const sigmaControl = Math.fround(setup.sigmaControl ?? 0);
  const maxSteps = setup.maxSteps ?? TRACKING_MAX_STEPS;
  const nullBlend = Math.fround(setup.nullBlend ?? 0);
  return (state) => {
    switch (setup.estimator) {
      case 'delta':
        return transmittanceDeltaTracking(medium, d, sigmaMaj, state, maxSteps);
      case 'ratio':
        return transmittanceRatioTracking(medium, d, sigmaMaj, state, maxSteps);
      case 'residual':
        return transmittanceResidualRatioTracking(
          medium,
          d,
          sigmaControl,
          sigmaMaj,
          state,
          maxSteps,
        );
      case 'unbiasedRayMarching':
        return transmittanceUnbiasedRayMarching(medium, d, sigmaMaj, state, maxSteps);
      case 'nullScattering':
        return transmittanceNullScattering(medium, d, sigmaMaj, nullBlend, state, maxSteps);
      case 'trackLength':
        return {
          estimate: transmittanceTrackLength(medium.sigma0, d, rngNextFloat(state)),
          lookups: 0,
          capped: 0,
        };
    }
  };
}
