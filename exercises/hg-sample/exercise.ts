// Henyey–Greenstein sampling (chapter 3): the public part of the exercise. The
// sampler is graded by a chi-square test of its output against the analytic HG
// density of μ, so a sampler that returns the wrong distribution fails however
// consistent its own pdf is.
import type { ChiSquareCheck, ExerciseDefinition } from '../../src/grading/exercise.ts';

/** CDF of μ under HG, F(μ) = (1 − g²)/(2g)·[(1 + g² − 2gμ)^{−1/2} − 1/(1 + g)] (physics.md §2.4). */
export function hgCdf(g: number, mu: number): number {
  if (Math.abs(g) < 1e-6) return (1 + mu) / 2;
  const m = Math.min(1, Math.max(-1, mu));
  return ((1 - g * g) / (2 * g)) * (1 / Math.sqrt(1 + g * g - 2 * g * m) - 1 / (1 + g));
}

/** Its inverse, the float64 inverse-CDF sample (for the histogram's bin edges). */
export function hgInverseCdf(g: number, p: number): number {
  if (Math.abs(g) < 1e-6) return 2 * p - 1;
  const s = (1 - g * g) / (1 - g + 2 * g * p);
  return Math.min(1, Math.max(-1, (1 + g * g - s * s) / (2 * g)));
}

/**
 * χ² check of the sampled μ at asymmetry g. n = 20000 stratified uniforms, 20
 * equiprobable bins (1000 expected per bin), α = 1e-6. With stratified ξ a monotone
 * inverse-CDF sampler puts exactly n/bins samples in each bin (up to f32 rounding
 * at the edges), so the reference's statistic is ≈ 0 under every seed, far below the
 * critical value 63.7; the wrong samplers in wrong/ give statistics in the thousands.
 */
export function hgChiSquare(
  g: number,
  name: string,
  points: number,
  message: string,
): ChiSquareCheck {
  return {
    kind: 'chi-square',
    name,
    points,
    message,
    n: 20000,
    bins: 20,
    alpha: 1e-6,
    args: (xi) => [g, xi],
    cdf: (mu) => hgCdf(g, mu),
    inverseCdf: (p) => hgInverseCdf(g, p),
    xLabel: `μ = cos θ at g = ${g}`,
  };
}

export const EXERCISE: ExerciseDefinition = {
  id: 'hg-sample',
  chapter: '03-phase-functions-and-in-scattering',
  title: 'Sampling the Henyey–Greenstein phase function',
  starter: `// Importance sampling of Henyey–Greenstein: map a uniform ξ ∈ [0, 1) to a cosine μ
// distributed with the density 2π p_HG(μ; g) on [−1, 1], by inverting the CDF.
// μ must increase with ξ: ξ = 0 gives μ = −1 and ξ → 1 gives μ → 1.
fn sampleHgMu(g: f32, xi: f32) -> f32 {
  // Your code here.
  return 2.0 * xi - 1.0;
}
`,
  signature: 'fn sampleHgMu(g: f32, xi: f32) -> f32',
  hints: [
    'Integrate 2π p_HG(μ) from −1 to μ to get the CDF, set it equal to ξ and solve for μ.',
    'Let s = (1 − g²)/(1 − g + 2gξ); then μ = (1 + g² − s²)/(2g).',
    'For |g| < 1e-3 return 2ξ − 1: the formula divides two tiny numbers there. Clamp μ to [−1, 1].',
  ],
  gradingNotes:
    'Public: χ² of 20000 stratified samples in 20 equiprobable bins at α = 1e-6 (critical value ' +
    '63.7) for g = 0.7 and g = −0.5. Hidden checks draw g and ξ from the grading seed: the ' +
    'distribution with independent uniforms (χ² in other bins and Kolmogorov–Smirnov), end ' +
    'points, medians and single values, and nearly isotropic g.',
  subject: {
    name: 'sampleHgMu',
    params: [
      { name: 'g', type: 'f32' },
      { name: 'xi', type: 'f32' },
    ],
    result: 'f32',
  },
  reference: `import package::phase::hgSampleMu;
fn sampleHgMu(g: f32, xi: f32) -> f32 {
  return hgSampleMu(g, xi, 1.0 - xi).mu;
}`,
  checks: [
    hgChiSquare(
      0.7,
      'Distribution of μ for a forward lobe, g = 0.7',
      3,
      'Your samples are not distributed like Henyey–Greenstein at g = 0.7: too many or too few ' +
        'land in some bins (see the histogram). Uniform μ = 2ξ − 1 fails here; so does a sign error, ' +
        'which mirrors the lobe.',
    ),
    hgChiSquare(
      -0.5,
      'Distribution of μ for a backward lobe, g = −0.5',
      2,
      'Your samples are not distributed like Henyey–Greenstein at g = −0.5: a backward lobe ' +
        'should pile up near μ = −1.',
    ),
  ],
};
