// <sb-beer-law>'s work for the compute worker (src/workers): the CPU fallback's beam picture.
import { paintBeam } from './cpuBackend.ts';

export const jobs = { paintBeam };
