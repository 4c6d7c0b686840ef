// GPU backend of <sb-rayleigh-sky>: the kernel in shaders/kernels/rayleigh-sky.wesl,
// linked against the shared library, evaluates the probe directions and the direct
// sun in a compute pass and draws the panorama in render passes, both timed with
// timestamp queries where available and wall time otherwise.
import { runCompute } from '../../gpu/compute.ts';
import { gpuCore } from '../../gpu/core.ts';
import { FullScreenPass } from '../../gpu/fullScreenPass.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { packStruct } from '../../gpu/layout.ts';
import { rayleighSkyKernel } from '../../gpu/layouts.generated.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { GpuTiming } from '../base/imageKernel.ts';
import { exposureScale, probesFor, type Rgb, type SkyInputs, type SkyProbes } from './model.ts';

const KERNEL = 'kernels/rayleigh-sky.wesl';
/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = rayleighSkyKernel.SkyParams;

export function packParams(
  inputs: SkyInputs,
  width: number,
  height: number,
): Uint32Array<ArrayBuffer> {
  const probes = probesFor(inputs);
  // Three probes in x, y, z; w unused (a fourth probe would fail the vec4 length check).
  const lanes = (values: number[]): number[] => [...values, 0];
  return packStruct(PARAMS, {
    sinSun: inputs.sinSun,
    cosSun: inputs.cosSun,
    exposureScale: exposureScale(inputs.exposure),
    scattering: inputs.scattering ? 1 : 0,
    steps: inputs.steps,
    sunSteps: inputs.sunSteps,
    width,
    height,
    probeMu: lanes(probes.map((probe) => probe.mu)),
    probeNu: lanes(probes.map((probe) => probe.nu)),
  });
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

/** The time of one panorama, measured over `passes` identical passes in one submit. */
export interface PanoramaTime {
  /** Time per panorama (ms): the span divided by `passes`. */
  milliseconds: number;
  /** The measured span (ms), for choosing the next pass count (nextPassCount). */
  spanMilliseconds: number;
  passes: number;
  timing: GpuTiming;
}

export class RayleighSkyGpu {
  private picture: Promise<FullScreenPass> | null = null;

  constructor(
    private readonly gpu: GpuContext,
    private readonly canvas: HTMLCanvasElement,
  ) {}

  private pass(): Promise<FullScreenPass> {
    this.picture ??= linkLibraryKernel(STATIC_KERNELS, KERNEL).then((code) =>
      FullScreenPass.create(this.gpu, this.canvas, {
        label: 'rayleigh-sky',
        code,
        vertexEntry: 'fullScreenVertex',
        fragmentEntry: 'skyFragment',
        uniformBytes: PARAMS.size,
      }),
    );
    this.picture.catch(() => {
      this.picture = null;
    });
    return this.picture;
  }

  async probes(inputs: SkyInputs): Promise<GpuProbes> {
    const code = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
    return computeProbesGpu(this.gpu.device, code, inputs);
  }

  /**
   * Draws the panorama `passes` times in one submit (the canvas shows the last) and
   * returns the time per panorama: from timestamp queries around the passes where the
   * device has them, else the wall time from submit until the queue is done.
   */
  async draw(inputs: SkyInputs, passes = 1): Promise<PanoramaTime> {
    const pass = await this.pass();
    // The timer is leased from the GPU core's pool (a sweep draws hundreds of times).
    return gpuCore(this.gpu.device)
      .lease()
      .run(async (lease) => {
        const timer = lease.timer();
        const start = performance.now();
        await pass.draw(packParams(inputs, this.canvas.width, this.canvas.height), {
          timer,
          passes,
        });
        await this.gpu.device.queue.onSubmittedWorkDone();
        const wallMs = performance.now() - start;
        const gpuMs = await timer.read();
        const span = gpuMs ?? wallMs;
        return {
          milliseconds: span / passes,
          spanMilliseconds: span,
          passes,
          timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
        };
      });
  }

  destroy(): void {
    void this.picture?.then((pass) => pass.destroy());
  }
}
