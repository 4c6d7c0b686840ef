// How a widget's frame time was measured: GPU timestamp queries where the adapter
// has them (and they can be trusted, src/gpu/device.ts), wall time around the GPU
// work otherwise, or wall time of the CPU twin. The readouts and cost lines say which.

export type GpuTiming = 'gpu-timestamp' | 'gpu-wall';

/** How a render's time was measured, for the readout. */
export function timingLabel(timing: GpuTiming | 'cpu'): string {
  if (timing === 'gpu-timestamp') return 'GPU timestamp query';
  if (timing === 'gpu-wall') return 'wall time; this GPU has no timestamp queries';
  return 'CPU wall time';
}
