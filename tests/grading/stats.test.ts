// The grader's statistics against known values (tables of the χ² and normal
// distributions) and against their defining properties.
import { describe, expect, it } from 'vitest';
import {
  bernoulliMeanZ,
  bernoulliVarianceZ,
  chiSquareEquiprobable,
  sampleMoments,
  seededUniforms,
} from '../../src/grading/stats.ts';
import {
  chiSquareCritical,
  chiSquareSurvival,
  normalCritical,
  twoSidedNormalTail,
} from '../../src/statistics/distributions.ts';
import { hgCdf, hgInverseCdf } from '../../exercises/hg-sample/exercise.ts';
import { opticalDepth } from '../../exercises/delta-tracking/exercise.ts';

describe('distribution functions', () => {
  it('reproduces χ² and normal table values', () => {
    // χ²_1(0.95) = 3.841459, χ²_19(0.999) = 43.8202, χ²_10(0.99) = 23.2093 (standard tables).
    expect(chiSquareCritical(0.05, 1)).toBeCloseTo(3.841459, 4);
    expect(chiSquareCritical(0.001, 19)).toBeCloseTo(43.8202, 3);
    expect(chiSquareCritical(0.01, 10)).toBeCloseTo(23.2093, 3);
    expect(chiSquareSurvival(2, 2)).toBeCloseTo(Math.exp(-1), 10);
    // Two-sided normal: z = 1.959964 at 5%, 4.891638 at 1e-6.
    expect(normalCritical(0.05)).toBeCloseTo(1.959964, 4);
    expect(normalCritical(1e-6)).toBeCloseTo(4.891638, 3);
    expect(twoSidedNormalTail(0)).toBeCloseTo(1, 6);
  });

  it('gives a stratified sample of a known distribution a tiny χ², a wrong one a huge χ²', () => {
    const n = 2000;
    const next = seededUniforms(7);
    const stratified = Array.from({ length: n }, (_, k) => hgInverseCdf(0.6, (k + next()) / n));
    const good = chiSquareEquiprobable(stratified, (x) => hgCdf(0.6, x), 20, 1e-6);
    expect(good.statistic).toBeLessThan(0.5);
    const uniform = stratified.map((_, k) => (2 * (k + 0.5)) / n - 1);
    const bad = chiSquareEquiprobable(uniform, (x) => hgCdf(0.6, x), 20, 1e-6);
    expect(bad.statistic).toBeGreaterThan(bad.critical);
    expect(good.observed.reduce((a, b) => a + b, 0)).toBe(n);
  });

  it('has an HG CDF that is the integral of the HG density', () => {
    // 2π ∫_{-1}^{μ} p_HG dμ' by the midpoint rule, against the closed form.
    const g = 0.7;
    const p = (mu: number): number => (1 - g * g) / (4 * Math.PI * (1 + g * g - 2 * g * mu) ** 1.5);
    let sum = 0;
    const steps = 20000;
    for (let i = 0; i < steps; i++)
      sum += 2 * Math.PI * p(-1 + ((i + 0.5) * 1.5) / steps) * (1.5 / steps);
    expect(hgCdf(g, 0.5)).toBeCloseTo(sum, 6);
    expect(hgInverseCdf(g, hgCdf(g, 0.3))).toBeCloseTo(0.3, 10);
  });

  it('integrates the sine medium exactly', () => {
    let sum = 0;
    const steps = 20000;
    for (let i = 0; i < steps; i++) {
      const s = ((i + 0.5) * 1.2) / steps;
      sum += 1 * (1 + 0.5 * Math.sin(3 * s)) * (1.2 / steps);
    }
    expect(opticalDepth(1, 0.5, 1.2)).toBeCloseTo(sum, 6);
  });
});

describe('Bernoulli z-tests', () => {
  it('accepts an exact Bernoulli sample and rejects a biased or non-binary one', () => {
    const t = 0.3;
    const n = 10000;
    const exact = Array.from({ length: n }, (_, k) => (k < n * t ? 1 : 0));
    const m = sampleMoments(exact);
    expect(Math.abs(bernoulliMeanZ(m, t))).toBeLessThan(0.01);
    expect(Math.abs(bernoulliVarianceZ(m, t))).toBeLessThan(0.1);
    const biased = sampleMoments(Array.from({ length: n }, (_, k) => (k < n * 0.27 ? 1 : 0)));
    expect(Math.abs(bernoulliMeanZ(biased, t))).toBeGreaterThan(4.9);
    const weights = sampleMoments(Array.from({ length: n }, () => t));
    expect(Math.abs(bernoulliMeanZ(weights, t))).toBeLessThan(1e-6);
    expect(Math.abs(bernoulliVarianceZ(weights, t))).toBeGreaterThan(100);
  });

  it('treats T = 1 as "exactly 1 every time"', () => {
    expect(bernoulliMeanZ(sampleMoments([1, 1, 1]), 1)).toBe(0);
    expect(bernoulliMeanZ(sampleMoments([1, 0, 1]), 1)).toBe(-Infinity);
  });
});
