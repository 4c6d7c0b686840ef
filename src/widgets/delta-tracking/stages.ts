// The progressive refinement of <sb-delta-tracking>'s single view (issue 23): the
// reader's spp is reached in stages of 1/16, 1/4 and all of the samples per pixel.
// The kernel draws a pixel's estimates one after another from the pixel's own PCG
// stream (shaders/kernels/delta-tracking.wesl, rngSeed(index, seed)), so the first
// s estimates of a stage are exactly the first s of the full picture: a later stage
// averages more of the same walks, and the picture refines rather than changes.
import type { Rung } from '../base/refinement.ts';

/** The fractions of the reader's spp drawn before it (the last stage draws all of it). */
export const STAGE_FRACTIONS = [1 / 16, 1 / 4] as const;

/**
 * The rungs of samples per pixel for a reader's `spp`, coarse to full, deduplicated.
 * A preview keeps at least 2 samples when the reader asked for 2 or more, since the
 * variance image and the bias test need two. Work is the sample count (per pixel of
 * a fixed image size), so costs learnt at one spp predict another's.
 */
export function sampleRungs(spp: number): Rung<number>[] {
  const full = Math.max(1, Math.round(spp));
  const floor = Math.min(2, full);
  const counts = [
    ...new Set([...STAGE_FRACTIONS.map((f) => Math.max(floor, Math.ceil(f * full))), full]),
  ].sort((a, b) => a - b);
  return counts.map((count) => ({
    value: count,
    work: count,
    label: count === full ? `${count} samples per pixel` : `${count} of ${full} samples per pixel`,
  }));
}
