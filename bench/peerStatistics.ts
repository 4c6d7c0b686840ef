// Statistics of the peers bench (bench/peers.ts) that do not need a GPU or Mitsuba,
// kept apart so that tests/bench can check them.

/**
 * The standard error of an RGB image's mean over pixels and channels, from the variances
 * of its values (pixel by pixel, RGB interleaved): per channel √(Σ_p v_p)/P, the pixels
 * being independent, averaged over the channels. A channel's values are not independent of
 * the other channels' (the same paths carry all three; a gray scene's are equal), so the
 * channels' errors add as if fully correlated: an upper bound, exact for gray scenes.
 * Summing all 3P variances as independent understated the error by √3 for the gray peer
 * scenes, and with it inflated the agreement |z| (2.7 for the grid, 1.6 corrected).
 */
export function imageMeanStandardError(valueVariances: ArrayLike<number>, channels = 3): number {
  const pixels = Math.floor(valueVariances.length / channels);
  if (pixels === 0) return NaN;
  let sum = 0;
  for (let c = 0; c < channels; c++) {
    let channel = 0;
    for (let p = 0; p < pixels; p++) channel += valueVariances[p * channels + c]!;
    sum += Math.sqrt(channel) / pixels;
  }
  return sum / channels;
}
