// Delta tracking: hidden tests. They run the estimator on media the statement does not
// show: extinction() keeps its signature, but behind it is a Lorentzian bump
//   σt(s) = σ0 (1 + a (2/(1 + x²) − 1)),  x = (s − c)/w,
// (σ0(1 − a) ≤ σt ≤ σ0(1 + a), so the statement's majorant bound still holds) whose
// centre c and width w the harness passes as inputs the student's function never
// receives. Every case is drawn from the grading seed, and each check tests the mean
// against e^{−τ}, that estimates are 0 or 1, and the lookups and random numbers per
// estimate (src/grading/checks/tracking.ts). Design and power: see HIDDEN_DESIGN below
// and the README's table.
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import type {
  MediumFamily,
  TrackingArgs,
  TrackingCase,
  TrackingCheck,
} from '../../src/grading/checks/tracking.ts';

const f = Math.fround;

/** ∫₀^s σt for the bump: σ0 [(1 − a) s + 2 a w (atan((s − c)/w) + atan(c/w))]. */
function bumpDepth(sigma0: number, a: number, c: number, w: number, s: number): number {
  return sigma0 * ((1 - a) * s + 2 * a * w * (Math.atan((s - c) / w) + Math.atan(c / w)));
}

export const BUMP_MEDIUM: MediumFamily = {
  id: 'bump',
  parameters: ['sbg_bumpCentre', 'sbg_bumpWidth'],
  body: [
    '  let x = (s - sbg_bumpCentre) / sbg_bumpWidth;',
    '  return sigma0 * (1.0 + amplitude * (2.0 / (1.0 + x * x) - 1.0));',
  ].join('\n'),
  sigma: ([sigma0, a], [c = 0, w = 1], s) => {
    const x = (s - c) / w;
    return sigma0 * (1 + a * (2 / (1 + x * x) - 1));
  },
  tau: ([sigma0, a], [c = 0, w = 1], s) => bumpDepth(sigma0, a, c, w, s),
};

/**
 * A seeded bump medium whose transmittance is near `target` (drawn in [tLow, tHigh]):
 * d log-uniform in [0.2, 5], a in [0, aMax], c in [0, d], w in [0.1d, 0.6d], σ0 from
 * the target τ, σ̄ = σ0 (1 + a)·(ratio in [1.05, ratioMax]). All values f32.
 */
function bumpCase(
  r: CaseSampler,
  tLow: number,
  tHigh: number,
  aMax: number,
  ratioMax: number,
): TrackingCase {
  const d = r.logUniform(0.2, 5);
  const a = r.uniform(0, aMax);
  const c = r.uniform(0, d);
  const w = r.uniform(0.1 * d, 0.6 * d);
  const target = r.uniform(tLow, tHigh);
  const sigma0 = f(-Math.log(target) / bumpDepth(1, a, c, w, d));
  const majorant = f(sigma0 * (1 + a) * r.uniform(1.05, ratioMax));
  return { args: [sigma0, a, d, majorant] as TrackingArgs, params: [c, w] };
}

/** Calls per case and the checks' false-fail probability (split over their z-tests). */
export const HIDDEN_DESIGN = {
  media: 4,
  calls: 32768,
  transmittance: [0.85, 0.95],
  thickCalls: 8192,
  thickTransmittance: [0.008, 0.03],
  noMediumCalls: 8192,
  alpha: 1e-6,
} as const;

function hiddenMedia(seed: number): TrackingCase[] {
  const r = caseSampler(seed, 'delta-tracking hidden media');
  const [lo, hi] = HIDDEN_DESIGN.transmittance;
  return Array.from({ length: HIDDEN_DESIGN.media }, () => bumpCase(r, lo, hi, 0.9, 2.5));
}

function thickMedium(seed: number): TrackingCase[] {
  const r = caseSampler(seed, 'delta-tracking thick medium');
  const [lo, hi] = HIDDEN_DESIGN.thickTransmittance;
  return [bumpCase(r, lo, hi, 0.5, 1.5)];
}

/** σ0 = 0 with a positive majorant (every collision null: T = 1, L ~ Poisson(σ̄d)), and σ̄ = 0. */
function noMedium(seed: number): TrackingCase[] {
  const r = caseSampler(seed, 'delta-tracking no medium');
  const d = r.logUniform(0.2, 5);
  const majorant = f(r.logUniform(0.5, 6) / d);
  const a = r.uniform(0, 0.9);
  const c = r.uniform(0, d);
  const w = r.uniform(0.1 * d, 0.6 * d);
  const d2 = r.logUniform(0.2, 5);
  return [
    { args: [0, a, d, majorant], params: [c, w] },
    { args: [0, a, d2, 0], params: [c, w] },
  ];
}

const TESTS = { mean: true, binary: true, work: true } as const;

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'tracking',
    name: 'Delta tracking on hidden media',
    points: 3,
    message:
      'On media the statement does not show (the same extinction(), another σt(s)) your ' +
      'estimator is not delta tracking.',
    family: BUMP_MEDIUM,
    cases: hiddenMedia,
    n: HIDDEN_DESIGN.calls,
    tests: TESTS,
    alpha: HIDDEN_DESIGN.alpha,
  } satisfies TrackingCheck,
  {
    kind: 'tracking',
    name: 'An optically thick hidden medium',
    points: 1,
    message: 'In an optically thick medium your estimator is not delta tracking.',
    family: BUMP_MEDIUM,
    cases: thickMedium,
    n: HIDDEN_DESIGN.thickCalls,
    tests: TESTS,
    alpha: HIDDEN_DESIGN.alpha,
  } satisfies TrackingCheck,
  {
    kind: 'tracking',
    name: 'No medium',
    points: 2,
    message:
      'With σt ≡ 0 every collision is null and the walk must escape: T = 1 every time, with ' +
      'one lookup per tentative collision (a loop cap that returns "absorbed" biases T low). ' +
      'A majorant of 0 means no medium: return 1 before drawing any random number ' +
      '(−ln(1 − ξ)/0 is not a distance).',
    family: BUMP_MEDIUM,
    cases: noMedium,
    n: HIDDEN_DESIGN.noMediumCalls,
    tests: TESTS,
    alpha: HIDDEN_DESIGN.alpha,
  } satisfies TrackingCheck,
];

/** The hidden media under a seed, for the power table and the tests. */
export const HIDDEN_CASES = { hiddenMedia, thickMedium, noMedium };
