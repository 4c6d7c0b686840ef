// WGSL room module (shaders/room.wesl, chapter 12's Cornell-box-like room) vs its float64
// twin src/reference/room.ts: where a ray leaves the room, the faces' normals and albedos,
// points of the ceiling emitter and the geometry term of a connection to it.
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  roomWallAlbedo,
  roomWallHit,
  roomWallNormal,
  squareLightGeometry,
  squareLightPoint,
} from '../../src/reference/room.ts';

const vec = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;

// One subtraction and one division per axis: a few f32 ULPs of h; the face index is exact.
const HIT: Tolerance = { relative: 2e-6, absolute: 1e-6, reason: 'one division (≤ 2.5 ULP)' };

describeShaderFunction({
  module: 'room',
  fn: 'roomWallHit',
  args: ['f32', 'f32[3]', 'f32[3]'],
  result: 'vec2f',
  wrapper: {
    imports: ['roomWallHit'],
    wgsl: `fn caseUnderTest(h: f32, o: array<f32, 3>, d: array<f32, 3>) -> vec2f {
  return roomWallHit(h, ${vec('o')}, ${vec('d')});
}`,
  },
  twin: (h: number, o: number[], d: number[]) => roomWallHit(h, o, d),
  tolerance: HIT,
  cases: [
    {
      name: 'straight down from the centre: the floor',
      args: [1, [0, 0, 0], [0, -1, 0]],
      expected: [1, 0],
    },
    { name: 'straight up: the ceiling', args: [2, [0, 0.5, 0], [0, 1, 0]], expected: [1.5, 1] },
    { name: 'toward the back', args: [1, [0, 0, 0.5], [0, 0, -1]], expected: [1.5, 2] },
    {
      name: 'toward −x: the left (red) wall',
      args: [1, [0.25, 0, 0], [-1, 0, 0]],
      expected: [1.25, 3],
    },
    {
      name: 'toward +x: the right (green) wall',
      args: [1, [0, 0, 0], [1, 0, 0]],
      expected: [1, 4],
    },
    { name: 'out through the open front', args: [1, [0, 0, 0], [0, 0, 1]], expected: [1, 5] },
    { name: 'oblique: the nearest face wins', args: [3, [1, -2, 0.5], [0.6, -0.48, -0.64]] },
    {
      name: 'origin on the floor leaving through it: t = 0',
      args: [1, [0.2, -1, 0], [0, -1, 0]],
      expected: [0, 0],
    },
    {
      name: 'zero direction: the sentinel',
      args: [1, [0, 0, 0], [0, 0, 0]],
      expected: [3.4e38, 5],
    },
  ],
});

describeShaderFunction({
  module: 'room',
  fn: 'roomWallNormal',
  args: ['u32'],
  result: 'vec3f',
  twin: (face: number) => roomWallNormal(face),
  tolerance: { absolute: 0, reason: 'exact constants' },
  cases: [0, 1, 2, 3, 4, 5, 6].map((face) => ({ name: `face ${face}`, args: [face] })),
});

describeShaderFunction({
  module: 'room',
  fn: 'roomWallAlbedo',
  args: ['u32', 'u32'],
  result: 'vec3f',
  twin: (face: number, walls: number) => roomWallAlbedo(face, walls),
  tolerance: { relative: 1e-7, absolute: 0, reason: 'f32 constants' },
  cases: [
    { name: 'Cornell: left is red', args: [3, 0], expected: [0.63, 0.065, 0.05] },
    { name: 'Cornell: right is green', args: [4, 0], expected: [0.14, 0.45, 0.091] },
    { name: 'Cornell: floor is white', args: [0, 0], expected: [0.725, 0.725, 0.725] },
    { name: 'white: left is white', args: [3, 1], expected: [0.725, 0.725, 0.725] },
    { name: 'black: everything is black', args: [2, 2], expected: [0, 0, 0] },
    { name: 'the open front is black', args: [5, 0], expected: [0, 0, 0] },
  ],
});

describeShaderFunction({
  module: 'room',
  fn: 'squareLightPoint',
  args: ['f32', 'f32', 'f32[2]'],
  result: 'vec3f',
  wrapper: {
    imports: ['squareLightPoint'],
    wgsl: `fn caseUnderTest(h: f32, a: f32, u: array<f32, 2>) -> vec3f {
  return squareLightPoint(h, a, vec2f(u[0], u[1]));
}`,
  },
  twin: (h: number, a: number, u: number[]) => squareLightPoint(h, a, [u[0]!, u[1]!]),
  tolerance: { relative: 1e-6, absolute: 1e-7, reason: 'two flops' },
  cases: [
    { name: 'the centre', args: [2, 0.5, [0.5, 0.5]], expected: [0, 2, 0] },
    { name: 'a corner', args: [2, 0.5, [0, 0]], expected: [-0.5, 2, -0.5] },
    { name: 'a generic point', args: [7.5, 2.25, [0.1234, 0.9876]] },
  ],
});

// One rsqrt (≤ 2 ULP... WGSL allows 2 ULP) times three products.
const GEOMETRY: Tolerance = { relative: 2e-6, absolute: 1e-12, reason: 'inverseSqrt and products' };

describeShaderFunction({
  module: 'room',
  fn: 'squareLightGeometry',
  args: ['f32[3]', 'f32[3]', 'f32[3]'],
  result: 'f32',
  wrapper: {
    imports: ['squareLightGeometry'],
    wgsl: `fn caseUnderTest(p: array<f32, 3>, n: array<f32, 3>, y: array<f32, 3>) -> f32 {
  return squareLightGeometry(${vec('p')}, ${vec('n')}, ${vec('y')});
}`,
  },
  twin: (p: number[], n: number[], y: number[]) => squareLightGeometry(p, n, y),
  tolerance: GEOMETRY,
  cases: [
    {
      name: 'straight below at distance 2: 1/4',
      args: [
        [0, 0, 0],
        [0, 1, 0],
        [0, 2, 0],
      ],
      expected: 0.25,
    },
    {
      name: 'oblique from a wall',
      args: [
        [-2.5, 0.3, 1],
        [1, 0, 0],
        [0.4, 2.5, -0.2],
      ],
    },
    {
      name: 'behind the surface: 0',
      args: [
        [0, 0, 0],
        [0, -1, 0],
        [0, 2, 0],
      ],
      expected: 0,
    },
    {
      name: 'above the emitter: 0',
      args: [
        [0, 3, 0],
        [0, 1, 0],
        [0, 2, 0],
      ],
      expected: 0,
    },
    {
      name: 'on the emitter point: 0',
      args: [
        [0, 2, 0],
        [0, 1, 0],
        [0, 2, 0],
      ],
      expected: 0,
    },
  ],
});
