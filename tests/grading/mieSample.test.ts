// The mie-sample exercise (chapter 3): its tables are the library's, in the library's
// layout, and the WGSL the student reads holds them exactly; the CPU distribution the
// checks test against is the table's own (its derivative is the table's density); the
// reference transcription agrees with the library's phaseTabulatedSampleMu on the GPU;
// the check sizes give the verdicts on the wrong samplers that expected.json states with
// certainty (power from their exact distributions); and each wrong submission fails
// exactly the checks it should. The self-test (selfTest.test.ts) repeats the scores under
// three seeds.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { EXERCISE, XI_BELOW_ONE, nodeCdf } from '../../exercises/mie-sample/exercise.ts';
import { DISTRIBUTION_ALPHA, DISTRIBUTION_DESIGN } from '../../exercises/mie-sample/hidden.ts';
import {
  EXERCISE_TABLES,
  FLAT_INTERVAL,
  MIE_EXERCISE_INTERVALS,
  MIE_EXERCISE_NODES,
  SMALL_PARTICLE,
  TABLES,
  TABLE_WGSL,
  sizeParameter,
  tableMeanCosine,
  tableMuCdf,
  tableMuInverseCdf,
} from '../../exercises/mie-sample/tables.ts';
import { hgCdf } from '../../exercises/hg-sample/exercise.ts';
import { distributionPower } from '../../src/grading/checks/distribution.ts';
import type { CasesCheck, ChiSquareCheck, ExerciseDefinition } from '../../src/grading/exercise.ts';
import { gradeSubmission } from '../../src/grading/grade.ts';
import { EXERCISES_DIR, loadFullExercise, wrongSubmissions } from '../../src/grading/node.ts';
import { chiSquareCritical } from '../../src/statistics/distributions.ts';
import { phaseTabulatedEval, type PhaseTable } from '../../src/reference/mie.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const K = MIE_EXERCISE_INTERVALS;

function table(index: number): PhaseTable {
  const t = TABLES[index];
  if (!t) throw new Error(`no table ${index}`);
  return t;
}

/** CDF of μ under the wrong sampler s = r (linear in ξ inside each interval). */
function linearInCdfMuCdf(index: number, mu: number): number {
  const t = table(index);
  const x = Math.min(2, Math.max(0, 1 - mu));
  let k = 0;
  while (k < K - 1 && (t.oneMinusMu[k + 1] ?? 2) <= x) k++;
  const lower = t.oneMinusMu[k] ?? 0;
  const width = (t.oneMinusMu[k + 1] ?? 2) - lower;
  const s = width > 0 ? Math.min(1, Math.max(0, (x - lower) / width)) : 0;
  const ck = t.cdf[k] ?? 0;
  return 1 - (ck + ((t.cdf[k + 1] ?? 1) - ck) * s);
}

/** The wrong samplers with a closed-form distribution: P(F(X) ≤ p) for table `index`. */
const ALTERNATIVES: Record<string, (index: number) => (p: number) => number> = {
  'linear-in-cdf': (i) => (p) => linearInCdfMuCdf(i, tableMuInverseCdf(i, p)),
  'hg-same-g': (i) => (p) => hgCdf(tableMeanCosine(i), tableMuInverseCdf(i, p)),
  mirrored: (i) => (p) => 1 - tableMuCdf(i, -tableMuInverseCdf(i, p)),
};

/** The deterministic statistic of the public χ² (stratified ξ): n·B·Σ(q_j − 1/B)². */
function stratifiedStatistic(check: ChiSquareCheck, alternative: (p: number) => number): number {
  let sum = 0;
  for (let j = 0; j < check.bins; j++) {
    const q = alternative((j + 1) / check.bins) - alternative(j / check.bins);
    sum += (q - 1 / check.bins) ** 2;
  }
  return check.n * check.bins * sum;
}

describe('mie-sample tables', () => {
  it('are the library tables of the stated particles, in its layout', () => {
    expect(TABLES).toHaveLength(EXERCISE_TABLES.length);
    expect(sizeParameter(EXERCISE_TABLES[0]!)).toBeCloseTo(17.14, 2);
    expect(sizeParameter(EXERCISE_TABLES[3]!)).toBeCloseTo(99.96, 2);
    for (const t of TABLES) {
      expect(t.cdf).toHaveLength(MIE_EXERCISE_NODES);
      expect(t.cdf[0]).toBe(0);
      expect(t.cdf[K]).toBe(1);
      expect(t.oneMinusMu[0]).toBe(0);
      expect(t.oneMinusMu[K]).toBe(2);
      expect(t.onePlusMu[K]).toBe(0);
      for (let k = 0; k < K; k++) {
        expect(t.cdf[k + 1]!).toBeGreaterThan(t.cdf[k]!);
        expect(t.oneMinusMu[k + 1]!).toBeGreaterThan(t.oneMinusMu[k]!);
        expect(t.pdf[k]!).toBeGreaterThan(0);
        expect(Math.abs(t.oneMinusMu[k]! + t.onePlusMu[k]! - 2)).toBeLessThan(3e-7);
      }
    }
    // The mean cosines the statement's particles should have: strongly forward droplets,
    // soot in between, Rayleigh symmetric.
    expect(tableMeanCosine(0)).toBeGreaterThan(0.75);
    expect(Math.abs(tableMeanCosine(SMALL_PARTICLE))).toBeLessThan(1e-3);
    expect(tableMeanCosine(2)).toBeGreaterThan(0.15);
    expect(tableMeanCosine(2)).toBeLessThan(0.35);
    expect(tableMeanCosine(3)).toBeGreaterThan(tableMeanCosine(0));
  });

  it('has the nearly flat interval the hidden check needs', () => {
    const t = table(SMALL_PARTICLE);
    const a = t.pdf[FLAT_INTERVAL]!;
    const b = t.pdf[FLAT_INTERVAL + 1]!;
    const relative = Math.abs(b - a) / a;
    // Not exactly flat (then b − a = 0 would be guarded by a == b), but flat enough that
    // the textbook root's rounding error, ≈ 6e-8/relative in s, times the interval's width
    // in μ (≈ 0.05) exceeds the 1e-5 tolerance many times over.
    expect(relative).toBeGreaterThan(0);
    expect(relative).toBeLessThan(1e-5);
    expect(1 - t.oneMinusMu[FLAT_INTERVAL]!).toBeGreaterThan(0);
    expect(1 - t.oneMinusMu[FLAT_INTERVAL + 1]!).toBeLessThan(0);
  });

  it('are in the WGSL exactly as the GPU should read them', () => {
    const read = (name: string): number[] => {
      const match = new RegExp(`const ${name} = array<f32, \\d+>\\(([^;]*)\\);`).exec(TABLE_WGSL);
      if (!match) throw new Error(`no ${name} in the helpers`);
      return (match[1] ?? '')
        .split('\n')
        .filter((line) => !line.trim().startsWith('//'))
        .join('')
        .split(',')
        .map((s) => s.trim())
        .filter((s) => s.length > 0)
        .map(Number);
    };
    const columns: [string, keyof PhaseTable][] = [
      ['MIE_TABLE_ONE_MINUS_MU', 'oneMinusMu'],
      ['MIE_TABLE_ONE_PLUS_MU', 'onePlusMu'],
      ['MIE_TABLE_PDF', 'pdf'],
      ['MIE_TABLE_CDF', 'cdf'],
    ];
    for (const [name, column] of columns) {
      const values = read(name).map(Math.fround);
      const expected = TABLES.flatMap((t) => Array.from(t[column]));
      expect(values, name).toEqual(expected);
    }
  });

  it('give a CPU distribution whose density is the table and whose inverse is the sampler', () => {
    for (let i = 0; i < TABLES.length; i++) {
      const t = table(i);
      for (let k = 0; k <= K; k++) {
        expect(tableMuCdf(i, 1 - t.oneMinusMu[k]!)).toBeCloseTo(1 - t.cdf[k]!, 6);
      }
      for (let j = 1; j < 200; j++) {
        const mu = -1 + (2 * j) / 200;
        // dF/dμ = 2π p(μ): the CDF integrates the table's own linear density.
        const h = 1e-6;
        const slope = (tableMuCdf(i, mu + h) - tableMuCdf(i, mu - h)) / (2 * h);
        expect(slope / (2 * Math.PI * phaseTabulatedEval(t, mu))).toBeCloseTo(1, 3);
        const p = j / 200;
        expect(tableMuCdf(i, tableMuInverseCdf(i, p))).toBeCloseTo(p, 7);
      }
    }
  });
});

describe('mie-sample check design', () => {
  const publicChi = EXERCISE.checks.filter((c): c is ChiSquareCheck => c.kind === 'chi-square');
  const statisticFor = (name: string, alternative: string): number => {
    const check = publicChi.find((c) => c.name.includes(name));
    if (!check) throw new Error(name);
    const index = check.args(0.5)[0] ?? 0;
    return stratifiedStatistic(check, ALTERNATIVES[alternative]!(index));
  };

  it('rejects linear interpolation in ξ publicly only for the cloud droplet', () => {
    const critical20 = chiSquareCritical(1e-6, 19);
    const critical40 = chiSquareCritical(1e-6, 39);
    expect(critical20).toBeCloseTo(63.68, 2);
    expect(critical40).toBeCloseTo(96.13, 2);
    expect(statisticFor('cloud', 'linear-in-cdf')).toBeGreaterThan(1.5 * critical40);
    expect(statisticFor('water', 'linear-in-cdf')).toBeLessThan(critical20 / 5);
    for (const wrong of ['hg-same-g', 'mirrored']) {
      expect(statisticFor('water', wrong)).toBeGreaterThan(50 * critical20);
      expect(statisticFor('cloud', wrong)).toBeGreaterThan(50 * critical40);
    }
  });

  it('sizes the hidden distributions so that every verdict on the wrong samplers is certain', () => {
    // [wrong sampler][table]: true = rejected with power ≥ 0.9999, false = power ≤ 1e-4.
    const verdicts: Record<string, boolean[]> = {
      'linear-in-cdf': [false, false, false, true],
      'hg-same-g': [true, true, true, true],
      mirrored: [true, false, true, true],
    };
    for (const [wrong, expected] of Object.entries(verdicts)) {
      expected.forEach((rejected, index) => {
        const { n, bins } = DISTRIBUTION_DESIGN[index]!;
        const { power } = distributionPower(
          n,
          bins,
          DISTRIBUTION_ALPHA,
          ALTERNATIVES[wrong]!(index),
        );
        if (rejected) expect(power, `${wrong}, table ${index}`).toBeGreaterThan(0.9999);
        else expect(power, `${wrong}, table ${index}`).toBeLessThan(1e-4);
      });
    }
  });

  it('gives hg-same-g the tables’ exact mean cosines', () => {
    const source = readFileSync(
      join(EXERCISES_DIR, 'mie-sample', 'wrong', 'hg-same-g.wgsl'),
      'utf8',
    );
    const gs = [...source.matchAll(/g = (0\.\d{5,});/g)].map((m) => Number(m[1]));
    expect(gs).toHaveLength(TABLES.length);
    gs.forEach((g, i) => expect(Math.fround(g)).toBe(Math.fround(tableMeanCosine(i))));
  });
});

describe('mie-sample on the GPU', () => {
  it('has a reference that agrees with the library’s phaseTabulatedSampleMu', async () => {
    // The library function on the table padded to its 513 nodes: the padding's CDF is 2,
    // above every ξ, so the bisection stays among the exercise's nodes (at ξ = 1 it enters
    // interval K, of mass 1, at r = 0, which gives node K: μ = −1).
    const library = `import package::mie::PhaseTable;
import package::mie::phaseTabulatedSampleMu;
// The library's table functions take a pointer to a private table (shaders/mie.wesl).
var<private> full: PhaseTable;
fn sampleMieMu(table: u32, xi: f32) -> f32 {
  for (var k = 0u; k < MIE_TABLE_NODES; k++) {
    full.oneMinusMu[k] = tableOneMinusMu(table, k);
    full.onePlusMu[k] = tableOnePlusMu(table, k);
    full.pdf[k] = tablePdf(table, k);
    full.cdf[k] = tableCdf(table, k);
  }
  for (var k = MIE_TABLE_NODES; k < 513u; k++) {
    full.cdf[k] = 2.0;
  }
  return phaseTabulatedSampleMu(&full, xi).mu;
}`;
    const cases = EXERCISE_TABLES.flatMap((t) => [
      ...Array.from({ length: 257 }, (_, j) => ({
        label: `table ${t.index}, ξ = ${j}/256`,
        args: [t.index, Math.min(1, j / 256)],
      })),
      ...Array.from({ length: MIE_EXERCISE_NODES }, (_, k) => ({
        label: `table ${t.index}, ξ = C_${k}`,
        args: [t.index, nodeCdf(t.index, k)],
      })),
      { label: `table ${t.index}, ξ = 1 − 2⁻²⁴`, args: [t.index, XI_BELOW_ONE] },
    ]);
    const agreement: CasesCheck = {
      kind: 'cases',
      name: 'reference = library',
      points: 1,
      message: 'the transcription differs from the library',
      rtol: 0,
      atol: 1e-7,
      cases,
    };
    const exercise: ExerciseDefinition = { ...EXERCISE, reference: library, checks: [agreement] };
    const device = await nodeDevice();
    const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, EXERCISE.reference, {
      which: 'public',
      seed: 1,
    });
    expect(outcome.status).toBe('graded');
    if (outcome.status !== 'graded') return;
    expect(outcome.score, outcome.checks[0]?.message).toBe(1);
  }, 120_000);

  it('fails each wrong submission on exactly the checks its reason names', async () => {
    const failing: Record<string, string[]> = {
      'linear-in-cdf.wgsl': [
        'Water droplet: nodes and midpoints',
        'Near-Rayleigh particle: single values',
        'Distribution of μ for the cloud droplet',
        'Distribution of μ for table 3',
        'A nearly flat interval',
        'ξ next to 0 and 1',
        'Single values',
      ],
      'textbook-quadratic.wgsl': ['A nearly flat interval'],
      'search-misses-last.wgsl': [
        'End points of every table',
        'Water droplet: nodes and midpoints',
        'ξ next to 0 and 1',
      ],
      'nodes-not-intervals.wgsl': ['End points of every table', 'ξ next to 0 and 1'],
      'mirrored.wgsl': [
        ...EXERCISE.checks.map((c) => c.name),
        'Distribution of μ for table 0',
        'Distribution of μ for table 2',
        'Distribution of μ for table 3',
        'On and next to the node CDFs',
        'A nearly flat interval',
        'ξ next to 0 and 1',
        'Single values',
      ],
      'hg-same-g.wgsl': [
        ...EXERCISE.checks.map((c) => c.name).filter((n) => n !== 'End points of every table'),
        'Distribution of μ for table 0',
        'Distribution of μ for table 1',
        'Distribution of μ for table 2',
        'Distribution of μ for table 3',
        'On and next to the node CDFs',
        'A nearly flat interval',
        'ξ next to 0 and 1',
        'Single values',
      ],
    };
    const device = await nodeDevice();
    const exercise = await loadFullExercise('mie-sample');
    const wrong = wrongSubmissions('mie-sample');
    expect(wrong.map((w) => w.file).sort()).toEqual(Object.keys(failing).sort());
    for (const submission of wrong) {
      const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, submission.source, {
        which: 'all',
        seed: 7,
      });
      expect(outcome.status, submission.file).toBe('graded');
      if (outcome.status !== 'graded') continue;
      const failed = outcome.checks.filter((c) => c.verdict === 'fail').map((c) => c.name);
      expect(failed.sort(), submission.file).toEqual([...(failing[submission.file] ?? [])].sort());
      const range = submission.score === 'full' ? [outcome.maxScore] : (submission.score ?? []);
      expect(range, submission.file).toContain(outcome.score);
    }
  }, 300_000);
});
