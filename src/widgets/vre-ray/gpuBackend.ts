// GPU backend of <sb-vre-ray>: the kernel in shaders/kernels/vre-ray.wesl,
// linked against the shared library, marches the ray in a compute pass (timed
// with timestamp queries where available) and draws it in a render pass.
import { runCompute } from '../../gpu/compute.ts';
import { packStruct } from '../../gpu/layout.ts';
import { vreRayKernel } from '../../gpu/layouts.generated.ts';
import { FullScreenPass } from '../../gpu/fullScreenPass.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import {
  MARCH_STEPS,
  depthsFor,
  viewRange,
  type VreRayInputs,
  type VreRayResult,
} from './model.ts';

const KERNEL = 'kernels/vre-ray.wesl';
/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = vreRayKernel.VreRayParams;
/** Words the march writes: three curves of n + 1 samples and L at the eye. */
export const OUTPUT_WORDS = 3 * (MARCH_STEPS + 1) + 1;

export function packParams(
  inputs: VreRayInputs,
  width: number,
  height: number,
): Uint32Array<ArrayBuffer> {
  const [viewMin, viewMax] = viewRange(inputs.length);
  return packStruct(PARAMS, {
    sigma: inputs.sigma,
    albedo: inputs.albedo,
    emission: inputs.emission,
    inscatter: inputs.inscatter,
    background: inputs.background,
    length: inputs.length,
    steps: MARCH_STEPS,
    viewMin,
    viewMax,
    width,
    height,
  });
}

/** Splits the kernel's output into the widget's result. */
export function unpackMarch(
  inputs: VreRayInputs,
  output: Uint32Array,
): Omit<VreRayResult, 'milliseconds' | 'timing'> {
  const values = new Float32Array(output.buffer, output.byteOffset, output.length);
  const m = MARCH_STEPS + 1;
  return {
    depths: depthsFor(inputs.length),
    emitted: Float64Array.from(values.subarray(0, m)),
    inscattered: Float64Array.from(values.subarray(m, 2 * m)),
    transmittance: Float64Array.from(values.subarray(2 * m, 3 * m)),
    total: values[3 * m] ?? NaN,
  };
}

export class VreRayGpu {
  private picture: Promise<FullScreenPass> | null = null;

  constructor(
    private readonly gpu: GpuContext,
    private readonly canvas: HTMLCanvasElement,
  ) {}

  private pass(): Promise<FullScreenPass> {
    this.picture ??= linkLibraryKernel(STATIC_KERNELS, KERNEL).then((code) =>
      FullScreenPass.create(this.gpu, this.canvas, {
        label: 'vre-ray',
        code,
        vertexEntry: 'fullScreenVertex',
        fragmentEntry: 'rayFragment',
        uniformBytes: PARAMS.size,
      }),
    );
    this.picture.catch(() => {
      this.picture = null;
    });
    return this.picture;
  }

  async march(inputs: VreRayInputs): Promise<VreRayResult> {
    const code = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
    const { output, gpuMs, wallMs } = await runCompute(this.gpu.device, {
      code,
      entryPoint: 'marchRay',
      inputs: [],
      outputWords: OUTPUT_WORDS,
      workgroups: [1],
      uniforms: packParams(inputs, this.canvas.width, this.canvas.height),
    });
    return {
      ...unpackMarch(inputs, output),
      milliseconds: gpuMs ?? wallMs,
      timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
    };
  }

  async draw(inputs: VreRayInputs): Promise<void> {
    const pass = await this.pass();
    await pass.draw(packParams(inputs, this.canvas.width, this.canvas.height));
  }

  destroy(): void {
    void this.picture?.then((pass) => pass.destroy());
  }
}
