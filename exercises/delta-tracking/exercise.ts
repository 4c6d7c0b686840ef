// Delta-tracking transmittance (chapter 6): the public part of the exercise,
// graded by a z-test of the mean against exp(−τ) and of the variance against the
// binary estimator's T(1 − T).
import type { ExerciseDefinition, MonteCarloCheck } from '../../src/grading/exercise.ts';

/** Exact optical depth of σt(s) = σ0 (1 + a sin(3 s)) over [0, d]: σ0 (d + a (1 − cos 3d)/3). */
export function opticalDepth(sigma0: number, amplitude: number, d: number): number {
  const f = Math.fround;
  const s0 = f(sigma0);
  const a = f(amplitude);
  const dd = f(d);
  return s0 * (dd + (a * (1 - Math.cos(3 * dd))) / 3);
}

/**
 * Statistical design. n = 65536 independent calls per case, two-sided α = 1e-6
 * (pass when |z| ≤ 4.89).
 * - Reference (a correct delta tracker, outputs Bernoulli(T)): the exact binomial
 *   probability of |z| > 4.89 is 1.0e-6 at the public case (T = 0.1552, by direct
 *   summation of the binomial pmf) and 1.3e-6 at the thick case (T = 0.0083,
 *   nT = 544, the upper tail slightly heavier than the normal's). For a binary
 *   estimator s² = m(1 − m)·n/(n − 1) is a function of the mean, so the variance test
 *   fails only together with the mean test. A seed therefore fails the reference
 *   with probability < 3e-6 over all checks; the self-test pins three seeds exactly.
 * - Power (z of each wrong submission in wrong/, mean ± spread from its own
 *   variance): exp of a one-sample optical depth, mean z = 54 ± 0.6 (public) and
 *   9.1 ± 0.11 (thick), variance z = −83 and −23; ignoring null collisions, mean
 *   z = −75 ± 0.9 (public) and −14 ± 0.6 (thick); ratio tracking, right mean but
 *   variance z = −59 (public) and −13 (thick). The closest call, the thick-case mean
 *   of the exp(−τ̂) submission, is 37 of its own spreads beyond the threshold.
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
    n: 65536,
    expected: Math.exp(-opticalDepth(args[0], args[1], args[2])),
    alpha: 1e-6,
  };
}

const PUBLIC_CASE = [1, 0.9, 1.5, 2] as const;

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
  ],
  gradingNotes:
    'n = 65536 calls; mean z-test against exp(−τ) and variance z-test against T(1 − T), ' +
    'two-sided α = 1e-6 (|z| ≤ 4.89). Public: σ0 = 1, a = 0.9, d = 1.5, σ̄ = 2. Hidden: thick ' +
    'segment, σ0 = 0, σ̄ = 0.',
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
  helpers: {
    imports: ['import package::rng::rngNextFloat;'],
    wgsl: `fn extinction(sigma0: f32, amplitude: f32, s: f32) -> f32 {
  return sigma0 * (1.0 + amplitude * sin(3.0 * s));
}
fn sbg_keepHelpers(state: ptr<function, u32>) -> f32 {
  return rngNextFloat(state);
}`,
  },
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
  ],
};
