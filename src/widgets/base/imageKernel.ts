// The GPU side shared by the image widgets: pack a kernel's 8-scalar uniform
// block, dispatch a per-pixel kernel (8×8 workgroups) with runCompute, and read
// its output buffer back with the time it took (timestamp queries where the
// GPU has them, wall time otherwise).
import { runCompute } from '../../gpu/compute.ts';
import type { GpuTiming } from './timing.ts';

export type { GpuTiming };

/** Views of a fresh uniform block of `bytes` bytes, as u32 and as f32 words. */
export function uniformWords(bytes: number): { u32: Uint32Array<ArrayBuffer>; f32: Float32Array } {
  const buffer = new ArrayBuffer(bytes);
  return { u32: new Uint32Array(buffer), f32: new Float32Array(buffer) };
}

export interface ImageKernelResult {
  /** The output buffer read back: wordsPerPixel planes of width·height words. */
  output: Uint32Array;
  milliseconds: number;
  timing: GpuTiming;
}

/** Runs the kernel's `renderImage` entry point over a width × height image. */
export async function runImageKernel(
  device: GPUDevice,
  code: string,
  width: number,
  height: number,
  wordsPerPixel: number,
  uniforms: Uint32Array<ArrayBuffer>,
): Promise<ImageKernelResult> {
  const { output, gpuMs, wallMs } = await runCompute(device, {
    code,
    entryPoint: 'renderImage',
    inputs: [],
    outputWords: wordsPerPixel * width * height,
    workgroups: [Math.ceil(width / 8), Math.ceil(height / 8)],
    uniforms,
  });
  return {
    output,
    milliseconds: gpuMs ?? wallMs,
    timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
  };
}
