// Hard cases of the chromatic free flights (shaders/chromatic.wesl) on the GPU and the twin:
// a channel with σt = 0, a channel 100× (and 10^6×) thicker than the others, albedo 0 and 1,
// and the lookup cap, which must be counted, never silent (physics.md §4.5). Every estimate
// must be finite (WGSL may assume no NaN or Inf, §10) and, where a closed form exists,
// unbiased: |mean − exact| < 5·sqrt(s²/N) per channel (fixed seeds, p ≈ 5.7e-7 per check).
import { describe, expect, it } from 'vitest';
import type { ChromaticMedium, Rgb } from '../../src/reference/chromatic.ts';
import { rngSeed } from '../../src/reference/rng.ts';
import { moments } from '../support/statistics.ts';
import { gpuChromaticWalks } from '../support/chromaticGpu.ts';
import {
  CHROMATIC_ESTIMATORS,
  chromaticSlabExpectations,
  twinChromaticWalker,
  type ChromaticWalk,
} from '../support/chromaticWalks.ts';

const WALKS = 1 << 14;

const medium = (sigmaT: Rgb, albedo: Rgb): ChromaticMedium => ({
  sigmaT,
  albedo,
  densityBase: 1,
  densitySlope: 0,
});

const finite = (walks: ChromaticWalk[]): boolean =>
  walks.every((w) => [...w.T, ...w.S].every(Number.isFinite));

function expectUnbiased(walks: ChromaticWalk[], m: ChromaticMedium, d: number): void {
  const exact = chromaticSlabExpectations(m, d);
  for (const key of ['T', 'S'] as const) {
    for (let c = 0; c < 3; c++) {
      const s = moments(walks.map((w) => w[key][c]!));
      const bound = 5 * Math.sqrt(s.variance / s.n) + 1e-6;
      expect(
        Math.abs(s.mean - exact[key][c]!),
        `${key}[${c}] mean ${s.mean} vs ${exact[key][c]} (bound ${bound})`,
      ).toBeLessThan(bound);
    }
  }
}

const CASES: [string, ChromaticMedium][] = [
  ['a channel with σt = 0', medium([0, 2, 8], [0.9, 0.7, 0.5])],
  ['a channel 100× thicker', medium([0.02, 0.02, 2], [0.9, 0.9, 0.9])],
  ['albedo 0 in every channel', medium([0.5, 2, 8], [0, 0, 0])],
  ['albedo 1 in every channel', medium([0.5, 2, 8], [1, 1, 1])],
];

describe('chromatic hard cases: finite and unbiased on the GPU', () => {
  for (const [name, m] of CASES) {
    for (const estimator of CHROMATIC_ESTIMATORS) {
      it(`${estimator}: ${name}`, async () => {
        const walks = await gpuChromaticWalks(estimator, m, 1, 5, WALKS);
        expect(finite(walks)).toBe(true);
        expectUnbiased(walks, m, 1);
        if (m.sigmaT[0] === 0 && estimator === 'oneChannel') {
          // A channel that cannot collide passes every time, without a lookup of its own.
          expect(walks.every((w) => w.T[0] === 1 && w.S[0] === 0)).toBe(true);
        }
        if (m.albedo.every((a) => a === 0)) {
          // Albedo 0: no estimator may report a scattering weight.
          expect(walks.every((w) => w.S.every((x) => x === 0))).toBe(true);
        }
      }, 60_000);
    }
  }

  it('a channel 10^6× thicker (σt = 1e6/m, d = 1 mm): hero and spectral weights stay finite', async () => {
    // d = 1 mm keeps spectral tracking's σ̄d = 1000 null collisions per flight affordable;
    // the blue optical depth 1000 is still far beyond f32's e^-104.
    const m = medium([1, 1, 1e6], [0.9, 0.9, 0.9]);
    for (const estimator of CHROMATIC_ESTIMATORS) {
      const walks = await gpuChromaticWalks(estimator, m, 1e-3, 9, 4096);
      expect(finite(walks), estimator).toBe(true);
      // T_b = e^-1000 = 0 in f32 and float64: no walk may transmit blue.
      expect(walks.every((w) => w.T[2] === 0)).toBe(true);
    }
  }, 60_000);

  it('the lookup cap is counted on the GPU and in the twin, and a capped flight passes', async () => {
    // σ̄ d = 8 tentative collisions on average (spectral) with a cap of 2 lookups.
    const m = medium([0.5, 2, 8], [1, 1, 1]);
    for (const estimator of ['spectralAverage', 'spectralMax'] as const) {
      const walks = await gpuChromaticWalks(estimator, m, 1, 2, 4096, 2);
      const twin = twinChromaticWalker({ estimator, medium: m, d: 1, maxSteps: 2 });
      let twinCapped = 0;
      for (let i = 0; i < 4096; i++) twinCapped += twin({ value: rngSeed(i, 2) }).capped;
      const gpuCapped = walks.reduce((n, w) => n + w.capped, 0);
      expect(gpuCapped, estimator).toBeGreaterThan(100);
      expect(Math.abs(gpuCapped - twinCapped)).toBeLessThanOrEqual(0.01 * 4096);
      expect(walks.every((w) => w.lookups <= 2)).toBe(true);
      expect(finite(walks)).toBe(true);
    }
  }, 60_000);
});
