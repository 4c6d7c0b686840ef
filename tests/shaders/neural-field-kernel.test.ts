// The neural field's kernels (shaders/kernels/neural-field.wesl), run through Dawn as
// the widget dispatches them (NeuralTrainerGpu), against the float64 twin
// (src/widgets/inverse-render/neuralModel.ts on src/reference/neural.ts): the
// rendered field, the loss and the gradient of every parameter (hash-table entries
// summed by the CAS loop along the ray, MLP weights by the workgroup reduction), and a
// short optimization whose loss falls.
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { neuralMlpOffset } from '../../src/reference/neural.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { KERNEL } from '../../src/widgets/inverse-render/gpuBackend.ts';
import {
  BOX_MAX,
  BOX_MIN,
  problemCameras,
  problemFrom,
  type Hyper,
  type Problem,
} from '../../src/widgets/inverse-render/model.ts';
import {
  NEURAL_KERNEL,
  NeuralTrainerGpu,
} from '../../src/widgets/inverse-render/neuralGpuBackend.ts';
import {
  initialNeuralField,
  lossAndGradientNeuralCpu,
  renderNeuralCpu,
} from '../../src/widgets/inverse-render/neuralModel.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice, 60_000);

const FULL: Hyper = { learningRate: 0.02, regularizer: 0, regularizerWeight: 0, batch: 1e9 };

function problem(tableLog2: number, views: number, size: number, steps: number): Problem {
  return {
    ...problemFrom({ model: 'neural', table: tableLog2, views, steps, seed: 1, novel: 60 }, 'gpu'),
    size,
  };
}

async function trainer(p: Problem): Promise<NeuralTrainerGpu> {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, NEURAL_KERNEL);
  const gridCode = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
  return NeuralTrainerGpu.create(device, code, gridCode, p);
}

/** A random network (rounded to f32 for both sides): table entries in ±tableScale, weights in ±0.8. */
function randomParameters(p: Problem, seed: number, tableScale: number): Float32Array<ArrayBuffer> {
  const values = new Float32Array(initialNeuralField(p.tableSize, seed).values);
  const state = { value: rngSeed(13, seed) };
  const offset = neuralMlpOffset(p.tableSize);
  for (let i = 0; i < values.length; i++) {
    const u = 2 * rngNextFloat(state) - 1;
    values[i] = i < offset ? tableScale * u : 0.8 * u;
  }
  values[offset + 336] = -1; // b₂'s density: σt ≈ 3 m⁻¹ at the start
  return values;
}

const fieldOf = (values: Float32Array, p: Problem) => ({
  tableSize: p.tableSize,
  values: Float64Array.from(values),
  boxMin: BOX_MIN,
  boxMax: BOX_MAX,
});

describe('neural-field kernels vs the float64 twin', () => {
  // The first test builds both kernels' pipelines, which takes SwiftShader a minute or
  // more on a loaded machine: generous time limits, no timings asserted.
  it(
    'renderField draws the twin’s image (training and held-out views) within 2e-5',
    { timeout: 240_000 },
    async () => {
      const p = problem(10, 2, 8, 16);
      const gpu = await trainer(p);
      const values = randomParameters(p, 1, 0.5);
      gpu.writeParameters(values);
      const { image } = await gpu.render();
      const twin = renderNeuralCpu(fieldOf(values, p), problemCameras(p), p.size, p.steps);
      let worst = 0;
      for (let i = 0; i < twin.length; i++) worst = Math.max(worst, Math.abs(image[i]! - twin[i]!));
      // f32 rounding of 16 samples × (64 table reads, 340 weights) and of the sample positions.
      expect(worst).toBeLessThan(2e-5);
      gpu.destroy();
    },
  );

  for (const [label, seed, tableScale, tableLog2] of [
    ['features ±0.5, 2¹⁰ entries (levels 0–3 dense)', 1, 0.5, 10],
    ['features ±2, 2⁸ entries (levels 0–2 dense, 5 hashed)', 2, 2, 8],
  ] as const) {
    it(
      `lossGradient: ∂L/∂θ of every parameter within the f32 budget (${label}, 2 views of 8×8, 16 steps)`,
      { timeout: 120_000 },
      async () => {
        const p = problem(tableLog2, 2, 8, 16);
        const gpu = await trainer(p);
        const values = randomParameters(p, seed, tableScale);
        gpu.writeParameters(values);
        const targets = await gpu.readTargets();
        const { loss, gradient, dropped } = await gpu.lossAndGradient(FULL);
        const twin = lossAndGradientNeuralCpu(fieldOf(values, p), p, Float64Array.from(targets), {
          withMagnitude: true,
        });
        expect(dropped).toBe(0);
        expect(Math.abs(loss - twin.loss)).toBeLessThan(1e-5 * twin.loss);
        const largest = twin.gradient.reduce((m, g) => Math.max(m, Math.abs(g)), 0);
        expect(largest).toBeGreaterThan(1e-5);
        let worst = 0;
        let nonzero = 0;
        for (let i = 0; i < gradient.length; i++) {
          expect(Number.isFinite(gradient[i]!)).toBe(true);
          const scale = twin.magnitude![i]!;
          if (scale === 0) {
            expect(gradient[i]).toBe(0);
            continue;
          }
          nonzero += 1;
          worst = Math.max(worst, Math.abs(gradient[i]! - twin.gradient[i]!) / scale);
        }
        expect(nonzero).toBeGreaterThan(1000);
        expect(worst).toBeLessThan(GRADIENT_TOLERANCE);
        gpu.destroy();
      },
    );
  }

  it(
    'training: 30 full-batch iterations (η = 0.05) at least halve the loss, no dropped adds',
    { timeout: 180_000 },
    async () => {
      const p = problem(10, 2, 8, 12);
      const gpu = await trainer(p);
      const report = await gpu.train(30, { ...FULL, learningRate: 0.05 });
      expect(report.losses).toHaveLength(30);
      expect(report.dropped).toBe(0);
      expect(report.losses[29]!).toBeLessThan(report.losses[0]! / 2);
      gpu.destroy();
    },
  );
});

/**
 * Per-parameter tolerance of the f32 gradient against Σ|contributions| of the twin:
 * each contribution is a product of f32 numbers (≈ 10 roundings), the CAS and the
 * workgroup sums add ≤ 2⁻²⁴ per term, and the kernel's radiance behind a sample,
 * C − L_{≤k}, cancels; the sample positions carry ≈ 1e-6 m of rounding (cameras 3.6 m
 * away), which moves the trilinear fractions of the finest level (4.4 cm cells) by
 * 2e-5 and the features by that times their neighbours' differences.
 */
const GRADIENT_TOLERANCE = 1e-3;
