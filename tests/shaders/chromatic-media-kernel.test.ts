// The <sb-chromatic-media> kernel (shaders/kernels/chromatic-media.wesl) on Dawn against its
// float64 twin (src/widgets/chromatic-media/model.ts, renderChromaticCpu): the same picture,
// pixel by pixel from the same PCG streams, for each estimator; and the three estimators
// agree with each other on the picture's mean (all unbiased for the same radiance).
import { describe, expect, it } from 'vitest';
import { linkKernel } from '../../src/gpu/link.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { chromaticPassGpu } from '../../src/widgets/chromatic-media/gpuBackend.ts';
import {
  PIXEL_WORDS,
  renderChromaticCpu,
  type ChromaticInputs,
} from '../../src/widgets/chromatic-media/model.ts';

const KERNEL = readFileSync(
  fileURLToPath(new URL('../../shaders/kernels/chromatic-media.wesl', import.meta.url)),
  'utf8',
);

const INPUTS: ChromaticInputs = {
  spread: 16,
  density: 2,
  albedo: 0.9,
  g: 0.3,
  spp: 2,
  target: 2,
  exposure: 0,
};
const SIZE = 16;

/** Per-pixel z-scores of the difference of two pictures' means (pixels with variance only). */
function zScores(a: ArrayLike<number>, b: ArrayLike<number>, spp: number): number[] {
  const z: number[] = [];
  for (let i = 0; i < SIZE * SIZE; i++)
    for (let c = 0; c < 3; c++) {
      const stats = [a, b].map((sums) => {
        const mean = (sums[PIXEL_WORDS * i + c] ?? 0) / spp;
        const square = (sums[PIXEL_WORDS * i + 3 + c] ?? 0) / spp;
        return { mean, se2: Math.max(square - mean * mean, 0) / (spp - 1) };
      });
      const se2 = stats[0]!.se2 + stats[1]!.se2;
      if (se2 > 0) z.push((stats[0]!.mean - stats[1]!.mean) / Math.sqrt(se2));
    }
  return z;
}

describe('chromatic-media kernel vs its twin', () => {
  for (const estimator of [0, 1, 2, 3]) {
    it(`estimator ${estimator}: the twin replays ≥ 90% of the pixels to 1e-3`, async () => {
      const device = await nodeDevice();
      const code = await linkKernel(SHADER_LIBRARY, KERNEL);
      const gpu = await chromaticPassGpu(device, code, INPUTS, estimator, SIZE, 2, 5);
      const twin = renderChromaticCpu(INPUTS, estimator, SIZE, 2, 5);
      let agree = 0;
      for (let i = 0; i < SIZE * SIZE; i++) {
        let same = true;
        for (let c = 0; c < 3; c++) {
          const a = gpu.sums[PIXEL_WORDS * i + c]!;
          const b = twin.sums[PIXEL_WORDS * i + c]!;
          if (!Number.isFinite(a) || Math.abs(a - b) > 1e-3 * Math.max(Math.abs(b), 1e-2))
            same = false;
        }
        if (same) agree++;
      }
      // Misses: a long walk's f32 position drifts from float64 until one comparison flips.
      expect(agree / (SIZE * SIZE)).toBeGreaterThanOrEqual(0.9);
    }, 60_000);
  }

  it('the three estimators estimate the same picture, pixel by pixel (z-scores)', async () => {
    const device = await nodeDevice();
    const code = await linkKernel(SHADER_LIBRARY, KERNEL);
    const spp = 256;
    const runs = await Promise.all(
      [0, 1, 2].map((e) => chromaticPassGpu(device, code, INPUTS, e, SIZE, spp, 11)),
    );
    for (const other of [runs[1]!, runs[2]!]) {
      const z = zScores(runs[0]!.sums, other.sums, spp);
      const n = z.length;
      const meanZ = z.reduce((x, y) => x + y, 0) / n;
      const meanZ2 = z.reduce((x, y) => x + y * y, 0) / n;
      // Unbiased estimators: z has mean 0 and variance ≈ 1 (the SEs are themselves estimated
      // from 256 samples, so a bias of one SE per pixel would show as mean z ≈ 1).
      expect(Math.abs(meanZ), `mean z ${meanZ} over ${n}`).toBeLessThan(0.15);
      expect(meanZ2, `mean z² ${meanZ2}`).toBeLessThan(1.5);
    }
  }, 120_000);
});
