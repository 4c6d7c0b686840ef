// The hg-lobe widget's float64 model held to analytic facts (physics.md §2.2, §2.4):
// the closed-form CDF and its bin probabilities, the chi-square machinery on known
// counts, the normalisation quadrature, and the CPU twin's sampler (the widget's
// fallback and the GPU kernel's reference) against the closed form.
import { describe, expect, it } from 'vitest';
import { hgEval } from '../../src/reference/phase.ts';
import { sampleHistogramCpu } from '../../src/widgets/hg-lobe/cpuBackend.ts';
import {
  BIN_COUNT,
  binEdge,
  chiSquareTest,
  hgBinProbabilities,
  hgCdf,
  meanCosine,
  polarLayout,
  sphereIntegral,
  inputsFrom,
} from '../../src/widgets/hg-lobe/model.ts';
import { chiSquareCritical, chiSquareSurvival } from '../../src/statistics/distributions.ts';

const G_VALUES = [-0.99, -0.6, -0.3, -1e-7, 0, 1e-7, 0.3, 0.6, 0.9, 0.99];

describe('closed-form HG CDF (physics.md §2.4)', () => {
  it('at g = 0 it is the isotropic CDF (1 + μ)/2 exactly: the rewritten form has no 0/0', () => {
    for (const mu of [-1, -0.75, -0.5, 0, 0.25, 0.5, 1]) expect(hgCdf(0, mu)).toBe((1 + mu) / 2);
  });

  it('for |g| ≤ 1e-7 it differs from (1 + μ)/2 by O(g) only (the textbook form loses all digits there)', () => {
    for (const g of [1e-7, -1e-7])
      for (const mu of [-0.9, -0.2, 0.4, 0.8])
        expect(Math.abs(hgCdf(g, mu) - (1 + mu) / 2)).toBeLessThan(1e-6);
  });

  it('matches the textbook F(μ) = (1−g²)/(2g)[(1+g²−2gμ)^(−1/2) − 1/(1+g)] where that is well conditioned', () => {
    for (const g of [-0.9, -0.3, 0.3, 0.6, 0.9])
      for (const mu of [-1, -0.7, -0.1, 0.2, 0.5, 0.95, 1]) {
        const textbook = ((1 - g * g) / (2 * g)) * ((1 + g * g - 2 * g * mu) ** -0.5 - 1 / (1 + g));
        // Relative 1e-13: the textbook form cancels by at most a few digits at these g.
        expect(Math.abs(hgCdf(g, mu) - textbook)).toBeLessThan(1e-13);
      }
  });

  it('runs from 0 at μ = −1 to 1 at μ = +1 and its derivative is 2π·p_HG (the pdf of μ)', () => {
    for (const g of G_VALUES) {
      expect(hgCdf(g, -1)).toBe(0);
      expect(Math.abs(hgCdf(g, 1) - 1)).toBeLessThan(1e-15);
      for (const mu of [-0.8, -0.1, 0.3, 0.7]) {
        // Central difference, h = 1e-5: truncation ~h²·F‴ and rounding ~1e-16/h, both < 1e-6 relative here.
        const h = 1e-5;
        const derivative = (hgCdf(g, mu + h) - hgCdf(g, mu - h)) / (2 * h);
        const density = 2 * Math.PI * hgEval(g, mu);
        expect(Math.abs(derivative - density) / density).toBeLessThan(1e-6);
      }
    }
  });
});

describe('analytic bin probabilities', () => {
  it('are non-negative and sum to 1 for every g (to float64 rounding of 64 differences)', () => {
    for (const g of G_VALUES) {
      const probabilities = hgBinProbabilities(g);
      expect(probabilities).toHaveLength(BIN_COUNT);
      let sum = 0;
      for (const p of probabilities) {
        expect(p).toBeGreaterThanOrEqual(0);
        sum += p;
      }
      expect(Math.abs(sum - 1)).toBeLessThan(1e-14);
    }
  });

  it('at g = 0 every bin holds 1/64', () => {
    for (const p of hgBinProbabilities(0)) expect(p).toBeCloseTo(1 / BIN_COUNT, 15);
  });

  it('each equals 2π∫p dμ over its bin by quadrature, independently of the CDF', () => {
    for (const g of [-0.6, 0.3, 0.9]) {
      const probabilities = hgBinProbabilities(g);
      for (const k of [0, 17, 40, 63]) {
        const a = binEdge(k);
        const b = binEdge(k + 1);
        // Simpson with 2000 panels: relative error ~(h/w)⁴/180 with w = (1 − g)²/(2|g|)
        // the width of the peak (w ≈ 5.6e-3 at g = 0.9, h = 1.6e-5): below 1e-12.
        const n = 2000;
        let sum = 0;
        for (let i = 0; i <= n; i++) {
          const weight = i === 0 || i === n ? 1 : i % 2 === 1 ? 4 : 2;
          sum += weight * hgEval(g, a + ((b - a) * i) / n);
        }
        const integral = (2 * Math.PI * sum * (b - a)) / (3 * n);
        expect(Math.abs(probabilities[k]! - integral) / integral).toBeLessThan(1e-9);
      }
    }
  });
});

describe('chi-square machinery', () => {
  it('the critical value at α = 0.01 for df = 63 is 92.01 (tables) and for df = 1 is 6.635', () => {
    expect(chiSquareCritical(0.01, 63)).toBeCloseTo(92.01, 2);
    expect(chiSquareCritical(0.01, 1)).toBeCloseTo(6.635, 3);
    expect(chiSquareCritical(0.05, 10)).toBeCloseTo(18.307, 3);
  });

  it('the tail of χ²₂ is exp(−x/2) (closed form)', () => {
    for (const x of [0.1, 1, 5, 20])
      expect(chiSquareSurvival(x, 2)).toBeCloseTo(Math.exp(-x / 2), 12);
  });

  it('computes Pearson’s statistic on known counts: equal counts give 0, a known deviation its value', () => {
    const uniform = new Array<number>(BIN_COUNT).fill(1 / BIN_COUNT);
    const exact = chiSquareTest(new Array<number>(BIN_COUNT).fill(100), uniform, 6400);
    expect(exact.statistic).toBe(0);
    expect(exact.df).toBe(63);
    expect(exact.passes).toBe(true);
    // Two bins off by ±10 from E = 100: χ² = 2·10²/100 = 2.
    const counts = new Array<number>(BIN_COUNT).fill(100);
    counts[0] = 110;
    counts[1] = 90;
    expect(chiSquareTest(counts, uniform, 6400).statistic).toBeCloseTo(2, 12);
    // All samples in one bin: a gross failure.
    const lumped = new Array<number>(BIN_COUNT).fill(0);
    lumped[5] = 6400;
    expect(chiSquareTest(lumped, uniform, 6400).passes).toBe(false);
  });

  it('pools bins with expected counts below 5 into one cell (the χ² law needs E ≥ 5)', () => {
    const probabilities = hgBinProbabilities(0.99);
    const n = 1024;
    const sparse = [...probabilities].filter((p) => n * p < 5).length;
    expect(sparse).toBeGreaterThan(0);
    const expected = [...probabilities].map((p) => Math.round(n * p));
    const result = chiSquareTest(expected, probabilities, n);
    expect(result.pooled).toBe(sparse);
    expect(result.df).toBe(BIN_COUNT - sparse);
  });
});

describe('normalisation and mean cosine of the twin', () => {
  it('∫p dω = 1 by quadrature to 1e-12 for g up to ±0.99 (physics.md §2.2)', () => {
    for (const g of G_VALUES) {
      expect(Math.abs(sphereIntegral((mu) => hgEval(g, mu)) - 1)).toBeLessThan(1e-12);
    }
  });

  // One chi-square test per g at a family-wise α = 0.01 (Bonferroni).
  const SAMPLED_G = [-0.3, 0, 0.6, 0.9];
  for (const g of SAMPLED_G) {
    it(`g = ${g}: the CPU twin's 2^15 samples pass χ² at α = 0.01/${SAMPLED_G.length} and have mean cosine g within 5 SE`, () => {
      const histogram = sampleHistogramCpu(Math.fround(g), 2 ** 15, 5);
      const test = chiSquareTest(
        histogram.bins,
        hgBinProbabilities(Math.fround(g)),
        histogram.sampleCount,
        0.01 / SAMPLED_G.length,
      );
      expect(test.pValue).toBeGreaterThan(0.01 / SAMPLED_G.length);
      expect(Math.abs(meanCosine(histogram, Math.fround(g)).zScore)).toBeLessThan(5);
    });
  }

  it('the standard error is √(Var μ / N) with Var μ = (1 + 2g²)/3 − g² (HG Legendre moments g^l)', () => {
    const g = Math.fround(0.6);
    const histogram = sampleHistogramCpu(g, 2 ** 15, 9);
    const predicted = Math.sqrt(((1 + 2 * g * g) / 3 - g * g) / histogram.sampleCount);
    // The sample SE estimates it with relative error ~1/√(2N) ≈ 0.4%; 5% is generous.
    expect(meanCosine(histogram, g).standardError / predicted).toBeCloseTo(1, 1);
  });
});

describe('polar layout', () => {
  it('fits the lobe in the canvas and puts log rings on decades', () => {
    const inputs = inputsFrom({ g: 0.9, compare: 'isotropic', scale: 'log', samples: 16, seed: 1 });
    const layout = polarLayout(inputs, 960, 480);
    const forward = layout.pixelsPerUnit * (Math.log10(hgEval(inputs.g, 1)) - layout.logFloor);
    expect(forward).toBeLessThanOrEqual(0.45 * 960 + 1e-9);
    for (const ring of layout.rings) expect(Math.log10(ring.value) % 1).toBeCloseTo(0, 12);
  });

  it('rounds the sample exponent and seed and rounds g to f32, as the GPU sees it', () => {
    const inputs = inputsFrom({
      g: 0.6,
      compare: 'none',
      scale: 'linear',
      samples: 12.4,
      seed: 3.6,
    });
    expect(inputs.sampleCount).toBe(4096);
    expect(inputs.seed).toBe(4);
    expect(inputs.g).toBe(Math.fround(0.6));
  });
});
