// The integrator module's pure functions vs their float64 twins: truncated free flights
// (sampling and density, including the uniform limit k → 0 and a thick segment),
// equiangular points on a ray segment, Beer's law per channel and the channel helpers.
// The estimators themselves are tested on whole images (tests/shaders/scene-render.test.ts,
// tests/reference/render-analytic.test.ts).
import { describeShaderFunction } from '../support/shaderHarness.ts';
import {
  averageComponent,
  equiangularSegmentSample,
  maxComponent,
  sampleTruncatedExponential,
  transmittanceBeer,
  truncatedExponentialPdf,
} from '../../src/reference/integrator.ts';
import type { Vec3 } from '../../src/reference/phase.ts';

const v3 = (a: readonly number[]): Vec3 => [a[0] ?? NaN, a[1] ?? NaN, a[2] ?? NaN];
const V3 = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;

describeShaderFunction({
  module: 'integrator',
  fn: 'sampleTruncatedExponential',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: sampleTruncatedExponential,
  tolerance: {
    relative: 2e-6,
    absolute: 1e-6,
    reason: 'WGSL log (2^-21 absolute near 1), exp (3 + 2|x| ULP) and a division',
  },
  cases: [
    { name: 'k = 0: uniform, s = uL', args: [0, 2, 0.25], expected: 0.5 },
    { name: 'u = 0: s = 0', args: [1, 2, 0], expected: 0 },
    { name: 'median of k = 1, L = ∞-like (L = 50): ln 2', args: [1, 50, 0.5], expected: Math.LN2 },
    { name: 'thin: kL = 1e-6, the series branch', args: [1e-6, 1, 0.7] },
    { name: 'thick: kL = 200, e^{-kL} underflows', args: [100, 2, 0.999] },
    { name: 'largest u stays inside the segment', args: [3, 1, 1 - 2 ** -24] },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'truncatedExponentialPdf',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: truncatedExponentialPdf,
  tolerance: { relative: 5e-6, reason: 'WGSL exp (3 + 2|x| ULP), oneMinusExpOverX and a division' },
  cases: [
    { name: 'k = 0: 1/L', args: [0, 4, 1], expected: 0.25 },
    {
      name: 'k = 1, L = 1, s = 0: 1/(1 − e^{-1})',
      args: [1, 1, 0],
      expected: 1 / (1 - Math.exp(-1)),
    },
    { name: 'thin segment: ≈ 1/L', args: [1e-7, 2, 1] },
    { name: 'thick: k e^{-ks}', args: [50, 3, 0.01], expected: 50 * Math.exp(-0.5) },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'equiangularSegmentSample',
  args: ['f32[3]', 'f32[3]', 'f32[3]', 'f32[2]', 'f32'],
  result: 'vec2f',
  wrapper: {
    imports: ['equiangularSegmentSample'],
    wgsl: `fn caseUnderTest(l: array<f32, 3>, o: array<f32, 3>, d: array<f32, 3>, s: array<f32, 2>, xi: f32) -> vec2f { return equiangularSegmentSample(${V3('l')}, ${V3('o')}, ${V3('d')}, vec2f(s[0], s[1]), xi); }`,
  },
  twin: (l: number[], o: number[], d: number[], s: number[], xi: number) => [
    ...equiangularSegmentSample(v3(l), v3(o), v3(d), [s[0] ?? NaN, s[1] ?? NaN], xi),
  ],
  tolerance: {
    relative: 2e-4,
    absolute: 2e-5,
    reason: 'atan2 and tan from sin/cos (2^-11 absolute on SwiftShader)',
  },
  cases: [
    {
      name: 'ξ = ½ on a segment symmetric about the light: the closest point, pdf 1/(h·(θb − θa))',
      args: [[0, 1, -2], [0, 0, 0], [0, 0, -1], [1, 3], 0.5],
      expected: [2, 1 / (Math.PI / 2)],
    },
    { name: 'ξ = 0: the segment start', args: [[0, 0.5, -1], [0, 0, 0], [0, 0, -1], [0, 5], 0] },
    {
      name: 'a light on the ray: the uniform fallback',
      args: [[0, 0, -3], [0, 0, 0], [0, 0, -1], [1, 5], 0.25],
      expected: [2, 0.25],
    },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'transmittanceBeer',
  args: ['f32[3]', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['transmittanceBeer'],
    wgsl: `fn caseUnderTest(s: array<f32, 3>, d: f32) -> vec3f { return transmittanceBeer(${V3('s')}, d); }`,
  },
  twin: (s: number[], d: number) => [...transmittanceBeer(v3(s) as [number, number, number], d)],
  tolerance: { relative: 2e-5, absolute: 2 ** -126, reason: 'WGSL exp: 3 + 2|x| ULP' },
  cases: [
    { name: 'per channel', args: [[0, 1, 2], 0.5], expected: [1, Math.exp(-0.5), Math.exp(-1)] },
    {
      name: 'opaque: exactly 0 beyond τ = 103.97',
      args: [[1e6, 200, 0.1], 1],
      expected: [0, 0, Math.exp(-0.1)],
    },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'maxComponent',
  args: ['f32[3]'],
  result: 'f32',
  wrapper: {
    imports: ['maxComponent'],
    wgsl: `fn caseUnderTest(v: array<f32, 3>) -> f32 { return maxComponent(${V3('v')}); }`,
  },
  twin: (v: number[]) => maxComponent(v),
  tolerance: { absolute: 0, reason: 'exact' },
  cases: [{ name: 'the largest channel', args: [[0.5, 2, -1]], expected: 2 }],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'averageComponent',
  args: ['f32[3]'],
  result: 'f32',
  wrapper: {
    imports: ['averageComponent'],
    wgsl: `fn caseUnderTest(v: array<f32, 3>) -> f32 { return averageComponent(${V3('v')}); }`,
  },
  twin: (v: number[]) => averageComponent(v),
  tolerance: { relative: 3e-7, reason: 'two sums and a division' },
  cases: [{ name: 'the channel mean', args: [[1, 2, 6]], expected: 3 }],
});
