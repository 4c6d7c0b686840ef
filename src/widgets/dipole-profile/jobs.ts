// The float64 work of <sb-dipole-profile>'s CPU fallback that ran on the page at every
// input (issue 23): the three profiles per channel (model.ts, evaluateProfilesCpu) and
// the lit disc's pixels (cpuBackend.ts, discPixelsCpu), and the Monte Carlo replay in
// chunks of batches (cpuBackend.ts, monteCarloCpu). They run in the compute worker
// (src/workers/compute.ts), cached there by the parameters each depends on, so a change
// of exposure redraws the disc without recomputing the curves, and a change of g or
// of the photon target recomputes neither. No DOM, no GPU.
import type { SlabRun } from '../../subsurface/slabKernel.ts';
import {
  curvesCpu,
  discPixelsCpu,
  slabChunkCpu,
  type DiscInputs,
  type DiscPixels,
  type SlabChunk,
} from './cpuBackend.ts';
import type { CurveInputs, ProfileCurves, ProfileInputs } from './model.ts';

/** The fields of the inputs the curves depend on (the job's cache key). */
export const curveInputsOf = (inputs: ProfileInputs): CurveInputs => ({
  sigmaSPrime: inputs.sigmaSPrime,
  sigmaA: inputs.sigmaA,
  eta: inputs.eta,
});

/** The fields of the inputs the disc depends on (the job's cache key). */
export const discInputsOf = (inputs: ProfileInputs): DiscInputs => ({
  ...curveInputsOf(inputs),
  exposure: inputs.exposure,
  view: inputs.view,
});

export const jobs = {
  /** The dipole, better-dipole and Burley profiles on the grid, their totals, and the time (ms). */
  curves(inputs: CurveInputs): { curves: ProfileCurves; milliseconds: number } {
    return curvesCpu(inputs);
  },
  /** The disc picture's bytes at CPU_DISC_SIZE² and the time (ms). */
  disc(inputs: DiscInputs): DiscPixels {
    return discPixelsCpu(inputs);
  },
  /** Batches [first, last) of the twin's Monte Carlo replay of `run` (cpuBackend.ts, monteCarloCpu). */
  slabChunk(run: SlabRun, first: number, last: number): SlabChunk {
    return slabChunkCpu(run, first, last);
  },
};
