// Runs of the slab Monte Carlo (src/subsurface/slabKernel.ts) for the published
// benchmarks of physics.md §7, and the bound a run must meet: the distance to the
// published value within Z_BOUND standard errors of the run's own batch spread, plus
// half a unit in the last published digit (the published value's own rounding).
import { expect } from 'vitest';
import {
  planBatches,
  type ChannelEstimate,
  type SlabRun,
} from '../../src/subsurface/slabKernel.ts';
import type { SlabBenchmark } from './subsurfaceTables.ts';

/**
 * 5 standard errors: two-sided p ≈ 5.7e-7 per check under the null hypothesis (the batch
 * standard error itself is estimated from ≥ 64 batches, so its own relative error is ≤ 9%
 * and the effective bound stays above 4.5σ, p ≤ 7e-6).
 */
export const Z_BOUND = 5;

export function benchmarkRun(
  benchmark: SlabBenchmark,
  photons: number,
  seed: number,
  incidenceCos = benchmark.incidenceCos,
): SlabRun {
  return {
    channels: [{ sigmaA: benchmark.sigmaA, sigmaS: benchmark.sigmaS }],
    g: benchmark.g,
    thickness: benchmark.thickness,
    eta: benchmark.eta,
    incidenceCos,
    maxCollisions: 65536,
    seed,
    threadOffset: 0,
    profile: { bins: 32, rMin: 1e-3, rMax: 10 },
    ...planBatches(photons),
  };
}

export interface Comparison {
  value: number;
  se: number;
  published: number;
  z: number;
}

/**
 * |MC − published| ≤ Z_BOUND·SE + half a unit in the published value's last decimal
 * (`decimals` places, e.g. 4 for Giovanelli's 0.2600); returns the z-score.
 */
export function expectMatches(
  estimate: { mean: number; se: number },
  published: number,
  decimals: number,
  what: string,
): Comparison {
  const bound = Z_BOUND * estimate.se + 0.5 * 10 ** -decimals;
  const z = (estimate.mean - published) / estimate.se;
  expect(estimate.se, `${what}: a standard error was measured`).toBeGreaterThan(0);
  expect(
    Math.abs(estimate.mean - published),
    `${what}: MC ${estimate.mean} ± ${estimate.se} vs published ${published} (z = ${z.toFixed(2)}, bound ${bound})`,
  ).toBeLessThanOrEqual(bound);
  return { value: estimate.mean, se: estimate.se, published, z };
}

/** Checks a benchmark's reflectance (with or without R_sp, as published) and transmittance. */
export function expectBenchmark(benchmark: SlabBenchmark, estimate: ChannelEstimate): void {
  const reflectance = benchmark.includesSpecular
    ? estimate.totalReflectance
    : estimate.diffuseReflectance;
  expectMatches(
    reflectance,
    benchmark.reflectance,
    benchmark.decimals,
    `${benchmark.name}, reflectance`,
  );
  if (benchmark.transmittance !== undefined)
    expectMatches(
      estimate.transmittance,
      benchmark.transmittance,
      benchmark.decimals,
      `${benchmark.name}, Tt`,
    );
  else expect(estimate.transmittance.mean, 'a half-space transmits nothing').toBe(0);
  expect(estimate.capped, 'no walk reached the cap').toBe(0);
}
