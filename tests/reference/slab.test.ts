// The float64 twin of the slab Monte Carlo (src/reference/slab.ts, replayed batch by
// batch by src/subsurface/slabKernel.ts) against the published benchmarks of
// physics.md §7 with fixed seeds and bounds of 5 standard errors from its own batch
// spread; the H-function reference behind benchmark C; and the estimator's
// bookkeeping: the ratio standard error, appended runs, the specular and unscattered
// parts and the conservation of energy in a non-absorbing slab.
import { describe, expect, it } from 'vitest';
import { chandrasekharH } from '../support/hFunction.ts';
import { benchmarkRun, expectBenchmark, expectMatches } from '../support/slabBenchmarks.ts';
import { SLAB_BENCHMARKS } from '../support/subsurfaceTables.ts';
import {
  appendBatches,
  planBatches,
  ratioEstimate,
  runSlabCpu,
  runSlabCpuBatches,
  summarize,
  type SlabRun,
} from '../../src/subsurface/slabKernel.ts';
import {
  SLAB_EXIT_CAPPED,
  slabPhotonWalk,
  slabSpecularReflectance,
} from '../../src/reference/slab.ts';

describe('the twin reproduces the published benchmarks (physics.md §7), fixed seeds, 5σ', () => {
  const photons = [1 << 15, 1 << 14, 1 << 14];
  SLAB_BENCHMARKS.forEach((benchmark, k) => {
    it(`${benchmark.name}, ${photons[k]} photons`, () => {
      const run = benchmarkRun(benchmark, photons[k]!, 11 + k);
      expectBenchmark(benchmark, summarize(run, runSlabCpu(run))[0]!);
    });
  });

  it('benchmark C rests on H(1; ϖ = 0.9) = 1.8500985168 (physics.md §7 C)', () => {
    expect(chandrasekharH(0.9)(1)).toBeCloseTo(1.8500985168, 9);
  });
});

describe('estimator bookkeeping', () => {
  it('the ratio standard error of equal batches is the standard error of the batch means', () => {
    const sums = [3, 5, 4, 8, 6];
    const walks = sums.map(() => 10);
    const means = sums.map((s) => s / 10);
    const mean = means.reduce((a, b) => a + b) / means.length;
    const sd = Math.sqrt(means.reduce((a, m) => a + (m - mean) ** 2, 0) / (means.length - 1));
    const estimate = ratioEstimate(sums, walks);
    expect(estimate.mean).toBeCloseTo(mean, 14);
    expect(estimate.se).toBeCloseTo(sd / Math.sqrt(means.length), 14);
  });

  it('a progressive run (two dispatches, the second with a thread offset) equals one run of both halves', () => {
    const base: SlabRun = {
      ...benchmarkRun(SLAB_BENCHMARKS[0]!, 1 << 12, 5),
      photonsPerThread: 4,
      batches: 16,
    };
    const whole = runSlabCpu({ ...base, batches: 32 });
    const first = runSlabCpu(base);
    const second = runSlabCpu({ ...base, threadOffset: 16 * 64 });
    const joined = appendBatches(first, second);
    expect(joined.channels[0]!.reflected).toEqual(whole.channels[0]!.reflected);
    // Batches [16, 32) of the whole run are the second dispatch.
    expect(runSlabCpuBatches(base, 16, 32).channels[0]!.transmitted).toEqual(
      second.channels[0]!.transmitted,
    );
  });

  it('no absorption, matched slab: R_d + T_t = 1 for every batch (energy is conserved)', () => {
    const run: SlabRun = {
      channels: [{ sigmaA: 0, sigmaS: 10 }],
      g: 0.5,
      thickness: 0.3,
      eta: 1,
      incidenceCos: 0.7,
      maxCollisions: 65536,
      seed: 3,
      threadOffset: 0,
      profile: { bins: 8, rMin: 0.01, rMax: 1 },
      ...planBatches(4096),
    };
    const batches = runSlabCpu(run).channels[0]!;
    batches.walks.forEach((n, b) =>
      expect((batches.reflected[b]! + batches.transmitted[b]!) / n).toBeCloseTo(1, 12),
    );
  });

  it('with a Fresnel boundary the specular part is added to the diffuse one, and the unscattered beam follows the two faces’ reflections', () => {
    const run: SlabRun = {
      channels: [{ sigmaA: 1, sigmaS: 1 }],
      g: 0,
      thickness: 0.5,
      eta: 1.5,
      incidenceCos: 1,
      maxCollisions: 65536,
      seed: 9,
      threadOffset: 0,
      profile: { bins: 8, rMin: 0.01, rMax: 1 },
      ...planBatches(1 << 14),
    };
    const estimate = summarize(run, runSlabCpu(run))[0]!;
    expect(estimate.specular).toBeCloseTo(0.04, 7);
    expect(estimate.totalReflectance.mean).toBeCloseTo(estimate.diffuseReflectance.mean + 0.04, 12);
    // Unscattered: enters with 1 − R (R = 0.04 at normal incidence), crosses τ = 1 and
    // leaves with probability 1 − R; a packet reflected at the bottom and again at the
    // top crosses twice more, so T_u = (1 − R)² e^{−τ} Σ_k (R² e^{−2τ})^k.
    const R = 0.04;
    const exact = ((1 - R) ** 2 * Math.exp(-1)) / (1 - R * R * Math.exp(-2));
    expectMatches(estimate.unscattered, exact, 9, 'T_u through two n = 1.5 faces');
  });

  it('the cap stops a conservative half-space walk and reports the weight it still carries', () => {
    const capped = slabPhotonWalk(
      { sigmaA: 0, sigmaS: 1, g: 0, thickness: 1e30, eta: 1.3, incidenceCos: 1, maxCollisions: 3 },
      { value: 12345 },
    );
    // Three free flights cannot bring the packet back through an n = 1.3 surface every time;
    // whenever it has not left, it is capped with all the weight it entered with (σa = 0).
    const entered = 1 - slabSpecularReflectance(1.3, 1);
    if (capped.exit === SLAB_EXIT_CAPPED) expect(capped.weight).toBeCloseTo(entered, 15);
    const run: SlabRun = {
      channels: [{ sigmaA: 0, sigmaS: 1 }],
      g: 0,
      thickness: Infinity,
      eta: 1.3,
      incidenceCos: 1,
      maxCollisions: 16,
      seed: 1,
      threadOffset: 0,
      profile: { bins: 8, rMin: 0.01, rMax: 100 },
      ...planBatches(2048),
    };
    const estimate = summarize(run, runSlabCpu(run))[0]!;
    expect(estimate.capped).toBeGreaterThan(0);
    // σa = 0: every packet leaves or is capped with its whole weight 1 − R_sp.
    // (The run rounds η to f32 as the GPU sees it.)
    expect(estimate.diffuseReflectance.mean + estimate.cappedWeight).toBeCloseTo(
      1 - slabSpecularReflectance(Math.fround(1.3), 1),
      12,
    );
  });
});
