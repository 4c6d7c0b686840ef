// Float64 twin of shaders/camera.wesl: camera frames, perspective and orthographic
// cameras, and the ray through a continuous pixel coordinate (row 0 at the top).
import { orthonormalBasis, type Vec3 } from './directions.ts';

export const CAMERA_PERSPECTIVE = 0;
export const CAMERA_ORTHOGRAPHIC = 1;

export interface Camera {
  position: Vec3;
  projection: number;
  forward: Vec3;
  right: Vec3;
  up: Vec3;
  halfExtent: readonly [number, number];
  imageSize: readonly [number, number];
}

export interface Ray {
  origin: Vec3;
  direction: Vec3;
}

const F32_MAX = 3.4028234663852886e38;
// Shorter views are degenerate: f32 flushes such lengths (and their squares) to 0.
const F32_MIN_NORMAL = 1.1754943508222875e-38;
const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];
const length = (a: Vec3): number => Math.hypot(a[0], a[1], a[2]);
const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);

/** [forward, right, up]: orthonormal and right-handed, as cameraFrame in WGSL. */
export function cameraFrame(view: Vec3, upHint: Vec3): [Vec3, Vec3, Vec3] {
  const viewLength = length(view);
  const forward: Vec3 =
    viewLength >= F32_MIN_NORMAL && viewLength <= F32_MAX
      ? [view[0] / viewLength, view[1] / viewLength, view[2] / viewLength]
      : [0, 0, -1];
  const side = cross(forward, upHint);
  const sideLength = length(side);
  const right: Vec3 =
    sideLength >= F32_MIN_NORMAL && sideLength > 1e-6 * length(upHint) && sideLength <= F32_MAX
      ? [side[0] / sideLength, side[1] / sideLength, side[2] / sideLength]
      : orthonormalBasis(forward).tangent;
  return [forward, right, cross(right, forward)];
}

export function cameraPerspective(
  position: Vec3,
  target: Vec3,
  upHint: Vec3,
  fovYDegrees: number,
  width: number,
  height: number,
): Camera {
  const [forward, right, up] = cameraFrame(sub(target, position), upHint);
  const fov = (clamp(fovYDegrees, 1e-3, 179) * Math.PI) / 180;
  const w = Math.max(width, 1);
  const h = Math.max(height, 1);
  const halfHeight = Math.tan(0.5 * fov);
  return {
    position,
    projection: CAMERA_PERSPECTIVE,
    forward,
    right,
    up,
    halfExtent: [(halfHeight * w) / h, halfHeight],
    imageSize: [w, h],
  };
}

export function cameraOrthographic(
  position: Vec3,
  direction: Vec3,
  upHint: Vec3,
  footprintWidth: number,
  footprintHeight: number,
  width: number,
  height: number,
): Camera {
  const [forward, right, up] = cameraFrame(direction, upHint);
  return {
    position,
    projection: CAMERA_ORTHOGRAPHIC,
    forward,
    right,
    up,
    halfExtent: [0.5 * Math.max(footprintWidth, 0), 0.5 * Math.max(footprintHeight, 0)],
    imageSize: [Math.max(width, 1), Math.max(height, 1)],
  };
}

export function cameraPlanePoint(
  camera: Camera,
  pixel: readonly [number, number],
): [number, number] {
  return [
    ((2 * pixel[0]) / camera.imageSize[0] - 1) * camera.halfExtent[0],
    (1 - (2 * pixel[1]) / camera.imageSize[1]) * camera.halfExtent[1],
  ];
}

export function cameraRay(camera: Camera, pixel: readonly [number, number]): Ray {
  const [u, v] = cameraPlanePoint(camera, pixel);
  const offset = add(scale(camera.right, u), scale(camera.up, v));
  if (camera.projection === CAMERA_ORTHOGRAPHIC) {
    return { origin: add(camera.position, offset), direction: camera.forward };
  }
  const d = add(camera.forward, offset);
  return { origin: camera.position, direction: scale(d, 1 / length(d)) };
}

export function orbitCameraPosition(
  target: Vec3,
  distance: number,
  azimuth: number,
  elevation: number,
): Vec3 {
  const e = clamp(elevation, -1.5697963, 1.5697963);
  return add(
    target,
    scale(
      [Math.cos(e) * Math.sin(azimuth), Math.sin(e), Math.cos(e) * Math.cos(azimuth)],
      distance,
    ),
  );
}
