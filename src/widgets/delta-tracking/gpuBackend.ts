// GPU backend of <sb-delta-tracking>: the kernel in
// shaders/kernels/delta-tracking.wesl, linked against the shared library,
// averages spp transmittance estimates per pixel in a compute pass (timed with
// timestamp queries where available, wall time otherwise) and writes the means,
// the means of the squares, the lookup counts and the capped counts into a
// storage buffer, which is read back for the statistics and the two images.
import type { GpuContext } from '../../gpu/device.ts';
import { packStruct } from '../../gpu/layout.ts';
import { deltaTrackingKernel } from '../../gpu/layouts.generated.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import { runImageKernel, type GpuTiming } from '../base/imageKernel.ts';
import {
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  SPP_MAX,
  type TrackingImage,
  type TrackingInputs,
} from './model.ts';

const KERNEL = 'kernels/delta-tracking.wesl';
/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = deltaTrackingKernel.DeltaParams;

export function packParams(
  inputs: TrackingInputs,
  width: number,
  height: number,
  spp = inputs.spp,
): Uint32Array<ArrayBuffer> {
  return packStruct(PARAMS, {
    width,
    height,
    spp,
    estimator: inputs.code,
    majorantScale: inputs.majorantScale,
    seed: inputs.seed >>> 0,
  });
}

export interface GpuImage extends TrackingImage {
  mean: Float32Array;
  meanSquare: Float32Array;
  milliseconds: number;
  timing: GpuTiming;
}

/** Runs renderImage on a device (the widget's, or Dawn's in the tests). */
export async function renderImageGpu(
  device: GPUDevice,
  code: string,
  inputs: TrackingInputs,
  width: number,
  height: number,
  spp = inputs.spp,
): Promise<GpuImage> {
  const pixels = width * height;
  const { output, milliseconds, timing } = await runImageKernel(
    device,
    code,
    width,
    height,
    4,
    packParams(inputs, width, height, spp),
  );
  const floats = new Float32Array(output.buffer, output.byteOffset, 2 * pixels);
  let lookups = 0;
  let capped = 0;
  for (let i = 0; i < pixels; i++) {
    lookups += output[2 * pixels + i]!;
    capped += output[3 * pixels + i]!;
  }
  return {
    width,
    height,
    spp: Math.min(Math.max(spp, 1), SPP_MAX),
    mean: floats.slice(0, pixels),
    meanSquare: floats.slice(pixels, 2 * pixels),
    lookups,
    capped,
    milliseconds,
    timing,
  };
}

export class DeltaTrackingGpu {
  constructor(private readonly gpu: GpuContext) {}

  async render(inputs: TrackingInputs, spp = inputs.spp): Promise<GpuImage> {
    const code = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
    return renderImageGpu(this.gpu.device, code, inputs, IMAGE_WIDTH, IMAGE_HEIGHT, spp);
  }
}
