// Every exercise of the book, and a loader for its public part. The page imports
// this (one chunk per exercise through the dynamic imports); hidden checks are not
// reachable from here (see hiddenIndex.ts, imported only by the command line).
import type { ExerciseDefinition } from '../src/grading/exercise.ts';

type Loader = () => Promise<{ EXERCISE: ExerciseDefinition }>;

const LOADERS: Record<string, Loader> = {
  'beer-law': () => import('./beer-law/exercise.ts'),
  'hg-eval': () => import('./hg-eval/exercise.ts'),
  'hg-sample': () => import('./hg-sample/exercise.ts'),
  'mie-sample': () => import('./mie-sample/exercise.ts'),
  'raymarch-exact': () => import('./raymarch-exact/exercise.ts'),
  'delta-tracking': () => import('./delta-tracking/exercise.ts'),
  'single-scatter-shadow': () => import('./single-scatter-shadow/exercise.ts'),
  'hash-encoding': () => import('./hash-encoding/exercise.ts'),
  'dipole-rd': () => import('./dipole-rd/exercise.ts'),
  'hero-weight': () => import('./hero-weight/exercise.ts'),
  'null-scattering': () => import('./null-scattering/exercise.ts'),
  'room-irradiance': () => import('./room-irradiance/exercise.ts'),
};

/** Ids of all exercises, in book order. */
export const EXERCISE_IDS: readonly string[] = Object.keys(LOADERS);

/** The public definition of exercise `id` (statement data, starter, public checks). */
export async function loadExercise(id: string): Promise<ExerciseDefinition> {
  const loader = LOADERS[id];
  if (!loader) throw new Error(`unknown exercise "${id}" (known: ${EXERCISE_IDS.join(', ')})`);
  return (await loader()).EXERCISE;
}
