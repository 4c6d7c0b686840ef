// Null-scattering transmittance: hidden tests. The same extinction(sigma0, amplitude, s)
// hides delta tracking's Lorentzian bump (exercises/delta-tracking/hidden.ts, BUMP_MEDIUM),
// whose centre and width the harness passes as inputs the student's function never sees,
// and every case (medium, majorant, P_n) is drawn from the grading seed. Each check runs the
// mean and mean-square z-tests with the estimator's exact moments (exercise.ts). P_n stays
// in [0.55, 0.9] and T ≥ 0.4 so that E[X⁴] stays within a few times E[X²]² (the normal
// approximation of the mean-square test needs a moderate fourth moment), and P_n keeps its
// distance from delta and ratio tracking's (deltaLikeProbability) so that both fail with
// certainty; tests/grading/nullScattering.test.ts checks the design over many seeds.
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import type {
  TrackingArgs,
  TrackingCase,
  TrackingCheck,
} from '../../src/grading/checks/tracking.ts';
import { BUMP_MEDIUM } from '../delta-tracking/hidden.ts';
import { nullScatteringMoments } from './exercise.ts';

const f = Math.fround;

/** ∫₀^d σt of the bump with σ0 = 1 (exercises/delta-tracking/hidden.ts). */
function bumpDepth(a: number, c: number, w: number, s: number): number {
  return (1 - a) * s + 2 * a * w * (Math.atan((s - c) / w) + Math.atan(c / w));
}

/**
 * P_n that delta tracking's variance would match: delta tracking has E[X²] = T, the estimator
 * exp(−∫(σ̄ − σn²/(σ̄P_n))), equal at P* = ∫σn²/(σ̄∫|σn|) (|σn| keeps it positive when σ̄
 * is low). The cases draw P_n a fraction u ∈ [0.35, 0.7] of the way from P* to ratio
 * tracking's 1, so that neither tracker has the estimator's variance, whatever the medium.
 */
function deltaLikeProbability(sigma: (s: number) => number, majorant: number, d: number): number {
  const steps = 512;
  let squares = 0;
  let magnitudes = 0;
  for (let i = 0; i < steps; i++) {
    const sigmaN = majorant - sigma(((i + 0.5) * d) / steps);
    squares += sigmaN * sigmaN;
    magnitudes += Math.abs(sigmaN);
  }
  return magnitudes > 0 ? Math.min(squares / (majorant * magnitudes), 1) : 1;
}

/**
 * A seeded bump medium with T near `target` ∈ [tLow, tHigh]: d log-uniform in [0.4, 3],
 * a ∈ [0.3, 0.9], c ∈ [0, d], w ∈ [0.1d, 0.6d], σ̄ = max σt·(ratio ∈ [rLow, rHigh]), and
 * P_n between delta tracking's P* and 1 (deltaLikeProbability), kept in [0.55, pMax].
 * All values f32.
 */
function bumpCase(
  r: CaseSampler,
  tLow: number,
  tHigh: number,
  ratioLow: number,
  ratioHigh: number,
  pMax: number,
): TrackingCase {
  const d = r.logUniform(0.4, 3);
  const a = r.uniform(0.3, 0.9);
  const c = r.uniform(0, d);
  const w = r.uniform(0.1 * d, 0.6 * d);
  const target = r.uniform(tLow, tHigh);
  const sigma0 = f(-Math.log(target) / bumpDepth(a, c, w, d));
  const majorant = f(sigma0 * (1 + a) * r.uniform(ratioLow, ratioHigh));
  const args: TrackingArgs = [sigma0, a, d, majorant];
  const star = deltaLikeProbability((s) => BUMP_MEDIUM.sigma(args, [c, w], s), majorant, d);
  const nullProbability = f(
    Math.min(Math.max(star + (1 - star) * r.uniform(0.35, 0.7), 0.55), pMax),
  );
  return { args: [sigma0, a, d, majorant, nullProbability], params: [c, w] };
}

export const HIDDEN_DESIGN = {
  validMedia: 4,
  lowMedia: 3,
  calls: 32768,
  lowCalls: 65536,
  noMediumCalls: 16384,
  alpha: 1e-6,
} as const;

function validMedia(seed: number): TrackingCase[] {
  const r = caseSampler(seed, 'null-scattering valid majorant');
  return Array.from({ length: HIDDEN_DESIGN.validMedia }, () =>
    bumpCase(r, 0.4, 0.7, 1.05, 1.5, 0.9),
  );
}

/** σ̄ at 0.5–0.75 of max σt: σn < 0 around the bump's peak; P_n ≤ 0.75, far from ratio tracking. */
function lowMedia(seed: number): TrackingCase[] {
  const r = caseSampler(seed, 'null-scattering low majorant');
  return Array.from({ length: HIDDEN_DESIGN.lowMedia }, () =>
    bumpCase(r, 0.4, 0.7, 0.5, 0.75, 0.75),
  );
}

/**
 * σ0 = 0 with σ̄ > 0: every vertex has σn = σ̄, so a null vertex carries 1/P_n and a real one
 * (probability 1 − P_n) gives 0: T = 1 with E[X²] = e^{σ̄d(1/P_n − 1)}. And σ̄ = 0: exactly 1.
 */
function noMedium(seed: number): TrackingCase[] {
  const r = caseSampler(seed, 'null-scattering no medium');
  const d = r.logUniform(0.4, 3);
  const majorant = f(r.uniform(0.5, 1.5) / d);
  const a = r.uniform(0, 0.9);
  const c = r.uniform(0, d);
  const w = r.uniform(0.1 * d, 0.6 * d);
  return [
    { args: [0, a, d, majorant, r.uniform(0.75, 0.9)], params: [c, w] },
    { args: [0, a, d, 0, r.uniform(0.75, 0.9)], params: [c, w] },
  ];
}

const TESTS = { mean: true, secondMoment: true } as const;
const ESTIMATOR = 'null-scattering tracking with the given P_n';

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'tracking',
    name: 'Hidden media, valid majorant, several P_n',
    points: 3,
    message:
      'On media the statement does not show (the same extinction(), another σt(s)) and other ' +
      'values of P_n, your estimator is not null-scattering tracking.',
    family: BUMP_MEDIUM,
    cases: validMedia,
    n: HIDDEN_DESIGN.calls,
    tests: TESTS,
    alpha: HIDDEN_DESIGN.alpha,
    moments: nullScatteringMoments,
    estimator: ESTIMATOR,
  } satisfies TrackingCheck,
  {
    kind: 'tracking',
    name: 'Hidden media, majorant below σt',
    points: 2,
    message:
      'On hidden media whose majorant is below σt around a peak, your estimator is biased or ' +
      'has the wrong variance: σn = σ̄ − σt is negative there and the factor σn/(σ̄·P_n) too.',
    family: BUMP_MEDIUM,
    cases: lowMedia,
    n: HIDDEN_DESIGN.lowCalls,
    tests: TESTS,
    alpha: HIDDEN_DESIGN.alpha,
    moments: nullScatteringMoments,
    estimator: ESTIMATOR,
  } satisfies TrackingCheck,
  {
    kind: 'tracking',
    name: 'No medium',
    points: 1,
    message:
      'With σt ≡ 0 every vertex has σn = σ̄: a null vertex carries 1/P_n and a real one ends ' +
      'the path with 0, so the mean is 1 and the mean square e^{σ̄d(1/P_n − 1)}. A majorant of ' +
      '0 means no medium: return 1 before drawing any random number.',
    family: BUMP_MEDIUM,
    cases: noMedium,
    n: HIDDEN_DESIGN.noMediumCalls,
    tests: TESTS,
    alpha: HIDDEN_DESIGN.alpha,
    moments: nullScatteringMoments,
    estimator: ESTIMATOR,
  } satisfies TrackingCheck,
];

export const HIDDEN_CASES = { validMedia, lowMedia, noMedium };
