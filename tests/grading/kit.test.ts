// The deployment kits' pieces, without running a grader: the store-only zip (read
// back by an independent reader written here, and by `unzip -t` where installed),
// the project copy and its pruned lockfile, the PrairieLearn questions (uuid, info.json,
// question.html, starter), the shell scripts' syntax, the choice of the submitted
// file, and the results.json validators on reports that break each rule.
import { execFileSync, spawnSync } from 'node:child_process';
import {
  existsSync,
  mkdtempSync,
  readFileSync,
  readdirSync,
  rmSync,
  statSync,
  writeFileSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { inflateRawSync } from 'node:zlib';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { EXERCISE_IDS, loadExercise } from '../../exercises/index.ts';
import { VULKAN_ICDS, graderEnvironment, pickSubmission } from '../../src/grading/kit/driver.ts';
import { projectCopy, sourceClosure, PROJECT_ROOT } from '../../src/grading/kit/project.ts';
import { questionUuid, statementHtml } from '../../src/grading/kit/prairielearn.ts';
import { gradescopeProblems, prairieLearnProblems } from '../../src/grading/kit/validate.ts';
import { crc32, createZip } from '../../src/grading/kit/zip.ts';
import { runKit } from '../../src/grading/kit/index.ts';

/** Reads a ZIP by its central directory, as unzip does; checks every CRC. */
function readZip(bytes: Uint8Array): Map<string, { data: Buffer; mode: number }> {
  const buf = Buffer.from(bytes);
  const eocd = buf.lastIndexOf(Buffer.from([0x50, 0x4b, 0x05, 0x06]));
  if (eocd < 0) throw new Error('no end of central directory');
  const count = buf.readUInt16LE(eocd + 10);
  let at = buf.readUInt32LE(eocd + 16);
  const out = new Map<string, { data: Buffer; mode: number }>();
  for (let i = 0; i < count; i++) {
    if (buf.readUInt32LE(at) !== 0x02014b50) throw new Error(`bad central header ${i}`);
    const method = buf.readUInt16LE(at + 10);
    const crc = buf.readUInt32LE(at + 16);
    const size = buf.readUInt32LE(at + 20);
    const nameLength = buf.readUInt16LE(at + 28);
    const extra = buf.readUInt16LE(at + 30);
    const comment = buf.readUInt16LE(at + 32);
    const mode = buf.readUInt32LE(at + 38) >>> 16;
    const local = buf.readUInt32LE(at + 42);
    const name = buf.toString('utf8', at + 46, at + 46 + nameLength);
    if (buf.readUInt32LE(local) !== 0x04034b50) throw new Error(`bad local header ${name}`);
    const start = local + 30 + buf.readUInt16LE(local + 26) + buf.readUInt16LE(local + 28);
    const raw = buf.subarray(start, start + buf.readUInt32LE(local + 18));
    const data = method === 8 ? inflateRawSync(raw) : Buffer.from(raw);
    if (data.length !== size || crc32(data) !== crc) throw new Error(`bad data for ${name}`);
    out.set(name, { data, mode: mode & 0o777 });
    at += 46 + nameLength + extra + comment;
  }
  return out;
}

function listTree(root: string, dir = ''): string[] {
  return readdirSync(join(root, dir)).flatMap((name) => {
    const path = dir ? `${dir}/${name}` : name;
    return statSync(join(root, path)).isDirectory() ? listTree(root, path) : [path];
  });
}

describe('store-only zip', () => {
  it('CRC-32 matches the standard check value', () => {
    expect(crc32(new TextEncoder().encode('123456789'))).toBe(0xcbf43926);
  });

  it('round-trips names, bytes and modes, and refuses unsafe names', () => {
    const entries = [
      {
        name: 'run_autograder',
        data: new TextEncoder().encode('#!/bin/sh\necho ok\n'),
        mode: 0o755,
      },
      { name: 'a/b/ünïcode.txt', data: new Uint8Array([0, 1, 2, 255]) },
      { name: 'empty', data: new Uint8Array() },
    ];
    const back = readZip(createZip(entries));
    expect([...back.keys()]).toEqual(entries.map((e) => e.name));
    expect(back.get('run_autograder')?.mode).toBe(0o755);
    expect(back.get('a/b/ünïcode.txt')?.mode).toBe(0o644);
    expect([...(back.get('a/b/ünïcode.txt')?.data ?? [])]).toEqual([0, 1, 2, 255]);
    expect(() => createZip([{ name: '../x', data: new Uint8Array() }])).toThrow(/invalid/);
    expect(() => createZip([{ name: '/x', data: new Uint8Array() }])).toThrow(/invalid/);
    expect(() =>
      createZip([
        { name: 'x', data: new Uint8Array() },
        { name: 'x', data: new Uint8Array() },
      ]),
    ).toThrow(/duplicate/);
  });
});

describe('project copy', () => {
  it('follows imports (not comments or strings) and keeps type-only packages out', () => {
    const closure = sourceClosure(PROJECT_ROOT, ['src/grading/cli.ts']);
    expect(closure.files).toContain('src/grading/grade.ts');
    expect(closure.files).toContain('exercises/index.ts');
    expect(closure.packages).toContain('webgpu');
    expect(closure.packages).not.toContain('@webgpu/types');
    expect(closure.files).not.toContain('src/grading/kit/index.ts');
    expect(closure.files.some((f) => f.startsWith('src/widgets/'))).toBe(false);
  });

  it('follows modules named in strings and loaded at run time (a child process’s script)', () => {
    const root = mkdtempSync(join(tmpdir(), 'kit-closure-'));
    try {
      writeFileSync(
        join(root, 'main.ts'),
        "// import { x } from './commented.ts';\n" +
          "import { a } from './a.ts';\n" +
          "const worker = join(dirname(fileURLToPath(import.meta.url)), 'worker.ts');\n" +
          "const missing = 'not-here.ts';\n",
      );
      writeFileSync(
        join(root, 'a.ts'),
        "import type { T } from 'types-only';\nimport 'side-effect';\n",
      );
      writeFileSync(join(root, 'worker.ts'), "import { b } from 'real-package/sub';\n");
      writeFileSync(join(root, 'commented.ts'), '');
      expect(sourceClosure(root, ['main.ts'])).toEqual({
        files: ['a.ts', 'main.ts', 'worker.ts'],
        packages: ['real-package', 'side-effect'],
      });
    } finally {
      rmSync(root, { recursive: true, force: true });
    }
  });

  it('installs exactly the checkout’s versions, with a lockfile closed under dependencies', () => {
    const copy = projectCopy();
    const paths = copy.files.map((f) => f.path);
    for (const must of ['src/grading/cli.ts', 'src/grading/kit/driver.ts', 'package.json'])
      expect(paths).toContain(must);
    for (const id of EXERCISE_IDS) {
      expect(paths).toContain(`exercises/${id}/hidden.ts`);
      expect(paths).toContain(`exercises/${id}/wrong/expected.json`);
    }
    expect(paths.some((p) => p.startsWith('shaders/') && p.endsWith('.wesl'))).toBe(true);
    expect(Object.keys(copy.dependencies)).toContain('tsx');
    for (const [name, version] of Object.entries(copy.dependencies)) {
      const installed = JSON.parse(
        readFileSync(join(PROJECT_ROOT, 'node_modules', name, 'package.json'), 'utf8'),
      ) as { version: string };
      expect(version, name).toBe(installed.version);
    }
    const file = (path: string) =>
      JSON.parse(new TextDecoder().decode(copy.files.find((f) => f.path === path)?.data)) as {
        dependencies?: Record<string, string>;
        packages: Record<
          string,
          { dependencies?: Record<string, string>; dev?: boolean; version?: string }
        >;
      };
    const pkg = file('package.json');
    const lock = file('package-lock.json');
    expect(lock.packages['']?.dependencies).toEqual(pkg.dependencies);
    for (const [key, entry] of Object.entries(lock.packages)) {
      expect(entry.dev, key).toBeUndefined();
      for (const dep of Object.keys(entry.dependencies ?? {})) {
        // Node's lookup: nested node_modules first, then each ancestor's.
        const parts = key.split('/node_modules/');
        const found = parts
          .map(
            (_, i) =>
              `${parts.slice(0, parts.length - i).join('/node_modules/')}/node_modules/${dep}`,
          )
          .concat(`node_modules/${dep}`)
          .some((candidate) => lock.packages[candidate.replace(/^\/node_modules/, 'node_modules')]);
        expect(found, `${key} → ${dep}`).toBe(true);
      }
    }
  });
});

describe('grader environment', () => {
  it('keeps a chosen Vulkan driver, else picks the first software driver installed', () => {
    expect(graderEnvironment({ VK_ICD_FILENAMES: '/x/icd.json' })['VK_ICD_FILENAMES']).toBe(
      '/x/icd.json',
    );
    const installed = VULKAN_ICDS.find((path) => existsSync(path));
    expect(graderEnvironment({})['VK_ICD_FILENAMES']).toBe(installed);
    // SwiftShader first: Dawn refuses the lavapipe of Mesa 22.3.
    expect(VULKAN_ICDS[0]).toMatch(/swiftshader/);
    expect(VULKAN_ICDS.at(-1)).toMatch(/lvp_icd/);
  });
});

describe('submission file choice', () => {
  it('takes the one .wgsl file, whatever its name', () => {
    expect(pickSubmission(['notes.txt', 'sub/solution.WGSL'], 'beer-law')).toEqual({
      file: 'sub/solution.WGSL',
    });
  });
  it('explains none and several, naming the expected file', () => {
    const none = pickSubmission(['a.py'], 'beer-law');
    expect('problem' in none && none.problem).toMatch(/No \.wgsl file.*a\.py.*beer-law\.wgsl/);
    const empty = pickSubmission([], 'beer-law');
    expect('problem' in empty && empty.problem).toMatch(/empty/);
    const two = pickSubmission(['a.wgsl', 'b.wgsl'], 'beer-law');
    expect('problem' in two && two.problem).toMatch(/2 \.wgsl files \(a\.wgsl, b\.wgsl\)/);
  });
});

describe('results.json validators', () => {
  const test = {
    name: 'T',
    score: 1,
    max_score: 2,
    status: 'failed',
    visibility: 'visible',
    output: '',
  };
  it('accept the documented Gradescope fields and flag each broken rule', () => {
    expect(
      gradescopeProblems({
        score: 1,
        execution_time: 3,
        output: 'x',
        stdout_visibility: 'hidden',
        tests: [test],
      }),
    ).toEqual([]);
    expect(gradescopeProblems({ tests: [{ ...test }] })).toEqual([]);
    expect(gradescopeProblems({ output: 'x' })).toEqual(['no top-level score and no tests to sum']);
    expect(gradescopeProblems({ score: -1, tests: [test] })).toContain(
      'score must be a finite number ≥ 0',
    );
    expect(gradescopeProblems({ score: 5, tests: [test] })).toContain(
      "score 5 exceeds the tests' total 2",
    );
    expect(gradescopeProblems({ score: 1, tests: [{ ...test, score: 3 }] })).toContain(
      'tests[0].score 3 exceeds max_score 2',
    );
    expect(gradescopeProblems({ score: 1, tests: [{ ...test, visibility: 'secret' }] })[0]).toMatch(
      /visibility/,
    );
    expect(gradescopeProblems({ score: 1, stdout_visibility: 'never', tests: [test] })[0]).toMatch(
      /stdout_visibility/,
    );
    expect(gradescopeProblems({ score: 1, tests: [{ ...test, status: 'ok' }] })[0]).toMatch(
      /status/,
    );
    expect(gradescopeProblems({ score: 1, tests: [{ ...test, maxScore: 2 }] })[0]).toMatch(
      /unknown field "maxScore"/,
    );
    expect(gradescopeProblems({ score: '1', tests: [test] })[0]).toMatch(/score/);
    expect(gradescopeProblems([])).toEqual(['results.json is not a JSON object']);
  });

  it('accept the documented PrairieLearn fields and flag each broken rule', () => {
    const pl = { name: 'T', points: 1, max_points: 2, message: 'm', output: 'o' };
    expect(prairieLearnProblems({ gradable: true, score: 0.5, message: 'm', tests: [pl] })).toEqual(
      [],
    );
    expect(prairieLearnProblems({ gradable: false, message: 'm' })).toEqual([]);
    expect(prairieLearnProblems({ score: 1.5 })).toEqual(['score must be a number in [0, 1]']);
    expect(prairieLearnProblems({ gradable: true })).toEqual(['score must be a number in [0, 1]']);
    expect(prairieLearnProblems({ gradable: 'yes', score: 1 })).toEqual([
      'gradable must be a boolean',
    ]);
    expect(prairieLearnProblems({ score: 1, tests: [{ ...pl, points: 3 }] })).toEqual([
      'tests[0].points 3 exceeds max_points 2',
    ]);
    expect(prairieLearnProblems({ score: 1, tests: [{ points: 1 }] })).toEqual([
      'tests[0].name must be a non-empty string',
    ]);
    expect(prairieLearnProblems({ score: 1 }, 2 * 1024 * 1024)[0]).toMatch(/limit 1 MB/);
  });
});

describe('PrairieLearn questions', () => {
  it('uuids are valid version-5 UUIDs, stable and distinct', () => {
    const ids = EXERCISE_IDS.map(questionUuid);
    for (const uuid of ids)
      expect(uuid).toMatch(/^[0-9a-f]{8}-[0-9a-f]{4}-5[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}$/);
    expect(new Set(ids).size).toBe(ids.length);
    expect(questionUuid('beer-law')).toBe(questionUuid('beer-law'));
  });

  it('statements keep TeX for MathJax, escape HTML and cannot open a Mustache tag', () => {
    const html = statementHtml(
      '# Title\n\nInline $a<b_{x}$ and {{x}} {{{y}}}\n\n$$\ne^{{-\\tau}}\n$$\n',
    );
    expect(html).toContain('<h3>Title</h3>');
    expect(html).toContain('\\(a&lt;b_{x}\\)');
    expect(html).toContain('\\[');
    expect(html).not.toMatch(/\{\{|\}\}/);
  });
});

describe('grade kit command', () => {
  let out: string;
  beforeAll(() => {
    out = mkdtempSync(join(tmpdir(), 'kit-unit-'));
  });
  afterAll(() => rmSync(out, { recursive: true, force: true }));

  it('refuses bad arguments with status 2', async () => {
    expect(await runKit(['moodle', '--out', join(out, 'a')])).toBe(2);
    expect(await runKit(['gradescope', '--out', join(out, 'b')])).toBe(2);
    expect(await runKit(['gradescope', '--exercise', 'nope', '--out', join(out, 'c')])).toBe(2);
    expect(
      await runKit([
        'gradescope',
        '--exercise',
        'beer-law',
        '--out',
        join(out, 'd'),
        '--time-limit',
        '2',
      ]),
    ).toBe(2);
    expect(await runKit(['prairielearn', '--out', join(out, 'e'), '--image', 'Bad Name'])).toBe(2);
  });

  it('writes a Gradescope zip identical to its folder, with valid scripts', async () => {
    const dir = join(out, 'gs');
    expect(
      await runKit(['gradescope', '--exercise', 'beer-law', '--out', dir, '--time-limit', '30']),
    ).toBe(0);
    expect(await runKit(['gradescope', '--exercise', 'beer-law', '--out', dir])).toBe(2); // not empty
    const folder = join(dir, 'autograder');
    const zip = readZip(readFileSync(join(dir, 'scatterbook-beer-law-gradescope.zip')));
    expect([...zip.keys()].sort()).toEqual(listTree(folder).sort());
    for (const [name, entry] of zip)
      expect(entry.data.equals(readFileSync(join(folder, name))), name).toBe(true);
    expect(zip.get('setup.sh')?.mode).toBe(0o755);
    expect(zip.get('run_autograder')?.mode).toBe(0o755);
    for (const script of ['setup.sh', 'run_autograder'])
      expect(spawnSync('bash', ['-n', join(folder, script)]).status, script).toBe(0);
    const setup = readFileSync(join(folder, 'setup.sh'), 'utf8');
    expect(setup).toContain(`NODE_VERSION='${process.versions.node}'`);
    expect(setup).toMatch(/SHASUMS256\.txt.*sha256sum -c/);
    expect(setup).toContain('npm ci');
    expect(setup).toContain("--self-test --exercise 'beer-law'");
    expect(readFileSync(join(folder, 'run_autograder'), 'utf8')).toContain('--time-limit 30');
    if (spawnSync('unzip', ['-v']).status === 0)
      execFileSync('unzip', ['-tq', join(dir, 'scatterbook-beer-law-gradescope.zip')]);
  });

  it('writes one PrairieLearn question per exercise and the grader image', async () => {
    const dir = join(out, 'pl');
    expect(
      await runKit([
        'prairielearn',
        '--out',
        dir,
        '--image',
        'me/scatterbook-grader:2',
        '--time-limit',
        '50',
      ]),
    ).toBe(0);
    for (const id of EXERCISE_IDS) {
      const q = join(dir, 'questions/scatterbook', id);
      const info = JSON.parse(readFileSync(join(q, 'info.json'), 'utf8')) as Record<
        string,
        unknown
      >;
      const exercise = await loadExercise(id);
      expect(info).toMatchObject({
        uuid: questionUuid(id),
        title: exercise.title,
        topic: 'Scatterbook',
        type: 'v3',
        gradingMethod: 'External',
        externalGradingOptions: {
          enabled: true,
          image: 'me/scatterbook-grader:2',
          serverFilesCourse: ['scatterbook/'],
          entrypoint: `/grade/serverFilesCourse/scatterbook/entrypoint.sh ${id}`,
          timeout: 80,
        },
      });
      const html = readFileSync(join(q, 'question.html'), 'utf8');
      expect(html).toContain(`<pl-file-editor file-name="${id}.wgsl"`);
      expect(html).toContain('source-file-name="starter.wgsl"');
      expect(html).toContain('<pl-external-grader-results>');
      expect(html).toContain('<pl-submission-panel>');
      expect(html).not.toMatch(/\{\{/);
      expect(readFileSync(join(q, 'starter.wgsl'), 'utf8')).toBe(exercise.starter);
    }
    const docker = readFileSync(join(dir, 'grader-image/Dockerfile'), 'utf8');
    expect(docker).toMatch(/^FROM node:20-bookworm/m);
    expect(docker).toContain('VK_ICD_FILENAMES=/usr/lib/chromium/vk_swiftshader_icd.json');
    expect(docker).toContain('--self-test');
    // The image may be public: only the throwaway self-test stage sees the sources.
    const stages = docker.split(/^FROM /m).slice(1);
    expect(stages.map((stage) => stage.split(/\s/)[0])).toEqual([
      'node:20-bookworm-slim',
      'runtime',
      'runtime',
    ]);
    for (const stage of [stages[0], stages[2]]) expect(stage).not.toContain('serverFilesCourse');
    expect(stages[1]).toContain('serverFilesCourse/scatterbook/');
    expect(listTree(join(dir, 'grader-image')).sort()).toEqual([
      'Dockerfile',
      'package-lock.json',
      'package.json',
    ]);
    const server = join(dir, 'serverFilesCourse/scatterbook');
    for (const file of ['package.json', 'package-lock.json'])
      expect(readFileSync(join(dir, 'grader-image', file), 'utf8')).toBe(
        readFileSync(join(server, file), 'utf8'),
      );
    expect(listTree(server)).toContain('exercises/beer-law/hidden.ts');
    expect(listTree(dir).some((p) => p.startsWith('questions/') && p.includes('hidden'))).toBe(
      false,
    );
    const entry = join(server, 'entrypoint.sh');
    expect(statSync(entry).mode & 0o777).toBe(0o755);
    expect(spawnSync('bash', ['-n', entry]).status).toBe(0);
    expect(readFileSync(entry, 'utf8')).toContain('--time-limit 50');
  });
});
