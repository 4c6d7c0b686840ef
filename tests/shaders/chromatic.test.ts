// WGSL chromatic module (shaders/chromatic.wesl) vs its float64 twin through Dawn:
//  1. the closed-form functions (optical depth, hero weights, spectral-tracking
//     probabilities) on a table of cases, one invocation each;
//  2. the three estimators' free flights as many walks on the GPU (walk i seeded with
//     rngSeed(i, frame)), unbiased against the closed forms of a chromatic slab
//     (T_c = e^{−σt,c D(d)}, S_c = α_c(1 − T_c); tests/support/chromaticWalks.ts), and
//     replayed seed by seed on the twin, which draws the identical PCG stream.
// Statistics: fixed seeds; |mean − exact| < 5·sqrt(s²/N) per channel (p ≈ 5.7e-7 each).
import { beforeAll, describe, expect, it } from 'vitest';
import { gpuChromaticWalks } from '../support/chromaticGpu.ts';
import { linkKernel } from '../../src/gpu/link.ts';
import { runCompute } from '../../src/gpu/compute.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import {
  chromaticOpticalDepth,
  heroBalanceWeight,
  heroChannelWeights,
  spectralEventProbabilities,
  type ChromaticMedium,
  type Rgb,
} from '../../src/reference/chromatic.ts';
import { rngSeed } from '../../src/reference/rng.ts';
import { moments } from '../support/statistics.ts';
import {
  CHROMATIC_ESTIMATORS,
  chromaticMediumAsF32,
  chromaticSlabExpectations,
  twinChromaticWalker,
} from '../support/chromaticWalks.ts';

// ---------------------------------------------------------------------------
// 1. Closed-form functions.

const FUNCTION_KERNEL = `
import package::chromatic::{ChromaticMedium, chromaticOpticalDepth, heroBalanceWeight, heroChannelWeights, spectralEventProbabilities};

struct Case {
  medium: ChromaticMedium,
  logPdfs: vec3f,
  s: f32,
  sigmaA: vec3f,
  hero: u32,
  sigmaS: vec3f,
  scheme: u32,
  sigmaN: vec3f,
  pad0: f32,
  weight: vec3f,
  pad1: f32,
}

@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read_write> outputs: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&cases)) {
    return;
  }
  let c = cases[i];
  let w = heroChannelWeights(c.logPdfs, c.hero);
  let p = spectralEventProbabilities(c.sigmaA, c.sigmaS, c.sigmaN, c.weight, c.scheme);
  let o = 8u * i;
  outputs[o] = chromaticOpticalDepth(c.medium, c.s);
  outputs[o + 1u] = w.x;
  outputs[o + 2u] = w.y;
  outputs[o + 3u] = w.z;
  outputs[o + 4u] = p.x;
  outputs[o + 5u] = p.y;
  outputs[o + 6u] = p.z;
  outputs[o + 7u] = heroBalanceWeight(exp(c.logPdfs), c.hero);
}
`;

interface FunctionCase {
  name: string;
  medium: ChromaticMedium;
  s: number;
  logPdfs: Rgb;
  hero: number;
  sigmaA: Rgb;
  sigmaS: Rgb;
  sigmaN: Rgb;
  weight: Rgb;
  scheme: number;
}

const base: FunctionCase = {
  name: '',
  medium: { sigmaT: [0.5, 2, 8], densityBase: 1, albedo: [0.9, 0.7, 0.5], densitySlope: 0 },
  s: 1,
  logPdfs: [Math.log(0.2), Math.log(1.5), Math.log(3)],
  hero: 0,
  sigmaA: [0.1, 0.6, 4],
  sigmaS: [0.4, 1.4, 4],
  sigmaN: [7.5, 6, 0],
  weight: [1, 1, 1],
  scheme: 0,
};

const FUNCTION_CASES: FunctionCase[] = [
  { ...base, name: 'default medium, average scheme' },
  { ...base, name: 'max scheme, hero 2', scheme: 1, hero: 2 },
  {
    ...base,
    name: 'linear density, weighted path',
    medium: { ...base.medium, densityBase: 0.2, densitySlope: 1.6 },
    s: 0.75,
    weight: [3, 0.5, 0.01],
  },
  {
    ...base,
    name: 'density through 0 at s = 0.5, s = 2',
    medium: { ...base.medium, densityBase: 1, densitySlope: -2 },
    s: 2,
  },
  {
    ...base,
    name: 'log pdfs of a long path (e^-1000, far below f32) and an impossible channel',
    logPdfs: [-1000, -1001, -1e30],
    hero: 1,
  },
  { ...base, name: 'zero weight absorbs', weight: [0, 0, 0], scheme: 1 },
  { ...base, name: 's < 0 has depth 0', s: -3 },
];

function packFunctionCases(cases: readonly FunctionCase[]): Uint32Array {
  // std430: ChromaticMedium (words 0–7), then four vec3f each followed by a 4-byte field.
  const words = new Uint32Array(28 * cases.length);
  const f = new Float32Array(words.buffer);
  cases.forEach((c, i) => {
    const o = 28 * i;
    const m = c.medium;
    f.set([...m.sigmaT, m.densityBase, ...m.albedo, m.densitySlope], o);
    f.set([...c.logPdfs, c.s, ...c.sigmaA], o + 8);
    words[o + 15] = c.hero;
    f.set(c.sigmaS, o + 16);
    words[o + 19] = c.scheme;
    f.set(c.sigmaN, o + 20);
    f.set(c.weight, o + 24);
  });
  return words;
}

describe('chromatic closed-form functions: WGSL vs twin', () => {
  let gpu: Float32Array = new Float32Array();
  beforeAll(async () => {
    const device = await nodeDevice();
    const code = await linkKernel(SHADER_LIBRARY, FUNCTION_KERNEL);
    const { output } = await runCompute(device, {
      code,
      inputs: [packFunctionCases(FUNCTION_CASES)],
      outputWords: 8 * FUNCTION_CASES.length,
      workgroups: [1],
    });
    gpu = new Float32Array(output.buffer);
  }, 60_000);
  FUNCTION_CASES.forEach((c, i) => {
    it(c.name, () => {
      const r = (v: Rgb): Rgb => [Math.fround(v[0]), Math.fround(v[1]), Math.fround(v[2])];
      const m = chromaticMediumAsF32(c.medium);
      const logPdfs = r(c.logPdfs);
      const w = heroChannelWeights(logPdfs, c.hero);
      const p = spectralEventProbabilities(
        r(c.sigmaA),
        r(c.sigmaS),
        r(c.sigmaN),
        r(c.weight),
        c.scheme,
      );
      const balance = heroBalanceWeight(logPdfs.map(Math.exp) as Rgb, c.hero);
      const twin = [chromaticOpticalDepth(m, Math.fround(c.s)), ...w, ...p, balance];
      // A few f32 roundings (exp: 3 + 2|x| ULP in WGSL, physics.md §10): 1e-5 relative.
      twin.forEach((x, k) => {
        const g = gpu[8 * i + k]!;
        expect(Number.isFinite(g), `output ${k} finite`).toBe(true);
        expect(Math.abs(g - x), `output ${k}: gpu ${g} vs twin ${x}`).toBeLessThanOrEqual(
          1e-5 * Math.abs(x) + 1e-6,
        );
      });
    });
  });
});

// ---------------------------------------------------------------------------
// 2. Many walks on the GPU.

/** 2^16 walks per GPU run: 5 SE of a transmittance 0.14 is ±0.007. */
const GPU_WALKS = 1 << 16;
/** Walks replayed on the twin, seed by seed. */
const TWIN_WALKS = 4000;

const close = (a: Rgb, b: Rgb): boolean =>
  a.every((x, c) => Math.abs(x - b[c]!) <= 1e-4 * Math.max(Math.abs(b[c]!), 1e-3));

describe('chromatic free flights on the GPU: unbiased, and replayed by the twin', () => {
  const slabs: [string, ChromaticMedium, number][] = [
    [
      'homogeneous σt = (0.5, 2, 8)',
      { sigmaT: [0.5, 2, 8], densityBase: 1, albedo: [0.9, 0.7, 0.5], densitySlope: 0 },
      1,
    ],
    [
      'linear density 0.2 + 1.6 s',
      { sigmaT: [0.5, 2, 8], densityBase: 0.2, albedo: [0.9, 0.7, 0.5], densitySlope: 1.6 },
      1,
    ],
  ];
  for (const [name, medium, d] of slabs) {
    const exact = chromaticSlabExpectations(medium, d);
    for (const estimator of CHROMATIC_ESTIMATORS) {
      it(`${estimator}, ${name}`, async () => {
        const gpu = await gpuChromaticWalks(estimator, medium, d, 3, GPU_WALKS);
        for (const key of ['T', 'S'] as const) {
          for (let c = 0; c < 3; c++) {
            const m = moments(gpu.map((w) => w[key][c]!));
            const bound = 5 * Math.sqrt(m.variance / m.n) + 1e-6;
            expect(
              Math.abs(m.mean - exact[key][c]!),
              `${key}[${c}] mean ${m.mean} vs ${exact[key][c]}`,
            ).toBeLessThan(bound);
          }
        }
        expect(gpu.every((w) => w.capped === 0)).toBe(true);
        const walk = twinChromaticWalker({ estimator, medium, d, maxSteps: 65536 });
        let agree = 0;
        for (let i = 0; i < TWIN_WALKS; i++) {
          const twin = walk({ value: rngSeed(i, 3) });
          const g = gpu[i]!;
          if (close(g.T, twin.T) && close(g.S, twin.S) && g.lookups === twin.lookups) agree++;
        }
        // Misses are f32-vs-float64 ties in a comparison (ξ·ρ̄ < ρ, ξ < P): rare.
        expect(agree / TWIN_WALKS).toBeGreaterThanOrEqual(0.99);
      }, 60_000);
    }
  }
});
