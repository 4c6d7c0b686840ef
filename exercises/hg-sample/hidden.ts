// Henyey–Greenstein sampling: hidden tests. Nothing here is fixed except the end point
// ξ = 0: every g and ξ is drawn from the grading seed (src/grading/checks/generated.ts),
// so no table of inputs covers them. The distribution checks feed independent
// (unstratified) uniforms and test them in bins rotated by a seeded offset, plus the
// Kolmogorov–Smirnov test of the whole CDF (src/grading/checks/distribution.ts): a
// sampler exact only at the strata or bin edges of the public check fails them.
import type { CaseSpec, CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import type { DistributionCheck } from '../../src/grading/checks/distribution.ts';
import { hgCdf, hgInverseCdf } from './exercise.ts';

const POINT_TOLERANCE = { rtol: 1e-4, atol: 1e-5 } as const;

/**
 * Distribution checks: n = 2^17 independent uniforms, 128 rotated equiprobable bins,
 * α = 1e-6 split between χ² and KS. |g| is drawn in [0.5, 0.95], where the power
 * against the sampler that is exact at 21 quantiles and linear between them is ≥ 0.99
 * (tests/grading/power.test.ts computes it; README table).
 */
export const DISTRIBUTION_DESIGN = {
  n: 131072,
  bins: 128,
  alpha: 1e-6,
  gRange: [0.5, 0.95],
} as const;

function lobeCheck(sign: 1 | -1, name: string, points: number, message: string): DistributionCheck {
  const [lo, hi] = DISTRIBUTION_DESIGN.gRange;
  return {
    kind: 'distribution',
    name,
    points,
    message,
    n: DISTRIBUTION_DESIGN.n,
    bins: DISTRIBUTION_DESIGN.bins,
    alpha: DISTRIBUTION_DESIGN.alpha,
    draw: (seed) => {
      const g = sign * caseSampler(seed, `hg-sample ${name}`).uniform(lo, hi);
      return {
        label: sign > 0 ? 'a hidden forward lobe' : 'a hidden backward lobe',
        args: (xi) => [g, xi],
        cdf: (mu) => hgCdf(g, mu),
        inverseCdf: (p) => hgInverseCdf(g, p),
      };
    },
    xLabel: 'μ = cos θ',
  };
}

/**
 * |g| where the statement's formula (with its |g| < 1e-3 branch) is accurate to the
 * tolerance in f32: [0.05, 0.95]. Between 1e-6 and 0.05 both the f32 cancellation of
 * the formula and the 2ξ − 1 branch's O(g) error exceed 1e-5, so no case lies there.
 */
function ordinaryG(r: CaseSampler): number {
  return r.sign() * r.uniform(0.05, 0.95);
}

function ordinaryCases(r: CaseSampler, count: number): CaseSpec[] {
  return Array.from({ length: count }, (_, k) => ({
    label: `ordinary case ${k + 1}`,
    args: [ordinaryG(r), r.uniform(0, 1)],
  }));
}

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  lobeCheck(
    1,
    'Distribution of μ for a hidden forward lobe',
    2,
    'Your samples are not distributed like Henyey–Greenstein for a forward lobe, tested with ' +
      'independent uniforms in bins other than the public ones and over the whole CDF: check the ' +
      'inverse CDF between the points the public check tests, not only at them.',
  ),
  lobeCheck(
    -1,
    'Distribution of μ for a hidden backward lobe',
    1,
    'Your samples are not distributed like Henyey–Greenstein for a backward lobe (g < 0).',
  ),
  {
    kind: 'generated-cases',
    name: 'End points, medians and single values',
    points: 1,
    message:
      'Your sampler does not map ξ = 0 to μ = −1, ξ = ½ to the median g(3 − g²)/2, or some ξ to ' +
      'the inverse CDF: keep μ increasing with ξ as the statement says.',
    ...POINT_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hg-sample end points');
      return [
        { label: 'ξ = 0', args: [ordinaryG(r), 0] },
        { label: 'median', args: [ordinaryG(r), 0.5] },
        { label: 'median', args: [ordinaryG(r), 0.5] },
        // Single values over the whole range of g and ξ: a sampler exact only where the
        // distribution checks look (|g| ≥ 0.5) and wrong for smaller |g| scored 8/10 with
        // 4 of them; 24 hit a wrong region of g-measure 10 % with probability
        // 1 − 0.9^24 = 0.92, one of 20 % with 0.995 (deterministic cases cost nothing).
        ...ordinaryCases(r, 24),
      ];
    },
  },
  {
    kind: 'generated-cases',
    name: 'Nearly isotropic g',
    points: 1,
    message:
      'For |g| ≤ 1e-6 the inverse CDF divides two tiny numbers and leaves [−1, 1] in f32: use ' +
      'μ = 2ξ − 1 for very small |g| (where the formula loses every digit in f32), and the formula elsewhere.',
    ...POINT_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hg-sample nearly isotropic');
      const tiny = Array.from({ length: 3 }, () => ({
        label: 'tiny |g|',
        args: [r.sign() * r.logUniform(1e-9, 1e-6), r.uniform(0, 1)],
      }));
      return [...tiny, ...ordinaryCases(r, 16)];
    },
  },
];
