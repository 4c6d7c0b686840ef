// The float64 twin of shaders/volume.wesl held to the laws it implements
// (chapter 7): opacity correction composes like Beer's law, a transfer-function
// lookup stays in the hull of its control points, front-to-back compositing of a
// homogeneous volume matches the closed form for any step, and early termination
// drops at most ε·L_max.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { makeDensityGrid, type Vec3 } from '../../src/reference/medium.ts';
import {
  compositeFrontToBack,
  makeTransferFunction,
  opacityCorrected,
  opacityToOpticalDepth,
  transferLookup,
  volumeRaymarch,
  volumeStepCount,
} from '../../src/reference/volume.ts';

const opacity = fc.double({ min: 0, max: 0.999, noNaN: true });
const ratio = fc.double({ min: 0.01, max: 16, noNaN: true });
const smallRatio = fc.double({ min: 0.01, max: 4, noNaN: true });

describe('opacity correction α′ = 1 − (1 − α)^{Δs/Δs₀}', () => {
  it('two half steps make one full step: 1 − (1 − α′(½))² = α', () => {
    fc.assert(
      fc.property(opacity, (a) => {
        const half = opacityCorrected(a, 0.5);
        expect(1 - (1 - half) ** 2).toBeCloseTo(a, 12);
      }),
    );
  });

  it('corrections compose: α′(α′(α, r₁), r₂) = α′(α, r₁·r₂)', () => {
    fc.assert(
      fc.property(
        fc.double({ min: 0, max: 0.95, noNaN: true }),
        smallRatio,
        smallRatio,
        (a, r1, r2) => {
          const twice = opacityCorrected(opacityCorrected(a, r1), r2);
          const once = opacityCorrected(a, r1 * r2);
          // Compare the transmittances 1 − α′ relatively. The intermediate α′(α, r₁) is
          // stored as a number near 1, with absolute precision 2⁻⁵³, so 1 − α′ ≥ 0.05⁴
          // (α ≤ 0.95, r ≤ 4) keeps the composition well conditioned.
          expect(Math.abs(1 - twice - (1 - once))).toBeLessThanOrEqual(1e-6 * (1 - once) + 1e-15);
        },
      ),
    );
  });

  it('is the opacity of Beer’s law over the step: α′ = 1 − e^{−r·τ₀} with τ₀ = −ln(1 − α)', () => {
    fc.assert(
      fc.property(opacity, ratio, (a, r) => {
        const tau0 = opacityToOpticalDepth(a);
        expect(opacityCorrected(a, r)).toBeCloseTo(1 - Math.exp(-r * tau0), 12);
      }),
    );
  });

  it('stays in [0, 1] and grows with the step and with α', () => {
    fc.assert(
      fc.property(opacity, ratio, ratio, (a, r1, r2) => {
        const [lo, hi] = r1 < r2 ? [r1, r2] : [r2, r1];
        const small = opacityCorrected(a, lo);
        const large = opacityCorrected(a, hi);
        expect(small).toBeGreaterThanOrEqual(0);
        expect(large).toBeLessThanOrEqual(1);
        expect(large).toBeGreaterThanOrEqual(small);
        expect(opacityCorrected(Math.min(a + 0.001, 1), lo)).toBeGreaterThanOrEqual(small);
      }),
    );
  });

  it('is exact at the reference step and at the ends', () => {
    expect(opacityCorrected(0.3, 1)).toBe(0.3);
    expect(opacityCorrected(0, 5)).toBe(0);
    expect(opacityCorrected(1, 1e-9)).toBe(1);
    expect(opacityCorrected(1, 0)).toBe(0);
    expect(opacityToOpticalDepth(0.5)).toBeCloseTo(Math.LN2, 15);
  });
});

describe('transferLookup: piecewise-linear colour and opacity', () => {
  const points = fc
    .array(
      fc.record({
        value: fc.double({ min: -1024, max: 3071, noNaN: true }),
        r: fc.double({ min: 0, max: 1, noNaN: true }),
        a: fc.double({ min: 0, max: 1, noNaN: true }),
      }),
      { minLength: 1, maxLength: 16 },
    )
    .map((list) =>
      [...list]
        .sort((p, q) => p.value - q.value)
        .map((p) => ({
          value: p.value,
          color: [p.r, 1 - p.r, 0.5] as const,
          opacity: p.a,
        })),
    );

  it('stays within the hull of the control points, and equals them at distinct values', () => {
    fc.assert(
      fc.property(points, fc.double({ min: -1100, max: 3200, noNaN: true }), (list, v) => {
        const tf = makeTransferFunction(list);
        const q = transferLookup(tf, v);
        const alphas = list.map((p) => p.opacity);
        expect(q[3]).toBeGreaterThanOrEqual(Math.min(...alphas) - 1e-12);
        expect(q[3]).toBeLessThanOrEqual(Math.max(...alphas) + 1e-12);
        list.forEach((p, k) => {
          const distinct = list.every((other, j) => j === k || other.value !== p.value);
          if (distinct) expect(transferLookup(tf, p.value)[3]).toBeCloseTo(p.opacity, 12);
        });
      }),
    );
  });

  it('is continuous between points: a small change of v changes q little', () => {
    const tf = makeTransferFunction([
      { value: 0, color: [0, 0, 0], opacity: 0 },
      { value: 100, color: [1, 1, 1], opacity: 1 },
    ]);
    expect(transferLookup(tf, 50)).toEqual([0.5, 0.5, 0.5, 0.5]);
    expect(transferLookup(tf, 50 + 1e-9)[3] - 0.5).toBeLessThan(1e-10);
  });
});

describe('compositing and marching', () => {
  it('front-to-back compositing of n equal steps gives L = c·(1 − (1 − α)ⁿ), T = (1 − α)ⁿ', () => {
    fc.assert(
      fc.property(opacity, fc.integer({ min: 1, max: 64 }), (a, n) => {
        let accumulated: [number, number, number, number] = [0, 0, 0, 1];
        for (let i = 0; i < n; i++)
          accumulated = compositeFrontToBack(accumulated, [0.7, 0.2, 1], a);
        expect(accumulated[3]).toBeCloseTo((1 - a) ** n, 12);
        expect(accumulated[0]).toBeCloseTo(0.7 * (1 - (1 - a) ** n), 12);
      }),
    );
  });

  const box: [Vec3, Vec3] = [
    [-1, -1, -1],
    [1, 1, 1],
  ];
  const constant = makeDensityGrid(new Array(8).fill(500), [2, 2, 2], box[0], box[1], 1);

  it('a homogeneous volume gives the closed form for every step size (opacity correction is exact)', () => {
    const tf = makeTransferFunction([{ value: 0, color: [1, 0.5, 0.25], opacity: 0.1 }]);
    fc.assert(
      fc.property(fc.double({ min: 0.01, max: 3, noNaN: true }), (step) => {
        // Along x through the 2 m box with Δs₀ = 0.1 m: T = 0.9^{20}.
        const r = volumeRaymarch(
          constant.grid,
          constant.volume,
          -500,
          tf,
          0.1,
          [-3, 0.2, 0.1],
          [1, 0, 0],
          step,
          0,
        );
        expect(r.transmittance).toBeCloseTo(0.9 ** 20, 10);
        expect(r.color[0]).toBeCloseTo(1 - 0.9 ** 20, 10);
        expect(r.plannedSteps).toBe(volumeStepCount(2, step));
      }),
    );
  });

  it('early termination drops at most ε·L_max and never adds radiance', () => {
    const values = Array.from({ length: 64 }, (_, i) => 600 * Math.abs(Math.sin(1.7 * i)));
    const grid = makeDensityGrid(values, [4, 4, 4], box[0], box[1], 1);
    const tf = makeTransferFunction([
      { value: 0, color: [0.2, 0.1, 0.9], opacity: 0 },
      { value: 300, color: [1, 0.8, 0.3], opacity: 0.4 },
    ]);
    fc.assert(
      fc.property(
        fc.double({ min: -0.9, max: 0.9, noNaN: true }),
        fc.double({ min: 0.001, max: 0.3, noNaN: true }),
        (y, epsilon) => {
          const march = (threshold: number) =>
            volumeRaymarch(
              grid.grid,
              grid.volume,
              0,
              tf,
              0.05,
              [-3, y, 0.3],
              [1, 0, 0],
              0.02,
              threshold,
            );
          const full = march(0);
          const stopped = march(epsilon);
          for (const c of [0, 1, 2] as const) {
            const dropped = full.color[c] - stopped.color[c];
            expect(dropped).toBeGreaterThanOrEqual(-1e-12);
            expect(dropped).toBeLessThanOrEqual(epsilon * 1 + 1e-12);
          }
          if (stopped.terminated) expect(stopped.transmittance).toBeLessThan(epsilon);
        },
      ),
    );
  });
});
