// The profile kernel of <sb-dipole-profile> (shaders/kernels/dipole-profile.wesl) as a
// device call: its uniform block and the compute pass that samples the three diffusion
// profiles. No browser imports, so the tests and the bench run it through Dawn too.
import { runCompute } from '../../gpu/compute.ts';
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
/** Byte size of DipoleProfileParams. */
export const PARAMS_BYTES = 64;

export function packParams(
  inputs: ProfileInputs,
  width: number,
  height: number,
): Uint32Array<ArrayBuffer> {
  const buffer = new ArrayBuffer(PARAMS_BYTES);
  const f32 = new Float32Array(buffer);
  const u32 = new Uint32Array(buffer);
  for (let c = 0; c < 3; c++) {
    f32[c] = inputs.sigmaSPrime[c]!;
    f32[4 + c] = inputs.sigmaA[c]!;
  }
  f32[8] = inputs.eta;
  f32[9] = GRID_R_MIN;
  f32[10] = GRID_R_MAX;
  u32[11] = GRID_COUNT;
  f32[12] = inputs.exposure;
  f32[13] = inputs.view;
  f32[14] = width;
  f32[15] = height;
  return u32;
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
