// The inverse-render widget's kernels (shaders/kernels/inverse-render.wesl), run
// through Dawn exactly as the widget dispatches them (InverseTrainerGpu), against
// the float64 twin in src/widgets/inverse-render/model.ts: the target images, the
// rendered grid, the gradient of the loss with respect to every parameter (with and
// without a regularizer), the hard cases, and whole optimization runs (the GPU
// follows the twin's trajectory; the loss falls tenfold within a bounded number of
// iterations, with the full batch and with random batches).
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { cameraRay } from '../../src/reference/camera.ts';
import { marchSegment, type ParameterGrid } from '../../src/reference/inverse.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { InverseTrainerGpu, KERNEL } from '../../src/widgets/inverse-render/gpuBackend.ts';
import {
  BACKGROUND,
  BOX_MAX,
  BOX_MIN,
  InverseOptimizerCpu,
  PREVIEW_TARGET_STEPS,
  addRegularizerCpu,
  lossAndGradientCpu,
  problemCameras,
  problemFrom,
  renderGridCpu,
  renderTargetsCpu,
  type Hyper,
  type Problem,
} from '../../src/widgets/inverse-render/model.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

const FULL: Hyper = { learningRate: 0.05, regularizer: 0, regularizerWeight: 0, batch: 1e9 };

function problem(resolution: number, views: number, size: number, steps: number): Problem {
  return {
    ...problemFrom({ grid: resolution, views, steps, seed: 1, novel: 60 }, 'gpu'),
    size,
  };
}

async function trainer(
  p: Problem,
  options: { previewSteps?: number } = {},
): Promise<InverseTrainerGpu> {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
  return InverseTrainerGpu.create(device, code, p, options);
}

/** Raw values uniform in [lo, hi] (ρ) and [−2, 2] (emission), rounded to f32 for both sides. */
function randomField(
  resolution: number,
  seed: number,
  lo: number,
  hi: number,
): Float32Array<ArrayBuffer> {
  const state = { value: rngSeed(resolution, seed) };
  const values = new Float32Array(4 * resolution ** 3);
  for (let i = 0; i < values.length; i++) {
    const u = rngNextFloat(state);
    values[i] = i % 4 === 0 ? lo + (hi - lo) * u : -2 + 4 * u;
  }
  return values;
}

function gridOf(values: Float32Array, resolution: number): ParameterGrid {
  return { resolution, values: Float64Array.from(values), boxMin: BOX_MIN, boxMax: BOX_MAX };
}

/** Training and held-out pixels (flattened indices) whose rays miss the box. */
function missingPixels(p: Problem): number[] {
  const missing: number[] = [];
  problemCameras(p).forEach((camera, view) => {
    for (let y = 0; y < p.size; y++)
      for (let x = 0; x < p.size; x++) {
        const ray = cameraRay(camera, [x + 0.5, y + 0.5]);
        if (marchSegment(BOX_MIN, BOX_MAX, ray.origin, ray.direction, p.steps).count === 0)
          missing.push((view * p.size + y) * p.size + x);
      }
  });
  return missing;
}

/**
 * Per-parameter tolerance of the f32 gradient. The twin reports, per parameter, the
 * sum over its contributions of the size of the numbers each is made of (weight ×
 * activation slope × h|g|(T + max C) for ρ; the same with T·α·|g| for e). Against
 * that scale the kernel's rounding is small (the running C − L_{≤k} cancels at most
 * n·2⁻²⁴ of C, the CAS sums add ≤ 2⁻²⁴ per term), but the sample positions carry
 * ≈ 1e-6 m of rounding (cameras 3.6 m away, 4 ULP); across voxels of Δ = 0.25 m the
 * trilinear fractions move by 4e-6, ρ by 4e-6 × its neighbour differences (≤ 3),
 * σt = 10·softplus(ρ) by ≤ 1.2e-4 m⁻¹, and over a chord of ≤ 3.5 m every
 * transmittance by ≤ 4e-4 relatively. Measured worst: 1.1e-4 (dense grid).
 */
const GRADIENT_TOLERANCE = 5e-4;

describe('inverse-render kernels vs the float64 twin', () => {
  it('renderTarget draws the hidden volume as renderTargetsCpu does (192 steps, every view), with or without a preview never read', async () => {
    const p = problem(8, 3, 12, 16);
    const twin = renderTargetsCpu(p);
    // Without a preview, and with one that is never read: the exact targets are held back
    // until the preview has come back (gpuBackend.ts), and readTargets must still get them.
    for (const options of [{}, { previewSteps: PREVIEW_TARGET_STEPS }]) {
      const gpu = await trainer(p, options);
      const targets = await gpu.readTargets();
      // 192 steps of exp (≤ 3 + 2x ULP) and positions off by 1e-6 m in a field whose
      // σt changes by at most ≈ 100 m⁻¹ per m: τ moves by < 2e-5 over a chord.
      let worst = 0;
      for (let i = 0; i < twin.length; i++)
        worst = Math.max(worst, Math.abs(targets[i]! - twin[i]!));
      expect(worst).toBeLessThan(1e-4);
      gpu.destroy();
    }
  });

  it('the targets’ preview (PREVIEW_TARGET_STEPS) comes first, as the twin draws it, and the exact targets stay exact', async () => {
    const p = problem(8, 3, 12, 16);
    const gpu = await trainer(p, { previewSteps: PREVIEW_TARGET_STEPS });
    const preview = await gpu.readPreviewTargets();
    expect(preview).not.toBeNull();
    // Read once only.
    expect(await gpu.readPreviewTargets()).toBeNull();
    const targets = await gpu.readTargets();
    const twin = renderTargetsCpu(p);
    const twinPreview = renderTargetsCpu(p, problemCameras(p), PREVIEW_TARGET_STEPS);
    let exact = 0;
    let previewError = 0;
    let differs = 0;
    for (let i = 0; i < twin.length; i++) {
      exact = Math.max(exact, Math.abs(targets[i]! - twin[i]!));
      previewError = Math.max(previewError, Math.abs(preview![i]! - twinPreview[i]!));
      if (preview![i] !== targets[i]) differs += 1;
    }
    // The exact targets are not disturbed by the preview's parameters (192 steps), and the
    // preview is the midpoint rule with PREVIEW_TARGET_STEPS samples, not the exact targets
    // read early.
    expect(exact).toBeLessThan(1e-4);
    expect(previewError).toBeLessThan(1e-4);
    expect(differs).toBeGreaterThan(twin.length / 4);
    gpu.destroy();
  });

  it('renderField draws a random grid as renderGridCpu does, and a ray that misses shows the background', async () => {
    const p = problem(8, 2, 12, 16);
    const gpu = await trainer(p);
    const values = randomField(8, 3, -3, 2);
    gpu.writeField(values);
    const { image } = await gpu.render();
    const cameras = problemCameras(p);
    const twin = renderGridCpu(gridOf(values, 8), cameras, p.size, p.steps);
    let worst = 0;
    for (let i = 0; i < twin.length; i++) worst = Math.max(worst, Math.abs(image[i]! - twin[i]!));
    expect(worst).toBeLessThan(GRADIENT_TOLERANCE);
    // The image corners look past the box: exactly the background there.
    const missing = missingPixels(p);
    expect(missing.length).toBeGreaterThan(0);
    for (const i of missing)
      for (let c = 0; c < 3; c++) expect(image[3 * i + c]).toBe(Math.fround(BACKGROUND[c]!));
    gpu.destroy();
  });

  for (const [label, seed, lo, hi] of [
    ['mixed density', 1, -3, 2],
    ['thin haze', 2, -6, -2],
    ['dense', 3, 0, 3],
  ] as const) {
    it(`lossGradient: ∂L/∂θ of every parameter within the f32 budget (${label}, 8³, 2 views of 8×8, 16 steps)`, async () => {
      const p = problem(8, 2, 8, 16);
      const gpu = await trainer(p);
      const values = randomField(8, seed, lo, hi);
      gpu.writeField(values);
      const targets = await gpu.readTargets();
      const { loss, gradient } = await gpu.lossAndGradient(FULL);
      const twin = lossAndGradientCpu(gridOf(values, 8), p, Float64Array.from(targets), {
        withMagnitude: true,
      });
      expect(loss).toBeCloseTo(twin.loss, 5);
      // Some rays of these views miss the box (their contributions are 0 on both sides).
      expect(missingPixels(p).some((i) => i < 2 * 64)).toBe(true);
      let worst = 0;
      for (let i = 0; i < gradient.length; i++) {
        expect(Number.isFinite(gradient[i]!)).toBe(true);
        const scale = twin.magnitude![i]!;
        const difference = Math.abs(gradient[i]! - twin.gradient[i]!);
        if (scale === 0) expect(gradient[i]).toBe(0);
        else worst = Math.max(worst, difference / scale);
      }
      expect(worst).toBeLessThan(GRADIENT_TOLERANCE);
      gpu.destroy();
    });
  }

  for (const [name, regularizer] of [
    ['total variation', 1],
    ['sparsity', 2],
  ] as const) {
    it(`regularize adds the ${name} gradient as addRegularizerCpu does`, async () => {
      const p = problem(8, 2, 8, 16);
      const gpu = await trainer(p);
      const values = randomField(8, 5, -4, 2);
      gpu.writeField(values);
      const targets = await gpu.readTargets();
      const hyper: Hyper = { ...FULL, regularizer, regularizerWeight: 0.02 };
      const { gradient } = await gpu.lossAndGradient(hyper);
      const grid = gridOf(values, 8);
      const twin = lossAndGradientCpu(grid, p, Float64Array.from(targets), { withMagnitude: true });
      const regularized = Float64Array.from(twin.gradient);
      addRegularizerCpu(grid, hyper, regularized);
      // The regularizer's own terms: λ/V·2(n ρ − Σρ) or λ/V·(softplus, sigmoid), ≈ 1e-6 relative.
      const regularizerScale = (0.02 / 512) * 2 * 6 * 4;
      for (let i = 0; i < gradient.length; i++) {
        const budget = GRADIENT_TOLERANCE * twin.magnitude![i]! + 1e-6 * regularizerScale;
        expect(Math.abs(gradient[i]! - regularized[i]!)).toBeLessThanOrEqual(budget);
      }
      expect(regularized.some((g, i) => Math.abs(g - twin.gradient[i]!) > 1e-6)).toBe(true);
      gpu.destroy();
    });
  }

  it('hard cases: an empty grid and an opaque grid give finite gradients and no dropped adds', async () => {
    const p = problem(8, 2, 8, 16);
    for (const raw of [-30, 30]) {
      const gpu = await trainer(p);
      gpu.writeField(randomField(8, 9, raw, raw));
      const { loss, gradient } = await gpu.lossAndGradient(FULL);
      expect(Number.isFinite(loss)).toBe(true);
      expect(gradient.every(Number.isFinite)).toBe(true);
      const report = await gpu.train(1, FULL);
      expect(report.dropped).toBe(0);
      expect(Number.isFinite(report.losses[0]!)).toBe(true);
      gpu.destroy();
    }
  });
});

describe('optimization on the GPU (fixed seed, 16³, 4 views of 16×16, 32 steps, η = 0.05)', () => {
  const p = problem(16, 4, 16, 32);

  it('follows the float64 optimizer: the first 6 losses agree to 1e-4 relatively', async () => {
    const gpu = await trainer(p);
    const report = await gpu.train(6, FULL);
    const cpu = new InverseOptimizerCpu(p, Float64Array.from(await gpu.readTargets()));
    for (let i = 0; i < 6; i++) {
      const twin = cpu.step(FULL);
      expect(Math.abs(report.losses[i]! - twin) / twin).toBeLessThan(1e-4);
    }
    expect(report.iteration).toBe(6);
    gpu.destroy();
  });

  // Measured on Dawn: 10× after 61 iterations with the full batch (1024 rays; the
  // float64 optimizer's own test in tests/reference/inverse.test.ts), after 79 with
  // random batches of 256 rays, which this test runs (4× cheaper per iteration).
  for (const [label, batch, bound] of [['random batches of 256 rays', 256, 150]] as const) {
    it(`with ${label}, the loss falls below 1/10 of its start within ${bound} iterations`, async () => {
      const gpu = await trainer(p);
      const report = await gpu.train(bound, { ...FULL, batch });
      const losses = Array.from(report.losses);
      expect(losses[0]).toBeGreaterThan(0.01);
      // Batches are noisy: average over 5 iterations before comparing.
      const smoothed = (i: number): number =>
        losses.slice(Math.max(0, i - 4), i + 1).reduce((a, b) => a + b, 0) / Math.min(i + 1, 5);
      expect(smoothed(losses.length - 1)).toBeLessThan(losses[0]! / 10);
      expect(losses.every(Number.isFinite)).toBe(true);
      expect(report.dropped).toBe(0);
      gpu.destroy();
    }, 60_000);
  }
});
