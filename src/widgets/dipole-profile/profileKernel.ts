// The profile kernel of <sb-dipole-profile> (shaders/kernels/dipole-profile.wesl) as a
// device call: its uniform block and the compute pass that samples the three diffusion
// profiles. No browser imports, so the tests and the bench run it through Dawn too.
import { runCompute } from '../../gpu/compute.ts';
import { packStruct } from '../../gpu/layout.ts';
import { dipoleProfileKernel } from '../../gpu/layouts.generated.ts';
import type { GpuTiming } from '../base/imageKernel.ts';
import {
  GRID_COUNT,
  GRID_R_MAX,
  GRID_R_MIN,
  unpackProfiles,
  type ProfileCurves,
  type ProfileInputs,
} from './model.ts';

export const PROFILE_KERNEL = 'kernels/dipole-profile.wesl';
/** The kernel's uniform, laid out from its WGSL declaration. */
export const PROFILE_PARAMS = dipoleProfileKernel.DipoleProfileParams;

export function packParams(
  inputs: ProfileInputs,
  width: number,
  height: number,
): Uint32Array<ArrayBuffer> {
  return packStruct(PROFILE_PARAMS, {
    sigmaSPrime: [...inputs.sigmaSPrime, 0],
    sigmaA: [...inputs.sigmaA, 0],
    eta: inputs.eta,
    rMin: GRID_R_MIN,
    rMax: GRID_R_MAX,
    count: GRID_COUNT,
    exposure: inputs.exposure,
    viewRadius: inputs.view,
    width,
    height,
  });
}

export interface GpuCurves {
  curves: ProfileCurves;
  milliseconds: number;
  timing: GpuTiming;
}

/** The curves on a device (the widget's, or Dawn's in the tests). */
export async function evaluateProfilesGpu(
  device: GPUDevice,
  code: string,
  inputs: ProfileInputs,
): Promise<GpuCurves> {
  const { output, gpuMs, wallMs } = await runCompute(device, {
    code,
    entryPoint: 'evaluateProfiles',
    inputs: [],
    outputWords: 9 * GRID_COUNT + 15,
    workgroups: [Math.ceil((GRID_COUNT + 1) / 64)],
    uniforms: packParams(inputs, 1, 1),
  });
  return {
    curves: unpackProfiles(new Float32Array(output.buffer, output.byteOffset, output.length)),
    milliseconds: gpuMs ?? wallMs,
    timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
  };
}
