// Float64 twin of shaders/geometry.wesl: ray segments inside a box and a sphere,
// with the same clamps and the same "empty" convention [1, 0].
import { FINITE_LIMIT } from './transmittance.ts';
import type { Vec3 } from './phase.ts';

export const RAY_T_LIMIT = 1e17;
export type Segment = readonly [number, number];
const EMPTY: Segment = [1, 0];

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);
const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

export function segmentIsEmpty(segment: Segment): boolean {
  return !(segment[0] <= segment[1]);
}

/** offset/slope clamped to ±FINITE_LIMIT (float64 never overflows here; WGSL tests first). */
export function planeCrossing(offset: number, slope: number): number {
  return clamp(offset / slope, -FINITE_LIMIT, FINITE_LIMIT);
}

/** planeCrossing per component (geometry.wesl planeCrossings, rayBoxSegment's slabs as vectors). */
export function planeCrossings(offset: Vec3, slope: Vec3): Vec3 {
  return [
    planeCrossing(offset[0], slope[0]),
    planeCrossing(offset[1], slope[1]),
    planeCrossing(offset[2], slope[2]),
  ];
}

export function rayBoxSegment(
  boxMin: Vec3,
  boxMax: Vec3,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): Segment {
  if (!(boxMin[0] <= boxMax[0] && boxMin[1] <= boxMax[1] && boxMin[2] <= boxMax[2])) return EMPTY;
  let t0 = clamp(tMin, -RAY_T_LIMIT, RAY_T_LIMIT);
  let t1 = clamp(tMax, -RAY_T_LIMIT, RAY_T_LIMIT);
  for (let axis = 0; axis < 3; axis++) {
    const lo = boxMin[axis] as number;
    const hi = boxMax[axis] as number;
    const o = origin[axis] as number;
    const d = direction[axis] as number;
    if (d === 0) {
      if (o < lo || o > hi) return EMPTY;
    } else {
      const ta = planeCrossing(lo - o, d);
      const tb = planeCrossing(hi - o, d);
      t0 = Math.max(t0, Math.min(ta, tb));
      t1 = Math.min(t1, Math.max(ta, tb));
    }
  }
  return t0 <= t1 ? [t0, t1] : EMPTY;
}

/**
 * Where a ray from a point of the closed box leaves it, at most tMax (geometry.wesl
 * rayBoxExit): the nearest crossing of a face the ray moves toward; axes with d = 0 never
 * bind; never negative.
 */
export function rayBoxExit(
  boxMin: Vec3,
  boxMax: Vec3,
  origin: Vec3,
  direction: Vec3,
  tMax: number,
): number {
  let t = Math.min(tMax, RAY_T_LIMIT);
  for (let axis = 0; axis < 3; axis++) {
    const d = direction[axis] as number;
    if (d === 0) continue;
    const face = (d > 0 ? boxMax[axis] : boxMin[axis]) as number;
    t = Math.min(t, planeCrossing(face - (origin[axis] as number), d));
  }
  return Math.max(t, 0);
}

export function raySphereSegment(
  center: Vec3,
  radius: number,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): Segment {
  if (!(radius > 0)) return EMPTY;
  const f: Vec3 = [origin[0] - center[0], origin[1] - center[1], origin[2] - center[2]];
  const b = -dot(f, direction);
  const closest: Vec3 = [f[0] + b * direction[0], f[1] + b * direction[1], f[2] + b * direction[2]];
  const discriminant = radius * radius - dot(closest, closest);
  if (discriminant < 0) return EMPTY;
  const c = dot(f, f) - radius * radius;
  const q = b + (b >= 0 ? 1 : -1) * Math.sqrt(discriminant);
  let near = 0;
  let far = 0;
  if (q !== 0) {
    const ta = c / q;
    near = Math.min(ta, q);
    far = Math.max(ta, q);
  }
  const t0 = Math.max(clamp(tMin, -RAY_T_LIMIT, RAY_T_LIMIT), near);
  const t1 = Math.min(clamp(tMax, -RAY_T_LIMIT, RAY_T_LIMIT), far);
  return t0 <= t1 ? [t0, t1] : EMPTY;
}
