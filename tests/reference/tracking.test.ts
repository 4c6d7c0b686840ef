// The float64 tracking twin against the closed forms of physics.md §4: free-flight
// sampling (§1), the means, variances and costs of delta, ratio and residual ratio
// tracking, the structure of unbiased ray marching (E[N], the comb-size table, zero
// variance for constant σt), the §4.5 failure modes, and the closed-form helpers.
//
// Statistics: fixed seeds (rngSeed(walk, frame), one frame per experiment). A mean
// passes when |mean − T| < 5·sqrt(Var/N) (two-sided p ≈ 5.7e-7 per check, so the
// ~40 such checks of this file together stay far below 0.01, Bonferroni). A sample
// variance passes when it is within 5 standard errors of the closed form, the
// standard error from the 4th-moment formula SE² = (μ4 − σ⁴(N−3)/(N−1))/N with the
// sample's own μ4. The two chi-square tests use α = 0.01/2 each (Bonferroni).
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  FREE_FLIGHT_NEVER,
  TRACKING_MAX_STEPS,
  URM_MAX_ORDER,
  deltaTrackingVariance,
  expectedDeltaTrackingLookups,
  expectedRatioTrackingLookups,
  nullCollisionWeight,
  ratioTrackingVariance,
  ratioTrackingVarianceHomogeneous,
  sampleFreeFlight,
  transmittanceDeltaTracking,
  transmittanceRatioTracking,
  transmittanceResidualRatioTracking,
  transmittanceTrackLength,
  transmittanceUnbiasedRayMarching,
  unbiasedRayMarchingCombSize,
  unbiasedRayMarchingExpectedOrder,
  unbiasedRayMarchingOrderProbability,
  type TransmittanceEstimate,
} from '../../src/reference/tracking.ts';
import {
  gridMedium,
  homogeneousMedium,
  mediumExtinction,
  mediumMajorant,
  mediumOpticalDepth,
  sineMedium,
  type Medium1D,
} from '../../src/reference/medium.ts';
import { rngNextFloat, rngSeed, type RngState } from '../../src/reference/rng.ts';
import { simpson } from '../support/quadrature.ts';
import { expectMean, expectVariance, type Moments, moments } from '../support/statistics.ts';

/** Upper points of χ² at α = 0.005 (0.01 split over this file's two tests), mpmath. */
const CHI_SQUARE_63_AT_0005 = 95.6493;
const CHI_SQUARE_10_AT_0005 = 25.1882;

type Walk = (state: RngState) => TransmittanceEstimate;

interface Summary extends Moments {
  meanLookups: number;
  lookupVariance: number;
  capped: number;
}

function summarize(estimates: readonly number[], lookups: readonly number[], capped = 0): Summary {
  const n = estimates.length;
  const meanLookups = lookups.reduce((a, b) => a + b, 0) / n;
  const lookupVariance = lookups.reduce((a, b) => a + (b - meanLookups) ** 2, 0) / (n - 1);
  return { ...moments(estimates), meanLookups, lookupVariance, capped };
}

/** Runs n independent walks, walk i seeded with rngSeed(i, frame) as on the GPU. */
function run(walk: Walk, n: number, frame: number): Summary {
  const estimates: number[] = [];
  const lookups: number[] = [];
  let capped = 0;
  for (let i = 0; i < n; i++) {
    const result = walk({ value: rngSeed(i, frame) });
    estimates.push(result.estimate);
    lookups.push(result.lookups);
    capped += result.capped;
  }
  return summarize(estimates, lookups, capped);
}

function expectMeanLookups(summary: Summary, predicted: number): void {
  const bound = 5 * Math.sqrt(summary.lookupVariance / summary.n);
  expect(
    Math.abs(summary.meanLookups - predicted),
    `lookups ${summary.meanLookups} vs ${predicted} (5σ = ${bound})`,
  ).toBeLessThan(bound);
}

// Integrals below use simpson's default 2000 intervals: error < 1e-12 for these smooth integrands.
const exactT = (medium: Medium1D, d: number): number => Math.exp(-mediumOpticalDepth(medium, 0, d));

// The media of physics.md §4: a homogeneous one, the smooth sinusoid σ = 1 + 0.5 sin 3t
// on [0, 2] (T = 0.134440) and a sharp-edged grid.
const SINE = sineMedium(1, 0.5, 3);
const SINE_LENGTH = 2;
const SINE_T = 0.13443986429189056;
const GRID = gridMedium([0.5, 3, 0.2, 2, 0, 1.5, 4, 0.1], 0.25);
const GRID_LENGTH = 2;
const N = 100_000;
const MAX = TRACKING_MAX_STEPS;

describe('free-flight sampling t = −ln(1 − ξ)/σ̄ (physics.md §1)', () => {
  it('samples the exponential pdf σ̄e^{−σ̄t}: χ² over 64 equiprobable bins (100 000 draws, α = 0.005)', () => {
    const sigmaMaj = 2.5;
    const bins = new Array<number>(64).fill(0);
    const state = { value: rngSeed(3, 99) };
    const n = 100_000;
    for (let i = 0; i < n; i++) {
      const t = sampleFreeFlight(sigmaMaj, rngNextFloat(state));
      const cdf = -Math.expm1(-sigmaMaj * t);
      const bin = Math.min(Math.floor(cdf * 64), 63);
      bins[bin] = (bins[bin] ?? 0) + 1;
    }
    const expected = n / 64;
    const chiSquare = bins.reduce((sum, count) => sum + (count - expected) ** 2 / expected, 0);
    expect(chiSquare).toBeLessThan(CHI_SQUARE_63_AT_0005);
  });

  it('ξ = 1 − 2⁻²⁴ (the largest stream value) gives the finite maximum 16.6355/σ̄ (§9 row 16)', () => {
    expect(sampleFreeFlight(1, 1 - 2 ** -24)).toBeCloseTo(16.635532333438686, 12);
    expect(sampleFreeFlight(4, 1 - 2 ** -24)).toBeCloseTo(16.635532333438686 / 4, 12);
    expect(sampleFreeFlight(1, 1)).toBe(sampleFreeFlight(1, 1 - 2 ** -24));
  });

  it('σ̄ ≤ 0 means no collisions: the largest finite f32, never Infinity (§4.5, §10)', () => {
    expect(sampleFreeFlight(0, 0.5)).toBe(FREE_FLIGHT_NEVER);
    expect(sampleFreeFlight(-3, 0.5)).toBe(FREE_FLIGHT_NEVER);
    expect(sampleFreeFlight(1e-45, 0.5)).toBe(FREE_FLIGHT_NEVER);
    expect(Number.isFinite(FREE_FLIGHT_NEVER)).toBe(true);
    expect(Math.fround(FREE_FLIGHT_NEVER)).toBe(FREE_FLIGHT_NEVER);
  });

  it('ξ = 0 gives t = +0, and t is finite, ≥ 0 and increasing in ξ for every σ̄ > 0', () => {
    expect(Object.is(sampleFreeFlight(3, 0), 0)).toBe(true);
    fc.assert(
      fc.property(
        fc.double({ min: 1e-40, max: 3e38, noNaN: true }),
        fc.double({ min: 0, max: 1, noNaN: true }),
        fc.double({ min: 0, max: 1, noNaN: true }),
        (sigma, a, b) => {
          const [lo, hi] = a < b ? [a, b] : [b, a];
          const tLo = sampleFreeFlight(sigma, lo);
          const tHi = sampleFreeFlight(sigma, hi);
          return tLo >= 0 && tHi <= FREE_FLIGHT_NEVER && tLo <= tHi;
        },
      ),
    );
  });

  it('the track-length estimator averages to e^{−σd} over ξ (midpoint rule, 1e5 nodes: error ≤ 1e-5)', () => {
    for (const [sigma, d] of [
      [1, 1],
      [2, 0.3],
      [0.5, 4],
    ] as const) {
      const n = 100_000;
      let sum = 0;
      for (let i = 0; i < n; i++) sum += transmittanceTrackLength(sigma, d, (i + 0.5) / n);
      expect(Math.abs(sum / n - Math.exp(-sigma * d))).toBeLessThan(1e-5);
    }
    expect(transmittanceTrackLength(0, 1e30, 0)).toBe(1);
    expect(transmittanceTrackLength(5, 0, 0)).toBe(1);
  });
});

describe('null-collision weight 1 − σ/σ̄ (physics.md §4.2)', () => {
  it('is 1 − σ/σ̄, negative for σ > σ̄ (not clamped at 0, §4.5) and exactly 1 for σ = 0', () => {
    expect(nullCollisionWeight(0.5, 2)).toBe(0.75);
    expect(nullCollisionWeight(2, 1)).toBe(-1);
    expect(nullCollisionWeight(-0.5, 0.5)).toBe(2);
    expect(nullCollisionWeight(0, 0)).toBe(1);
    expect(nullCollisionWeight(0, 1)).toBe(1);
  });

  it('bounds |σ/σ̄| by 2²⁰ so the weight stays finite for σ̄ → 0', () => {
    expect(nullCollisionWeight(1, 0)).toBe(1 - 2 ** 20);
    expect(nullCollisionWeight(-1, 0)).toBe(1 + 2 ** 20);
    expect(nullCollisionWeight(3e38, 1e-30)).toBe(1 - 2 ** 20);
  });
});

describe('delta tracking (Woodcock, physics.md §4.1)', () => {
  it('homogeneous σ = 1, d = 1, σ̄ = 2: unbiased, Var = T(1 − T), lookups (σ̄/σ)(1 − e^{−σd})', () => {
    const medium = homogeneousMedium(1);
    const s = run((state) => transmittanceDeltaTracking(medium, 1, 2, state, MAX), N, 1);
    const T = Math.exp(-1);
    expectMean(s, T, deltaTrackingVariance(T));
    expectVariance(s, deltaTrackingVariance(T));
    expectMeanLookups(s, expectedDeltaTrackingLookups(1, 2, 1));
    expect(s.capped).toBe(0);
  });

  it('smooth sinusoid (σ̄ = 1.5): unbiased for T = 0.134440 with Var = T(1 − T)', () => {
    const s = run((state) => transmittanceDeltaTracking(SINE, SINE_LENGTH, 1.5, state, MAX), N, 2);
    expect(exactT(SINE, SINE_LENGTH)).toBeCloseTo(SINE_T, 12);
    expectMean(s, SINE_T, deltaTrackingVariance(SINE_T));
    expectVariance(s, deltaTrackingVariance(SINE_T));
  });

  it('sharp-edged grid with its max-cell majorant: unbiased, estimates only 0 or 1', () => {
    const sigmaMaj = mediumMajorant(GRID, 0, GRID_LENGTH);
    expect(sigmaMaj).toBe(4);
    const T = exactT(GRID, GRID_LENGTH);
    const s = run(
      (state) => transmittanceDeltaTracking(GRID, GRID_LENGTH, sigmaMaj, state, MAX),
      N,
      3,
    );
    expectMean(s, T, deltaTrackingVariance(T));
    expectVariance(s, deltaTrackingVariance(T));
    expect(s.min).toBe(0);
    expect(s.max).toBe(1);
  });

  it('with a tight homogeneous majorant it is the track-length estimator, seed by seed', () => {
    const medium = homogeneousMedium(1.7);
    for (let i = 0; i < 2000; i++) {
      const seed = rngSeed(i, 4);
      const tracked = transmittanceDeltaTracking(medium, 0.8, 1.7, { value: seed }, MAX);
      const xi = rngNextFloat({ value: seed });
      expect(tracked.estimate).toBe(transmittanceTrackLength(1.7, 0.8, xi));
    }
  });
});

describe('ratio tracking (physics.md §4.2)', () => {
  it('homogeneous σ = 1, d = 1, σ̄ = 2: unbiased, Var = 0.087795, lookups σ̄d', () => {
    const medium = homogeneousMedium(1);
    const s = run((state) => transmittanceRatioTracking(medium, 1, 2, state, MAX), N, 5);
    const variance = ratioTrackingVarianceHomogeneous(1, 2);
    expect(variance).toBeCloseTo(0.087795, 6);
    expectMean(s, Math.exp(-1), variance);
    expectVariance(s, variance);
    expectMeanLookups(s, expectedRatioTrackingLookups(2, 1));
  });

  it('smooth sinusoid, σ̄ = 1.5: Var = T²(exp(∫σ²/σ̄) − 1) = 0.064260', () => {
    const integral = simpson((t) => mediumExtinction(SINE, t) ** 2 / 1.5, 0, SINE_LENGTH);
    const variance = ratioTrackingVariance(SINE_T, integral);
    expect(variance).toBeCloseTo(0.06426, 5);
    const s = run((state) => transmittanceRatioTracking(SINE, SINE_LENGTH, 1.5, state, MAX), N, 6);
    expectMean(s, SINE_T, variance);
    expectVariance(s, variance);
    expectMeanLookups(s, 1.5 * SINE_LENGTH);
  });

  it('sharp-edged grid: unbiased and every estimate in [0, 1] (σ̄ ≥ σt keeps the weights in [0, 1])', () => {
    const T = exactT(GRID, GRID_LENGTH);
    const integral = [0.5, 3, 0.2, 2, 0, 1.5, 4, 0.1].reduce((a, s) => a + (0.25 * s * s) / 4, 0);
    const variance = ratioTrackingVariance(T, integral);
    const s = run((state) => transmittanceRatioTracking(GRID, GRID_LENGTH, 4, state, MAX), N, 7);
    expectMean(s, T, variance);
    expectVariance(s, variance);
    expect(s.min).toBeGreaterThanOrEqual(0);
    expect(s.max).toBeLessThanOrEqual(1);
  });

  it('lookups in an empty medium are Poisson(σ̄d): χ² over 0..9 and ≥ 10 (α = 0.005)', () => {
    const medium = homogeneousMedium(0);
    const sigmaMaj = 3;
    const counts = new Array<number>(11).fill(0);
    const n = 40_000;
    for (let i = 0; i < n; i++) {
      const r = transmittanceRatioTracking(medium, 1, sigmaMaj, { value: rngSeed(i, 8) }, MAX);
      expect(r.estimate).toBe(1);
      const bin = Math.min(r.lookups, 10);
      counts[bin] = (counts[bin] ?? 0) + 1;
    }
    let cumulative = 0;
    let chiSquare = 0;
    for (let k = 0; k < 10; k++) {
      let factorial = 1;
      for (let i = 2; i <= k; i++) factorial *= i;
      const p = (Math.exp(-sigmaMaj) * sigmaMaj ** k) / factorial;
      cumulative += p;
      chiSquare += ((counts[k] ?? 0) - n * p) ** 2 / (n * p);
    }
    const tail = n * (1 - cumulative);
    chiSquare += ((counts[10] ?? 0) - tail) ** 2 / tail;
    expect(chiSquare).toBeLessThan(CHI_SQUARE_10_AT_0005);
  });
});

describe('residual ratio tracking (physics.md §4.3)', () => {
  it('sinusoid with σc = 1, σ̄r = 0.5: unbiased with Var = 0.012399, 1/3 of the lookups of σ̄ = 1.5', () => {
    const integral = simpson((t) => (mediumExtinction(SINE, t) - 1) ** 2 / 0.5, 0, SINE_LENGTH);
    const variance = ratioTrackingVariance(SINE_T, integral);
    expect(variance).toBeCloseTo(0.012399, 6);
    const s = run(
      (state) => transmittanceResidualRatioTracking(SINE, SINE_LENGTH, 1, 0.5, state, MAX),
      N,
      9,
    );
    expectMean(s, SINE_T, variance);
    expectVariance(s, variance);
    expectMeanLookups(s, 0.5 * SINE_LENGTH);
  });

  it('grid with the mean as control (σc = 1.4125, σ̄r = 2.6): unbiased', () => {
    const T = exactT(GRID, GRID_LENGTH);
    const cells = [0.5, 3, 0.2, 2, 0, 1.5, 4, 0.1];
    const integral = cells.reduce((a, s) => a + (0.25 * (s - 1.4125) ** 2) / 2.6, 0);
    const variance = ratioTrackingVariance(T, integral);
    const s = run(
      (state) => transmittanceResidualRatioTracking(GRID, GRID_LENGTH, 1.4125, 2.6, state, MAX),
      N,
      10,
    );
    expectMean(s, T, variance);
    expectVariance(s, variance);
  });

  it('has zero variance when the control equals σt: every estimate is e^{−σc·d}', () => {
    const medium = homogeneousMedium(1.3);
    for (let i = 0; i < 1000; i++) {
      const r = transmittanceResidualRatioTracking(
        medium,
        2,
        1.3,
        0.7,
        { value: rngSeed(i, 11) },
        MAX,
      );
      expect(r.estimate).toBe(Math.exp(-2.6));
    }
  });
});

describe('unbiased ray marching (Kettunen et al. 2021, physics.md §4.4)', () => {
  it('the roulette has E[N] = 0.1·(2 + (e² − 5)/2) = 0.31945, P(N = 1) = 0, P(N ≥ 3) = 0.1·2/3', () => {
    expect(unbiasedRayMarchingExpectedOrder()).toBeCloseTo(0.1 * (2 + (Math.E ** 2 - 5) / 2), 14);
    expect(unbiasedRayMarchingExpectedOrder()).toBeCloseTo(0.31945, 5);
    expect(unbiasedRayMarchingOrderProbability(0)).toBe(1);
    expect(unbiasedRayMarchingOrderProbability(1)).toBeCloseTo(0.1, 15);
    expect(unbiasedRayMarchingOrderProbability(2)).toBeCloseTo(0.1, 15);
    expect(unbiasedRayMarchingOrderProbability(3)).toBeCloseTo(0.1 * (2 / 3), 15);
    // The order cap is reached with probability 0.1·2^16/17! ≈ 1.8e-11.
    expect(unbiasedRayMarchingOrderProbability(URM_MAX_ORDER + 1)).toBeLessThan(2e-11);
  });

  it('comb sizes M follow the §4.4 table (τ̄ = 0, 1, 2, 5, 10, 50 → 1, 4, 5, 10, 15, 50)', () => {
    const table = [
      [0, 1],
      [1, 4],
      [2, 5],
      [5, 10],
      [10, 15],
      [50, 50],
    ] as const;
    for (const [tauMaj, size] of table)
      expect(unbiasedRayMarchingCombSize(tauMaj, MAX), `τ̄ = ${tauMaj}`).toBe(size);
  });

  it('the comb size fits the lookup budget for every order: (URM_MAX_ORDER + 1)·M ≤ maxSteps', () => {
    expect(unbiasedRayMarchingCombSize(1e30, MAX)).toBe(Math.floor(MAX / (URM_MAX_ORDER + 1)));
    expect(unbiasedRayMarchingCombSize(50, 100)).toBe(5);
    expect(unbiasedRayMarchingCombSize(50, 0)).toBe(1);
    expect(unbiasedRayMarchingCombSize(-1, MAX)).toBe(1);
  });

  it('draws orders with mean E[N] = 0.31945: mean lookups = (1 + E[N])·M', () => {
    const combSize = unbiasedRayMarchingCombSize(3, MAX);
    expect(combSize).toBe(7);
    const s = run(
      (state) => transmittanceUnbiasedRayMarching(SINE, SINE_LENGTH, 1.5, state, MAX),
      N,
      12,
    );
    expectMeanLookups(s, (1 + unbiasedRayMarchingExpectedOrder()) * combSize);
  });

  it('has zero variance for constant σt: σt = 1.3, d = 2 gives e^{−2.6} = 0.0742736 every time', () => {
    const medium = homogeneousMedium(1.3);
    let orders = 0;
    for (let i = 0; i < 4000; i++) {
      const r = transmittanceUnbiasedRayMarching(medium, 2, 1.3, { value: rngSeed(i, 13) }, MAX);
      expect(Math.abs(r.estimate - 0.07427357821433388)).toBeLessThan(1e-15);
      if (r.lookups > unbiasedRayMarchingCombSize(2.6, MAX)) orders++;
    }
    expect(orders, 'some walks used higher orders').toBeGreaterThan(0);
  });

  it('smooth sinusoid: unbiased, and > 100× lower variance than ratio tracking at similar cost', () => {
    const s = run(
      (state) => transmittanceUnbiasedRayMarching(SINE, SINE_LENGTH, 1.5, state, MAX),
      N,
      14,
    );
    expectMean(s, SINE_T);
    // §4.4: std 1.3e-3 to 2.7e-3 for M = 8 and 4 (here M = 7); ratio tracking's Var = 0.064.
    expect(s.variance).toBeLessThan(0.06426 / 100);
    expect(s.capped).toBe(0);
  });

  it('sharp-edged grid: unbiased', () => {
    const s = run(
      (state) => transmittanceUnbiasedRayMarching(GRID, GRID_LENGTH, 4, state, MAX),
      N,
      15,
    );
    expectMean(s, exactT(GRID, GRID_LENGTH));
  });

  it('order 0 alone (jittered ray marching) would be biased; the higher orders remove it (§9 row 27)', () => {
    // One comb point, N = 0 only: E[e^{−τ̂}] ≠ e^{−τ}. With M = 1 (σ̄ = 0 hint) the
    // full estimator is still unbiased.
    const zeroOrder: number[] = [];
    const full: number[] = [];
    for (let i = 0; i < N; i++) {
      const state = { value: rngSeed(i, 16) };
      const u = rngNextFloat({ value: rngSeed(i, 17) });
      zeroOrder.push(Math.exp(-SINE_LENGTH * mediumExtinction(SINE, u * SINE_LENGTH)));
      full.push(transmittanceUnbiasedRayMarching(SINE, SINE_LENGTH, 0, state, MAX).estimate);
    }
    const biased = summarize(zeroOrder, []);
    expect(biased.mean).toBeCloseTo(0.17173, 2);
    expect(Math.abs(biased.mean - SINE_T)).toBeGreaterThan(10 * Math.sqrt(biased.variance / N));
    expectMean(summarize(full, []), SINE_T);
  });
});

describe('failure modes of physics.md §4.5', () => {
  const dense = homogeneousMedium(2);

  it('delta tracking with σt = 2 > σ̄ = 1 is biased high: exp(−∫min(σt, σ̄)) = 0.36788, not 0.135335', () => {
    const s = run((state) => transmittanceDeltaTracking(dense, 1, 1, state, MAX), N, 20);
    expectMean(s, Math.exp(-1), deltaTrackingVariance(Math.exp(-1)));
    expect(s.mean - Math.exp(-2)).toBeGreaterThan(0.2);
  });

  it('ratio tracking with σt = 2 > σ̄ = 1 stays unbiased (weights −1) with variance 0.9817', () => {
    const s = run((state) => transmittanceRatioTracking(dense, 1, 1, state, MAX), N, 21);
    const variance = ratioTrackingVarianceHomogeneous(2, 1);
    expect(variance).toBeCloseTo(0.9817, 4);
    expectMean(s, Math.exp(-2), variance);
    expectVariance(s, variance);
    expect(s.min).toBe(-1);
  });

  it('σt ≡ 0 with σ̄ > 0: delta and ratio tracking return exactly 1 and still spend Poisson(σ̄d) lookups', () => {
    const empty = homogeneousMedium(0);
    const delta = run((state) => transmittanceDeltaTracking(empty, 2, 1.5, state, MAX), N, 22);
    const ratio = run((state) => transmittanceRatioTracking(empty, 2, 1.5, state, MAX), N, 23);
    for (const s of [delta, ratio]) {
      expect(s.min).toBe(1);
      expect(s.max).toBe(1);
      expectMeanLookups(s, 3);
    }
  });

  it('σ̄ = 0: transmittance 1 without sampling — no lookups and no random numbers drawn', () => {
    const empty = homogeneousMedium(0);
    for (const walk of [transmittanceDeltaTracking, transmittanceRatioTracking]) {
      const state = { value: 12345 };
      expect(walk(empty, 5, 0, state, MAX)).toEqual({ estimate: 1, lookups: 0, capped: 0 });
      expect(state.value).toBe(12345);
    }
    const state = { value: 12345 };
    expect(transmittanceResidualRatioTracking(empty, 5, 0, 0, state, MAX).estimate).toBe(1);
    expect(state.value).toBe(12345);
  });

  it('the loop cap: a walk that needs more than maxSteps lookups stops with capped = 1 and reports them', () => {
    const empty = homogeneousMedium(0);
    const capped = transmittanceRatioTracking(empty, 100, 1, { value: 1 }, 10);
    expect(capped).toEqual({ estimate: 1, lookups: 10, capped: 1 });
    const delta = transmittanceDeltaTracking(empty, 100, 1, { value: 1 }, 10);
    expect(delta).toEqual({ estimate: 1, lookups: 10, capped: 1 });
    const residual = transmittanceResidualRatioTracking(empty, 100, 0, 1, { value: 1 }, 10);
    expect(residual).toEqual({ estimate: 1, lookups: 10, capped: 1 });
    const none = transmittanceDeltaTracking(empty, 100, 1, { value: 1 }, 0);
    expect(none).toEqual({ estimate: 1, lookups: 0, capped: 1 });
    const marched = transmittanceUnbiasedRayMarching(empty, 1, 1, { value: 1 }, 0);
    expect(marched.capped).toBe(1);
    expect(marched.lookups).toBe(0);
  });
});

describe('closed forms of physics.md §4', () => {
  it('delta tracking variance T(1 − T): 0.232544 at T = e^{-1}, 0 at T ∈ {0, 1}', () => {
    expect(deltaTrackingVariance(0.367879)).toBeCloseTo(0.232544, 6);
    expect(deltaTrackingVariance(0)).toBe(0);
    expect(deltaTrackingVariance(1)).toBe(0);
  });

  it('ratio tracking variance, homogeneous: the §4.2 table, and T(1 − T) for a tight majorant', () => {
    expect(ratioTrackingVarianceHomogeneous(1, 2)).toBeCloseTo(0.087795, 6);
    expect(ratioTrackingVarianceHomogeneous(1, 4)).toBeCloseTo(0.038439, 6);
    expect(ratioTrackingVarianceHomogeneous(2, 2.5)).toBeCloseTo(0.072402, 6);
    fc.assert(
      fc.property(fc.double({ min: 1e-3, max: 20, noNaN: true }), (tau) => {
        const T = Math.exp(-tau);
        const v = ratioTrackingVarianceHomogeneous(tau, tau);
        return Math.abs(v - deltaTrackingVariance(T)) <= 1e-12;
      }),
    );
    expect(ratioTrackingVarianceHomogeneous(0, 0)).toBe(0);
    expect(ratioTrackingVarianceHomogeneous(1, 0)).toBe(Infinity);
  });

  it('the general form T²(exp(∫σ²/σ̄) − 1) reduces to the homogeneous one', () => {
    expect(ratioTrackingVariance(Math.exp(-1), 1 / 2)).toBeCloseTo(
      ratioTrackingVarianceHomogeneous(1, 2),
      14,
    );
  });

  it('expected delta tracking lookups (σ̄/σ)(1 − e^{−σd}): σ̄d when σ → 0, 1 − e^{−τ} for a tight majorant', () => {
    expect(expectedDeltaTrackingLookups(1, 2, 1)).toBeCloseTo(2 * (1 - Math.exp(-1)), 14);
    expect(expectedDeltaTrackingLookups(0, 1.5, 2)).toBe(3);
    expect(expectedDeltaTrackingLookups(1e-12, 1.5, 2)).toBeCloseTo(3, 9);
    expect(expectedDeltaTrackingLookups(3, 3, 1)).toBeCloseTo(1 - Math.exp(-3), 14);
    expect(expectedDeltaTrackingLookups(1, 0, 1)).toBe(0);
    expect(expectedRatioTrackingLookups(1.5, 2)).toBe(3);
  });
});
