// GPU backend of <sb-transfer-function>: the kernel in
// shaders/kernels/transfer-function.wesl, linked against the shared library, ray
// casts rows of the image in a compute pass (timed with timestamp queries where
// available, wall time otherwise). The phantom lives in an r32float 3D texture
// read with textureLoad (medium.wesl's gridDensityTrilinear), which runCompute's
// storage-buffer bindings cannot hold, so this backend binds it through its own
// layout. The output (colour planes and step counts) is read back: the widget
// needs the numbers for the RMSE and paints them into a 2D canvas.
import { gpuCore, mapRange } from '../../gpu/core.ts';
import { withErrorScopes } from '../../gpu/errors.ts';
import { packStruct } from '../../gpu/layout.ts';
import { transferFunctionKernel } from '../../gpu/layouts.generated.ts';
import { linkLibraryKernel, type KernelLibrary } from '../../gpu/link.ts';
import type { DensityGridData } from '../../reference/medium.ts';
import {
  packTransferFunction,
  TRANSFER_FUNCTION_WORDS,
  type TransferFunction,
} from '../../reference/volume.ts';
import type { GpuTiming } from '../base/imageKernel.ts';
import { CT_RESCALE_INTERCEPT } from './phantom.ts';
import { BACKGROUND, frameCamera, VOXEL, type FrameInputs, type VolumeImage } from './model.ts';

const KERNEL = 'kernels/transfer-function.wesl';
/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = transferFunctionKernel.TransferParams;
/** Output words per pixel: r, g, b, steps, planned steps, flags. */
const WORDS_PER_PIXEL = 6;

export interface RowsRequest {
  inputs: Pick<FrameInputs, 'tf' | 'azimuth' | 'elevation'>;
  size: number;
  stepVoxels: number;
  threshold: number;
  rowStart: number;
  rowEnd: number;
}

export interface GpuRows extends VolumeImage {
  rowStart: number;
  rows: number;
  milliseconds: number;
  timing: GpuTiming;
}

export function packParams(request: RowsRequest, data: DensityGridData): Uint32Array<ArrayBuffer> {
  const { grid } = data;
  const camera = frameCamera(request.inputs.azimuth, request.inputs.elevation, request.size);
  const { position, projection, forward, right, up, halfExtent, imageSize } = camera;
  return packStruct(PARAMS, {
    width: request.size,
    height: request.size,
    rowOffset: request.rowStart,
    rows: request.rowEnd - request.rowStart,
    camera: { position, projection, forward, right, up, halfExtent, imageSize },
    dimensions: grid.dimensions,
    valueOffset: CT_RESCALE_INTERCEPT,
    boundsMin: grid.boundsMin,
    densityScale: grid.densityScale,
    boundsMax: grid.boundsMax,
    referenceStep: VOXEL,
    background: BACKGROUND,
    stepSize: request.stepVoxels * VOXEL,
    threshold: request.threshold,
  });
}

export class VolumeRendererGpu {
  private constructor(
    private readonly device: GPUDevice,
    private readonly data: DensityGridData,
    private readonly pipeline: GPUComputePipeline,
    private readonly layout: GPUBindGroupLayout,
    private readonly texture: GPUTexture,
  ) {}

  /** Links the kernel, builds the pipeline and uploads the grid into a 3D texture. */
  static async create(
    device: GPUDevice,
    library: KernelLibrary,
    data: DensityGridData,
  ): Promise<VolumeRendererGpu> {
    const code = await linkLibraryKernel(library, KERNEL);
    const [nx, ny, nz] = data.grid.dimensions;
    const parts = await withErrorScopes(device, 'transfer-function pipeline', () => {
      const core = gpuCore(device);
      const layout = core.bindGroupLayout([
        { binding: 0, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } },
        { binding: 1, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } },
        {
          binding: 2,
          visibility: GPUShaderStage.COMPUTE,
          texture: { sampleType: 'unfilterable-float', viewDimension: '3d' },
        },
        { binding: 3, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'storage' } },
      ]);
      const pipeline = core.computePipeline({
        code,
        entryPoint: 'renderImage',
        layout: core.pipelineLayout([layout]),
      });
      const texture = device.createTexture({
        size: [nx, ny, nz],
        dimension: '3d',
        format: 'r32float',
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
      });
      const volume = data.volume;
      device.queue.writeTexture(
        { texture },
        volume.buffer,
        { offset: volume.byteOffset, bytesPerRow: nx * 4, rowsPerImage: ny },
        [nx, ny, nz],
      );
      return { layout, pipeline, texture };
    });
    return new VolumeRendererGpu(device, data, parts.pipeline, parts.layout, parts.texture);
  }

  /** Ray casts rows [rowStart, rowEnd) and reads them back with the time the pass took. */
  async renderRows(request: RowsRequest): Promise<GpuRows> {
    const { device } = this;
    const rows = Math.max(0, Math.min(request.rowEnd, request.size) - request.rowStart);
    const pixels = rows * request.size;
    const outputBytes = Math.max(16, WORDS_PER_PIXEL * pixels * 4);
    // Buffers and timer leased from the GPU core's pools; bound with their own sizes.
    return gpuCore(device)
      .lease()
      .run(async (lease) => {
        const sized = (bytes: number): number => Math.ceil(bytes / 16) * 16;
        const uniform = (purpose: string, data: Uint32Array): GPUBufferBinding => ({
          buffer: lease.upload(
            `transfer-function.${purpose}`,
            data,
            GPUBufferUsage.UNIFORM,
            sized(data.byteLength),
          ),
          size: sized(data.byteLength),
        });
        const timer = lease.timer();
        const readBack = await withErrorScopes(device, 'transfer-function render', () => {
          const params = packParams(request, this.data);
          const tfWords = packTransferFunction(
            request.inputs.tf as TransferFunction,
            new Uint32Array(TRANSFER_FUNCTION_WORDS),
          );
          const output = lease.buffer(
            'transfer-function.output',
            sized(outputBytes),
            GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC,
            true,
          );
          const read = lease.buffer(
            'transfer-function.read',
            outputBytes,
            GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
          );
          const bindGroup = device.createBindGroup({
            layout: this.layout,
            entries: [
              { binding: 0, resource: uniform('params', params) },
              { binding: 1, resource: uniform('tf', tfWords) },
              { binding: 2, resource: this.texture.createView() },
              { binding: 3, resource: { buffer: output, size: sized(outputBytes) } },
            ],
          });
          const encoder = device.createCommandEncoder();
          const pass = encoder.beginComputePass(timer.passDescriptor());
          pass.setPipeline(this.pipeline);
          pass.setBindGroup(0, bindGroup);
          pass.dispatchWorkgroups(Math.ceil(request.size / 8), Math.ceil(Math.max(rows, 1) / 8));
          pass.end();
          timer.resolve(encoder);
          encoder.copyBufferToBuffer(output, 0, read, 0, outputBytes);
          device.queue.submit([encoder.finish()]);
          return read;
        });
        const start = performance.now();
        const words = new Uint32Array(await mapRange(readBack, WORDS_PER_PIXEL * pixels * 4));
        const wallMs = performance.now() - start;
        const gpuMs = await timer.read();
        const rgb = new Float32Array(words.buffer, 0, 3 * pixels);
        const stepsPerPixel = words.slice(3 * pixels, 4 * pixels);
        const plannedPerPixel = words.slice(4 * pixels, 5 * pixels);
        let steps = 0;
        let plannedSteps = 0;
        let terminatedRays = 0;
        let cappedRays = 0;
        for (let i = 0; i < pixels; i++) {
          steps += words[3 * pixels + i]!;
          plannedSteps += words[4 * pixels + i]!;
          const flags = words[5 * pixels + i]!;
          terminatedRays += flags & 1;
          cappedRays += (flags >> 1) & 1;
        }
        return {
          size: request.size,
          rgb,
          steps,
          plannedSteps,
          terminatedRays,
          cappedRays,
          stepsPerPixel,
          plannedPerPixel,
          rowStart: request.rowStart,
          rows,
          milliseconds: gpuMs ?? wallMs,
          timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
        };
      });
  }

  destroy(): void {
    this.texture.destroy();
  }
}
