// GPU backend of <sb-hg-lobe>: the kernel in shaders/kernels/hg-lobe.wesl, linked
// against the shared library, draws N cosines with the HG sampler and bins them
// in a compute pass (timed with timestamp queries where available, wall time
// otherwise), and draws the polar lobe in a render pass.
import { runCompute } from '../../gpu/compute.ts';
import { packStruct } from '../../gpu/layout.ts';
import { hgLobeKernel } from '../../gpu/layouts.generated.ts';
import { FullScreenPass } from '../../gpu/fullScreenPass.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import {
  BIN_COUNT,
  WORKGROUP_SIZE,
  type HgHistogram,
  type HgLobeInputs,
  type PolarLayout,
} from './model.ts';

const KERNEL = 'kernels/hg-lobe.wesl';
/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = hgLobeKernel.HgLobeParams;
const COMPARE_IDS = { none: 0, isotropic: 1, rayleigh: 2 } as const;

export function packParams(inputs: HgLobeInputs, layout: PolarLayout): Uint32Array<ArrayBuffer> {
  return packStruct(PARAMS, {
    g: inputs.g,
    compareLobe: COMPARE_IDS[inputs.compare],
    logScale: inputs.scale === 'log' ? 1 : 0,
    sampleCount: inputs.sampleCount,
    seed: inputs.seed,
    width: layout.width,
    height: layout.height,
    pixelsPerUnit: layout.pixelsPerUnit,
    logFloor: layout.logFloor,
    ringStep: layout.ringStep,
    centreX: layout.centreX,
    centreY: layout.centreY,
  });
}

export function workgroupsFor(sampleCount: number): number {
  return Math.ceil(sampleCount / WORKGROUP_SIZE);
}

/** Output words of the sampling pass: the bins, then (Σμ, Σμ²) per workgroup. */
export function histogramWords(sampleCount: number): number {
  return BIN_COUNT + 2 * workgroupsFor(sampleCount);
}

/** Reads the sampling pass's output: the bins as they are, the f32 partial sums added in float64. */
export function unpackHistogram(
  output: Uint32Array,
  sampleCount: number,
): Omit<HgHistogram, 'milliseconds' | 'timing'> {
  const bins = Uint32Array.from(output.subarray(0, BIN_COUNT));
  const partials = new Float32Array(
    output.buffer,
    output.byteOffset + 4 * BIN_COUNT,
    2 * workgroupsFor(sampleCount),
  );
  let sumMu = 0;
  let sumMuSquared = 0;
  for (let w = 0; w < partials.length; w += 2) {
    sumMu += partials[w]!;
    sumMuSquared += partials[w + 1]!;
  }
  return { bins, sampleCount, sumMu, sumMuSquared };
}

/** Runs the sampling pass on a device (the widget's, or Dawn's in the tests). */
export async function sampleHistogramGpu(
  device: GPUDevice,
  code: string,
  inputs: HgLobeInputs,
  layout: PolarLayout,
): Promise<HgHistogram> {
  const { output, gpuMs, wallMs } = await runCompute(device, {
    code,
    entryPoint: 'sampleCosines',
    inputs: [],
    outputWords: histogramWords(inputs.sampleCount),
    workgroups: [workgroupsFor(inputs.sampleCount)],
    uniforms: packParams(inputs, layout),
  });
  return {
    ...unpackHistogram(output, inputs.sampleCount),
    milliseconds: gpuMs ?? wallMs,
    timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
  };
}

export class HgLobeGpu {
  private picture: Promise<FullScreenPass> | null = null;

  constructor(
    private readonly gpu: GpuContext,
    private readonly canvas: HTMLCanvasElement,
  ) {}

  private pass(): Promise<FullScreenPass> {
    this.picture ??= linkLibraryKernel(STATIC_KERNELS, KERNEL).then((code) =>
      FullScreenPass.create(this.gpu, this.canvas, {
        label: 'hg-lobe',
        code,
        vertexEntry: 'fullScreenVertex',
        fragmentEntry: 'lobeFragment',
        uniformBytes: PARAMS.size,
      }),
    );
    this.picture.catch(() => {
      this.picture = null;
    });
    return this.picture;
  }

  async sample(inputs: HgLobeInputs, layout: PolarLayout): Promise<HgHistogram> {
    const code = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
    return sampleHistogramGpu(this.gpu.device, code, inputs, layout);
  }

  async draw(inputs: HgLobeInputs, layout: PolarLayout): Promise<void> {
    const pass = await this.pass();
    await pass.draw(packParams(inputs, layout));
  }

  destroy(): void {
    void this.picture?.then((pass) => pass.destroy());
  }
}
