// The hero-weight exercise (chapter 12): the reference is the library's heroBalanceWeight and
// scores full marks; each known-wrong submission (forgetting the 1/3 of choosing the hero, the
// power heuristic, dividing by the hero's pdf only) fails the checks it should, with the message
// that names its mistake, and scores what expected.json states.
import { describe, expect, it } from 'vitest';
import { WEIGHT_MESSAGE } from '../../exercises/hero-weight/exercise.ts';
import { gradeReference, gradeSubmission } from '../../src/grading/grade.ts';
import { loadFullExercise, wrongSubmissions } from '../../src/grading/node.ts';
import { heroBalanceWeight } from '../../src/reference/chromatic.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const ID = 'hero-weight';

describe('hero-weight exercise', () => {
  it('the balance weight is the same for every hero and 1/p for equal pdfs (the twin)', () => {
    for (const hero of [0, 1, 2])
      expect(heroBalanceWeight([0.5, 2, 6], hero)).toBeCloseTo(3 / 8.5, 14);
    expect(heroBalanceWeight([4, 4, 4], 0)).toBeCloseTo(0.25, 14);
  });

  it('the reference scores full marks under two seeds', async () => {
    const device = await nodeDevice();
    const exercise = await loadFullExercise(ID);
    for (const seed of [1, 2]) {
      const outcome = await gradeReference(device, SHADER_LIBRARY, exercise, {
        which: 'all',
        seed,
      });
      expect(outcome.status).toBe('graded');
      if (outcome.status !== 'graded') return;
      expect(outcome.score).toBe(outcome.maxScore);
    }
  }, 60_000);

  it('each wrong submission fails with its message and scores what expected.json says', async () => {
    const device = await nodeDevice();
    const exercise = await loadFullExercise(ID);
    const wrong = wrongSubmissions(ID);
    expect(wrong.map((w) => w.file).sort()).toEqual([
      'hero-only.wgsl',
      'no-third.wgsl',
      'power-heuristic.wgsl',
    ]);
    for (const submission of wrong) {
      const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, submission.source, {
        which: 'all',
        seed: 5,
      });
      expect(outcome.status, submission.file).toBe('graded');
      if (outcome.status !== 'graded') continue;
      const [min, max] =
        submission.score === 'full'
          ? [outcome.maxScore, outcome.maxScore]
          : (submission.score ?? [0, outcome.maxScore]);
      expect(outcome.score, submission.file).toBeGreaterThanOrEqual(min);
      expect(outcome.score, submission.file).toBeLessThanOrEqual(max);
      const failed = outcome.checks.filter((c) => c.verdict !== 'pass');
      // Every wrong submission fails the public check of different pdfs, whose message names
      // all three slips (factor 3, 1/p_hero, power heuristic).
      const different = failed.find((c) => c.name === 'Different pdfs, each channel the hero');
      expect(different, submission.file).toBeDefined();
      expect(different?.message).toContain(WEIGHT_MESSAGE);
    }
  }, 120_000);
});
