// The kits' driver, run on the grading machine (Gradescope's container, or the
// PrairieLearn external-grader image) by `run_autograder` / `entrypoint.sh`:
//
//   node --import tsx src/grading/kit/driver.ts gradescope --exercise ID [--time-limit S]
//   node --import tsx src/grading/kit/driver.ts prairielearn --exercise ID [--time-limit S]
//
// It finds the student's one `.wgsl` file (Gradescope: under $AUTOGRADER_ROOT/submission,
// default /autograder; PrairieLearn: $GRADE_ROOT/student, default /grade, else the
// `_files` of $GRADE_ROOT/data/data.json), grades it with the `grade` command in a child
// process under a wall-clock limit, checks the report against the platform's fields
// (validate.ts) and writes results.json ($AUTOGRADER_ROOT/results/ or $GRADE_ROOT/results/).
// Whatever goes wrong — no file or several, the grader crashing, hanging past the limit
// or writing an invalid report — a valid results.json is written: the student's
// problems as a refused submission, the grader's as "grading failed, will be regraded"
// (never a score of 0 presented as the student's). The shell scripts around this add a
// last fallback for when Node itself cannot run.
import { spawn } from 'node:child_process';
import { execFileSync } from 'node:child_process';
import {
  existsSync,
  lstatSync,
  mkdirSync,
  mkdtempSync,
  readFileSync,
  readdirSync,
  rmSync,
  writeFileSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import { EXERCISE_IDS, loadExercise } from '../../../exercises/index.ts';
import { renderReport, type ReportFormat } from '../reports.ts';
import type { GradeOutcome } from '../types.ts';
import { gradescopeProblems, prairieLearnProblems } from './validate.ts';

export type Platform = 'gradescope' | 'prairielearn';

const PROJECT = resolve(dirname(fileURLToPath(import.meta.url)), '../../..');
/** Default wall-clock limit of one grading, seconds (the kits write their own). */
export const DEFAULT_TIME_LIMIT_S = 60;
/**
 * Beyond the grade command's own limit, before the driver kills it: the command
 * needs a moment after its limit to write the report and release the GPU.
 */
export function killGraceS(timeLimitS: number): number {
  return Math.min(15, Math.max(2, timeLimitS / 4));
}
/** Most of the grader's stderr kept for the instructor. */
const STDERR_KEEP = 4000;

/**
 * Vulkan drivers Dawn can use without a GPU, best first. SwiftShader (Chromium's
 * software Vulkan) is what this project tests with; Debian's chromium package ships
 * it, Google Chrome's .deb ships it under /opt/google/chrome. Mesa's lavapipe is last:
 * Dawn refuses Mesa 22.3's (Debian 12) for a missing shaderUniform*ArrayDynamicIndexing.
 */
export const VULKAN_ICDS = [
  '/usr/lib/chromium/vk_swiftshader_icd.json',
  '/opt/google/chrome/vk_swiftshader_icd.json',
  '/usr/share/vulkan/icd.d/lvp_icd.x86_64.json',
];

/** The environment of the grade command: a software Vulkan driver unless one is set. */
export function graderEnvironment(env: NodeJS.ProcessEnv): NodeJS.ProcessEnv {
  const out = { ...env };
  if (!out['VK_ICD_FILENAMES']) {
    const icd = VULKAN_ICDS.find((path) => existsSync(path));
    if (icd) out['VK_ICD_FILENAMES'] = icd;
  }
  // Chromium and Chrome ship the Vulkan loader next to SwiftShader; use it when the
  // system has none (as scripts/gpu-env.sh does).
  const icd = out['VK_ICD_FILENAMES'];
  if (icd && !hasSystemVulkanLoader()) {
    const folder = dirname(icd);
    if (existsSync(join(folder, 'libvulkan.so.1')))
      out['LD_LIBRARY_PATH'] = [folder, out['LD_LIBRARY_PATH']].filter(Boolean).join(':');
  }
  return out;
}

function hasSystemVulkanLoader(): boolean {
  try {
    return / libvulkan\.so\.1 /.test(execFileSync('ldconfig', ['-p'], { encoding: 'utf8' }));
  } catch {
    return false;
  }
}

/**
 * Every regular file under `folder`, relative to it; dot files, macOS archive junk and
 * symbolic links skipped (a link could point the grader at any file of the machine, or
 * loop).
 */
function listSubmission(folder: string): string[] {
  const out: string[] = [];
  const walk = (dir: string): void => {
    if (!existsSync(dir)) return;
    for (const name of readdirSync(dir).sort()) {
      if (name.startsWith('.') || name === '__MACOSX') continue;
      const path = join(dir, name);
      const stat = lstatSync(path);
      if (stat.isDirectory()) walk(path);
      else if (stat.isFile()) out.push(relative(folder, path));
    }
  };
  walk(folder);
  return out;
}

/** The one `.wgsl` file among `files`, or the student-facing reason there is not one. */
export function pickSubmission(
  files: readonly string[],
  exerciseId: string,
): { file: string } | { problem: string } {
  const wgsl = files.filter((f) => f.toLowerCase().endsWith('.wgsl'));
  const expected = `${exerciseId}.wgsl`;
  if (wgsl.length === 1) return { file: wgsl[0] as string };
  if (wgsl.length === 0) {
    const found = files.length
      ? ` It holds: ${files.slice(0, 10).join(', ')}${files.length > 10 ? ', …' : ''}.`
      : ' It is empty.';
    return {
      problem:
        `No .wgsl file was found in your submission.${found} Submit exactly one file, ${expected}: ` +
        'the exercise page’s “Download submission” button saves your code under that name.',
    };
  }
  return {
    problem:
      `Your submission holds ${wgsl.length} .wgsl files (${wgsl.join(', ')}); the grader cannot ` +
      `tell which one to grade. Submit exactly one file, ${expected}.`,
  };
}

interface GradeRun {
  /** The validated report's text, when the grade command produced one. */
  report?: string;
  /** Why there is no valid report (for the instructor). */
  failure?: string;
  /** The command ran past its wall-clock limit and was killed. */
  killed?: boolean;
  seconds: number;
}

function problemsOf(platform: Platform, text: string): string[] {
  let parsed: unknown;
  try {
    parsed = JSON.parse(text);
  } catch (error) {
    return [`not JSON: ${(error as Error).message}`];
  }
  return platform === 'gradescope'
    ? gradescopeProblems(parsed)
    : prairieLearnProblems(parsed, Buffer.byteLength(text));
}

/** Runs the grade command on `submission` in a child process, killed after the limit. */
export async function runGrader(
  platform: Platform,
  exerciseId: string,
  submission: string,
  timeLimitS: number,
  project = PROJECT,
): Promise<GradeRun> {
  const work = mkdtempSync(join(tmpdir(), 'scatterbook-grade-'));
  const out = join(work, 'report.json');
  const started = performance.now();
  const args = [
    '--import',
    'tsx',
    join(project, 'src/grading/cli.ts'),
    '--exercise',
    exerciseId,
    '--submission',
    submission,
    '--format',
    platform,
    '--out',
    out,
    '--time-limit',
    String(timeLimitS),
  ];
  let stderr = '';
  const code = await new Promise<number | string>((done) => {
    // detached: the child leads its own process group, so a kill reaches anything it started.
    const child = spawn(process.execPath, args, {
      cwd: project,
      env: graderEnvironment(process.env),
      stdio: ['ignore', 'ignore', 'pipe'],
      detached: true,
    });
    child.stderr.on('data', (chunk: Buffer) => {
      stderr = (stderr + chunk.toString('utf8')).slice(-STDERR_KEEP);
    });
    const timer = setTimeout(
      () => {
        try {
          if (child.pid) process.kill(-child.pid, 'SIGKILL');
        } catch {
          child.kill('SIGKILL');
        }
      },
      (timeLimitS + killGraceS(timeLimitS)) * 1000,
    );
    child.on('error', (error) => {
      clearTimeout(timer);
      done(`could not start (${error.message})`);
    });
    child.on('exit', (status, signal) => {
      clearTimeout(timer);
      done(signal ? `killed by ${signal}` : (status ?? -1));
    });
  });
  const seconds = (performance.now() - started) / 1000;
  process.stderr.write(stderr);
  try {
    const text = existsSync(out) ? readFileSync(out, 'utf8') : '';
    if (!text) {
      const killed = typeof code === 'string' && code.startsWith('killed');
      const why = killed
        ? `it did not finish within ${timeLimitS + killGraceS(timeLimitS)} s and was ${code}`
        : `it exited with ${String(code)} without a report`;
      return { failure: `the grade command failed: ${why}.\n${stderr.trim()}`, killed, seconds };
    }
    const problems = problemsOf(platform, text);
    if (problems.length)
      return {
        failure: `the grade command wrote an invalid ${platform} report: ${problems.join('; ')}`,
        seconds,
      };
    // A report was written: it stands even if the command then had to be killed.
    if (platform === 'gradescope') {
      const report = JSON.parse(text) as Record<string, unknown>;
      // Gradescope's execution_time: the wall clock of the whole grading, if the command left it out.
      if (report['execution_time'] === undefined) {
        report['execution_time'] = Math.round(seconds);
        return { report: `${JSON.stringify(report, null, 2)}\n`, seconds };
      }
    }
    return { report: text, seconds };
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
}

function fallbackReport(
  platform: Platform,
  outcome: GradeOutcome,
  exerciseId: string,
  title: string,
  seconds?: number,
): string {
  return renderReport(platform as ReportFormat, outcome, {
    exerciseId,
    title,
    ...(seconds !== undefined ? { executionTimeS: seconds } : {}),
  });
}

/** The `.wgsl` files PrairieLearn put in data.json's submitted `_files`, written to `folder`. */
function filesFromData(dataFile: string, folder: string): string[] {
  let data: unknown;
  try {
    data = JSON.parse(readFileSync(dataFile, 'utf8'));
  } catch {
    return [];
  }
  const files = (data as { submitted_answers?: { _files?: unknown } })?.submitted_answers?._files;
  if (!Array.isArray(files)) return [];
  const written: string[] = [];
  for (const entry of files as { name?: unknown; contents?: unknown }[]) {
    if (typeof entry?.name !== 'string' || typeof entry.contents !== 'string') continue;
    // Only a plain file name: data.json comes from the student's submission.
    const name = entry.name.replace(/^.*[\\/]/, '');
    if (!name || name.startsWith('.')) continue;
    writeFileSync(join(folder, name), Buffer.from(entry.contents, 'base64'));
    written.push(name);
  }
  return written;
}

/** Grades one submission for `platform` and writes results.json; returns its path. */
export async function gradeForPlatform(
  platform: Platform,
  exerciseId: string,
  timeLimitS: number,
  env: NodeJS.ProcessEnv = process.env,
  project = PROJECT,
): Promise<string> {
  const root =
    platform === 'gradescope'
      ? resolve(env['AUTOGRADER_ROOT'] || '/autograder')
      : resolve(env['GRADE_ROOT'] || '/grade');
  const resultsDir = join(root, 'results');
  mkdirSync(resultsDir, { recursive: true });
  const results = join(resultsDir, 'results.json');
  let title = exerciseId;
  let text: string;
  try {
    if (!EXERCISE_IDS.includes(exerciseId))
      throw new Error(`the kit names exercise "${exerciseId}", which this grader does not have`);
    title = (await loadExercise(exerciseId)).title;
    let folder = join(root, platform === 'gradescope' ? 'submission' : 'student');
    let files = listSubmission(folder);
    let scratch: string | null = null;
    if (platform === 'prairielearn' && !files.some((f) => f.toLowerCase().endsWith('.wgsl'))) {
      scratch = mkdtempSync(join(tmpdir(), 'scatterbook-student-'));
      const fromData = filesFromData(join(root, 'data', 'data.json'), scratch);
      if (fromData.length) {
        folder = scratch;
        files = fromData;
      }
    }
    const picked = pickSubmission(files, exerciseId);
    if ('problem' in picked) {
      text = fallbackReport(
        platform,
        { status: 'rejected', message: picked.problem },
        exerciseId,
        title,
      );
    } else {
      const run = await runGrader(
        platform,
        exerciseId,
        join(folder, picked.file),
        timeLimitS,
        project,
      );
      if (run.report !== undefined) {
        text = run.report;
      } else {
        process.stderr.write(`driver: ${run.failure ?? 'unknown failure'}\n`);
        // Both are the grader's failures, reported as such (to be regraded), never as a 0.
        text = fallbackReport(
          platform,
          run.killed
            ? {
                status: 'timeout',
                message: `grading did not finish within its limit of ${timeLimitS} s and was stopped.`,
              }
            : {
                status: 'internal-error',
                message: 'the grader stopped without a report (the details are in the grader log).',
              },
          exerciseId,
          title,
          run.seconds,
        );
      }
    }
    if (scratch) rmSync(scratch, { recursive: true, force: true });
  } catch (error) {
    process.stderr.write(`driver: ${(error as Error).stack ?? String(error)}\n`);
    text = fallbackReport(
      platform,
      {
        status: 'internal-error',
        message: 'the grader failed (the details are in the grader log).',
      },
      exerciseId,
      title,
    );
  }
  writeFileSync(results, text);
  return results;
}

async function main(argv: string[]): Promise<number> {
  const platform = argv[0];
  if (platform !== 'gradescope' && platform !== 'prairielearn') {
    process.stderr.write(
      'usage: driver.ts gradescope|prairielearn --exercise ID [--time-limit S]\n',
    );
    return 2;
  }
  const { values } = parseArgs({
    args: argv.slice(1),
    options: { exercise: { type: 'string' }, 'time-limit': { type: 'string' } },
    strict: true,
  });
  const limit = Number(values['time-limit'] ?? DEFAULT_TIME_LIMIT_S);
  const results = await gradeForPlatform(
    platform,
    values.exercise ?? '',
    Number.isFinite(limit) && limit > 0 ? limit : DEFAULT_TIME_LIMIT_S,
  );
  process.stdout.write(`results written to ${results}\n`);
  return 0;
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  main(process.argv.slice(2)).then(
    (code) => process.exit(code),
    (error: unknown) => {
      process.stderr.write(`driver: ${(error as Error).stack ?? String(error)}\n`);
      process.exit(2);
    },
  );
}
