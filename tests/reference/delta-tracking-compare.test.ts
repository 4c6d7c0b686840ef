// The pure logic of the delta-tracking widget's comparison view
// (src/widgets/delta-tracking/compare.ts) and the base pieces it added: the
// equal-time allocation of samples from measured costs, the slope fitted to a
// sweep of RMSE against time, merging several series onto one time axis
// (base/sweep.ts) and the decade labels of a logarithmic axis (base/plot.ts).
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { logTickLabel } from '../../src/widgets/base/plot.ts';
import { mergeSeries, type SweepPoint } from '../../src/widgets/base/sweep.ts';
import {
  CALIBRATION_SPP,
  CALIBRATION_TARGET_MS,
  ESTIMATOR_ORDER,
  FIT_MIN_SPP,
  calibrationSpp,
  costPerSample,
  equalTimeSpp,
  median,
  planEqualTime,
  sppSlope,
  timeSlope,
  type EstimatorKey,
} from '../../src/widgets/delta-tracking/compare.ts';
import { SPP_MAX } from '../../src/widgets/delta-tracking/model.ts';

const SWEEP = [1, 2, 4, 8, 16, 32, 64, 128, 256];

describe('cost per sample from repeated renders', () => {
  it('the median ignores one slow render, for odd and even counts', () => {
    expect(median([5, 1, 3])).toBe(3);
    expect(median([4, 1, 3, 100])).toBe(3.5);
    expect(median([7])).toBe(7);
    expect(() => median([])).toThrow();
    expect(costPerSample([32, 30, 400], 16)).toBe(2);
  });
});

describe('spp of the timed calibration renders', () => {
  it('raises the warm-up spp by powers of two until a render lasts the target time, up to the cap', () => {
    expect(calibrationSpp(CALIBRATION_TARGET_MS)).toBe(CALIBRATION_SPP);
    expect(calibrationSpp(40)).toBe(CALIBRATION_SPP); // slow enough already (SwiftShader)
    expect(calibrationSpp(CALIBRATION_TARGET_MS / 2)).toBe(2 * CALIBRATION_SPP);
    expect(calibrationSpp(CALIBRATION_TARGET_MS / 3)).toBe(4 * CALIBRATION_SPP);
    expect(calibrationSpp(1e-3)).toBe(SPP_MAX); // a fast GPU
    expect(calibrationSpp(0)).toBe(SPP_MAX); // faster than the clock
    expect(calibrationSpp(1, 8, 10, 32)).toBe(32);
  });
});

describe('equal-time allocation: spp_i = max(1, round(budget / cost_i)), clamped to the kernel', () => {
  it('rounds budget over cost to the nearest whole spp', () => {
    expect(equalTimeSpp(10, 3)).toBe(3);
    expect(equalTimeSpp(10, 2.5)).toBe(4);
    expect(equalTimeSpp(10, 4)).toBe(3); // 2.5 rounds up
    expect(equalTimeSpp(10, 0.1)).toBe(100);
  });

  it('gives at least one sample, and at most SPP_MAX', () => {
    expect(equalTimeSpp(1, 50)).toBe(1);
    expect(equalTimeSpp(1e6, 1e-3)).toBe(SPP_MAX);
    expect(equalTimeSpp(1e6, 1e-3, 256)).toBe(256);
    expect(equalTimeSpp(0, 1)).toBe(1);
  });

  it('a broken cost measurement (0, NaN, ∞) does not starve the estimator: it gets the cap', () => {
    expect(equalTimeSpp(10, 0)).toBe(SPP_MAX);
    expect(equalTimeSpp(10, Number.NaN)).toBe(SPP_MAX);
    expect(equalTimeSpp(10, Number.POSITIVE_INFINITY)).toBe(SPP_MAX);
  });

  it('a worked case: the budget is the reference at spp, and cheaper estimators get more samples', () => {
    const costs = { biased: 1, delta: 2, ratio: 4, residual: 2.5, urm: 9 };
    const plan = planEqualTime(costs, 'delta', 4);
    expect(plan.budgetMs).toBe(8);
    expect(plan.spp).toEqual({ biased: 8, delta: 4, ratio: 2, residual: 3, urm: 1 });
  });

  it('property: the reference keeps its spp, every spp is in 1 … SPP_MAX, and an unclamped spp spends the budget to within half a sample', () => {
    const cost = fc.double({ min: 1e-4, max: 100, noNaN: true });
    fc.assert(
      fc.property(
        fc.record({ biased: cost, delta: cost, ratio: cost, residual: cost, urm: cost }),
        fc.constantFrom(...ESTIMATOR_ORDER),
        fc.integer({ min: 1, max: 256 }),
        (costs: Record<EstimatorKey, number>, reference: EstimatorKey, spp: number) => {
          const plan = planEqualTime(costs, reference, spp);
          expect(plan.spp[reference]).toBe(spp);
          for (const key of ESTIMATOR_ORDER) {
            const n = plan.spp[key];
            expect(Number.isInteger(n)).toBe(true);
            expect(n).toBeGreaterThanOrEqual(1);
            expect(n).toBeLessThanOrEqual(SPP_MAX);
            if (n > 1 && n < SPP_MAX)
              expect(Math.abs(n * costs[key] - plan.budgetMs)).toBeLessThanOrEqual(
                costs[key] / 2 + 1e-9 * plan.budgetMs,
              );
          }
        },
      ),
    );
  });
});

/** A sweep whose render costs overhead + perSample·n ms and whose RMSE is sqrt(bias² + variance/n). */
function syntheticSweep(overhead: number, perSample: number, variance: number, bias = 0) {
  return SWEEP.map((n): SweepPoint => ({
    n,
    milliseconds: overhead + perSample * n,
    rmse: Math.sqrt(bias ** 2 + variance / n),
  }));
}

describe('slope of log RMSE against log time', () => {
  it('is exactly −½ for an unbiased estimator whose time is proportional to spp', () => {
    expect(timeSlope(syntheticSweep(0, 0.5, 0.1))).toBeCloseTo(-0.5, 12);
  });

  it(`is fitted over spp ≥ ${FIT_MIN_SPP}, where a fixed dispatch cost no longer hides the −½`, () => {
    // 3 ms of fixed cost against 1 ms per sample: all nine points fit −0.63, the
    // points at spp ≥ 16 (where the fixed cost is at most 16%) −0.53.
    const points = syntheticSweep(3, 1, 0.1);
    const all = timeSlope(points, 1)!;
    const tail = timeSlope(points)!;
    expect(all).toBeLessThan(-0.6); // the flat times at small spp steepen the fit
    expect(tail).toBeGreaterThan(-0.56);
    expect(tail).toBeLessThan(-0.5);
  });

  it('is near 0 for a biased estimator once its bias dominates: the plateau', () => {
    // exp(−τ̂)'s bias ≈ 0.03 and per-sample variance ≈ 0.0094 on the widget image.
    const slope = timeSlope(syntheticSweep(0, 0.5, 0.0094, 0.03))!;
    expect(slope).toBeGreaterThan(-0.2);
    expect(slope).toBeLessThan(0);
  });

  it('against spp it is −½ whatever the fixed cost, and near 0 on the plateau', () => {
    expect(sppSlope(syntheticSweep(3, 1, 0.1))).toBeCloseTo(-0.5, 12);
    expect(sppSlope(syntheticSweep(10, 0.01, 0.1))).toBeCloseTo(-0.5, 12);
    const plateau = sppSlope(syntheticSweep(0, 1, 0.0094, 0.03))!;
    expect(plateau).toBeGreaterThan(-0.2);
    expect(sppSlope([])).toBeNull();
  });

  it('falls back to all points with fewer than two at spp ≥ 16, skips times of 0, and is null without two points', () => {
    const short = syntheticSweep(0, 1, 0.1).slice(0, 4);
    expect(timeSlope(short)).toBeCloseTo(-0.5, 12);
    expect(timeSlope([{ n: 1, rmse: 0.1, milliseconds: 0 }, ...short.slice(0, 2)])).toBeCloseTo(
      -0.5,
      12,
    );
    expect(timeSlope(short.slice(0, 1))).toBeNull();
    expect(timeSlope([])).toBeNull();
  });
});

describe('several sweep series on one time axis', () => {
  it('x is the sorted union of log₁₀ ms; each series is NaN where it has no point', () => {
    const a: SweepPoint[] = [
      { n: 1, rmse: 0.5, milliseconds: 10 },
      { n: 2, rmse: 0.3, milliseconds: 1 },
    ];
    const b: SweepPoint[] = [
      { n: 1, rmse: 0.2, milliseconds: 100 },
      { n: 2, rmse: 0.1, milliseconds: 10 },
    ];
    const { x, values } = mergeSeries([a, b]);
    expect(x).toEqual([0, 1, 2]);
    expect(values[0]).toEqual([0.3, 0.5, Number.NaN]);
    expect(values[1]).toEqual([Number.NaN, 0.1, 0.2]);
  });

  it('one series comes out sorted by time, as the single-series sweep plots it', () => {
    const points = syntheticSweep(3, 0.2, 0.1).reverse();
    const { x, values } = mergeSeries([points]);
    expect(x).toEqual([...x].sort((p, q) => p - q));
    expect(values[0]).toEqual(
      [...points].sort((p, q) => p.milliseconds - q.milliseconds).map((p) => p.rmse),
    );
  });
});

describe('labels of a logarithmic axis', () => {
  it('labels decades only, without rounding small values to 0', () => {
    expect(logTickLabel(1)).toBe('1');
    expect(logTickLabel(0.01)).toBe('0.01');
    expect(logTickLabel(1e-4)).toBe('1×10⁻⁴');
    expect(logTickLabel(1e5)).toBe('1×10⁵');
    expect(logTickLabel(2e-3)).toBe('');
    expect(logTickLabel(0)).toBe('');
    expect(logTickLabel(Number.NaN)).toBe('');
  });
});
