// The child process of the grade command (see supervise.ts): receives one GradeJob
// over IPC, grades it on Dawn, answers with the outcome and exits at once, without
// waiting for the GPU device or the Dawn instance to wind down (they may keep the
// event loop alive, e.g. behind a kernel that never ended). Exits too when the
// parent goes away.
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { nodeDevice } from '../gpu/nodeDevice.ts';
import { loadShaderLibrary } from '../gpu/shaderSourcesNode.ts';
import { gradeSubmission } from './grade.ts';
import { decodeSubmission } from './instrument.ts';
import { loadFullExercise } from './node.ts';
import type { GradeAnswer, GradeJob } from './supervise.ts';

const SHADERS = resolve(dirname(fileURLToPath(import.meta.url)), '../../shaders');

async function grade(job: GradeJob): Promise<GradeAnswer> {
  let title = job.exercise;
  try {
    const exercise = await loadFullExercise(job.exercise);
    title = exercise.title;
    const source = decodeSubmission(readFileSync(job.submission));
    const library = loadShaderLibrary(SHADERS);
    const device = await nodeDevice();
    const outcome = await gradeSubmission(device, library, exercise, source, {
      which: 'all',
      ...(job.seed !== undefined ? { seed: job.seed } : {}),
    });
    return { outcome, title };
  } catch (error) {
    // gradeSubmission does not throw; this is loading the exercise, the file or the GPU.
    const detail = error instanceof Error ? `${error.name}: ${error.message}` : String(error);
    return {
      outcome: {
        status: 'internal-error',
        message: `The grader failed before grading (${detail}). This is not a problem with your code.`,
      },
      title,
    };
  }
}

process.on('disconnect', () => process.exit(0));
process.once('message', (job: GradeJob) => {
  void grade(job).then((answer) => {
    process.send?.(answer, undefined, undefined, () => process.exit(0));
  });
});
