// The readouts of <sb-photon-map>'s error-vs-time sweep, from its three series of
// points (chapter 10, "Bias versus variance"). A power law is fitted only where one
// is expected: progressive photon mapping (r ∝ N^(−1/7), RMSE ∝ N^(−2/7)) against N
// and against time, and path tracing (unbiased, RMSE ∝ t^(−1/2)) against time. The
// fixed-radius series gets none: its bias r²/10·∇²ρ does not fall with N, and at
// small N its time is mostly the fixed cost of the gather, so a slope through it
// would describe neither. It is summarised by where it ends and by what the last
// 4× photons still bought: photon noise alone (∝ N^(−1/2)) would give −50 %, bias
// alone 0 %.
import { formatNumber } from '../base/format.ts';
import { logLogSlope, type SweepPoint } from '../base/sweep.ts';
import { PROGRESSIVE_RMSE_EXPONENT } from './model.ts';

export interface PhotonSweepSummary {
  /** Fixed radius: the error at the largest N and its change over the last 4× N. */
  plateau: string;
  /** Progressive radius: fitted exponents against N and against time, and the radii used. */
  progressive: string;
  /** Path tracing: fitted exponent against time. */
  pathTracing: string;
}

/** A relative change as a signed percentage with a typographic minus, "−12 %". */
export function percent(change: number): string {
  return `${change >= 0 ? '+' : '−'}${formatNumber(Math.abs(100 * change), 2)} %`;
}

/** A fitted exponent with a typographic minus, or "no fit". */
function exponent(slope: number | null): string {
  return slope === null ? 'no fit' : formatNumber(slope, 2).replace('-', '−');
}

/**
 * @param photonsPerStep the sweep renders N = photonsPerStep·n photons at step n.
 * @param radiusAt the progressive radius at N photons.
 */
export function summariseSweep(
  fixed: readonly SweepPoint[],
  progressive: readonly SweepPoint[],
  pathTraced: readonly SweepPoint[],
  photonsPerStep: number,
  radiusAt: (photons: number) => number,
): PhotonSweepSummary {
  const last = fixed.at(-1);
  const earlier = last && fixed.find((q) => q.n * 4 === last.n);
  const plateau =
    last && earlier
      ? `${formatNumber(last.rmse, 3)} at N = ${(photonsPerStep * last.n).toLocaleString('en-US')}; ${percent(last.rmse / earlier.rmse - 1)} over the last 4× N (noise alone: −50 %, bias alone: 0 %)`
      : 'too few points';
  const photons = progressive.map((q) => photonsPerStep * q.n);
  const errors = progressive.map((q) => q.rmse);
  const radii =
    photons.length > 0
      ? `; r from ${formatNumber(radiusAt(photons[0]!), 3)} to ${formatNumber(radiusAt(photons.at(-1)!), 3)} m`
      : '';
  return {
    plateau,
    progressive: `p = ${exponent(logLogSlope(photons, errors))} vs N (expected ${exponent(PROGRESSIVE_RMSE_EXPONENT)}), ${exponent(
      logLogSlope(
        progressive.map((q) => q.milliseconds),
        errors,
      ),
    )} vs time${radii}`,
    pathTracing: `p = ${exponent(
      logLogSlope(
        pathTraced.map((q) => q.milliseconds),
        pathTraced.map((q) => q.rmse),
      ),
    )} vs time (expected −0.5)`,
  };
}
