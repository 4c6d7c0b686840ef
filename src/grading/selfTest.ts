// The grader's check of itself (`grade --self-test`, and tests/grading/selfTest.test.ts):
// every reference solution scores full marks, every known-wrong submission in
// exercises/<id>/wrong/ gets its expected outcome and score, and every grade is the
// same under several seeds (no flaky grading).
import type { ShaderLibrary } from '../gpu/link.ts';
import { EXERCISE_IDS } from '../../exercises/index.ts';
import { gradeReference, gradeSubmission } from './grade.ts';
import { loadFullExercise, wrongSubmissions } from './node.ts';
import type { GradeOutcome } from './types.ts';

export const SELF_TEST_SEEDS: readonly number[] = [1, 20261123, 0xdeadbeef];

export interface SelfTestLine {
  exercise: string;
  subject: string;
  ok: boolean;
  detail: string;
}

function describe(outcome: GradeOutcome): string {
  return outcome.status === 'graded'
    ? `${outcome.score}/${outcome.maxScore}`
    : `${outcome.status}: ${outcome.message.split('\n')[0] ?? ''}`;
}

/** The outcomes under all seeds, once when they agree. */
function describeAll(outcomes: readonly GradeOutcome[]): string {
  const texts = outcomes.map(describe);
  return texts.every((t) => t === texts[0])
    ? `${texts[0] ?? ''} (all ${texts.length} seeds)`
    : texts.join(' | ');
}

/** Grades of one submission under every seed, and whether they all agree. */
async function underSeeds(
  grade: (seed: number) => Promise<GradeOutcome>,
  seeds: readonly number[],
): Promise<{ outcomes: GradeOutcome[]; stable: boolean }> {
  const outcomes: GradeOutcome[] = [];
  for (const seed of seeds) outcomes.push(await grade(seed));
  const key = (o: GradeOutcome): string =>
    o.status === 'graded'
      ? `graded ${o.score} ${o.checks.map((c) => c.verdict).join(',')}`
      : o.status;
  const first = key(outcomes[0] as GradeOutcome);
  return { outcomes, stable: outcomes.every((o) => key(o) === first) };
}

/** Runs the self-test over `ids` (default: all exercises). */
export async function runSelfTest(
  device: GPUDevice,
  library: ShaderLibrary,
  ids: readonly string[] = EXERCISE_IDS,
  seeds: readonly number[] = SELF_TEST_SEEDS,
  onLine?: (line: SelfTestLine) => void,
): Promise<SelfTestLine[]> {
  const lines: SelfTestLine[] = [];
  const report = (line: SelfTestLine): void => {
    lines.push(line);
    onLine?.(line);
  };
  for (const id of ids) {
    const exercise = await loadFullExercise(id);
    const reference = await underSeeds(
      (seed) => gradeReference(device, library, exercise, { which: 'all', seed }),
      seeds,
    );
    const full = reference.outcomes.every((o) => o.status === 'graded' && o.score === o.maxScore);
    report({
      exercise: id,
      subject: 'reference solution',
      ok: full && reference.stable,
      detail: describeAll(reference.outcomes),
    });
    for (const wrong of wrongSubmissions(id)) {
      const graded = await underSeeds(
        (seed) => gradeSubmission(device, library, exercise, wrong.source, { which: 'all', seed }),
        seeds,
      );
      const status = wrong.status ?? 'graded';
      const matches = graded.outcomes.every((o) => {
        if (o.status !== status) return false;
        if (o.status !== 'graded' || !wrong.score) return true;
        const [min, max] = wrong.score === 'full' ? [o.maxScore, o.maxScore] : wrong.score;
        return o.score >= min && o.score <= max;
      });
      const range = wrong.score;
      const expected =
        status === 'graded' && range
          ? range === 'full'
            ? 'expected full marks'
            : `expected ${range[0] === range[1] ? range[0] : range.join('–')} points`
          : `expected ${status}`;
      report({
        exercise: id,
        subject: `wrong/${wrong.file}`,
        ok: matches && graded.stable,
        detail:
          `${describeAll(graded.outcomes)} (${expected}` +
          `${graded.stable ? '' : '; NOT STABLE ACROSS SEEDS'}) — ${wrong.reason}`,
      });
    }
  }
  return lines;
}
