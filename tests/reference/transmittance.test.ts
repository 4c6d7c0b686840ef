// The float64 transmittance twin against closed forms and the laws of physics.md §1:
// Beer's law, T ∈ [0, 1], T(p→p) = 1, the multiplicative property, and the exact
// integrals of the smooth and layered profiles against independent quadrature.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  GRID1D_MAX_CELLS,
  opticalThicknessGrid1D,
  opticalThicknessHomogeneous,
  opticalThicknessSine,
  transmittanceFromOpticalThickness,
  transmittanceHomogeneous,
} from '../../src/reference/transmittance.ts';
import { simpson } from '../support/quadrature.ts';

const sigma = fc.double({ min: 0, max: 50, noNaN: true });
const length = fc.double({ min: 0, max: 20, noNaN: true });

describe("Beer's law (physics.md §1)", () => {
  it('matches the tabulated exp(−σt·d) values of §1.1', () => {
    expect(transmittanceHomogeneous(1, 1)).toBeCloseTo(0.3678794412, 10);
    expect(transmittanceHomogeneous(3, 1)).toBeCloseTo(0.04978706837, 11);
    expect(transmittanceHomogeneous(10, 1)).toBeCloseTo(4.539992976e-5, 14);
  });

  it('σt·d = 1e6 underflows to exactly 0; σt = 1e6 over 1e-6 gives 1/e (hard cases 10, 11)', () => {
    expect(transmittanceHomogeneous(1e6, 1)).toBe(0);
    expect(transmittanceHomogeneous(1e6, 1e-6)).toBeCloseTo(Math.exp(-1), 15);
  });

  it('T lies in [0, 1] and T(p→p) = 1 for all inputs', () => {
    fc.assert(
      fc.property(sigma, length, (s, d) => {
        const t = transmittanceHomogeneous(s, d);
        return t >= 0 && t <= 1 && transmittanceHomogeneous(s, 0) === 1;
      }),
    );
  });

  it('T never exceeds 1 even for a negative optical thickness (clamped)', () => {
    expect(transmittanceFromOpticalThickness(-3)).toBe(1);
    expect(opticalThicknessHomogeneous(-2, 1)).toBe(0);
  });

  it('is multiplicative: T(d1 + d2) = T(d1)·T(d2)', () => {
    fc.assert(
      fc.property(sigma, length, length, (s, d1, d2) => {
        const whole = transmittanceHomogeneous(s, d1 + d2);
        const product = transmittanceHomogeneous(s, d1) * transmittanceHomogeneous(s, d2);
        return Math.abs(whole - product) <= 1e-12 * Math.max(whole, 1e-300) + 1e-300;
      }),
    );
  });

  it('decreases monotonically with distance', () => {
    fc.assert(
      fc.property(fc.double({ min: 1e-3, max: 50, noNaN: true }), length, length, (s, a, b) => {
        const [near, far] = a < b ? [a, b] : [b, a];
        return transmittanceHomogeneous(s, far) <= transmittanceHomogeneous(s, near);
      }),
    );
  });
});

describe('smooth profile σ0(1 + a sin(k s + φ))', () => {
  const parameters = fc.record({
    sigma0: fc.double({ min: 0, max: 10, noNaN: true }),
    amplitude: fc.double({ min: 0, max: 1, noNaN: true }),
    frequency: fc.double({ min: 0.1, max: 10, noNaN: true }),
    phase: fc.double({ min: -Math.PI, max: Math.PI, noNaN: true }),
    s0: fc.double({ min: 0, max: 5, noNaN: true }),
    length: fc.double({ min: 0, max: 5, noNaN: true }),
  });

  it('equals the quadrature of σt(s) (Simpson, 2000 intervals: error ≤ 1e-9 here)', () => {
    fc.assert(
      fc.property(parameters, (p) => {
        const s1 = p.s0 + p.length;
        const exact = opticalThicknessSine(p.sigma0, p.amplitude, p.frequency, p.phase, p.s0, s1);
        const quadrature = simpson(
          (s) => p.sigma0 * (1 + p.amplitude * Math.sin(p.frequency * s + p.phase)),
          p.s0,
          s1,
        );
        return Math.abs(exact - quadrature) <= 1e-8 * (1 + Math.abs(quadrature));
      }),
      { numRuns: 200 },
    );
  });

  it('is additive over adjacent segments: τ(a, c) = τ(a, b) + τ(b, c)', () => {
    fc.assert(
      fc.property(parameters, fc.double({ min: 0, max: 1, noNaN: true }), (p, t) => {
        const s1 = p.s0 + p.length;
        const mid = p.s0 + t * p.length;
        const whole = opticalThicknessSine(p.sigma0, p.amplitude, p.frequency, p.phase, p.s0, s1);
        const parts =
          opticalThicknessSine(p.sigma0, p.amplitude, p.frequency, p.phase, p.s0, mid) +
          opticalThicknessSine(p.sigma0, p.amplitude, p.frequency, p.phase, mid, s1);
        return Math.abs(whole - parts) <= 1e-12 * (1 + whole);
      }),
    );
  });

  it('reproduces chapter 2’s worked example: τ(0, 1) = 1 + (0.8/3)(1 − cos 3) for σ̄ = 1', () => {
    expect(opticalThicknessSine(1, 0.8, 3, 0, 0, 1)).toBeCloseTo(
      1 + (0.8 / 3) * (1 - Math.cos(3)),
      14,
    );
    expect(Math.exp(-opticalThicknessSine(1, 0.8, 3, 0, 0, 1))).toBeCloseTo(0.216392, 6);
  });

  it('with amplitude 0 reduces to the homogeneous medium', () => {
    expect(opticalThicknessSine(2.5, 0, 3, 1, 0.5, 2)).toBeCloseTo(
      opticalThicknessHomogeneous(2.5, 1.5),
      14,
    );
  });
});

describe('piecewise-constant (layered) profile', () => {
  const cells = fc.array(fc.double({ min: 0, max: 10, noNaN: true }), {
    minLength: GRID1D_MAX_CELLS,
    maxLength: GRID1D_MAX_CELLS,
  });

  it('equals the quadrature of the step function', () => {
    fc.assert(
      fc.property(
        cells,
        fc.double({ min: 0, max: 20, noNaN: true }),
        fc.double({ min: 0, max: 20, noNaN: true }),
        (sigmas, a, b) => {
          const [s0, s1] = a < b ? [a, b] : [b, a];
          const h = 1.25;
          const step = (s: number): number => sigmas[Math.floor(s / h)] ?? 0;
          // Riemann sum on a fine grid aligned with the cells: exact up to the two partial cells.
          const n = 16000;
          let quadrature = 0;
          for (let i = 0; i < n; i++)
            quadrature += step(s0 + ((i + 0.5) * (s1 - s0)) / n) * ((s1 - s0) / n);
          const exact = opticalThicknessGrid1D(sigmas, GRID1D_MAX_CELLS, h, s0, s1);
          return Math.abs(exact - quadrature) <= 2 * 10 * ((s1 - s0) / n) + 1e-9;
        },
      ),
      { numRuns: 100 },
    );
  });

  it('with equal cells reduces to the homogeneous medium inside the grid', () => {
    const equal = new Array<number>(GRID1D_MAX_CELLS).fill(0.7);
    expect(opticalThicknessGrid1D(equal, GRID1D_MAX_CELLS, 0.5, 0.3, 6.1)).toBeCloseTo(
      0.7 * 5.8,
      13,
    );
  });

  it('the multiplicative property holds across cell edges', () => {
    const layers = [0.5, 1.5, 0.8, 1.2, 2, 0.2, 1, 0.8];
    const T = (a: number, b: number): number =>
      transmittanceFromOpticalThickness(opticalThicknessGrid1D(layers, 8, 0.25, a, b));
    expect(T(0, 2)).toBeCloseTo(T(0, 0.6) * T(0.6, 2), 14);
    expect(T(0, 2)).toBeCloseTo(Math.exp(-2), 14);
  });
});
