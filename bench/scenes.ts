// Benchmark: what specialization saves. Every example scene (public/scenes/) is rendered
// on the GPU (Dawn; SwiftShader without a GPU) twice, same seeds and samples: with the
// kernel its plan links (src/scene/plan.ts) and with the general kernel (every effect,
// tracking everywhere, the path tracer with the order read at run time). The table gives
// the time per sample per pixel over the image and per path sample (median over passes,
// GPU timestamps where the device has them, after a warm-up pass; compilation excluded),
// the time saving (general ÷ specialized) and the saving at equal error (per-sample
// variance × time), the linked kernel sizes, density lookups per
// sample, the float64 twin's time per path sample on the CPU, and whether the two GPU
// images agree (the largest |z| of the image-mean difference per channel).
import { fileURLToPath } from 'node:url';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { GpuSceneRenderer } from '../src/scene/gpuRenderer.ts';
import { resolveScene, type ResolvedScene } from '../src/scene/load.ts';
import { nodeFileReader } from '../src/scene/loadNode.ts';
import { packScene } from '../src/scene/pack.ts';
import { GENERAL_CONDITIONS, plan, type Conditions } from '../src/scene/plan.ts';
import { renderScene } from '../src/scene/renderScene.ts';
import { parseScene } from '../src/scene/validate.ts';
import { readFileSync } from 'node:fs';
import { median, type BenchTable } from './table.ts';

const SCENES = [
  'fog-slab',
  'emissive-smoke',
  'smoke-spotlight',
  'cloud-sky',
  'white-furnace',
  'rayleigh-haze',
  'spheres-on-floor',
  'mie-fog',
];

interface Timed {
  nsPerPathSample: number;
  msPerSppImage: number;
  timing: string;
  lookupsPerSample: number;
  mean: number[];
  meanVariance: number[];
  /** Per-sample variance averaged over pixels and channels (n·SE²). */
  sampleVariance: number;
  lines: number;
}

/**
 * Times two kernels on the same scene pass by pass, alternating, so that a change in the
 * machine's load during the run affects both alike.
 */
async function timeKernels(
  device: GPUDevice,
  resolved: ResolvedScene,
  kernels: readonly Conditions[],
  spp: number,
  samplesPerPass: number,
): Promise<Timed[]> {
  const library = loadShaderLibrary(fileURLToPath(new URL('../shaders', import.meta.url)));
  const packed = packScene(resolved);
  const renderers: GpuSceneRenderer[] = [];
  try {
    for (const conditions of kernels)
      renderers.push(await GpuSceneRenderer.create(device, library, packed, conditions));
    // Warm-up: the first dispatch of a pipeline pays for caches and thread start-up.
    for (const renderer of renderers) {
      await renderer.renderPass(0, samplesPerPass);
      renderer.accumulation.reset();
    }
    const pixels = packed.width * packed.height;
    const times: number[][] = renderers.map(() => []);
    let timing = 'none';
    for (let offset = 0; offset < spp; offset += samplesPerPass) {
      const samples = Math.min(samplesPerPass, spp - offset);
      for (let k = 0; k < renderers.length; k++) {
        const output = await renderers[k]!.renderPass(offset, samples);
        times[k]!.push(output.milliseconds / samples);
        timing = output.timing ?? renderers[k]!.timing;
      }
    }
    const images = await Promise.all(renderers.map((r) => r.accumulation.readImage()));
    return renderers.map((renderer, k) => {
      const acc = images[k]!;
      const mean = acc.mean();
      const se = acc.standardError();
      const channel = (values: Float64Array, square: boolean) =>
        [0, 1, 2].map((c) => {
          let sum = 0;
          for (let i = 0; i < pixels; i++)
            sum += square ? values[3 * i + c]! ** 2 : values[3 * i + c]!;
          return sum / (square ? pixels * pixels : pixels);
        });
      let variance = 0;
      for (const e of se) variance += e * e * acc.samples;
      const msPerSppImage = median(times[k]!);
      return {
        nsPerPathSample: (1e6 * msPerSppImage) / pixels,
        msPerSppImage,
        timing,
        lookupsPerSample: acc.lookups / (acc.samples * pixels),
        mean: channel(mean, false),
        meanVariance: channel(se, true),
        sampleVariance: variance / se.length,
        lines: renderer.code.split('\n').length,
      };
    });
  } finally {
    for (const renderer of renderers) renderer.destroy();
  }
}

export async function benchScenes(
  device: GPUDevice,
  options: {
    size: number;
    spp: number;
    samplesPerPass: number;
    cpuSpp: number;
    /** A subset of the example scenes (all when absent or empty). */
    only?: readonly string[];
  },
): Promise<BenchTable> {
  const rows: BenchTable['rows'] = [];
  const names = options.only?.length ? SCENES.filter((s) => options.only?.includes(s)) : SCENES;
  for (const name of names) {
    const json = JSON.parse(
      readFileSync(new URL(`../public/scenes/${name}.json`, import.meta.url), 'utf8'),
    ) as Record<string, unknown>;
    const image = json.image as { width: number; height: number };
    const scale = options.size / Math.max(image.width, image.height);
    const size = {
      width: Math.max(1, Math.round(image.width * scale)),
      height: Math.max(1, Math.round(image.height * scale)),
    };
    json.image = size;
    const resolved = await resolveScene(parseScene(json), nodeFileReader);
    const scenePlan = plan(resolved.scene);
    const [specialized, general] = (await timeKernels(
      device,
      resolved,
      [scenePlan.conditions, GENERAL_CONDITIONS],
      options.spp,
      options.samplesPerPass,
    )) as [Timed, Timed];
    const z = specialized.mean.map(
      (m, c) =>
        Math.abs(m - general.mean[c]!) /
        Math.sqrt(specialized.meanVariance[c]! + general.meanVariance[c]! || 1),
    );
    const cpuStart = performance.now();
    const cpu = await renderScene(resolved, { kind: 'cpu' }, { spp: options.cpuSpp });
    const cpuNs =
      (1e6 * (performance.now() - cpuStart)) /
      (options.cpuSpp * cpu.accumulator.width * cpu.accumulator.height);
    rows.push({
      scene: name,
      image: `${size.width}×${size.height}`,
      integrator: scenePlan.integrator,
      'WGSL lines specialized/general': `${specialized.lines}/${general.lines}`,
      [`specialized ms/spp (${specialized.timing})`]: specialized.msPerSppImage,
      'general ms/spp': general.msPerSppImage,
      'specialized ns/path sample': specialized.nsPerPathSample,
      'general ns/path sample': general.nsPerPathSample,
      'time saving (general ÷ specialized)': general.msPerSppImage / specialized.msPerSppImage,
      'efficiency gain (var×time, general ÷ specialized)':
        (general.sampleVariance * general.msPerSppImage) /
        (specialized.sampleVariance * specialized.msPerSppImage),
      'lookups/sample specialized/general': `${specialized.lookupsPerSample.toFixed(1)}/${general.lookupsPerSample.toFixed(1)}`,
      'CPU twin ns/path sample': cpuNs,
      'agreement max |z| (image mean)': Math.max(...z),
    });
  }
  return {
    title: 'Scenes: specialized vs general kernel (GPU), and the CPU twin',
    notes: [
      `Each example scene at ${options.size} px on its long side, ${options.spp} spp in passes of ${options.samplesPerPass}; times are medians over passes after a warm-up pass (compilation excluded).`,
      'ms/spp: milliseconds per sample per pixel over the whole image; ns/path sample: that divided by the pixels.',
      'Time saving = general ÷ specialized time per sample; the two kernels run pass by pass, alternating. Efficiency gain = general ÷ specialized (per-sample variance × time per sample), the saving at equal error: the specialized estimators differ (closed forms, equiangular points, reservoir-chosen scattering points), so a kernel can cost more per sample and still win. Both render the same number of samples from the same seeds and must agree within Monte Carlo error (|z| < 5).',
      `CPU twin: float64, one thread, ${options.cpuSpp} spp, wall time including JavaScript overheads.`,
    ],
    rows,
  };
}
