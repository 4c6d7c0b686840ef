// The raymarch-steps widget's kernel (shaders/kernels/raymarch-steps.wesl), run
// through Dawn exactly as the widget dispatches it, against the float64 twin in
// src/widgets/raymarch-steps/model.ts (same rays, same marches, same PCG streams);
// and the orders of convergence the chapter states (physics.md §3), measured on the twin.
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { renderImageGpu } from '../../src/widgets/raymarch-steps/gpuBackend.ts';
import {
  RAY_LENGTH,
  REFERENCE_STEPS,
  SWEEP_STEPS,
  convergenceSlope,
  inputsFrom,
  referenceImageCpu,
  renderImageCpu,
  rmse,
  type MarchInputs,
} from '../../src/widgets/raymarch-steps/model.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

const KERNEL = 'kernels/raymarch-steps.wesl';
const WIDTH = 32;
const HEIGHT = 20;
const EPSILON = 2 ** -24;

function inputs(placement: string, update: string, steps: number, density = 1.5): MarchInputs {
  return inputsFrom({ steps, placement, update, density, seed: 7 });
}

/**
 * Absolute tolerance of one f32 pixel against its float64 twin (physics.md §10).
 * L depends on the step thicknesses x_i = σt(t_i)·h with |∂L/∂x_i| ≤ Le_max + L_bg
 * (a step gains at most T·Le_i and removes at most what lies behind it), with
 * Le_max = 1 + 2·1.5 = 4 and L_bg = 0.2, for both updates (the clamped linear
 * factor is continuous). Σ|Δx_i| ≤ d·|Δσt|: WGSL sin is allowed 2⁻¹¹ absolute,
 * times σ0·0.5 with σ0 ≤ 2σ̄, plus ≈ 16 ULP of σt from exp (σ0's bump), the phase
 * argument and t_i = (i + u)h. The compositing then rounds N times: 8·N ULP of
 * (Le_max + L_bg). The sin term dominates: 6.2e-3 at σ̄ = 1.5.
 */
function tolerance(input: MarchInputs): number {
  const sigma0Max = 2 * input.density;
  const deltaTau = RAY_LENGTH * sigma0Max * (0.5 * 2 ** -11 + 1.5 * 16 * EPSILON);
  return 4.2 * deltaTau + 8 * input.steps * EPSILON * 4.2;
}

async function gpuImage(input: MarchInputs, steps = input.steps) {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
  return renderImageGpu(device, code, input, WIDTH, HEIGHT, steps);
}

describe('raymarch-steps kernel vs the float64 twin, pixel by pixel', () => {
  for (const placement of ['left', 'midpoint', 'jittered-ray', 'jittered-strata'])
    for (const update of ['exact', 'linear'])
      for (const steps of [4, 64]) {
        it(`${placement}, ${update} update, N = ${steps}: every pixel within the f32 budget, same clamped steps`, async () => {
          const input = inputs(placement, update, steps);
          const gpu = await gpuImage(input);
          const cpu = renderImageCpu(WIDTH, HEIGHT, input);
          const tol = tolerance(input);
          let worst = 0;
          for (let i = 0; i < WIDTH * HEIGHT; i++) {
            expect(Number.isFinite(gpu.radiance[i]!)).toBe(true);
            worst = Math.max(worst, Math.abs(gpu.radiance[i]! - cpu.radiance[i]!));
          }
          expect(worst).toBeLessThan(tol);
          expect(gpu.capped).toBe(false);
          // A step with σt·h within ~1e-3 of 1 could round either way; none of these
          // images has one, so the counts agree exactly.
          expect(gpu.clampedSteps).toBe(cpu.clampedSteps);
        });
      }
});

describe('the linear update fails where σt·h > 1 (physics.md §1.1) and is clamped, not negative', () => {
  it('N = 4 at σ̄ = 1.5 (σt·h up to 2.25) clamps steps on the GPU and the twin; N = 64 clamps none', async () => {
    const coarse = inputs('left', 'linear', 4);
    const gpu = await gpuImage(coarse);
    expect(gpu.clampedSteps).toBeGreaterThan(0);
    expect(renderImageCpu(WIDTH, HEIGHT, coarse).clampedSteps).toBe(gpu.clampedSteps);
    for (const l of gpu.radiance) expect(l).toBeGreaterThanOrEqual(0);
    const fine = inputs('left', 'linear', 64);
    expect((await gpuImage(fine)).clampedSteps).toBe(0);
    expect(renderImageCpu(WIDTH, HEIGHT, fine).clampedSteps).toBe(0);
  });

  it('the exact update never clamps, even at σ̄ = 5 and N = 1 (σt·h = 30)', async () => {
    const input = inputs('left', 'exact', 1, 5);
    expect((await gpuImage(input)).clampedSteps).toBe(0);
  });
});

describe('orders of convergence on the twin (physics.md §3), RMSE ∝ N^p fitted over N = 4 … 64', () => {
  const reference = referenceImageCpu(WIDTH, HEIGHT, 1.5);
  const fitted = (placement: string, update: string): number => {
    const steps = SWEEP_STEPS.filter((n) => n >= 4 && n <= 64);
    const input = inputs(placement, update, 1);
    const errors = steps.map((n) =>
      rmse(renderImageCpu(WIDTH, HEIGHT, input, n).radiance, reference),
    );
    return -(convergenceSlope(steps, errors) ?? 0);
  };

  // Bands: the fitted order of a smooth integrand approaches the asymptotic one
  // from below as h shrinks; measured 0.97 (left), 2.00 (midpoint), 1.46 (strata), 1.07 (midpoint, linear).
  it('left samples converge at first order (0.85 … 1.15)', () => {
    const order = fitted('left', 'exact');
    expect(order).toBeGreaterThan(0.85);
    expect(order).toBeLessThan(1.15);
  });

  it('midpoint samples converge at second order (1.85 … 2.15)', () => {
    const order = fitted('midpoint', 'exact');
    expect(order).toBeGreaterThan(1.85);
    expect(order).toBeLessThan(2.15);
  });

  it('jittered strata fall between, near h^{3/2} (1.3 … 1.7)', () => {
    const order = fitted('jittered-strata', 'exact');
    expect(order).toBeGreaterThan(1.3);
    expect(order).toBeLessThan(1.7);
  });

  it('the linear update drags midpoint samples back to first order (0.85 … 1.25)', () => {
    const order = fitted('midpoint', 'linear');
    expect(order).toBeGreaterThan(0.85);
    expect(order).toBeLessThan(1.25);
  });

  it(`the N = ${REFERENCE_STEPS} reference is converged: it differs from N = 4096 by < 1/10 of the N = 256 midpoint RMSE`, () => {
    const fine = renderImageCpu(WIDTH, HEIGHT, inputs('midpoint', 'exact', 4096)).radiance;
    const at256 = rmse(
      renderImageCpu(WIDTH, HEIGHT, inputs('midpoint', 'exact', 256)).radiance,
      fine,
    );
    expect(rmse(reference, fine)).toBeLessThan(at256 / 10);
  });
});
