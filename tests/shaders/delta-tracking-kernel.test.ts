// The delta-tracking widget's kernel (shaders/kernels/delta-tracking.wesl), run
// through Dawn exactly as the widget dispatches it, against the float64 twin in
// src/widgets/delta-tracking/model.ts (same rays, same estimators, same PCG
// streams); and the statistics chapter 6 states (physics.md §3, §4.1, §4.5),
// checked on the GPU output and on the twin: delta tracking's variance T(1 − T),
// the RMSE of every unbiased estimator falling as spp^(−½) while the biased one
// levels off (what the comparison's sweep shows), and the clamp to SPP_MAX that
// the comparison's equal-time allocation relies on.
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { renderImageGpu } from '../../src/widgets/delta-tracking/gpuBackend.ts';
import {
  SPP_MAX,
  exactImage,
  imageStatistics,
  inputsFrom,
  renderImageCpu,
  sampleVariance,
  type TrackingImage,
  type TrackingInputs,
} from '../../src/widgets/delta-tracking/model.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

const KERNEL = 'kernels/delta-tracking.wesl';
const WIDTH = 32;
const HEIGHT = 20;

function inputs(estimator: string, majorant: string, spp: number, seed = 7): TrackingInputs {
  return inputsFrom({ estimator, majorant, spp, seed });
}

async function gpuImage(input: TrackingInputs, width = WIDTH, height = HEIGHT) {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
  return renderImageGpu(device, code, input, width, height);
}

/**
 * Per-pixel tolerance of the GPU mean against the twin when both replay the same
 * walks. Delta tracking's estimates are exactly 0 or 1, so only the f32 sum of spp
 * of them rounds (exact below 2^24). The weighted estimators multiply ~τ̄ ≤ 20 factors
 * 1 − σt/σ̄ whose σt carries WGSL sin's 2⁻¹¹ absolute error times σ0·a ≤ 1.2 over σ̄ ≥ 0.6
 * (≈ 1e-3 per factor, so 2e-2 relative in the worst pixel); URM's series multiplies its
 * τ errors (≤ d·σ0·a·2⁻¹¹ ≈ 1.2e-3) by weights up to 1/w_k. exp(−τ̂) of one step carries
 * the same 1.2e-3. Hence 1e-6 for delta, 2e-2 for the others.
 */
const TOLERANCE: Readonly<Record<string, number>> = {
  biased: 2e-2,
  delta: 1e-6,
  ratio: 2e-2,
  residual: 2e-2,
  urm: 2e-2,
};

/**
 * A tentative collision whose acceptance test ξ < σt/σ̄ (or free flight against
 * the distance left) falls within f32 rounding of its threshold can go either way
 * on the GPU and the twin; the two walks then consume different numbers and the
 * pixel's later samples diverge. As in tests/shaders/tracking.test.ts such ties
 * are rare: at least 97% of the pixels must agree.
 */
const MIN_AGREEMENT = 0.97;

describe('delta-tracking kernel vs the float64 twin, pixel by pixel', () => {
  for (const estimator of ['biased', 'delta', 'ratio', 'residual', 'urm'])
    for (const majorant of ['tight', 'low'])
      for (const seed of [3, 11]) {
        it(`${estimator}, ${majorant} majorant, seed ${seed}: ≥ 97% of pixels replay the twin within the f32 budget`, async () => {
          const input = inputs(estimator, majorant, 8, seed);
          const gpu = await gpuImage(input);
          const cpu = renderImageCpu(WIDTH, HEIGHT, input);
          let agree = 0;
          for (let i = 0; i < WIDTH * HEIGHT; i++) {
            expect(Number.isFinite(gpu.mean[i]!)).toBe(true);
            const scale = Math.max(1, Math.abs(cpu.mean[i]!));
            if (Math.abs(gpu.mean[i]! - cpu.mean[i]!) <= TOLERANCE[estimator]! * scale) agree++;
          }
          expect(agree / (WIDTH * HEIGHT)).toBeGreaterThanOrEqual(MIN_AGREEMENT);
          expect(gpu.capped).toBe(0);
          expect(cpu.capped).toBe(0);
          // Lookups replay too, up to the diverged pixels (a few lookups each).
          expect(Math.abs(gpu.lookups - cpu.lookups)).toBeLessThanOrEqual(0.05 * cpu.lookups);
        });
      }
});

/** Mean bias over the pixels and its 5-SE bound from a per-pixel variance. */
function biasAndBound(image: TrackingImage, exact: Float64Array, variance: ArrayLike<number>) {
  const stats = imageStatistics(image, exact, variance);
  return { bias: stats.bias, bound: 5 * stats.biasError };
}

describe('statistics of the estimators on the widget image (GPU output and twin)', () => {
  const GPU_SPP = 64;
  const CPU_SPP = 16;
  const sources = [
    ['GPU', async (input: TrackingInputs) => gpuImage({ ...input, spp: GPU_SPP })],
    [
      'twin',
      async (input: TrackingInputs) => renderImageCpu(WIDTH, HEIGHT, { ...input, spp: CPU_SPP }),
    ],
  ] as const;

  for (const [name, render] of sources) {
    it(`${name}: delta tracking with a tight majorant is unbiased within 5 SE, SE from Var = T(1 − T) (physics.md §4.1)`, async () => {
      const image = await render(inputs('delta', 'tight', 1, 21));
      const exact = exactImage(WIDTH, HEIGHT);
      const { bias, bound } = biasAndBound(
        image,
        exact,
        Array.from(exact, (t) => t * (1 - t)),
      );
      expect(Math.abs(bias)).toBeLessThan(bound);
    });

    it(`${name}: delta tracking's per-pixel variance averages to T(1 − T) within 5 SE (physics.md §4.1)`, async () => {
      const image = await render(inputs('delta', 'loose', 1, 22));
      const exact = exactImage(WIDTH, HEIGHT);
      const variance = sampleVariance(image);
      let measured = 0;
      let predicted = 0;
      for (let i = 0; i < exact.length; i++) {
        measured += variance[i]!;
        predicted += exact[i]! * (1 - exact[i]!);
      }
      // Var(s²) ≤ μ₄/n and μ₄ ≤ σ² for |X − T| ≤ 1, so SE(Σs²) ≤ sqrt(Σσ²/n).
      const bound = 5 * Math.sqrt(predicted / image.spp);
      expect(Math.abs(measured - predicted)).toBeLessThan(bound);
    });

    it(`${name}: exp(−τ̂) of one jittered step is biased high by more than 5 SE (Jensen, physics.md §3)`, async () => {
      const image = await render(inputs('biased', 'tight', 1, 23));
      const { bias, bound } = biasAndBound(image, exactImage(WIDTH, HEIGHT), sampleVariance(image));
      expect(bias).toBeGreaterThan(bound);
    });

    it(`${name}: delta tracking with a majorant below σt is biased high by more than 5 SE (physics.md §4.5)`, async () => {
      const image = await render(inputs('delta', 'low', 1, 24));
      const { bias, bound } = biasAndBound(image, exactImage(WIDTH, HEIGHT), sampleVariance(image));
      expect(bias).toBeGreaterThan(bound);
    });

    for (const estimator of ['ratio', 'residual', 'urm'])
      for (const majorant of ['tight', 'low'])
        it(`${name}: ${estimator} with a ${majorant} majorant is unbiased within 5 SE (physics.md §4.2–4.5)`, async () => {
          const image = await render(inputs(estimator, majorant, 1, 25));
          const { bias, bound } = biasAndBound(
            image,
            exactImage(WIDTH, HEIGHT),
            sampleVariance(image),
          );
          expect(Math.abs(bias)).toBeLessThan(bound);
        });
  }
});

/**
 * Mean squared error of the pixel means against the exact T, with its standard
 * error from the spread of the per-pixel squared errors (the pixels are
 * independent: each has its own PCG stream).
 */
function mseWithError(image: TrackingImage, exact: Float64Array): { mse: number; se: number } {
  const pixels = exact.length;
  let sum = 0;
  let sumSquares = 0;
  for (let i = 0; i < pixels; i++) {
    const e2 = (image.mean[i]! - exact[i]!) ** 2;
    sum += e2;
    sumSquares += e2 * e2;
  }
  const mse = sum / pixels;
  const variance = Math.max(sumSquares / pixels - mse * mse, 0) * (pixels / (pixels - 1));
  return { mse, se: Math.sqrt(variance / pixels) };
}

describe('convergence with spp on the GPU (the comparison sweep, physics.md §3–4)', () => {
  const LOW = 4;
  const HIGH = 64;
  const exact = exactImage(WIDTH, HEIGHT);

  for (const estimator of ['delta', 'ratio', 'residual', 'urm'])
    it(`${estimator}: RMSE ∝ spp^p with p = −½ within 5 SE between spp ${LOW} and ${HIGH}`, async () => {
      // Different seeds, so the two images are independent.
      const low = mseWithError(await gpuImage(inputs(estimator, 'tight', LOW, 31)), exact);
      const high = mseWithError(await gpuImage(inputs(estimator, 'tight', HIGH, 32)), exact);
      // p = ½ ln(MSE_high/MSE_low)/ln(HIGH/LOW); its SE by the delta method.
      const ln = Math.log(HIGH / LOW);
      const p = (0.5 * Math.log(high.mse / low.mse)) / ln;
      const se = (0.5 * Math.hypot(low.se / low.mse, high.se / high.mse)) / ln;
      expect(Math.abs(p + 0.5)).toBeLessThan(5 * se);
      expect(se).toBeLessThan(0.05); // the bound is tight enough to mean something
    });

  it(`biased exp(−τ̂): the MSE at spp ${HIGH} stays far above 1/${HIGH / LOW} of the MSE at spp ${LOW} (the plateau)`, async () => {
    const low = mseWithError(await gpuImage(inputs('biased', 'tight', LOW, 33)), exact);
    const high = mseWithError(await gpuImage(inputs('biased', 'tight', HIGH, 34)), exact);
    const unbiasedWouldBe = low.mse / (HIGH / LOW);
    const se = Math.hypot(high.se, low.se / (HIGH / LOW));
    expect(high.mse - unbiasedWouldBe).toBeGreaterThan(5 * se);
  });
});

describe(`spp above the kernel's cap SPP_MAX = ${SPP_MAX} (the equal-time row clamps to it)`, () => {
  it('the GPU and the twin both average exactly SPP_MAX estimates', async () => {
    const input = inputs('delta', 'tight', 2 * SPP_MAX, 41);
    const gpu = await gpuImage(input, 16, 10);
    const cpu = renderImageCpu(16, 10, input);
    expect(gpu.spp).toBe(SPP_MAX);
    expect(cpu.spp).toBe(SPP_MAX);
    // Delta tracking's sums of 0/1 estimates are exact in f32: the means agree
    // wherever the walks replay (ties aside, as above), and the lookups match.
    let agree = 0;
    for (let i = 0; i < 160; i++) if (Math.abs(gpu.mean[i]! - cpu.mean[i]!) <= 1e-6) agree++;
    expect(agree / 160).toBeGreaterThanOrEqual(MIN_AGREEMENT);
    expect(Math.abs(gpu.lookups - cpu.lookups)).toBeLessThanOrEqual(0.05 * cpu.lookups);
  });
});
