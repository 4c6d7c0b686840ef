// The room-irradiance exercise (chapter 12): the number the statement gives is the
// reference's (π(1 − F) at normal incidence, η = 1.3, from the float64 Fresnel), the
// reference scores full marks under two seeds, the starter scores nothing, and each wrong
// submission fails every check, as expected.json says. The self-test (selfTest.test.ts)
// repeats the scores under three seeds.
import { describe, expect, it } from 'vitest';
import { EXERCISE } from '../../exercises/room-irradiance/exercise.ts';
import { fresnelDielectric } from '../../src/reference/fresnel.ts';
import { gradeSubmission } from '../../src/grading/grade.ts';
import { loadFullExercise, wrongSubmissions } from '../../src/grading/node.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

describe('room-irradiance exercise', () => {
  it('the statement’s value at normal incidence is π(1 − ((η − 1)/(η + 1))²)', () => {
    const normal = Math.PI * (1 - ((1.3 - 1) / (1.3 + 1)) ** 2);
    expect(Math.PI * (1 - fresnelDielectric(1, 1.3))).toBeCloseTo(normal, 12);
    expect(normal).toBeCloseTo(3.0881, 4);
  });

  it('the reference scores full marks and the starter nothing', async () => {
    const device = await nodeDevice();
    const exercise = await loadFullExercise('room-irradiance');
    for (const seed of [1, 7]) {
      const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, EXERCISE.reference, {
        which: 'all',
        seed,
      });
      expect(outcome.status).toBe('graded');
      if (outcome.status !== 'graded') return;
      expect(outcome.score, JSON.stringify(outcome.checks)).toBe(outcome.maxScore);
    }
    const starter = await gradeSubmission(device, SHADER_LIBRARY, exercise, EXERCISE.starter, {
      which: 'all',
      seed: 1,
    });
    expect(starter.status).toBe('graded');
    if (starter.status === 'graded') expect(starter.score).toBe(0);
  }, 120_000);

  it('fails each wrong submission on every check', async () => {
    const device = await nodeDevice();
    const exercise = await loadFullExercise('room-irradiance');
    const wrong = wrongSubmissions('room-irradiance');
    expect(wrong.map((w) => w.file).sort()).toEqual([
      'extra-cosine.wgsl',
      'no-pi.wgsl',
      'reflected.wgsl',
    ]);
    for (const submission of wrong) {
      const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, submission.source, {
        which: 'all',
        seed: 7,
      });
      expect(outcome.status, submission.file).toBe('graded');
      if (outcome.status !== 'graded') continue;
      expect(
        outcome.checks.filter((c) => c.verdict !== 'fail').map((c) => c.name),
        submission.file,
      ).toEqual([]);
      const range = submission.score === 'full' ? [outcome.maxScore] : (submission.score ?? []);
      expect(range, submission.file).toContain(outcome.score);
    }
  }, 120_000);
});
