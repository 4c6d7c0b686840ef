// Node-only access to exercises: the full definition with hidden checks, the
// files of an exercise folder (starter, known-wrong submissions). Used by the
// command line and the tests; never imported by the page.
import { readdirSync, readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadExercise } from '../../exercises/index.ts';
import { HIDDEN_LOADERS } from '../../exercises/hiddenIndex.ts';
import type { ExerciseDefinition, WrongExpectation } from './exercise.ts';
import { decodeSubmission } from './instrument.ts';

export const EXERCISES_DIR = resolve(dirname(fileURLToPath(import.meta.url)), '../../exercises');

/** The exercise with its hidden checks. */
export async function loadFullExercise(id: string): Promise<ExerciseDefinition> {
  const exercise = await loadExercise(id);
  const hidden = HIDDEN_LOADERS[id];
  if (!hidden)
    throw new Error(`exercise "${id}" has no hidden.ts registered in exercises/hiddenIndex.ts`);
  return { ...exercise, hiddenChecks: (await hidden()).HIDDEN_CHECKS };
}

export function readExerciseFile(id: string, file: string): string {
  return readFileSync(join(EXERCISES_DIR, id, file), 'utf8');
}

export interface WrongSubmission extends WrongExpectation {
  source: string;
}

/** exercises/<id>/wrong/*.wgsl with their expectations from wrong/expected.json. */
export function wrongSubmissions(id: string): WrongSubmission[] {
  const folder = join(EXERCISES_DIR, id, 'wrong');
  const expected = JSON.parse(
    readFileSync(join(folder, 'expected.json'), 'utf8'),
  ) as WrongExpectation[];
  const files = readdirSync(folder).filter((f) => f.endsWith('.wgsl'));
  for (const file of files) {
    if (!expected.some((e) => e.file === file))
      throw new Error(`exercises/${id}/wrong/${file} has no entry in expected.json`);
  }
  // Decoded as the grade command decodes a submission (UTF-8, or UTF-16 with its mark).
  return expected.map((e) => ({
    ...e,
    source: decodeSubmission(readFileSync(join(folder, e.file))),
  }));
}
