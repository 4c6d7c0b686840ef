// The float64 work of <sb-raymarch-steps>'s CPU fallback, run in the compute worker
// (src/workers/compute.ts) and cached there by arguments: the marched image at the
// fallback's resolution, and the converged reference (once per density). No DOM, no GPU.
import { referenceCpu, renderCpu } from './cpuBackend.ts';
import type { MarchImage, MarchInputs } from './model.ts';

export const jobs = {
  /** The float64 image with `steps` steps per ray and its CPU time (ms). */
  render(inputs: MarchInputs, steps: number): { image: MarchImage; milliseconds: number } {
    return renderCpu(inputs, steps);
  },
  /** The reference image (N = REFERENCE_STEPS, midpoint, exact update) of a density. */
  reference(density: number): Float64Array {
    return referenceCpu(density);
  },
};
