// Runs shaders/volume.wesl's volumeRaymarch on the GPU (Dawn) for a list of rays
// through one density grid, for tests/shaders/volume.test.ts. The grid's samples
// are an r32float 3D texture, which the table harness cannot bind, so this
// dispatch creates the texture and binds it through an explicit layout (as
// tests/support/densityGridGpu.ts does for the medium module).
import { gpuCore } from '../../src/gpu/core.ts';
import { withErrorScopes } from '../../src/gpu/errors.ts';
import { linkKernel } from '../../src/gpu/link.ts';
import type { DensityGridData, Vec3 } from '../../src/reference/medium.ts';
import {
  packTransferFunction,
  TRANSFER_FUNCTION_WORDS,
  type TransferFunction,
  type VolumeMarchResult,
} from '../../src/reference/volume.ts';
import { nodeDevice } from './nodeGpu.ts';
import { SHADER_LIBRARY } from './shaderLibrary.ts';

const KERNEL = `
import package::medium::DensityGrid;
import package::volume::{TransferFunction, volumeRaymarch};

struct MarchSetup {
  dimensions: vec3u,
  valueOffset: f32,
  boundsMin: vec3f,
  densityScale: f32,
  boundsMax: vec3f,
  referenceStep: f32,
}
@group(0) @binding(0) var<uniform> setup: MarchSetup;
@group(0) @binding(1) var<uniform> tf: TransferFunction;
@group(0) @binding(2) var<storage, read> rays: array<f32>;
@group(0) @binding(3) var<storage, read_write> outputs: array<u32>;
@group(0) @binding(4) var volume: texture_3d<f32>;

@compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (8u * i >= arrayLength(&outputs)) { return; }
  let o = 8u * i;
  let grid = DensityGrid(setup.dimensions, setup.boundsMin, setup.boundsMax, setup.densityScale);
  let r = volumeRaymarch(grid, volume, setup.valueOffset, tf, setup.referenceStep,
    vec3f(rays[o], rays[o + 1u], rays[o + 2u]), vec3f(rays[o + 3u], rays[o + 4u], rays[o + 5u]),
    rays[o + 6u], rays[o + 7u]);
  outputs[o] = bitcast<u32>(r.color.x);
  outputs[o + 1u] = bitcast<u32>(r.color.y);
  outputs[o + 2u] = bitcast<u32>(r.color.z);
  outputs[o + 3u] = bitcast<u32>(r.transmittance);
  outputs[o + 4u] = r.steps;
  outputs[o + 5u] = r.plannedSteps;
  outputs[o + 6u] = r.terminated;
  outputs[o + 7u] = r.capped;
}
`;

export interface MarchRay {
  origin: Vec3;
  direction: Vec3;
  stepSize: number;
  threshold: number;
}

/** A ray as the GPU sees it (f32 components). */
export function f32MarchRay(ray: MarchRay): MarchRay {
  const f = Math.fround;
  return {
    origin: [f(ray.origin[0]), f(ray.origin[1]), f(ray.origin[2])],
    direction: [f(ray.direction[0]), f(ray.direction[1]), f(ray.direction[2])],
    stepSize: f(ray.stepSize),
    threshold: f(ray.threshold),
  };
}

/** A transfer function as the GPU sees it (f32 values, colours and opacities). */
export function f32TransferFunction(tf: TransferFunction): TransferFunction {
  const f = Math.fround;
  return {
    count: tf.count,
    values: tf.values.map(f),
    rgba: tf.rgba.map((q) => [f(q[0]), f(q[1]), f(q[2]), f(q[3])] as const),
  };
}

let pipeline: Promise<{ layout: GPUBindGroupLayout; pipeline: GPUComputePipeline }> | null = null;

async function marchPipeline(device: GPUDevice) {
  pipeline ??= (async () => {
    const code = await linkKernel(SHADER_LIBRARY, KERNEL);
    const layout = device.createBindGroupLayout({
      entries: [
        { binding: 0, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } },
        { binding: 1, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } },
        { binding: 2, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'read-only-storage' } },
        { binding: 3, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'storage' } },
        {
          binding: 4,
          visibility: GPUShaderStage.COMPUTE,
          texture: { sampleType: 'unfilterable-float', viewDimension: '3d' },
        },
      ],
    });
    const core = gpuCore(device);
    const made = await withErrorScopes(device, 'volume march kernel', () =>
      core.computePipeline({ code, entryPoint: 'main', layout: core.pipelineLayout([layout]) }),
    );
    return { layout, pipeline: made };
  })();
  return pipeline;
}

/** volumeRaymarch on the GPU for each ray. */
export async function gpuVolumeRaymarch(
  data: DensityGridData,
  valueOffset: number,
  tf: TransferFunction,
  referenceStep: number,
  rays: readonly MarchRay[],
): Promise<VolumeMarchResult[]> {
  const device = await nodeDevice();
  const { layout, pipeline: compute } = await marchPipeline(device);
  const setup = new ArrayBuffer(48);
  const setupU32 = new Uint32Array(setup);
  const setupF32 = new Float32Array(setup);
  data.grid.dimensions.forEach((n, a) => (setupU32[a] = n >>> 0));
  setupF32[3] = valueOffset;
  data.grid.boundsMin.forEach((v, a) => (setupF32[4 + a] = v));
  setupF32[7] = data.grid.densityScale;
  data.grid.boundsMax.forEach((v, a) => (setupF32[8 + a] = v));
  setupF32[11] = referenceStep;
  const tfWords = packTransferFunction(tf, new Uint32Array(TRANSFER_FUNCTION_WORDS));
  const rayData = new Float32Array(Math.max(8 * rays.length, 8));
  rays.forEach((r, i) =>
    rayData.set([...r.origin, ...r.direction, r.stepSize, r.threshold], 8 * i),
  );
  const outputBytes = 32 * rays.length;
  const [nx, ny, nz] = data.grid.dimensions.map((n) => Math.max(n, 1)) as [number, number, number];
  const made: (GPUBuffer | GPUTexture)[] = [];
  const buffer = (source: ArrayBufferView | null, size: number, usage: number): GPUBuffer => {
    const b = device.createBuffer({ size: Math.ceil(size / 16) * 16, usage });
    if (source) device.queue.writeBuffer(b, 0, source.buffer, source.byteOffset, source.byteLength);
    made.push(b);
    return b;
  };
  try {
    const readBack = await withErrorScopes(device, 'volume march', () => {
      const texture = device.createTexture({
        size: [nx, ny, nz],
        dimension: '3d',
        format: 'r32float',
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
      });
      made.push(texture);
      const samples = new Float32Array(nx * ny * nz);
      if (data.volume.length === samples.length) samples.set(data.volume);
      device.queue.writeTexture({ texture }, samples, { bytesPerRow: nx * 4, rowsPerImage: ny }, [
        nx,
        ny,
        nz,
      ]);
      const UNIFORM = GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST;
      const output = buffer(null, outputBytes, GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC);
      const read = buffer(null, outputBytes, GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST);
      const bindGroup = device.createBindGroup({
        layout,
        entries: [
          { binding: 0, resource: { buffer: buffer(setupU32, 48, UNIFORM) } },
          { binding: 1, resource: { buffer: buffer(tfWords, tfWords.byteLength, UNIFORM) } },
          {
            binding: 2,
            resource: {
              buffer: buffer(
                rayData,
                rayData.byteLength,
                GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST,
              ),
            },
          },
          { binding: 3, resource: { buffer: output, size: outputBytes } },
          { binding: 4, resource: texture.createView() },
        ],
      });
      const encoder = device.createCommandEncoder();
      const pass = encoder.beginComputePass();
      pass.setPipeline(compute);
      pass.setBindGroup(0, bindGroup);
      pass.dispatchWorkgroups(Math.ceil(rays.length / 64));
      pass.end();
      encoder.copyBufferToBuffer(output, 0, read, 0, outputBytes);
      device.queue.submit([encoder.finish()]);
      return read;
    });
    await readBack.mapAsync(GPUMapMode.READ);
    const words = new Uint32Array(readBack.getMappedRange().slice(0, outputBytes));
    readBack.unmap();
    const floats = new Float32Array(words.buffer);
    return rays.map((_, i) => ({
      color: [floats[8 * i]!, floats[8 * i + 1]!, floats[8 * i + 2]!],
      transmittance: floats[8 * i + 3]!,
      steps: words[8 * i + 4]!,
      plannedSteps: words[8 * i + 5]!,
      terminated: words[8 * i + 6]!,
      capped: words[8 * i + 7]!,
    }));
  } finally {
    for (const resource of made) resource.destroy();
  }
}
