// The kits end to end, as the platforms run them: the Gradescope kit unpacked as
// Gradescope unpacks it ($AUTOGRADER_ROOT/source, run_autograder copied to the root)
// and the PrairieLearn entrypoint against a temporary /grade ($GRADE_ROOT). Instead of
// `npm ci` on a fresh machine, the kit's project copy gets this checkout's
// node_modules (a symlink), so the copied sources themselves are what runs; one case
// points $SCATTERBOOK_PROJECT at this checkout instead. Correct, wrong and hostile
// submissions, none and two files, data.json-only PrairieLearn submissions, a grader
// that crashes, hangs or writes a broken report, and no Node at all: every run must
// leave a results.json that passes the platform's field list (validate.ts).
import { spawnSync } from 'node:child_process';
import {
  chmodSync,
  cpSync,
  existsSync,
  mkdirSync,
  mkdtempSync,
  readFileSync,
  rmSync,
  symlinkSync,
  writeFileSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { gradeForPlatform } from '../../src/grading/kit/driver.ts';
import { runKit } from '../../src/grading/kit/index.ts';
import { PROJECT_ROOT } from '../../src/grading/kit/project.ts';
import { gradescopeProblems, prairieLearnProblems } from '../../src/grading/kit/validate.ts';

const CORRECT = `fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return exp(-max(sigmaT * d, 0.0));
}
`;
const WRONG = readFileSync(join(PROJECT_ROOT, 'exercises/beer-law/wrong/no-clamp.wgsl'), 'utf8');
/** A storage binding of its own: the harness's pipeline layout has no room for it. */
const HOSTILE_BINDING = `@group(0) @binding(2) var<storage, read_write> leak: array<u32>;
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  leak[0] = 1u;
  return exp(-max(sigmaT * d, 0.0));
}
`;
/** An endless loop behind a comment that a carriage return ends. */
const HOSTILE_LOOP =
  'fn transmittance(sigmaT: f32, d: f32) -> f32 {\n' +
  '  var x = 0.0;\n' +
  '  // spin\r  loop { x = x + 1.0; }\n' +
  '  return x;\n' +
  '}\n';
const TIME_LIMIT_S = 20;

type Json = Record<string, unknown> & { tests?: Record<string, unknown>[] };

let work: string;
let gsKit: string;
let plProject: string;

function fresh(name: string): string {
  const dir = join(work, name);
  rmSync(dir, { recursive: true, force: true });
  mkdirSync(dir, { recursive: true });
  return dir;
}

function run(
  script: string,
  env: Record<string, string>,
  args: string[] = [],
): { status: number | null; seconds: number; log: string } {
  const started = performance.now();
  const result = spawnSync('bash', [script, ...args], {
    env: { ...process.env, ...env },
    encoding: 'utf8',
    timeout: 180_000,
  });
  return {
    status: result.status,
    seconds: (performance.now() - started) / 1000,
    log: `${result.stdout}\n${result.stderr}`,
  };
}

function readResults(root: string, platform: 'gradescope' | 'prairielearn'): Json {
  const text = readFileSync(join(root, 'results/results.json'), 'utf8');
  const parsed = JSON.parse(text) as Json;
  const problems =
    platform === 'gradescope'
      ? gradescopeProblems(parsed)
      : prairieLearnProblems(parsed, Buffer.byteLength(text));
  expect(problems, text).toEqual([]);
  return parsed;
}

/** A Gradescope machine: the kit unpacked in source/, run_autograder at the root. */
function gradescopeRoot(name: string, files: Record<string, string>): string {
  const root = fresh(name);
  cpSync(gsKit, join(root, 'source'), { recursive: true });
  symlinkSync(join(PROJECT_ROOT, 'node_modules'), join(root, 'source/scatterbook/node_modules'));
  cpSync(join(root, 'source/run_autograder'), join(root, 'run_autograder'));
  mkdirSync(join(root, 'submission'), { recursive: true });
  for (const [path, content] of Object.entries(files)) {
    mkdirSync(join(root, 'submission', path, '..'), { recursive: true });
    writeFileSync(join(root, 'submission', path), content);
  }
  return root;
}

function gradescope(files: Record<string, string>, env: Record<string, string> = {}) {
  const root = gradescopeRoot(`gs-${Math.random().toString(36).slice(2)}`, files);
  const result = run(join(root, 'run_autograder'), { AUTOGRADER_ROOT: root, ...env });
  expect(result.status, result.log).toBe(0);
  return { results: readResults(root, 'gradescope'), ...result };
}

function prairieLearn(
  student: Record<string, string>,
  data: unknown = { params: {}, submitted_answers: {} },
  exercise = 'beer-law',
) {
  const root = fresh(`pl-${Math.random().toString(36).slice(2)}`);
  mkdirSync(join(root, 'student'), { recursive: true });
  mkdirSync(join(root, 'data'), { recursive: true });
  writeFileSync(join(root, 'data/data.json'), JSON.stringify(data));
  for (const [path, content] of Object.entries(student))
    writeFileSync(join(root, 'student', path), content);
  // As in the image: the sources from serverFilesCourse, the packages installed apart.
  const result = run(
    join(plProject, 'entrypoint.sh'),
    { GRADE_ROOT: root, SCATTERBOOK_NODE_MODULES: join(PROJECT_ROOT, 'node_modules') },
    [exercise],
  );
  expect(
    existsSync(join(plProject, 'node_modules')),
    'entrypoint wrote into serverFilesCourse',
  ).toBe(false);
  expect(result.status, result.log).toBe(0);
  return { results: readResults(root, 'prairielearn'), ...result };
}

function sumOf(tests: Record<string, unknown>[] | undefined, key: string): number {
  return (tests ?? []).reduce((sum, t) => sum + Number(t[key] ?? 0), 0);
}

beforeAll(async () => {
  work = mkdtempSync(join(tmpdir(), 'kit-run-'));
  const limit = ['--time-limit', String(TIME_LIMIT_S)];
  expect(
    await runKit(['gradescope', '--exercise', 'beer-law', '--out', join(work, 'gs-kit'), ...limit]),
  ).toBe(0);
  gsKit = join(work, 'gs-kit/autograder');
  expect(await runKit(['prairielearn', '--out', join(work, 'pl-kit'), ...limit])).toBe(0);
  plProject = join(work, 'pl-kit/serverFilesCourse/scatterbook');
}, 60_000);

afterAll(() => rmSync(work, { recursive: true, force: true }));

describe('Gradescope run_autograder', () => {
  it('gives a correct submission full marks, hidden checks after publication', () => {
    const { results } = gradescope({ 'beer-law.wgsl': CORRECT });
    const tests = results.tests ?? [];
    expect(results.score).toBe(sumOf(tests, 'max_score'));
    expect(Number(results.score)).toBeGreaterThan(0);
    expect(tests.every((t) => t['status'] === 'passed')).toBe(true);
    expect(tests.some((t) => t['visibility'] === 'after_published')).toBe(true);
    expect(results.execution_time).toEqual(expect.any(Number));
  }, 90_000);

  it('grades a wrong submission, under any file name, below full marks', () => {
    const { results } = gradescope({ 'my solution.wgsl': WRONG, 'notes.txt': 'hi' });
    const tests = results.tests ?? [];
    expect(Number(results.score)).toBeGreaterThan(0);
    expect(Number(results.score)).toBeLessThan(sumOf(tests, 'max_score'));
    expect(tests.some((t) => t['status'] === 'failed')).toBe(true);
  }, 90_000);

  it('ends hostile submissions in a report with no marks, within the time limit', () => {
    for (const source of [HOSTILE_BINDING, HOSTILE_LOOP]) {
      const { results, seconds, log } = gradescope({ 'beer-law.wgsl': source });
      // The student's outcome (refused, loop budget), not a grader failure: a score of 0.
      expect(results.score, log).toBe(0);
      expect(sumOf(results.tests, 'score')).toBe(0);
      expect((results.tests ?? []).some((t) => t['visibility'] === 'visible')).toBe(true);
      expect(seconds).toBeLessThan(TIME_LIMIT_S + 20);
    }
  }, 180_000);

  it('refuses none or several .wgsl files with a visible reason', () => {
    const none = gradescope({ 'solution.txt': CORRECT }).results;
    expect(none.score).toBe(0);
    expect(JSON.stringify(none.tests)).toMatch(/No \.wgsl file.*solution\.txt.*beer-law\.wgsl/);
    const two = gradescope({ 'a.wgsl': CORRECT, 'sub/b.wgsl': CORRECT }).results;
    expect(two.score).toBe(0);
    expect(JSON.stringify(two.tests)).toMatch(/2 \.wgsl files/);
    const empty = gradescope({}).results;
    expect(JSON.stringify(empty.tests)).toMatch(/empty/);
    // A symbolic link is not a submitted file: it could point at any file of the machine.
    const root = gradescopeRoot('gs-symlink', {});
    symlinkSync('/etc/hostname', join(root, 'submission/beer-law.wgsl'));
    const linked = run(join(root, 'run_autograder'), { AUTOGRADER_ROOT: root });
    expect(linked.status).toBe(0);
    expect(JSON.stringify(readResults(root, 'gradescope').tests)).toMatch(/No \.wgsl file/);
  }, 60_000);

  it('honours SCATTERBOOK_PROJECT (this checkout instead of the kit’s copy)', () => {
    const { results } = gradescope(
      { 'beer-law.wgsl': CORRECT },
      { SCATTERBOOK_PROJECT: PROJECT_ROOT },
    );
    expect(results.score).toBe(sumOf(results.tests, 'max_score'));
  }, 90_000);

  it('still writes a grader-failure report when Node cannot run at all', () => {
    const bin = fresh('no-node-bin');
    writeFileSync(join(bin, 'node'), '#!/bin/sh\nexit 127\n');
    chmodSync(join(bin, 'node'), 0o755);
    const { results } = gradescope(
      { 'beer-law.wgsl': CORRECT },
      { PATH: `${bin}:${process.env['PATH'] ?? ''}` },
    );
    expect(results.score).toBeUndefined();
    expect(results.tests?.[0]?.['name']).toBe('Grading failed — will be regraded');
    expect(results.tests?.[0]?.['visibility']).toBe('visible');
  }, 30_000);
});

describe('PrairieLearn entrypoint', () => {
  it('scores a correct submission 1 and a wrong one between 0 and 1', () => {
    const correct = prairieLearn({ 'beer-law.wgsl': CORRECT }).results;
    expect(correct).toMatchObject({ gradable: true, score: 1 });
    const wrong = prairieLearn({ 'beer-law.wgsl': WRONG }).results;
    expect(wrong.gradable).toBe(true);
    expect(Number(wrong.score)).toBeGreaterThan(0);
    expect(Number(wrong.score)).toBeLessThan(1);
    // Hidden checks: name and pass/fail only.
    const hidden = (wrong.tests ?? []).filter((t) => String(t['name']).endsWith('(hidden)'));
    expect(hidden.length).toBeGreaterThan(0);
    for (const t of hidden) expect(t['output']).toBeUndefined();
  }, 90_000);

  it('reads the file from data.json when /grade/student is empty', () => {
    const data = {
      params: {},
      submitted_answers: {
        _files: [{ name: 'beer-law.wgsl', contents: Buffer.from(CORRECT).toString('base64') }],
      },
    };
    expect(prairieLearn({}, data).results).toMatchObject({ gradable: true, score: 1 });
  }, 90_000);

  it('reports hostile, missing and misconfigured submissions as not gradable, with the reason', () => {
    const hostile = prairieLearn({ 'beer-law.wgsl': HOSTILE_BINDING }).results;
    expect(hostile.score ?? 0).toBe(0);
    expect(hostile.gradable).toBe(false);
    expect(String(hostile.message)).toMatch(/refused.*@binding/s);
    const none = prairieLearn({}).results;
    expect(none).toMatchObject({ gradable: false });
    expect(String(none.message)).toMatch(/No \.wgsl file/);
    const unknown = prairieLearn({ 'x.wgsl': CORRECT }, undefined, 'no-such-exercise').results;
    expect(unknown).toMatchObject({ gradable: false });
    expect(String(unknown.message)).toMatch(/regraded/);
  }, 120_000);
});

describe('driver against a broken grader', () => {
  /** A project whose grade command misbehaves as `body` says. */
  function brokenProject(name: string, body: string): string {
    const root = fresh(name);
    mkdirSync(join(root, 'src/grading'), { recursive: true });
    symlinkSync(join(PROJECT_ROOT, 'node_modules'), join(root, 'node_modules'));
    writeFileSync(
      join(root, 'src/grading/cli.ts'),
      `const out = process.argv[process.argv.indexOf('--out') + 1] ?? '';\n${body}\n`,
    );
    return root;
  }

  for (const [name, body] of [
    ['crashes', "throw new Error('boom');"],
    ['hangs', 'setInterval(() => undefined, 1000);'],
    [
      'writes-invalid',
      'import(\'node:fs\').then((fs) => fs.writeFileSync(out, \'{"score": "ten"}\'));',
    ],
  ] as const) {
    it(`reports a grader that ${name} as a grader failure, not a score`, async () => {
      const project = brokenProject(name, body);
      for (const platform of ['gradescope', 'prairielearn'] as const) {
        const root = fresh(`${name}-${platform}`);
        const folder = join(root, platform === 'gradescope' ? 'submission' : 'student');
        mkdirSync(folder, { recursive: true });
        writeFileSync(join(folder, 'beer-law.wgsl'), CORRECT);
        const started = performance.now();
        const env = platform === 'gradescope' ? { AUTOGRADER_ROOT: root } : { GRADE_ROOT: root };
        const path = await gradeForPlatform(platform, 'beer-law', 2, env, project);
        expect((performance.now() - started) / 1000).toBeLessThan(15);
        expect(existsSync(path)).toBe(true);
        const results = readResults(root, platform);
        if (platform === 'gradescope') {
          expect(results.score).toBeUndefined();
          expect(results.tests?.[0]?.['name']).toBe('Grading failed — will be regraded');
          expect(results['extra_data']).toEqual({
            grader_failure: name === 'hangs' ? 'timeout' : 'internal-error',
          });
        } else {
          expect(results.gradable).toBe(false);
          expect(String(results.message)).toMatch(/regraded/);
        }
      }
    }, 60_000);
  }
});
