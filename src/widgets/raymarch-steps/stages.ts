// The progressive refinement of <sb-raymarch-steps> on the GPU (issue 23): the image
// at 1/4, then 1/2, then all of its side, each with the reader's N steps per ray and
// compared with a reference of its own size. The marches are the same per ray, so a
// coarse stage is the full picture seen through larger pixels.
import type { Rung } from '../base/refinement.ts';
import { IMAGE_HEIGHT, IMAGE_WIDTH } from './model.ts';

/** The divisors of the image's side, coarse to full. */
export const STAGE_SCALES = [4, 2, 1] as const;

export interface ImageSize {
  width: number;
  height: number;
}

/**
 * The rungs for N steps per ray: work is rays × steps, so that the cost per unit of
 * work learnt at one N predicts another's (a march's cost grows with its steps).
 */
export function imageRungs(steps: number): Rung<ImageSize>[] {
  const n = Math.max(1, Math.round(steps));
  return STAGE_SCALES.map((scale) => {
    const width = Math.max(1, Math.round(IMAGE_WIDTH / scale));
    const height = Math.max(1, Math.round(IMAGE_HEIGHT / scale));
    return {
      value: { width, height },
      work: width * height * n,
      label: `${width}×${height} pixels`,
    };
  });
}
