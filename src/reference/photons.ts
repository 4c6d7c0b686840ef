// Float64 twin of shaders/photons.wesl (chapter 10, "Photon mapping and volume
// caustics"): the sun's radiance, cone and samplers, the photon power, the ideal
// dielectric, the uniform-grid cell of a point and the kernel of the volume radiance
// estimate. Written from the formulas; the sampling conventions (which uniform number
// drives which angle, directionAroundAxis's azimuth) are shared so that a WGSL result
// can be compared with a twin that draws the same point.
import { fresnelDielectric } from './fresnel.ts';
import { directionAroundAxis, type Vec3 } from './directions.ts';

const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const normalize = (a: Vec3): Vec3 => {
  const l = Math.hypot(a[0], a[1], a[2]);
  return [a[0] / l, a[1] / l, a[2] / l];
};

/** L = E/(π sin²θmax) (the cone integral of L cos θ is E). */
export function sunRadiance(irradiance: number, sinThetaMax: number): number {
  const s = Math.max(sinThetaMax, 1e-6);
  // E < 0 counts as 0 and the quotient saturates at the largest f32, as in the shader.
  return Math.min(Math.max(irradiance, 0) / (Math.PI * s * s), 3.4028234663852886e38);
}

/** Ω = 2π(1 − cos θmax). */
export function sunConeSolidAngle(sinThetaMax: number): number {
  const s = Math.min(Math.max(sinThetaMax, 0), 1);
  return 2 * Math.PI * (1 - Math.sqrt(1 - s * s));
}

/** Direction with pdf ∝ cos θ in the cone: sin²θ = u.x sin²θmax. */
export function sunConeSampleCosine(
  axis: Vec3,
  sinThetaMax: number,
  u: readonly [number, number],
): Vec3 {
  const sin2 = Math.min(Math.max(u[0], 0), 1) * sinThetaMax * sinThetaMax;
  return directionAroundAxis(axis, Math.sqrt(1 - sin2), Math.sqrt(sin2), u[1]);
}

/** Direction uniform in solid angle in the cone: cos θ = 1 − u.x(1 − cos θmax). */
export function sunConeSampleUniform(
  axis: Vec3,
  sinThetaMax: number,
  u: readonly [number, number],
): Vec3 {
  const s = Math.min(Math.max(sinThetaMax, 0), 1);
  const cosMax = Math.sqrt(1 - s * s);
  const cosTheta = 1 - Math.min(Math.max(u[0], 0), 1) * (1 - cosMax);
  return directionAroundAxis(axis, cosTheta, Math.sqrt(Math.max(0, 1 - cosTheta * cosTheta)), u[1]);
}

/** ΔΦ = E·A/N: N photons carry the disc's flux E·A. */
export function photonPower(irradiance: number, area: number, count: number): number {
  return count === 0 ? 0 : (irradiance * area) / count;
}

/** Fresnel-weighted choice between mirror reflection and Snell refraction. */
export function dielectricScatter(direction: Vec3, normal: Vec3, eta: number, u: number): Vec3 {
  let n = normal;
  let cosI = -dot(direction, n);
  let relative = eta;
  if (cosI < 0) {
    n = [-n[0], -n[1], -n[2]];
    cosI = -cosI;
    relative = 1 / eta;
  }
  const f = fresnelDielectric(cosI, relative);
  if (u < f) {
    return normalize([
      direction[0] + 2 * cosI * n[0],
      direction[1] + 2 * cosI * n[1],
      direction[2] + 2 * cosI * n[2],
    ]);
  }
  const sin2T = (1 - cosI * cosI) / (relative * relative);
  const cosT = Math.sqrt(Math.max(0, 1 - sin2T));
  const k = cosI / relative - cosT;
  return normalize([
    direction[0] / relative + k * n[0],
    direction[1] / relative + k * n[1],
    direction[2] / relative + k * n[2],
  ]);
}

/** ⌊(p − gridMin)/h⌋ per axis, clamped to the grid. */
export function photonCellCoord(
  p: Vec3,
  gridMin: Vec3,
  cellSize: number,
  dims: readonly [number, number, number],
): [number, number, number] {
  return [0, 1, 2].map((k) =>
    Math.min(Math.max(Math.floor((p[k]! - gridMin[k]!) / cellSize), 0), dims[k]! - 1),
  ) as [number, number, number];
}

/** x + nx·(y + ny·z). */
export function photonCellIndex(
  cell: readonly [number, number, number],
  dims: readonly [number, number, number],
): number {
  return cell[0] + dims[0] * (cell[1] + dims[1] * cell[2]);
}

/** 1/((4/3)πr³) inside the gather sphere, 0 outside. */
export function photonKernel(distanceSquared: number, radius: number): number {
  // r² below the smallest normal f32 has no volume, as in the shader (a GPU may flush r² to 0).
  if (!(radius > 0) || radius * radius < 2 ** -126 || !(distanceSquared < radius * radius))
    return 0;
  // Saturates at the largest f32 like the shader (r³ leaves the f32 range below r ≈ 2.3e-13 m).
  return Math.min(3 / (4 * Math.PI * radius ** 3), 3.4028234663852886e38);
}
