// WGSL volume module (chapter 7) vs its float64 twin: transfer-function lookup,
// opacity correction, compositing and step counts through the table harness;
// volumeRaymarch through its own kernel (tests/support/volumeGpu.ts, the grid is
// a 3D texture), on the hard cases the doc comments name and on a heterogeneous
// grid.
//
// Tolerances. transferLookup is one division and a mix: a few ULP of the largest
// |q|. opacityToOpticalDepth uses WGSL log (absolute error 2⁻²¹ on [0.5, 2], so
// relative ≤ 2⁻²¹/τ₀ ≤ 7.4e-6 for α ≥ 1/16, where τ₀ ≥ 0.0645) or an 8-term Horner
// series (≈ 8 ULP): 1e-5 relative. opacityCorrected adds oneMinusExpOverX (2 ULP)
// and the product r·τ₀; since ∂α'/∂x·x = x e^{−x} ≤ 1 − e^{−x}, a relative error in
// x moves α' by at most the same relative amount: 2e-5.
import { afterAll, describe, expect, it } from 'vitest';
import { makeDensityGrid, type DensityGridData, type Vec3 } from '../../src/reference/medium.ts';
import {
  compositeFrontToBack,
  makeTransferFunction,
  opacityCorrected,
  opacityToOpticalDepth,
  transferLookup,
  TRANSFER_MAX_POINTS,
  volumeRaymarch,
  volumeStepCount,
  VOLUME_MAX_STEPS,
  type TransferFunction,
} from '../../src/reference/volume.ts';
import { FINITE_LIMIT } from '../../src/reference/transmittance.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { describeShaderFunction, type ShaderCase } from '../support/shaderHarness.ts';
import { releaseNodeDevice } from '../support/nodeGpu.ts';
import {
  f32MarchRay,
  f32TransferFunction,
  gpuVolumeRaymarch,
  type MarchRay,
} from '../support/volumeGpu.ts';

afterAll(releaseNodeDevice);

const F32_EPSILON = 2 ** -24;

/** Flat arguments of the lookup wrapper: count, 16 values, 16 × rgba. */
function tfArgs(
  points: readonly [number, number, number, number, number][],
  count = points.length,
): [number, number[], number[]] {
  const values = new Array<number>(TRANSFER_MAX_POINTS).fill(0);
  const rgba = new Array<number>(4 * TRANSFER_MAX_POINTS).fill(0);
  points.slice(0, TRANSFER_MAX_POINTS).forEach(([v, r, g, b, a], k) => {
    values[k] = v;
    rgba.splice(4 * k, 4, r, g, b, a);
  });
  return [count, values, rgba];
}

function tfFromArgs(count: number, values: readonly number[], rgba: readonly number[]) {
  const n = Math.min(count, TRANSFER_MAX_POINTS);
  return {
    count,
    values: values.slice(0, n),
    rgba: Array.from(
      { length: n },
      (_, k) => [rgba[4 * k]!, rgba[4 * k + 1]!, rgba[4 * k + 2]!, rgba[4 * k + 3]!] as const,
    ),
  };
}

const RAMP: [number, number, number, number, number][] = [
  [-1000, 0, 0, 0, 0],
  [200, 0.8, 0.3, 0.2, 0],
  [700, 1, 0.9, 0.8, 0.6],
  [1500, 1, 1, 1, 0.9],
];
const SIXTEEN = Array.from(
  { length: 16 },
  (_, k) =>
    [-1024 + 256 * k, k / 15, 1 - k / 15, 0.5, (k % 5) / 4] as [
      number,
      number,
      number,
      number,
      number,
    ],
);

const lookupCases: ShaderCase[] = [
  {
    name: 'count 0: nothing emits or absorbs',
    args: [...tfArgs([], 0), 17],
    expected: [0, 0, 0, 0],
  },
  {
    name: 'one point: its colour and opacity everywhere (below)',
    args: [...tfArgs([[40, 0.2, 0.4, 0.6, 0.3]]), -900],
    expected: [0.2, 0.4, 0.6, 0.3],
  },
  { name: 'one point: above', args: [...tfArgs([[40, 0.2, 0.4, 0.6, 0.3]]), 3000] },
  { name: 'below the first point: clamped to q₀', args: [...tfArgs(RAMP), -1024] },
  { name: 'exactly at the first point', args: [...tfArgs(RAMP), -1000] },
  { name: 'inside the first segment', args: [...tfArgs(RAMP), 0] },
  { name: 'exactly at an inner point', args: [...tfArgs(RAMP), 700], expected: [1, 0.9, 0.8, 0.6] },
  { name: 'inside the opacity ramp (450 HU)', args: [...tfArgs(RAMP), 450] },
  { name: 'exactly at the last point', args: [...tfArgs(RAMP), 1500], expected: [1, 1, 1, 0.9] },
  { name: 'above the last point: clamped to q_{n−1}', args: [...tfArgs(RAMP), 3071] },
  {
    name: 'a jump (two equal values): v at the jump takes the right-hand value',
    args: [
      ...tfArgs([
        [0, 0, 0, 0, 0],
        [300, 0.1, 0.1, 0.1, 0.1],
        [300, 1, 1, 1, 0.8],
        [900, 1, 1, 1, 0.8],
      ]),
      300,
    ],
    expected: [1, 1, 1, 0.8],
  },
  {
    name: 'a jump: just below it, the left segment',
    args: [
      ...tfArgs([
        [0, 0, 0, 0, 0],
        [300, 0.1, 0.1, 0.1, 0.1],
        [300, 1, 1, 1, 0.8],
        [900, 1, 1, 1, 0.8],
      ]),
      299.5,
    ],
  },
  { name: 'sixteen points (the maximum), last segment', args: [...tfArgs(SIXTEEN), 2800] },
  { name: 'sixteen points, a middle segment', args: [...tfArgs(SIXTEEN), 100.25] },
  { name: 'count 20 is clamped to the 16 points held', args: [...tfArgs(SIXTEEN, 20), 3070] },
];

describeShaderFunction({
  module: 'volume',
  fn: 'transferLookup',
  args: ['u32', 'f32[16]', 'f32[64]', 'f32'],
  result: 'vec4f',
  twin: ((count: number, values: number[], rgba: number[], v: number) =>
    transferLookup(tfFromArgs(count, values, rgba), v)) as (...args: never[]) => readonly number[],
  tolerance: {
    absolute: 8 * F32_EPSILON,
    reason: 'one division and a mix of values ≤ 1: a few ULP of 1',
  },
  wrapper: {
    imports: ['TransferFunction', 'transferLookup'],
    wgsl: `fn caseUnderTest(count: u32, values: array<f32, 16>, rgba: array<f32, 64>, v: f32) -> vec4f {
  var tf: TransferFunction;
  var vs = values;
  var qs = rgba;
  tf.count = count;
  for (var k = 0u; k < 16u; k++) {
    tf.values[k / 4u][k % 4u] = vs[k];
    tf.rgba[k] = vec4f(qs[4u * k], qs[4u * k + 1u], qs[4u * k + 2u], qs[4u * k + 3u]);
  }
  return transferLookup(&tf, v);
}`,
  },
  cases: lookupCases,
});

describeShaderFunction({
  module: 'volume',
  fn: 'opacityToOpticalDepth',
  args: ['f32'],
  result: 'f32',
  twin: opacityToOpticalDepth,
  tolerance: {
    relative: 1e-5,
    reason: 'WGSL log: 2⁻²¹ absolute on [0.5, 2] (≤ 7.4e-6 relative for α ≥ 1/16); series ≈ 8 ULP',
  },
  cases: [
    { name: 'α = 0 gives 0', args: [0], expected: 0 },
    { name: 'negative α is clamped to 0', args: [-0.3], expected: 0 },
    {
      name: 'α = 1e-8: the series keeps full precision (naive f32 log(1 − α) gives 0)',
      args: [1e-8],
    },
    { name: 'α = 1e-6 (naive f32: 3% off)', args: [1e-6] },
    { name: 'α = 0.01', args: [0.01] },
    { name: 'α just below the series limit 1/16', args: [0.0624999] },
    { name: 'α = 1/16: the log branch', args: [0.0625] },
    { name: 'α = 1 − e^{−1} gives 1', args: [1 - Math.exp(-1)], expected: 1 },
    { name: 'α = 0.5 gives ln 2', args: [0.5], expected: Math.LN2 },
    { name: 'α = 0.999999', args: [0.999999] },
    { name: 'α = 1: an opaque step, τ₀ = 1e18 (FINITE_LIMIT)', args: [1], expected: FINITE_LIMIT },
    { name: 'α > 1 is clamped to 1', args: [7], expected: FINITE_LIMIT },
  ],
});

describeShaderFunction({
  module: 'volume',
  fn: 'opacityCorrected',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: opacityCorrected,
  tolerance: {
    relative: 2e-5,
    absolute: 1e-12,
    reason: 'τ₀ within 1e-5 (log) and oneMinusExpOverX 2 ULP; α′ inherits x’s relative error',
  },
  cases: [
    {
      name: 'stepRatio = 1 returns α exactly',
      args: [0.37, 1],
      expected: 0.37,
      tolerance: { ulps: 0, reason: 'exact' },
    },
    { name: 'half a reference step: 1 − √(1 − α)', args: [0.75, 0.5], expected: 0.5 },
    { name: 'two reference steps: 1 − (1 − α)²', args: [0.5, 2], expected: 0.75 },
    { name: 'an eighth of a step of a faint voxel (α = 1e-6)', args: [1e-6, 0.125] },
    { name: 'α = 0 gives 0', args: [0, 3], expected: 0 },
    { name: 'α = 1 gives 1 for any step > 0', args: [1, 0.25], expected: 1 },
    { name: 'α = 1 and a zero step gives 0 (0⁰ = 1)', args: [1, 0], expected: 0 },
    { name: 'a zero step gives 0', args: [0.5, 0], expected: 0 },
    { name: 'α = 0.999 over 8 steps is ≈ 1', args: [0.999, 8] },
    { name: 'a huge ratio (1e20, clamped to 1e18) gives 1', args: [0.2, 1e20], expected: 1 },
    { name: 'negative α is clamped to 0', args: [-1, 2], expected: 0 },
    { name: 'α at the series limit 1/16, a quarter step', args: [0.0625, 0.25] },
  ],
});

describeShaderFunction({
  module: 'volume',
  fn: 'compositeFrontToBack',
  args: ['f32[4]', 'f32[3]', 'f32'],
  result: 'vec4f',
  twin: ((accumulated: number[], color: number[], alpha: number) =>
    compositeFrontToBack(
      accumulated as unknown as [number, number, number, number],
      color as unknown as [number, number, number],
      alpha,
    )) as (...args: never[]) => readonly number[],
  tolerance: { ulps: 4, absolute: 1e-30, reason: 'two products and a sum per channel' },
  wrapper: {
    imports: ['compositeFrontToBack'],
    wgsl: `fn caseUnderTest(a: array<f32, 4>, c: array<f32, 3>, alpha: f32) -> vec4f {
  return compositeFrontToBack(vec4f(a[0], a[1], a[2], a[3]), vec3f(c[0], c[1], c[2]), alpha);
}`,
  },
  cases: [
    {
      name: 'α = 0 changes nothing',
      args: [[0.1, 0.2, 0.3, 0.6], [1, 1, 1], 0],
      expected: [0.1, 0.2, 0.3, 0.6],
    },
    {
      name: 'α = 1 makes T exactly 0',
      args: [[0.1, 0.2, 0.3, 0.5], [1, 0.5, 0.25], 1],
      expected: [0.6, 0.45, 0.425, 0],
    },
    { name: 'a typical step', args: [[0.05, 0.02, 0.01, 0.8], [0.9, 0.6, 0.4], 0.3] },
    {
      name: 'T = 0 (terminated): nothing more is added',
      args: [[0.7, 0.6, 0.5, 0], [1, 1, 1], 0.9],
      expected: [0.7, 0.6, 0.5, 0],
    },
    {
      name: 'α > 1 is clamped to 1',
      args: [[0, 0, 0, 1], [0.2, 0.4, 0.8], 3],
      expected: [0.2, 0.4, 0.8, 0],
    },
    {
      name: 'α < 0 is clamped to 0',
      args: [[0, 0, 0, 1], [0.2, 0.4, 0.8], -2],
      expected: [0, 0, 0, 1],
    },
  ],
});

describeShaderFunction({
  module: 'volume',
  fn: 'volumeStepCount',
  args: ['f32', 'f32'],
  result: 'u32',
  twin: volumeStepCount,
  tolerance: { reason: 'exact counts' },
  cases: [
    { name: 'ceil(1/0.3) = 4 steps of 0.25', args: [1, 0.3], expected: 4 },
    { name: 'an exact multiple: 0.5/0.125 = 4', args: [0.5, 0.125], expected: 4 },
    {
      name: 'ℓ = 1 with f32(0.01) = 0.0099999998: 100 steps, not a 101st sliver (the 1 ppm slack)',
      args: [1, 0.01],
      expected: 100,
    },
    { name: 'a step larger than the segment gives 1', args: [0.1, 1], expected: 1 },
    { name: 'stepSize 0 gives the cap', args: [1, 0], expected: VOLUME_MAX_STEPS },
    { name: 'a negative stepSize gives the cap', args: [1, -1], expected: VOLUME_MAX_STEPS },
    { name: 'an empty segment gives 1', args: [0, 0.1], expected: 1 },
    { name: 'a negative length gives 1', args: [-1, 0.1], expected: 1 },
    { name: '1e5 steps are capped at 8192', args: [100, 0.001], expected: VOLUME_MAX_STEPS },
    {
      name: 'stepSize 1e-30: no overflow of ℓ/Δs, the cap',
      args: [1, 1e-30],
      expected: VOLUME_MAX_STEPS,
    },
    { name: 'length 1e30: the cap', args: [1e30, 1], expected: VOLUME_MAX_STEPS },
  ],
});

// ---- volumeRaymarch: its own kernel (the grid is a texture) ---------------------

const BOX_MIN: Vec3 = [-0.5, -0.5, -0.5];
const BOX_MAX: Vec3 = [0.5, 0.5, 0.5];
/** A constant 4³ grid of stored value 1100 (100 HU with the CT intercept −1000 below). */
const CONSTANT = makeDensityGrid(new Array(64).fill(1100), [4, 4, 4], BOX_MIN, BOX_MAX, 1);
const OFFSET = -1000;
/** Heterogeneous 8³ grid, deterministic (PCG), values 0 … 2000 (−1000 … +1000 after the offset). */
function heterogeneousGrid(): DensityGridData {
  const state = { value: rngSeed(7, 3) };
  const values = Array.from({ length: 512 }, () => 2000 * rngNextFloat(state));
  return makeDensityGrid(values, [8, 8, 8], BOX_MIN, BOX_MAX, 1);
}
const HETEROGENEOUS = heterogeneousGrid();

const flat = (opacity: number, color: [number, number, number] = [0.8, 0.6, 0.4]) =>
  makeTransferFunction([{ value: 0, color, opacity }]);
const ramp = makeTransferFunction([
  { value: -400, color: [0.6, 0.1, 0.05], opacity: 0 },
  { value: 0, color: [0.9, 0.5, 0.35], opacity: 0.05 },
  { value: 300, color: [0.95, 0.85, 0.7], opacity: 0.02 },
  { value: 700, color: [1, 1, 1], opacity: 0.5 },
]);
/** One voxel of the 4³ grid is 0.25 m; of the 8³ grid 0.125 m. */
const along = (x: number, stepSize: number, threshold = 0): MarchRay => ({
  origin: [-2, x, 0.1],
  direction: [1, 0, 0],
  stepSize,
  threshold,
});

async function both(
  data: DensityGridData,
  tf: TransferFunction,
  referenceStep: number,
  rays: MarchRay[],
) {
  const gpuRays = rays.map(f32MarchRay);
  const gpuTf = f32TransferFunction(tf);
  const gpu = await gpuVolumeRaymarch(data, OFFSET, gpuTf, referenceStep, gpuRays);
  const twin = gpuRays.map((r) =>
    volumeRaymarch(
      data.grid,
      data.volume,
      OFFSET,
      gpuTf,
      Math.fround(referenceStep),
      r.origin,
      r.direction,
      r.stepSize,
      r.threshold,
    ),
  );
  return { gpu, twin };
}

describe('volumeRaymarch: WGSL vs float64 twin on the hard cases', () => {
  it('a homogeneous volume matches the closed form c·(1 − (1 − α)^{ℓ/Δs₀}) for any step', async () => {
    const alpha = 0.2;
    const tf = flat(alpha);
    const steps = [0.01, 0.1, 0.3, 1, 5];
    const { gpu, twin } = await both(
      CONSTANT,
      tf,
      0.25,
      steps.map((s) => along(0, s)),
    );
    steps.forEach((_, i) => {
      // ℓ = 1 m through the box; the reference step Δs₀ = 0.25 m.
      const expected = 1 - (1 - alpha) ** (1 / 0.25);
      for (const c of [0, 1, 2] as const) {
        const colour = [0.8, 0.6, 0.4][c]!;
        expect(Math.abs(twin[i]!.color[c] - colour * expected)).toBeLessThan(1e-6);
        expect(Math.abs(gpu[i]!.color[c] - colour * expected)).toBeLessThan(2e-5);
      }
      expect(gpu[i]!.transmittance).toBeCloseTo(0.8 ** 4, 4);
      expect(gpu[i]!.steps).toBe(twin[i]!.steps);
    });
  });

  it('zero opacity everywhere leaves T = 1 exactly, and T = ε = 1 does not stop the march', async () => {
    const { gpu, twin } = await both(CONSTANT, flat(0), 0.25, [along(0, 0.1, 1)]);
    for (const r of [gpu[0]!, twin[0]!]) {
      expect(r.transmittance).toBe(1);
      expect(r.color).toEqual([0, 0, 0]);
      expect(r.steps).toBe(10);
      expect(r.plannedSteps).toBe(10);
      expect(r.terminated).toBe(0);
    }
  });

  it('opacity 1: T = 0 after the first step; threshold 0 keeps marching (T < 0 is false), ε = 0.01 stops', async () => {
    const { gpu, twin } = await both(CONSTANT, flat(1, [0.3, 0.6, 0.9]), 0.25, [
      along(0, 0.1, 0),
      along(0, 0.1, 0.01),
    ]);
    for (const results of [gpu, twin]) {
      const [off, on] = results as [(typeof results)[number], (typeof results)[number]];
      expect(off.transmittance).toBe(0);
      expect(off.steps).toBe(10);
      expect(off.terminated).toBe(0);
      expect(on.steps).toBe(1);
      expect(on.terminated).toBe(1);
      for (const r of [off, on]) {
        expect(r.color[0]).toBeCloseTo(0.3, 6);
        expect(r.color[2]).toBeCloseTo(0.9, 6);
      }
    }
  });

  it('a step larger than the volume takes one step (h = ℓ, midpoint sample)', async () => {
    const { gpu, twin } = await both(CONSTANT, flat(0.2), 0.25, [along(0, 3)]);
    for (const r of [gpu[0]!, twin[0]!]) {
      expect(r.steps).toBe(1);
      expect(r.plannedSteps).toBe(1);
    }
    // One step of 1 m is still exact for a constant medium: 1 − 0.8⁴.
    expect(gpu[0]!.color[0]).toBeCloseTo(0.8 * (1 - 0.8 ** 4), 4);
  });

  it('a ray that misses the box (or points away from it) returns L = 0, T = 1 and no steps', async () => {
    const rays: MarchRay[] = [
      { origin: [-2, 0.9, 0], direction: [1, 0, 0], stepSize: 0.1, threshold: 0 },
      { origin: [-2, 0, 0], direction: [-1, 0, 0], stepSize: 0.1, threshold: 0 },
      { origin: [-2, 0, 0], direction: [0, 0, 1], stepSize: 0.1, threshold: 0 },
    ];
    const { gpu, twin } = await both(CONSTANT, flat(0.5), 0.25, rays);
    for (const r of [...gpu, ...twin]) {
      expect(r.steps).toBe(0);
      expect(r.plannedSteps).toBe(0);
      expect(r.transmittance).toBe(1);
      expect(r.color).toEqual([0, 0, 0]);
    }
  });

  it('an origin inside the box marches from t = 0', async () => {
    const { gpu, twin } = await both(CONSTANT, flat(0.2), 0.25, [
      { origin: [0, 0, 0], direction: [1, 0, 0], stepSize: 0.1, threshold: 0 },
    ]);
    expect(twin[0]!.plannedSteps).toBe(5);
    expect(gpu[0]!.plannedSteps).toBe(5);
    expect(gpu[0]!.transmittance).toBeCloseTo(0.8 ** 2, 5);
  });

  it('a segment needing more than 8192 steps is marched with longer steps and flagged capped', async () => {
    const { gpu, twin } = await both(CONSTANT, flat(0.2), 0.25, [along(0, 1e-5)]);
    for (const r of [gpu[0]!, twin[0]!]) {
      expect(r.steps).toBe(VOLUME_MAX_STEPS);
      expect(r.capped).toBe(1);
    }
    // Longer steps are still exact for the constant medium.
    expect(gpu[0]!.transmittance).toBeCloseTo(0.8 ** 4, 3);
  });

  it('an empty grid (flat box) composites nothing', async () => {
    const flatBox = makeDensityGrid([1100], [1, 1, 1], [0, -0.5, -0.5], [0, 0.5, 0.5], 1);
    const { gpu, twin } = await both(flatBox, flat(0.5), 0.25, [along(0, 0.1)]);
    for (const r of [gpu[0]!, twin[0]!]) {
      expect(r.steps).toBe(0);
      expect(r.transmittance).toBe(1);
    }
  });
});

describe('volumeRaymarch: WGSL vs twin on a heterogeneous grid', () => {
  // 48 rays at odd angles through a random 8³ grid with a ramp transfer function.
  const rays: MarchRay[] = Array.from({ length: 48 }, (_, i) => {
    const a = 0.37 * i;
    const direction: Vec3 = [Math.cos(a) * 0.9, 0.3 * Math.sin(1.7 * a), Math.sin(a) * 0.9];
    const norm = Math.hypot(...direction);
    return {
      origin: [
        (-1.3 * direction[0]) / norm,
        (-1.3 * direction[1]) / norm + 0.05,
        (-1.3 * direction[2]) / norm,
      ],
      direction: [direction[0] / norm, direction[1] / norm, direction[2] / norm],
      stepSize: [0.02, 0.0625, 0.3][i % 3]!,
      threshold: i % 2 === 0 ? 0 : 0.05,
    };
  });

  it('colour, transmittance and step counts agree within the f32 budget', async () => {
    const { gpu, twin } = await both(HETEROGENEOUS, ramp, 0.125, rays);
    let sameSteps = 0;
    gpu.forEach((g, i) => {
      const t = twin[i]!;
      // Sample positions t_i carry ≈ 2.4e-7 m of f32 error (t ≤ 2.6 m); the grid's slope
      // is up to 2000 per 0.125 m (1.6e4 per m) and the ramp's opacity slope ≤ 1.2e-3 per
      // unit, so each α moves by ≲ 5e-6, partly cancelling over ≤ 70 steps; measured
      // ≤ 1.6e-6. 2e-5 leaves room without hiding a wrong sample position (≈ 1e-2).
      expect(Math.abs(g.transmittance - t.transmittance)).toBeLessThan(2e-5);
      for (const c of [0, 1, 2] as const)
        expect(Math.abs(g.color[c] - t.color[c])).toBeLessThan(2e-5);
      expect(g.plannedSteps).toBe(t.plannedSteps);
      if (g.steps === t.steps) sameSteps += 1;
      expect(g.capped).toBe(0);
    });
    // Termination can flip only where T passes ε within rounding; none of these rays does.
    expect(sameSteps).toBe(rays.length);
  });

  it('early termination drops at most ε·L_max of radiance (on both implementations)', async () => {
    const epsilon = 0.05;
    const withoutEt = rays.map((r) => ({ ...r, threshold: 0 }));
    const withEt = rays.map((r) => ({ ...r, threshold: epsilon }));
    const off = await both(HETEROGENEOUS, ramp, 0.125, withoutEt);
    const on = await both(HETEROGENEOUS, ramp, 0.125, withEt);
    const lMax = 1; // the brightest emission channel of the ramp
    for (const [a, b] of [
      [off.gpu, on.gpu],
      [off.twin, on.twin],
    ] as const) {
      a.forEach((r, i) => {
        for (const c of [0, 1, 2] as const) {
          const dropped = r.color[c] - b[i]!.color[c];
          expect(dropped).toBeGreaterThanOrEqual(-1e-6);
          expect(dropped).toBeLessThanOrEqual(epsilon * lMax + 1e-6);
        }
        expect(b[i]!.steps).toBeLessThanOrEqual(r.steps);
      });
    }
  });
});
