// Float64 twin of shaders/moments.wesl: the per-pixel moments of a progressive render
// (running mean and M2, the sum of squared deviations, per channel; Chan, Golub &
// LeVeque 1979). The CPU accumulator (src/scene/accumulation.ts, ImageAccumulator) keeps
// the same moments in float64.
import type { Vec3 } from './directions.ts';

/** One pixel's moments, as the WGSL struct PixelMoments. */
export interface PixelMoments {
  mean: Vec3;
  lookups: number;
  m2: Vec3;
  capped: number;
}

/**
 * The per-pixel standard error of the mean, sqrt(M2 / (n (n − 1))) per channel: the
 * unbiased sample variance s² = M2 / (n − 1), divided by n. A negative M2 (rounding)
 * counts as 0; n < 2 has no estimate (the result is not finite), as in the shader.
 */
export function momentsStandardError(moments: PixelMoments, samples: number): Vec3 {
  const se = (m2: number): number => Math.sqrt(Math.max(m2, 0) / (samples * (samples - 1)));
  return [se(moments.m2[0]), se(moments.m2[1]), se(moments.m2[2])];
}
