// The GPU renderer: links shaders/kernels/scene-render.wesl with the plan's conditions
// (or the general ones), uploads the packed scene (storage buffer), the grid (two
// r32float 3D textures) and the phase tables (storage buffer), and runs passes of the kernel, each followed in the same
// compute pass by the accumulate kernel into a GpuAccumulation that stays on the GPU;
// a pass reads back only its GPU timestamps. Works in the browser and in Node (Dawn)
// alike: the caller passes the device and the shader library.
import { gpuCore } from '../gpu/core.ts';
import { withErrorScopes } from '../gpu/errors.ts';
import { wordsOf, writeStruct } from '../gpu/layout.ts';
import { sceneRenderKernel } from '../gpu/layouts.generated.ts';
import { linkLibraryKernel, type KernelLibrary } from '../gpu/link.ts';
import { GpuTimer } from '../gpu/timing.ts';
import { PHASE_TABLE_WORDS } from '../phase/registry.ts';
import { gridScaledSamples, type DensityGridData } from '../reference/medium.ts';
import { PASS_WORDS_PER_PIXEL, type Accumulation } from './accumulation.ts';
import { GpuAccumulation } from './gpuAccumulation.ts';
import type { PackedScene } from './pack.ts';
import type { Conditions } from './plan.ts';
import type { PassOutput, PassRenderer } from './render.ts';

export const SCENE_KERNEL = 'kernels/scene-render.wesl';
/** The scene kernel's per-pass uniform, laid out from its WGSL declaration. */
const RENDER_PASS = sceneRenderKernel.RenderPass;
const ENTRY_POINT = 'renderScene';

/** The linked WGSL of the scene kernel for the given conditions. */
export function linkSceneKernel(library: KernelLibrary, conditions: Conditions): Promise<string> {
  return linkLibraryKernel(library, SCENE_KERNEL, conditions);
}

function bindGroupLayout(device: GPUDevice): GPUBindGroupLayout {
  const texture: GPUTextureBindingLayout = {
    sampleType: 'unfilterable-float',
    viewDimension: '3d',
  };
  const visibility = GPUShaderStage.COMPUTE;
  return gpuCore(device).bindGroupLayout([
    { binding: 0, visibility, buffer: { type: 'read-only-storage' } },
    { binding: 1, visibility, buffer: { type: 'storage' } },
    // The grid's samples (integrator.wesl sceneDensity, a storage buffer) and its majorant
    // grid (a texture). Four storage buffers in all, within WebGPU's default
    // maxStorageBuffersPerShaderStage (8).
    { binding: 2, visibility, buffer: { type: 'read-only-storage' } },
    { binding: 3, visibility, texture },
    { binding: 4, visibility, buffer: { type: 'uniform' } },
    // The phase tables (integrator.wesl scenePhaseTables): in every layout, read only by
    // kernels linked with a tabulated phase function's condition.
    { binding: 5, visibility, buffer: { type: 'read-only-storage' } },
  ]);
}

/** A compute pipeline for linked code, from the device's GPU core (compiling is the slow part). */
function pipelineFor(device: GPUDevice, code: string): Promise<GPUComputePipeline> {
  const core = gpuCore(device);
  return core.computePipelineAsync({
    code,
    entryPoint: ENTRY_POINT,
    layout: core.pipelineLayout([bindGroupLayout(device)]),
  });
}

/** The grid's extinction densities (its samples clamped and scaled, gridScaledSamples) in a storage buffer. */
function sampleBuffer(device: GPUDevice, data: DensityGridData): GPUBuffer {
  const samples = gridScaledSamples(data.grid, data.volume);
  const buffer = device.createBuffer({
    size: samples.byteLength,
    usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST,
  });
  device.queue.writeBuffer(buffer, 0, samples);
  return buffer;
}

function volumeTexture(device: GPUDevice, data: DensityGridData): GPUTexture {
  const [nx, ny, nz] = data.grid.dimensions;
  const texture = device.createTexture({
    size: [nx, ny, nz],
    dimension: '3d',
    format: 'r32float',
    usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
  });
  device.queue.writeTexture(
    { texture },
    data.volume as Float32Array<ArrayBuffer>,
    { bytesPerRow: nx * 4, rowsPerImage: ny },
    [nx, ny, nz],
  );
  return texture;
}

export class GpuSceneRenderer implements PassRenderer {
  timing: 'gpu-timestamp' | 'gpu-wall';
  /** The linked WGSL this renderer runs. */
  readonly code: string;
  /** The moments of every pass so far, on the GPU. */
  readonly accumulation: GpuAccumulation;
  private readonly resources: (GPUBuffer | GPUTexture)[];
  private readonly timer: GpuTimer;
  /** The kernel's RenderPass uniform, rewritten in place each pass. */
  private readonly passWords = wordsOf(new ArrayBuffer(RENDER_PASS.size));
  private released = false;

  private constructor(
    private readonly device: GPUDevice,
    private readonly pipeline: GPUComputePipeline,
    code: string,
    private readonly packed: PackedScene,
    private readonly bindGroup: GPUBindGroup,
    private readonly output: GPUBuffer,
    private readonly uniforms: GPUBuffer,
    resources: (GPUBuffer | GPUTexture)[],
    accumulation: GpuAccumulation,
  ) {
    this.code = code;
    this.resources = resources;
    this.accumulation = accumulation;
    this.timer = new GpuTimer(device);
    this.timing = this.timer.available ? 'gpu-timestamp' : 'gpu-wall';
  }

  /**
   * Links and compiles the kernel of `conditions` without a scene (both cached per
   * device): a widget warms a variant it may need next, so that switching to it does
   * not wait for the compiler.
   */
  static async prepare(
    device: GPUDevice,
    library: KernelLibrary,
    conditions: Conditions,
  ): Promise<void> {
    const code = await linkSceneKernel(library, conditions);
    await withErrorScopes(device, 'scene kernel', () => pipelineFor(device, code));
  }

  /** Links, compiles (cached) and uploads; the scene must be packed (pack.ts). */
  static async create(
    device: GPUDevice,
    library: KernelLibrary,
    packed: PackedScene,
    conditions: Conditions,
  ): Promise<GpuSceneRenderer> {
    const code = await linkSceneKernel(library, conditions);
    // The kernel, the accumulation and the upload do not depend on each other: their error
    // scopes are answered together (errors.ts pops each call's scopes at once), one round
    // trip to the GPU process where three in a row cost a widget's new scene 20–30 ms on
    // SwiftShader (bench/firstPictureProbe.ts).
    const pipelineMade = withErrorScopes(device, 'scene kernel', () => pipelineFor(device, code));
    const accumulationMade = GpuAccumulation.create(device, library, packed.width, packed.height);
    const made: (GPUBuffer | GPUTexture)[] = [];
    const outputBytes = PASS_WORDS_PER_PIXEL * 4 * packed.width * packed.height;
    const partsMade = withErrorScopes(device, 'scene upload', () => {
      const records = device.createBuffer({
        size: packed.records.byteLength,
        usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST,
      });
      device.queue.writeBuffer(records, 0, packed.records);
      // The pass's sums stay on the GPU: the accumulate kernel reads them.
      const output = device.createBuffer({ size: outputBytes, usage: GPUBufferUsage.STORAGE });
      const uniforms = device.createBuffer({
        size: RENDER_PASS.size,
        usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
      });
      const density = sampleBuffer(device, packed.density);
      const majorant = volumeTexture(device, packed.majorant);
      // At least one table's bytes (zeros without tables): the binding's minimum size for
      // a kernel that declares the runtime-sized array<PhaseTable>.
      const phaseTables = device.createBuffer({
        size: Math.max(packed.phaseTables.byteLength, PHASE_TABLE_WORDS * 4),
        usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST,
      });
      if (packed.phaseTables.length > 0)
        device.queue.writeBuffer(phaseTables, 0, packed.phaseTables);
      made.push(records, output, uniforms, density, majorant, phaseTables);
      const bindGroup = device.createBindGroup({
        layout: bindGroupLayout(device),
        entries: [
          { binding: 0, resource: { buffer: records } },
          { binding: 1, resource: { buffer: output } },
          { binding: 2, resource: { buffer: density } },
          { binding: 3, resource: majorant.createView() },
          { binding: 4, resource: { buffer: uniforms } },
          { binding: 5, resource: { buffer: phaseTables } },
        ],
      });
      return { bindGroup, output, uniforms };
    });
    const [pipelineResult, accumulationResult, partsResult] = await Promise.allSettled([
      pipelineMade,
      accumulationMade,
      partsMade,
    ]);
    if (
      pipelineResult.status === 'rejected' ||
      accumulationResult.status === 'rejected' ||
      partsResult.status === 'rejected'
    ) {
      for (const r of made) r.destroy();
      if (accumulationResult.status === 'fulfilled') accumulationResult.value.destroy();
      const failed = [pipelineResult, accumulationResult, partsResult].find(
        (result) => result.status === 'rejected',
      );
      throw (failed as PromiseRejectedResult).reason;
    }
    const pipeline = pipelineResult.value;
    const accumulation = accumulationResult.value;
    const parts = partsResult.value;
    return new GpuSceneRenderer(
      device,
      pipeline,
      code,
      packed,
      parts.bindGroup,
      parts.output,
      parts.uniforms,
      made,
      accumulation,
    );
  }

  /**
   * One pass: the scene kernel and the accumulate kernel in one timed compute pass
   * (the time covers both), nothing read back but the timestamps.
   */
  async renderPass(sampleOffset: number, samples: number): Promise<PassOutput> {
    const { device, packed } = this;
    const pass = this.passWords.u32;
    const { seed, width, height } = packed;
    writeStruct(RENDER_PASS, { sampleOffset, samples, seed, width, height }, this.passWords);
    const start = performance.now();
    await withErrorScopes(device, 'scene pass', () => {
      device.queue.writeBuffer(this.uniforms, 0, pass);
      const encoder = device.createCommandEncoder();
      const computePass = encoder.beginComputePass(this.timer.passDescriptor());
      computePass.setPipeline(this.pipeline);
      computePass.setBindGroup(0, this.bindGroup);
      computePass.dispatchWorkgroups(Math.ceil(packed.width / 8), Math.ceil(packed.height / 8));
      this.accumulation.encodeAdd(computePass, this.output, samples);
      computePass.end();
      this.timer.resolve(encoder);
      device.queue.submit([encoder.finish()]);
    });
    const gpuMs = await this.timer.read();
    if (gpuMs !== null) return { milliseconds: gpuMs, timing: 'gpu-timestamp' };
    await device.queue.onSubmittedWorkDone();
    return { milliseconds: performance.now() - start, timing: 'gpu-wall' };
  }

  release(): Accumulation {
    this.released = true;
    this.destroy();
    return this.accumulation;
  }

  destroy(): void {
    this.timer.destroy();
    for (const r of this.resources) r.destroy();
    if (!this.released) this.accumulation.destroy();
  }
}
