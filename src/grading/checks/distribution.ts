// A sampler's output against an analytic distribution, with power against samplers
// that are right only at a few points. The public χ² check (grade.ts) feeds stratified
// uniforms and bins equiprobably, so a sampler that is exact at the strata edges and
// anything in between (e.g. linear between 21 quantiles) fills every bin exactly. This
// check feeds independent (unstratified) uniforms from the seed and applies two tests:
//   - Pearson's χ² in `bins` equiprobable bins whose edges are rotated by a seeded
//     offset u0 (bin j holds F(x) ∈ [(j + u0)/B, (j + 1 + u0)/B) mod 1), so no fixed
//     set of exact points can line up with them;
//   - the one-sample Kolmogorov–Smirnov test of the whole CDF (Stephens' finite-n
//     scaling, Kolmogorov's limiting distribution).
// Each test runs at α/2, so a correct sampler fails the check with probability ≤ α.
import type { CheckResult } from '../types.ts';
import {
  chiSquareCritical,
  chiSquareSurvival,
  kolmogorovCritical,
  kolmogorovScaled,
  noncentralChiSquareSurvival,
  normalCdf,
} from '../../statistics/distributions.ts';
import { mixSeed, seededUniforms } from '../stats.ts';
import { caseSampler, saltOf } from './generated.ts';
import type { CheckRuntime } from './runtime.ts';

/** One distribution to test under one seed. */
export interface DistributionCase {
  /** Says which distribution, for the message (hidden checks: no parameter values). */
  label: string;
  /** The sampler's arguments for a uniform ξ. */
  args: (xi: number) => number[];
  cdf: (x: number) => number;
  inverseCdf: (p: number) => number;
}

export interface DistributionCheck {
  kind: 'distribution';
  name: string;
  points: number;
  message: string;
  /** Independent uniforms per seed. */
  n: number;
  /** Equiprobable bins of the χ² test. */
  bins: number;
  /** Probability that a correct sampler fails the check (split between the two tests). */
  alpha: number;
  /** The distribution tested under a seed (e.g. HG with a seeded g). */
  draw: (seed: number) => DistributionCase;
  xLabel: string;
}

export interface DistributionStatistics {
  chiSquare: number;
  chiSquareCritical: number;
  chiSquarePValue: number;
  /** Stephens-scaled KS statistic and its critical value. */
  ks: number;
  ksCritical: number;
  /** Raw sup |F̂ − F|. */
  ksDistance: number;
  observed: number[];
  expected: number;
  offset: number;
}

/** Both tests on the probabilities p_i = F(x_i) of the samples (pure; CPU-testable). */
export function distributionStatistics(
  probabilities: readonly number[],
  bins: number,
  alpha: number,
  offset: number,
): DistributionStatistics {
  const n = probabilities.length;
  const observed = new Array<number>(bins).fill(0);
  for (const p of probabilities) {
    const shifted = p * bins - offset;
    const bin = ((Math.floor(shifted) % bins) + bins) % bins;
    observed[bin] = (observed[bin] ?? 0) + 1;
  }
  const expected = n / bins;
  const chiSquare = observed.reduce(
    (sum, o) => sum + ((o - expected) * (o - expected)) / expected,
    0,
  );
  const sorted = Float64Array.from(probabilities).sort();
  let distance = 0;
  for (let i = 0; i < n; i++) {
    const p = sorted[i] ?? 0;
    distance = Math.max(distance, (i + 1) / n - p, p - i / n);
  }
  return {
    chiSquare,
    chiSquareCritical: chiSquareCritical(alpha / 2, bins - 1),
    chiSquarePValue: chiSquareSurvival(chiSquare, bins - 1),
    ks: kolmogorovScaled(distance, n),
    ksCritical: kolmogorovCritical(alpha / 2),
    ksDistance: distance,
    observed,
    expected,
    offset,
  };
}

/**
 * Power of the check against an alternative sampler whose output has probability
 * G(p) = P(F(X) ≤ p) (G = identity for a correct sampler): the χ² test's power from the
 * noncentral χ² with λ = n·B·Σ(q_j − 1/B)² (q_j: the alternative's bin masses), taken as
 * the minimum over the seeded rotation u0; the KS test's power bounded below by the
 * normal approximation of F̂ at the point of largest |G(p) − p|. The check fails when
 * either test rejects, so its power is at least the larger of the two.
 */
export function distributionPower(
  n: number,
  bins: number,
  alpha: number,
  alternative: (p: number) => number,
): { chiSquare: number; ks: number; power: number; lambda: number; distance: number } {
  const critical = chiSquareCritical(alpha / 2, bins - 1);
  let worst = Infinity;
  let worstLambda = Infinity;
  for (let k = 0; k < 16; k++) {
    const u0 = k / 16;
    let sum = 0;
    for (let j = 0; j < bins; j++) {
      const a = (j + u0) / bins;
      const b = (j + 1 + u0) / bins;
      const q = b <= 1 ? alternative(b) - alternative(a) : 1 - alternative(a) + alternative(b - 1);
      sum += (q - 1 / bins) ** 2;
    }
    const lambda = n * bins * sum;
    const power = noncentralChiSquareSurvival(critical, bins - 1, lambda);
    if (power < worst) {
      worst = power;
      worstLambda = lambda;
    }
  }
  let distance = 0;
  let at = 0.5;
  for (let i = 1; i < 20000; i++) {
    const p = i / 20000;
    const gap = Math.abs(alternative(p) - p);
    if (gap > distance) {
      distance = gap;
      at = p;
    }
  }
  const root = Math.sqrt(n);
  const threshold = kolmogorovCritical(alpha / 2) / (root + 0.12 + 0.11 / root);
  const g = alternative(at);
  const sd = Math.sqrt(Math.max(g * (1 - g), 1e-300) / n);
  const ks = normalCdf((distance - threshold) / sd);
  return { chiSquare: worst, ks, power: Math.max(worst, ks), lambda: worstLambda, distance };
}

export async function runDistributionCheck(
  runtime: CheckRuntime,
  check: DistributionCheck,
  visibility: 'public' | 'hidden',
): Promise<CheckResult> {
  const salt = saltOf(`distribution:${check.name}`);
  const which = check.draw(runtime.seed);
  const offset = caseSampler(runtime.seed, `distribution offset:${check.name}`).uniform(0, 1);
  const uniform = seededUniforms(mixSeed(runtime.seed, salt));
  const calls: number[][] = [];
  for (let i = 0; i < check.n; i++) {
    calls.push(which.args(Math.min(Math.fround(uniform()), 1 - 2 ** -24)));
  }
  const { values } = await runtime.run(
    calls,
    mixSeed(runtime.seed, salt),
    `running the check "${check.name}"`,
  );
  const bad = values.findIndex((v) => !Number.isFinite(v));
  const probabilities = values.map((v) => Math.min(1, Math.max(0, which.cdf(v))));
  const stats = distributionStatistics(probabilities, check.bins, check.alpha, offset);
  const chiPass = stats.chiSquare <= stats.chiSquareCritical;
  const ksPass = stats.ks <= stats.ksCritical;
  const pass = bad < 0 && chiPass && ksPass;
  const summary =
    `${check.n} independent samples (${which.label}): χ² = ${stats.chiSquare.toFixed(1)} in ` +
    `${check.bins} equiprobable bins (critical ${stats.chiSquareCritical.toFixed(1)}), ` +
    `Kolmogorov–Smirnov (√n + 0.12 + 0.11/√n)·D = ${stats.ks.toFixed(2)} with D = ` +
    `${stats.ksDistance.toExponential(2)} (critical ${stats.ksCritical.toFixed(2)}); each test ` +
    `at significance ${check.alpha / 2}.`;
  const message = pass
    ? `Your samples follow the analytic distribution: ${summary}`
    : bad >= 0
      ? `${check.message} Your function returned ${runtime.formatNumber(values[bad] ?? NaN)} for some ξ.`
      : `${check.message} ${chiPass ? '' : 'The χ² test rejects it. '}${ksPass ? '' : 'The Kolmogorov–Smirnov test rejects it. '}${summary}`;
  // The figure shows the rotated bins in order; the bin that wraps around 1 is left out.
  const inner = Array.from({ length: check.bins - 1 }, (_, j) => j);
  return {
    name: check.name,
    visibility,
    verdict: pass ? 'pass' : 'fail',
    points: pass ? check.points : 0,
    maxPoints: check.points,
    message,
    figure: {
      kind: 'histogram',
      edges: Array.from({ length: check.bins }, (_, j) =>
        which.inverseCdf((j + offset) / check.bins),
      ),
      observed: inner.map((j) => stats.observed[j] ?? 0),
      expected: inner.map(() => stats.expected),
      xLabel: check.xLabel,
    },
  };
}
