// The pure logic of the delta-tracking widget's comparison view (chapter 6):
// all five estimators side by side at equal sample count and at equal time.
// Equal time works from a cost model measured once: the time per sample of each
// estimator (median of a few renders, so one slow frame on a busy machine does
// not set it), a budget equal to the reference estimator's time at the chosen
// spp, and for every estimator the spp that spends that budget. The sweep of all
// estimators fits log RMSE against log time; an unbiased estimator falls as
// spp^(−½) (physics.md §4), so as time^(−½) once the time is proportional to spp.
import { logLogSlope, type SweepPoint } from '../base/sweep.ts';
import { SPP_MAX } from './model.ts';

/** The estimators in the order of the chapter: biased first, then the unbiased ones. */
export const ESTIMATOR_ORDER = ['biased', 'delta', 'ratio', 'residual', 'urm'] as const;
export type EstimatorKey = (typeof ESTIMATOR_ORDER)[number];

/** Samples per pixel of the warm-up render that starts each estimator's calibration. */
export const CALIBRATION_SPP = 8;
/**
 * Shortest time (ms) a timed calibration render should take. Shorter renders are
 * dominated by the fixed cost of a dispatch and by the resolution of the clock
 * (0.1 ms for the CPU fallback in a browser), so their spp is raised until they
 * last about this long (calibrationSpp).
 */
export const CALIBRATION_TARGET_MS = 10;
/** Calibration renders per estimator; their median time sets the cost per sample. */
export const CALIBRATION_RUNS = 3;
/**
 * Untimed passes over all five estimators before any is timed: the first runs of
 * a code path are slow (a GPU may still be raising its clocks; JavaScript
 * compiles the CPU fallback's estimators, which share code, over several calls,
 * hence two passes there) and would make the estimator timed first look costlier
 * than it is. The last pass's times only choose the calibration spp (calibrationSpp).
 */
export const CALIBRATION_WARMUP: Readonly<Record<'gpu' | 'cpu', number>> = { gpu: 1, cpu: 2 };
/**
 * Renders per image of the comparison: the image is the first, its time the
 * median of all, so that one frame delayed by other work on the machine does not
 * decide which estimator looks cheaper.
 */
export const TIMING_RUNS = 3;
/**
 * The slope of a sweep is fitted to the points with spp ≥ FIT_MIN_SPP only. At
 * smaller spp the fixed cost of a dispatch dominates the time, which then barely
 * grows while the RMSE falls, and the fitted slope would be steeper than −½.
 */
export const FIT_MIN_SPP = 16;

/**
 * Colours (Okabe & Ito's colour-blind-safe set) and dash patterns of the sweep's
 * series, so that the curves differ in more than colour.
 */
export const SERIES_STYLE: Readonly<Record<EstimatorKey, { color: string; dash: number[] }>> = {
  biased: { color: '#d55e00', dash: [] },
  delta: { color: '#0072b2', dash: [10, 5] },
  ratio: { color: '#009e73', dash: [2, 4] },
  residual: { color: '#cc79a7', dash: [12, 4, 3, 4] },
  urm: { color: '#e69f00', dash: [6, 3] },
};

/** The median of a non-empty list (the mean of the middle two for an even count). */
export function median(values: readonly number[]): number {
  if (values.length === 0) throw new Error('median of an empty list');
  const sorted = [...values].sort((a, b) => a - b);
  const middle = Math.floor(sorted.length / 2);
  return sorted.length % 2 === 1 ? sorted[middle]! : (sorted[middle - 1]! + sorted[middle]!) / 2;
}

/**
 * The spp of the timed calibration renders, from the warm-up render (warmupMs at
 * warmupSpp): warmupSpp times the power of two that brings a render to at least
 * targetMs, at most max. A warm-up too fast for the clock (0 ms) gives max.
 */
export function calibrationSpp(
  warmupMs: number,
  warmupSpp = CALIBRATION_SPP,
  targetMs = CALIBRATION_TARGET_MS,
  max = SPP_MAX,
): number {
  if (!(warmupMs > 0)) return max;
  if (warmupMs >= targetMs) return Math.min(warmupSpp, max);
  return Math.min(warmupSpp * 2 ** Math.ceil(Math.log2(targetMs / warmupMs)), max);
}

/** Time per sample (ms) from renders at spp samples per pixel: median time over spp. */
export function costPerSample(milliseconds: readonly number[], spp: number): number {
  return median(milliseconds) / Math.max(spp, 1);
}

/**
 * The spp that spends budgetMs at costPerSampleMs per sample:
 * max(1, round(budget/cost)), clamped to the kernel's 1 … SPP_MAX. A cost that
 * is zero or not finite (a timer that returned nothing) gives the cap, so the
 * estimator is not starved by a broken measurement.
 */
export function equalTimeSpp(budgetMs: number, costPerSampleMs: number, max = SPP_MAX): number {
  if (!(costPerSampleMs > 0) || !Number.isFinite(costPerSampleMs)) return max;
  if (!(budgetMs > 0)) return 1;
  return Math.min(Math.max(1, Math.round(budgetMs / costPerSampleMs)), max);
}

export interface EqualTimePlan {
  /** The time the reference estimator takes at the chosen spp (ms). */
  budgetMs: number;
  /** Samples per pixel of each estimator in the equal-time row. */
  spp: Record<EstimatorKey, number>;
}

/**
 * Equal-time allocation: the budget is the reference estimator's cost per sample
 * times spp, and every estimator gets equalTimeSpp(budget, its cost). The
 * reference itself gets spp back (up to the clamp).
 */
export function planEqualTime(
  costs: Readonly<Record<EstimatorKey, number>>,
  reference: EstimatorKey,
  spp: number,
  max = SPP_MAX,
): EqualTimePlan {
  const budgetMs = costs[reference] * spp;
  const allocation = {} as Record<EstimatorKey, number>;
  for (const key of ESTIMATOR_ORDER) allocation[key] = equalTimeSpp(budgetMs, costs[key], max);
  return { budgetMs, spp: allocation };
}

/** The points a slope is fitted to: those with n ≥ minSpp, or all if fewer than two qualify. */
function fitRange(points: readonly SweepPoint[], minSpp: number): readonly SweepPoint[] {
  const tail = points.filter((p) => p.n >= minSpp);
  return tail.length >= 2 ? tail : points;
}

/**
 * The fitted exponent p of RMSE ∝ time^p over the points with n ≥ minSpp (all
 * points if fewer than two qualify); null without two usable points.
 */
export function timeSlope(points: readonly SweepPoint[], minSpp = FIT_MIN_SPP): number | null {
  // A time of 0 (a coarse wall clock on a tiny render) has no logarithm.
  const used = fitRange(
    points.filter((p) => p.milliseconds > 0),
    minSpp,
  );
  return logLogSlope(
    used.map((p) => p.milliseconds),
    used.map((p) => p.rmse),
  );
}

/**
 * The fitted exponent p of RMSE ∝ spp^p over the same points: free of timing
 * noise, it shows the −½ of an unbiased estimator (physics.md §4) however busy
 * the machine is, and a plateau (p near 0) for a biased one.
 */
export function sppSlope(points: readonly SweepPoint[], minSpp = FIT_MIN_SPP): number | null {
  const used = fitRange(points, minSpp);
  return logLogSlope(
    used.map((p) => p.n),
    used.map((p) => p.rmse),
  );
}

/** True when estimator is one of the five keys. */
export function isEstimatorKey(estimator: string): estimator is EstimatorKey {
  return (ESTIMATOR_ORDER as readonly string[]).includes(estimator);
}
