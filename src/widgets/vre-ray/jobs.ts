// <sb-vre-ray>'s work for the compute worker (src/workers): the CPU fallback's ray picture.
import { paintRay } from './cpuBackend.ts';

export const jobs = { paintRay };
