// `scatterbook render` (src/cli/render.ts) run as a child process, the way a user runs
// it: PFM (bottom row first) + PNG + stats JSON on the CPU backend (and the same pixels
// as an in-process render with the same seeds), the GPU backend through Dawn, progress on
// stderr, and the exit status and messages for invalid scenes and command lines.
import { execFile } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/scene/image.ts';
import { renderScene } from '../../src/scene/renderScene.ts';
import { exampleScene, exampleSceneJson } from '../support/sceneRender.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const DIRECTORY = mkdtempSync(join(tmpdir(), 'scatterbook-render-'));

interface Run {
  code: number;
  stdout: string;
  stderr: string;
}

function render(...args: string[]): Promise<Run> {
  return new Promise((resolve) => {
    execFile(
      'sh',
      // As `npm run render` runs it: the prebuilt bundle (scripts/cli.mjs).
      ['scripts/gpu-env.sh', 'node', 'scripts/cli.mjs', 'render', ...args],
      { cwd: ROOT, env: { ...process.env, NO_COLOR: '1' }, timeout: 170_000 },
      (error, stdout, stderr) => {
        const code = error ? (typeof error.code === 'number' ? error.code : -1) : 0;
        resolve({ code, stdout, stderr });
      },
    );
  });
}

const file = (name: string): string => join(DIRECTORY, name);

interface Stats {
  backend: string;
  kernel: string;
  image: { width: number; height: number };
  samplesPerPixel: number;
  plan: { integrator: string; conditions: Record<string, boolean> };
  passes: { samples: number; milliseconds: number; timing: string }[];
  timing: { msPerSamplePerPixel: number; nsPerPathSample: number };
  startup: {
    nodeBootstrapMs: number;
    phases: Record<string, { start: number; end: number }>;
    firstPassSubmittedMs: number | null;
    firstPassCpuMs: number | null;
  };
  standardError: { values: (number | null)[] };
}

describe('scatterbook render', () => {
  it('CPU backend: PFM, PNG and stats; the PFM holds the same pixels as an in-process render', async () => {
    const scene = 'public/scenes/spheres-on-floor.json';
    const run = await render(
      scene,
      '--out',
      file('spheres.pfm'),
      '--png',
      file('spheres.png'),
      '--stats',
      file('spheres.json'),
      '--spp',
      '12',
      '--backend',
      'cpu',
    );
    expect(run.code, run.stderr).toBe(0);
    expect(run.stderr).toMatch(/render: 12\/12 spp \(pass \d+\/\d+\)/);
    expect(run.stderr).toMatch(
      /48×32, 12 spp, path-tracing \(plan kernel\) on cpu: .* ms per sample per pixel/,
    );
    const pfm = decodePfm(new Uint8Array(readFileSync(file('spheres.pfm'))));
    expect([pfm.width, pfm.height]).toEqual([48, 32]);
    const reference = await renderScene(
      await exampleScene('spheres-on-floor'),
      { kind: 'cpu' },
      { spp: 12 },
    );
    const mean = reference.accumulator.mean();
    // The PFM is f32; row 0 at the top in memory, whatever PFM's bottom-first storage.
    mean.forEach((v, k) => expect(pfm.rgb[k]).toBe(Math.fround(v)));
    expect(readFileSync(file('spheres.png')).subarray(1, 4).toString()).toBe('PNG');
    const stats = JSON.parse(readFileSync(file('spheres.json'), 'utf8')) as Stats;
    expect(stats).toMatchObject({
      backend: 'cpu',
      kernel: 'plan',
      image: { width: 48, height: 32 },
      samplesPerPixel: 12,
      plan: { integrator: 'path-tracing', conditions: { media: false, surfaceScattering: true } },
    });
    expect(stats.passes.reduce((n, p) => n + p.samples, 0)).toBe(12);
    expect(stats.passes.every((p) => p.timing === 'cpu' && p.milliseconds > 0)).toBe(true);
    expect(stats.standardError.values).toHaveLength(48 * 32 * 3);
    const se = reference.accumulator.standardError();
    stats.standardError.values.forEach((v, k) => expect(v).toBeCloseTo(se[k]!, 12));
    expect(stats.timing.nsPerPathSample).toBeGreaterThan(0);
  }, 180_000);

  it('GPU backend through Dawn: the white furnace renders the environment', async () => {
    const run = await render(
      'public/scenes/white-furnace.json',
      '--out',
      file('furnace.pfm'),
      '--stats',
      file('furnace.json'),
      '--spp',
      '8',
    );
    expect(run.code, run.stderr).toBe(0);
    const stats = JSON.parse(readFileSync(file('furnace.json'), 'utf8')) as Stats;
    expect(stats.backend).toBe('gpu');
    expect(['gpu-timestamp', 'gpu-wall']).toContain(stats.passes[0]?.timing);
    // Start-up phases in ms since the process started: the program loads, Dawn makes the
    // device, both kernels compile at once, and the first pass is submitted after them.
    const { phases, firstPassSubmittedMs, firstPassCpuMs, nodeBootstrapMs } = stats.startup;
    const phase = (name: string) => {
      const span = phases[name];
      expect(span, name).toBeDefined();
      expect(span!.end, name).toBeGreaterThanOrEqual(span!.start);
      return span!;
    };
    const load = phase('load program');
    expect(load.start).toBe(0);
    expect(nodeBootstrapMs).toBeGreaterThan(0);
    expect(nodeBootstrapMs).toBeLessThan(load.end);
    const device = phase('adapter and device');
    expect(phase('import webgpu').end).toBeLessThanOrEqual(device.start);
    expect(device.start).toBeGreaterThanOrEqual(load.end);
    const sceneKernel = phase('compile scene kernel');
    const accumulateKernel = phase('compile accumulate kernel');
    expect(sceneKernel.start).toBeGreaterThanOrEqual(device.end);
    expect(sceneKernel.start).toBeGreaterThanOrEqual(phase('read scene').end);
    expect(sceneKernel.start).toBeGreaterThanOrEqual(phase('shader library').end);
    expect(accumulateKernel.start).toBeLessThan(sceneKernel.end);
    expect(sceneKernel.start).toBeLessThan(accumulateKernel.end);
    const rendering = phase('render');
    expect(rendering.start).toBeGreaterThanOrEqual(Math.max(sceneKernel.end, accumulateKernel.end));
    expect(firstPassSubmittedMs).not.toBeNull();
    expect(firstPassSubmittedMs!).toBeGreaterThanOrEqual(rendering.start);
    expect(firstPassSubmittedMs!).toBeLessThanOrEqual(rendering.end);
    expect(firstPassCpuMs).toBeGreaterThan(0);
    const { rgb } = decodePfm(new Uint8Array(readFileSync(file('furnace.pfm'))));
    // The image mean is 1 within 5 pooled standard errors (8 samples per pixel are too few
    // for per-pixel bounds; tests/shaders/scene-render.test.ts checks pixels).
    const se = stats.standardError.values.map((v) => v ?? 0);
    const meanOver = rgb.reduce((a, b) => a + b) / rgb.length;
    const pooled = Math.sqrt(se.reduce((a, b) => a + b * b, 0)) / rgb.length;
    expect(Math.abs(meanOver - 1)).toBeLessThan(5 * pooled + 1e-5);
    expect(pooled).toBeGreaterThan(0);
  }, 180_000);

  it('an invalid scene exits with status 2 and every validation message', async () => {
    const json = exampleSceneJson('fog-slab');
    (json.media as { sigmaS: number[] }[])[0]!.sigmaS = [1, -2, 1];
    (json.image as { width: number }).width = 0;
    writeFileSync(file('bad.json'), JSON.stringify(json));
    const run = await render(file('bad.json'), '--out', file('bad.pfm'));
    expect(run.code).toBe(2);
    expect(run.stderr).toContain('image.width = 0: must be ≥ 1 (pixels)');
    expect(run.stderr).toContain('media[0].sigmaS[1] = -2: must be ≥ 0 (1/m)');
    writeFileSync(file('broken.json'), '{ "image": ');
    const broken = await render(file('broken.json'), '--out', file('bad.pfm'));
    expect(broken.code).toBe(2);
    expect(broken.stderr).toMatch(/scene: not valid JSON/);
  }, 60_000);

  it('command-line mistakes exit with status 2 and say what is wrong', async () => {
    const scene = 'public/scenes/fog-slab.json';
    const [noOut, missing, backend, spp] = await Promise.all([
      render(scene),
      render(file('nowhere.json'), '--out', file('x.pfm')),
      render(scene, '--out', file('x.pfm'), '--backend', 'tpu'),
      render(scene, '--out', file('x.pfm'), '--spp', '0'),
    ]);
    for (const run of [noOut, missing, backend, spp]) expect(run.code).toBe(2);
    expect(noOut.stderr).toContain('render needs --out IMAGE.pfm');
    expect(missing.stderr).toContain('no such file');
    expect(backend.stderr).toContain('--backend must be gpu or cpu, got "tpu"');
    expect(spp.stderr).toContain('--spp must be an integer in [1, 1000000], got "0"');
  }, 60_000);
});
