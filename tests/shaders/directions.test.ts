// WGSL directions module vs its float64 twin: the orthonormal basis of Duff et al. 2017,
// directions around an axis and uniform directions on the sphere (moved from phase.wesl,
// whose samplers build on them; tolerances from tests/support/phaseHarness.ts).
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  directionAroundAxis,
  orthonormalBasis,
  sampleUniformSphere,
  type Vec3,
} from '../../src/reference/directions.ts';
import { ONE_MINUS_EPSILON_F32 } from '../support/f32.ts';
import { asVec3, AZIMUTH_FREE, TRIG_DIRECTION, vec } from '../support/phaseHarness.ts';

const normalize = (v: readonly number[]): Vec3 => {
  const length = Math.hypot(v[0] ?? 0, v[1] ?? 0, v[2] ?? 0);
  return [(v[0] ?? 0) / length, (v[1] ?? 0) / length, (v[2] ?? 0) / length];
};
const OBLIQUE_WO = normalize([0.3, -0.5, 0.81]);
const OBLIQUE_WI = normalize([-0.6, 0.2, 0.77]);

// ---------------------------------------------------------------------------
// Frames and uniform directions
// ---------------------------------------------------------------------------
const BASIS_NORMALS: readonly Vec3[] = [
  [0, 0, 1],
  [0, 0, -1],
  [1, 0, 0],
  [0, 1, 0],
  OBLIQUE_WO,
  OBLIQUE_WI,
  normalize([1e-4, 1e-4, -1]),
  normalize([1, 1e-6, -1e-6]),
];
// Duff et al. 2017: each component is a few products and one 2.5-ULP division
// of O(1) numbers.
const BASIS: Tolerance = {
  absolute: 1e-6,
  reason: 'O(1) products and one WGSL division: ≤ 8 ULP of 1',
};
for (const field of ['tangent', 'bitangent'] as const) {
  describeShaderFunction({
    module: 'directions',
    fn: 'orthonormalBasis',
    args: ['f32[3]'],
    result: 'vec3f',
    wrapper: {
      imports: ['orthonormalBasis'],
      wgsl: `fn caseUnderTest(n: array<f32, 3>) -> vec3f { return orthonormalBasis(${vec('n')}).${field}; }`,
    },
    twin: (n: readonly number[]) => orthonormalBasis(asVec3(n))[field],
    tolerance: BASIS,
    cases: BASIS_NORMALS.map((n, k) => ({
      name: `${field} of normal #${k} (${n.map((c) => c.toFixed(3)).join(', ')})`,
      args: [n],
    })),
  });
}

describeShaderFunction({
  module: 'directions',
  fn: 'directionAroundAxis',
  args: ['f32[3]', 'f32', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['directionAroundAxis'],
    wgsl: `fn caseUnderTest(axis: array<f32, 3>, cosTheta: f32, sinTheta: f32, uPhi: f32) -> vec3f {
  return directionAroundAxis(${vec('axis')}, cosTheta, sinTheta, uPhi);
}`,
  },
  twin: (axis: readonly number[], cosTheta: number, sinTheta: number, uPhi: number) =>
    directionAroundAxis(asVec3(axis), cosTheta, sinTheta, uPhi),
  tolerance: TRIG_DIRECTION,
  cases: [
    { name: 'θ = 0 returns the axis', args: [OBLIQUE_WO, 1, 0, 0.3], expected: OBLIQUE_WO },
    { name: 'θ = π returns −axis', args: [[0, 0, 1], -1, 0, 0.8], expected: [0, 0, -1] },
    {
      name: 'θ = π/2, uPhi = ½ (φ = 0) is the tangent',
      args: [[0, 0, 1], 0, 1, 0.5],
      expected: [1, 0, 0],
    },
    { name: 'oblique axis, θ = 60°', args: [OBLIQUE_WO, 0.5, Math.sqrt(0.75), 0.1] },
    { name: 'axis −z, θ = 30°, uPhi = 0 (φ = −π)', args: [[0, 0, -1], Math.sqrt(0.75), 0.5, 0] },
  ],
});

describeShaderFunction({
  module: 'directions',
  fn: 'sampleUniformSphere',
  args: ['f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['sampleUniformSphere'],
    wgsl: 'fn caseUnderTest(u0: f32, u1: f32) -> vec3f { return sampleUniformSphere(vec2f(u0, u1)); }',
  },
  twin: (u0: number, u1: number) => sampleUniformSphere([u0, u1]),
  tolerance: TRIG_DIRECTION,
  cases: [
    { name: 'u.x = 0 is the north pole', args: [0, 0.3], expected: [0, 0, 1] },
    { name: 'u.x = ½, u.y = ½ is +x on the equator', args: [0.5, 0.5], expected: [1, 0, 0] },
    { name: 'u.x = 1 − 2^-24 is next to the south pole', args: [ONE_MINUS_EPSILON_F32, 0.7] },
    { name: 'u.x = 2^-24 is next to the north pole', args: [2 ** -24, 0.1] },
    { name: 'u = (0.3, 0.8)', args: [0.3, 0.8] },
    { name: 'u = (0.9, 0.05)', args: [0.9, 0.05] },
  ],
});

describeShaderFunction({
  module: 'directions',
  fn: 'sampleUniformSphere',
  args: ['f32', 'f32'],
  result: 'vec2f',
  wrapper: {
    imports: ['sampleUniformSphere'],
    wgsl: `fn caseUnderTest(u0: f32, u1: f32) -> vec2f {
  let w = sampleUniformSphere(vec2f(u0, u1));
  return vec2f(w.z, dot(w, w));
}`,
  },
  twin: (u0: number, u1: number) => {
    const w = sampleUniformSphere([u0, u1]);
    return [w[2], w[0] ** 2 + w[1] ** 2 + w[2] ** 2];
  },
  tolerance: AZIMUTH_FREE,
  cases: [0, 2 ** -24, 0.25, 0.5, 0.6, ONE_MINUS_EPSILON_F32].map((u0) => ({
    name: `z = 1 − 2u.x and unit length at u.x = ${u0}`,
    args: [u0, 0.37],
  })),
});
