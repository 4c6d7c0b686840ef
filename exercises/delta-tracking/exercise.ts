// Delta-tracking transmittance (chapter 6): the public part of the exercise. The page
// bundles this file, so it holds only what the statement shows: the public medium
// σ0(1 + a sin 3s), the public case and its checks. The hidden media live in hidden.ts.
import type { ExerciseDefinition, MonteCarloCheck } from '../../src/grading/exercise.ts';
import {
  trackingHelpers,
  type MediumFamily,
  type TrackingArgs,
  type TrackingCheck,
} from '../../src/grading/checks/tracking.ts';

/** Exact optical depth of σt(s) = σ0 (1 + a sin(3 s)) over [0, d]: σ0 (d + a (1 − cos 3d)/3). */
export function opticalDepth(sigma0: number, amplitude: number, d: number): number {
  const f = Math.fround;
  const s0 = f(sigma0);
  const a = f(amplitude);
  const dd = f(d);
  return s0 * (dd + (a * (1 - Math.cos(3 * dd))) / 3);
}

/** The statement's medium behind extinction(), with its float64 twin. */
export const SINE_MEDIUM: MediumFamily = {
  id: 'sine',
  parameters: [],
  body: '  return sigma0 * (1.0 + amplitude * sin(3.0 * s));',
  sigma: ([sigma0, a], _params, s) => sigma0 * (1 + a * Math.sin(3 * s)),
  tau: ([sigma0, a], _params, s) => opticalDepth(sigma0, a, s),
};

/** Calls per public case, and the two-sided significance of each public z-test. */
export const PUBLIC_CALLS = 65536;
export const PUBLIC_ALPHA = 1e-6;

/**
 * Statistical design of the public checks (T = 0.9077 at the public case, chosen near
 * 0.9 so that n stays moderate). n = 2^16 calls, |z| ≤ 4.89 (α = 1e-6, normal
 * approximation: the skewness of the sum, (1 − 2T)/√(nT(1 − T)) = −0.011, changes the
 * tail by < 5 %). A relative bias of 1 % moves the mean's z by
 * 0.01·√(nT/(1 − T)) = 8.03, so it fails with probability Φ(8.03 − 4.89) = 0.9992.
 * For a binary estimator s² = m(1 − m)·n/(n − 1), so the variance test fails together
 * with a biased mean; it is there for non-binary estimators (ratio tracking, e^{−τ̂}).
 */
export function deltaTrackingCheck(
  kind: 'mean' | 'variance',
  args: readonly [number, number, number, number],
  name: string,
  points: number,
  message: string,
): MonteCarloCheck {
  return {
    kind,
    name,
    points,
    message,
    args,
    n: PUBLIC_CALLS,
    expected: Math.exp(-opticalDepth(args[0], args[1], args[2])),
    alpha: PUBLIC_ALPHA,
  };
}

export const PUBLIC_CASE = [0.1, 0.9, 0.6, 0.2] as const;

/** Lookups and random numbers per estimate on the public case (see checks/tracking.ts). */
export const PUBLIC_WORK_CHECK: TrackingCheck = {
  kind: 'tracking',
  name: 'Lookups and random numbers per estimate',
  points: 1,
  message:
    'Your estimator does not use the medium as delta tracking does: one extinction() lookup ' +
    'per tentative collision inside the segment (none for the step that leaves it), one ' +
    'random number for each tentative distance and one for each real/null decision.',
  family: SINE_MEDIUM,
  cases: () => [{ args: PUBLIC_CASE as TrackingArgs, params: [] }],
  n: 16384,
  tests: { work: true },
  alpha: PUBLIC_ALPHA,
};

export const EXERCISE: ExerciseDefinition = {
  id: 'delta-tracking',
  chapter: '06-unbiased-transmittance',
  title: 'Delta-tracking transmittance',
  starter: `// Delta (Woodcock) tracking of the transmittance through [0, d] of the medium
// σt(s) = extinction(sigma0, amplitude, s), with majorant sigmaMaj ≥ σt(s).
// rngNextFloat(state) returns the next uniform number in [0, 1).
// Return 1.0 if the walk leaves the segment, 0.0 if it is absorbed by a real collision.
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  var t = 0.0;
  // Your loop here.
  return 1.0;
}
`,
  signature:
    'fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32',
  hints: [
    'loop { t += -log(1.0 - rngNextFloat(state)) / sigmaMaj; if (t >= d) { return 1.0; } ... }',
    'A collision is real with probability σt(t)/σ̄: compare rngNextFloat(state) * sigmaMaj with extinction(...).',
    'Return 0 or 1 only; do not return a weight or exp(−something): that is another estimator.',
    'The grader counts your extinction() calls and random numbers: one lookup per tentative ' +
      'collision inside [0, d], one random number per distance and one per real/null decision.',
  ],
  gradingNotes:
    'Public: n = 65536 calls at σ0 = 0.1, a = 0.9, d = 0.6, σ̄ = 0.2; mean z-test ' +
    'against exp(−τ) and variance z-test against T(1 − T), two-sided α = 1e-6 (|z| ≤ 4.89), and ' +
    'the extinction() lookups and random numbers per estimate. Hidden checks run the same tests ' +
    'on media the statement does not show.',
  subject: {
    name: 'deltaTracking',
    params: [
      { name: 'sigma0', type: 'f32' },
      { name: 'amplitude', type: 'f32' },
      { name: 'd', type: 'f32' },
      { name: 'sigmaMaj', type: 'f32' },
      { name: 'state', type: 'ptr<function, u32>' },
    ],
    result: 'f32',
  },
  helpers: trackingHelpers(SINE_MEDIUM),
  reference: `import package::tracking::sampleFreeFlight;
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  if (sigmaMaj <= 0.0) {
    return 1.0;
  }
  var t = 0.0;
  var estimate = 1.0;
  // Breaks, then one return: naga (Firefox) rejects a function that ends in a loop.
  loop {
    t += sampleFreeFlight(sigmaMaj, rngNextFloat(state));
    if (t >= d) {
      break;
    }
    if (rngNextFloat(state) * sigmaMaj < extinction(sigma0, amplitude, t)) {
      estimate = 0.0;
      break;
    }
  }
  return estimate;
}`,
  checks: [
    deltaTrackingCheck(
      'mean',
      PUBLIC_CASE,
      'Mean equals exp(−τ)',
      3,
      'Your estimator is biased: its average over many calls is not exp(−τ). Check that a ' +
        'collision is real with probability σt(t)/σ̄ (null collisions continue) and that you ' +
        'return 1 only when t ≥ d.',
    ),
    deltaTrackingCheck(
      'variance',
      PUBLIC_CASE,
      'Variance of a binary estimator',
      2,
      'Your estimator does not have the variance T(1 − T) of delta tracking: it must return ' +
        'exactly 0 or 1 per call. Returning a weight (ratio tracking) or exp(−τ̂) is another estimator.',
    ),
    PUBLIC_WORK_CHECK,
  ],
};
