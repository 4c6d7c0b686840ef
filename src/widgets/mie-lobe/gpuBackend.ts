// GPU backend of <sb-mie-lobe>: shaders/kernels/mie-lobe.wesl evaluates the tabulated
// phase function (shaders/mie.wesl's phaseTabulatedEvalTerms) at the plot's angles.
// The table itself comes from the float64 series in the worker.
import { runCompute } from '../../gpu/compute.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import { PHASE_TABLE_NODES } from '../../reference/mie.ts';
import type { MieAnalysis } from './model.ts';

const KERNEL = 'kernels/mie-lobe.wesl';
const WORKGROUP_SIZE = 64;

/** The table as the kernel's PhaseTable: four arrays of f32, one after the other. */
export function packTable(table: MieAnalysis['table']): Uint32Array<ArrayBuffer> {
  const floats = new Float32Array(4 * PHASE_TABLE_NODES);
  floats.set(table.oneMinusMu, 0);
  floats.set(table.onePlusMu, PHASE_TABLE_NODES);
  floats.set(table.pdf, 2 * PHASE_TABLE_NODES);
  floats.set(table.cdf, 3 * PHASE_TABLE_NODES);
  return new Uint32Array(floats.buffer);
}

/** The angles as (1 − μ, 1 + μ) pairs. */
export function packComplements(
  oneMinusMu: Float64Array,
  onePlusMu: Float64Array,
): Uint32Array<ArrayBuffer> {
  const floats = new Float32Array(2 * oneMinusMu.length);
  oneMinusMu.forEach((t, i) => {
    floats[2 * i] = t;
    floats[2 * i + 1] = onePlusMu[i]!;
  });
  return new Uint32Array(floats.buffer);
}

export interface GpuLobe {
  values: Float64Array;
  milliseconds: number;
  timing: 'gpu-timestamp' | 'gpu-wall';
}

export class MieLobeGpu {
  constructor(private readonly gpu: GpuContext) {}

  async evaluate(
    table: MieAnalysis['table'],
    oneMinusMu: Float64Array,
    onePlusMu: Float64Array,
  ): Promise<GpuLobe> {
    const code = await linkLibraryKernel(STATIC_KERNELS, KERNEL);
    const count = oneMinusMu.length;
    const { output, gpuMs, wallMs } = await runCompute(this.gpu.device, {
      code,
      entryPoint: 'evaluateLobe',
      inputs: [packTable(table), packComplements(oneMinusMu, onePlusMu)],
      outputWords: count,
      workgroups: [Math.ceil(count / WORKGROUP_SIZE)],
    });
    return {
      values: Float64Array.from(new Float32Array(output.buffer, 0, count)),
      milliseconds: gpuMs ?? wallMs,
      timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
    };
  }
}
