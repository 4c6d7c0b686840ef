// WGSL camera module vs its float64 twin: frames, the pixel mapping (row 0 at the
// top, box-filter pixel squares) and rays of perspective and orthographic cameras,
// with the hard cases of a degenerate view and an up hint parallel to the view.
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  cameraFrame,
  cameraOrthographic,
  cameraPerspective,
  cameraRay,
  orbitCameraPosition,
} from '../../src/reference/camera.ts';
import type { Vec3 } from '../../src/reference/phase.ts';

const v3 = (a: readonly number[]): Vec3 => [a[0] ?? NaN, a[1] ?? NaN, a[2] ?? NaN];
const WGSL_V3 = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;

const FRAME_TOLERANCE: Tolerance = {
  absolute: 2e-6,
  reason: 'normalize (inverseSqrt, 2 ULP) and cross products of unit vectors in f32',
};

describeShaderFunction({
  module: 'camera',
  fn: 'cameraFrame',
  args: ['f32[3]', 'f32[3]'],
  result: 'vec4f',
  wrapper: {
    imports: ['cameraFrame'],
    // The right axis and up·forward (0 for an orthonormal frame); the twin's frame
    // properties are checked for all inputs in tests/reference/camera.test.ts.
    wgsl: `fn caseUnderTest(view: array<f32, 3>, up: array<f32, 3>) -> vec4f {
  let f = cameraFrame(${WGSL_V3('view')}, ${WGSL_V3('up')});
  return vec4f(f[1], dot(f[2], f[0]));
}`,
  },
  twin: (view: number[], up: number[]) => {
    const [forward, right, newUp] = cameraFrame(v3(view), v3(up));
    const upDotForward = newUp[0] * forward[0] + newUp[1] * forward[1] + newUp[2] * forward[2];
    return [...right, upDotForward];
  },
  tolerance: FRAME_TOLERANCE,
  cases: [
    {
      name: 'looking down −z with +y up: right = +x',
      args: [
        [0, 0, -5],
        [0, 1, 0],
      ],
      expected: [1, 0, 0, 0],
    },
    {
      name: 'looking along +x: right = +z',
      args: [
        [2, 0, 0],
        [0, 1, 0],
      ],
      expected: [0, 0, 1, 0],
    },
    {
      name: 'oblique view, tilted up hint',
      args: [
        [1, -2, 0.5],
        [0.1, 1, 0.2],
      ],
    },
    {
      name: 'up hint parallel to the view: orthonormalBasis fallback',
      args: [
        [0, 3, 0],
        [0, 1, 0],
      ],
    },
    {
      name: 'zero view: looks down −z',
      args: [
        [0, 0, 0],
        [0, 1, 0],
      ],
      expected: [1, 0, 0, 0],
    },
    {
      name: 'zero up hint: still a frame',
      args: [
        [0, 0, -1],
        [0, 0, 0],
      ],
    },
  ],
});

const perspectiveWrapper = `fn caseUnderTest(p: array<f32, 3>, t: array<f32, 3>, fov: f32, w: f32, h: f32, px: f32, py: f32) -> vec3f {
  let camera = cameraPerspective(${WGSL_V3('p')}, ${WGSL_V3('t')}, vec3f(0.0, 1.0, 0.0), fov, w, h);
  return cameraRay(camera, vec2f(px, py)).direction;
}`;

const TAN_30 = Math.tan(Math.PI / 6);
const unit = (v: Vec3): number[] => {
  const l = Math.hypot(...v);
  return v.map((x) => x / l);
};

describeShaderFunction({
  module: 'camera',
  fn: 'cameraRay',
  args: ['f32[3]', 'f32[3]', 'f32', 'f32', 'f32', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: { imports: ['cameraPerspective', 'cameraRay'], wgsl: perspectiveWrapper },
  twin: (p: number[], t: number[], fov: number, w: number, h: number, px: number, py: number) => [
    ...cameraRay(cameraPerspective(v3(p), v3(t), [0, 1, 0], fov, w, h), [px, py]).direction,
  ],
  // WGSL tan has no stated bound of its own (it inherits sin/cos ÷): SwiftShader's
  // 2^-11 absolute sine error moves tan(30°) by ≤ 1e-3 relative.
  tolerance: { absolute: 1e-3, reason: 'tan(fov/2) from sin/cos with 2^-11 error on SwiftShader' },
  cases: [
    {
      name: 'image centre: the view direction',
      args: [[0, 0, 5], [0, 0, 0], 60, 64, 32, 32, 16],
      expected: [0, 0, -1],
    },
    {
      name: 'top-centre edge (row 0 is the top): up by the half fov',
      args: [[0, 0, 5], [0, 0, 0], 60, 64, 32, 32, 0],
      expected: unit([0, TAN_30, -1]),
    },
    {
      name: 'right edge: right by aspect·tan(fov/2)',
      args: [[0, 0, 5], [0, 0, 0], 60, 64, 32, 64, 16],
      expected: unit([2 * TAN_30, 0, -1]),
    },
    {
      name: 'a pixel centre of an oblique camera',
      args: [[3, 2, 1], [0, 0.5, 0], 40, 100, 80, 10.5, 70.5],
    },
  ],
});

const orthoWrapper = `fn caseUnderTest(p: array<f32, 3>, d: array<f32, 3>, fw: f32, fh: f32, w: f32, h: f32, px: f32, py: f32) -> vec3f {
  let camera = cameraOrthographic(${WGSL_V3('p')}, ${WGSL_V3('d')}, vec3f(0.0, 1.0, 0.0), fw, fh, w, h);
  return cameraRay(camera, vec2f(px, py)).origin;
}`;

describeShaderFunction({
  module: 'camera',
  fn: 'cameraOrthographic',
  args: ['f32[3]', 'f32[3]', 'f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: { imports: ['cameraOrthographic', 'cameraRay'], wgsl: orthoWrapper },
  twin: (
    p: number[],
    d: number[],
    fw: number,
    fh: number,
    w: number,
    h: number,
    px: number,
    py: number,
  ) => [...cameraRay(cameraOrthographic(v3(p), v3(d), [0, 1, 0], fw, fh, w, h), [px, py]).origin],
  tolerance: { absolute: 2e-6, relative: 1e-6, reason: 'a few f32 products and sums' },
  cases: [
    {
      name: 'top-left corner of a 4 m × 2 m footprint on a square image: exact rectangle',
      args: [[0, 0, 5], [0, 0, -1], 4, 2, 64, 64, 0, 0],
      expected: [-2, 1, 5],
    },
    {
      name: 'bottom-right corner',
      args: [[0, 0, 5], [0, 0, -1], 4, 2, 64, 64, 64, 64],
      expected: [2, -1, 5],
    },
    {
      name: 'pixel centre (0.5, 0.5) of an 8 × 8 image',
      args: [[1, 1, 1], [0, 0, -1], 2, 2, 8, 8, 0.5, 0.5],
      expected: [0.125, 1.875, 1],
    },
    {
      name: 'negative footprint clamps to a point',
      args: [[1, 2, 3], [1, 0, 0], -1, -1, 8, 8, 0, 0],
      expected: [1, 2, 3],
    },
  ],
});

describeShaderFunction({
  module: 'camera',
  fn: 'orbitCameraPosition',
  args: ['f32[3]', 'f32', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['orbitCameraPosition'],
    wgsl: `fn caseUnderTest(t: array<f32, 3>, r: f32, a: f32, e: f32) -> vec3f { return orbitCameraPosition(${WGSL_V3('t')}, r, a, e); }`,
  },
  twin: (t: number[], r: number, a: number, e: number) => [...orbitCameraPosition(v3(t), r, a, e)],
  tolerance: {
    absolute: 3e-3,
    reason: 'sin/cos with 2^-11 absolute error on SwiftShader, times r ≤ 3',
  },
  cases: [
    { name: 'azimuth 0, elevation 0: on +z', args: [[0, 0, 0], 3, 0, 0], expected: [0, 0, 3] },
    { name: 'azimuth π/2: on +x', args: [[1, 1, 1], 2, Math.PI / 2, 0], expected: [3, 1, 1] },
    {
      name: 'elevation past the pole is clamped just below it',
      args: [[0, 0, 0], 1, 0, 2],
      expected: [0, Math.sin(1.5697963), Math.cos(1.5697963)],
    },
  ],
});
