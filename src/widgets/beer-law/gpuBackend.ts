// GPU backend of <sb-beer-law>: the kernel in shaders/kernels/beer-law.wesl,
// linked against the shared library, samples T(s) in a compute pass (timed with
// timestamp queries where available) and draws the beam in a render pass.
import { runCompute } from '../../gpu/compute.ts';
import { packStruct, vec4s } from '../../gpu/layout.ts';
import { beerLawKernel } from '../../gpu/layouts.generated.ts';
import { FullScreenPass } from '../../gpu/fullScreenPass.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import {
  CURVE_SAMPLES,
  depthsFor,
  viewRange,
  type BeerLawInputs,
  type BeerLawResult,
} from './model.ts';
import { LAYER_THICKNESS, LAYER_WEIGHTS, PROFILE_IDS } from './profiles.ts';

const KERNEL = 'kernels/beer-law.wesl';
/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = beerLawKernel.BeerLawParams;

export function packParams(
  inputs: BeerLawInputs,
  width: number,
  height: number,
): Uint32Array<ArrayBuffer> {
  const [viewMin, viewMax] = viewRange(inputs.thickness);
  return packStruct(PARAMS, {
    sigmaT: inputs.sigmaT,
    sigmaS: inputs.sigmaS,
    thickness: inputs.thickness,
    split: inputs.split,
    profile: PROFILE_IDS[inputs.profile],
    sampleCount: CURVE_SAMPLES,
    cellCount: LAYER_WEIGHTS.length,
    cellSize: LAYER_THICKNESS,
    viewMin,
    viewMax,
    width,
    height,
    layers: vec4s(LAYER_WEIGHTS),
  });
}

export class BeerLawGpu {
  private picture: Promise<FullScreenPass> | null = null;

  constructor(
    private readonly gpu: GpuContext,
    private readonly canvas: HTMLCanvasElement,
  ) {}

  private pass(): Promise<FullScreenPass> {
    this.picture ??= linkLibraryKernel(STATIC_KERNELS, KERNEL).then((code) =>
      FullScreenPass.create(this.gpu, this.canvas, {
        label: 'beer-law',
        code,
        vertexEntry: 'fullScreenVertex',
        fragmentEntry: 'beamFragment',
        uniformBytes: PARAMS.size,
      }),
    );
    this.picture.catch(() => {
      this.picture = null;
    });
    return this.picture;
  }

  async computeCurve(inputs: BeerLawInputs): Promise<BeerLawResult> {
    const code = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
    const n = CURVE_SAMPLES;
    const { output, gpuMs, wallMs } = await runCompute(this.gpu.device, {
      code,
      entryPoint: 'sampleTransmittance',
      inputs: [],
      outputWords: 2 * n + 3,
      workgroups: [Math.ceil(n / 64)],
      uniforms: packParams(inputs, this.canvas.width, this.canvas.height),
    });
    const values = new Float32Array(output.buffer);
    return {
      depths: depthsFor(inputs.thickness, n),
      transmittance: Float64Array.from(values.subarray(0, n)),
      opticalDepth: Float64Array.from(values.subarray(n, 2 * n)),
      exit: values[2 * n] ?? NaN,
      beforeSplit: values[2 * n + 1] ?? NaN,
      afterSplit: values[2 * n + 2] ?? NaN,
      milliseconds: gpuMs ?? wallMs,
      timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
    };
  }

  async draw(inputs: BeerLawInputs): Promise<void> {
    const pass = await this.pass();
    await pass.draw(packParams(inputs, this.canvas.width, this.canvas.height));
  }

  destroy(): void {
    void this.picture?.then((pass) => pass.destroy());
  }
}
