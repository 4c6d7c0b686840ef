// Float64 twin of shaders/surfaces.wesl: first hits of rays with planes, spheres and
// boxes, facing normals, the Lambertian BRDF and cosine-weighted sampling. The hit
// functions reuse the geometry twin (segments inside a box or a ball) and pick the
// first crossing in the open interval (tMin, tMax).
import {
  RAY_T_LIMIT,
  planeCrossing,
  rayBoxSegment,
  raySphereSegment,
  type Segment,
} from './geometry.ts';
import { directionAroundAxis, type Vec3 } from './directions.ts';

export const SURFACE_PLANE = 0;
export const SURFACE_SPHERE = 1;
export const SURFACE_BOX = 2;
/** The largest finite f32, as in the shader. */
export const SURFACE_NO_HIT = (2 - 2 ** -23) * 2 ** 127;

/** Same fields as the WGSL struct Surface (without its padding). */
export interface Surface {
  kind: number;
  a: Vec3;
  radius: number;
  b: Vec3;
  albedo: Vec3;
}

const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const normalize = (a: Vec3): Vec3 => {
  const n = Math.hypot(a[0], a[1], a[2]);
  return [a[0] / n, a[1] / n, a[2] / n];
};

export function planeHitDistance(
  point: Vec3,
  normal: Vec3,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): number {
  const slope = dot(normal, direction);
  if (slope === 0) return SURFACE_NO_HIT;
  const t = planeCrossing(dot(normal, sub(point, origin)), slope);
  return t > tMin && t < tMax ? t : SURFACE_NO_HIT;
}

export function firstCrossing(segment: Segment, tMin: number, tMax: number): number {
  const [t0, t1] = segment;
  if (!(t0 <= t1)) return SURFACE_NO_HIT;
  for (const t of [t0, t1]) if (t > tMin && t < tMax) return t;
  return SURFACE_NO_HIT;
}

export function sphereHitDistance(
  center: Vec3,
  radius: number,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): number {
  const segment = raySphereSegment(center, radius, origin, direction, -RAY_T_LIMIT, RAY_T_LIMIT);
  return firstCrossing(segment, tMin, tMax);
}

export function boxHitDistance(
  boxMin: Vec3,
  boxMax: Vec3,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): number {
  const segment = rayBoxSegment(boxMin, boxMax, origin, direction, -RAY_T_LIMIT, RAY_T_LIMIT);
  return firstCrossing(segment, tMin, tMax);
}

export function boxNormal(boxMin: Vec3, boxMax: Vec3, p: Vec3): Vec3 {
  let axis = 0;
  let largest = -1;
  for (let k = 0; k < 3; k++) {
    const half = 0.5 * (boxMax[k]! - boxMin[k]!);
    const offset = Math.abs(p[k]! - 0.5 * (boxMin[k]! + boxMax[k]!));
    const q = half > 0 ? offset / half : 1e30;
    if (q > largest) {
      largest = q;
      axis = k;
    }
  }
  const normal: [number, number, number] = [0, 0, 0];
  normal[axis] = p[axis]! >= 0.5 * (boxMin[axis]! + boxMax[axis]!) ? 1 : -1;
  return normal;
}

export function surfaceHitDistance(
  surface: Surface,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): number {
  if (surface.kind === SURFACE_SPHERE)
    return sphereHitDistance(surface.a, surface.radius, origin, direction, tMin, tMax);
  if (surface.kind === SURFACE_BOX)
    return boxHitDistance(surface.a, surface.b, origin, direction, tMin, tMax);
  return planeHitDistance(surface.a, surface.b, origin, direction, tMin, tMax);
}

export function surfaceNormalFacing(surface: Surface, p: Vec3, direction: Vec3): Vec3 {
  const normal =
    surface.kind === SURFACE_SPHERE
      ? normalize(sub(p, surface.a))
      : surface.kind === SURFACE_BOX
        ? boxNormal(surface.a, surface.b, p)
        : normalize(surface.b);
  return dot(normal, direction) > 0 ? [-normal[0], -normal[1], -normal[2]] : normal;
}

export function lambertianBrdf(albedo: Vec3): Vec3 {
  return albedo.map((a) => Math.min(Math.max(a, 0), 1) / Math.PI) as unknown as Vec3;
}

/** Malley: a uniform point of the unit disk lifted to the hemisphere has pdf cos θ/π. */
export function sampleCosineHemisphere(normal: Vec3, u: readonly [number, number]): Vec3 {
  const x = Math.min(Math.max(u[0], 0), 1);
  return directionAroundAxis(normal, Math.sqrt(1 - x), Math.sqrt(x), u[1]);
}

export function surfaceOffsetOrigin(p: Vec3, normal: Vec3): Vec3 {
  const epsilon = 1e-4 * Math.max(1, Math.abs(p[0]), Math.abs(p[1]), Math.abs(p[2]));
  return [p[0] + epsilon * normal[0], p[1] + epsilon * normal[1], p[2] + epsilon * normal[2]];
}
