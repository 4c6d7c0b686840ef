// Progressive accumulation on the GPU (src/scene/gpuAccumulation.ts with
// shaders/kernels/scene-accumulate.wesl and scene-statistics.wesl) and its float64 twin
// (src/scene/accumulation.ts), through Dawn:
//  - the pairwise (Chan) update equals the two-pass mean and variance of the raw samples;
//  - passes of any size add up to the same image (the kernel replays the same samples),
//    within f32 rounding;
//  - 1024 passes of values with s/mean = 3·10⁻⁴ keep mean and variance, where naive f32
//    sums of x and x² would lose the variance entirely;
//  - the reduction kernel's statistics equal the float64 twin's on the read-back image,
//    with a mask and against a reference.
import { beforeAll, describe, expect, it } from 'vitest';
import {
  ImageAccumulator,
  imageStatistics,
  PASS_WORDS_PER_PIXEL,
  type ImageStatistics,
} from '../../src/scene/accumulation.ts';
import { GpuAccumulation } from '../../src/scene/gpuAccumulation.ts';
import { GpuSceneRenderer } from '../../src/scene/gpuRenderer.ts';
import { packScene } from '../../src/scene/pack.ts';
import { plan } from '../../src/scene/plan.ts';
import { renderScene } from '../../src/scene/renderScene.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { exampleScene } from '../support/sceneRender.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

let device: GPUDevice;
beforeAll(async () => {
  device = await nodeDevice();
}, 60_000);

const GPU_TIMEOUT = 180_000;

/** Pass sums (PASS_WORDS_PER_PIXEL words per pixel) of `samples[pixel][k]` (one channel, copied to all three). */
function passSums(values: number[][], f32 = false): Float32Array | Float64Array {
  const out = f32
    ? new Float32Array(PASS_WORDS_PER_PIXEL * values.length)
    : new Float64Array(PASS_WORDS_PER_PIXEL * values.length);
  values.forEach((pixel, i) => {
    let sum = 0;
    let squares = 0;
    for (const x of pixel) {
      sum += x;
      squares += x * x;
    }
    for (let c = 0; c < 3; c++) {
      out[PASS_WORDS_PER_PIXEL * i + c] = sum;
      out[PASS_WORDS_PER_PIXEL * i + 3 + c] = squares;
    }
  });
  return out;
}

/** Adds synthetic passes to a GPU accumulation through its accumulate kernel. */
async function addOnGpu(
  accumulation: GpuAccumulation,
  passes: { sums: Float32Array<ArrayBuffer>; samples: number }[],
): Promise<void> {
  const input = device.createBuffer({
    size: passes[0]!.sums.byteLength,
    usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST,
  });
  for (const pass of passes) {
    // One submit per pass: the accumulate kernel's parameters are written per pass.
    device.queue.writeBuffer(input, 0, pass.sums);
    const encoder = device.createCommandEncoder();
    const compute = encoder.beginComputePass();
    accumulation.encodeAdd(compute, input, pass.samples);
    compute.end();
    device.queue.submit([encoder.finish()]);
  }
  await device.queue.onSubmittedWorkDone();
  input.destroy();
}

const relative = (a: number, b: number): number => Math.abs(a - b) / Math.max(Math.abs(b), 1e-30);

describe('progressive accumulation', () => {
  it('the float64 pairwise update equals the two-pass mean and variance of the samples', () => {
    const samples = [0.3, 2.5, 1.25, 0.0, 7.5, 3.125, 0.5, 4.0, 1.0, 2.0];
    const accumulator = new ImageAccumulator(1, 1);
    // Passes of 1, 3, 2 and 4 samples.
    let start = 0;
    for (const size of [1, 3, 2, 4]) {
      const pass = samples.slice(start, start + size);
      accumulator.addPass(passSums([pass]), passSums([pass]), size);
      start += size;
    }
    const n = samples.length;
    const mean = samples.reduce((a, b) => a + b, 0) / n;
    const variance = samples.reduce((a, x) => a + (x - mean) ** 2, 0) / (n - 1);
    expect(accumulator.samples).toBe(n);
    expect(accumulator.mean()[0]).toBeCloseTo(mean, 14);
    expect(accumulator.standardError()[1]).toBeCloseTo(Math.sqrt(variance / n), 14);
  });

  it(
    'f32 moments on the GPU keep the variance over 1024 passes where s/mean = 3e-4',
    async () => {
      // Two pixels: x = 1000 + 0.3·t with t in {−1, 1} alternating (exact in f32), and a
      // pixel that sees the same values in passes of 4.
      const accumulation = await GpuAccumulation.create(device, SHADER_LIBRARY, 2, 1);
      const passes: { sums: Float32Array<ArrayBuffer>; samples: number }[] = [];
      const value = (k: number): number => 1000 + 0.3 * (k % 2 === 0 ? -1 : 1);
      for (let k = 0; k < 1024; k++)
        passes.push({
          sums: passSums([[value(k)], [value(k)]], true) as Float32Array<ArrayBuffer>,
          samples: 1,
        });
      await addOnGpu(accumulation, passes);
      const image = await accumulation.readImage();
      const n = 1024;
      const exactMean = 1000;
      const exactVariance = (0.3 ** 2 * n) / (n - 1);
      expect(image.samples).toBe(n);
      expect(relative(image.mean()[0]!, exactMean)).toBeLessThan(1e-6);
      expect(relative(image.standardError()[0]! ** 2 * n, exactVariance)).toBeLessThan(0.02);
      // Naive f32 sums lose it: Σx² − n·mean² cancels 7 digits away (a check that the
      // case is hard, not a test of the renderer).
      let sum = Math.fround(0);
      let squares = Math.fround(0);
      for (let k = 0; k < n; k++) {
        sum = Math.fround(sum + value(k));
        squares = Math.fround(squares + Math.fround(value(k) * value(k)));
      }
      const naive = (squares - (sum * sum) / n) / (n - 1);
      expect(relative(naive, exactVariance)).toBeGreaterThan(0.5);
      accumulation.destroy();
    },
    GPU_TIMEOUT,
  );

  it(
    'passes of any size add up to the same GPU image (the same samples) within f32 rounding',
    async () => {
      const scene = await exampleScene('fog-slab', { image: { width: 12, height: 9 } });
      const backend = { kind: 'gpu' as const, device, library: SHADER_LIBRARY };
      const whole = await renderScene(scene, backend, { spp: 16, samplesPerPass: 16 });
      const passes = await renderScene(scene, backend, { spp: 16, samplesPerPass: 3 });
      expect(passes.passes.map((p) => p.samples)).toEqual([3, 3, 3, 3, 3, 1]);
      const a = whole.accumulator;
      const b = passes.accumulator;
      expect(b.samples).toBe(16);
      expect(b.lookups).toBe(a.lookups);
      const meanA = a.mean();
      const meanB = b.mean();
      const seA = a.standardError();
      const seB = b.standardError();
      for (let k = 0; k < meanA.length; k++) {
        expect(Math.abs(meanB[k]! - meanA[k]!)).toBeLessThanOrEqual(
          1e-5 * Math.abs(meanA[k]!) + 1e-30,
        );
        expect(Math.abs(seB[k]! - seA[k]!)).toBeLessThanOrEqual(
          1e-3 * seA[k]! + 1e-6 * Math.abs(meanA[k]!),
        );
      }
    },
    GPU_TIMEOUT,
  );

  it(
    'the reduction kernel equals the float64 statistics of the read-back image',
    async () => {
      const scene = await exampleScene('smoke-spotlight', { image: { width: 20, height: 15 } });
      const packed = packScene(scene);
      const conditions = plan(scene.scene).conditions;
      const image = await GpuSceneRenderer.create(device, SHADER_LIBRARY, packed, conditions);
      const reference = await GpuSceneRenderer.create(
        device,
        SHADER_LIBRARY,
        { ...packed, seed: packed.seed + 1 },
        conditions,
      );
      try {
        const mask = Uint8Array.from({ length: 20 * 15 }, (_, i) => (i % 7 < 3 ? 1 : 0));
        image.accumulation.setMask(mask);
        await image.renderPass(0, 4);
        // A snapshot is a frozen copy: later passes do not change it.
        const early = await image.accumulation.readImage();
        const snapshot = image.accumulation.snapshot();
        for (let k = 1; k < 3; k++) await image.renderPass(4 * k, 4);
        await reference.renderPass(0, 8);
        const frozen = await snapshot.readImage();
        expect(frozen.samples).toBe(4);
        expect(Array.from(frozen.mean())).toEqual(Array.from(early.mean()));
        expect(frozen.lookups).toBe(early.lookups);
        const frozenStats = await snapshot.statistics(reference.accumulation);
        const frozenTwin = imageStatistics(early, await reference.accumulation.readImage(), mask);
        expect(relative(frozenStats.maskedLuminance, frozenTwin.maskedLuminance)).toBeLessThan(
          1e-4,
        );
        expect(relative(frozenStats.rmse, frozenTwin.rmse)).toBeLessThan(1e-4);
        snapshot.destroy();
        const onGpu = await image.accumulation.statistics(reference.accumulation);
        const host = await image.accumulation.readImage();
        const twin = imageStatistics(host, await reference.accumulation.readImage(), mask);
        const close = (key: keyof ImageStatistics, tolerance: number): void => {
          const g = onGpu[key];
          const t = twin[key];
          expect(Number.isFinite(t), key).toBe(true);
          expect(relative(g, t), `${key}: GPU ${g}, twin ${t}`).toBeLessThan(tolerance);
        };
        expect(onGpu.samples).toBe(12);
        expect(onGpu.lookups).toBe(twin.lookups);
        expect(onGpu.capped).toBe(twin.capped);
        for (const key of [
          'meanRadiance',
          'meanStandardError',
          'rmsStandardError',
          'maxPixelStandardError',
          'maskedLuminance',
          'rmse',
        ] as const)
          close(key, 1e-4);
        // The plain statistics (no reference) agree too, and say there is none.
        const alone = await image.accumulation.statistics();
        expect(alone.rmse).toBeNaN();
        expect(relative(alone.meanRadiance, twin.meanRadiance)).toBeLessThan(1e-4);
      } finally {
        image.destroy();
        reference.destroy();
      }
    },
    GPU_TIMEOUT,
  );
});
