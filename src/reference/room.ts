// Float64 twin of shaders/room.wesl: the Cornell-box-like room of chapter 12's translucent
// sphere (faces 0 floor, 1 ceiling, 2 back, 3 left, 4 right, 5 open front; a square emitter
// of half-side a in the ceiling, facing down). Written from the geometry, not the shader.
export type Vec3 = [number, number, number];

/** The face names, in index order. */
export const ROOM_FACES = ['floor', 'ceiling', 'back', 'left', 'right', 'front'] as const;

/**
 * (t, face): where the ray from `origin` (inside the cube [−h, h]³) leaves it. Each axis with
 * a nonzero direction component offers the plane it moves toward; the nearest wins.
 */
export function roomWallHit(
  halfSize: number,
  origin: readonly number[],
  direction: readonly number[],
): [number, number] {
  // Axis order y, z, x decides ties (an edge) the same way as the shader.
  const axes: [number, number, number][] = [
    [1, 0, 1],
    [2, 2, 5],
    [0, 3, 4],
  ];
  let best = 3.4e38;
  let face = 5;
  for (const [k, negative, positive] of axes) {
    const d = direction[k]!;
    if (d === 0) continue;
    const plane = d > 0 ? halfSize : -halfSize;
    const t = (plane - origin[k]!) / d;
    if (t < best) {
      best = t;
      face = d > 0 ? positive : negative;
    }
  }
  return [Math.max(best, 0), face];
}

/** Inward unit normal of a face (the front gets −z); out of range: zero. */
export function roomWallNormal(face: number): Vec3 {
  const normals: Vec3[] = [
    [0, 1, 0],
    [0, -1, 0],
    [0, 0, 1],
    [1, 0, 0],
    [-1, 0, 0],
    [0, 0, -1],
  ];
  return normals[face] ?? [0, 0, 0];
}

/** Cornell colours (walls 0), all white (1), all black (2); the front is black. */
export function roomWallAlbedo(face: number, walls: number): Vec3 {
  if (face > 4 || walls >= 2) return [0, 0, 0];
  if (walls === 0 && face === 3) return [0.63, 0.065, 0.05];
  if (walls === 0 && face === 4) return [0.14, 0.45, 0.091];
  return [0.725, 0.725, 0.725];
}

/** A uniform point of the ceiling emitter |x|, |z| ≤ a at y = h. */
export function squareLightPoint(
  halfSize: number,
  lightHalf: number,
  u: readonly [number, number],
): Vec3 {
  return [lightHalf * (2 * u[0] - 1), halfSize, lightHalf * (2 * u[1] - 1)];
}

/** cos θ_p cos θ_light / d² of the connection p → y (the emitter faces −y). */
export function squareLightGeometry(
  p: readonly number[],
  normal: readonly number[],
  lightPoint: readonly number[],
): number {
  const w = [lightPoint[0]! - p[0]!, lightPoint[1]! - p[1]!, lightPoint[2]! - p[2]!];
  const d2 = w[0]! ** 2 + w[1]! ** 2 + w[2]! ** 2;
  if (!(d2 > 0)) return 0;
  const d = Math.sqrt(d2);
  const cosP = Math.max(0, (normal[0]! * w[0]! + normal[1]! * w[1]! + normal[2]! * w[2]!) / d);
  const cosL = Math.max(0, w[1]! / d);
  return (cosP * cosL) / d2;
}
