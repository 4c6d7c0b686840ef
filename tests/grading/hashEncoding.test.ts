// The hash-encoding exercise (chapter 8): its reference (the library's hashCellLocate,
// hashGridIndex, hashLevelResolution and trilinearWeight on the exercise's table), run
// on the GPU by the grader, and a student-style solution (fixtures/hash-encoding.wgsl) agree with the float64 twin (src/reference/neural.ts's
// neuralEncode on the same table) on every public case and on the hidden cases of
// several seeds; the starter is the statement's; and each known-wrong submission fails
// exactly the public checks whose messages name its mistake. The self-test
// (selfTest.test.ts) holds the total scores of wrong/expected.json under three seeds.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { EXERCISE } from '../../exercises/hash-encoding/exercise.ts';
import { HIDDEN_CHECKS } from '../../exercises/hash-encoding/hidden.ts';
import { expectedFeature, tableFeature } from '../../exercises/hash-encoding/table.ts';
import type { CaseSpec, CasesCheck, ExerciseDefinition } from '../../src/grading/exercise.ts';
import { gradeSubmission } from '../../src/grading/grade.ts';
import { EXERCISES_DIR, wrongSubmissions } from '../../src/grading/node.ts';
import type { NeuralField } from '../../src/reference/neural.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const SEEDS = [1, 77, 31337];

/** Every case the exercise grades: the public ones and the hidden ones of SEEDS. */
function allCases(): CaseSpec[] {
  const cases: CaseSpec[] = [];
  for (const check of EXERCISE.checks) if (check.kind === 'cases') cases.push(...check.cases);
  for (const seed of SEEDS)
    for (const check of HIDDEN_CHECKS)
      if (check.kind === 'generated-cases') cases.push(...check.generate(seed));
  return cases;
}

describe('hash-encoding exercise', () => {
  it('has a table in [−1, 1) whose entries are unrelated to their neighbours', () => {
    let sum = 0;
    let lag = 0;
    const n = 4096;
    for (let e = 0; e < n; e++) {
      const v = tableFeature(3, e, 0);
      expect(v).toBeGreaterThanOrEqual(-1);
      expect(v).toBeLessThan(1);
      sum += v;
      lag += v * tableFeature(3, e + 1, 0);
    }
    // Mean ≈ 0 and lag-1 correlation ≈ 0 (standard errors ≈ 0.6/√n = 0.009).
    expect(Math.abs(sum / n)).toBeLessThan(0.05);
    expect(Math.abs(lag / n / (1 / 3))).toBeLessThan(0.1);
    // The two features of an entry differ, and so do the levels.
    expect(tableFeature(3, 17, 0)).not.toBe(tableFeature(3, 17, 1));
    expect(tableFeature(3, 17, 0)).not.toBe(tableFeature(4, 17, 0));
  });

  it('ships the statement’s starter', () => {
    const starter = readFileSync(join(EXERCISES_DIR, 'hash-encoding', 'starter.wgsl'), 'utf8');
    expect(starter).toBe(EXERCISE.starter);
  });

  it('grades against a reference that agrees with the float64 twin on every case', async () => {
    const cases = allCases();
    const agreement: CasesCheck = {
      kind: 'cases',
      name: 'reference = float64 twin',
      points: 1,
      message: 'unused',
      rtol: 0,
      atol: 1,
      cases,
      // The figure carries every case's GPU value as a number.
      figure: { argIndex: 0, xLabel: 'x' },
    };
    const exercise: ExerciseDefinition = { ...EXERCISE, checks: [agreement] };
    const device = await nodeDevice();
    // Submitted: the student-style solution of the seeded tests (submissions cannot
    // import the library); the reference is the exercise's.
    const fixture = readFileSync(
      join(import.meta.dirname, 'fixtures', 'hash-encoding.wgsl'),
      'utf8',
    );
    const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, fixture, {
      which: 'public',
      seed: 1,
    });
    expect(outcome.status).toBe('graded');
    if (outcome.status !== 'graded') return;
    const figure = outcome.checks[0]?.figure;
    if (figure?.kind !== 'series') throw new Error('no values from the grader');
    const fields = new Map<number, NeuralField>();
    let worst = 0;
    cases.forEach((c, i) => {
      const twin = expectedFeature(c.args, fields);
      const error = Math.abs(figure.reference[i]! - twin);
      worst = Math.max(worst, error, Math.abs(figure.student[i]! - twin));
      expect(error, c.label).toBeLessThan(1e-5);
    });
    // The checks' tolerance (1e-4 absolute) is ten times the f32 error of both (the
    // rounding of p times N_l ≤ 45, exercise.ts's TOLERANCE).
    expect(worst).toBeLessThan(1e-5);
  }, 120_000);

  it('fails each wrong submission on exactly the public checks that name its mistake', async () => {
    const failing: Record<string, string[]> = {
      'wrong-prime-order.wgsl': [
        'Spatial hash: vertices of the hashed levels',
        'Hashed levels inside the cells',
        'Points outside the box',
      ],
      'no-modulo.wgsl': [
        'Spatial hash: vertices of the hashed levels',
        'Hashed levels inside the cells',
        'Points outside the box',
      ],
      'signed-modulo.wgsl': [
        'Spatial hash: vertices of the hashed levels',
        'Hashed levels inside the cells',
        'Points outside the box',
      ],
      'nearest-vertex.wgsl': [
        'Trilinear interpolation inside the cells (dense levels)',
        'Hashed levels inside the cells',
        'Points outside the box',
      ],
      'off-by-one-resolution.wgsl': EXERCISE.checks.map((c) => c.name),
    };
    const device = await nodeDevice();
    const wrong = wrongSubmissions('hash-encoding');
    expect(wrong.map((w) => w.file).sort()).toEqual(Object.keys(failing).sort());
    for (const submission of wrong) {
      const outcome = await gradeSubmission(device, SHADER_LIBRARY, EXERCISE, submission.source, {
        which: 'public',
        seed: 1,
      });
      expect(outcome.status, submission.file).toBe('graded');
      if (outcome.status !== 'graded') continue;
      const failed = outcome.checks.filter((c) => c.verdict === 'fail');
      expect(
        failed.map((c) => c.name),
        submission.file,
      ).toEqual(failing[submission.file]);
      // The first failing check's message names the mistake's ingredient.
      const first = failed[0]!.message;
      if (submission.file === 'nearest-vertex.wgsl') expect(first).toContain('trilinear');
      else if (submission.file === 'off-by-one-resolution.wgsl') expect(first).toContain('N_l');
      else expect(first).toMatch(/2654435761.*mod T/);
    }
  }, 180_000);
});
