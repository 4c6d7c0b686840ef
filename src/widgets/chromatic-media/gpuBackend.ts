// GPU backend of <sb-chromatic-media>: one pass of one estimator of
// shaders/kernels/chromatic-media.wesl over the picture, timed with timestamp queries where
// available (else the wall time of the dispatch and read-back), its per-pixel sums read back
// for the statistics (model.ts).
import { runCompute } from '../../gpu/compute.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { GpuTiming } from '../base/timing.ts';
import { PIXEL_WORDS, packParams, type ChromaticInputs } from './model.ts';

export const CHROMATIC_KERNEL = 'kernels/chromatic-media.wesl';

export interface GpuPass {
  sums: Float32Array;
  milliseconds: number;
  timing: GpuTiming;
}

/** One pass on a device (the widget's, or Dawn's in the tests). */
export async function chromaticPassGpu(
  device: GPUDevice,
  code: string,
  inputs: ChromaticInputs,
  estimator: number,
  size: number,
  spp: number,
  frame: number,
): Promise<GpuPass> {
  const { output, gpuMs, wallMs } = await runCompute(device, {
    code,
    entryPoint: 'renderChromatic',
    inputs: [packParams(inputs, estimator, size, spp, frame)],
    outputWords: PIXEL_WORDS * size * size,
    workgroups: [Math.ceil(size / 8), Math.ceil(size / 8)],
  });
  return {
    sums: new Float32Array(output.buffer, output.byteOffset, output.length),
    milliseconds: gpuMs ?? wallMs,
    timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
  };
}

export class ChromaticGpu {
  constructor(private readonly gpu: GpuContext) {}

  async pass(
    inputs: ChromaticInputs,
    estimator: number,
    size: number,
    spp: number,
    frame: number,
  ): Promise<GpuPass> {
    const code = await linkLibraryKernel(STATIC_KERNELS, CHROMATIC_KERNEL);
    return chromaticPassGpu(this.gpu.device, code, inputs, estimator, size, spp, frame);
  }
}
