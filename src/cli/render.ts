// `scatterbook render`: renders a scene file (README "Scenes") headlessly, on the GPU
// through Dawn (SwiftShader where there is no GPU) or on the CPU with the float64 twin,
// and writes linear float RGB as PFM (bottom row first, as the format prescribes), an
// optional tone-mapped PNG and an optional JSON file of statistics: the plan, the time of
// every pass, the samples and the per-pixel standard error.
import { writeFile } from 'node:fs/promises';
import { fileURLToPath } from 'node:url';
import type { PrelinkedKernels } from '../gpu/link.ts';
import { diskCachedKernels } from '../gpu/linkCacheNode.ts';
import { loadShaderLibrary } from '../gpu/shaderSourcesNode.ts';
import { GpuAccumulation } from '../scene/gpuAccumulation.ts';
import { GpuSceneRenderer } from '../scene/gpuRenderer.ts';
import { encodePfm, toneMapRgba8 } from '../scene/image.ts';
import type { ResolvedScene } from '../scene/load.ts';
import { loadSceneFile } from '../scene/loadNode.ts';
import { GENERAL_CONDITIONS, plan } from '../scene/plan.ts';
import type { RenderProgress } from '../scene/render.ts';
import { renderScene, type Backend, type SceneRender } from '../scene/renderScene.ts';
import { SceneValidationError } from '../scene/validate.ts';
import { StartupTimer, type StartupReport } from './startup.ts';

const SHADERS_DIRECTORY = fileURLToPath(new URL('../../shaders', import.meta.url));
/** Linked WGSL per kernel variant (src/gpu/linkCacheNode.ts); git ignores .cache/. */
const LINKED_CACHE_DIRECTORY = fileURLToPath(new URL('../../.cache/wgsl', import.meta.url));

export const RENDER_SYNOPSIS = `  scatterbook render SCENE.json --out IMAGE.pfm [--png IMAGE.png] [--spp N]
                     [--backend gpu|cpu] [--stats FILE.json] [--kernel plan|general]
                     [--exposure EV]`;

export const RENDER_HELP = `render  Renders a scene description (see the README's "Scenes" section).
        --out       linear float RGB, PFM (rows stored bottom row first, little-endian)
        --png       a preview: radiance × 2^EV (--exposure, default 0), clamped, sRGB
        --spp       samples per pixel (default: the scene's samplesPerPixel)
        --backend   gpu (default; Dawn, SwiftShader without a GPU) or cpu (float64 twin)
        --stats     JSON: plan, per-pass times, samples, per-pixel standard error,
                    start-up phases (ms since the process started)
        --kernel    plan (default: only the effects the scene needs) or general
        Progress goes to stderr; an invalid scene exits with status 2 and its errors.`;

/** A bad command line or scene (exit status 2), as main.ts's UsageError. */
export class RenderInputError extends Error {}

export interface RenderFlags {
  out?: string;
  png?: string;
  spp?: string;
  backend?: string;
  stats?: string;
  kernel?: string;
  exposure?: string;
}

function positiveInteger(name: string, text: string | undefined, max: number): number | undefined {
  if (text === undefined) return undefined;
  const value = Number(text);
  if (!Number.isInteger(value) || value < 1 || value > max)
    throw new RenderInputError(
      `${name} must be an integer in [1, ${max}], got ${JSON.stringify(text)}`,
    );
  return value;
}

function progressPrinter(): (progress: RenderProgress) => void {
  const tty = process.stderr.isTTY === true;
  let lastPrint = 0;
  return (p) => {
    const now = p.elapsedMs;
    const done = p.pass === p.passes;
    if (p.passes === 1 || (!done && now - lastPrint < (tty ? 100 : 1000))) return;
    lastPrint = now;
    const left = (now / p.samples) * (p.totalSamples - p.samples);
    const line =
      `render: ${p.samples}/${p.totalSamples} spp (pass ${p.pass}/${p.passes}), ` +
      `${(now / 1000).toFixed(1)} s${done ? '' : `, about ${(left / 1000).toFixed(1)} s left`}`;
    process.stderr.write(tty ? `\r${line}${done ? '\n' : ''}` : `${line}\n`);
  };
}

function statistics(
  scenePath: string,
  render: SceneRender,
  deviceName: string,
  wallMs: number,
  startup: StartupReport,
) {
  const { accumulator: acc } = render;
  const mean = acc.mean();
  const se = acc.standardError();
  const pixels = acc.width * acc.height;
  const channelMean = (values: Float64Array): number[] =>
    [0, 1, 2].map((c) => {
      let sum = 0;
      for (let i = 0; i < pixels; i++) sum += values[3 * i + c]!;
      return sum / pixels;
    });
  const channelMax = (values: Float64Array): number[] =>
    [0, 1, 2].map((c) => {
      let max = 0;
      for (let i = 0; i < pixels; i++) max = Math.max(max, values[3 * i + c]!);
      return max;
    });
  const passMs = render.passes.reduce((sum, p) => sum + p.milliseconds, 0);
  const finite = (x: number): number | null => (Number.isFinite(x) ? x : null);
  return {
    scene: scenePath,
    backend: render.backend,
    device: deviceName,
    kernel: render.conditions === render.plan.conditions ? 'plan' : 'general',
    image: { width: acc.width, height: acc.height },
    samplesPerPixel: render.spp,
    plan: {
      integrator: render.plan.integrator,
      scatteringOrder: render.plan.scatteringOrder,
      conditions: render.conditions,
      effects: render.plan.effects,
    },
    passes: render.passes,
    timing: {
      passMs,
      wallMs,
      timing: render.passes[0]?.timing ?? null,
      msPerSamplePerPixel: passMs / Math.max(render.spp, 1),
      nsPerPathSample: (1e6 * passMs) / Math.max(render.spp * pixels, 1),
    },
    startup,
    densityLookups: acc.lookups,
    cappedWalks: acc.capped,
    radiance: { unit: 'W/(m²·sr)', meanOverPixels: channelMean(mean), max: channelMax(mean) },
    standardError: {
      layout: 'width × height × RGB, interleaved, row 0 at the top; null with fewer than 2 samples',
      meanOverPixels: channelMean(se).map(finite),
      max: channelMax(se).map(finite),
      values: Array.from(se, finite),
    },
  };
}

async function readScene(scenePath: string): Promise<ResolvedScene> {
  try {
    return await loadSceneFile(scenePath);
  } catch (error) {
    if (error instanceof SceneValidationError)
      throw new RenderInputError(`${scenePath}: ${error.message}`);
    if ((error as NodeJS.ErrnoException).code === 'ENOENT')
      throw new RenderInputError(`cannot read ${scenePath}: no such file`);
    throw error;
  }
}

interface OpenDevice {
  device: GPUDevice;
  release: () => Promise<void>;
}

/** Dawn (the webgpu package, imported only for the GPU backend) and its device. */
async function openDevice(timer: StartupTimer): Promise<OpenDevice> {
  const { nodeDevice, releaseNodeDevice } = await timer.time(
    'import webgpu',
    () => import('../gpu/nodeDevice.ts'),
  );
  const device = await timer.time('adapter and device', nodeDevice);
  return { device, release: releaseNodeDevice };
}

/**
 * The shader library (linked WGSL from the disk cache, src/gpu/linkCacheNode.ts) with the
 * scene kernel of the render's conditions and the accumulate kernel compiled, both at
 * once (createComputePipelineAsync): renderScene then finds both pipelines in the
 * device's GPU core (src/gpu/core.ts) and goes straight to uploading the scene.
 */
async function compileKernels(
  device: GPUDevice,
  resolved: ResolvedScene,
  kernel: 'plan' | 'general',
  timer: StartupTimer,
): Promise<PrelinkedKernels> {
  const cached = await timer.time('shader library', () =>
    diskCachedKernels(loadShaderLibrary(SHADERS_DIRECTORY), LINKED_CACHE_DIRECTORY),
  );
  const library: PrelinkedKernels = {
    prelinked: (path, conditions) =>
      timer.time(`link ${path}`, () => cached.prelinked(path, conditions)),
  };
  const conditions = kernel === 'general' ? GENERAL_CONDITIONS : plan(resolved.scene).conditions;
  await Promise.all([
    timer.time('compile scene kernel', () => GpuSceneRenderer.prepare(device, library, conditions)),
    timer.time('compile accumulate kernel', () => GpuAccumulation.prepare(device, library)),
  ]);
  return library;
}

export async function runRender(
  positionals: string[],
  flags: RenderFlags,
  timer: StartupTimer = new StartupTimer(),
): Promise<void> {
  if (positionals.length !== 2)
    throw new RenderInputError(
      positionals.length < 2
        ? 'render needs a SCENE.json'
        : `render takes one scene, got ${positionals.slice(1).join(' ')}`,
    );
  const scenePath = positionals[1]!;
  if (!flags.out) throw new RenderInputError('render needs --out IMAGE.pfm');
  const backendName = flags.backend ?? 'gpu';
  if (backendName !== 'gpu' && backendName !== 'cpu')
    throw new RenderInputError(`--backend must be gpu or cpu, got ${JSON.stringify(backendName)}`);
  const kernel = flags.kernel ?? 'plan';
  if (kernel !== 'plan' && kernel !== 'general')
    throw new RenderInputError(`--kernel must be plan or general, got ${JSON.stringify(kernel)}`);
  const spp = positiveInteger('--spp', flags.spp, 1_000_000);
  const exposure = flags.exposure === undefined ? 0 : Number(flags.exposure);
  if (!Number.isFinite(exposure) || Math.abs(exposure) > 64)
    throw new RenderInputError(
      `--exposure must be a number of stops in [-64, 64], got ${flags.exposure}`,
    );

  // Dawn's device does not depend on the scene: it is requested first and made while the
  // scene is read and validated.
  const start = performance.now();
  const gpu = backendName === 'gpu' ? openDevice(timer) : null;
  // Handled below (awaited, or released after a bad scene); this keeps a failure that
  // comes while the scene is being read from counting as an unhandled rejection.
  gpu?.catch(() => undefined);
  let render: SceneRender;
  let deviceName = 'CPU (float64 twin, one thread)';
  try {
    const resolved = await timer.time('read scene', () => readScene(scenePath));
    let backend: Backend = { kind: 'cpu' };
    if (gpu) {
      const { device } = await gpu;
      const info = (device as GPUDevice & { adapterInfo?: GPUAdapterInfo }).adapterInfo;
      deviceName = `Dawn (webgpu npm package)${info ? `: ${[info.vendor, info.architecture, info.description].filter(Boolean).join(' ')}` : ''}`;
      const library = await compileKernels(device, resolved, kernel, timer);
      backend = { kind: 'gpu', device, library };
      if (flags.stats) timer.watchFirstSubmit(device);
    }
    const renderStart = timer.now();
    render = await renderScene(resolved, backend, {
      ...(spp !== undefined ? { spp } : {}),
      kernel,
      onPass: progressPrinter(),
    });
    timer.record('render', renderStart);
  } finally {
    if (gpu) await (await gpu.catch(() => null))?.release();
  }
  const wallMs = performance.now() - start;
  const { accumulator: acc } = render;
  const mean = acc.mean();
  await writeFile(flags.out, encodePfm(acc.width, acc.height, mean));
  if (flags.png) {
    // pngjs only for a preview (a third of the command's module loading under tsx).
    const { PNG } = await import('pngjs');
    const png = new PNG({ width: acc.width, height: acc.height });
    png.data = Buffer.from(toneMapRgba8(acc.width, acc.height, mean, exposure));
    await writeFile(flags.png, PNG.sync.write(png));
  }
  if (flags.stats)
    await writeFile(
      flags.stats,
      `${JSON.stringify(statistics(scenePath, render, deviceName, wallMs, timer.report()), null, 2)}\n`,
    );
  const passMs = render.passes.reduce((sum, p) => sum + p.milliseconds, 0);
  const pathSamples = render.spp * acc.width * acc.height;
  process.stderr.write(
    `render: ${acc.width}×${acc.height}, ${render.spp} spp, ${render.plan.integrator} ` +
      `(${kernel} kernel) on ${render.backend}: ${(passMs / render.spp).toFixed(2)} ms per sample per pixel over the image, ` +
      `${((1e6 * passMs) / pathSamples).toFixed(0)} ns per path sample (${render.passes[0]?.timing ?? ''}), ` +
      `${(wallMs / 1000).toFixed(1)} s in all` +
      `${acc.capped > 0 ? `; ${acc.capped} walks reached a cap` : ''}\n`,
  );
}
