// The grade command's supervisor with stand-in workers: every way a worker can end —
// an answer, a crash without one, a hang, an answer and then a refusal to exit — gives
// an outcome, and the worker is gone afterwards.
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { gradeUnderLimit } from '../../src/grading/supervise.ts';
import { MAX_SUBMISSION_BYTES } from '../../src/grading/instrument.ts';

const work = mkdtempSync(join(tmpdir(), 'grade-supervise-'));
afterAll(() => rmSync(work, { recursive: true, force: true }));
const submission = join(work, 'a.wgsl');
writeFileSync(submission, 'fn f() {}\n');

/** A stand-in worker module with `body` run on the job message. */
function worker(name: string, body: string): string {
  const file = join(work, `${name}.mjs`);
  writeFileSync(
    file,
    `import { writeFileSync } from 'node:fs';\nprocess.once('message', (job) => {\n${body}\n});\n`,
  );
  return file;
}

function alive(pid: number): boolean {
  try {
    process.kill(pid, 0);
    return true;
  } catch {
    return false;
  }
}

const job = { exercise: 'beer-law', submission };

describe('gradeUnderLimit', () => {
  it('passes the worker’s outcome through', async () => {
    const answering = worker(
      'answer',
      "process.send({ outcome: { status: 'loop-budget', message: job.exercise }, title: 'T' }, () => process.exit(0));",
    );
    const result = await gradeUnderLimit(job, 30, 'fallback', answering);
    expect(result.outcome).toEqual({ status: 'loop-budget', message: 'beer-law' });
    expect(result.title).toBe('T');
    expect(result.seconds).toBeGreaterThanOrEqual(0);
  });

  it('reports a worker that dies without an answer as internal-error', async () => {
    const crashing = worker('crash', 'process.exit(7);');
    const result = await gradeUnderLimit(job, 30, 'fallback', crashing);
    expect(result.outcome.status).toBe('internal-error');
    if (result.outcome.status === 'internal-error')
      expect(result.outcome.message).toContain('exit status 7');
    expect(result.title).toBe('fallback');
  });

  it('kills a worker that never answers at the limit and reports a timeout', async () => {
    const hanging = worker(
      'hang',
      'writeFileSync(process.env.PID_FILE, String(process.pid)); setInterval(() => {}, 1000);',
    );
    const pidFile = join(work, 'hang.pid');
    process.env['PID_FILE'] = pidFile;
    const result = await gradeUnderLimit(job, 1.5, 'fallback', hanging);
    expect(result.outcome.status).toBe('timeout');
    if (result.outcome.status === 'timeout')
      expect(result.outcome.message).toContain('wall-clock limit of 1.5 s');
    const pid = Number(readFileSync(pidFile, 'utf8'));
    await new Promise((r) => setTimeout(r, 200));
    expect(alive(pid)).toBe(false);
  });

  it('keeps an answer from a worker that then does not exit, and kills it', async () => {
    const lingering = worker(
      'linger',
      "writeFileSync(process.env.PID_FILE, String(process.pid)); process.send({ outcome: { status: 'rejected', message: 'm' }, title: 'T' }); setInterval(() => {}, 1000);",
    );
    const pidFile = join(work, 'linger.pid');
    process.env['PID_FILE'] = pidFile;
    const result = await gradeUnderLimit(job, 30, 'fallback', lingering);
    expect(result.outcome.status).toBe('rejected');
    await new Promise((r) => setTimeout(r, 200));
    expect(alive(Number(readFileSync(pidFile, 'utf8')))).toBe(false);
  });

  it('refuses a file over the size cap without starting a worker', async () => {
    const big = join(work, 'big.wgsl');
    writeFileSync(big, ' '.repeat(MAX_SUBMISSION_BYTES + 1));
    const never = worker('never', 'process.exit(9);');
    const result = await gradeUnderLimit({ ...job, submission: big }, 30, 'fallback', never);
    expect(result.outcome.status).toBe('rejected');
  });
});
