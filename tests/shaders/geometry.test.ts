// WGSL geometry module vs its float64 twin: the segment of a ray inside a box and a
// sphere, with the hard cases (parallel rays, flat boxes, tangent rays, origins inside,
// a far ray at a small sphere where the textbook quadratic cancels).
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import { describe, expect, it } from 'vitest';
import { rayBoxExit, rayBoxSegment, raySphereSegment } from '../../src/reference/geometry.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import type { Vec3 } from '../../src/reference/phase.ts';

const v3 = (a: readonly number[]): Vec3 => [a[0] ?? NaN, a[1] ?? NaN, a[2] ?? NaN];

// Divisions (2.5 ULP) and min/max (exact) on f32 inputs; absolute for t near 0.
const BOX_TOLERANCE: Tolerance = {
  relative: 4e-7,
  absolute: 1e-6,
  reason: 'one f32 division (2.5 ULP) per plane crossing',
};

describeShaderFunction({
  module: 'geometry',
  fn: 'rayBoxSegment',
  args: ['f32[3]', 'f32[3]', 'f32[3]', 'f32[3]', 'f32', 'f32'],
  result: 'vec2f',
  wrapper: {
    imports: ['rayBoxSegment'],
    wgsl: `fn caseUnderTest(lo: array<f32, 3>, hi: array<f32, 3>, o: array<f32, 3>, d: array<f32, 3>, tMin: f32, tMax: f32) -> vec2f {
  return rayBoxSegment(vec3f(lo[0], lo[1], lo[2]), vec3f(hi[0], hi[1], hi[2]), vec3f(o[0], o[1], o[2]), vec3f(d[0], d[1], d[2]), tMin, tMax);
}`,
  },
  twin: (lo: number[], hi: number[], o: number[], d: number[], tMin: number, tMax: number) => [
    ...rayBoxSegment(v3(lo), v3(hi), v3(o), v3(d), tMin, tMax),
  ],
  tolerance: BOX_TOLERANCE,
  cases: [
    {
      name: 'through the unit cube along +x: [1, 2]',
      args: [[0, 0, 0], [1, 1, 1], [-1, 0.5, 0.5], [1, 0, 0], 0, 10],
      expected: [1, 2],
    },
    {
      name: 'diagonal through the cube',
      args: [[-1, -1, -1], [1, 1, 1], [-3, -2.5, -2], [0.6, 0.48, 0.64], 0, 100],
    },
    {
      name: 'origin inside: t0 = tMin',
      args: [[0, 0, 0], [2, 2, 2], [1, 1, 1], [0, 0, -1], 0, 10],
      expected: [0, 1],
    },
    {
      name: 'parallel to a slab, outside it: a miss',
      args: [[0, 0, 0], [1, 1, 1], [-1, 2, 0.5], [1, 0, 0], 0, 10],
      expected: [1, 0],
    },
    {
      name: 'parallel on the face: touches along the whole face',
      args: [[0, 0, 0], [1, 1, 1], [-1, 1, 0.5], [1, 0, 0], 0, 10],
      expected: [1, 2],
    },
    {
      name: 'flat box (a plane) crossed: t0 = t1',
      args: [[0, 0, 0], [1, 0, 1], [0.5, -2, 0.5], [0, 1, 0], 0, 10],
      expected: [2, 2],
    },
    {
      name: 'inverted box: empty',
      args: [[1, 0, 0], [0, 1, 1], [-1, 0.5, 0.5], [1, 0, 0], 0, 10],
      expected: [1, 0],
    },
    {
      name: 'segment ends before the box: empty',
      args: [[0, 0, 0], [1, 1, 1], [-5, 0.5, 0.5], [1, 0, 0], 0, 2],
      expected: [1, 0],
    },
    {
      name: 'subnormal direction component: finite crossings, hit along x',
      args: [[0, 0, 0], [1, 1, 1], [-1, 0.5, 0.5], [1, 1e-40, 0], 0, 10],
      expected: [1, 2],
    },
  ],
});

describeShaderFunction({
  module: 'geometry',
  fn: 'rayBoxExit',
  args: ['f32[3]', 'f32[3]', 'f32[3]', 'f32[3]', 'f32'],
  result: 'f32',
  wrapper: {
    imports: ['rayBoxExit'],
    wgsl: `fn caseUnderTest(lo: array<f32, 3>, hi: array<f32, 3>, o: array<f32, 3>, d: array<f32, 3>, tMax: f32) -> f32 {
  return rayBoxExit(vec3f(lo[0], lo[1], lo[2]), vec3f(hi[0], hi[1], hi[2]), vec3f(o[0], o[1], o[2]), vec3f(d[0], d[1], d[2]), tMax);
}`,
  },
  twin: (lo: number[], hi: number[], o: number[], d: number[], tMax: number) =>
    rayBoxExit(v3(lo), v3(hi), v3(o), v3(d), tMax),
  tolerance: BOX_TOLERANCE,
  cases: [
    {
      name: 'from the centre along −z: 1',
      args: [[0, 0, 0], [2, 2, 2], [1, 1, 1], [0, 0, -1], 10],
      expected: 1,
    },
    {
      name: 'oblique from inside: the nearest far face (y)',
      args: [[-1, -1, -1], [1, 1, 1], [0.2, 0.5, -0.3], [0.48, 0.6, -0.64], 100],
      expected: 0.5 / 0.6,
    },
    {
      name: 'tMax binds: 0.25',
      args: [[-1, -1, -1], [1, 1, 1], [0, 0, 0], [1, 0, 0], 0.25],
      expected: 0.25,
    },
    {
      name: 'on the face it moves toward: 0',
      args: [[0, 0, 0], [1, 1, 1], [1, 0.5, 0.5], [1, 0, 0], 10],
      expected: 0,
    },
    {
      name: 'on a face, moving along it: the other axis binds',
      args: [[0, 0, 0], [1, 1, 1], [0.25, 1, 0.5], [1, 0, 0], 10],
      expected: 0.75,
    },
    {
      name: 'just outside (rounding) and moving away: 0, not negative',
      args: [[0, 0, 0], [1, 1, 1], [1.000001, 0.5, 0.5], [1, 0, 0], 10],
      expected: 0,
    },
    {
      name: 'zero direction: tMax',
      args: [[0, 0, 0], [1, 1, 1], [0.5, 0.5, 0.5], [0, 0, 0], 7],
      expected: 7,
    },
    {
      name: 'subnormal slope on one axis: the other axes bind',
      args: [[0, 0, 0], [1, 1, 1], [0.5, 0.5, 0.5], [1e-40, 0, 1], 10],
      expected: 0.5,
    },
    {
      name: 'huge tMax: clamped to 1e17 when nothing binds',
      args: [[0, 0, 0], [1, 1, 1], [0.5, 0.5, 0.5], [0, 0, 0], 3e38],
      expected: 1e17,
    },
  ],
});

describe('geometry.rayBoxExit (twin): rayBoxSegment’s t1 for origins in the box', () => {
  it('agrees with rayBoxSegment(…, 0, tMax)[1] at 2000 random interior points and directions', () => {
    const state = { value: rngSeed(19, 0) };
    const between = (a: number, b: number): number => a + (b - a) * rngNextFloat(state);
    for (let i = 0; i < 2000; i++) {
      const lo: Vec3 = [between(-3, 0), between(-3, 0), between(-3, 0)];
      const hi: Vec3 = [between(0, 3), between(0, 3), between(0, 3)];
      const o: Vec3 = [between(lo[0], hi[0]), between(lo[1], hi[1]), between(lo[2], hi[2])];
      // Some directions parallel to an axis plane, as a directional light's can be.
      const d = [between(-1, 1), between(-1, 1), between(-1, 1)].map((x, axis) =>
        i % 5 === 0 && axis === i % 3 ? 0 : x,
      ) as unknown as Vec3;
      const tMax = i % 7 === 0 ? between(0, 1) : 1e17;
      const [t0, t1] = rayBoxSegment(lo, hi, o, d, 0, tMax);
      expect(t0).toBe(0);
      expect(rayBoxExit(lo, hi, o, d, tMax)).toBeCloseTo(t1, 12);
    }
  });
});

// Haines et al. 2019: dot products (≈ 3 ULP each), one sqrt and one division.
const SPHERE_TOLERANCE: Tolerance = {
  relative: 2e-6,
  absolute: 2e-6,
  reason: 'dot products, sqrt (1 ULP) and c/q (2.5 ULP) in f32 on f32 inputs',
};

describeShaderFunction({
  module: 'geometry',
  fn: 'raySphereSegment',
  args: ['f32[3]', 'f32', 'f32[3]', 'f32[3]', 'f32', 'f32'],
  result: 'vec2f',
  wrapper: {
    imports: ['raySphereSegment'],
    wgsl: `fn caseUnderTest(c: array<f32, 3>, r: f32, o: array<f32, 3>, d: array<f32, 3>, tMin: f32, tMax: f32) -> vec2f {
  return raySphereSegment(vec3f(c[0], c[1], c[2]), r, vec3f(o[0], o[1], o[2]), vec3f(d[0], d[1], d[2]), tMin, tMax);
}`,
  },
  twin: (c: number[], r: number, o: number[], d: number[], tMin: number, tMax: number) => [
    ...raySphereSegment(v3(c), r, v3(o), v3(d), tMin, tMax),
  ],
  tolerance: SPHERE_TOLERANCE,
  cases: [
    {
      name: 'through the centre of the unit sphere: [2, 4]',
      args: [[0, 0, 0], 1, [0, 0, -3], [0, 0, 1], 0, 10],
      expected: [2, 4],
    },
    {
      name: 'origin at the centre: [0, r]',
      args: [[1, 2, 3], 0.5, [1, 2, 3], [0, 1, 0], 0, 10],
      expected: [0, 0.5],
    },
    {
      name: 'tangent ray: t0 = t1 = 3',
      args: [[0, 0, 0], 1, [1, 0, -3], [0, 0, 1], 0, 10],
      expected: [3, 3],
    },
    {
      name: 'a miss',
      args: [[0, 0, 0], 1, [1.5, 0, -3], [0, 0, 1], 0, 10],
      expected: [1, 0],
    },
    {
      name: 'zero radius: empty',
      args: [[0, 0, 0], 0, [0, 0, -3], [0, 0, 1], 0, 10],
      expected: [1, 0],
    },
    {
      name: 'sphere behind the origin: empty',
      args: [[0, 0, 0], 1, [0, 0, 3], [0, 0, 1], 0, 10],
      expected: [1, 0],
    },
    {
      // The textbook b² − c loses every digit here (c ≈ 1e8, b² ≈ 1e8, Δ ≈ 1e-6).
      name: 'a 1 mm sphere seen from 10 km: [1e4 − 1e-3, 1e4 + 1e-3]',
      args: [[0, 0, 0], 1e-3, [0, 0, -1e4], [0, 0, 1], 0, 1e5],
      expected: [1e4 - 1e-3, 1e4 + 1e-3],
      tolerance: {
        relative: 2e-7,
        reason: 'near 1e4 an f32 ULP is 1e-3; the chord itself is exact',
      },
    },
    {
      name: 'oblique chord',
      args: [[0.2, -0.1, 0.3], 1.3, [-2, 0.4, -1], [0.8, 0, 0.6], 0, 10],
    },
  ],
});
