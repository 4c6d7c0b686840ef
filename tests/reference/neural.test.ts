// The float64 twin of shaders/neural.wesl (chapter 8): the hash encoding's pieces
// against their definitions (level resolutions, Instant-NGP's hash in exact integer
// arithmetic, dense indexing of the coarse levels), the analytic gradient of the image
// loss with respect to every MLP weight and to the hash-table entries against central
// finite differences of the twin's own loss on random small networks, and the
// optimization: with a fixed seed Adam lowers the neural field's loss at least
// fivefold within a bounded number of iterations.
import { describe, expect, it } from 'vitest';
import {
  NEURAL_HIDDEN,
  NEURAL_INPUTS,
  NEURAL_LEVELS,
  NEURAL_MLP_SIZE,
  hashCellLocate,
  hashGridIndex,
  hashLevelResolution,
  neuralBackward,
  neuralForward,
  neuralMlpOffset,
  spatialHash,
  type NeuralField,
} from '../../src/reference/neural.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import {
  BOX_MAX,
  BOX_MIN,
  problemFrom,
  renderTargetsCpu,
  type Hyper,
  type Problem,
} from '../../src/widgets/inverse-render/model.ts';
import {
  NeuralOptimizerCpu,
  initialNeuralField,
  lossAndGradientNeuralCpu,
  lossNeuralCpu,
} from '../../src/widgets/inverse-render/neuralModel.ts';

/** 2 views of 4×4 pixels, 10 samples per ray, 2⁸ entries per level (levels 0–2 dense). */
function smallProblem(views = 2): Problem {
  return {
    ...problemFrom({ model: 'neural', table: 8, views, steps: 10, seed: 0, novel: 60 }, 'gpu'),
    size: 4,
  };
}

/** A random network: table entries uniform in ±tableScale, weights in ±0.8, biases in ±0.3. */
function randomField(problem: Problem, seed: number, tableScale: number): NeuralField {
  const field = initialNeuralField(problem.tableSize, seed);
  const state = { value: rngSeed(11, seed) };
  const offset = neuralMlpOffset(problem.tableSize);
  for (let i = 0; i < field.values.length; i++) {
    const u = 2 * rngNextFloat(state) - 1;
    field.values[i] = i < offset ? tableScale * u : 0.8 * u;
  }
  // b₂: a medium density start (ρ ≈ −1, σt ≈ 3 m⁻¹), so that transmittance and emission both matter.
  field.values[offset + 336] = -1 + 0.3 * (2 * rngNextFloat(state) - 1);
  return field;
}

function randomTargets(problem: Problem, seed: number): Float64Array {
  const state = { value: rngSeed(7, seed) };
  const n = 3 * problem.views.length * problem.size * problem.size;
  return Float64Array.from({ length: n }, () => rngNextFloat(state));
}

describe('the hash encoding', () => {
  it('N_l = ⌊4·2^{l/2}⌋ exactly for l = 0 … 15 (4, 5, 8, 11, 16, 22, 32, 45 for the 8 levels)', () => {
    for (let l = 0; l < 16; l++) expect(hashLevelResolution(l)).toBe(Math.floor(4 * 2 ** (l / 2)));
    expect(Array.from({ length: 8 }, (_, l) => hashLevelResolution(l))).toEqual([
      4, 5, 8, 11, 16, 22, 32, 45,
    ]);
    expect(hashLevelResolution(40)).toBe(hashLevelResolution(15));
  });

  it('the spatial hash is (x·1 ⊕ y·2654435761 ⊕ z·805459861) mod 2³² mod T, in exact integers', () => {
    const state = { value: 3 };
    for (let k = 0; k < 200; k++) {
      const v = [0, 1, 2].map(() => Math.floor(rngNextFloat(state) * 5000)) as [
        number,
        number,
        number,
      ];
      const T = 2 ** (8 + (k % 9));
      const wrap = 2n ** 32n;
      const exact =
        (BigInt(v[0]) ^
          ((BigInt(v[1]) * 2654435761n) % wrap) ^
          ((BigInt(v[2]) * 805459861n) % wrap)) %
        BigInt(T);
      expect(spatialHash(v, T)).toBe(Number(exact));
    }
  });

  it('a dense level gives every vertex its own entry; a hashed one stays inside the table', () => {
    const T = 2 ** 12;
    for (const n of [4, 5, 8, 11]) {
      const seen = new Set<number>();
      for (let z = 0; z <= n; z++)
        for (let y = 0; y <= n; y++)
          for (let x = 0; x <= n; x++) seen.add(hashGridIndex([x, y, z], n, T));
      expect(seen.size).toBe((n + 1) ** 3);
      expect(Math.max(...seen)).toBeLessThan(T);
    }
    // 17³ = 4913 vertices > 2¹²: hashed; entries cover most of the table.
    const hashed = new Set<number>();
    for (let z = 0; z <= 16; z++)
      for (let y = 0; y <= 16; y++)
        for (let x = 0; x <= 16; x++) hashed.add(hashGridIndex([x, y, z], 16, T));
    expect(Math.max(...hashed)).toBeLessThan(T);
    expect(hashed.size).toBeGreaterThan(0.6 * T);
  });

  it('hashCellLocate: vertices at the cell corners, the far face in the last cell with fraction 1', () => {
    const inside = hashCellLocate([0.1, -0.35, 0.9], BOX_MIN, BOX_MAX, 8);
    expect(inside.base).toEqual([4, 2, 7]);
    expect(inside.fraction[0]).toBeCloseTo(0.4, 12);
    expect(inside.fraction[1]).toBeCloseTo(0.6, 12);
    expect(inside.fraction[2]).toBeCloseTo(0.6, 12);
    const corner = hashCellLocate([1, 1, 5], BOX_MIN, BOX_MAX, 8);
    expect(corner.base).toEqual([7, 7, 7]);
    expect(corner.fraction).toEqual([1, 1, 1]);
  });
});

describe('the MLP: backward against central differences of forward (float64)', () => {
  it('∂(c·out)/∂W and ∂(c·out)/∂y for random weights, features and output weights c', () => {
    const state = { value: 99 };
    const draw = (): number => 2 * rngNextFloat(state) - 1;
    const mlp = Float64Array.from({ length: NEURAL_MLP_SIZE }, draw);
    const y = Float64Array.from({ length: NEURAL_INPUTS }, draw);
    const c = [draw(), draw(), draw(), draw()] as const;
    const hidden = new Float64Array(NEURAL_HIDDEN);
    const objective = (): number => {
      const out = neuralForward(mlp, y, hidden);
      return c[0] * out[0] + c[1] * out[1] + c[2] * out[2] + c[3] * out[3];
    };
    objective();
    const gradient = new Float64Array(NEURAL_MLP_SIZE);
    const dy = new Float64Array(NEURAL_INPUTS);
    neuralBackward(mlp, y, hidden, c, gradient, dy);
    const h = 1e-6;
    const difference = (values: Float64Array, i: number): number => {
      const saved = values[i]!;
      values[i] = saved + h;
      const up = objective();
      values[i] = saved - h;
      const down = objective();
      values[i] = saved;
      return (up - down) / (2 * h);
    };
    // The objective is piecewise linear in each weight: central differences are exact
    // up to rounding (≈ 1e-16/1e-6) unless a pre-activation lies within 1e-6 of 0.
    for (let i = 0; i < NEURAL_MLP_SIZE; i++)
      expect(Math.abs(gradient[i]! - difference(mlp, i))).toBeLessThan(1e-8);
    for (let i = 0; i < NEURAL_INPUTS; i++)
      expect(Math.abs(dy[i]! - difference(y, i))).toBeLessThan(1e-8);
  });
});

describe('the analytic gradient equals central finite differences of the loss (float64)', () => {
  // Central differences with ε = 1e-5 err by ε²/6·|L'''| (≈ 1e-11·|L'''|) plus the
  // loss's rounding (≈ 1e-16·L/ε ≈ 3e-12 absolute); ReLU kinks could only matter within
  // 1e-5 of a zero pre-activation (none with these seeds: the test would show it).
  // Relative error is |analytic − numeric| / |numeric| for parameters with
  // |∂L/∂θ| > 1e-2 of the largest (≥ 1e-5 here, so the difference's own error stays below
  // 1e-6 of it), absolute against the largest for the rest.
  const EPSILON = 1e-5;
  for (const [label, seed, views, tableScale] of [
    ['features ±0.5, 2 views', 1, 2, 0.5],
    ['features ±2, 1 view', 2, 1, 2],
    ['features ±0.1, 3 views', 3, 3, 0.1],
  ] as const) {
    it(`${label}: MLP weights (all for the first) and 150 table entries, relative error < 1e-6`, () => {
      const problem = smallProblem(views);
      const field = randomField(problem, seed, tableScale);
      const targets = randomTargets(problem, seed);
      const { gradient } = lossAndGradientNeuralCpu(field, problem, targets);
      const offset = neuralMlpOffset(problem.tableSize);
      const lossAt = (): number => lossNeuralCpu(field, problem, targets);
      // The MLP, then every 13th table entry across all levels (every level's entries are hit).
      const stride = seed === 1 ? 1 : 3;
      const checked = [
        ...Array.from(
          { length: Math.ceil(NEURAL_MLP_SIZE / stride) },
          (_, i) => offset + stride * i,
        ),
        ...Array.from({ length: 150 }, (_, k) => Math.floor((k * offset) / 150)),
      ];
      const largest = Math.max(...checked.map((i) => Math.abs(gradient[i]!)));
      expect(largest).toBeGreaterThan(1e-4);
      let worstRelative = 0;
      let worstAbsolute = 0;
      let nonzeroTable = 0;
      for (const i of checked) {
        const saved = field.values[i]!;
        field.values[i] = saved + EPSILON;
        const up = lossAt();
        field.values[i] = saved - EPSILON;
        const down = lossAt();
        field.values[i] = saved;
        const numeric = (up - down) / (2 * EPSILON);
        const analytic = gradient[i]!;
        if (i < offset && analytic !== 0) nonzeroTable += 1;
        if (Math.abs(numeric) > 1e-2 * largest)
          worstRelative = Math.max(worstRelative, Math.abs(analytic - numeric) / Math.abs(numeric));
        else worstAbsolute = Math.max(worstAbsolute, Math.abs(analytic - numeric) / largest);
      }
      expect(lossAt()).toBeCloseTo(lossAndGradientNeuralCpu(field, problem, targets).loss, 14);
      expect(nonzeroTable).toBeGreaterThan(10);
      expect(worstRelative).toBeLessThan(1e-6);
      expect(worstAbsolute).toBeLessThan(1e-7);
    });
  }

  it('the magnitudes bound the gradient: |∂L/∂θ| ≤ Σ|contributions| for every parameter', () => {
    const problem = smallProblem(2);
    const field = randomField(problem, 4, 0.5);
    const targets = randomTargets(problem, 4);
    const plain = lossAndGradientNeuralCpu(field, problem, targets);
    const { gradient, magnitude } = lossAndGradientNeuralCpu(field, problem, targets, {
      withMagnitude: true,
    });
    for (let i = 0; i < gradient.length; i++) {
      expect(gradient[i]).toBeCloseTo(plain.gradient[i]!, 15);
      expect(Math.abs(gradient[i]!)).toBeLessThanOrEqual(magnitude![i]! * (1 + 1e-12));
    }
  });
});

describe('the optimization', () => {
  it(`Adam lowers the training loss at least fivefold within 150 iterations (${NEURAL_LEVELS} levels, 2¹⁰ entries)`, () => {
    const problem: Problem = {
      ...problemFrom(
        { model: 'neural', table: 10, views: 4, steps: 16, seed: 2, novel: 60 },
        'cpu',
      ),
      size: 8,
    };
    const targets = renderTargetsCpu(problem);
    const optimizer = new NeuralOptimizerCpu(problem, targets);
    const hyper: Hyper = { learningRate: 0.02, regularizer: 0, regularizerWeight: 0, batch: 1e9 };
    const first = optimizer.step(hyper);
    let last = first;
    for (let k = 1; k < 150 && last > first / 5; k++) last = optimizer.step(hyper);
    expect(last).toBeLessThan(first / 5);
  });
});
