// <sb-exercise exercise="ID">: an autograded exercise in the page (issue 7). The
// statement was rendered into the element at build time (src/book/build/exercises.ts)
// and is kept; the view adds a CodeMirror WGSL editor, Run checks (the public checks
// of the one grading core, src/grading/grade.ts, on a GPU device of its own), Cancel,
// Reset, Hints one at a time, export and import of all exercises' progress, and the
// results with the student's values next to the reference's (view.ts). It draws
// nothing with the page's shared device, so the base chooses no backend for it: the
// view checks WebGPU itself, and without it the editor, saving and downloading work.
import { defineWidget } from '../base/definition.ts';
import { EXERCISE_WIDGET } from './schema.ts';
import type { StoredResult } from './progress.ts';

/** What the readouts show: the last stored result of the public checks, if any. */
export interface ExerciseFrame {
  result: StoredResult | null;
}

/** A non-graded outcome in a few words, for the readout and the stored summary. */
export const STATUS_WORDS: Record<StoredResult['status'], string> = {
  graded: 'graded',
  'compile-error': 'does not compile',
  'wrong-signature': 'wrong signature',
  'loop-budget': 'a loop ran past its budget',
  rejected: 'refused before compiling',
  timeout: 'timed out',
  'device-lost': 'GPU device lost',
  'internal-error': 'grader error',
};

/** Every public check passed. */
export function allPassed(result: StoredResult): boolean {
  return result.status === 'graded' && result.passed === result.total;
}

export const widget = defineWidget<ExerciseFrame>({
  entry: EXERCISE_WIDGET,
  readouts: {
    rows: [
      {
        key: 'checks',
        label: 'Public checks',
        format: ({ result }) =>
          result === null
            ? 'not run yet'
            : {
                text:
                  result.status === 'graded'
                    ? `${result.passed} of ${result.total} passed`
                    : STATUS_WORDS[result.status],
                state: allPassed(result) ? 'ok' : 'bad',
              },
      },
      {
        key: 'points',
        label: 'Points (public)',
        format: ({ result }) =>
          result === null
            ? '—'
            : {
                text: result.status === 'graded' ? `${result.score} of ${result.maxScore}` : '0',
                state: allPassed(result) ? 'ok' : 'bad',
              },
      },
    ],
  },
  load: () => import('./view.ts'),
});
