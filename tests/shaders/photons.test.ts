// shaders/photons.wesl against its float64 twin (src/reference/photons.ts), and the
// photon-map pipeline of shaders/kernels/photon-map.wesl (chapter 10, "Photon mapping
// and volume caustics"):
// - energy: N photons carry exactly the light's power E·A;
// - the volume density estimate of a known photon distribution (a Gaussian blob)
//   converges to the analytic density as r shrinks and N grows, with its exact mean and
//   variance at each (N, r) as the bound;
// - the GPU-built grid (counting sort) finds exactly the photons within r of a query,
//   against brute force, and the CPU twin's grid does too;
// - without caustics (η = 1) the photon map agrees with the path tracer (twins) within
//   their standard errors plus the stated bias of the radius.
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import type { Vec3 } from '../../src/reference/phase.ts';
import {
  dielectricScatter,
  photonCellCoord,
  photonCellIndex,
  photonKernel,
  photonPower,
  sunConeSampleCosine,
  sunConeSampleUniform,
  sunConeSolidAngle,
  sunRadiance,
} from '../../src/reference/photons.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { renderPhotonMapGpu } from '../../src/widgets/photon-map/gpuBackend.ts';
import {
  DEFAULT_INPUTS,
  RECORD_WORDS,
  SCENE,
  bruteForceCpu,
  buildGridCpu,
  gatherCpu,
  gridFor,
  pathTraceCpu,
  photonMapImageCpu,
  progressiveRadius,
  tracePhotonsCpu,
  type PhotonSet,
} from '../../src/widgets/photon-map/model.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { TRIG_DIRECTION } from '../support/phaseHarness.ts';
import { describeShaderFunction } from '../support/shaderHarness.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

const asVec3 = (v: readonly number[]): Vec3 => [v[0]!, v[1]!, v[2]!];
const vecArg = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;

describeShaderFunction({
  module: 'photons',
  fn: 'sunRadiance',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: sunRadiance,
  tolerance: { relative: 4e-7 * 4, reason: 'three f32 products and a division' },
  cases: [
    { name: 'E = 1, θ = 1.5°', args: [1, Math.sin((1.5 * Math.PI) / 180)] },
    { name: 'E = 3, θ = 0.27° (the real sun)', args: [3, 0.00465] },
    { name: 'a hemisphere: L = E/π', args: [Math.PI, 1], expected: 1 },
  ],
});

describeShaderFunction({
  module: 'photons',
  fn: 'sunConeSolidAngle',
  args: ['f32'],
  result: 'f32',
  twin: sunConeSolidAngle,
  tolerance: { relative: 2e-6, reason: 'sin²/(1 + cos) has no cancellation: a few f32 roundings' },
  cases: [
    { name: 'θ = 1.5°', args: [Math.sin((1.5 * Math.PI) / 180)] },
    { name: 'θ = 0.01° (1 − cos θ cancels to 0 in f32)', args: [Math.sin((0.01 * Math.PI) / 180)] },
    { name: 'hemisphere 2π', args: [1], expected: 2 * Math.PI },
  ],
});

describeShaderFunction({
  module: 'photons',
  fn: 'photonPower',
  args: ['f32', 'f32', 'u32'],
  result: 'f32',
  twin: photonPower,
  tolerance: { relative: 3e-7 * 2, reason: 'a product and a division in f32' },
  cases: [
    { name: 'E·A/N, the widget’s disc', args: [1, Math.PI, 65536] },
    { name: 'N = 1 carries all', args: [2, 3, 1], expected: 6 },
    { name: 'N = 0 carries nothing', args: [1, 1, 0], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'photons',
  fn: 'photonKernel',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: photonKernel,
  tolerance: { relative: 1e-6, reason: 'r³ and one division in f32' },
  cases: [
    { name: 'inside, r = 0.04', args: [0.001, 0.04], expected: 3 / (4 * Math.PI * 0.04 ** 3) },
    { name: 'outside', args: [0.01, 0.05], expected: 0 },
    { name: 'r = 0', args: [0, 0], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'photons',
  fn: 'photonCellIndex',
  args: ['f32[3]'],
  result: 'u32',
  wrapper: {
    imports: ['photonCellIndex', 'photonCellCoord'],
    wgsl: `fn caseUnderTest(p: array<f32, 3>) -> u32 {
  let dims = vec3u(40u, 40u, 25u);
  return photonCellIndex(photonCellCoord(${vecArg('p')}, vec3f(-0.8, -0.8, -0.5), 0.04, dims), dims);
}`,
  },
  twin: (p: readonly number[]) =>
    photonCellIndex(
      photonCellCoord(
        asVec3(p),
        [-0.8, -0.8, -0.5].map(Math.fround) as unknown as Vec3,
        Math.fround(0.04),
        [40, 40, 25],
      ),
      [40, 40, 25],
    ),
  tolerance: {
    absolute: 0,
    reason: 'integer cells; no point lies within f32 rounding of a cell face',
  },
  cases: [
    { name: 'box centre', args: [[0.01, 0.01, 0.01]] },
    { name: 'a corner cell', args: [[-0.79, 0.79, 0.49]] },
    { name: 'outside is clamped to the grid', args: [[2, -3, 0.3]] },
  ],
});

const SUN_AXIS = [0, -1, 0];
const CONE_US: readonly (readonly [number, number])[] = [
  [0.5, 0.5],
  [0.1, 0.9],
  [0.97, 0.03],
];

describeShaderFunction({
  module: 'photons',
  fn: 'sunConeSampleCosine',
  args: ['f32[3]', 'f32', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['sunConeSampleCosine'],
    wgsl: `fn caseUnderTest(axis: array<f32, 3>, s: f32, u0: f32, u1: f32) -> vec3f {
  return sunConeSampleCosine(${vecArg('axis')}, s, vec2f(u0, u1));
}`,
  },
  twin: (axis: readonly number[], s: number, u0: number, u1: number) =>
    sunConeSampleCosine(asVec3(axis), s, [u0, u1]),
  tolerance: TRIG_DIRECTION,
  cases: CONE_US.map((u) => ({
    name: `θ = 20°, u = ${u.join(', ')}`,
    args: [SUN_AXIS, Math.sin(0.349), u[0], u[1]],
  })),
});

describeShaderFunction({
  module: 'photons',
  fn: 'sunConeSampleUniform',
  args: ['f32[3]', 'f32', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['sunConeSampleUniform'],
    wgsl: `fn caseUnderTest(axis: array<f32, 3>, s: f32, u0: f32, u1: f32) -> vec3f {
  return sunConeSampleUniform(${vecArg('axis')}, s, vec2f(u0, u1));
}`,
  },
  twin: (axis: readonly number[], s: number, u0: number, u1: number) =>
    sunConeSampleUniform(asVec3(axis), s, [u0, u1]),
  tolerance: TRIG_DIRECTION,
  cases: CONE_US.map((u) => ({
    name: `θ = 20°, u = ${u.join(', ')}`,
    args: [[0.6, 0, 0.8], Math.sin(0.349), u[0], u[1]],
  })),
});

describeShaderFunction({
  module: 'photons',
  fn: 'dielectricScatter',
  args: ['f32[3]', 'f32[3]', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['dielectricScatter'],
    wgsl: `fn caseUnderTest(d: array<f32, 3>, n: array<f32, 3>, eta: f32, u: f32) -> vec3f {
  return dielectricScatter(normalize(${vecArg('d')}), normalize(${vecArg('n')}), eta, u);
}`,
  },
  twin: (d: readonly number[], n: readonly number[], eta: number, u: number) => {
    const unit = (v: readonly number[]): Vec3 => {
      const l = Math.hypot(v[0]!, v[1]!, v[2]!);
      return [v[0]! / l, v[1]! / l, v[2]! / l];
    };
    return dielectricScatter(unit(d), unit(n), eta, u);
  },
  tolerance: { absolute: 2e-6, reason: 'a few f32 roundings of unit vectors and a square root' },
  cases: [
    {
      name: 'normal incidence refracts straight on',
      args: [[0, -1, 0], [0, 1, 0], 1.5, 0.5],
      expected: [0, -1, 0],
    },
    {
      name: 'normal incidence, u < F = 0.04 reflects',
      args: [[0, -1, 0], [0, 1, 0], 1.5, 0.01],
      expected: [0, 1, 0],
    },
    { name: 'oblique entry (Snell)', args: [[0.6, -0.8, 0], [0, 1, 0], 1.5, 0.9] },
    {
      name: 'leaving beyond the critical angle: total internal reflection',
      args: [[0.8, 0.6, 0], [0, 1, 0], 1.5, 0.99],
    },
    { name: 'η = 1 passes straight through', args: [[0.6, -0.8, 0], [0, 1, 0], 1, 0.001] },
  ],
});

describe('energy: the emitted photons carry the light’s power', () => {
  it('N·ΔΦ = E·A for the widget’s disc (twin trace) and every photon starts with ΔΦ', () => {
    const inputs = { ...DEFAULT_INPUTS, photons: 3000 };
    const set = tracePhotonsCpu(inputs);
    const area = Math.PI * SCENE.diskRadius ** 2;
    expect(set.emittedPower).toBeCloseTo(SCENE.irradiance * area, 12);
    for (let i = 0; i < set.count; i++)
      expect(set.powers[i]).toBe(set.emittedPower / inputs.photons);
    // The glass focuses part of the photons: some collisions come after the sphere.
    expect(Array.from(set.glass).some((g) => g > 0)).toBe(true);
  });
});

/** N photons from a standard-normal blob of scale s around c, each of power 1/N, isotropic. */
function gaussianBlob(n: number, s: number, c: Vec3, seed: number): PhotonSet {
  const positions = new Float64Array(3 * n);
  const directions = new Float64Array(3 * n);
  const state = { value: rngSeed(0, seed) };
  for (let i = 0; i < n; i++) {
    for (let k = 0; k < 3; k += 1) {
      // Box–Muller, one coordinate per pair of uniforms.
      const u1 = 1 - rngNextFloat(state);
      const u2 = rngNextFloat(state);
      positions[3 * i + k] = c[k]! + s * Math.sqrt(-2 * Math.log(u1)) * Math.cos(2 * Math.PI * u2);
    }
    directions.set([0, -1, 0], 3 * i);
  }
  return {
    count: n,
    positions,
    powers: new Float64Array(n).fill(1 / n),
    directions,
    glass: new Uint32Array(n),
    overflow: 0,
    emittedPower: 1,
  };
}

/** P(|X| < r) for X ~ N(0, s²I₃): the χ distribution with 3 degrees of freedom. */
function ballProbability(r: number, s: number): number {
  const x = r / s;
  return erf(x / Math.SQRT2) - Math.sqrt(2 / Math.PI) * x * Math.exp(-0.5 * x * x);
}

function erf(x: number): number {
  // Abramowitz & Stegun 7.1.26 is too coarse here; sum the Maclaurin series (|x| ≤ 3).
  let term = x;
  let sum = x;
  for (let n = 1; n < 200; n++) {
    term *= (-x * x) / n;
    sum += term / (2 * n + 1);
  }
  return (2 / Math.sqrt(Math.PI)) * sum;
}

describe('density estimation of a known photon distribution (volume radiance estimate)', () => {
  it('the estimate at the blob centre converges to the analytic density as r shrinks and N grows', () => {
    // Isotropic phase (g = 0): the estimate is p·Σ ΔΦ K = (1/4π)·(photons in the ball)/(N·V).
    const s = 0.15;
    const centre: Vec3 = [0, 0, 0];
    const density = (2 * Math.PI * s * s) ** -1.5;
    const steps = [
      { n: 2000, r: 0.12 },
      { n: 20000, r: 0.07 },
      { n: 200000, r: 0.035 },
    ];
    const biases: number[] = [];
    const errors: number[] = [];
    for (const [k, { n, r }] of steps.entries()) {
      const set = gaussianBlob(n, s, centre, 11 + k);
      const sorted = buildGridCpu(set, gridFor(r));
      const estimate = gatherCpu(set, sorted, centre, [0, 0, 1], 0, r).sum * 4 * Math.PI;
      const volume = (4 / 3) * Math.PI * r ** 3;
      const p = ballProbability(r, s);
      const mean = p / volume;
      const sd = Math.sqrt((p * (1 - p)) / n) / volume;
      // The estimate is a binomial count: within 5 standard deviations of its exact mean.
      expect(Math.abs(estimate - mean)).toBeLessThan(5 * sd);
      biases.push(Math.abs(mean - density) / density);
      errors.push(Math.abs(estimate - density) / density);
    }
    // The bias (r²/10·∇²ρ/ρ = 3r²/(10 s²) to first order) falls with r …
    expect(biases[0]!).toBeGreaterThan(biases[1]!);
    expect(biases[1]!).toBeGreaterThan(biases[2]!);
    expect(biases[2]!).toBeLessThan(0.02);
    // … and at the largest N with the smallest r the whole error is small.
    expect(errors[2]!).toBeLessThan(0.05);
  });
});

describe('progressive radius schedule r_k = r₀ (N_k/N₀)^(−1/7)', () => {
  it('passes through (N₀, r₀), halves per 128× photons and balances bias² against variance', () => {
    expect(progressiveRadius(0.04, 65536, 65536)).toBe(0.04);
    expect(progressiveRadius(0.04, 4096, 4096 * 128)).toBeCloseTo(0.02, 12);
    expect(progressiveRadius(0.04, 65536, 4096)).toBeCloseTo(0.04 * 16 ** (1 / 7), 12);
    // Chapter 10, "Bias versus variance": MSE = a·r⁴ + b/(N r³). Along the schedule
    // N r⁷ is constant, so both terms fall as N^(−4/7) and the RMSE as N^(−2/7).
    const counts = [4096, 16384, 65536, 262144];
    const radii = counts.map((n) => progressiveRadius(0.06, 4096, n));
    for (const [k, n] of counts.entries())
      expect(n * radii[k]! ** 7).toBeCloseTo(4096 * 0.06 ** 7, 15);
    const rmse = counts.map((n, k) => Math.sqrt(3 * radii[k]! ** 4 + 2e-9 / (n * radii[k]! ** 3)));
    const slope = Math.log(rmse[3]! / rmse[0]!) / Math.log(counts[3]! / counts[0]!);
    expect(slope).toBeCloseTo(-2 / 7, 12);
  });
});

describe('the uniform grid returns exactly the photons within r', () => {
  const radius = 0.05;
  const set = gaussianBlob(6000, 0.25, [0.1, -0.1, 0], 5);
  // Keep the blob inside the box, where the grid lies.
  const inside: number[] = [];
  for (let i = 0; i < set.count; i++) {
    const p = [0, 1, 2].map((k) => set.positions[3 * i + k]!);
    if (p.every((v, k) => v > SCENE.boxMin[k]! && v < SCENE.boxMax[k]!)) inside.push(i);
  }
  const photons: PhotonSet = {
    ...set,
    count: inside.length,
    positions: Float64Array.from(
      inside.flatMap((i) => [0, 1, 2].map((k) => Math.fround(set.positions[3 * i + k]!))),
    ),
    powers: Float64Array.from(inside.map((i) => Math.fround(set.powers[i]!))),
    directions: Float64Array.from(inside.flatMap(() => [0, -1, 0])),
    glass: new Uint32Array(inside.length),
  };
  const queryState = { value: rngSeed(3, 3) };
  const queries: Vec3[] = Array.from(
    { length: 96 },
    () =>
      [0, 1, 2].map((k) =>
        Math.fround(
          0.1 * (k === 1 ? -1 : k === 0 ? 1 : 0) + 0.5 * (rngNextFloat(queryState) - 0.5),
        ),
      ) as unknown as Vec3,
  );

  it('CPU twin: the counting-sorted grid equals brute force at every query', () => {
    const sorted = buildGridCpu(photons, gridFor(radius));
    for (const q of queries) {
      const grid = gatherCpu(photons, sorted, q, [0, 0, 1], 0.3, radius);
      const brute = bruteForceCpu(photons, q, [0, 0, 1], 0.3, radius);
      expect(grid.found).toBe(brute.found);
      expect(grid.sum).toBeCloseTo(brute.sum, 9);
    }
  });

  it('GPU: histogram, prefix sum and scatter, then the query, equal brute force', async () => {
    const device = await nodeDevice();
    const code = await linkLibraryKernel(SHADER_LIBRARY, 'kernels/photon-map.wesl');
    const records = new Float32Array(photons.count * RECORD_WORDS);
    for (let i = 0; i < photons.count; i++)
      records.set(
        [...photons.positions.subarray(3 * i, 3 * i + 3), photons.powers[i]!, 0, -1, 0, 0],
        i * RECORD_WORDS,
      );
    const queryData = new Float32Array(queries.flatMap((q) => [...q, 0, 0, 1]));
    const result = await renderPhotonMapGpu(
      device,
      code,
      { ...DEFAULT_INPUTS, g: 0.3, radius },
      8,
      8,
      1,
      {
        photonsIn: records,
        queries: queryData,
        skipImage: true,
      },
    );
    expect(result.stored).toBe(photons.count);
    let total = 0;
    queries.forEach((q, k) => {
      const brute = bruteForceCpu(photons, q, [0, 0, 1], 0.3, radius);
      // Photons within f32 rounding of the sphere |x − q| = r may fall either way.
      const margin =
        bruteForceCpu(photons, q, [0, 0, 1], 0.3, radius * (1 + 1e-5)).found -
        bruteForceCpu(photons, q, [0, 0, 1], 0.3, radius * (1 - 1e-5)).found;
      expect(Math.abs(result.queries[2 * k + 1]! - brute.found)).toBeLessThanOrEqual(margin);
      if (margin === 0) expect(result.queries[2 * k]!).toBeCloseTo(brute.sum, 1);
      total += brute.found;
    });
    // The queries do find photons (the test is not vacuous).
    expect(total).toBeGreaterThan(100);
  });
});

describe('consistency without caustics (η = 1): photon map = path tracer within error', () => {
  it('at four pixels, |L_pm − L_pt| ≤ 4·SE + the bias bound of the radius', () => {
    const inputs = { ...DEFAULT_INPUTS, eta: 1, radius: 0.05 };
    const width = 16;
    const height = 12;
    // Pixels whose rays cross the lit fog below and beside the (now invisible) sphere.
    const pixels = [6 * width + 4, 7 * width + 8, 9 * width + 11, 4 * width + 12];
    const maps = 4;
    const pm: number[][] = pixels.map(() => []);
    for (let m = 0; m < maps; m++) {
      const set = tracePhotonsCpu({ ...inputs, photons: 100000, seed: 100 + m });
      const sorted = buildGridCpu(set, gridFor(inputs.radius));
      const image = photonMapImageCpu(inputs, set, sorted, width, height, 8, 7 + m, pixels);
      pixels.forEach((p, k) => pm[k]!.push(image[p]!));
    }
    const spp = 4000;
    const pt = pathTraceCpu(inputs, width, height, spp, 9, pixels);
    pixels.forEach((p, k) => {
      const ptMean = pt.sum[p]! / spp;
      const ptSe = Math.sqrt(Math.max(0, pt.sumSq[p]! / spp - ptMean ** 2) / (spp - 1));
      const values = pm[k]!;
      const pmMean = values.reduce((a, b) => a + b, 0) / maps;
      const pmSe = Math.sqrt(values.reduce((a, b) => a + (b - pmMean) ** 2, 0) / (maps - 1) / maps);
      // Bias of the radius: the kernel ball reaches out of the fog where the ray enters
      // and leaves it; averaged over a ray of length ℓ in the fog it loses
      // 2·∫₀^r V_cap(d)/V dd / ℓ = 0.375·r/ℓ = 1.9 % (r = 5 cm, ℓ = 1 m), and the
      // curvature of the lighting adds r²/10·∇²L/L ≈ σt²r²/10 < 0.1 %; allowed 3 %.
      // The photon maps' own noise is the spread of 4 independent maps.
      const bound = 4 * Math.hypot(ptSe, pmSe) + 0.03 * ptMean;
      expect(Math.abs(pmMean - ptMean)).toBeLessThan(bound);
    });
  });
});

describe('the GPU gather in bands of rows (issue 23)', () => {
  it('every row of a many-band image is the twin’s row: the same photons, the same random numbers', async () => {
    const inputs = { ...DEFAULT_INPUTS, photons: 20000, seed: 5 };
    const set = tracePhotonsCpu(inputs);
    const sorted = buildGridCpu(set, gridFor(inputs.radius));
    const records = new Float32Array(set.count * RECORD_WORDS);
    const words = new Uint32Array(records.buffer);
    for (let i = 0; i < set.count; i++) {
      records.set(
        [
          ...set.positions.subarray(3 * i, 3 * i + 3),
          set.powers[i]!,
          ...set.directions.subarray(3 * i, 3 * i + 3),
        ],
        i * RECORD_WORDS,
      );
      words[i * RECORD_WORDS + 7] = set.glass[i]!;
    }
    const width = 16;
    const height = 28; // bands of 8, 8, 8 and 4 rows
    const device = await nodeDevice();
    const code = await linkLibraryKernel(SHADER_LIBRARY, 'kernels/photon-map.wesl');
    const gpu = await renderPhotonMapGpu(device, code, inputs, width, height, 1, {
      photonsIn: records,
      bandRows: 8,
    });
    const twin = photonMapImageCpu(inputs, set, sorted, width, height, 1, inputs.seed);
    let lit = 0;
    for (let row = 0; row < height; row++) {
      let difference = 0;
      let scale = 0;
      for (let x = 0; x < width; x++) {
        const p = row * width + x;
        difference += Math.abs(gpu.image[p]! - twin[p]!);
        scale += Math.abs(twin[p]!);
      }
      // f32 against float64 marching: a rare step may round the other way.
      expect(difference, `row ${row}`).toBeLessThanOrEqual(0.02 * scale + 1e-6);
      if (scale > 0) lit += 1;
    }
    expect(lit).toBeGreaterThan(height / 2);
    const abort = new AbortController();
    abort.abort();
    await expect(
      renderPhotonMapGpu(device, code, inputs, width, height, 1, {
        photonsIn: records,
        signal: abort.signal,
        bandRows: 8,
      }),
    ).rejects.toMatchObject({ name: 'AbortError' });
  });
});
