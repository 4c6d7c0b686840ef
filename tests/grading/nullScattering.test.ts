// The null-scattering exercise (chapter 12): the exact moments the checks use agree with the
// library's twin (a Monte Carlo of transmittanceNullScattering's estimator family) and with
// the closed forms of delta and ratio tracking; the public and hidden designs keep the
// fourth moment moderate; the reference solution scores full marks on the GPU; and each
// wrong submission fails exactly the checks its reason names (expected.json gives the
// scores, which the self-test repeats under three seeds).
import { describe, expect, it } from 'vitest';
import {
  PUBLIC_LOW,
  PUBLIC_VALID,
  nullScatteringMoment,
} from '../../exercises/null-scattering/exercise.ts';
import { HIDDEN_CASES, HIDDEN_DESIGN } from '../../exercises/null-scattering/hidden.ts';
import { SINE_MEDIUM } from '../../exercises/delta-tracking/exercise.ts';
import { BUMP_MEDIUM } from '../../exercises/delta-tracking/hidden.ts';
import type { TrackingCase } from '../../src/grading/checks/tracking.ts';
import { gradeReference, gradeSubmission } from '../../src/grading/grade.ts';
import { loadFullExercise, wrongSubmissions } from '../../src/grading/node.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const publicCase = (args: readonly number[]): TrackingCase => ({
  args: args as unknown as TrackingCase['args'],
  params: [],
});

describe('null-scattering exercise: moments', () => {
  it('E[X] is e^{−τ}; P_n = 1 gives ratio tracking’s E[X²] = T²·exp(∫σt²/σ̄)', () => {
    for (const args of [PUBLIC_VALID, PUBLIC_LOW]) {
      const c = publicCase(args);
      const tau = SINE_MEDIUM.tau(c.args, [], args[2]);
      expect(nullScatteringMoment(SINE_MEDIUM, c, 1)).toBeCloseTo(Math.exp(-tau), 8);
      const ratio = publicCase([...args.slice(0, 4), 1]);
      const [s0, a, d, maj] = args;
      let integral = 0;
      const n = 4096;
      for (let i = 0; i < n; i++) {
        const s = ((i + 0.5) * d) / n;
        integral += ((s0 * (1 + a * Math.sin(3 * s))) ** 2 / maj) * (d / n);
      }
      expect(nullScatteringMoment(SINE_MEDIUM, ratio, 2)).toBeCloseTo(
        Math.exp(-2 * tau + integral),
        6,
      );
    }
  });

  it('a Monte Carlo of the estimator (float64, fixed seed) has the mean square the checks expect', () => {
    // Poisson process of rate σ̄ on [0, d]; null with probability P_n, factor σn/(σ̄P_n).
    let state = 12345;
    const uniform = (): number => {
      state = (Math.imul(state, 1664525) + 1013904223) >>> 0;
      return (state + 0.5) / 2 ** 32;
    };
    for (const args of [PUBLIC_VALID, PUBLIC_LOW]) {
      const [s0, a, d, maj, pn] = args;
      const n = 200_000;
      let sum2 = 0;
      for (let i = 0; i < n; i++) {
        let t = 0;
        let w = 1;
        for (;;) {
          t += -Math.log(1 - uniform()) / maj;
          if (t >= d) break;
          if (uniform() >= pn) {
            w = 0;
            break;
          }
          w *= (maj - s0 * (1 + a * Math.sin(3 * t))) / (maj * pn);
        }
        sum2 += w * w;
      }
      const c = publicCase(args);
      const second = nullScatteringMoment(SINE_MEDIUM, c, 2);
      const fourth = nullScatteringMoment(SINE_MEDIUM, c, 4);
      const bound = 5 * Math.sqrt((fourth - second * second) / n);
      expect(Math.abs(sum2 / n - second)).toBeLessThan(bound);
    }
  });

  it('every public and hidden case keeps E[X⁴]/E[X²]² below 6 (the mean-square z-test is near normal)', () => {
    const cases: [TrackingCase, typeof SINE_MEDIUM][] = [
      [publicCase(PUBLIC_VALID), SINE_MEDIUM],
      [publicCase(PUBLIC_LOW), SINE_MEDIUM],
    ];
    for (const seed of [1, 2, 3, 7, 11, 2026])
      for (const c of [
        ...HIDDEN_CASES.validMedia(seed),
        ...HIDDEN_CASES.lowMedia(seed),
        ...HIDDEN_CASES.noMedium(seed),
      ])
        cases.push([c, BUMP_MEDIUM]);
    for (const [c, family] of cases) {
      const second = nullScatteringMoment(family, c, 2);
      const fourth = nullScatteringMoment(family, c, 4);
      expect(fourth / second ** 2, JSON.stringify(c)).toBeLessThan(6);
    }
  });
});

describe('null-scattering exercise: hidden design', () => {
  type Wrong = 'noDivide' | 'clampNull' | 'ratio' | 'delta';
  /** E[X^m] of a wrong estimator by Campbell's identity, E[∏f] = exp(−∫σ̄(1 − E[f^m | s])). */
  function wrongMoment(c: TrackingCase, wrong: Wrong | 'correct', m: number): number {
    const [, , d, majorant, p = 1] = c.args;
    if (!(majorant > 0)) return 1;
    const factor = (s: number): number => {
      const sigmaN = majorant - BUMP_MEDIUM.sigma(c.args, c.params, s);
      switch (wrong) {
        case 'correct':
          return p * (sigmaN / (majorant * p)) ** m;
        case 'noDivide':
          return p * (sigmaN / majorant) ** m;
        case 'clampNull':
          return p * (Math.max(sigmaN, 0) / (majorant * p)) ** m;
        case 'ratio':
          return (sigmaN / majorant) ** m;
        case 'delta':
          return Math.max(sigmaN, 0) / majorant;
      }
    };
    const steps = 512;
    let integral = 0;
    for (let i = 0; i < steps; i++) integral += majorant * (1 - factor(((i + 0.5) * d) / steps));
    return Math.exp((-integral * d) / steps);
  }

  /** The larger expected |z| of the pooled mean and mean-square tests for a wrong estimator. */
  function expectedZ(cases: readonly TrackingCase[], n: number, wrong: Wrong): number {
    let dm = 0;
    let vm = 0;
    let d2 = 0;
    let v2 = 0;
    for (const c of cases) {
      const T = wrongMoment(c, 'correct', 1);
      const second = wrongMoment(c, 'correct', 2);
      const fourth = wrongMoment(c, 'correct', 4);
      dm += n * (wrongMoment(c, wrong, 1) - T);
      vm += n * (second - T * T);
      d2 += n * (wrongMoment(c, wrong, 2) - second);
      v2 += n * (fourth - second * second);
    }
    const z = (shift: number, variance: number): number =>
      variance > 0 ? Math.abs(shift) / Math.sqrt(variance) : Math.abs(shift) > 1e-12 ? Infinity : 0;
    return Math.max(z(dm, vm), z(d2, v2));
  }

  it('every wrong estimator fails every hidden check it should with expected |z| ≥ 10 (60 seeds), so verdicts do not depend on the seed', () => {
    const checks = [
      {
        cases: HIDDEN_CASES.validMedia,
        n: HIDDEN_DESIGN.calls,
        wrong: ['noDivide', 'ratio', 'delta'],
      },
      {
        cases: HIDDEN_CASES.lowMedia,
        n: HIDDEN_DESIGN.lowCalls,
        wrong: ['noDivide', 'clampNull', 'ratio', 'delta'],
      },
      {
        cases: HIDDEN_CASES.noMedium,
        n: HIDDEN_DESIGN.noMediumCalls,
        wrong: ['noDivide', 'ratio', 'delta'],
      },
    ] as const;
    for (let seed = 1; seed <= 60; seed++)
      for (const check of checks)
        for (const wrong of check.wrong)
          expect(
            expectedZ(check.cases(seed), check.n, wrong),
            `${wrong}, seed ${seed}`,
          ).toBeGreaterThan(10);
    // Clamping σn is exact under a valid majorant: those checks cannot tell it apart.
    expect(expectedZ(HIDDEN_CASES.validMedia(1), HIDDEN_DESIGN.calls, 'clampNull')).toBe(0);
  });
});

describe('null-scattering exercise on the GPU', () => {
  it('the reference scores full marks under two seeds', async () => {
    const device = await nodeDevice();
    const exercise = await loadFullExercise('null-scattering');
    for (const seed of [1, 2]) {
      const outcome = await gradeReference(device, SHADER_LIBRARY, exercise, {
        which: 'all',
        seed,
      });
      expect(outcome.status, JSON.stringify(outcome).slice(0, 2000)).toBe('graded');
      if (outcome.status !== 'graded') continue;
      expect(outcome.score, outcome.checks.map((c) => c.message).join('\n')).toBe(outcome.maxScore);
    }
  }, 300_000);

  it('fails each wrong submission on the checks its reason names', async () => {
    const publicValid = 'Valid majorant, P_n = 0.7';
    const publicLow = 'Majorant below σt, P_n = 0.8';
    const hiddenValid = 'Hidden media, valid majorant, several P_n';
    const hiddenLow = 'Hidden media, majorant below σt';
    const noMedium = 'No medium';
    const all = [publicValid, publicLow, hiddenValid, hiddenLow, noMedium];
    // The checks each submission must fail (|z| ≥ 10 by design, see above), and may fail.
    const failing: Record<string, { must: string[]; may?: string[] }> = {
      'no-divide.wgsl': { must: all },
      'clamp-null.wgsl': { must: [publicLow, hiddenLow] },
      'sigma-t-weight.wgsl': { must: all },
      'exp-estimate.wgsl': { must: all },
      'delta-tracking.wgsl': { must: all },
      'ratio-tracking.wgsl': {
        must: [publicValid, publicLow, hiddenValid, noMedium],
        may: [hiddenLow],
      },
    };
    const device = await nodeDevice();
    const exercise = await loadFullExercise('null-scattering');
    const wrong = wrongSubmissions('null-scattering');
    expect(wrong.map((w) => w.file).sort()).toEqual(Object.keys(failing).sort());
    for (const submission of wrong) {
      const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, submission.source, {
        which: 'all',
        seed: 7,
      });
      expect(outcome.status, submission.file).toBe('graded');
      if (outcome.status !== 'graded') continue;
      const failed = outcome.checks.filter((c) => c.verdict === 'fail').map((c) => c.name);
      const { must, may = [] } = failing[submission.file] ?? { must: [] };
      for (const name of must) expect(failed, submission.file).toContain(name);
      for (const name of failed) expect([...must, ...may], submission.file).toContain(name);
      const range = submission.score === 'full' ? [outcome.maxScore] : (submission.score ?? []);
      expect(outcome.score, submission.file).toBeGreaterThanOrEqual(range[0] ?? Infinity);
      expect(outcome.score, submission.file).toBeLessThanOrEqual(
        range[range.length - 1] ?? -Infinity,
      );
    }
  }, 300_000);
});
