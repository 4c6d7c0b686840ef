// What grading costs: for every exercise, the wall time of grading the reference
// solution with the public checks (what a student waits for after Run checks in the
// page) and with all checks (what the instructor's `grade` command runs per
// submission), on this machine's GPU through Dawn. The first run compiles the
// pipelines (cold); the median of the following runs is the warm cost.
import { fileURLToPath } from 'node:url';
import { EXERCISE_IDS } from '../exercises/index.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { gradeReference } from '../src/grading/grade.ts';
import { loadFullExercise } from '../src/grading/node.ts';
import type { GradeOptions } from '../src/grading/types.ts';
import { median, type BenchTable } from './table.ts';

async function timeGrading(
  run: () => Promise<unknown>,
  repeats: number,
): Promise<{ cold: number; warm: number }> {
  const times: number[] = [];
  for (let i = 0; i <= repeats; i++) {
    const start = performance.now();
    await run();
    times.push(performance.now() - start);
  }
  return { cold: times[0] ?? NaN, warm: median(times.slice(1)) };
}

export async function benchGrading(
  device: GPUDevice,
  options: { repeats: number },
): Promise<BenchTable> {
  const library = loadShaderLibrary(fileURLToPath(new URL('../shaders', import.meta.url)));
  const rows: BenchTable['rows'] = [];
  for (const id of EXERCISE_IDS) {
    const exercise = await loadFullExercise(id);
    const grade = (which: GradeOptions['which']) => async () => {
      const outcome = await gradeReference(device, library, exercise, { which });
      if (outcome.status !== 'graded' || outcome.score !== outcome.maxScore)
        throw new Error(`bench: the reference of ${id} did not score full marks`);
    };
    const publicTime = await timeGrading(grade('public'), options.repeats);
    const allTime = await timeGrading(grade('all'), options.repeats);
    rows.push({
      exercise: id,
      'public checks': exercise.checks.length,
      'hidden checks': exercise.hiddenChecks?.length ?? 0,
      'public ms (cold)': publicTime.cold,
      'public ms (warm median)': publicTime.warm,
      'all ms (cold)': allTime.cold,
      'all ms (warm median)': allTime.warm,
    });
  }
  return {
    title: 'Grading cost per exercise (reference solution, Dawn in Node)',
    notes: [
      'public: the checks the page runs on Run checks; all: public + hidden, as `npm run grade` runs them.',
      `cold: first run (compiles the pipelines); warm: median of ${options.repeats} further runs.`,
    ],
    rows,
  };
}
