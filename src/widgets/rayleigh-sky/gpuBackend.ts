// GPU backend of <sb-rayleigh-sky>: the kernel in shaders/kernels/rayleigh-sky.wesl,
// linked against the shared library, evaluates the probe directions and the direct
// sun in a compute pass (timed with timestamp queries where available, wall time
// otherwise) and draws the panorama in a render pass (wall time, submit to done).
import { runCompute } from '../../gpu/compute.ts';
import { FullScreenPass } from '../../gpu/fullScreenPass.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { SHADER_LIBRARY } from '../../gpu/shaderSources.ts';
import { exposureScale, probesFor, type Rgb, type SkyInputs, type SkyProbes } from './model.ts';

const KERNEL = 'kernels/rayleigh-sky.wesl';
/** Byte size of SkyParams in the kernel (8 scalars + 2 vec4f). */
const PARAMS_BYTES = 64;

export function packParams(
  inputs: SkyInputs,
  width: number,
  height: number,
): Uint32Array<ArrayBuffer> {
  const buffer = new ArrayBuffer(PARAMS_BYTES);
  const f32 = new Float32Array(buffer);
  const u32 = new Uint32Array(buffer);
  f32[0] = inputs.sinSun;
  f32[1] = inputs.cosSun;
  f32[2] = exposureScale(inputs.exposure);
  u32[3] = inputs.scattering ? 1 : 0;
  u32[4] = inputs.steps;
  u32[5] = inputs.sunSteps;
  f32[6] = width;
  f32[7] = height;
  probesFor(inputs).forEach((probe, k) => {
    f32[8 + k] = probe.mu;
    f32[12 + k] = probe.nu;
  });
  return u32;
}

export interface GpuProbes extends SkyProbes {
  /** True when the kernel reported that a march hit its step cap. */
  capped: boolean;
  milliseconds: number;
  timing: 'gpu-timestamp' | 'gpu-wall';
}

/** Runs the probe pass on a device (the widget's, or Dawn's in the tests). */
export async function computeProbesGpu(
  device: GPUDevice,
  code: string,
  inputs: SkyInputs,
): Promise<GpuProbes> {
  const { output, gpuMs, wallMs } = await runCompute(device, {
    code,
    entryPoint: 'skyProbes',
    inputs: [],
    outputWords: 16,
    workgroups: [1],
    uniforms: packParams(inputs, 1, 1),
  });
  const values = new Float32Array(output.buffer, output.byteOffset, 16);
  const rgb = (k: number): Rgb => [values[4 * k]!, values[4 * k + 1]!, values[4 * k + 2]!];
  return {
    radiance: [rgb(0), rgb(1), rgb(2)],
    sunTransmittance: rgb(3),
    capped: [3, 7, 11, 15].some((i) => values[i] !== 0),
    milliseconds: gpuMs ?? wallMs,
    timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
  };
}

export class RayleighSkyGpu {
  private picture: Promise<FullScreenPass> | null = null;

  constructor(
    private readonly gpu: GpuContext,
    private readonly canvas: HTMLCanvasElement,
  ) {}

  private pass(): Promise<FullScreenPass> {
    this.picture ??= linkLibraryKernel(SHADER_LIBRARY, KERNEL).then((code) =>
      FullScreenPass.create(this.gpu, this.canvas, {
        label: 'rayleigh-sky',
        code,
        vertexEntry: 'fullScreenVertex',
        fragmentEntry: 'skyFragment',
        uniformBytes: PARAMS_BYTES,
      }),
    );
    this.picture.catch(() => {
      this.picture = null;
    });
    return this.picture;
  }

  async probes(inputs: SkyInputs): Promise<GpuProbes> {
    const code = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
    return computeProbesGpu(this.gpu.device, code, inputs);
  }

  /** Draws the panorama; returns the wall time (ms) from submit until the queue is done. */
  async draw(inputs: SkyInputs): Promise<number> {
    const pass = await this.pass();
    const start = performance.now();
    await pass.draw(packParams(inputs, this.canvas.width, this.canvas.height));
    await this.gpu.device.queue.onSubmittedWorkDone();
    return performance.now() - start;
  }

  destroy(): void {
    void this.picture?.then((pass) => pass.destroy());
  }
}
