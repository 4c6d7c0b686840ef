// WGSL inverse module (chapter 8) vs its float64 twin, function by function through
// the table-driven harness: activations and their chain rule, trilinear lookups,
// the march segment, one compositing step and its derivative, the loss, Adam, the
// regularizers and the stratified batches. The whole-ray gradient kernel is held
// against the twin in tests/shaders/inverse-render-kernel.test.ts.
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  adamStep,
  compositeStep,
  compositeStepBackward,
  fieldActivate,
  fieldActivateBackward,
  gridCornerIndex,
  gridPointLocate,
  marchSegment,
  pixelLossGradient,
  pixelSquaredError,
  sigmoid,
  softplus,
  sparsityGradient,
  stratifiedSubsetIndex,
  totalVariationGradient,
  trilinearWeight,
  type Vec4,
} from '../../src/reference/inverse.ts';
import type { Vec3 } from '../../src/reference/phase.ts';

const v3 = (a: readonly number[]): Vec3 => [a[0] ?? NaN, a[1] ?? NaN, a[2] ?? NaN];
const v4 = (a: readonly number[]): Vec4 => [a[0] ?? NaN, a[1] ?? NaN, a[2] ?? NaN, a[3] ?? NaN];
const W3 = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;
const W4 = (name: string): string => `vec4f(${name}[0], ${name}[1], ${name}[2], ${name}[3])`;

// exp is allowed 3 + 2|x| ULP and log 2⁻²¹ absolute near 1 (physics.md §10); softplus
// and sigmoid add a division and a few roundings.
const ACTIVATION: Tolerance = {
  relative: 4e-6,
  absolute: 1e-6,
  reason: 'exp (3 + 2|x| ULP, |x| ≤ 30 here), log (2⁻²¹ absolute near 1) and one division',
};

describeShaderFunction({
  module: 'inverse',
  fn: 'softplus',
  args: ['f32'],
  result: 'f32',
  twin: softplus,
  tolerance: ACTIVATION,
  cases: [
    { name: 'x = 0: ln 2', args: [0], expected: Math.LN2 },
    { name: 'x = 1', args: [1] },
    { name: 'x = −3', args: [-3] },
    { name: 'x = 8: ≈ x', args: [8] },
    {
      name: 'x = −30: 9.36e-14, not 0 (Goldberg log1p)',
      args: [-30],
      tolerance: {
        relative: 1e-5,
        reason: 'exp(−30) to 63 ULP; the corrected log1p is exact there',
      },
    },
    { name: 'x = 100: no overflow', args: [100], expected: 100 },
    { name: 'x = −100: 0 or subnormal, never NaN', args: [-100] },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'sigmoid',
  args: ['f32'],
  result: 'f32',
  twin: sigmoid,
  tolerance: ACTIVATION,
  cases: [
    { name: 'x = 0: ½', args: [0], expected: 0.5 },
    { name: 'x = 2.5', args: [2.5] },
    { name: 'x = −2.5', args: [-2.5] },
    { name: 'x = 100: 1', args: [100], expected: 1 },
    { name: 'x = −100: 0 (e⁻¹⁰⁰ may flush), never NaN', args: [-100] },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'fieldActivate',
  args: ['f32[4]'],
  result: 'vec4f',
  wrapper: {
    imports: ['fieldActivate'],
    wgsl: `fn caseUnderTest(raw: array<f32, 4>) -> vec4f { return fieldActivate(${W4('raw')}); }`,
  },
  twin: (raw: number[]) => [...fieldActivate(v4(raw))],
  tolerance: { ...ACTIVATION, absolute: 1e-5, reason: `${ACTIVATION.reason}; σt = 10·softplus` },
  cases: [
    { name: 'the initial state ρ = −5, e = 0', args: [[-5, 0, 0, 0]] },
    { name: 'dense and saturated', args: [[3, 9, -9, 0.3]] },
    { name: 'extremes stay finite', args: [[-60, 60, -60, 0]] },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'fieldActivateBackward',
  args: ['f32[4]', 'f32[4]'],
  result: 'vec4f',
  wrapper: {
    imports: ['fieldActivateBackward'],
    wgsl: `fn caseUnderTest(raw: array<f32, 4>, g: array<f32, 4>) -> vec4f { return fieldActivateBackward(${W4('raw')}, ${W4('g')}); }`,
  },
  twin: (raw: number[], g: number[]) => [...fieldActivateBackward(v4(raw), v4(g))],
  tolerance: { relative: 1e-5, absolute: 1e-12, reason: 'two sigmoids and a product per channel' },
  cases: [
    {
      name: 'moderate values',
      args: [
        [-1.3, 0.4, -2.2, 5],
        [0.3, -0.5, 0.8, 0.1],
      ],
    },
    {
      name: 'saturated colour: c(1 − c) from sigmoid(e)·sigmoid(−e), not 0',
      args: [
        [-20, 17, -17, 0],
        [1, 1, 1, 1],
      ],
      tolerance: { relative: 4e-5, reason: 'exp(−17) to 37 ULP, then products' },
    },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'gridPointLocate',
  args: ['f32[3]', 'u32'],
  result: 'vec3f',
  wrapper: {
    imports: ['gridPointLocate'],
    // The continuous voxel coordinate base + fraction; the base alone is checked below.
    wgsl: `fn caseUnderTest(p: array<f32, 3>, n: u32) -> vec3f {
  let point = gridPointLocate(${W3('p')}, vec3f(-1.0), vec3f(1.0), n);
  return vec3f(point.base) + point.fraction;
}`,
  },
  twin: (p: number[], n: number) => {
    const point = gridPointLocate(v3(p), [-1, -1, -1], [1, 1, 1], n);
    return [0, 1, 2].map((a) => point.base[a]! + point.fraction[a]!);
  },
  tolerance: {
    absolute: 4e-6,
    reason: 'one division and a product of f32 coordinates (≤ 32 voxels)',
  },
  cases: [
    { name: 'voxel centre (2, 1, 3) of 4³', args: [[0.25, -0.25, 0.75], 4], expected: [2, 1, 3] },
    { name: 'box centre of 32³', args: [[0, 0, 0], 32], expected: [15.5, 15.5, 15.5] },
    { name: 'outside the box: clamped to the border', args: [[-5, 0.999, 7], 8] },
    { name: 'resolution 1 is read as 2', args: [[0.1, 0.2, 0.3], 1] },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'gridCornerIndex',
  args: ['f32[3]', 'u32', 'u32'],
  result: 'u32',
  wrapper: {
    imports: ['gridPointLocate', 'gridCornerIndex'],
    wgsl: `fn caseUnderTest(p: array<f32, 3>, corner: u32, n: u32) -> u32 {
  return gridCornerIndex(gridPointLocate(${W3('p')}, vec3f(-1.0), vec3f(1.0), n).base, corner, n);
}`,
  },
  twin: (p: number[], corner: number, n: number) =>
    gridCornerIndex(gridPointLocate(v3(p), [-1, -1, -1], [1, 1, 1], n).base, corner, n),
  tolerance: { reason: 'integer index: exact' },
  cases: [
    { name: 'corner 0 at the box centre of 16³', args: [[0.01, 0.01, 0.01], 0, 16] },
    { name: 'corner 7 at the box centre of 16³', args: [[0.01, 0.01, 0.01], 7, 16] },
    { name: 'corner 5 near the top face of 32³', args: [[-0.4, 0.99, 0.2], 5, 32] },
    { name: 'corner 7 at the far corner: the last voxel', args: [[1, 1, 1], 7, 8], expected: 511 },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'trilinearWeight',
  args: ['f32[3]', 'u32'],
  result: 'f32',
  wrapper: {
    imports: ['trilinearWeight'],
    wgsl: `fn caseUnderTest(f: array<f32, 3>, corner: u32) -> f32 { return trilinearWeight(${W3('f')}, corner); }`,
  },
  twin: (f: number[], corner: number) => trilinearWeight(v3(f), corner),
  tolerance: { relative: 3e-7, absolute: 1e-9, reason: 'two products and up to three 1 − f' },
  cases: [
    { name: 'corner 0 at the origin of the block: 1', args: [[0, 0, 0], 0], expected: 1 },
    { name: 'corner 7 at the origin: 0', args: [[0, 0, 0], 7], expected: 0 },
    { name: 'corner 5 at (0.3, 0.6, 0.9)', args: [[0.3, 0.6, 0.9], 5], expected: 0.3 * 0.4 * 0.9 },
    { name: 'corner 2 at the block centre: 1/8', args: [[0.5, 0.5, 0.5], 2], expected: 0.125 },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'marchSegment',
  args: ['f32[3]', 'f32[3]', 'u32'],
  result: 'vec3f',
  wrapper: {
    imports: ['marchSegment'],
    wgsl: `fn caseUnderTest(o: array<f32, 3>, d: array<f32, 3>, steps: u32) -> vec3f {
  let s = marchSegment(vec3f(-1.0), vec3f(1.0), ${W3('o')}, ${W3('d')}, steps);
  return vec3f(s.start, s.step, f32(s.count));
}`,
  },
  twin: (o: number[], d: number[], steps: number) => {
    const s = marchSegment([-1, -1, -1], [1, 1, 1], v3(o), v3(d), steps);
    return [s.start, s.step, s.count];
  },
  tolerance: {
    relative: 1e-6,
    absolute: 1e-6,
    reason: 'slab divisions (2.5 ULP) and one more division',
  },
  cases: [
    {
      name: 'straight through along −z: [2, 4], 8 steps',
      args: [[0, 0, 3], [0, 0, -1], 8],
      expected: [2, 0.25, 8],
    },
    { name: 'a miss: no samples', args: [[0, 3, 5], [0, 0.6, -0.8], 16], expected: [0, 0, 0] },
    { name: 'origin inside: starts at 0', args: [[0, 0, 0], [1, 0, 0], 4], expected: [0, 0.25, 4] },
    { name: '0 steps is read as 1', args: [[0, 0, 3], [0, 0, -1], 0], expected: [2, 2, 1] },
    {
      name: 'steps capped at 512',
      args: [[0, 0, 3], [0, 0, -1], 100000],
      expected: [2, 2 / 512, 512],
    },
  ],
});

// exp(−x) within 3 + 2x ULP and the series of oneMinusExpOverX (2 ULP); products and a sum.
const COMPOSITE: Tolerance = {
  relative: 2e-6,
  absolute: 2e-7,
  reason:
    'exp (3 + 2x ULP, x ≤ 4 here), oneMinusExpOverX (2 ULP), 3 products and a sum per channel',
};

describeShaderFunction({
  module: 'inverse',
  fn: 'compositeStep',
  args: ['f32[4]', 'f32[4]', 'f32'],
  result: 'vec4f',
  wrapper: {
    imports: ['compositeStep'],
    wgsl: `fn caseUnderTest(s: array<f32, 4>, x: array<f32, 4>, h: f32) -> vec4f { return compositeStep(${W4('s')}, ${W4('x')}, h); }`,
  },
  twin: (s: number[], x: number[], h: number) => [...compositeStep(v4(s), v4(x), h)],
  tolerance: COMPOSITE,
  cases: [
    { name: 'first step from the eye', args: [[0, 0, 0, 1], [2, 0.9, 0.5, 0.1], 0.1] },
    { name: 'a later, thick step', args: [[0.2, 0.3, 0.1, 0.4], [30, 0.2, 0.8, 0.6], 0.125] },
    {
      name: 'a very thin step: α = x(1 − x/2), not 0',
      args: [[0, 0, 0, 1], [1e-6, 1, 1, 1], 0.01],
      tolerance: { relative: 1e-6, absolute: 1e-14, reason: 'the series of oneMinusExpOverX' },
    },
    {
      name: 'σ = 0: nothing changes',
      args: [[0.1, 0.2, 0.3, 0.5], [0, 1, 1, 1], 0.1],
      expected: [0.1, 0.2, 0.3, 0.5],
    },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'compositeStepBackward',
  args: ['f32[3]', 'f32[4]', 'f32[4]', 'f32', 'f32[3]'],
  result: 'vec4f',
  wrapper: {
    imports: ['compositeStepBackward'],
    wgsl: `fn caseUnderTest(g: array<f32, 3>, b: array<f32, 4>, x: array<f32, 4>, h: f32, behind: array<f32, 3>) -> vec4f {
  return compositeStepBackward(${W3('g')}, ${W4('b')}, ${W4('x')}, h, ${W3('behind')});
}`,
  },
  twin: (g: number[], b: number[], x: number[], h: number, behind: number[]) => [
    ...compositeStepBackward(v3(g), v4(b), v4(x), h, v3(behind)),
  ],
  tolerance: {
    ...COMPOSITE,
    absolute: 1e-8,
    reason: `${COMPOSITE.reason}; dot products of the gradient`,
  },
  cases: [
    {
      name: 'a bright sample in front of a dim background',
      args: [[0.1, -0.2, 0.05], [0, 0, 0, 1], [3, 0.9, 0.6, 0.2], 0.1, [0.05, 0.06, 0.07]],
    },
    {
      name: 'deep in the ray (T = 0.05)',
      args: [[0.3, 0.3, 0.3], [0.4, 0.4, 0.4, 0.05], [10, 0.1, 0.1, 0.1], 0.05, [0.01, 0.01, 0.01]],
    },
    {
      name: 'empty sample: ∂/∂c = 0, ∂/∂σ = h(g·c − g·B)',
      args: [[1, 1, 1], [0, 0, 0, 1], [0, 0.5, 0.5, 0.5], 0.2, [0.2, 0.2, 0.2]],
      expected: [0.2 * (1.5 - 0.6), 0, 0, 0],
    },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'pixelSquaredError',
  args: ['f32[3]', 'f32[3]'],
  result: 'f32',
  wrapper: {
    imports: ['pixelSquaredError'],
    wgsl: `fn caseUnderTest(c: array<f32, 3>, t: array<f32, 3>) -> f32 { return pixelSquaredError(${W3('c')}, ${W3('t')}); }`,
  },
  twin: (c: number[], t: number[]) => pixelSquaredError(v3(c), v3(t)),
  tolerance: { relative: 5e-7, absolute: 1e-12, reason: 'three differences, squares and sums' },
  cases: [
    {
      name: 'equal colours: 0',
      args: [
        [0.3, 0.4, 0.5],
        [0.3, 0.4, 0.5],
      ],
      expected: 0,
    },
    {
      name: 'a typical error',
      args: [
        [0.3, 0.4, 0.5],
        [0.9, 0.1, 0.45],
      ],
    },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'pixelLossGradient',
  args: ['f32[3]', 'f32[3]', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['pixelLossGradient'],
    wgsl: `fn caseUnderTest(c: array<f32, 3>, t: array<f32, 3>, w: f32) -> vec3f { return pixelLossGradient(${W3('c')}, ${W3('t')}, w); }`,
  },
  twin: (c: number[], t: number[], w: number) => [...pixelLossGradient(v3(c), v3(t), w)],
  tolerance: { relative: 4e-7, absolute: 1e-14, reason: 'a difference and two products' },
  cases: [{ name: 'w = 1/(3·1024)', args: [[0.3, 0.4, 0.5], [0.9, 0.1, 0.45], 1 / 3072] }],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'adamStep',
  args: ['f32', 'f32', 'f32', 'f32', 'u32', 'f32'],
  result: 'vec3f',
  twin: (value: number, g: number, m: number, v: number, t: number, lr: number) => [
    ...adamStep(value, g, m, v, t, lr),
  ],
  // pow(β, t) = exp2(t·log2 β) carries ≈ (3 + 2|t log2 β|) ULP plus log2's error; the
  // update's η·m̂/√v̂ is then a few more ULP of a number ≤ η.
  tolerance: {
    relative: 2e-6,
    absolute: 1e-7,
    reason: 'pow(β, t) as exp2(t·log2 β), sqrt and two divisions',
  },
  cases: [
    {
      name: 'first step: θ − η·sign(g)',
      args: [1, 3e-7, 0, 0, 1, 0.05],
      expected: [0.95, 3e-8, 9e-16],
    },
    { name: 'a later step with history', args: [-4.2, -2e-5, -1e-5, 3e-10, 37, 0.05] },
    {
      name: 'zero gradient and moments: unchanged',
      args: [0.7, 0, 0, 0, 5, 0.1],
      expected: [0.7, 0, 0],
    },
    {
      name: 'iteration 0 is read as 1',
      args: [1, 1e-3, 0, 0, 0, 0.05],
      expected: [0.95, 1e-4, 1e-8],
    },
    { name: 'late iteration: bias corrections → 1', args: [2, 1e-4, 1e-4, 1e-8, 3000, 0.01] },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'totalVariationGradient',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: totalVariationGradient,
  tolerance: {
    relative: 4e-7,
    absolute: 1e-6,
    reason: 'one product and a difference (may cancel)',
  },
  cases: [
    { name: 'interior voxel above its neighbours', args: [1, 3, 6], expected: 6 },
    { name: 'corner voxel (3 neighbours)', args: [-5, -12, 3], expected: -6 },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'sparsityGradient',
  args: ['f32'],
  result: 'f32',
  twin: sparsityGradient,
  tolerance: { relative: 1e-5, absolute: 1e-9, reason: 'softplus, sigmoid and a division' },
  cases: [
    { name: 'haze (ρ = −2)', args: [-2] },
    { name: 'σt ≈ 1/√2 m⁻¹, the peak', args: [-2.6] },
    { name: 'dense voxel: the prior lets go', args: [3] },
    { name: 'empty voxel: ≈ 0', args: [-20] },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'stratifiedSubsetIndex',
  args: ['u32', 'u32', 'u32', 'u32'],
  result: 'u32',
  twin: stratifiedSubsetIndex,
  tolerance: { reason: 'integer arithmetic and the PCG hash: exact' },
  cases: [
    { name: 'full batch: the identity', args: [17, 100, 100, 3], expected: 17 },
    { name: 'batch 1024 of 8192, member 0', args: [0, 1024, 8192, 0] },
    { name: 'batch 1024 of 8192, last member', args: [1023, 1024, 8192, 41] },
    { name: 'uneven strata: 7 of 100', args: [3, 7, 100, 4095] },
    { name: 'the largest widget case: 16384 of 16384 + 1', args: [16383, 16384, 16385, 1 << 20] },
  ],
});
