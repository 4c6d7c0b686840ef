// The float64 twin of null-scattering transmittance (Miller, Georgiev & Jarosz 2019;
// src/reference/tracking.ts transmittanceNullScattering) against closed forms: it is
// unbiased for every choice of P_n (β = 0: delta tracking's σn/σ̄, β = 0.5, β = 1: ratio
// tracking's 1), including a majorant below σt, where P_n must come from |σn|; its variance
// is E[T̂²] − T² with E[T̂²] = exp(−∫(σ̄ − σn²/(σ̄P_n)) ds) (Campbell's identity on the
// Poisson process of tentative collisions), which reduces to delta tracking's T(1 − T) at
// β = 0 and ratio tracking's T²(exp(∫σt²/σ̄) − 1) at β = 1 (chapter 6, eq:ratio-variance).
//
// Fixed seeds; a mean passes within 5·sqrt(Var/N) and a variance within 5 standard errors
// (p ≈ 5.7e-7 per check, tests/support/statistics.ts).
import { describe, expect, it } from 'vitest';
import {
  deltaTrackingVariance,
  nullScatteringProbability,
  nullScatteringSecondMomentRate,
  nullScatteringWalk,
  ratioTrackingVariance,
  ratioTrackingVarianceHomogeneous,
  TRACKING_MAX_STEPS,
  transmittanceDeltaTracking,
  transmittanceNullScattering,
} from '../../src/reference/tracking.ts';
import {
  homogeneousMedium,
  mediumExtinction,
  sineMedium,
  type Medium1D,
} from '../../src/reference/medium.ts';
import { rngSeed } from '../../src/reference/rng.ts';
import { simpson } from '../support/quadrature.ts';
import { expectMean, expectVariance, moments } from '../support/statistics.ts';

const WALKS = 100_000;

function estimates(
  medium: Medium1D,
  d: number,
  sigmaMaj: number,
  nullBlend: number,
  frame: number,
) {
  const values: number[] = [];
  const lookups: number[] = [];
  for (let i = 0; i < WALKS; i++) {
    const r = transmittanceNullScattering(
      medium,
      d,
      sigmaMaj,
      nullBlend,
      { value: rngSeed(i, frame) },
      TRACKING_MAX_STEPS,
    );
    values.push(r.estimate);
    lookups.push(r.lookups);
  }
  return { values: moments(values), lookups: moments(lookups) };
}

/** E[T̂²] by quadrature of the twin's rate over [0, d]. */
function secondMoment(medium: Medium1D, d: number, sigmaMaj: number, nullBlend: number): number {
  const rate = (s: number): number => {
    const sigmaT = mediumExtinction(medium, s);
    return nullScatteringSecondMomentRate(
      sigmaT,
      sigmaMaj,
      nullScatteringProbability(sigmaT, sigmaMaj, nullBlend),
    );
  };
  return Math.exp(-simpson(rate, 0, d, 2000));
}

const SINE = sineMedium(1, 0.5, 3);
const SINE_T = 0.13443986429189056;

describe('null-scattering transmittance (twin) against closed forms', () => {
  it('the second moment is delta tracking’s T at β = 0 and ratio tracking’s at β = 1', () => {
    // Homogeneous σt = 1, σ̄ = 2, d = 1.
    const T = Math.exp(-1);
    const one = homogeneousMedium(1);
    expect(secondMoment(one, 1, 2, 0) - T * T).toBeCloseTo(deltaTrackingVariance(T), 12);
    expect(secondMoment(one, 1, 2, 1) - T * T).toBeCloseTo(
      ratioTrackingVarianceHomogeneous(1, 2),
      12,
    );
    // The sinusoid: eq:ratio-variance with ∫σt²/σ̄.
    const integral = simpson((s) => mediumExtinction(SINE, s) ** 2 / 1.5, 0, 2, 2000);
    expect(secondMoment(SINE, 2, 1.5, 1) - SINE_T ** 2).toBeCloseTo(
      ratioTrackingVariance(SINE_T, integral),
      10,
    );
    expect(secondMoment(SINE, 2, 1.5, 0)).toBeCloseTo(SINE_T, 10);
  });

  [0, 0.5, 1].forEach((nullBlend, k) => {
    it(`homogeneous σt = 1, σ̄ = 2, d = 1, β = ${nullBlend}: unbiased for e^{−1} with the closed-form variance`, () => {
      const T = Math.exp(-1);
      const one = homogeneousMedium(1);
      // P_n = 1 − (1 − β)/2, so E[T̂²] = exp(−(2 − 1/(2P_n))).
      const pn = 1 - (1 - nullBlend) / 2;
      const variance = Math.exp(-(2 - 1 / (2 * pn))) - T * T;
      expect(secondMoment(one, 1, 2, nullBlend) - T * T).toBeCloseTo(variance, 12);
      const { values } = estimates(one, 1, 2, nullBlend, 400 + k);
      expectMean(values, T, variance);
      expectVariance(values, variance);
    });

    it(`sinusoid with σ̄ = 1.2 below max σt = 1.5 (σn < 0 on part of the ray), β = ${nullBlend}: unbiased`, () => {
      const variance = secondMoment(SINE, 2, 1.2, nullBlend) - SINE_T ** 2;
      expect(Number.isFinite(variance)).toBe(true);
      const { values } = estimates(SINE, 2, 1.2, nullBlend, 410 + k);
      expectMean(values, SINE_T, variance);
      expectVariance(values, variance);
      expect(values.min).toBeLessThan(0);
    });
  });

  it('P_n from |σn| is what keeps β = 0 unbiased under a low majorant: delta tracking’s clamp is biased high there', () => {
    // σt = 2 > σ̄ = 1: delta tracking treats every collision as real, E = e^{−1} (chapter 6,
    // eq:delta-low-majorant); null scattering with P_n = |σn|/(|σn| + σt) = 1/3 gives e^{−2}.
    const dense = homogeneousMedium(2);
    const T = Math.exp(-2);
    const variance = Math.exp(1 / (1 / 3) - 1) - T * T;
    const { values } = estimates(dense, 1, 1, 0, 420);
    expectMean(values, T, variance);
    const delta: number[] = [];
    for (let i = 0; i < WALKS; i++)
      delta.push(
        transmittanceDeltaTracking(dense, 1, 1, { value: rngSeed(i, 420) }, TRACKING_MAX_STEPS)
          .estimate,
      );
    expectMean(moments(delta), Math.exp(-1), deltaTrackingVariance(Math.exp(-1)));
  });

  it('under a valid majorant, raising β lowers the variance and raises the lookups (delta → ratio)', () => {
    const runs = [0, 0.25, 0.5, 0.75, 1].map((beta, k) => ({
      exact: secondMoment(SINE, 2, 1.5, beta),
      run: estimates(SINE, 2, 1.5, beta, 430 + k),
    }));
    for (let k = 1; k < runs.length; k++) {
      expect(runs[k]!.exact).toBeLessThan(runs[k - 1]!.exact);
      expect(runs[k]!.run.lookups.mean).toBeGreaterThan(runs[k - 1]!.run.lookups.mean);
    }
    // Ratio tracking spends σ̄d = 3 lookups on average; delta tracking stops at the first real one.
    expectMean(runs[4]!.run.lookups, 3);
    expect(runs[0]!.run.lookups.mean).toBeLessThan(1.5);
  });

  it('the walk the figure draws is the estimator’s walk: same vertices, same weight', () => {
    for (const beta of [0, 0.5, 1])
      for (let i = 0; i < 2000; i++) {
        const { vertices, result } = nullScatteringWalk(
          SINE,
          2,
          1.5,
          beta,
          { value: rngSeed(i, 440) },
          TRACKING_MAX_STEPS,
        );
        const direct = transmittanceNullScattering(
          SINE,
          2,
          1.5,
          beta,
          { value: rngSeed(i, 440) },
          TRACKING_MAX_STEPS,
        );
        expect(result).toEqual(direct);
        expect(vertices.length).toBe(direct.lookups);
        expect(vertices.at(-1)?.weight ?? 1).toBe(direct.estimate);
      }
  });

  it('P_n = 0 where σn ≠ 0 is reported, not silently biased: the second-moment rate is NaN', () => {
    expect(nullScatteringSecondMomentRate(1, 2, 0)).toBeNaN();
    expect(nullScatteringSecondMomentRate(2, 2, 0)).toBe(2);
  });
});

describe('the numbers chapter 12 quotes (sinusoid of chapter 6, σ̄ = 1.5, d = 2)', () => {
  /** E[lookups] = σ̄∫₀^d exp(−(1 − β)τ(s)) ds: real vertices thin the collisions at rate (1 − β)σt. */
  const lookups = (beta: number): number =>
    simpson((s) => 1.5 * Math.exp(-(1 - beta) * mediumOpticalDepthOf(s)), 0, 2, 2000);
  const mediumOpticalDepthOf = (s: number): number =>
    simpson((u) => mediumExtinction(SINE, u), 0, s, 200);
  const variance = (beta: number): number => secondMoment(SINE, 2, 1.5, beta) - SINE_T ** 2;

  it('variances 0.1164, 0.0892, 0.0771, 0.0643 and lookups 1.122, 1.383, 1.748, 3.000 for β = 0, 0.25, 0.5, 1', () => {
    const betas = [0, 0.25, 0.5, 1];
    expect(betas.map((b) => variance(b).toFixed(4))).toEqual([
      '0.1164',
      '0.0892',
      '0.0771',
      '0.0643',
    ]);
    expect(betas.map((b) => lookups(b).toFixed(3))).toEqual(['1.122', '1.383', '1.748', '3.000']);
    // The twin spends what the formula says (β = 0.25: 5σ of Poisson-like counts).
    const { lookups: measured } = estimates(SINE, 2, 1.5, 0.25, 450);
    expectMean(measured, lookups(0.25));
  });

  it('variance × lookups is lowest at β = 0.25 among 0, 0.25, …, 1: 0.123 against 0.131 (delta) and 0.193 (ratio)', () => {
    const products = [0, 0.25, 0.5, 0.75, 1].map((b) => variance(b) * lookups(b));
    expect(products.indexOf(Math.min(...products))).toBe(1);
    expect(products.map((x) => x.toFixed(3))).toEqual([
      '0.131',
      '0.123',
      '0.135',
      '0.157',
      '0.193',
    ]);
  });
});
