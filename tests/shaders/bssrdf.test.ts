// WGSL bssrdf and dielectric modules vs their float64 twins (chapter 11, physics.md §6.1):
// the Fibonacci lattice of irradiance samples, the transmitted irradiance with Fresnel,
// Jensen & Buhler's node criterion, the exitant-radiance factor, and Snell refraction with
// total internal reflection.
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  bssrdfExitFactor,
  fibonacciSpherePoint,
  gatherAcceptsNode,
  irradianceSample,
} from '../../src/reference/bssrdf.ts';
import { refractDirection } from '../../src/reference/dielectric.ts';

type V3 = [number, number, number];
const v3 = (a: readonly number[]): V3 => [a[0] ?? NaN, a[1] ?? NaN, a[2] ?? NaN];
const vec = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;

// WGSL cos/sin may err by 2⁻¹¹ absolute (README pitfalls); SwiftShader does far better, but
// the bound is what the spec allows. z is one division (exact to 2.5 ULP).
const LATTICE: Tolerance = { absolute: 5e-4, reason: 'WGSL sin/cos: 2⁻¹¹ absolute' };

describeShaderFunction({
  module: 'bssrdf',
  fn: 'fibonacciSpherePoint',
  args: ['u32', 'u32'],
  result: 'vec3f',
  twin: (i: number, n: number) => fibonacciSpherePoint(i, n),
  tolerance: LATTICE,
  cases: [
    { name: 'one point: the equator at φ = 0', args: [0, 1], expected: [1, 0, 0] },
    {
      name: 'first of 4: z = 3/4, φ = 0',
      args: [0, 4],
      expected: [Math.sqrt(1 - 0.5625), 0, 0.75],
    },
    { name: 'last of 4: z = −3/4', args: [3, 4] },
    { name: 'i = 5 of 100', args: [5, 100] },
    { name: 'i = 40000 of 65536 (the split phase)', args: [40000, 65536] },
    { name: 'count 0 is taken as 1', args: [0, 0], expected: [1, 0, 0] },
  ],
});

// fresnelDielectric's ≲ 12 ULP times a cosine.
const IRRADIANCE: Tolerance = {
  relative: 4e-6,
  absolute: 1e-7,
  reason: 'Fresnel (≲ 12 ULP) × cos',
};

describeShaderFunction({
  module: 'bssrdf',
  fn: 'irradianceSample',
  args: ['f32[3]', 'f32[3]', 'f32'],
  result: 'f32',
  wrapper: {
    imports: ['irradianceSample'],
    wgsl: `fn caseUnderTest(n: array<f32, 3>, l: array<f32, 3>, eta: f32) -> f32 {
  return irradianceSample(${vec('n')}, ${vec('l')}, eta);
}`,
  },
  twin: (n: number[], l: number[], eta: number) => irradianceSample(v3(n), v3(l), eta),
  tolerance: IRRADIANCE,
  cases: [
    { name: 'head-on, η = 1.5: 1 − 0.04', args: [[0, 0, 1], [0, 0, 1], 1.5], expected: 0.96 },
    { name: 'η = 1: the plain cosine 0.6', args: [[0, 0, 1], [0.8, 0, 0.6], 1], expected: 0.6 },
    { name: 'oblique, η = 1.3', args: [[0, 0, 1], [0.8, 0, 0.6], 1.3] },
    { name: 'facing away: 0', args: [[0, 0, 1], [0, 0.6, -0.8], 1.3], expected: 0 },
    { name: 'grazing: 0', args: [[0, 0, 1], [1, 0, 0], 1.3], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'bssrdf',
  fn: 'gatherAcceptsNode',
  args: ['f32', 'f32[3]', 'f32[3]', 'f32[3]', 'f32[3]', 'f32'],
  result: 'f32',
  wrapper: {
    imports: ['gatherAcceptsNode'],
    wgsl: `fn caseUnderTest(area: f32, c: array<f32, 3>, lo: array<f32, 3>, hi: array<f32, 3>, x: array<f32, 3>, epsilon: f32) -> f32 {
  return select(0.0, 1.0, gatherAcceptsNode(area, ${vec('c')}, ${vec('lo')}, ${vec('hi')}, ${vec('x')}, epsilon));
}`,
  },
  twin: (area: number, c: number[], lo: number[], hi: number[], x: number[], epsilon: number) =>
    gatherAcceptsNode(area, v3(c), v3(lo), v3(hi), v3(x), epsilon) ? 1 : 0,
  tolerance: { absolute: 0, reason: 'a decision away from its threshold' },
  cases: [
    {
      name: 'small, far node: used whole (ΔA/d² = 0.01 < 0.1)',
      args: [1, [0, 0, 0], [-1, -1, -1], [1, 1, 1], [10, 0, 0], 0.1],
      expected: 1,
    },
    {
      name: 'the same node with ε = 0.005: descend',
      args: [1, [0, 0, 0], [-1, -1, -1], [1, 1, 1], [10, 0, 0], 0.005],
      expected: 0,
    },
    {
      name: 'x inside the box: always descend',
      args: [1e-6, [0, 0, 0], [-1, -1, -1], [1, 1, 1], [0.5, 0.5, 0.5], 10],
      expected: 0,
    },
    {
      name: 'ε = 0 accepts nothing',
      args: [1e-6, [0, 0, 0], [-1, -1, -1], [1, 1, 1], [100, 0, 0], 0],
      expected: 0,
    },
  ],
});

// 16-point Gauss–Legendre external moment (≲ 2e-6, tests/shaders/fresnel.test.ts) against
// the twin's adaptive quadrature, divided into (1 − F): ≲ 3e-6 relative.
describeShaderFunction({
  module: 'bssrdf',
  fn: 'bssrdfExitFactor',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: bssrdfExitFactor,
  tolerance: {
    relative: 5e-6,
    absolute: 1e-8,
    reason: 'Gauss–Legendre moment vs adaptive (≲ 2e-6)',
  },
  cases: [
    {
      name: 'normal view, η = 1.3: (1 − 0.017)/(π(1 − 0.061132))',
      args: [1, 1.3],
      expected: (1 - (0.3 / 2.3) ** 2) / (Math.PI * (1 - 0.061132)),
      tolerance: { relative: 2e-6, reason: 'published F_dr^ext(1.3) = 0.061132 to 6 digits' },
    },
    { name: 'η = 1: 1/π', args: [0.5, 1], expected: 1 / Math.PI },
    { name: 'oblique, marble η = 1.5', args: [0.3, 1.5] },
    { name: 'grazing: 0', args: [0, 1.3], expected: 0 },
  ],
});

// One division, a sqrt and a normalize: a few ULP per component.
describeShaderFunction({
  module: 'dielectric',
  fn: 'refractDirection',
  args: ['f32[3]', 'f32[3]', 'f32'],
  result: 'vec4f',
  wrapper: {
    imports: ['refractDirection'],
    wgsl: `fn caseUnderTest(d: array<f32, 3>, n: array<f32, 3>, eta: f32) -> vec4f {
  return refractDirection(${vec('d')}, ${vec('n')}, eta);
}`,
  },
  twin: (d: number[], n: number[], eta: number) => refractDirection(d, n, eta),
  tolerance: { absolute: 2e-6, reason: 'a division, a sqrt and a normalize (≲ 8 ULP of 1)' },
  cases: [
    {
      name: 'normal incidence passes straight',
      args: [[0, 0, -1], [0, 0, 1], 1.5],
      expected: [0, 0, -1, 1],
    },
    {
      name: 'η = 1 keeps the direction',
      args: [[0.6, 0, -0.8], [0, 0, 1], 1],
      expected: [0.6, 0, -0.8, 1],
    },
    {
      name: '45° into glass: sin θt = sin 45°/1.5',
      args: [[Math.SQRT1_2, 0, -Math.SQRT1_2], [0, 0, 1], 1.5],
      expected: [Math.SQRT1_2 / 1.5, 0, -Math.sqrt(1 - 0.5 / 2.25), 1],
      tolerance: { absolute: 2e-6, reason: 'f32-rounded input direction' },
    },
    {
      name: 'beyond the critical angle from inside: mirror, flag 0',
      args: [[0.8, 0, 0.6], [0, 0, -1], 1 / 1.3],
      expected: [0.8, 0, -0.6, 0],
    },
    {
      name: 'oblique exit below the critical angle',
      args: [[0.5, 0, Math.sqrt(0.75)], [0, 0, -1], 1 / 1.3],
    },
  ],
});
