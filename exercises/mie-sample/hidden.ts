// Sampling a tabulated Mie phase function: hidden tests. Every ξ is drawn from the
// grading seed (src/grading/checks/generated.ts) except the fixed ends ξ = 0 and ξ = 1,
// so no table of inputs answers them. The distribution checks feed independent uniforms
// and test them in bins rotated by a seeded offset and by Kolmogorov–Smirnov
// (src/grading/checks/distribution.ts), for every table.
import type { CaseSpec, CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import type { DistributionCheck } from '../../src/grading/checks/distribution.ts';
import { TOLERANCE, nodeCdf } from './exercise.ts';
import {
  EXERCISE_TABLES,
  FLAT_INTERVAL,
  MIE_EXERCISE_INTERVALS,
  SMALL_PARTICLE,
  tableMuCdf,
  tableMuInverseCdf,
} from './tables.ts';

/**
 * Distribution checks: independent uniforms, rotated equiprobable bins, α = 1e-6 split
 * between χ² and KS. The sizes are the smallest that keep every verdict on the wrong
 * samplers of wrong/ certain under any seed (tests/grading/mieSample.test.ts computes the
 * power from their exact distributions, the minimum over the bins' rotation):
 * interpolating linearly in ξ inside an interval (s = r) has noncentrality λ ≥ 178 for the
 * cloud droplet at 8192 samples in 64 bins (power 0.99999), and is invisible elsewhere
 * (λ ≤ 4, power ≤ 1e-5: the water droplet would need n = 32768 in 128 bins to see it, the
 * near-Rayleigh and soot lobes are smooth at the scale of an interval); Henyey–Greenstein
 * with the table's g needs 16384 samples for soot (λ ≥ 289), 4096 suffice elsewhere.
 */
export const DISTRIBUTION_DESIGN: readonly { n: number; bins: number }[] = [
  { n: 4096, bins: 32 },
  { n: 4096, bins: 32 },
  { n: 16384, bins: 64 },
  { n: 8192, bins: 64 },
];

/** Significance of every distribution check. */
export const DISTRIBUTION_ALPHA = 1e-6;

function tableDistribution(table: number, points: number): DistributionCheck {
  const label = EXERCISE_TABLES[table]?.label ?? `table ${table}`;
  const design = DISTRIBUTION_DESIGN[table] ?? { n: 16384, bins: 64 };
  return {
    kind: 'distribution',
    name: `Distribution of μ for table ${table}`,
    points,
    message:
      `Your samples are not distributed as table ${table} (${label}), tested with ` +
      'independent uniforms in bins other than the public ones and over the whole CDF.',
    n: design.n,
    bins: design.bins,
    alpha: DISTRIBUTION_ALPHA,
    draw: () => ({
      label: `table ${table}`,
      args: (xi) => [table, xi],
      cdf: (mu) => tableMuCdf(table, mu),
      inverseCdf: (p) => tableMuInverseCdf(table, p),
    }),
    xLabel: `μ = cos θ, table ${table}`,
  };
}

const bits = new Uint32Array(1);
const float = new Float32Array(bits.buffer);

/** The f32 next to a positive f32 value, up (+1) or down (−1). */
function f32Neighbour(value: number, direction: 1 | -1): number {
  float[0] = value;
  bits[0] = (bits[0] ?? 0) + direction;
  return float[0] ?? value;
}

/** Tables whose single values and node neighbours the general checks draw. */
const GENERAL_TABLES = EXERCISE_TABLES.map((t) => t.index).filter((i) => i !== SMALL_PARTICLE);

function ordinary(r: CaseSampler, tables: readonly number[], label: string): CaseSpec {
  const table = tables[r.integer(0, tables.length - 1)] ?? 0;
  return { label: `table ${table}, ${label}`, args: [table, r.uniform(0, 1)] };
}

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  tableDistribution(0, 1),
  tableDistribution(1, 1),
  tableDistribution(2, 1),
  tableDistribution(3, 2),
  {
    kind: 'generated-cases',
    name: 'On and next to the node CDFs',
    points: 1,
    message:
      'At ξ = C_k, or one f32 step above or below it, your μ jumps: the interval search must ' +
      'find the largest k with C_k ≤ ξ (not k ± 1), and μ must be continuous across nodes.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'mie-sample nodes');
      const cases: CaseSpec[] = [];
      for (let j = 0; j < 8; j++) {
        const table = GENERAL_TABLES[r.integer(0, GENERAL_TABLES.length - 1)] ?? 0;
        const k = r.integer(1, MIE_EXERCISE_INTERVALS - 1);
        const c = nodeCdf(table, k);
        cases.push(
          { label: `table ${table}, ξ = C_k`, args: [table, c] },
          { label: `table ${table}, ξ just below C_k`, args: [table, f32Neighbour(c, -1)] },
          { label: `table ${table}, ξ just above C_k`, args: [table, f32Neighbour(c, 1)] },
        );
      }
      return cases;
    },
  },
  {
    kind: 'generated-cases',
    name: 'A nearly flat interval',
    points: 1,
    message:
      'Where the density is nearly constant across an interval (the middle of the ' +
      'near-Rayleigh table, where p_k and p_{k+1} agree to 4e-6), your root is wrong or ' +
      'NaN: the textbook formula (−a + √(a² + …))/(b − a) divides a rounding error by b − a ≈ 0. ' +
      'Use s = r(a + b)/(a + √(a² + (b − a)(a + b) r)).',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'mie-sample flat interval');
      const lower = nodeCdf(SMALL_PARTICLE, FLAT_INTERVAL);
      const mass = nodeCdf(SMALL_PARTICLE, FLAT_INTERVAL + 1) - lower;
      const flat = Array.from({ length: 6 }, () => ({
        label: 'table 1, ξ in the flat interval',
        args: [SMALL_PARTICLE, Math.fround(lower + mass * r.uniform(0.02, 0.98))],
      }));
      const others = Array.from({ length: 6 }, () => ordinary(r, [SMALL_PARTICLE], 'single ξ'));
      return [...flat, ...others];
    },
  },
  {
    kind: 'generated-cases',
    name: 'ξ next to 0 and 1',
    points: 1,
    message:
      'At ξ = 1, or within a few f32 steps of 0 or 1, your μ is wrong or not finite: the last ' +
      'interval must stay reachable (ξ ≥ C_{K−1}), and ξ = 1 must give μ = −1.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'mie-sample ends');
      // One ξ = 1 (a seeded table's), then per table: up to 4096 f32 steps (2.4e-4) below 1,
      // inside the last interval (mass ≥ 7e-4), anywhere in the last interval, up to 4096
      // steps above 0, and a tiny ξ.
      const one = r.integer(0, EXERCISE_TABLES.length - 1);
      return [
        { label: `table ${one}, ξ = 1`, args: [one, 1] },
        ...EXERCISE_TABLES.flatMap((t) => [
          {
            label: `table ${t.index}, ξ a few steps below 1`,
            args: [t.index, 1 - r.integer(1, 4096) * 2 ** -24],
          },
          {
            label: `table ${t.index}, ξ in the last interval`,
            args: [t.index, r.uniform(nodeCdf(t.index, MIE_EXERCISE_INTERVALS - 1), 1)],
          },
          {
            label: `table ${t.index}, ξ a few steps above 0`,
            args: [t.index, r.integer(1, 4096) * 2 ** -24],
          },
          { label: `table ${t.index}, tiny ξ`, args: [t.index, r.logUniform(1e-30, 1e-8)] },
        ]),
      ];
    },
  },
  {
    kind: 'generated-cases',
    name: 'Single values',
    points: 1,
    message:
      'For some ξ your μ differs from the inverse of the table’s CDF: check the quadratic ' +
      'inside the interval and which complement of μ you interpolate.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'mie-sample single values');
      // 24 draws: a sampler wrong on part of [0, 1) of measure q passes them all with
      // probability (1 − q)^24, 0.08 for q = 10 % (as hg-sample's single values).
      return Array.from({ length: 24 }, (_, k) => ordinary(r, GENERAL_TABLES, `ξ ${k + 1}`));
    },
  },
];
