// Sampling a tabulated Mie phase function (chapter 3): the public part of the exercise.
// The student inverts the CDF of a table in the library's layout (shaders/mie.wesl,
// PhaseTable): find the interval by bisection over the node CDFs, then invert the
// quadratic CDF of the linear density inside it in a form that never cancels. The
// reference is the library's phaseTabulatedSampleMu transcribed onto the 64-node tables
// (tests/grading/mieSample.test.ts checks it against the library function on the GPU).
// Point checks compare μ with it; the χ² checks compare the histogram with the exact
// distribution of the table (tables.ts), so a sampler that is only self-consistent fails.
import type { CaseSpec, ChiSquareCheck, ExerciseDefinition } from '../../src/grading/exercise.ts';
import {
  EXERCISE_TABLES,
  MIE_EXERCISE_INTERVALS,
  TABLES,
  TABLE_WGSL,
  tableMuCdf,
  tableMuInverseCdf,
} from './tables.ts';

/** Tolerance of every point case, as the statement states it (μ is dimensionless). */
export const TOLERANCE = { rtol: 1e-4, atol: 1e-5 } as const;

/** The largest f32 below 1, the largest ξ the χ² checks feed. */
export const XI_BELOW_ONE = 1 - 2 ** -24;

/** The f32 CDF value C_k of a table's node k (a ξ that lands exactly on a node). */
export function nodeCdf(table: number, k: number): number {
  return TABLES[table]?.cdf[k] ?? 0;
}

/**
 * χ² check of the sampled μ for one table: n = 8000 stratified uniforms in `bins` bins
 * that are equiprobable under the table's exact distribution, α = 1e-6. A correct
 * inverse-CDF sampler gives a statistic ≈ 0 (stratified ξ fill each bin exactly, up to
 * f32 rounding at the edges). The statistic is deterministic for a monotone sampler, so a
 * wrong one either always fails or always passes: interpolating linearly in ξ (s = r)
 * gives 156 in 40 bins for the cloud droplet (critical value 96.1) but only 6 in 20 bins
 * for the water droplet (tests/grading/mieSample.test.ts computes both).
 */
export function tableChiSquare(
  table: number,
  bins: number,
  name: string,
  points: number,
  message: string,
): ChiSquareCheck {
  return {
    kind: 'chi-square',
    name,
    points,
    message,
    n: 8000,
    bins,
    alpha: 1e-6,
    args: (xi) => [table, xi],
    cdf: (mu) => tableMuCdf(table, mu),
    inverseCdf: (p) => tableMuInverseCdf(table, p),
    xLabel: `μ = cos θ, table ${table}`,
  };
}

/** Public node and midpoint cases of the water droplet (table 0). */
function waterCases(): CaseSpec[] {
  const cases: CaseSpec[] = [];
  for (const k of [1, 3, 6, 10, 20, 40, 62]) {
    cases.push({ label: `ξ = C_${k} (a node)`, args: [0, nodeCdf(0, k)] });
    const mid = Math.fround((nodeCdf(0, k) + nodeCdf(0, k + 1)) / 2);
    cases.push({ label: `ξ midway through interval ${k}`, args: [0, mid] });
  }
  return cases.sort((a, b) => (a.args[1] ?? 0) - (b.args[1] ?? 0));
}

export const EXERCISE: ExerciseDefinition = {
  id: 'mie-sample',
  chapter: '03-phase-functions-and-in-scattering',
  title: 'Sampling a tabulated Mie phase function',
  starter: `// Importance sampling of a tabulated phase function: map a uniform ξ ∈ [0, 1] to a
// cosine μ distributed as table \`table\` (0 … 3), by inverting the table's CDF. The
// tables come from the book's Mie solver; read them with tableOneMinusMu(table, k),
// tableOnePlusMu(table, k), tablePdf(table, k) and tableCdf(table, k), k = 0 …
// MIE_TABLE_INTERVALS. The density is linear in μ between nodes, and the CDF runs
// from the forward direction: ξ = 0 gives μ = 1 and ξ = 1 gives μ = −1.
fn sampleMieMu(table: u32, xi: f32) -> f32 {
  // Your code here.
  return 1.0 - 2.0 * xi;
}
`,
  signature: 'fn sampleMieMu(table: u32, xi: f32) -> f32',
  hints: [
    `Bisection: keep lo = 0 and hi = MIE_TABLE_INTERVALS (= ${MIE_EXERCISE_INTERVALS}) with tableCdf(lo) ≤ ξ, and halve until hi − lo = 1; lo is the interval. Six steps suffice.`,
    'Inside interval k, with r = (ξ − C_k)/(C_{k+1} − C_k), a = p_k and b = p_{k+1}, the fraction s of the interval solves a·s + (b − a)·s²/2 = r·(a + b)/2.',
    'Solve it as s = r(a + b) / (a + sqrt(a² + (b − a)(a + b) r)): no subtraction, no division by b − a, and s = r when a = b. Guard an interval with no mass (r = 0) and clamp r and s to [0, 1].',
  ],
  gradingNotes:
    'Point cases pass when |μ − μ_ref| ≤ 1e-5 + 1e-4·|μ_ref| against the library sampler on the ' +
    'same table. Public: the end points of every table, nodes and midpoints of the water ' +
    'droplet, single values of the near-Rayleigh particle, and χ² of 8000 stratified samples ' +
    '(α = 1e-6) for the water droplet (20 equiprobable bins, critical value 63.7) and the cloud ' +
    'droplet (40 bins, 96.1). Hidden checks draw ξ from the grading seed: the distribution of ' +
    'every table with independent uniforms (χ² in rotated bins and Kolmogorov–Smirnov), ξ on ' +
    'and next to node CDFs, the nearly flat interval, ξ next to 0 and 1, and single values.',
  subject: {
    name: 'sampleMieMu',
    params: [
      { name: 'table', type: 'u32' },
      { name: 'xi', type: 'f32' },
    ],
    result: 'f32',
  },
  helpers: { imports: [], wgsl: TABLE_WGSL },
  // The library's phaseTabulatedSampleMu (shaders/mie.wesl) line by line on the exercise's
  // 64-node tables: the library function itself reads a 513-node PhaseTable through a
  // pointer, and copying a padded table per call made the reference's grading about three times
  // slower on SwiftShader. tests/grading/mieSample.test.ts grades this transcription
  // against the library function on the padded table (agreement to 1e-7).
  reference: `fn sampleMieMu(table: u32, xi: f32) -> f32 {
  let u = clamp(xi, 0.0, 1.0);
  var lo = 0u;
  var hi = MIE_TABLE_INTERVALS;
  for (var step = 0u; step < 6u; step++) {
    if (hi - lo <= 1u) {
      break;
    }
    let mid = (lo + hi) / 2u;
    if (tableCdf(table, mid) <= u) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  let lowerCdf = tableCdf(table, lo);
  let mass = tableCdf(table, lo + 1u) - lowerCdf;
  var r = 0.0;
  if (mass > 0.0) {
    r = clamp((u - lowerCdf) / mass, 0.0, 1.0);
  }
  let a = tablePdf(table, lo);
  let b = tablePdf(table, lo + 1u);
  let denominator = a + sqrt(max(0.0, a * a + (b - a) * (a + b) * r));
  var s = r;
  if (denominator > 0.0) {
    s = clamp(r * (a + b) / denominator, 0.0, 1.0);
  }
  let lowerT = tableOneMinusMu(table, lo);
  let lowerC = tableOnePlusMu(table, lo);
  let oneMinusMu = lowerT + s * (tableOneMinusMu(table, lo + 1u) - lowerT);
  let onePlusMu = lowerC - s * (lowerC - tableOnePlusMu(table, lo + 1u));
  if (oneMinusMu < onePlusMu) {
    return 1.0 - oneMinusMu;
  }
  return onePlusMu - 1.0;
}`,
  checks: [
    {
      kind: 'cases',
      name: 'End points of every table',
      points: 1,
      message:
        'ξ = 0 must give μ = 1 (the forward direction, where the CDF starts) and ξ = 1 must give ' +
        'μ = −1 for every table, with a finite μ: at ξ = 1 the bisection must stop at the last ' +
        'interval, not at the last node, whose interval has no mass.',
      ...TOLERANCE,
      cases: EXERCISE_TABLES.flatMap((t) => [
        { label: `table ${t.index}, ξ = 0`, args: [t.index, 0] },
        { label: `table ${t.index}, ξ = 1 − 2⁻²⁴`, args: [t.index, XI_BELOW_ONE] },
        { label: `table ${t.index}, ξ = 1`, args: [t.index, 1] },
      ]),
    },
    {
      kind: 'cases',
      name: 'Water droplet: nodes and midpoints',
      points: 2,
      message:
        'For the water droplet (table 0) your μ is off at a node CDF or inside an interval: at ' +
        'ξ = C_k you must return μ_k exactly (up to rounding), and inside the interval the root ' +
        'of the quadratic, not the linear interpolation of μ in ξ.',
      ...TOLERANCE,
      cases: waterCases(),
      figure: { argIndex: 1, xLabel: 'ξ, water droplet (table 0)' },
    },
    {
      kind: 'cases',
      name: 'Near-Rayleigh particle: single values',
      points: 1,
      message:
        'For the near-Rayleigh particle (table 1) your μ is off: its lobe ∝ 1 + μ² is nearly ' +
        'symmetric, and μ must still fall from 1 at ξ = 0 to −1 at ξ = 1.',
      ...TOLERANCE,
      cases: [0.05, 0.2, 0.35, 0.65, 0.8, 0.95].map((xi) => ({
        label: `table 1, ξ = ${xi}`,
        args: [1, xi],
      })),
      figure: { argIndex: 1, xLabel: 'ξ, near-Rayleigh particle (table 1)' },
    },
    tableChiSquare(
      0,
      20,
      'Distribution of μ for the water droplet',
      2,
      'Your samples are not distributed as the water droplet’s table (table 0): too many or too ' +
        'few land in some bins (see the histogram). Sampling Henyey–Greenstein with the same g, ' +
        'or a mirrored μ, fail here.',
    ),
    tableChiSquare(
      3,
      40,
      'Distribution of μ for the cloud droplet',
      2,
      'Your samples are not distributed as the cloud droplet’s table (table 3), whose forward ' +
        'intervals are steep: interpolating linearly in ξ inside an interval (s = r) puts too ' +
        'many samples at the steep end of each of them.',
    ),
  ],
};
