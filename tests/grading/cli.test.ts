// The grade command end to end, as an instructor (or a kit) runs it: hostile and
// endless submissions write a report and the process exits; the wall-clock limit
// writes a grader-side 'timeout' report; an oversized file is refused from its size.
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { MAX_SUBMISSION_BYTES } from '../../src/grading/instrument.ts';

const ROOT = resolve(import.meta.dirname, '../..');
const work = mkdtempSync(join(tmpdir(), 'grade-cli-'));
afterAll(() => rmSync(work, { recursive: true, force: true }));

interface Run {
  code: number | null;
  signal: NodeJS.Signals | null;
  stdout: string;
  stderr: string;
}

/** Runs `grade` with `args`; resolves when the process has exited. */
function grade(args: string[]): Promise<Run> {
  return new Promise((done) => {
    const child = spawn(process.execPath, ['--import', 'tsx', 'src/grading/cli.ts', ...args], {
      cwd: ROOT,
      env: process.env,
      stdio: ['ignore', 'pipe', 'pipe'],
    });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (chunk: Buffer) => (stdout += chunk.toString('utf8')));
    child.stderr.on('data', (chunk: Buffer) => (stderr += chunk.toString('utf8')));
    child.on('exit', (code, signal) => done({ code, signal, stdout, stderr }));
  });
}

describe('grade (command line)', () => {
  it('writes a report for an endless loop hidden behind a CR-ended comment, and exits', async () => {
    const out = join(work, 'endless.json');
    const run = await grade([
      '--exercise',
      'beer-law',
      '--submission',
      'exercises/beer-law/wrong/hostile-cr-endless.wgsl',
      '--format',
      'gradescope',
      '--out',
      out,
    ]);
    expect(run.code, run.stderr).toBe(0);
    const report = JSON.parse(readFileSync(out, 'utf8')) as {
      score: number;
      execution_time: number;
      tests: { name: string; visibility: string }[];
    };
    expect(report.score).toBe(0);
    expect(report.tests[0]?.name).toBe('Your loops end within their budget');
    expect(report.execution_time).toBeGreaterThanOrEqual(0);
  }, 120_000);

  it('refuses an extra binding with a PrairieLearn report on stdout, and exits', async () => {
    const run = await grade([
      '--exercise',
      'beer-law',
      '--submission',
      'exercises/beer-law/wrong/hostile-extra-binding.wgsl',
      '--format',
      'prairielearn',
    ]);
    expect(run.code, run.stderr).toBe(0);
    const report = JSON.parse(run.stdout) as { gradable: boolean; message: string };
    expect(report.gradable).toBe(false);
    expect(report.message).toContain('line 2, column 1: `@group`');
  }, 120_000);

  it('stops at the wall-clock limit with a grader-side timeout report', async () => {
    const out = join(work, 'timeout.json');
    const run = await grade([
      '--exercise',
      'delta-tracking',
      '--submission',
      'exercises/delta-tracking/starter.wgsl',
      '--format',
      'gradescope',
      '--out',
      out,
      '--time-limit',
      '0.2',
    ]);
    expect(run.code, run.stderr).toBe(0);
    const report = JSON.parse(readFileSync(out, 'utf8')) as Record<string, unknown>;
    expect(report).not.toHaveProperty('score');
    const tests = report['tests'] as { name: string; output: string }[];
    expect(tests[0]?.name).toBe('Grading failed — will be regraded');
    expect(tests[0]?.output).toContain('wall-clock limit of 0.2 s');
    expect(report['extra_data']).toEqual({ grader_failure: 'timeout' });
  }, 120_000);

  it('refuses a file over the size cap from its size alone', async () => {
    const big = join(work, 'big.wgsl');
    writeFileSync(
      big,
      `fn transmittance(sigmaT: f32, d: f32) -> f32 { return 1.0; }\n${'//'.repeat(MAX_SUBMISSION_BYTES)}`,
    );
    const run = await grade(['--exercise', 'beer-law', '--submission', big, '--format', 'json']);
    expect(run.code, run.stderr).toBe(0);
    const report = JSON.parse(run.stdout) as { status: string; message: string };
    expect(report.status).toBe('rejected');
    expect(report.message).toContain(`at most ${MAX_SUBMISSION_BYTES} bytes`);
  }, 120_000);

  it('exits 2 without a report for a bad --time-limit', async () => {
    const run = await grade([
      '--exercise',
      'beer-law',
      '--submission',
      'exercises/beer-law/starter.wgsl',
      '--time-limit',
      '-3',
    ]);
    expect(run.code).toBe(2);
    expect(run.stdout).toBe('');
    expect(run.stderr).toContain('--time-limit');
  }, 120_000);
});
