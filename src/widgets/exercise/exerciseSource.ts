// The page's view of the exercises and the grading core: the public definitions
// (exercises/index.ts → exercises/<id>/exercise.ts, never hidden.ts, so hidden
// checks stay out of the bundle) and gradeSubmission with the browser's shader
// library. The only module of the widget that imports part A's code. The grader, the
// WESL linker and the library source (about 160 KB gzip) load on the first check, not
// with the chapter.
import { EXERCISE_IDS, loadExercise } from '../../../exercises/index.ts';
import { DEFAULT_TIMEOUT_MS } from '../../grading/defaults.ts';
import type { ExerciseDefinition } from '../../grading/exercise.ts';
import type { GradeOptions, GradeOutcome } from '../../grading/types.ts';

/** The grading core's watchdog per GPU submission, the same as the command line's. */
export const GRADE_TIMEOUT_MS = DEFAULT_TIMEOUT_MS;

/** Every exercise id the book has (import validation). */
export function exerciseIds(): readonly string[] {
  return EXERCISE_IDS;
}

export async function loadExerciseForPage(id: string): Promise<ExerciseDefinition> {
  if (!EXERCISE_IDS.includes(id))
    throw new Error(`there is no exercise “${id}” (known: ${EXERCISE_IDS.join(', ')})`);
  return loadExercise(id);
}

/** The public checks of `exercise` on `device`. */
export async function gradeOnPage(
  device: GPUDevice,
  exercise: ExerciseDefinition,
  source: string,
  options: GradeOptions,
): Promise<GradeOutcome> {
  const [{ gradeSubmission }, { SHADER_LIBRARY }] = await Promise.all([
    import('../../grading/grade.ts'),
    import('../../gpu/shaderSources.ts'),
  ]);
  return gradeSubmission(device, SHADER_LIBRARY, exercise, source, { ...options, which: 'public' });
}
