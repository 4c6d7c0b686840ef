// The command line's launcher (scripts/cli.mjs, what `npm run render` and `npm run cli`
// run): it builds the command into a bundle in .cache/cli/ once, reuses it while the
// sources are unchanged, builds again when a source's hash changes, and runs the sources
// under tsx when asked (or when it cannot build), with the same output and exit status.
import { execFile } from 'node:child_process';
import { existsSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const CACHE = join(ROOT, '.cache', 'cli');
const MANIFEST = join(CACHE, 'manifest.json');

interface Run {
  code: number;
  stdout: string;
  stderr: string;
}

function cli(args: string[], env: Record<string, string> = {}): Promise<Run> {
  return new Promise((resolve) => {
    execFile(
      'sh',
      ['scripts/gpu-env.sh', 'node', 'scripts/cli.mjs', ...args],
      { cwd: ROOT, env: { ...process.env, NO_COLOR: '1', ...env }, timeout: 170_000 },
      (error, stdout, stderr) => {
        const code = error ? (typeof error.code === 'number' ? error.code : -1) : 0;
        resolve({ code, stdout, stderr });
      },
    );
  });
}

interface Manifest {
  digest: string;
  bundle: string;
  inputs: string[];
}

const manifest = (): Manifest => JSON.parse(readFileSync(MANIFEST, 'utf8')) as Manifest;

const TWIN = ['eval', 'transmittance.transmittanceHomogeneous', '--args', '[[1, 2]]'];
const TWIN_ARGS = [...TWIN, '--backend', 'cpu', '--json'];

describe('scripts/cli.mjs', () => {
  it('builds the bundle once and reuses it while the sources are unchanged', async () => {
    const first = await cli(['--help']);
    expect(first.code, first.stderr).toBe(0);
    expect(first.stdout).toContain('scatterbook render SCENE.json');
    const built = manifest();
    expect(built.inputs).toEqual(
      expect.arrayContaining(['src/cli/main.ts', 'src/cli/render.ts', 'src/scene/renderScene.ts']),
    );
    expect(built.inputs.some((file) => file.startsWith('node_modules/'))).toBe(false);
    const bundle = join(CACHE, built.bundle);
    const bundleTime = statSync(bundle).mtimeMs;
    const manifestTime = statSync(MANIFEST).mtimeMs;
    // A float64 twin through the bundle's on-demand import of src/reference/.
    const again = await cli(TWIN_ARGS);
    expect(again.code, again.stderr).toBe(0);
    expect(JSON.parse(again.stdout)).toMatchObject({ results: [Math.exp(-2)] });
    expect(manifest()).toEqual(built);
    expect(statSync(bundle).mtimeMs).toBe(bundleTime);
    expect(statSync(MANIFEST).mtimeMs).toBe(manifestTime);
  }, 180_000);

  it('builds again when the sources no longer match the bundle', async () => {
    const before = await cli(['--help']);
    expect(before.code, before.stderr).toBe(0);
    const current = manifest();
    // As after an edit: the recorded hash is not the sources' hash.
    writeFileSync(MANIFEST, JSON.stringify({ ...current, digest: '0'.repeat(32) }));
    const run = await cli(TWIN_ARGS);
    expect(run.code, run.stderr).toBe(0);
    expect(JSON.parse(run.stdout)).toMatchObject({ results: [Math.exp(-2)] });
    const rebuilt = manifest();
    expect(rebuilt.digest).toBe(current.digest);
    expect(existsSync(join(CACHE, rebuilt.bundle))).toBe(true);
  }, 180_000);

  it('SCATTERBOOK_TSX=1 runs the sources under tsx with the same output and exit status', async () => {
    const tsx = { SCATTERBOOK_TSX: '1' };
    const [bundled, underTsx, badBundled, badTsx] = await Promise.all([
      cli(TWIN_ARGS),
      cli(TWIN_ARGS, tsx),
      cli(['render', 'public/scenes/fog-slab.json']),
      cli(['render', 'public/scenes/fog-slab.json'], tsx),
    ]);
    expect(underTsx.code, underTsx.stderr).toBe(0);
    expect(underTsx.stdout).toBe(bundled.stdout);
    for (const run of [badBundled, badTsx]) {
      expect(run.code).toBe(2);
      expect(run.stderr).toContain('render needs --out IMAGE.pfm');
    }
  }, 180_000);
});
