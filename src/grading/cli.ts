// The instructor's command line:
//   npm run grade -- --exercise ID --submission FILE [--format gradescope|prairielearn|json|junit]
//                    [--out FILE] [--seed S] [--time-limit SECONDS]
//   npm run grade -- --self-test [--exercise ID]
// Grading runs public and hidden checks through Dawn in Node, in a worker process
// under a wall-clock limit (supervise.ts). Exit status: 0 when a report was written,
// whatever it says (a score, a compile error, a refused submission, an endless loop,
// and also the grader's own failures — timeout, device-lost, internal-error — which
// the report presents as such); 1 when the self-test fails; 2 for a usage error
// (unknown exercise, missing file, bad flags), when no report is written.
import { randomBytes } from 'node:crypto';
import { existsSync, statSync, writeFileSync, writeSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import { nodeDevice, releaseNodeDevice } from '../gpu/nodeDevice.ts';
import { loadShaderLibrary } from '../gpu/shaderSourcesNode.ts';
import { EXERCISE_IDS } from '../../exercises/index.ts';
import { loadExercise } from '../../exercises/index.ts';
import { REPORT_FORMATS, renderReport, summary, type ReportFormat } from './reports.ts';
import { runSelfTest } from './selfTest.ts';
import { DEFAULT_TIME_LIMIT_S, gradeUnderLimit } from './supervise.ts';

const USAGE = `usage:
  grade --exercise ID --submission FILE [--format gradescope|prairielearn|json|junit] [--out FILE] [--seed S]
        [--time-limit SECONDS (default ${DEFAULT_TIME_LIMIT_S})]
  grade --self-test [--exercise ID]
  grade kit gradescope --exercise ID --out DIR | grade kit prairielearn --out DIR  (grade kit --help)
exercises: ${EXERCISE_IDS.join(', ')}`;

class UsageError extends Error {}

function print(text: string): void {
  process.stdout.write(`${text}\n`);
}

/** The human summary goes to stderr so stdout carries only the report (`> r.json` stays valid). */
function note(text: string): void {
  process.stderr.write(`${text}\n`);
}

const SHADERS = resolve(dirname(fileURLToPath(import.meta.url)), '../../shaders');

async function main(argv: string[]): Promise<number> {
  // `grade kit …` writes a Gradescope or PrairieLearn kit (src/grading/kit/).
  if (argv[0] === 'kit') return (await import('./kit/index.ts')).runKit(argv.slice(1));
  let values;
  try {
    ({ values } = parseArgs({
      args: argv,
      options: {
        exercise: { type: 'string' },
        submission: { type: 'string' },
        format: { type: 'string', default: 'gradescope' },
        out: { type: 'string' },
        seed: { type: 'string' },
        'time-limit': { type: 'string' },
        'self-test': { type: 'boolean', default: false },
        help: { type: 'boolean', default: false },
      },
      strict: true,
      allowPositionals: false,
    }));
  } catch (error) {
    throw new UsageError((error as Error).message);
  }
  if (values.help) {
    print(USAGE);
    return 0;
  }
  const library = loadShaderLibrary(SHADERS);
  if (values['self-test']) {
    const ids = values.exercise ? [values.exercise] : EXERCISE_IDS;
    for (const id of ids)
      if (!EXERCISE_IDS.includes(id)) throw new UsageError(`unknown exercise "${id}"`);
    const device = await nodeDevice();
    const lines = await runSelfTest(device, library, ids, undefined, (line) =>
      print(`${line.ok ? 'ok  ' : 'FAIL'} ${line.exercise} ${line.subject}: ${line.detail}`),
    );
    const failed = lines.filter((l) => !l.ok).length;
    print(
      failed === 0
        ? `self-test passed (${lines.length} checks)`
        : `self-test FAILED: ${failed} of ${lines.length}`,
    );
    return failed === 0 ? 0 : 1;
  }
  if (!values.exercise) throw new UsageError('--exercise is required');
  if (!EXERCISE_IDS.includes(values.exercise))
    throw new UsageError(`unknown exercise "${values.exercise}"`);
  if (!values.submission) throw new UsageError('--submission is required');
  if (!existsSync(values.submission)) throw new UsageError(`no such file: ${values.submission}`);
  if (!statSync(values.submission).isFile())
    throw new UsageError(`not a file: ${values.submission}`);
  const format = values.format as ReportFormat;
  if (!REPORT_FORMATS.includes(format))
    throw new UsageError(`--format must be one of ${REPORT_FORMATS.join(', ')}`);
  let seed: number | undefined;
  if (values.seed !== undefined) {
    // Digits only: Number() would also accept '', '0x10', '1e3' and ' 7 '.
    seed = /^\d+$/.test(values.seed) ? Number(values.seed) : Number.NaN;
    if (!Number.isInteger(seed) || seed < 0 || seed > 0xffffffff)
      throw new UsageError('--seed must be an integer in [0, 2^32)');
  }
  // Without --seed every grading draws its own seed. Hidden cases and media are drawn
  // from it, and hidden.ts is open source, so a fixed default seed would let anyone
  // compute the hidden inputs and table them. The report states the seed; --seed
  // reproduces a grade.
  seed ??= randomBytes(4).readUInt32LE(0);
  let timeLimitS = DEFAULT_TIME_LIMIT_S;
  if (values['time-limit'] !== undefined) {
    timeLimitS = /^\d+(\.\d+)?$/.test(values['time-limit'])
      ? Number(values['time-limit'])
      : Number.NaN;
    if (!(timeLimitS > 0 && timeLimitS <= 86_400))
      throw new UsageError('--time-limit must be a number of seconds in (0, 86400]');
  }
  // The public part only, for the title (the worker loads the hidden checks).
  const title = (await loadExercise(values.exercise)).title;
  const { outcome, seconds } = await gradeUnderLimit(
    {
      exercise: values.exercise,
      submission: values.submission,
      ...(seed !== undefined ? { seed } : {}),
    },
    timeLimitS,
    title,
  );
  const context = { exerciseId: values.exercise, title, executionTimeS: seconds };
  note(summary(outcome, context));
  const report = renderReport(format, outcome, context);
  if (values.out) {
    writeFileSync(values.out, report);
    note(`${format} report written to ${values.out}`);
  } else {
    writeAllSync(1, report);
  }
  return 0;
}

/** Writes all of `text` to a file descriptor before returning (process.exit follows). */
function writeAllSync(fd: number, text: string): void {
  const bytes = Buffer.from(text, 'utf8');
  let offset = 0;
  while (offset < bytes.length) {
    try {
      offset += writeSync(fd, bytes, offset);
    } catch (error) {
      // A non-blocking pipe that is full: try again.
      if ((error as NodeJS.ErrnoException).code !== 'EAGAIN') throw error;
    }
  }
}

/** Releases the GPU device, but never waits more than `ms` for it (the process must exit). */
function releaseWithin(ms: number): Promise<void> {
  return Promise.race([
    releaseNodeDevice().catch(() => undefined),
    new Promise<void>((resolve) => setTimeout(resolve, ms).unref()),
  ]);
}

main(process.argv.slice(2))
  .then(async (code) => {
    await releaseWithin(5000);
    process.exit(code);
  })
  .catch(async (error: unknown) => {
    await releaseWithin(5000);
    if (error instanceof UsageError) {
      console.error(`grade: ${error.message}\n${USAGE}`);
    } else {
      console.error(`grade: grader failure: ${(error as Error).stack ?? String(error)}`);
    }
    process.exit(2);
  });
