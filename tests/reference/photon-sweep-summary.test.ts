// The readouts of <sb-photon-map>'s sweep (src/widgets/photon-map/summary.ts) on
// synthetic series with known laws: a fixed radius whose error is bias ⊕ noise, a
// progressive radius with RMSE ∝ N^(−2/7) exactly, and path tracing with ∝ t^(−1/2).
import { describe, expect, it } from 'vitest';
import type { SweepPoint } from '../../src/widgets/base/sweep.ts';
import { progressiveRadius } from '../../src/widgets/photon-map/model.ts';
import { percent, summariseSweep } from '../../src/widgets/photon-map/summary.ts';

const STEPS = [1, 2, 4, 8, 16, 32, 64];
const PER_STEP = 4096;

describe('photon-map sweep summary', () => {
  it('reports the fixed-radius plateau, and fits only the series with a power law', () => {
    // Fixed r: bias 0.003 (independent of N) ⊕ noise 0.4/√N, √(0.003² + 0.00078²) = 0.0031 at the end; time = 100 ms + 0.002 ms·N
    // (the fixed gather cost dominates at small N).
    const fixed: SweepPoint[] = STEPS.map((n) => ({
      n,
      rmse: Math.hypot(0.003, 0.4 / Math.sqrt(PER_STEP * n)),
      milliseconds: 100 + 0.002 * PER_STEP * n,
    }));
    const progressive: SweepPoint[] = STEPS.map((n) => ({
      n,
      rmse: 0.1 * (PER_STEP * n) ** (-2 / 7),
      milliseconds: 0.01 * PER_STEP * n,
    }));
    const pathTraced: SweepPoint[] = STEPS.map((n) => ({
      n,
      rmse: 2 / Math.sqrt(40 * n),
      milliseconds: 40 * n,
    }));
    const radiusAt = (photons: number): number => progressiveRadius(0.04, 65536, photons);
    const s = summariseSweep(fixed, progressive, pathTraced, PER_STEP, radiusAt);
    const change = fixed[6]!.rmse / fixed[4]!.rmse - 1;
    expect(s.plateau).toBe(
      `0.0031 at N = 262,144; ${percent(change)} over the last 4× N (noise alone: −50 %, bias alone: 0 %)`,
    );
    expect(change).toBeGreaterThan(-0.1);
    expect(s.progressive).toBe(
      'p = −0.29 vs N (expected −0.29), −0.29 vs time; r from 0.0594 to 0.0328 m',
    );
    expect(s.pathTracing).toBe('p = −0.5 vs time (expected −0.5)');
  });

  it('says so when the sweep stopped before it had two points', () => {
    const one: SweepPoint[] = [{ n: 1, rmse: 0.01, milliseconds: 10 }];
    const s = summariseSweep(one, one, one, PER_STEP, () => 0.04);
    expect(s.plateau).toBe('too few points');
    expect(s.progressive).toContain('p = no fit vs N');
    expect(s.pathTracing).toBe('p = no fit vs time (expected −0.5)');
  });

  it('formats signed percentages with a typographic minus', () => {
    expect(percent(-0.123)).toBe('−12 %');
    expect(percent(0.05)).toBe('+5 %');
  });
});
