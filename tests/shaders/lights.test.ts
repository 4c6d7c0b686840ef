// WGSL lights module vs its float64 twin (src/reference/lights.ts): the spot falloff's
// smoothstep and its hard cone, and what a point receives from a directional, point and
// spot light (direction toward the light, distance, irradiance perpendicular to it).
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  LIGHT_DISTANCE_INFINITE,
  lightSampleDirectional,
  lightSamplePoint,
  lightSampleSpot,
  spotFalloff,
  type Light,
} from '../../src/reference/lights.ts';
import type { Vec3 } from '../../src/reference/phase.ts';

const v3 = (a: readonly number[]): Vec3 => [a[0] ?? NaN, a[1] ?? NaN, a[2] ?? NaN];
const V3 = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;
const light = (
  kind: number,
  position: number[],
  direction: number[],
  value: number[],
  cosOuter = 0,
  cosInner = 0,
): Light => ({
  kind,
  cosOuter,
  cosInner,
  position: v3(position),
  direction: v3(direction),
  value: v3(value),
});

const ARITHMETIC: Tolerance = {
  relative: 2e-6,
  absolute: 1e-7,
  reason: 'a few f32 products, a division and sqrt (2.5 ULP each)',
};

describeShaderFunction({
  module: 'lights',
  fn: 'spotFalloff',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: spotFalloff,
  tolerance: {
    relative: 1e-5,
    absolute: 1e-6,
    reason: 'one f32 division of a difference of cosines',
  },
  cases: [
    { name: 'inside the inner cone: 1', args: [0.99, 0.8, 0.9], expected: 1 },
    { name: 'outside the outer cone: 0', args: [0.5, 0.8, 0.9], expected: 0 },
    { name: 'half way: smoothstep(½) = ½', args: [0.85, 0.8, 0.9], expected: 0.5 },
    { name: 'a quarter of the way: 0.15625', args: [0.825, 0.8, 0.9], expected: 0.15625 },
    {
      name: 'hard edge (equal cones), inside: 1 without dividing by 0',
      args: [0.9, 0.9, 0.9],
      expected: 1,
    },
    { name: 'hard edge (equal cones), outside: 0', args: [0.89, 0.9, 0.9], expected: 0 },
  ],
});

// Each light sample packed as (direction, distance) and (irradiance, 0) in two vec4f; the
// harness returns one vec4f, so each light kind has two tables: geometry and irradiance.
const sampleWrapper = (fn: string, withPoint: boolean, part: 'geometry' | 'irradiance') => ({
  imports: [fn, 'Light'],
  wgsl: `fn caseUnderTest(kind: u32, position: array<f32, 3>, direction: array<f32, 3>, value: array<f32, 3>, cones: array<f32, 2>, p: array<f32, 3>) -> vec4f {
  let light = Light(kind, cones[0], cones[1], 0.0, ${V3('position')}, 0.0, ${V3('direction')}, 0.0, ${V3('value')}, 0.0);
  let s = ${fn}(light${withPoint ? `, ${V3('p')}` : ''});
  return ${part === 'geometry' ? 'vec4f(s.direction, s.distance)' : 'vec4f(s.irradiance, 0.0)'};
}`,
});
type SampleFn = (light: Light, p: Vec3) => { direction: Vec3; distance: number; irradiance: Vec3 };
const sampleTwin =
  (fn: SampleFn, part: 'geometry' | 'irradiance') =>
  (
    kind: number,
    position: number[],
    direction: number[],
    value: number[],
    cones: number[],
    p: number[],
  ) => {
    const s = fn(light(kind, position, direction, value, cones[0], cones[1]), v3(p));
    return part === 'geometry' ? [...s.direction, s.distance] : [...s.irradiance, 0];
  };
const ARGS = ['u32', 'f32[3]', 'f32[3]', 'f32[3]', 'f32[2]', 'f32[3]'] as const;

for (const part of ['geometry', 'irradiance'] as const) {
  describeShaderFunction({
    module: 'lights',
    fn: 'lightSampleDirectional',
    args: ARGS,
    result: 'vec4f',
    wrapper: sampleWrapper('lightSampleDirectional', false, part),
    twin: sampleTwin((l) => lightSampleDirectional(l), part),
    tolerance: ARITHMETIC,
    cases: [
      {
        name: `${part}: toward where the beam comes from, at infinity, E unchanged`,
        args: [0, [0, 0, 0], [0, -1, 0], [1, 2, 3], [0, 0], [5, 5, 5]],
        expected: part === 'geometry' ? [0, 1, 0, LIGHT_DISTANCE_INFINITE] : [1, 2, 3, 0],
      },
      {
        name: `${part}: negative channels count as 0`,
        args: [0, [0, 0, 0], [0.6, 0, -0.8], [-1, 2, 0], [0, 0], [0, 0, 0]],
        expected: part === 'geometry' ? [-0.6, 0, 0.8, LIGHT_DISTANCE_INFINITE] : [0, 2, 0, 0],
      },
    ],
  });

  describeShaderFunction({
    module: 'lights',
    fn: 'lightSamplePoint',
    args: ARGS,
    result: 'vec4f',
    wrapper: sampleWrapper('lightSamplePoint', true, part),
    twin: sampleTwin(lightSamplePoint, part),
    tolerance: ARITHMETIC,
    cases: [
      {
        name: `${part}: I/r² at r = 2`,
        args: [1, [0, 2, 0], [0, 0, 1], [4, 8, 12], [0, 0], [0, 0, 0]],
        expected: part === 'geometry' ? [0, 1, 0, 2] : [1, 2, 3, 0],
      },
      {
        name: `${part}: oblique, r = 5`,
        args: [1, [3, 4, 0], [0, 0, 1], [25, 50, 75], [0, 0], [0, 0, 0]],
        expected: part === 'geometry' ? [0.6, 0.8, 0, 5] : [1, 2, 3, 0],
      },
      {
        name: `${part}: closer than 1e-6 m receives nothing (no overflow)`,
        args: [1, [0, 0, 1e-7], [0, 0, 1], [1, 1, 1], [0, 0], [0, 0, 0]],
        expected: part === 'geometry' ? [0, 0, 1, 0] : [0, 0, 0, 0],
      },
    ],
  });

  const cos20 = Math.cos((20 * Math.PI) / 180);
  const cos10 = Math.cos((10 * Math.PI) / 180);
  describeShaderFunction({
    module: 'lights',
    fn: 'lightSampleSpot',
    args: ARGS,
    result: 'vec4f',
    wrapper: sampleWrapper('lightSampleSpot', true, part),
    twin: sampleTwin(lightSampleSpot, part),
    tolerance: {
      ...ARITHMETIC,
      absolute: 2e-6,
      reason: `${ARITHMETIC.reason}; the falloff's division`,
    },
    cases: [
      {
        name: `${part}: on the axis, full intensity`,
        args: [2, [0, 3, 0], [0, -1, 0], [9, 9, 9], [cos20, cos10], [0, 0, 0]],
        expected: part === 'geometry' ? [0, 1, 0, 3] : [1, 1, 1, 0],
      },
      {
        name: `${part}: 15° off the axis, inside the falloff`,
        args: [
          2,
          [0, 1, 0],
          [0, -1, 0],
          [1, 1, 1],
          [cos20, cos10],
          [Math.tan((15 * Math.PI) / 180), 0, 0],
        ],
      },
      {
        name: `${part}: behind the spot: nothing`,
        args: [2, [0, 1, 0], [0, -1, 0], [1, 1, 1], [cos20, cos10], [0, 2, 0]],
        ...(part === 'irradiance' ? { expected: [0, 0, 0, 0] } : {}),
      },
    ],
  });
}
