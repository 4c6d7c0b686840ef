// <sb-chromatic-media>'s work for the compute worker (src/workers): the CPU fallback's passes,
// the float64 twin of the kernel at the fallback's smaller picture.
import { renderChromaticCpu } from './model.ts';

export const jobs = { pass: renderChromaticCpu };
