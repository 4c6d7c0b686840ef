// Null-scattering transmittance with a given P_n (chapter 12, Miller, Georgiev & Jarosz
// 2019): the public part of the exercise. The student's estimator walks the tentative
// collisions of rate σ̄, takes each as a null vertex with the constant probability P_n
// (argument nullProbability) and multiplies its weight by σn/(σ̄·P_n), or returns 0 at a
// real vertex. It is not binary, so the checks test its mean against T = e^{−τ} with
// Var = E[X²] − T², and its mean square against E[X²] with variance E[X⁴] − E[X²]², all
// exact (src/grading/checks/tracking.ts with `moments`):
//   E[X^m] = exp(−∫₀^d (σ̄ − σn(s)^m/(σ̄^{m−1} P_n^{m−1})) ds)
// (Campbell's identity for the Poisson process of tentative collisions; m = 1 gives T).
// The public medium is chapter 6's σ0(1 + a sin 3s); hidden.ts puts others behind it.
import type { ExerciseDefinition } from '../../src/grading/exercise.ts';
import {
  trackingHelpers,
  type MediumFamily,
  type TrackingCase,
  type TrackingCheck,
} from '../../src/grading/checks/tracking.ts';
import { SINE_MEDIUM } from '../delta-tracking/exercise.ts';

/** Composite Simpson's rule on [a, b] with an even number of intervals (smooth integrands). */
function simpson(f: (x: number) => number, a: number, b: number, intervals = 2048): number {
  const h = (b - a) / intervals;
  let sum = f(a) + f(b);
  for (let i = 1; i < intervals; i++) sum += (i % 2 === 1 ? 4 : 2) * f(a + i * h);
  return (sum * h) / 3;
}

/**
 * E[X^m] of the null-scattering estimator with constant P_n on one case, in float64 for
 * the case's f32 arguments. σ̄ ≤ 0 or d ≤ 0: the estimator returns 1 without sampling.
 */
export function nullScatteringMoment(
  family: MediumFamily,
  { args, params }: TrackingCase,
  m: number,
): number {
  const [, , d, majorant, nullProbability = 1] = args;
  if (!(majorant > 0) || !(d > 0)) return 1;
  const rate = (s: number): number => {
    const sigmaN = majorant - family.sigma(args, params, s);
    return majorant - sigmaN ** m / (majorant ** (m - 1) * nullProbability ** (m - 1));
  };
  return Math.exp(-simpson(rate, 0, d));
}

export const nullScatteringMoments = (
  family: MediumFamily,
  c: TrackingCase,
): { second: number; fourth: number } => ({
  second: nullScatteringMoment(family, c, 2),
  fourth: nullScatteringMoment(family, c, 4),
});

/** Calls per public case, and the false-fail probability of each public check. */
export const PUBLIC_CALLS = 65536;
export const PUBLIC_ALPHA = 1e-6;

/**
 * Public cases: σ0, a, d, σ̄, P_n (f32). VALID has σ̄ = 1 above max σt = 0.8; LOW has σ̄ = 0.6
 * below max σt = 0.9, so σn < 0 on part of the ray. Design (n = 2^16, each z-test at
 * |z| ≤ 5.03): on VALID, forgetting to divide by P_n shifts the mean by z ≈ −44, using σt/σ̄
 * as the weight by +70, e^{−τ̂} of a one-point τ̂ by +11 and its mean square by −84, and delta
 * tracking (which ignores P_n) moves the mean square by +39; on LOW, clamping σn at 0 (or
 * delta tracking's clamp) shifts the mean by +33 and ratio tracking's mean square by −11.
 */
export const PUBLIC_VALID = [0.5, 0.6, 1.5, 1, 0.7] as const;
export const PUBLIC_LOW = [0.5, 0.8, 1.5, 0.6, 0.8] as const;

const TESTS = { mean: true, secondMoment: true } as const;

function publicCheck(
  name: string,
  args: readonly [number, number, number, number, number],
  message: string,
): TrackingCheck {
  return {
    kind: 'tracking',
    name,
    points: 3,
    message,
    family: SINE_MEDIUM,
    cases: () => [{ args, params: [] }],
    n: PUBLIC_CALLS,
    tests: TESTS,
    alpha: PUBLIC_ALPHA,
    moments: nullScatteringMoments,
    estimator: 'null-scattering tracking with this P_n',
  };
}

export const EXERCISE: ExerciseDefinition = {
  id: 'null-scattering',
  chapter: '12-beyond-the-lecture',
  title: 'Null-scattering transmittance with a given P_n',
  starter: `// Transmittance through [0, d] of the medium σt(s) = extinction(sigma0, amplitude, s) by the
// null-scattering path integral: tentative collisions at rate sigmaMaj (σ̄); each is a null
// vertex with probability nullProbability (P_n), else a real vertex that ends the shadow path.
// σn = σ̄ − σt may be negative (σ̄ below σt). rngNextFloat(state) returns a uniform in [0, 1).
fn nullScattering(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, nullProbability: f32, state: ptr<function, u32>) -> f32 {
  var t = 0.0;
  var weight = 1.0;
  // Your loop here.
  return weight;
}
`,
  signature:
    'fn nullScattering(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, nullProbability: f32, state: ptr<function, u32>) -> f32',
  hints: [
    'loop { t += -log(1.0 - rngNextFloat(state)) / sigmaMaj; if (t >= d) { break; } ... }',
    'At a tentative collision: with probability nullProbability it is a null vertex, otherwise the path ends with 0.',
    'A null vertex multiplies the weight by f/p of the vertex: σn/σ̄ for the path, divided by the probability P_n of having chosen it.',
    'Do not clamp σn = σ̄ − σt at 0: a negative factor is what keeps the estimate unbiased under a low majorant.',
  ],
  gradingNotes:
    'Public: n = 65536 calls on σ0 = 0.5, a = 0.6, d = 1.5, σ̄ = 1, P_n = 0.7 and on σ0 = 0.5, ' +
    'a = 0.8, d = 1.5, σ̄ = 0.6 (below σt), P_n = 0.8; a z-test of the mean against exp(−τ) with ' +
    'the estimator’s exact variance, and of the mean square against its exact E[X²], α = 1e-6 per ' +
    'check. Hidden checks run the same tests on other media and other P_n.',
  subject: {
    name: 'nullScattering',
    params: [
      { name: 'sigma0', type: 'f32' },
      { name: 'amplitude', type: 'f32' },
      { name: 'd', type: 'f32' },
      { name: 'sigmaMaj', type: 'f32' },
      { name: 'nullProbability', type: 'f32' },
      { name: 'state', type: 'ptr<function, u32>' },
    ],
    result: 'f32',
  },
  helpers: trackingHelpers(SINE_MEDIUM),
  reference: `import package::tracking::sampleFreeFlight;
fn nullScattering(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, nullProbability: f32, state: ptr<function, u32>) -> f32 {
  if (sigmaMaj <= 0.0) {
    return 1.0;
  }
  var t = 0.0;
  var weight = 1.0;
  // Breaks, then one return: naga (Firefox) rejects a function that ends in a loop.
  loop {
    t += sampleFreeFlight(sigmaMaj, rngNextFloat(state));
    if (t >= d) {
      break;
    }
    let sigmaN = sigmaMaj - extinction(sigma0, amplitude, t);
    // A real vertex (probability 1 − P_n) ends the shadow path: its contribution is 0.
    if (rngNextFloat(state) >= nullProbability) {
      weight = 0.0;
      break;
    }
    // A null vertex: f/p = σn / (σ̄ · P_n), negative where σt > σ̄.
    weight *= sigmaN / (sigmaMaj * nullProbability);
  }
  return weight;
}`,
  checks: [
    publicCheck(
      'Valid majorant, P_n = 0.7',
      PUBLIC_VALID,
      'Your estimator is not null-scattering tracking with this P_n. Check that a tentative ' +
        'collision is null with probability nullProbability, that a null vertex multiplies the ' +
        'weight by σn/(σ̄·P_n), and that a real vertex returns 0.',
    ),
    publicCheck(
      'Majorant below σt, P_n = 0.8',
      PUBLIC_LOW,
      'With σ̄ below σt on part of the ray, σn = σ̄ − σt is negative there; the factor ' +
        'σn/(σ̄·P_n) must be negative too (no clamp at 0), or the estimate is biased.',
    ),
  ],
};
