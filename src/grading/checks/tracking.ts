// Checks of a delta-tracking estimator (chapter 6) that test the algorithm, not the
// numbers. The student's function sees the medium only through extinction() and draws
// random numbers only through rngNextFloat(); both are helpers linked in front of the
// submission, and both count their calls in private counters the harness writes out
// (Helpers.counters). A check then runs the estimator on media given by a MediumFamily:
// the public one is the statement's σ0(1 + a sin 3s); hidden ones (hidden.ts) put
// another σt(s) behind the same function, with parameters passed as extra inputs the
// student's code never receives as arguments, so τ in closed form, or T copied from the
// statement, gives the wrong answer there.
//
// Three tests, all exact in float64 for the medium of each case:
//   mean    z of Σ X against Σ n T_k (pooled over the cases), T = e^{−τ(d)};
//   binary  every estimate is exactly 0 or 1;
//   work    extinction() lookups L and random numbers D per estimate. Tentative
//           collisions form a Poisson process of rate σ̄ on [0, d]; one at s needs a
//           lookup when the walk survived to s, which has probability e^{−τ(s)}
//           (thinning: real collisions are a Poisson process of rate σt), so
//             E[L]        = σ̄ ∫₀^d e^{−τ(s)} ds,
//             E[L(L − 1)] = 2 ∫₀^d σ̄ (σ̄ − σt(s)) ∫_s^d e^{−τ(u)} du ds
//           (the pair correlation of two counted collisions s < u: the one at s is
//           null, no real collision before u). L's sample mean and variance are
//           z-tested against these; a lookup also at the step that leaves the segment
//           (L + X) is accepted too. Random numbers: one per tentative distance and one
//           per real/null decision, so an absorbed walk draws D = 2L and an escaped one
//           D − 2L ∈ {−1, 0, 1, 2} (the four orders of "draw, look up, test"); with
//           σ̄ = 0 the walk must return 1 with L = D = 0.
import type { CheckResult } from '../types.ts';
import type { Helpers } from '../exercise.ts';
import { normalCdf, normalCritical } from '../../statistics/distributions.ts';
import { mixSeed } from '../stats.ts';
import { saltOf } from './generated.ts';
import type { CheckRuntime } from './runtime.ts';

/** Names of the helpers' counters (reserved prefix: a submission cannot touch them). */
export const LOOKUP_COUNTER = 'sbg_lookups';
export const DRAW_COUNTER = 'sbg_draws';

/**
 * Arguments of the estimator: σ0, a, d, σ̄ (f32 values), then any of its own (the null-
 * scattering exercise passes P_n as the fifth).
 */
export type TrackingArgs = readonly [number, number, number, number, ...number[]];

/** A family of media behind extinction(sigma0, amplitude, s). */
export interface MediumFamily {
  id: string;
  /** Names of the f32 parameters the harness passes (e.g. a bump's centre and width). */
  parameters: readonly string[];
  /**
   * WGSL statements of extinction(sigma0: f32, amplitude: f32, s: f32) -> f32 after the
   * lookup is counted; they may read the parameters by name.
   */
  body: string;
  /** σt(s) and τ(0 → s) in float64 for the case's (f32) arguments and parameters. */
  sigma: (args: TrackingArgs, params: readonly number[], s: number) => number;
  tau: (args: TrackingArgs, params: readonly number[], s: number) => number;
}

export interface TrackingCase {
  args: TrackingArgs;
  /** The medium's parameters, in MediumFamily.parameters order. */
  params: readonly number[];
}

export interface TrackingCheck {
  kind: 'tracking';
  name: string;
  points: number;
  message: string;
  family: MediumFamily;
  /** The cases under a grading seed (hidden checks draw them; public ones are fixed). */
  cases: (seed: number) => readonly TrackingCase[];
  /** Calls per case. */
  n: number;
  tests: { mean?: boolean; binary?: boolean; work?: boolean; secondMoment?: boolean };
  /** Probability that a correct delta tracker fails this check (split over its z-tests). */
  alpha: number;
  /**
   * Exact E[X²] and E[X⁴] of an estimator that is not binary (null scattering: Miller et
   * al. 2019), in float64 for a case. When given, the mean test uses Var = E[X²] − T² and
   * the secondMoment test z-tests Σ X² against n·E[X²] with variance n(E[X⁴] − E[X²]²).
   */
  moments?: (family: MediumFamily, c: TrackingCase) => { second: number; fourth: number };
  /** The estimator's name in messages (default "delta tracking"). */
  estimator?: string;
}

/** The helpers (extinction and rngNextFloat, both counting) for a family of media. */
export function trackingHelpers(family: MediumFamily): Helpers {
  return {
    imports: [
      'import package::rng::pcgAdvance;',
      'import package::rng::pcgOutput;',
      'import package::rng::u32ToUnitFloat;',
    ],
    wgsl: [
      `var<private> ${LOOKUP_COUNTER}: u32;`,
      `var<private> ${DRAW_COUNTER}: u32;`,
      ...family.parameters.map((name) => `var<private> ${name}: f32;`),
      'fn extinction(sigma0: f32, amplitude: f32, s: f32) -> f32 {',
      `  ${LOOKUP_COUNTER} += 1u;`,
      family.body,
      '}',
      // rng.wesl's rngNextFloat, counted.
      'fn rngNextFloat(state: ptr<function, u32>) -> f32 {',
      `  ${DRAW_COUNTER} += 1u;`,
      '  *state = pcgAdvance(*state);',
      '  return u32ToUnitFloat(pcgOutput(*state));',
      '}',
    ].join('\n'),
    counters: [LOOKUP_COUNTER, DRAW_COUNTER],
    extraInputs: family.parameters,
  };
}

/** Exact (float64) moments of one case's estimate and lookup count. */
export interface TrackingExpectation {
  transmittance: number;
  /** E[X²] and E[X⁴] when the estimator is not binary (see TrackingCheck.moments). */
  second?: number;
  fourth?: number;
  /** Two accepted lookup conventions: canonical L, and L + X (a lookup at the exit step too). */
  lookups: readonly { mean: number; variance: number }[];
}

const QUADRATURE_STEPS = 8192;

export function trackingExpectation(
  family: MediumFamily,
  { args, params }: TrackingCase,
): TrackingExpectation {
  const [, , d, majorant] = args;
  const length = Math.max(d, 0);
  const T = Math.exp(-family.tau(args, params, length));
  if (majorant <= 0) {
    // No majorant: return 1 at once, no lookup, no draw (the statement's rule).
    return { transmittance: 1, lookups: [{ mean: 0, variance: 0 }] };
  }
  // G(s) = ∫₀^s e^{−τ} on a uniform grid (cumulative trapezoid; the integrands are smooth
  // and the relative error ~(d/M)² is far below the tests' resolution of ~1e-3).
  const m = QUADRATURE_STEPS;
  const h = length / m;
  const survival = new Float64Array(m + 1);
  const sigma = new Float64Array(m + 1);
  for (let i = 0; i <= m; i++) {
    survival[i] = Math.exp(-family.tau(args, params, i * h));
    sigma[i] = family.sigma(args, params, i * h);
  }
  const G = new Float64Array(m + 1);
  for (let i = 1; i <= m; i++)
    G[i] = (G[i - 1] ?? 0) + 0.5 * h * ((survival[i - 1] ?? 0) + (survival[i] ?? 0));
  const total = G[m] ?? 0;
  const meanL = majorant * total;
  let pair = 0;
  for (let i = 0; i <= m; i++) {
    const weight = i === 0 || i === m ? 0.5 : 1;
    pair += weight * h * majorant * (majorant - (sigma[i] ?? 0)) * (total - (G[i] ?? 0));
  }
  const factorial2 = 2 * pair;
  const varL = factorial2 + meanL - meanL * meanL;
  // E[L·X] = ∫ σ̄ (1 − σt(s)/σ̄) e^{−τ(d)} ds = T (σ̄ d − τ(d)).
  const tauD = family.tau(args, params, length);
  const meanLX = T * (majorant * length - tauD);
  const varLPlusX = varL + T * (1 - T) + 2 * (meanLX - meanL * T);
  return {
    transmittance: T,
    lookups: [
      { mean: meanL, variance: varL },
      { mean: meanL + T, variance: varLPlusX },
    ],
  };
}

export interface CaseOutput {
  values: ArrayLike<number>;
  lookups: ArrayLike<number>;
  draws: ArrayLike<number>;
}

export interface TrackingEvaluation {
  pass: boolean;
  mean?: { z: number; critical: number; pass: boolean; observed: number; expected: number };
  binary?: { nonBinary: number; pass: boolean };
  secondMoment?: { z: number; critical: number; pass: boolean; observed: number; expected: number };
  work?: {
    pass: boolean;
    badDraws: number;
    lookupZ: number;
    lookupVarianceZ: number;
    critical: number;
    observedLookups: number;
    expectedLookups: number;
    observedDraws: number;
  };
}

/** z of a pooled sum against its expectation; ±∞ or 0 when the variance is 0. */
function pooledZ(sum: number, expected: number, variance: number): number {
  if (variance > 0) return (sum - expected) / Math.sqrt(variance);
  return Math.abs(sum - expected) < 1e-9 ? 0 : sum > expected ? Infinity : -Infinity;
}

/** The check's tests on the outputs of its cases (pure; CPU-testable). */
export function evaluateTracking(
  tests: TrackingCheck['tests'],
  alpha: number,
  expectations: readonly TrackingExpectation[],
  outputs: readonly CaseOutput[],
): TrackingEvaluation {
  const zTests = (tests.mean ? 2 : 0) + (tests.work ? 2 : 0) + (tests.secondMoment ? 2 : 0);
  const share = zTests > 0 ? alpha / zTests : alpha;
  const result: TrackingEvaluation = { pass: true };
  if (tests.mean) {
    // The mean test gets two shares (it is the one whose power matters most).
    const critical = normalCritical(2 * share);
    let sum = 0;
    let expected = 0;
    let variance = 0;
    let count = 0;
    outputs.forEach((out, k) => {
      const e = expectations[k];
      const T = e?.transmittance ?? NaN;
      for (let i = 0; i < out.values.length; i++) sum += out.values[i] ?? NaN;
      expected += out.values.length * T;
      variance += out.values.length * (e?.second !== undefined ? e.second - T * T : T * (1 - T));
      count += out.values.length;
    });
    const z = pooledZ(sum, expected, variance);
    const pass = Number.isFinite(sum) && Math.abs(z) <= critical;
    result.mean = { z, critical, pass, observed: sum / count, expected: expected / count };
    result.pass &&= pass;
  }
  if (tests.secondMoment) {
    // Σ X² against Σ n E[X²], variance Σ n (E[X⁴] − E[X²]²): exact moments, normal z.
    const critical = normalCritical(2 * share);
    let sum = 0;
    let expected = 0;
    let variance = 0;
    let count = 0;
    outputs.forEach((out, k) => {
      const e = expectations[k];
      const second = e?.second ?? NaN;
      const fourth = e?.fourth ?? NaN;
      for (let i = 0; i < out.values.length; i++) sum += (out.values[i] ?? NaN) ** 2;
      expected += out.values.length * second;
      variance += out.values.length * (fourth - second * second);
      count += out.values.length;
    });
    const z = pooledZ(sum, expected, variance);
    const pass = Number.isFinite(sum) && Math.abs(z) <= critical;
    result.secondMoment = { z, critical, pass, observed: sum / count, expected: expected / count };
    result.pass &&= pass;
  }
  if (tests.binary) {
    let nonBinary = 0;
    for (const out of outputs)
      for (let i = 0; i < out.values.length; i++) {
        const v = out.values[i];
        if (v !== 0 && v !== 1) nonBinary++;
      }
    result.binary = { nonBinary, pass: nonBinary === 0 };
    result.pass &&= nonBinary === 0;
  }
  if (tests.work) {
    const critical = normalCritical(share);
    let badDraws = 0;
    let lookupSum = 0;
    let drawSum = 0;
    let count = 0;
    // Pooled over the cases with σ̄ > 0, for each accepted lookup convention.
    const conventions = [0, 1].map(() => ({ sum: 0, expected: 0, variance: 0, q: 0, q2: 0 }));
    outputs.forEach((out, k) => {
      const e = expectations[k] as TrackingExpectation;
      const deterministic = e.lookups.length === 1;
      for (let i = 0; i < out.values.length; i++) {
        const x = out.values[i] ?? NaN;
        const l = out.lookups[i] ?? 0;
        const dr = out.draws[i] ?? 0;
        lookupSum += l;
        drawSum += dr;
        count++;
        if (deterministic) {
          if (l !== 0 || dr !== 0) badDraws++;
          continue;
        }
        const extra = dr - 2 * l;
        if (x === 0 ? extra !== 0 : extra < -1 || extra > 2) badDraws++;
      }
      if (deterministic) return;
      e.lookups.forEach((moments, c) => {
        const acc = conventions[c];
        if (!acc) return;
        for (let i = 0; i < out.lookups.length; i++) {
          const dev = (out.lookups[i] ?? 0) - moments.mean;
          const q = dev * dev - moments.variance;
          acc.sum += dev;
          acc.q += q;
          acc.q2 += q * q;
        }
        acc.variance += out.lookups.length * moments.variance;
      });
    });
    let best = { z: 0, vz: 0, score: Infinity };
    for (const acc of conventions) {
      const z = pooledZ(acc.sum, 0, acc.variance);
      // Var of Σ((L − μ)² − v) estimated from the sample (its fourth moment).
      const vz = acc.q2 > 0 ? acc.q / Math.sqrt(acc.q2) : acc.q === 0 ? 0 : Infinity;
      const score = Math.max(Math.abs(z), Math.abs(vz));
      if (score < best.score) best = { z, vz, score };
    }
    const pass = badDraws === 0 && Math.abs(best.z) <= critical && Math.abs(best.vz) <= critical;
    const expectedLookups =
      outputs.reduce(
        (s, out, k) => s + out.values.length * (expectations[k]?.lookups[0]?.mean ?? 0),
        0,
      ) / Math.max(count, 1);
    result.work = {
      pass,
      badDraws,
      lookupZ: best.z,
      lookupVarianceZ: best.vz,
      critical,
      observedLookups: lookupSum / Math.max(count, 1),
      expectedLookups,
      observedDraws: drawSum / Math.max(count, 1),
    };
    result.pass &&= pass;
  }
  return result;
}

/**
 * Power of the pooled mean test against an estimator whose mean is (1 + bias)·T
 * (variance at the null's T(1 − T)): P(|Z + shift| > c).
 */
export function meanTestPower(
  expectations: readonly TrackingExpectation[],
  n: number,
  alpha: number,
  bias: number,
): { shift: number; power: number; critical: number } {
  let mean = 0;
  let variance = 0;
  for (const e of expectations) {
    mean += n * bias * e.transmittance;
    variance += n * e.transmittance * (1 - e.transmittance);
  }
  const critical = normalCritical(alpha);
  const shift = variance > 0 ? mean / Math.sqrt(variance) : Infinity;
  return {
    shift,
    critical,
    power: normalCdf(shift - critical) + normalCdf(-shift - critical),
  };
}

/** The z-tests' share of α for the mean test of a check (see evaluateTracking). */
export function meanTestAlpha(check: TrackingCheck): number {
  const zTests =
    (check.tests.mean ? 2 : 0) + (check.tests.work ? 2 : 0) + (check.tests.secondMoment ? 2 : 0);
  return zTests > 0 ? (2 * check.alpha) / zTests : check.alpha;
}

export async function runTrackingCheck(
  runtime: CheckRuntime,
  check: TrackingCheck,
  visibility: 'public' | 'hidden',
): Promise<CheckResult> {
  const cases = check.cases(runtime.seed);
  const helpers = trackingHelpers(check.family);
  const calls: number[][] = [];
  for (const c of cases) {
    const row = [...c.args, ...c.params];
    for (let i = 0; i < check.n; i++) calls.push(row);
  }
  // The same cases share one run (and one random stream) between checks.
  const shareKey = `${check.family.id}|${check.n}|${JSON.stringify(cases)}`;
  let output;
  try {
    output = await runtime.run(
      calls,
      mixSeed(runtime.seed, saltOf(shareKey)),
      `running the check "${check.name}"`,
      helpers,
      shareKey,
    );
  } catch (error) {
    // The submission compiled with the public helpers; should it not compile with this
    // check's medium (it can only see the same two functions), this check fails alone.
    const status = (error as { outcome?: { status?: string } }).outcome?.status;
    if (status !== 'compile-error' && status !== 'wrong-signature') throw error;
    return {
      name: check.name,
      visibility,
      verdict: 'fail',
      points: 0,
      maxPoints: check.points,
      message: `${check.message} Your code did not compile with this check's medium.`,
    };
  }
  const lookups = output.counters[0] ?? [];
  const draws = output.counters[1] ?? [];
  const outputs: CaseOutput[] = cases.map((_, k) => ({
    values: output.values.slice(k * check.n, (k + 1) * check.n),
    lookups: lookups.slice(k * check.n, (k + 1) * check.n),
    draws: draws.slice(k * check.n, (k + 1) * check.n),
  }));
  const expectations = cases.map((c): TrackingExpectation => {
    const e = trackingExpectation(check.family, c);
    if (!check.moments) return e;
    const { second, fourth } = check.moments(check.family, c);
    return { ...e, second, fourth };
  });
  const estimator = check.estimator ?? 'delta tracking';
  const e = evaluateTracking(check.tests, check.alpha, expectations, outputs);
  const where =
    visibility === 'public' && cases.length === 1 && cases[0]
      ? `${check.n} calls (${runtime.formatArgs(cases[0].args)})`
      : `${check.n} calls on each of ${cases.length} ${cases.length === 1 ? 'medium' : 'media'}`;
  const parts: string[] = [];
  if (e.mean)
    parts.push(
      `mean ${runtime.formatNumber(e.mean.observed)} against exp(−τ) averaging ` +
        `${runtime.formatNumber(e.mean.expected)}, z = ${e.mean.z.toFixed(2)} (pass when |z| ≤ ${e.mean.critical.toFixed(2)})`,
    );
  if (e.secondMoment)
    parts.push(
      `mean square ${runtime.formatNumber(e.secondMoment.observed)} against ` +
        `${runtime.formatNumber(e.secondMoment.expected)} for ${estimator}, z = ${e.secondMoment.z.toFixed(2)} ` +
        `(pass when |z| ≤ ${e.secondMoment.critical.toFixed(2)})`,
    );
  if (e.binary && e.binary.nonBinary > 0)
    parts.push(`${e.binary.nonBinary} estimates were neither 0 nor 1`);
  if (e.work)
    parts.push(
      `extinction() lookups per estimate ${e.work.observedLookups.toFixed(3)} against ` +
        `${e.work.expectedLookups.toFixed(3)} for delta tracking (z = ${e.work.lookupZ.toFixed(2)}, ` +
        `their variance z = ${e.work.lookupVarianceZ.toFixed(2)}; pass when |z| ≤ ${e.work.critical.toFixed(2)}), ` +
        `random numbers per estimate ${e.work.observedDraws.toFixed(3)}` +
        (e.work.badDraws > 0
          ? `; ${e.work.badDraws} estimates drew a number of random numbers that delta tracking cannot (one per tentative distance, one per real/null decision)`
          : ''),
    );
  const summary = `${where}: ${parts.join('; ')}.`;
  const failing: string[] = [];
  if (e.mean && !e.mean.pass) failing.push('its average is not exp(−τ)');
  if (e.secondMoment && !e.secondMoment.pass)
    failing.push(`its mean square (so its variance) is not that of ${estimator}`);
  if (e.binary && !e.binary.pass) failing.push('it does not return only 0 or 1');
  if (e.work && !e.work.pass)
    failing.push('it does not look up σt and draw random numbers as delta tracking does');
  const message = e.pass
    ? `Consistent with ${estimator}: ${summary}`
    : `${check.message} Here ${failing.join(', and ')}: ${summary}`;
  return {
    name: check.name,
    visibility,
    verdict: e.pass ? 'pass' : 'fail',
    points: e.pass ? check.points : 0,
    maxPoints: check.points,
    message,
  };
}
