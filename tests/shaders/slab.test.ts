// The slab Monte Carlo on the GPU (physics.md §7): the WGSL helpers of shaders/slab.wesl
// against their twins; single walks drawn from the same seeds on both sides (the stream
// is identical, so nearly every walk takes the same path); and the kernel
// shaders/kernels/slab.wesl against the published benchmarks A (van de Hulst slab),
// B (Giovanelli half-space, n = 1.5) and C (the H-function half-space, also at oblique
// incidence), each within 5 standard errors of its own batch spread, with fixed seeds.
import { beforeAll, describe, expect, it } from 'vitest';
import {
  describeShaderFunction,
  evaluateTable,
  type CaseOutcome,
} from '../support/shaderHarness.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { rngSeed } from '../../src/reference/rng.ts';
import {
  SLAB_EXIT_ABSORBED,
  SLAB_EXIT_BOTTOM,
  SLAB_EXIT_TOP,
  slabDistanceToBoundary,
  slabEntryDirection,
  slabPhotonWalk,
  slabProfileBin,
  slabProfileBinEdge,
  slabRadius,
  slabSpecularReflectance,
} from '../../src/reference/slab.ts';
import {
  runSlabCpu,
  runSlabGpu,
  summarize,
  type ChannelEstimate,
  type SlabRun,
} from '../../src/subsurface/slabKernel.ts';
import { benchmarkRun, expectBenchmark, expectMatches } from '../support/slabBenchmarks.ts';
import { SLAB_BENCHMARKS } from '../support/subsurfaceTables.ts';
import { halfSpaceReflectance } from '../support/hFunction.ts';

const F32_MAX = 3.4028234663852886e38;

describeShaderFunction({
  module: 'slab',
  fn: 'slabSpecularReflectance',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: slabSpecularReflectance,
  tolerance: { relative: 2e-6, absolute: 1e-7, reason: 'fresnelDielectric (fresnel.test.ts)' },
  cases: [
    { name: 'η = 1.5, normal incidence: R_sp = 0.04 (§7 B)', args: [1.5, 1], expected: 0.04 },
    { name: 'matched boundary: 0', args: [1, 0.3], expected: 0 },
    { name: 'η = 1.3, μ0 = 0.5', args: [1.3, 0.5] },
  ],
});

describeShaderFunction({
  module: 'slab',
  fn: 'slabEntryDirection',
  args: ['f32', 'f32'],
  result: 'vec3f',
  twin: (eta: number, mu: number) => [...slabEntryDirection(eta, mu)],
  tolerance: { absolute: 3e-7, reason: 'two square roots and a division of unit-size values' },
  cases: [
    { name: 'normal incidence goes straight in', args: [1.5, 1], expected: [0, 0, 1] },
    { name: 'η = 1.5, μ0 = 0.5: Snell', args: [1.5, 0.5] },
    { name: 'matched, μ0 = 0.2: unrefracted', args: [1, 0.2] },
    {
      name: 'η = 0.7, grazing: total reflection, sin θt clamped to 1',
      args: [0.7, 0],
      expected: [1, 0, 0],
    },
  ],
});

describeShaderFunction({
  module: 'slab',
  fn: 'slabDistanceToBoundary',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: slabDistanceToBoundary,
  tolerance: { ulps: 3, reason: 'one subtraction and one division (2.5 ULP)' },
  cases: [
    { name: 'up from z = 0.3 at uz = −0.5: 0.6', args: [0.3, -0.5, 1], expected: 0.6 },
    { name: 'down to the bottom of a slab of thickness 1', args: [0.3, 0.5, 1], expected: 1.4 },
    { name: 'down in a half-space: never', args: [0.3, 0.5, F32_MAX], expected: F32_MAX },
    { name: 'uz = 0: never', args: [0.3, 0, 1], expected: F32_MAX },
    {
      name: 'uz = −1e-38 from z = 1e3: would overflow, never',
      args: [1e3, -1e-38, 1],
      expected: F32_MAX,
    },
  ],
});

describeShaderFunction({
  module: 'slab',
  fn: 'slabRadius',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: slabRadius,
  tolerance: { ulps: 4, reason: 'two divisions, a sqrt and a product' },
  cases: [
    { name: '(3, 4) → 5', args: [3, 4], expected: 5 },
    { name: '(0, 0) → 0', args: [0, 0], expected: 0 },
    { name: '(1e30, −1e30) → √2·1e30: x² would overflow f32', args: [1e30, -1e30] },
    { name: '(1e-30, 2e-30): x² would underflow', args: [1e-30, 2e-30] },
  ],
});

describeShaderFunction({
  module: 'slab',
  fn: 'slabProfileBin',
  args: ['f32', 'f32', 'f32', 'u32'],
  result: 'u32',
  twin: slabProfileBin,
  tolerance: { ulps: 0, reason: 'an integer' },
  cases: [
    { name: 'r = 0 is bin 0', args: [0, 0.01, 100, 33], expected: 0 },
    {
      name: 'r = 0.1 of [0.01, 100) in 32 log bins: bin 9',
      args: [0.1, 0.01, 100, 33],
      expected: 9,
    },
    { name: 'r = 5', args: [5, 0.01, 100, 33] },
    { name: 'r = rMax: none (bins)', args: [100, 0.01, 100, 33], expected: 33 },
    { name: 'just below rMax: the last bin', args: [99.99, 0.01, 100, 33], expected: 32 },
    { name: 'bins = 100 is clamped to 64', args: [50, 0.01, 100, 100] },
  ],
});

describeShaderFunction({
  module: 'slab',
  fn: 'slabProfileBinEdge',
  args: ['u32', 'f32', 'f32', 'u32'],
  result: 'f32',
  twin: slabProfileBinEdge,
  tolerance: { relative: 3e-6, reason: 'exp of ≤ ln(1e4) = 9.2: 21 ULP, and a log' },
  cases: [
    { name: 'edge 0 is 0', args: [0, 0.01, 100, 33], expected: 0 },
    { name: 'edge 1 is rMin', args: [1, 0.01, 100, 33], expected: 0.01 },
    { name: 'edge 9 is 0.1', args: [9, 0.01, 100, 33], expected: 0.1 },
    { name: 'edge bins is rMax', args: [33, 0.01, 100, 33], expected: 100 },
  ],
});

// ---------------------------------------------------------------------------
// Single walks from the same seeds: GPU (f32) and twin (float64) draw the same stream.
// ---------------------------------------------------------------------------
const WALK_WRAPPER = {
  imports: ['SlabSetup', 'slabPhotonWalk'],
  wgsl: `fn caseUnderTest(sigmaA: f32, sigmaS: f32, g: f32, thickness: f32, eta: f32, mu0: f32, seed: u32) -> vec4f {
  var state = package::rng::rngSeed(seed, 0u);
  let r = slabPhotonWalk(SlabSetup(sigmaA, sigmaS, g, thickness, eta, mu0, 65536u), &state);
  return vec4f(f32(r.exit), r.weight, r.radius, f32(r.collisions));
}`,
};
const walkTwin = (
  sigmaA: number,
  sigmaS: number,
  g: number,
  thickness: number,
  eta: number,
  mu0: number,
  seed: number,
): number[] => {
  const r = slabPhotonWalk(
    { sigmaA, sigmaS, g, thickness, eta, incidenceCos: mu0, maxCollisions: 65536 },
    { value: rngSeed(seed, 0) },
  );
  return [r.exit, r.weight, r.radius, r.collisions];
};

describe('slabPhotonWalk: the same seeds on the GPU and in the twin', () => {
  const setups = [
    { name: 'benchmark A slab (g = 0.75, τ = 2, matched)', args: [10, 90, 0.75, 0.02, 1, 1] },
    { name: 'benchmark B half-space (n = 1.5)', args: [10, 90, 0, F32_MAX, 1.5, 1] },
    {
      name: 'skin-like half-space, oblique (μ0 = 0.6, g = 0.8)',
      args: [0.5, 5, 0.8, F32_MAX, 1.3, 0.6],
    },
  ];
  const WALKS = 512;
  const outcomes: CaseOutcome[][] = [];
  beforeAll(async () => {
    for (const setup of setups)
      outcomes.push(
        await evaluateTable({
          module: 'slab',
          fn: 'slabPhotonWalk',
          args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32', 'u32'],
          result: 'vec4f',
          wrapper: WALK_WRAPPER,
          twin: walkTwin,
          tolerance: { relative: 0, reason: 'compared statistically below' },
          cases: Array.from({ length: WALKS }, (_, seed) => ({
            name: `seed ${seed}`,
            args: [...setup.args, seed],
          })),
        }),
      );
  }, 60_000);

  setups.forEach((setup, s) => {
    it(`${setup.name}: ≥ 97% of ${WALKS} walks end alike; those agree in weight and radius to 1e-3`, () => {
      const results = outcomes[s]!;
      let same = 0;
      for (const { gpu, twin } of results) {
        for (const value of gpu) expect(Number.isFinite(value)).toBe(true);
        if (gpu[0] !== twin[0] || gpu[3] !== twin[3]) continue;
        same += 1;
        // The paths agree; f32 rounding of positions and weights stays small along them.
        expect(Math.abs(gpu[1]! - twin[1]!)).toBeLessThanOrEqual(1e-3 * Math.max(twin[1]!, 1e-3));
        expect(Math.abs(gpu[2]! - twin[2]!)).toBeLessThanOrEqual(1e-3 * Math.max(twin[2]!, 1e-4));
      }
      // A path diverges only when f32 and float64 fall on opposite sides of a comparison
      // (free path vs boundary distance, a Fresnel or roulette draw): rare, not never.
      expect(same / results.length).toBeGreaterThanOrEqual(0.97);
      const exits = new Set(results.map((r) => r.gpu[0]));
      expect(
        [...exits].every((e) => [SLAB_EXIT_TOP, SLAB_EXIT_BOTTOM, SLAB_EXIT_ABSORBED].includes(e!)),
      ).toBe(true);
    });
  });
});

// ---------------------------------------------------------------------------
// The kernel against the published benchmarks (physics.md §7)
// ---------------------------------------------------------------------------
describe('the slab kernel reproduces the published benchmarks (physics.md §7), fixed seeds, 5σ', () => {
  const photons = [1 << 16, 1 << 15, 1 << 15];
  const estimates: ChannelEstimate[] = [];
  let oblique: ChannelEstimate | null = null;
  let obliqueRun: SlabRun | null = null;
  beforeAll(async () => {
    const device = await nodeDevice();
    for (const [k, benchmark] of SLAB_BENCHMARKS.entries()) {
      const run = benchmarkRun(benchmark, photons[k]!, 2024 + k);
      estimates.push(summarize(run, (await runSlabGpu(device, SHADER_LIBRARY, run)).batches)[0]!);
    }
    obliqueRun = benchmarkRun(SLAB_BENCHMARKS[2]!, 1 << 15, 77, 0.5);
    oblique = summarize(
      obliqueRun,
      (await runSlabGpu(device, SHADER_LIBRARY, obliqueRun)).batches,
    )[0]!;
  }, 120_000);

  SLAB_BENCHMARKS.forEach((benchmark, k) => {
    it(`${benchmark.name}: ${benchmark.source}`, () => {
      const estimate = estimates[k]!;
      expect(estimate.photons).toBeGreaterThanOrEqual(photons[k]!);
      expect(estimate.batches).toBeGreaterThanOrEqual(64);
      expectBenchmark(benchmark, estimate);
    });
  });

  it('benchmark A: the unscattered transmittance is e^{−τ} = e^{−2} = 0.135335 (§7)', () => {
    expectMatches(estimates[0]!.unscattered, Math.exp(-2), 8, 'T_u');
  });

  it('benchmark B: the specular part is exactly R_sp = 0.04 (§7)', () => {
    expect(estimates[1]!.specular).toBeCloseTo(0.04, 7);
  });

  it('benchmark C at oblique incidence μ0 = 0.5: R = 1 − H(0.5)√(1 − ϖ) = 0.507939 (H by iteration)', () => {
    const exact = halfSpaceReflectance(0.9, 0.5);
    expect(exact).toBeCloseTo(0.5079389, 6);
    expectMatches(oblique!.diffuseReflectance, exact, 8, 'R(μ0 = 0.5)');
  });

  it('the radial profile accounts for every reflected photon inside r_max (Σ density·area = R_d)', () => {
    for (const estimate of [estimates[1]!, estimates[2]!, oblique!]) {
      const { edges, density } = estimate.profile;
      const binned = density.reduce(
        (sum, bin, k) => sum + bin.mean * Math.PI * (edges[k + 1]! ** 2 - edges[k]! ** 2),
        0,
      );
      // r_max = 10 cm is 1000 mean free paths: no packet leaves beyond it.
      expect(binned / estimate.diffuseReflectance.mean).toBeCloseTo(1, 5);
    }
  });

  it('the GPU and the twin replay the same walks: benchmark A batches agree closely', () => {
    const run = benchmarkRun(SLAB_BENCHMARKS[0]!, 1 << 13, 2024);
    const cpu = summarize(run, runSlabCpu(run))[0]!;
    // Same streams, so the two estimates differ far less than their standard error.
    return (async () => {
      const device = await nodeDevice();
      const gpu = summarize(run, (await runSlabGpu(device, SHADER_LIBRARY, run)).batches)[0]!;
      expect(Math.abs(gpu.diffuseReflectance.mean - cpu.diffuseReflectance.mean)).toBeLessThan(
        0.2 * cpu.diffuseReflectance.se,
      );
      expect(Math.abs(gpu.transmittance.mean - cpu.transmittance.mean)).toBeLessThan(
        0.2 * cpu.transmittance.se,
      );
    })();
  });
});
