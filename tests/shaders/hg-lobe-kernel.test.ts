// The hg-lobe widget's sampling kernel (shaders/kernels/hg-lobe.wesl), run through
// Dawn exactly as the widget dispatches it, against the widget's float64 replay of
// the same PCG streams, and against the closed form of the HG cosine distribution.
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { sampleHistogramCpu, shadeLobe } from '../../src/widgets/hg-lobe/cpuBackend.ts';
import { packParams, sampleHistogramGpu } from '../../src/widgets/hg-lobe/gpuBackend.ts';
import {
  chiSquareTest,
  hgBinProbabilities,
  meanCosine,
  polarLayout,
  type HgLobeInputs,
} from '../../src/widgets/hg-lobe/model.ts';
import { hgEval } from '../../src/reference/phase.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

function inputs(g: number, samplesExponent: number, seed: number): HgLobeInputs {
  return {
    g: Math.fround(g),
    compare: 'isotropic',
    scale: 'linear',
    samplesExponent,
    sampleCount: 2 ** samplesExponent,
    seed,
  };
}

// Linked once per file, and each (g, N, seed) sampled once: the chi-square and the
// mean-cosine tests read two different statistics of the same 2^18 samples, which is
// as valid as two draws and halves the file's GPU work on a software adapter.
let linked: Promise<string> | undefined;
const histograms = new Map<string, ReturnType<typeof sampleHistogramGpu>>();
async function gpuHistogram(input: HgLobeInputs) {
  const key = `${input.g}/${input.sampleCount}/${input.seed}`;
  let histogram = histograms.get(key);
  if (!histogram) {
    linked ??= linkLibraryKernel(SHADER_LIBRARY, 'kernels/hg-lobe.wesl');
    const [device, code] = await Promise.all([nodeDevice(), linked]);
    histogram = sampleHistogramGpu(device, code, input, polarLayout(input, 960, 480));
    histograms.set(key, histogram);
  }
  return histogram;
}

// Asymmetries of chapter 3 and the extremes the widget allows.
const G_VALUES = [-0.99, -0.3, 0, 0.6, 0.9, 0.99];
// Bonferroni: one chi-square test per g value at a family-wise α = 0.01.
const ALPHA = 0.01 / G_VALUES.length;

describe('hg-lobe sampling kernel vs the widget’s float64 replay', () => {
  for (const g of G_VALUES) {
    it(`g = ${g}: the GPU histogram equals the twin's, bin for bin, up to f32 ties at bin edges`, async () => {
      const input = inputs(g, 16, 7);
      const gpu = await gpuHistogram(input);
      const cpu = sampleHistogramCpu(input.g, input.sampleCount, input.seed);
      expect(gpu.bins.reduce((a, b) => a + b, 0)).toBe(input.sampleCount);
      // Same ξ bit for bit; μ differs by f32 rounding (≤ ~3e-7 absolute, physics.md
      // §2.4), which moves a sample to the neighbouring bin only within ~1e-5 of an
      // edge: a few samples in 10⁵. Each moved sample changes two bins by one.
      let moved = 0;
      for (let k = 0; k < gpu.bins.length; k++) moved += Math.abs(gpu.bins[k]! - cpu.bins[k]!);
      expect(moved / 2).toBeLessThanOrEqual(1e-3 * input.sampleCount);
      // Σμ: the f32 partial sums of 256 samples each carry ≲ 8 ulps of rounding
      // (tree reduction) plus the per-sample μ error; 1e-5 of N bounds both with margin.
      expect(Math.abs(gpu.sumMu - cpu.sumMu)).toBeLessThan(1e-5 * input.sampleCount);
    });
  }
});

describe('the GPU sampler draws the HG distribution (physics.md §2.4)', () => {
  for (const g of G_VALUES) {
    it(`g = ${g}: chi-square of 2^18 GPU samples in 64 bins passes at α = 0.01/${G_VALUES.length}`, async () => {
      const input = inputs(g, 18, 11);
      const gpu = await gpuHistogram(input);
      const test = chiSquareTest(gpu.bins, hgBinProbabilities(input.g), input.sampleCount, ALPHA);
      expect(test.pValue, `χ² = ${test.statistic}, df = ${test.df}`).toBeGreaterThan(ALPHA);
    });

    it(`g = ${g}: the GPU mean cosine is g within 5 standard errors (physics.md §2.2, ⟨μ⟩ = g)`, async () => {
      const input = inputs(g, 18, 11);
      const stats = meanCosine(await gpuHistogram(input), input.g);
      expect(Math.abs(stats.zScore)).toBeLessThan(5);
    });
  }

  it('a sign error in the convention would fail: g = 0.6 samples are not distributed as g = −0.6', async () => {
    const input = inputs(0.6, 16, 3);
    const gpu = await gpuHistogram(input);
    const mirrored = chiSquareTest(
      gpu.bins,
      hgBinProbabilities(Math.fround(-0.6)),
      input.sampleCount,
    );
    expect(mirrored.passes).toBe(false);
  });
});

const WIDTH = 960;
const HEIGHT = 480;

/** Renders lobeFragment into a 960×480 rgba8unorm texture and reads it back. */
async function renderPicture(input: HgLobeInputs): Promise<Uint8Array> {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, 'kernels/hg-lobe.wesl');
  device.pushErrorScope('validation');
  const module = device.createShaderModule({ code });
  const pipeline = device.createRenderPipeline({
    layout: 'auto',
    vertex: { module, entryPoint: 'fullScreenVertex' },
    fragment: { module, entryPoint: 'lobeFragment', targets: [{ format: 'rgba8unorm' }] },
    primitive: { topology: 'triangle-list' },
  });
  const texture = device.createTexture({
    size: [WIDTH, HEIGHT],
    format: 'rgba8unorm',
    usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC,
  });
  const uniform = device.createBuffer({
    size: 48,
    usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
  });
  device.queue.writeBuffer(uniform, 0, packParams(input, polarLayout(input, WIDTH, HEIGHT)));
  const readBack = device.createBuffer({
    size: WIDTH * HEIGHT * 4,
    usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
  });
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginRenderPass({
    colorAttachments: [{ view: texture.createView(), loadOp: 'clear', storeOp: 'store' }],
  });
  pass.setPipeline(pipeline);
  pass.setBindGroup(
    0,
    device.createBindGroup({
      layout: pipeline.getBindGroupLayout(0),
      entries: [{ binding: 1, resource: { buffer: uniform } }],
    }),
  );
  pass.draw(3);
  pass.end();
  encoder.copyTextureToBuffer({ texture }, { buffer: readBack, bytesPerRow: WIDTH * 4 }, [
    WIDTH,
    HEIGHT,
  ]);
  device.queue.submit([encoder.finish()]);
  const error = await device.popErrorScope();
  expect(error?.message ?? null).toBeNull();
  await readBack.mapAsync(GPUMapMode.READ);
  const pixels = new Uint8Array(readBack.getMappedRange().slice(0));
  readBack.unmap();
  for (const buffer of [readBack, uniform]) buffer.destroy();
  texture.destroy();
  return pixels;
}

describe('hg-lobe picture: the fragment shader vs the CPU fallback’s float64 shading', () => {
  const PICTURES: [string, HgLobeInputs][] = [
    ['g = 0.6, linear, isotropic outline', inputs(0.6, 16, 1)],
    ['g = 0.9, log radius, isotropic outline', { ...inputs(0.9, 16, 1), scale: 'log' }],
    ['g = −0.3, linear, Rayleigh outline', { ...inputs(-0.3, 16, 1), compare: 'rayleigh' }],
    ['g = 0, log radius, no outline', { ...inputs(0, 16, 1), scale: 'log', compare: 'none' }],
  ];
  for (const [name, input] of PICTURES) {
    it(name, async () => {
      const gpu = await renderPicture(input);
      const layout = polarLayout(input, WIDTH, HEIGHT);
      let far = 0;
      let total = 0;
      for (let row = 0; row < HEIGHT; row++)
        for (let column = 0; column < WIDTH; column++) {
          const rgb = shadeLobe(column + 0.5, row + 0.5, input, layout);
          let worst = 0;
          for (let c = 0; c < 3; c++) {
            const difference = Math.abs(
              gpu[4 * (row * WIDTH + column) + c]! - Math.round(255 * rgb[c]!),
            );
            worst = Math.max(worst, difference);
            total += difference;
          }
          if (worst > 2) far += 1;
        }
      // Both are rounded to 8 bits, so away from edges they agree exactly. At an
      // antialiased edge the coverage moves by (f32 error of the distance)/(1 px):
      // WGSL's atan2, sin and log2 carry errors of ~1e-6 relative (2^-11 absolute for
      // sin), which flips an 8-bit rounding on a handful of pixels. Budget: 0.1% of
      // pixels more than 2/255 apart, and a mean difference under 0.01/255 per channel
      // (observed ≈ 1e-4: a few hundred ±1 roundings in 1.4 million channels).
      expect(far / (WIDTH * HEIGHT)).toBeLessThan(1e-3);
      expect(total / (3 * WIDTH * HEIGHT)).toBeLessThan(0.01);
      // The picture is not blank: the lobe's fill colour appears on the forward (g ≥ 0)
      // or backward (g < 0) axis at half the lobe's radius.
      const side = input.g >= 0 ? 1 : -1;
      const peak = hgEval(input.g, side);
      const half =
        0.5 *
        layout.pixelsPerUnit *
        (input.scale === 'log' ? Math.log10(peak) - layout.logFloor : peak);
      const column = Math.round(layout.centreX + side * half);
      const row = Math.round(layout.centreY + 20);
      const offset = 4 * (row * WIDTH + column);
      expect(gpu[offset]!).toBeGreaterThan(gpu[offset + 2]! + 40);
    });
  }
});
