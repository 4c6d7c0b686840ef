// WGSL surfaces module vs its float64 twin (src/reference/surfaces.ts): first hits of
// rays with planes, spheres and boxes in the open interval (tMin, tMax), normals that face
// the incoming ray, the Lambertian BRDF, cosine-weighted sampling and the offset origin.
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  SURFACE_NO_HIT,
  boxHitDistance,
  boxNormal,
  lambertianBrdf,
  planeHitDistance,
  sampleCosineHemisphere,
  sphereHitDistance,
  surfaceNormalFacing,
  surfaceOffsetOrigin,
} from '../../src/reference/surfaces.ts';
import type { Vec3 } from '../../src/reference/phase.ts';

const v3 = (a: readonly number[]): Vec3 => [a[0] ?? NaN, a[1] ?? NaN, a[2] ?? NaN];
const V3 = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;
const HIT: Tolerance = {
  relative: 1e-6,
  absolute: 1e-6,
  reason: 'the geometry module: one division per plane (2.5 ULP), the sphere quadratic',
};
const ray = ['f32[3]', 'f32[3]', 'f32[3]', 'f32[3]', 'f32', 'f32'] as const;

describeShaderFunction({
  module: 'surfaces',
  fn: 'planeHitDistance',
  args: ray,
  result: 'f32',
  wrapper: {
    imports: ['planeHitDistance'],
    wgsl: `fn caseUnderTest(p: array<f32, 3>, n: array<f32, 3>, o: array<f32, 3>, d: array<f32, 3>, tMin: f32, tMax: f32) -> f32 { return planeHitDistance(${V3('p')}, ${V3('n')}, ${V3('o')}, ${V3('d')}, tMin, tMax); }`,
  },
  twin: (p: number[], n: number[], o: number[], d: number[], tMin: number, tMax: number) =>
    planeHitDistance(v3(p), v3(n), v3(o), v3(d), tMin, tMax),
  tolerance: HIT,
  cases: [
    {
      name: 'floor below: t = 2',
      args: [[0, 0, 0], [0, 1, 0], [0, 2, 0], [0, -1, 0], 0, 10],
      expected: 2,
    },
    {
      name: 'from below (two-sided): t = 1',
      args: [[0, 0, 0], [0, 1, 0], [1, -1, 1], [0, 1, 0], 0, 10],
      expected: 1,
    },
    {
      name: 'parallel: no hit',
      args: [[0, 0, 0], [0, 1, 0], [0, 1, 0], [1, 0, 0], 0, 10],
      expected: SURFACE_NO_HIT,
    },
    {
      name: 'beyond tMax: no hit',
      args: [[0, 0, 0], [0, 1, 0], [0, 5, 0], [0, -1, 0], 0, 4],
      expected: SURFACE_NO_HIT,
    },
    {
      name: 'behind the origin: no hit',
      args: [[0, 0, 0], [0, 1, 0], [0, 1, 0], [0, 1, 0], 0, 10],
      expected: SURFACE_NO_HIT,
    },
  ],
});

describeShaderFunction({
  module: 'surfaces',
  fn: 'sphereHitDistance',
  args: ['f32[3]', 'f32', 'f32[3]', 'f32[3]', 'f32', 'f32'],
  result: 'f32',
  wrapper: {
    imports: ['sphereHitDistance'],
    wgsl: `fn caseUnderTest(c: array<f32, 3>, r: f32, o: array<f32, 3>, d: array<f32, 3>, tMin: f32, tMax: f32) -> f32 { return sphereHitDistance(${V3('c')}, r, ${V3('o')}, ${V3('d')}, tMin, tMax); }`,
  },
  twin: (c: number[], r: number, o: number[], d: number[], tMin: number, tMax: number) =>
    sphereHitDistance(v3(c), r, v3(o), v3(d), tMin, tMax),
  tolerance: HIT,
  cases: [
    {
      name: 'from outside: the near side',
      args: [[0, 0, 0], 1, [0, 0, 5], [0, 0, -1], 0, 100],
      expected: 4,
    },
    {
      name: 'from inside: the far side',
      args: [[0, 0, 0], 1, [0, 0, 0.5], [0, 0, -1], 0, 100],
      expected: 1.5,
    },
    {
      name: 'a miss',
      args: [[0, 0, 0], 1, [0, 2, 5], [0, 0, -1], 0, 100],
      expected: SURFACE_NO_HIT,
    },
    {
      name: 'behind: no hit',
      args: [[0, 0, 0], 1, [0, 0, 5], [0, 0, 1], 0, 100],
      expected: SURFACE_NO_HIT,
    },
  ],
});

describeShaderFunction({
  module: 'surfaces',
  fn: 'boxHitDistance',
  args: ray,
  result: 'f32',
  wrapper: {
    imports: ['boxHitDistance'],
    wgsl: `fn caseUnderTest(lo: array<f32, 3>, hi: array<f32, 3>, o: array<f32, 3>, d: array<f32, 3>, tMin: f32, tMax: f32) -> f32 { return boxHitDistance(${V3('lo')}, ${V3('hi')}, ${V3('o')}, ${V3('d')}, tMin, tMax); }`,
  },
  twin: (lo: number[], hi: number[], o: number[], d: number[], tMin: number, tMax: number) =>
    boxHitDistance(v3(lo), v3(hi), v3(o), v3(d), tMin, tMax),
  tolerance: HIT,
  cases: [
    {
      name: 'from outside: entry',
      args: [[-1, -1, -1], [1, 1, 1], [-3, 0, 0], [1, 0, 0], 0, 100],
      expected: 2,
    },
    {
      name: 'from inside: exit',
      args: [[-1, -1, -1], [1, 1, 1], [0, 0, 0], [0, 1, 0], 0, 100],
      expected: 1,
    },
    {
      name: 'a flat box (a card) is hit',
      args: [[-1, 0, -1], [1, 0, 1], [0, 2, 0], [0, -1, 0], 0, 100],
      expected: 2,
    },
    {
      name: 'a miss',
      args: [[-1, -1, -1], [1, 1, 1], [-3, 2, 0], [1, 0, 0], 0, 100],
      expected: SURFACE_NO_HIT,
    },
  ],
});

describeShaderFunction({
  module: 'surfaces',
  fn: 'boxNormal',
  args: ['f32[3]', 'f32[3]', 'f32[3]'],
  result: 'vec3f',
  wrapper: {
    imports: ['boxNormal'],
    wgsl: `fn caseUnderTest(lo: array<f32, 3>, hi: array<f32, 3>, p: array<f32, 3>) -> vec3f { return boxNormal(${V3('lo')}, ${V3('hi')}, ${V3('p')}); }`,
  },
  twin: (lo: number[], hi: number[], p: number[]) => [...boxNormal(v3(lo), v3(hi), v3(p))],
  tolerance: { absolute: 0, reason: 'a choice of axis and sign: exact' },
  cases: [
    {
      name: '+x face',
      args: [
        [-1, -1, -1],
        [1, 1, 1],
        [1, 0.2, -0.3],
      ],
      expected: [1, 0, 0],
    },
    {
      name: '−y face of a long box',
      args: [
        [0, 0, 0],
        [4, 1, 1],
        [3.5, 0, 0.5],
      ],
      expected: [0, -1, 0],
    },
    {
      name: "flat axis: the card's face",
      args: [
        [-1, 0, -1],
        [1, 0, 1],
        [0.9, 0, 0.9],
      ],
      expected: [0, 1, 0],
    },
  ],
});

describeShaderFunction({
  module: 'surfaces',
  fn: 'surfaceNormalFacing',
  args: ['u32', 'f32[3]', 'f32', 'f32[3]', 'f32[3]', 'f32[3]'],
  result: 'vec3f',
  wrapper: {
    imports: ['surfaceNormalFacing', 'Surface'],
    wgsl: `fn caseUnderTest(kind: u32, a: array<f32, 3>, radius: f32, b: array<f32, 3>, p: array<f32, 3>, d: array<f32, 3>) -> vec3f {
  let s = Surface(kind, 0.0, 0.0, 0.0, ${V3('a')}, radius, ${V3('b')}, 0.0, vec3f(0.5), 0.0);
  return surfaceNormalFacing(s, ${V3('p')}, ${V3('d')});
}`,
  },
  twin: (kind: number, a: number[], radius: number, b: number[], p: number[], d: number[]) => [
    ...surfaceNormalFacing(
      { kind, a: v3(a), radius, b: v3(b), albedo: [0.5, 0.5, 0.5] },
      v3(p),
      v3(d),
    ),
  ],
  tolerance: { relative: 1e-6, absolute: 1e-6, reason: 'normalize: inverseSqrt (2 ULP)' },
  cases: [
    {
      name: 'plane seen from above',
      args: [0, [0, 0, 0], 0, [0, 2, 0], [1, 0, 1], [0, -1, 0]],
      expected: [0, 1, 0],
    },
    {
      name: 'plane seen from below: flipped',
      args: [0, [0, 0, 0], 0, [0, 2, 0], [1, 0, 1], [0, 1, 0]],
      expected: [0, -1, 0],
    },
    {
      name: 'sphere from outside',
      args: [1, [0, 0, 0], 2, [0, 0, 0], [0, 0, 2], [0, 0, -1]],
      expected: [0, 0, 1],
    },
    {
      name: 'sphere from inside: inward',
      args: [1, [0, 0, 0], 2, [0, 0, 0], [0, 0, 2], [0, 0, 1]],
      expected: [0, 0, -1],
    },
    {
      name: 'box face',
      args: [2, [-1, -1, -1], 0, [1, 1, 1], [-1, 0, 0], [1, 0, 0]],
      expected: [-1, 0, 0],
    },
  ],
});

describeShaderFunction({
  module: 'surfaces',
  fn: 'lambertianBrdf',
  args: ['f32[3]'],
  result: 'vec3f',
  wrapper: {
    imports: ['lambertianBrdf'],
    wgsl: `fn caseUnderTest(a: array<f32, 3>) -> vec3f { return lambertianBrdf(${V3('a')}); }`,
  },
  twin: (a: number[]) => [...lambertianBrdf(v3(a))],
  tolerance: { relative: 1e-6, reason: 'one f32 product' },
  cases: [
    { name: 'ρ/π', args: [[1, 0.5, 0]], expected: [1 / Math.PI, 0.5 / Math.PI, 0] },
    {
      name: 'albedo clamped to [0, 1]',
      args: [[2, -1, 0.25]],
      expected: [1 / Math.PI, 0, 0.25 / Math.PI],
    },
  ],
});

describeShaderFunction({
  module: 'surfaces',
  fn: 'sampleCosineHemisphere',
  args: ['f32[3]', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['sampleCosineHemisphere'],
    wgsl: `fn caseUnderTest(n: array<f32, 3>, ux: f32, uy: f32) -> vec3f { return sampleCosineHemisphere(${V3('n')}, vec2f(ux, uy)); }`,
  },
  twin: (n: number[], ux: number, uy: number) => [...sampleCosineHemisphere(v3(n), [ux, uy])],
  tolerance: { absolute: 2e-3, reason: 'sin/cos with 2^-11 absolute error on SwiftShader' },
  cases: [
    { name: 'u.x = 0: the normal itself', args: [[0, 1, 0], 0, 0.3], expected: [0, 1, 0] },
    { name: 'u.x = ¾: 60° from the normal', args: [[0, 0, 1], 0.75, 0.5] },
    { name: 'about a tilted normal', args: [[0.6, 0, 0.8], 0.4, 0.9] },
  ],
});

describeShaderFunction({
  module: 'surfaces',
  fn: 'surfaceOffsetOrigin',
  args: ['f32[3]', 'f32[3]'],
  result: 'vec3f',
  wrapper: {
    imports: ['surfaceOffsetOrigin'],
    wgsl: `fn caseUnderTest(p: array<f32, 3>, n: array<f32, 3>) -> vec3f { return surfaceOffsetOrigin(${V3('p')}, ${V3('n')}); }`,
  },
  twin: (p: number[], n: number[]) => [...surfaceOffsetOrigin(v3(p), v3(n))],
  tolerance: { relative: 1e-7, absolute: 1e-9, reason: 'one f32 multiply-add' },
  cases: [
    {
      name: 'near the origin: 1e-4 m along n',
      args: [
        [0, 0, 0],
        [0, 1, 0],
      ],
      expected: [0, 1e-4, 0],
    },
    {
      name: 'far away: scaled with the coordinates',
      args: [
        [1000, 0, 0],
        [1, 0, 0],
      ],
      expected: [1000.1, 0, 0],
    },
  ],
});
