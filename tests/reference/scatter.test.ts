// The float64 scatter twin against physics.md §5: the homogeneous-slab closed
// form (its published values and independent quadrature), convergence of the
// marched single scattering to it, and equiangular sampling (normalization,
// sampled density = evaluated pdf by chi-square, zero variance for 1/r²).
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { gridMedium, homogeneousMedium } from '../../src/reference/medium.ts';
import {
  MARCH_JITTERED_RAY,
  MARCH_JITTERED_STRATA,
  MARCH_LEFT,
  MARCH_MIDPOINT,
} from '../../src/reference/raymarch.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import {
  equiangularPdf,
  equiangularSample,
  shadowTransmittanceExact,
  singleScatterHomogeneousSlab,
  singleScatterMarched,
} from '../../src/reference/scatter.ts';
import { simpson } from '../support/quadrature.ts';

const PHASE_ISOTROPIC = 1 / (4 * Math.PI);
// §5 example: σs = 0.8, σa = 0.2, p = 1/(4π), E = 1, a = 0.3, b = 0.5, L = 2.
const EXAMPLE = [0.8, 0.2, PHASE_ISOTROPIC, 1, 0.3, 0.5, 2] as const;
const EXAMPLE_VALUE = 0.02987593155873194;
const EXAMPLE_B0_VALUE = 0.04077927647475037;

/** Upper 1% point of the chi-square distribution with 39 degrees of freedom. */
const CHI_SQUARE_39_AT_001 = 62.428;

describe('homogeneous-slab closed form (physics.md §5)', () => {
  it('σs = 0.8, σa = 0.2, p = 1/(4π), E = 1, a = 0.3, b = 0.5, L = 2 gives 0.02987593155873194', () => {
    expect(Math.abs(singleScatterHomogeneousSlab(...EXAMPLE) / EXAMPLE_VALUE - 1)).toBeLessThan(
      1e-15,
    );
  });

  it('b = 0 gives α·p·E·e^{−σt a}(1 − e^{−σt L}) = 0.04077927647475037', () => {
    expect(
      Math.abs(
        singleScatterHomogeneousSlab(0.8, 0.2, PHASE_ISOTROPIC, 1, 0.3, 0, 2) / EXAMPLE_B0_VALUE -
          1,
      ),
    ).toBeLessThan(1e-15);
  });

  it('equals Simpson quadrature of ∫₀^L e^{−σt t} σs p E e^{−σt(a + b t)} dt for all parameters', () => {
    fc.assert(
      fc.property(
        fc.double({ min: 0, max: 5, noNaN: true }),
        fc.double({ min: 0, max: 5, noNaN: true }),
        fc.double({ min: 0, max: 2, noNaN: true }),
        fc.double({ min: 0, max: 3, noNaN: true }),
        fc.double({ min: 0, max: 4, noNaN: true }),
        (sigmaS, sigmaA, a, b, length) => {
          const sigmaT = sigmaS + sigmaA;
          const quadrature = simpson(
            (t) =>
              Math.exp(-sigmaT * t) * sigmaS * PHASE_ISOTROPIC * Math.exp(-sigmaT * (a + b * t)),
            0,
            length,
            4000,
          );
          const closed = singleScatterHomogeneousSlab(
            sigmaS,
            sigmaA,
            PHASE_ISOTROPIC,
            1,
            a,
            b,
            length,
          );
          // Simpson's relative error for e^{−kt} with step δ is ≈ (kδ)⁴/180; here kδ ≤ 40·4/4000.
          return Math.abs(closed - quadrature) <= 1e-7 * quadrature + 1e-15;
        },
      ),
      { numRuns: 200 },
    );
  });

  it('thin limit (§9 row 18): σt(1+b)L = 1e-9 gives σs·p·E·e^{−σt a}·L to 1e-9 relative', () => {
    const value = singleScatterHomogeneousSlab(5e-10, 5e-10, 1, 1, 0, 0, 1);
    expect(Math.abs(value / 5e-10 - 1)).toBeLessThan(1e-9);
  });

  it('no medium scatters nothing; no scatterer scatters nothing; an infinitely thick slab gives α·p·E·e^{−σt a}/(1 + b)', () => {
    expect(singleScatterHomogeneousSlab(0, 0, 1, 1, 0, 0, 5)).toBe(0);
    expect(singleScatterHomogeneousSlab(0, 3, 1, 1, 0, 0, 5)).toBe(0);
    const thick = singleScatterHomogeneousSlab(0.6, 0.4, PHASE_ISOTROPIC, 2, 0.1, 1, 1e6);
    expect(thick).toBeCloseTo((0.6 * PHASE_ISOTROPIC * 2 * Math.exp(-0.1)) / 2, 15);
  });

  it('shadowTransmittanceExact is Beer’s law over ℓ(t) = a + b·t', () => {
    expect(shadowTransmittanceExact(1, 0.3, 0.5, 2)).toBeCloseTo(Math.exp(-1.3), 15);
    expect(shadowTransmittanceExact(0, 5, 5, 5)).toBe(1);
    expect(shadowTransmittanceExact(2, -1, -1, 1)).toBe(1); // negative a, b clamped to 0
  });
});

describe('marched single scattering converges to the closed form (physics.md §5)', () => {
  const medium = homogeneousMedium(1);
  const marched = (steps: number, scheme: number, seed = 0): number =>
    singleScatterMarched(medium, 0.8, PHASE_ISOTROPIC, 1, 0.3, 0.5, 2, steps, scheme, {
      value: seed,
    }).radiance;

  it('midpoint: O(h²), error ratio 4 ± 0.05 per halving; at N = 4096 the error is (128/4096)² of N = 128’s (±1%)', () => {
    for (const n of [8, 32, 128]) {
      const ratio =
        (marched(n, MARCH_MIDPOINT) - EXAMPLE_VALUE) /
        (marched(2 * n, MARCH_MIDPOINT) - EXAMPLE_VALUE);
      expect(Math.abs(ratio - 4)).toBeLessThan(0.05);
    }
    const extrapolated = (marched(128, MARCH_MIDPOINT) - EXAMPLE_VALUE) * (128 / 4096) ** 2;
    const error = marched(4096, MARCH_MIDPOINT) - EXAMPLE_VALUE;
    expect(Math.abs(error / extrapolated - 1)).toBeLessThan(0.01);
    expect(Math.abs(error / EXAMPLE_VALUE)).toBeLessThan(2e-8);
  });

  it('left: O(h), error ratio 2 ± 0.05 per halving for N ≥ 32', () => {
    for (const n of [32, 128, 512]) {
      const ratio =
        (marched(n, MARCH_LEFT) - EXAMPLE_VALUE) / (marched(2 * n, MARCH_LEFT) - EXAMPLE_VALUE);
      expect(Math.abs(ratio - 2)).toBeLessThan(0.05);
    }
  });

  it('one step of the midpoint rule is the closed form with the source frozen at L/2', () => {
    // σt = 1, α = 0.8: L̂ = α(1 − e^{−2})·p·E·e^{−(0.3 + 0.5·1)}.
    const expected = 0.8 * (1 - Math.exp(-2)) * PHASE_ISOTROPIC * Math.exp(-0.8);
    expect(marched(1, MARCH_MIDPOINT)).toBeCloseTo(expected, 15);
  });

  it('jittered per ray and per step: mean over 20 000 rays = its exact expectation (5 SE), O(h²) from L_ss', () => {
    // In a homogeneous medium only the shadow term moves with the offset, and
    // E[e^{−σt b ξ h}] = (1 − e^{−σt b h})/(σt b h); both jittered schemes have this mean.
    const n = 16;
    const step = 2 / n;
    const perStep = 0.8 * (1 - Math.exp(-step)) * PHASE_ISOTROPIC * Math.exp(-0.3);
    const jitter = (1 - Math.exp(-0.5 * step)) / (0.5 * step);
    let expectation = 0;
    for (let i = 0; i < n; i++)
      expectation += perStep * Math.exp(-i * step) * Math.exp(-0.5 * i * step) * jitter;
    expect(Math.abs(expectation / EXAMPLE_VALUE - 1)).toBeLessThan(1e-3); // O(h²) with h = 1/8
    for (const scheme of [MARCH_JITTERED_RAY, MARCH_JITTERED_STRATA]) {
      const values = Array.from({ length: 20_000 }, (_, i) => marched(n, scheme, rngSeed(i, 2)));
      const mean = values.reduce((a, b) => a + b, 0) / values.length;
      const se = Math.sqrt(
        values.reduce((a, v) => a + (v - mean) ** 2, 0) / (values.length - 1) / values.length,
      );
      expect(Math.abs(mean - expectation)).toBeLessThan(5 * se);
    }
  });

  it('reports the view ray’s transmittance and steps; albedo 0 scatters nothing', () => {
    const r = singleScatterMarched(
      medium,
      0.8,
      PHASE_ISOTROPIC,
      1,
      0.3,
      0.5,
      2,
      64,
      MARCH_MIDPOINT,
      { value: 0 },
    );
    expect(r.transmittance).toBeCloseTo(Math.exp(-2), 14);
    expect(r.steps).toBe(64);
    expect(r.clampedSteps).toBe(0);
    const dark = singleScatterMarched(
      medium,
      0,
      PHASE_ISOTROPIC,
      1,
      0.3,
      0.5,
      2,
      64,
      MARCH_MIDPOINT,
      { value: 0 },
    );
    expect(dark.radiance).toBe(0);
  });

  it('a grid medium aligned with the steps, with b = 0, is integrated exactly (σt and the shadow are constant per step)', () => {
    const cells = [0.5, 2, 1, 0.1];
    const grid = gridMedium(cells, 0.5);
    const r = singleScatterMarched(grid, 0.6, PHASE_ISOTROPIC, 3, 0.2, 0, 2, 4, MARCH_MIDPOINT, {
      value: 0,
    });
    let expected = 0;
    let transmittance = 1;
    for (const sigmaT of cells) {
      expected +=
        transmittance *
        0.6 *
        (1 - Math.exp(-sigmaT * 0.5)) *
        PHASE_ISOTROPIC *
        3 *
        Math.exp(-sigmaT * 0.2);
      transmittance *= Math.exp(-sigmaT * 0.5);
    }
    expect(r.radiance).toBeCloseTo(expected, 15);
  });
});

describe('equiangular sampling (Kulla & Fajardo 2012; physics.md §5)', () => {
  // A point light at distance h = 0.7 from the ray, segment t ∈ [−1.2, 3] around the closest point.
  const h = 0.7;
  const thetaA = Math.atan(-1.2 / h);
  const thetaB = Math.atan(3 / h);

  it('the pdf integrates to 1 over the segment (Simpson, 1e-6)', () => {
    const total = simpson((t) => equiangularPdf(h, thetaA, thetaB, t), -1.2, 3, 4000);
    expect(total).toBeCloseTo(1, 6);
  });

  it('ξ = 0 and ξ = 1 map to the segment’s ends; t is increasing in ξ', () => {
    expect(equiangularSample(h, thetaA, thetaB, 0)[0]).toBeCloseTo(-1.2, 12);
    expect(equiangularSample(h, thetaA, thetaB, 1)[0]).toBeCloseTo(3, 12);
    fc.assert(
      fc.property(
        fc.double({ min: 0, max: 1, noNaN: true }),
        fc.double({ min: 0, max: 1, noNaN: true }),
        (u, v) => {
          const [lo, hi] = u < v ? [u, v] : [v, u];
          return (
            equiangularSample(h, thetaA, thetaB, lo)[0] <=
            equiangularSample(h, thetaA, thetaB, hi)[0]
          );
        },
      ),
    );
  });

  it('the returned pdf is the evaluated pdf at the sampled t, and equals h/((θb − θa)(h² + t²))', () => {
    fc.assert(
      fc.property(fc.double({ min: 0, max: 1, noNaN: true }), (xi) => {
        const [t, pdf] = equiangularSample(h, thetaA, thetaB, xi);
        const direct = h / ((thetaB - thetaA) * (h * h + t * t));
        return (
          pdf === equiangularPdf(h, thetaA, thetaB, t) && Math.abs(pdf - direct) <= 1e-14 * direct
        );
      }),
    );
  });

  it('sampled t follow the pdf: chi-square over 40 equiprobable bins, 100 000 samples, α = 0.01', () => {
    // Bins of equal probability from the CDF (θ(t) − θa)/(θb − θa), written independently.
    const bins = 40;
    const counts = new Array<number>(bins).fill(0);
    const state = { value: rngSeed(4242, 0) };
    const n = 100_000;
    for (let i = 0; i < n; i++) {
      const [t] = equiangularSample(h, thetaA, thetaB, rngNextFloat(state));
      const cdf = (Math.atan2(t, h) - thetaA) / (thetaB - thetaA);
      const bin = Math.min(bins - 1, Math.max(0, Math.floor(cdf * bins)));
      counts[bin] = (counts[bin] ?? 0) + 1;
    }
    const expected = n / bins;
    const chiSquare = counts.reduce((sum, c) => sum + (c - expected) ** 2 / expected, 0);
    expect(chiSquare).toBeLessThan(CHI_SQUARE_39_AT_001);
  });

  it('f/pdf is constant for f = 1/(h² + t²): equiangular sampling has zero variance for 1/r²', () => {
    const exact = (thetaB - thetaA) / h; // ∫ dt/(h² + t²)
    for (const xi of [0, 0.1, 0.37, 0.5, 0.99]) {
      const [t, pdf] = equiangularSample(h, thetaA, thetaB, xi);
      expect(1 / (h * h + t * t) / pdf).toBeCloseTo(exact, 12);
    }
  });

  it('a degenerate segment (h = 0 or θb = θa) reports pdf 0, never Inf', () => {
    expect(equiangularSample(0, -1, 1, 0.5)[1]).toBe(0);
    expect(equiangularSample(1, 0.3, 0.3, 0.5)[1]).toBe(0);
    expect(equiangularPdf(0, -1, 1, 0)).toBe(0);
  });
});
