// GPU backend of <sb-raymarch-steps>: the kernel in
// shaders/kernels/raymarch-steps.wesl, linked against the shared library, marches
// one ray per pixel in a compute pass (timed with timestamp queries where
// available, wall time otherwise) and writes the radiances into a storage
// buffer, which is read back for the RMSE and the error image. The converged
// reference is the same kernel with midpoint samples and N = REFERENCE_STEPS,
// computed once per density scale and image size (a refinement stage draws a
// smaller image first, compared with a reference of its own size).
import type { GpuContext } from '../../gpu/device.ts';
import { packStruct } from '../../gpu/layout.ts';
import { raymarchStepsKernel } from '../../gpu/layouts.generated.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import { runImageKernel, type GpuTiming } from '../base/imageKernel.ts';
import { MARCH_MIDPOINT } from '../../reference/raymarch.ts';
import {
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  REFERENCE_STEPS,
  type MarchImage,
  type MarchInputs,
} from './model.ts';

const KERNEL = 'kernels/raymarch-steps.wesl';
/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = raymarchStepsKernel.RaymarchParams;

export function packParams(
  inputs: MarchInputs,
  width: number,
  height: number,
  steps = inputs.steps,
): Uint32Array<ArrayBuffer> {
  return packStruct(PARAMS, {
    width,
    height,
    steps,
    scheme: inputs.scheme,
    update: inputs.linear ? 1 : 0,
    seed: inputs.seed >>> 0,
    density: inputs.density,
  });
}

export interface GpuImage extends MarchImage {
  radiance: Float32Array;
  /** True when some ray took fewer steps than asked for (the MARCH_MAX_STEPS cap). */
  capped: boolean;
  milliseconds: number;
  timing: GpuTiming;
}

/** Runs renderImage on a device (the widget's, or Dawn's in the tests). */
export async function renderImageGpu(
  device: GPUDevice,
  code: string,
  inputs: MarchInputs,
  width: number,
  height: number,
  steps = inputs.steps,
): Promise<GpuImage> {
  const pixels = width * height;
  const { output, milliseconds, timing } = await runImageKernel(
    device,
    code,
    width,
    height,
    3,
    packParams(inputs, width, height, steps),
  );
  const radiance = new Float32Array(output.buffer, output.byteOffset, pixels);
  let clampedSteps = 0;
  let clampedPixels = 0;
  let capped = false;
  for (let i = 0; i < pixels; i++) {
    const clamped = output[pixels + i]!;
    clampedSteps += clamped;
    if (clamped > 0) clampedPixels += 1;
    if (output[2 * pixels + i] !== Math.max(steps, 1)) capped = true;
  }
  return {
    width,
    height,
    radiance,
    clampedSteps,
    clampedPixels,
    capped,
    milliseconds,
    timing,
  };
}

export class RaymarchStepsGpu {
  private readonly references = new Map<string, Promise<Float32Array>>();

  constructor(private readonly gpu: GpuContext) {}

  /** The image at width × height (the full size, or a refinement stage's smaller one). */
  async render(
    inputs: MarchInputs,
    steps = inputs.steps,
    width = IMAGE_WIDTH,
    height = IMAGE_HEIGHT,
  ): Promise<GpuImage> {
    const code = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
    return renderImageGpu(this.gpu.device, code, inputs, width, height, steps);
  }

  /**
   * The converged image (midpoint, exact update, N = REFERENCE_STEPS) at width × height,
   * once per density and size.
   */
  reference(density: number, width = IMAGE_WIDTH, height = IMAGE_HEIGHT): Promise<Float32Array> {
    const key = `${density}|${width}×${height}`;
    let cached = this.references.get(key);
    if (!cached) {
      const inputs: MarchInputs = {
        steps: REFERENCE_STEPS,
        placement: 'midpoint',
        scheme: MARCH_MIDPOINT,
        linear: false,
        density,
        seed: 0,
      };
      cached = this.render(inputs, REFERENCE_STEPS, width, height).then((image) => image.radiance);
      cached.catch(() => this.references.delete(key));
      if (this.references.size > 16) this.references.clear();
      this.references.set(key, cached);
    }
    return cached;
  }
}
