// Benchmark: Mitsuba 3 as a performance peer (issue 19). The same scenes, exported from
// our scene JSON to Mitsuba scene dicts (mitsubaDict below), rendered by our GPU kernel
// (Dawn; SwiftShader without a GPU) and by Mitsuba 3 (variant llvm_ad_rgb, volpath) in
// a virtual environment that this bench creates under .cache/peers (pip from PyPI; it
// prints "skipped: why" when it cannot: no python3 venv, no libLLVM-19, offline).
// Per scene: paths/s of each, the per-sample variance of each (ours: n·SE² per pixel and
// channel; Mitsuba's: spp × the variance of independent images), and the equal-error time
// ratio ours ÷ Mitsuba, (var_ours/var_mi)·(t_ours/t_mi) per path, for the render passes
// and for the whole process (our `render` command, Mitsuba's python, same spp). Our kernel
// is timed three times, alternating pass by pass: the plan's kernel; the plan's kernel
// without the one-medium kernels (oneHomogeneousMedium and oneGridMedium off: the general
// kernel); and the plan's kernel awaited with dawn.node's own busy poll instead of
// src/gpu/quietPolling.ts (the main thread spinning at a core beside SwiftShader's).
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { setQuietPolling } from '../src/gpu/quietPolling.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { GpuSceneRenderer } from '../src/scene/gpuRenderer.ts';
import { resolveScene, type ResolvedScene } from '../src/scene/load.ts';
import { nodeFileReader } from '../src/scene/loadNode.ts';
import { packScene } from '../src/scene/pack.ts';
import { plan, type Conditions } from '../src/scene/plan.ts';
import type { SceneDescription } from '../src/scene/types.ts';
import { parseScene } from '../src/scene/validate.ts';
import { median, type BenchTable } from './table.ts';
import { imageMeanStandardError } from './peerStatistics.ts';

const ROOT = fileURLToPath(new URL('..', import.meta.url));
const CACHE = `${ROOT}.cache/peers`;
const VENV = `${CACHE}/venv`;
const PYTHON = `${VENV}/bin/python`;
const PEER_SCRIPT = `${ROOT}bench/mitsuba_peer.py`;
const MITSUBA_PACKAGES = ['mitsuba==3.9.1', 'drjit==1.5.0', 'numpy'];
const LLVM_CANDIDATES = [
  '/usr/lib/x86_64-linux-gnu/libLLVM-19.so.1',
  '/usr/lib/x86_64-linux-gnu/libLLVM-19.so',
  '/usr/lib/llvm-19/lib/libLLVM-19.so',
  '/usr/lib/aarch64-linux-gnu/libLLVM-19.so.1',
];

type Peer = { python: string; env: NodeJS.ProcessEnv } | { skipped: string };

/** Mitsuba's Python and environment, creating the venv when it can; or why not. */
export function mitsubaPeer(): Peer {
  const llvm = [process.env.DRJIT_LIBLLVM_PATH, ...LLVM_CANDIDATES].find(
    (path): path is string => !!path && existsSync(path),
  );
  if (!llvm)
    return {
      skipped:
        "no libLLVM-19 (Mitsuba's llvm variants need it; Debian: apt-get install -y libllvm19, or set DRJIT_LIBLLVM_PATH)",
    };
  const env = { ...process.env, DRJIT_LIBLLVM_PATH: llvm };
  const probe = (): boolean =>
    existsSync(PYTHON) &&
    spawnSync(PYTHON, ['-c', 'import mitsuba, numpy'], { env, stdio: 'ignore' }).status === 0;
  if (probe()) return { python: PYTHON, env };
  if (spawnSync('python3', ['--version'], { stdio: 'ignore' }).status !== 0)
    return { skipped: 'no python3 on PATH' };
  mkdirSync(CACHE, { recursive: true });
  if (!existsSync(PYTHON)) {
    const venv = spawnSync('python3', ['-m', 'venv', VENV], { encoding: 'utf8' });
    if (venv.status !== 0)
      return {
        skipped: `python3 -m venv failed (Debian: apt-get install -y python3-venv): ${venv.stderr.trim().split('\n').at(-1) ?? ''}`,
      };
  }
  process.stderr.write(`peers: installing ${MITSUBA_PACKAGES.join(' ')} into ${VENV}\n`);
  const pip = spawnSync(PYTHON, ['-m', 'pip', 'install', '-q', ...MITSUBA_PACKAGES], {
    env,
    encoding: 'utf8',
  });
  if (pip.status !== 0)
    return {
      skipped: `pip install ${MITSUBA_PACKAGES.join(' ')} failed (offline?): ${pip.stderr.trim().split('\n').at(-1) ?? ''}`,
    };
  return probe() ? { python: PYTHON, env } : { skipped: 'mitsuba does not import after pip' };
}

// ---- The scenes (issue 19): a box [−1, 1]³ lit by the sun, 64×64 orthographic ----

const BOX = { type: 'box', min: [-1, -1, -1], max: [1, 1, 1] } as const;
const SUN = { type: 'directional', direction: [0.5, -0.8, -0.33], irradiance: [1, 1, 1] };
const HG = { type: 'henyey-greenstein', g: 0.6 };

function boxScene(
  size: number,
  order: number | 'unlimited',
  medium: Record<string, unknown>,
  lights: unknown[] = [SUN],
): Record<string, unknown> {
  return {
    image: { width: size, height: size },
    samplesPerPixel: 16,
    seed: 7,
    scatteringOrder: order,
    camera: {
      type: 'orthographic',
      position: [0, 0, 3],
      direction: [0, 0, -1],
      up: [0, 1, 0],
      width: 2.4,
      height: 2.4,
    },
    media: [{ bounds: BOX, phase: HG, ...medium }],
    lights,
    surfaces: [],
  };
}

const gray = (x: number): number[] => [x, x, x];

/** A smooth blob on an n³ grid filling the box: ρ = exp(−4 r²), r the distance to the centre. */
function blob(n: number): number[] {
  const values: number[] = [];
  for (let z = 0; z < n; z++)
    for (let y = 0; y < n; y++)
      for (let x = 0; x < n; x++) {
        const c = (i: number): number => (2 * (i + 0.5)) / n - 1;
        values.push(Math.exp(-4 * (c(x) ** 2 + c(y) ** 2 + c(z) ** 2)));
      }
  return values;
}

export function peerScenes(size: number): { name: string; json: Record<string, unknown> }[] {
  const homogeneous = (sigmaA: number, sigmaS: number) => ({
    type: 'homogeneous',
    sigmaA: gray(sigmaA),
    sigmaS: gray(sigmaS),
  });
  return [
    { name: 'single scattering', json: boxScene(size, 1, homogeneous(0.25, 1)) },
    { name: 'multiple scattering', json: boxScene(size, 'unlimited', homogeneous(0.02, 1.98)) },
    { name: 'thick (σt = 20, albedo 0.5), single', json: boxScene(size, 1, homogeneous(10, 10)) },
    {
      name: 'point light, single',
      json: boxScene(size, 1, homogeneous(0.25, 1), [
        { type: 'point', position: [0.3, 0.5, 0.2], intensity: [1, 1, 1] },
      ]),
    },
    {
      name: 'grid 16³, multiple',
      json: boxScene(size, 'unlimited', {
        type: 'grid',
        sigmaA: gray(0.2),
        sigmaS: gray(3.8),
        grid: { dimensions: [16, 16, 16], density: blob(16) },
      }),
    },
  ];
}

// ---- Export: our scene description → a Mitsuba 3 scene dict (JSON for mitsuba_peer.py) ----

type Dict = Record<string, unknown>;

const rgb = (value: readonly number[]): Dict => ({ type: 'rgb', value: [...value] });

/**
 * The Mitsuba dict of a scene: orthographic sensor, hdrfilm with a box filter (our pixel
 * footprint), independent sampler, volpath with max_depth = order + 1 (−1 unlimited), the
 * lights (directional: direction of travel and irradiance, as ours; point: intensity), and
 * each box medium as DESIGN.md prescribes for an exact comparison: a heterogeneous medium
 * (constvolume, or gridvolume for a grid, trilinear) whose bounding box is exactly the box,
 * inside a null-BSDF cube that is larger only along the view axis.
 */
export function mitsubaDict(scene: SceneDescription, resolved: ResolvedScene): Dict {
  const camera = scene.camera;
  if (camera.type !== 'orthographic') throw new Error('peers: orthographic cameras only');
  const dict: Dict = { type: 'scene' };
  const position = camera.position;
  const d = camera.direction;
  dict.sensor = {
    type: 'orthographic',
    to_world: {
      look_at: {
        origin: position,
        target: position.map((p, i) => p + d[i]!),
        up: camera.up,
      },
      scale: [camera.width / 2, camera.height / 2, 1],
    },
    film: {
      type: 'hdrfilm',
      width: scene.image.width,
      height: scene.image.height,
      rfilter: { type: 'box' },
      pixel_format: 'rgb',
    },
    sampler: { type: 'independent' },
  };
  const order = scene.scatteringOrder;
  dict.integrator = { type: 'volpath', max_depth: order === 'unlimited' ? -1 : order + 1 };
  scene.lights.forEach((light, i) => {
    if (light.type === 'directional')
      dict[`light${i}`] = {
        type: 'directional',
        direction: light.direction,
        irradiance: rgb(light.irradiance),
      };
    else if (light.type === 'point')
      dict[`light${i}`] = {
        type: 'point',
        position: light.position,
        intensity: rgb(light.intensity),
      };
    else throw new Error(`peers: no export for ${light.type} lights`);
  });
  const viewAxis = d.map((x) => Math.abs(x));
  const along = viewAxis.indexOf(Math.max(...viewAxis));
  scene.media.forEach((medium, i) => {
    if (medium.bounds.type !== 'box') throw new Error('peers: box media only');
    const { min, max } = medium.bounds;
    const centre = min.map((m, k) => (m + max[k]!) / 2);
    const half = min.map((m, k) => (max[k]! - m) / 2);
    // The volume's unit cube [0, 1]³ onto the box.
    const volumeToWorld = { translate_scale: { translate: min, scale: half.map((h) => 2 * h) } };
    const sigmaT = medium.sigmaA.map((a, k) => a + medium.sigmaS[k]!);
    // σt = scale × the volume, one value for all channels (the RGB ratios are in the albedo).
    if (sigmaT.some((t) => t !== sigmaT[0])) throw new Error('peers: gray σt only');
    const scale = sigmaT[0]!;
    const albedo = medium.sigmaS.map((s, k) => (sigmaT[k]! > 0 ? s / sigmaT[k]! : 0));
    const phase =
      medium.phase.type === 'henyey-greenstein'
        ? { type: 'hg', g: medium.phase.g }
        : medium.phase.type === 'isotropic'
          ? { type: 'isotropic' }
          : null;
    if (!phase) throw new Error(`peers: no export for the ${medium.phase.type} phase function`);
    let sigmaTVolume: Dict;
    if (medium.type === 'grid') {
      const grid = resolved.grid?.fine;
      if (!grid) throw new Error('peers: the grid was not resolved');
      const [nx, ny, nz] = grid.grid.dimensions;
      sigmaTVolume = {
        type: 'gridvolume',
        data: {
          grid: {
            shape: [nz, ny, nx],
            values: Array.from(grid.volume, (v) => v * grid.grid.densityScale),
          },
        },
        filter_type: 'trilinear',
        to_world: volumeToWorld,
      };
    } else {
      sigmaTVolume = { type: 'constvolume', value: 1, to_world: volumeToWorld };
    }
    dict[`medium${i}`] = {
      type: 'cube',
      // The null shell, 1 % larger than the box along the view axis only.
      to_world: {
        translate_scale: {
          translate: centre,
          scale: half.map((h, k) => (k === along ? 1.01 * h : h)),
        },
      },
      bsdf: { type: 'null' },
      interior: {
        type: 'heterogeneous',
        albedo: { type: 'constvolume', value: rgb(albedo), to_world: volumeToWorld },
        sigma_t: sigmaTVolume,
        scale,
        phase,
      },
    };
  });
  return dict;
}

// ---- Timing ----

interface OurTiming {
  pathsPerSecond: number;
  /** Per-sample variance, the mean over pixels and channels of n·SE². */
  sampleVariance: number;
  imageMean: number;
  /** The standard error of imageMean (imageMeanStandardError of the values' SE²). */
  imageMeanSe: number;
}

/** One way of running our kernel: its conditions, and whether Node polls quietly. */
interface OurVariant {
  conditions: Conditions;
  quietPolling: boolean;
}

/** Our kernels on one scene, pass by pass, alternating; medians of the GPU pass times. */
async function timeOurs(
  device: GPUDevice,
  resolved: ResolvedScene,
  kernels: readonly OurVariant[],
  spp: number,
  samplesPerPass: number,
): Promise<OurTiming[]> {
  const library = loadShaderLibrary(`${ROOT}shaders`);
  const packed = packScene(resolved);
  const renderers: GpuSceneRenderer[] = [];
  try {
    for (const { conditions } of kernels)
      renderers.push(await GpuSceneRenderer.create(device, library, packed, conditions));
    for (const renderer of renderers) {
      await renderer.renderPass(0, samplesPerPass);
      renderer.accumulation.reset();
    }
    const times: number[][] = renderers.map(() => []);
    for (let offset = 0; offset < spp; offset += samplesPerPass) {
      const samples = Math.min(samplesPerPass, spp - offset);
      for (let k = 0; k < renderers.length; k++) {
        setQuietPolling(kernels[k]!.quietPolling);
        const output = await renderers[k]!.renderPass(offset, samples).finally(() =>
          setQuietPolling(true),
        );
        times[k]!.push(output.milliseconds / samples);
      }
    }
    const pixels = packed.width * packed.height;
    const images = await Promise.all(renderers.map((r) => r.accumulation.readImage()));
    return images.map((acc, k) => {
      const mean = acc.mean();
      const seSquared = Array.from(acc.standardError(), (se) => se * se);
      const variance = seSquared.reduce((a, b) => a + b, 0);
      return {
        pathsPerSecond: pixels / (median(times[k]!) / 1000),
        sampleVariance: (variance * acc.samples) / seSquared.length,
        imageMean: mean.reduce((a, b) => a + b, 0) / mean.length,
        imageMeanSe: imageMeanStandardError(seSquared),
      };
    });
  } finally {
    for (const renderer of renderers) renderer.destroy();
  }
}

interface MitsubaResult {
  name: string;
  seconds: number[];
  width: number;
  height: number;
  mean: number[];
  sampleVariance: number[];
}

function runProcess(
  command: string,
  args: string[],
  env: NodeJS.ProcessEnv,
): Promise<{ stdout: string; ms: number }> {
  return new Promise((resolve, reject) => {
    const start = performance.now();
    const child = spawn(command, args, { env, cwd: ROOT, stdio: ['ignore', 'pipe', 'pipe'] });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (chunk: Buffer) => (stdout += chunk.toString()));
    child.stderr.on('data', (chunk: Buffer) => (stderr += chunk.toString()));
    child.on('error', reject);
    child.on('close', (code) =>
      code === 0
        ? resolve({ stdout, ms: performance.now() - start })
        : reject(
            new Error(`${command} ${args.join(' ')} exited with ${code}: ${stderr.slice(-2000)}`),
          ),
    );
  });
}

export async function benchPeers(
  device: GPUDevice,
  options: {
    size: number;
    /** Samples per pixel of our render and of each of Mitsuba's images. */
    spp: number;
    samplesPerPass: number;
    /** Independent Mitsuba images per scene (for its per-sample variance). */
    mitsubaImages: number;
    /** Also time the whole processes (our `render` command, Mitsuba's python). */
    processes: boolean;
  },
): Promise<BenchTable> {
  const title = 'Peers: our GPU kernel vs Mitsuba 3 (llvm_ad_rgb, volpath) on the same scenes';
  const peer = mitsubaPeer();
  if ('skipped' in peer) {
    console.log(`peers: skipped: ${peer.skipped}`);
    return { title, notes: [`skipped: ${peer.skipped}`], rows: [] };
  }
  mkdirSync(CACHE, { recursive: true });
  const scenes = [];
  for (const { name, json } of peerScenes(options.size)) {
    const resolved = await resolveScene(parseScene(json), nodeFileReader);
    scenes.push({ name, json, resolved, dict: mitsubaDict(resolved.scene, resolved) });
  }
  const jobPath = `${CACHE}/job.json`;
  writeFileSync(
    jobPath,
    JSON.stringify({
      variant: 'llvm_ad_rgb',
      scenes: scenes.map((s) => ({
        name: s.name,
        dict: s.dict,
        spp: options.spp,
        repeats: options.mitsubaImages,
        warmup_spp: 4,
      })),
    }),
  );
  const mitsubaRun = await runProcess(peer.python, [PEER_SCRIPT, jobPath], peer.env);
  const mitsuba = new Map<string, MitsubaResult>();
  for (const line of mitsubaRun.stdout.split('\n'))
    if (line.startsWith('{')) {
      const result = JSON.parse(line) as MitsubaResult;
      mitsuba.set(result.name, result);
    }

  const rows: BenchTable['rows'] = [];
  for (const [index, scene] of scenes.entries()) {
    const mi = mitsuba.get(scene.name);
    if (!mi) throw new Error(`peers: Mitsuba returned nothing for ${scene.name}`);
    const scenePlan = plan(scene.resolved.scene);
    const before = { ...scenePlan.conditions, oneHomogeneousMedium: false, oneGridMedium: false };
    const oneMedium =
      scenePlan.conditions.oneHomogeneousMedium || scenePlan.conditions.oneGridMedium;
    const [ours, previous, spinning] = (await timeOurs(
      device,
      scene.resolved,
      [
        { conditions: scenePlan.conditions, quietPolling: true },
        { conditions: before, quietPolling: true },
        { conditions: scenePlan.conditions, quietPolling: false },
      ],
      options.spp,
      options.samplesPerPass,
    )) as [OurTiming, OurTiming, OurTiming];
    const pixels = mi.width * mi.height;
    const miPathsPerSecond = (pixels * options.spp) / median(mi.seconds);
    const miVariance = mi.sampleVariance.reduce((a, b) => a + b, 0) / mi.sampleVariance.length;
    const miMean = mi.mean.reduce((a, b) => a + b, 0) / mi.mean.length;
    // The standard error of Mitsuba's mean image: per value, the per-sample variance / (images · spp).
    const miMeanSe = imageMeanStandardError(
      mi.sampleVariance.map((v) => v / (options.mitsubaImages * options.spp)),
    );
    const equalError = (t: OurTiming): number =>
      (t.sampleVariance / miVariance) * (miPathsPerSecond / t.pathsPerSecond);
    const row: BenchTable['rows'][number] = {
      scene: scene.name,
      'Mitsuba paths/s': miPathsPerSecond,
      'ours paths/s': ours.pathsPerSecond,
      'ours paths/s, previous kernel': oneMedium ? previous.pathsPerSecond : null,
      "ours paths/s, dawn.node's busy poll": spinning.pathsPerSecond,
      'variance per sample, Mitsuba ÷ ours': miVariance / ours.sampleVariance,
      'equal-error time, ours ÷ Mitsuba (pass)': equalError(ours),
      'same, previous kernel': oneMedium ? equalError(previous) : null,
      'image mean ours / Mitsuba': `${ours.imageMean.toPrecision(5)} / ${miMean.toPrecision(5)}`,
      'agreement |z| (image mean)':
        Math.abs(ours.imageMean - miMean) / Math.hypot(ours.imageMeanSe, miMeanSe),
    };
    if (options.processes) {
      const scenePath = `${CACHE}/scene-${index}.json`;
      writeFileSync(scenePath, JSON.stringify(scene.json));
      const onceJob = `${CACHE}/once-${index}.json`;
      writeFileSync(
        onceJob,
        JSON.stringify({
          variant: 'llvm_ad_rgb',
          scenes: [{ name: scene.name, dict: scene.dict, spp: options.spp }],
        }),
      );
      const oursProcess = await runProcess(
        'sh',
        [
          'scripts/gpu-env.sh',
          'node',
          'scripts/cli.mjs',
          'render',
          scenePath,
          '--out',
          `${CACHE}/scene-${index}.pfm`,
          '--spp',
          String(options.spp),
        ],
        process.env,
      );
      const miProcess = await runProcess(peer.python, [PEER_SCRIPT, onceJob, '--once'], peer.env);
      row['ours process s'] = oursProcess.ms / 1000;
      row['Mitsuba process s'] = miProcess.ms / 1000;
      row['equal-error time, ours ÷ Mitsuba (process)'] =
        (ours.sampleVariance / miVariance) * (oursProcess.ms / miProcess.ms);
    }
    rows.push(row);
  }
  return {
    title,
    notes: [
      `${options.size}×${options.size} orthographic, box [−1, 1]³, HG g = 0.6; ${options.spp} spp per image; ours in passes of ${options.samplesPerPass} (median GPU pass time, compilation excluded), Mitsuba ${options.mitsubaImages} independent images after a warm-up render (median wall time of mi.render, JIT excluded).`,
      'Variance per sample: ours n·SE² per pixel and channel, Mitsuba spp × the variance over its independent images, both averaged over pixels and channels. Equal-error time = (var_ours/var_Mitsuba)·(t_ours/t_Mitsuba) per path; ≤ 1 means we reach Mitsuba’s error in its time or less.',
      '"previous kernel": the plan without the one-medium kernels (oneHomogeneousMedium, oneGridMedium off: the general path tracer or single-scattering estimator), timed pass by pass alternating with the plan’s kernel; — where the plan does not use them.',
      '"dawn.node\'s busy poll": the plan’s kernel awaited as dawn.node does by itself (its main thread spins while SwiftShader works), instead of src/gpu/quietPolling.ts; same kernel, alternating.',
      'Process: the wall time of our `render` command (gpu-env.sh + node scripts/cli.mjs, the prebuilt bundle, as `npm run render` without npm) and of Mitsuba’s python (import, JIT, one render), same spp.',
      'Agreement: |z| of the image-mean difference (Mitsuba’s image is mirrored left–right by its look_at frame; the mean is not), each mean’s standard error from its pixels’ with the R, G, B errors added as fully correlated (exact for these gray scenes; bench/peerStatistics.ts).',
    ],
    rows,
  };
}
