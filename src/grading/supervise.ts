// The grade command's wall-clock limit. Grading runs in a child process (gradeWorker.ts)
// and this parent only waits for it, so the limit holds whatever the child is doing:
// a GPU that never answers, a Dawn call that blocks the child's event loop, a device
// or instance that keeps it alive after its work, or a crash. On the limit the child
// is killed and the outcome is 'timeout' (a failure on the grader's side, reported as
// such); a child that dies without an outcome gives 'internal-error'. Either way the
// caller gets an outcome to write as the report, and nothing is left running.
import { fork } from 'node:child_process';
import { statSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { MAX_SUBMISSION_BYTES, sizeRefusal } from './instrument.ts';
import type { GradeOutcome } from './types.ts';

/** Default wall-clock limit of one `grade` run, in seconds (flag `--time-limit`). */
export const DEFAULT_TIME_LIMIT_S = 120;

/** What the parent asks the worker to grade. */
export interface GradeJob {
  exercise: string;
  submission: string;
  seed?: number;
}

/** The worker's answer. */
export interface GradeAnswer {
  outcome: GradeOutcome;
  title: string;
}

export interface SupervisedGrade extends GradeAnswer {
  /** Wall-clock seconds from the start to the outcome. */
  seconds: number;
}

const WORKER = join(dirname(fileURLToPath(import.meta.url)), 'gradeWorker.ts');

/** Seconds the worker gets to exit by itself after it has answered, before it is killed. */
const EXIT_GRACE_MS = 3000;

/**
 * Grades `job` in a child process within `timeLimitS` seconds of wall clock. Never
 * rejects: every way the run can end is an outcome. A submission over the size cap is
 * refused from its file size alone, without reading it or starting a worker.
 */
export function gradeUnderLimit(
  job: GradeJob,
  timeLimitS: number,
  fallbackTitle: string,
  /** The worker module (the tests substitute ones that crash, hang or linger). */
  worker: string = WORKER,
): Promise<SupervisedGrade> {
  const started = performance.now();
  const seconds = (): number => (performance.now() - started) / 1000;
  let bytes: number;
  try {
    bytes = statSync(job.submission).size;
  } catch (error) {
    return Promise.resolve({
      outcome: {
        status: 'internal-error',
        message: `The grader could not read the submission (${(error as Error).message}).`,
      },
      title: fallbackTitle,
      seconds: seconds(),
    });
  }
  const tooLarge = sizeRefusal(bytes, MAX_SUBMISSION_BYTES);
  if (tooLarge) {
    return Promise.resolve({
      outcome: { status: 'rejected', message: tooLarge },
      title: fallbackTitle,
      seconds: seconds(),
    });
  }
  return new Promise((resolve) => {
    let settled = false;
    let answer: GradeAnswer | null = null;
    // The worker's stdout goes to our stderr: our stdout carries only the report.
    // It inherits our execArgv (the TypeScript loader) and stays in our process
    // group, so whoever kills this command's group kills the worker too.
    const child = fork(worker, [], { stdio: ['ignore', 2, 2, 'ipc'], serialization: 'advanced' });
    const finish = (result: GradeAnswer): void => {
      if (settled) return;
      settled = true;
      clearTimeout(limit);
      clearTimeout(grace);
      process.off('SIGTERM', onSignal);
      process.off('SIGINT', onSignal);
      if (child.exitCode === null && child.signalCode === null) child.kill('SIGKILL');
      resolve({ ...result, seconds: seconds() });
    };
    // Stopped from outside (Ctrl-C, `timeout`): take the worker along, exit as killed.
    const onSignal = (signal: NodeJS.Signals): void => {
      child.kill('SIGKILL');
      process.exit(signal === 'SIGINT' ? 130 : 143);
    };
    process.on('SIGTERM', onSignal);
    process.on('SIGINT', onSignal);
    let grace: ReturnType<typeof setTimeout> | undefined;
    const limit = setTimeout(() => {
      finish({
        outcome: {
          status: 'timeout',
          message:
            `Grading did not finish within the wall-clock limit of ${timeLimitS} s, so the ` +
            'grader stopped it (a loop that does far more work than the exercise needs can ' +
            'cause this too).',
        },
        title: answer?.title ?? fallbackTitle,
      });
    }, timeLimitS * 1000);
    child.on('message', (message: GradeAnswer) => {
      answer = message;
      // The answer stands; the worker should now exit by itself (it calls
      // process.exit), and is killed if something keeps it alive.
      grace = setTimeout(() => finish(message), EXIT_GRACE_MS);
    });
    child.on('error', (error) => {
      finish({
        outcome: {
          status: 'internal-error',
          message: `The grader could not start its worker process (${error.message}).`,
        },
        title: fallbackTitle,
      });
    });
    child.on('exit', (code, signal) => {
      if (answer) {
        finish(answer);
        return;
      }
      finish({
        outcome: {
          status: 'internal-error',
          message: `The grader's worker process ended without an outcome (${signal ? `signal ${signal}` : `exit status ${String(code)}`}).`,
        },
        title: fallbackTitle,
      });
    });
    child.send(job);
  });
}
