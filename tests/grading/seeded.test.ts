// Seeded hidden checks against solutions that are not the reference: a correct solution
// written as a student would (tests/grading/fixtures/<id>.wgsl, plus a differently
// ordered delta tracker) scores full marks under seeds the self-test does not use, and
// a table of the public inputs plus a guess (wrong/cheat-table.wgsl) scores exactly the
// public points, whatever the seed.
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { EXERCISE_IDS } from '../../exercises/index.ts';
import { gradeSubmission } from '../../src/grading/grade.ts';
import { EXERCISES_DIR, loadFullExercise } from '../../src/grading/node.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const SEEDS = [5, 4242, 987654321];
const FIXTURES = join(import.meta.dirname, 'fixtures');

describe('seeded hidden checks', () => {
  it('give a correct student-style solution full marks under other seeds', async () => {
    const device = await nodeDevice();
    const files = [
      ...EXERCISE_IDS.map((id) => [id, `${id}.wgsl`] as const),
      ['delta-tracking', 'delta-tracking-lookup-first.wgsl'] as const,
    ];
    for (const [id, file] of files) {
      const exercise = await loadFullExercise(id);
      const source = readFileSync(join(FIXTURES, file), 'utf8');
      for (const seed of SEEDS) {
        const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, source, {
          which: 'all',
          seed,
        });
        expect(outcome.status, `${file} seed ${seed}`).toBe('graded');
        if (outcome.status !== 'graded') continue;
        const failed = outcome.checks.filter((c) => c.verdict === 'fail');
        expect(
          failed.map((c) => `${c.name}: ${c.message}`),
          `${file} seed ${seed}`,
        ).toEqual([]);
      }
    }
  }, 240_000);

  it('give a table of the public inputs plus a guess at most the public points', async () => {
    const device = await nodeDevice();
    for (const id of EXERCISE_IDS) {
      const path = join(EXERCISES_DIR, id, 'wrong', 'cheat-table.wgsl');
      if (!existsSync(path)) continue;
      const exercise = await loadFullExercise(id);
      const publicPoints = exercise.checks.reduce((sum, c) => sum + c.points, 0);
      for (const seed of SEEDS) {
        const outcome = await gradeSubmission(
          device,
          SHADER_LIBRARY,
          exercise,
          readFileSync(path, 'utf8'),
          { which: 'all', seed },
        );
        expect(outcome.status).toBe('graded');
        if (outcome.status !== 'graded') continue;
        expect(outcome.score, `${id} seed ${seed}`).toBeLessThanOrEqual(publicPoints);
        for (const c of outcome.checks)
          if (c.visibility === 'hidden') expect(c.verdict, `${id}: ${c.name}`).toBe('fail');
      }
    }
  }, 120_000);
});
