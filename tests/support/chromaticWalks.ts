// One free flight through a chromatic slab [0, d] by each estimator of shaders/chromatic.wesl,
// in WGSL (for a kernel of many walks, walk i seeded with rngSeed(i, frame)) and in TypeScript
// on the float64 twin, drawing the identical PCG stream. Each walk returns two RGB estimates:
//   T: the transmittance of the slab (the weight of a flight that passes),
//   S: the weight of the first scattering event in the slab,
// whose expectations are, per channel, T_c = exp(−σt,c D(d)) and S_c = α_c (1 − T_c) for any
// density, since σs,c/σt,c = α_c everywhere (D = chromaticOpticalDepth).
import {
  CHROMATIC_PASSED,
  CHROMATIC_SCATTERED,
  chromaticOpticalDepth,
  deltaFreeFlight,
  heroChannelWeights,
  heroEventLogPdfs,
  spectralFreeFlight,
  SPECTRAL_AVERAGE,
  SPECTRAL_MAX,
  type ChromaticMedium,
  type Rgb,
} from '../../src/reference/chromatic.ts';
import { rngNextFloat, type RngState } from '../../src/reference/rng.ts';

export const CHROMATIC_ESTIMATORS = [
  'oneChannel',
  'hero',
  'spectralAverage',
  'spectralMax',
] as const;
export type ChromaticEstimator = (typeof CHROMATIC_ESTIMATORS)[number];

export interface ChromaticWalkSetup {
  estimator: ChromaticEstimator;
  medium: ChromaticMedium;
  d: number;
  maxSteps: number;
}

export interface ChromaticWalk {
  T: Rgb;
  S: Rgb;
  lookups: number;
  capped: number;
}

/** Words of the setup: estimator and padding (4), medium (8), d, maxSteps, padding (2). */
export const CHROMATIC_SETUP_WORDS = 16;
/** Words per walk in the output: T (3), S (3), lookups, capped. */
export const CHROMATIC_WALK_WORDS = 8;

export const CHROMATIC_WALK_WGSL = `
import package::chromatic::{ChromaticMedium, CHROMATIC_PASSED, CHROMATIC_SCATTERED, deltaFreeFlight, heroChannelWeights, heroEventLogPdfs, spectralFreeFlight};
import package::rng::{rngNextFloat, rngSeed};

struct WalkSetup {
  estimator: u32,
  pad0: u32,
  pad1: u32,
  pad2: u32,
  medium: ChromaticMedium,
  d: f32,
  maxSteps: u32,
}

struct Walk {
  T: vec3f,
  S: vec3f,
  lookups: u32,
  capped: u32,
}

fn chromaticWalk(setup: WalkSetup, state: ptr<function, u32>) -> Walk {
  let m = setup.medium;
  var walk = Walk(vec3f(0.0), vec3f(0.0), 0u, 0u);
  if (setup.estimator == 0u) {
    for (var c = 0u; c < 3u; c += 1u) {
      let f = deltaFreeFlight(m, m.sigmaT[c], setup.d, state, setup.maxSteps);
      walk.lookups += f.lookups;
      walk.capped += f.capped;
      if (f.event == CHROMATIC_PASSED) {
        walk.T[c] = 1.0;
      } else {
        walk.S[c] = m.albedo[c];
      }
    }
  } else if (setup.estimator == 1u) {
    let hero = min(u32(rngNextFloat(state) * 3.0), 2u);
    let f = deltaFreeFlight(m, m.sigmaT[hero], setup.d, state, setup.maxSteps);
    walk.lookups = f.lookups;
    walk.capped = f.capped;
    let collided = f.event == CHROMATIC_SCATTERED;
    let w = heroChannelWeights(heroEventLogPdfs(m, f.t, collided), hero);
    if (collided) {
      walk.S = m.albedo * w;
    } else {
      walk.T = w;
    }
  } else {
    let f = spectralFreeFlight(m, setup.d, vec3f(1.0), setup.estimator - 2u, state, setup.maxSteps);
    walk.lookups = f.lookups;
    walk.capped = f.capped;
    if (f.event == CHROMATIC_PASSED) {
      walk.T = f.weight;
    } else if (f.event == CHROMATIC_SCATTERED) {
      walk.S = f.weight;
    }
  }
  return walk;
}

struct WalkParams {
  walkCount: u32,
  frame: u32,
}

@group(0) @binding(0) var<storage, read> setup: WalkSetup;
@group(0) @binding(1) var<storage, read> params: WalkParams;
@group(0) @binding(2) var<storage, read_write> outputs: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= params.walkCount) {
    return;
  }
  var state = rngSeed(i, params.frame);
  let w = chromaticWalk(setup, &state);
  let o = ${CHROMATIC_WALK_WORDS}u * i;
  outputs[o] = bitcast<u32>(w.T.x);
  outputs[o + 1u] = bitcast<u32>(w.T.y);
  outputs[o + 2u] = bitcast<u32>(w.T.z);
  outputs[o + 3u] = bitcast<u32>(w.S.x);
  outputs[o + 4u] = bitcast<u32>(w.S.y);
  outputs[o + 5u] = bitcast<u32>(w.S.z);
  outputs[o + 6u] = w.lookups;
  outputs[o + 7u] = w.capped;
}
`;

/** The setup in the std430 layout of WalkSetup: ChromaticMedium is 16-byte aligned (words 4–11). */
export function packChromaticSetup(setup: ChromaticWalkSetup): Uint32Array {
  const words = new Uint32Array(CHROMATIC_SETUP_WORDS);
  const floats = new Float32Array(words.buffer);
  const m = setup.medium;
  words[0] = CHROMATIC_ESTIMATORS.indexOf(setup.estimator);
  floats.set([...m.sigmaT, m.densityBase, ...m.albedo, m.densitySlope, setup.d], 4);
  words[13] = setup.maxSteps;
  return words;
}

const f32Rgb = (v: Rgb): Rgb => [Math.fround(v[0]), Math.fround(v[1]), Math.fround(v[2])];

/** The medium as the GPU sees it (every number rounded to f32). */
export function chromaticMediumAsF32(m: ChromaticMedium): ChromaticMedium {
  return {
    sigmaT: f32Rgb(m.sigmaT),
    densityBase: Math.fround(m.densityBase),
    albedo: f32Rgb(m.albedo),
    densitySlope: Math.fround(m.densitySlope),
  };
}

/** The twin of chromaticWalk: one walk from the stream in `state`. */
export function twinChromaticWalker(setup: ChromaticWalkSetup): (state: RngState) => ChromaticWalk {
  const m = chromaticMediumAsF32(setup.medium);
  const d = Math.fround(setup.d);
  return (state) => {
    const walk: ChromaticWalk = { T: [0, 0, 0], S: [0, 0, 0], lookups: 0, capped: 0 };
    if (setup.estimator === 'oneChannel') {
      for (let c = 0; c < 3; c++) {
        const f = deltaFreeFlight(m, m.sigmaT[c]!, d, state, setup.maxSteps);
        walk.lookups += f.lookups;
        walk.capped += f.capped;
        if (f.event === CHROMATIC_PASSED) walk.T[c] = 1;
        else walk.S[c] = m.albedo[c]!;
      }
    } else if (setup.estimator === 'hero') {
      const hero = Math.min(Math.floor(rngNextFloat(state) * 3), 2);
      const f = deltaFreeFlight(m, m.sigmaT[hero]!, d, state, setup.maxSteps);
      walk.lookups = f.lookups;
      walk.capped = f.capped;
      const collided = f.event === CHROMATIC_SCATTERED;
      const w = heroChannelWeights(heroEventLogPdfs(m, f.t, collided), hero);
      if (collided) walk.S = [m.albedo[0] * w[0], m.albedo[1] * w[1], m.albedo[2] * w[2]];
      else walk.T = w;
    } else {
      const scheme = setup.estimator === 'spectralMax' ? SPECTRAL_MAX : SPECTRAL_AVERAGE;
      const f = spectralFreeFlight(m, d, [1, 1, 1], scheme, state, setup.maxSteps);
      walk.lookups = f.lookups;
      walk.capped = f.capped;
      if (f.event === CHROMATIC_PASSED) walk.T = f.weight;
      else if (f.event === CHROMATIC_SCATTERED) walk.S = f.weight;
    }
    return walk;
  };
}

/** Closed forms: T_c = exp(−σt,c D(d)), S_c = α_c (1 − T_c). */
export function chromaticSlabExpectations(medium: ChromaticMedium, d: number): { T: Rgb; S: Rgb } {
  const depth = chromaticOpticalDepth(medium, d);
  const T = medium.sigmaT.map((s) => Math.exp(-s * depth)) as Rgb;
  const S = medium.albedo.map((a, c) => a * (1 - T[c]!)) as Rgb;
  return { T, S };
}
