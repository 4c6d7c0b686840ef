// The rayleigh-sky widget's kernels (shaders/kernels/rayleigh-sky.wesl), run through
// Dawn exactly as the widget dispatches them, against the float64 twin in
// src/widgets/rayleigh-sky/model.ts with the same N and M: the probe radiances,
// the direct-sun transmittance, and the panorama against the CPU fallback's shading.
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { shadeSky } from '../../src/widgets/rayleigh-sky/cpuBackend.ts';
import { computeProbesGpu, packParams } from '../../src/widgets/rayleigh-sky/gpuBackend.ts';
import {
  BETA_RAYLEIGH,
  computeProbes,
  distanceToTop,
  inputsFrom,
  sunDensityIntegral,
  sunTransmittance,
  type SkyInputs,
} from '../../src/widgets/rayleigh-sky/model.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

const KERNEL = 'kernels/rayleigh-sky.wesl';

function inputs(elevation: number, steps: number, scattering = 'on'): SkyInputs {
  return inputsFrom({ 'sun-elevation': elevation, scattering, steps, exposure: 0 });
}

/**
 * Relative tolerance of an f32 march against its float64 twin (physics.md §10).
 * Inputs (μ, ν, sin and cos of the sun) are the same f32 numbers on both sides, so
 * the difference is f32 evaluation only:
 *  - each density e^{−h/H}: WGSL exp is good to 3 + 2|x| ULP with |x| = h/H ≤ 7.5,
 *    i.e. 18 ULP ≈ 1.1e-6, plus the altitude h = q/(r_s + R) from a few roundings
 *    (≈ 4 ULP of h, times |x| ≤ 7.5 in the exponent): ≈ 3e-6 per sample;
 *  - the two density sums accumulate in f32 over N + M terms: ≤ (N + M)·2⁻²⁴
 *    relative (the terms are positive, so no cancellation);
 *  - T = e^{−τ} turns a relative error δ of τ into an absolute error τ·δ of the
 *    exponent, and exp adds (3 + 2τ) ULP: both scale with (1 + τ_max), τ_max the
 *    largest optical depth on the paths (blue through the grazing sun ray);
 *  - the final radiance sums N positive terms: another N·2⁻²⁴.
 * Budget: 4·(2N + M + 64)·2⁻²⁴·(1 + τ_max), the factor 4 for the per-sample
 * terms above; 2.6e-4 at N = 128, M = 32, τ_max = 10.
 */
function tolerance(input: SkyInputs, tauMax: number): number {
  return 4 * (2 * input.steps + input.sunSteps + 64) * 2 ** -24 * (1 + tauMax);
}

/** The largest optical depth in any exponent: the blue view path at 10° plus the sun path from the ground. */
function largestOpticalDepth(input: SkyInputs): number {
  const view = sunDensityIntegral(0, Math.sin((10 * Math.PI) / 180), 256) ?? 0;
  const sun = sunDensityIntegral(0, Math.max(input.sinSun, 0), 256) ?? 0;
  return BETA_RAYLEIGH[2] * (view + sun);
}

async function gpuProbes(input: SkyInputs) {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
  return computeProbesGpu(device, code, input);
}

describe('rayleigh-sky probe kernel vs the float64 twin with the same N and M', () => {
  const CASES: [number, number][] = [
    [60, 32],
    [30, 4],
    [20, 128],
    [2, 32],
    [2, 128],
    [0, 16],
    [-5, 32],
    [90, 64],
  ];
  for (const [elevation, steps] of CASES) {
    it(`sun at ${elevation}°, N = ${steps}: three probes and T_sun within the f32 budget`, async () => {
      const input = inputs(elevation, steps);
      const gpu = await gpuProbes(input);
      const cpu = computeProbes(input);
      const tol = tolerance(input, largestOpticalDepth(input));
      expect(gpu.capped).toBe(false);
      for (let k = 0; k < 3; k++)
        for (let c = 0; c < 3; c++) {
          const reference = cpu.radiance[k]![c]!;
          const value = gpu.radiance[k]![c]!;
          expect(Number.isFinite(value)).toBe(true);
          // Below the horizon (−5°) the low air is in the Earth's shadow; the
          // radiance is still positive from the lit high air.
          expect(reference).toBeGreaterThan(0);
          expect(Math.abs(value - reference) / reference, `probe ${k}, channel ${c}`).toBeLessThan(
            tol,
          );
        }
      for (let c = 0; c < 3; c++) {
        const reference = cpu.sunTransmittance[c]!;
        expect(Math.abs(gpu.sunTransmittance[c]! - reference)).toBeLessThanOrEqual(
          tol * Math.max(reference, 2 ** -126),
        );
      }
    });
  }

  it('the sun below the horizon has T_sun = 0 exactly on both sides (the ray hits the Earth)', async () => {
    const input = inputs(-2, 32);
    expect(distanceToTop(0, input.sinSun)).toBeNull();
    expect((await gpuProbes(input)).sunTransmittance).toEqual([0, 0, 0]);
    expect(sunTransmittance(input.sinSun, input.sunSteps, true)).toEqual([0, 0, 0]);
  });

  it('scattering off: the GPU sky is exactly black and the sun exactly white', async () => {
    const gpu = await gpuProbes(inputs(30, 32, 'off'));
    for (const l of gpu.radiance) expect(l).toEqual([0, 0, 0]);
    expect(gpu.sunTransmittance).toEqual([1, 1, 1]);
  });

  it('an N above the cap is reported as capped, not silently truncated', async () => {
    const input = { ...inputs(30, 128), steps: 200 };
    expect((await gpuProbes(input)).capped).toBe(true);
  });

  it('the GPU zenith is blue at noon and the GPU sun red at sunset', async () => {
    const noon = await gpuProbes(inputs(60, 32));
    expect(noon.radiance[0]![2] / noon.radiance[0]![0]).toBeGreaterThan(1);
    const sunset = await gpuProbes(inputs(2, 32));
    expect(sunset.sunTransmittance[0] / sunset.sunTransmittance[2]).toBeGreaterThan(1);
  });
});

const WIDTH = 192; // 4·192 bytes per row, a multiple of 256 as copyTextureToBuffer needs
const HEIGHT = 144;

/** Renders skyFragment into a WIDTH × HEIGHT rgba8unorm texture and reads it back. */
async function renderPicture(input: SkyInputs): Promise<Uint8Array> {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
  device.pushErrorScope('validation');
  const module = device.createShaderModule({ code });
  const pipeline = device.createRenderPipeline({
    layout: 'auto',
    vertex: { module, entryPoint: 'fullScreenVertex' },
    fragment: { module, entryPoint: 'skyFragment', targets: [{ format: 'rgba8unorm' }] },
    primitive: { topology: 'triangle-list' },
  });
  const texture = device.createTexture({
    size: [WIDTH, HEIGHT],
    format: 'rgba8unorm',
    usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC,
  });
  const uniform = device.createBuffer({
    size: 64,
    usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
  });
  device.queue.writeBuffer(uniform, 0, packParams(input, WIDTH, HEIGHT));
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

describe('rayleigh-sky panorama: the fragment shader vs the CPU fallback’s float64 shading', () => {
  for (const [elevation, scattering] of [
    [30, 'on'],
    [2, 'on'],
    [30, 'off'],
  ] as const) {
    it(`sun at ${elevation}°, scattering ${scattering}`, async () => {
      const input = inputs(elevation, 16, scattering);
      const gpu = await renderPicture(input);
      const sun = sunTransmittance(input.sinSun, input.sunSteps, input.scattering);
      let far = 0;
      for (let row = 0; row < HEIGHT; row++)
        for (let column = 0; column < WIDTH; column++) {
          const rgb = shadeSky(column + 0.5, row + 0.5, WIDTH, HEIGHT, input, sun);
          for (let c = 0; c < 3; c++) {
            const difference = Math.abs(
              gpu[4 * (row * WIDTH + column) + c]! - Math.round(255 * rgb[c]!),
            );
            if (difference > 2) far += 1;
          }
        }
      // Away from edges both agree to an 8-bit rounding: the radiance differs by the
      // f32 budget above (< 1e-3), and WGSL sin/cos of the pixel angles (2⁻¹¹
      // absolute) move the view direction by < 0.03°, a tenth of a pixel here. At the
      // horizon line and the sun disc's antialiased edge that tenth of a pixel moves
      // coverage: budget 1% of channels more than 2/255 apart.
      expect(far / (3 * WIDTH * HEIGHT)).toBeLessThan(0.01);
    });
  }
});
