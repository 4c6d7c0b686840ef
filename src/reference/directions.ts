// Float64 twin of shaders/directions.wesl: an orthonormal frame completing a unit
// direction (Duff et al. 2017), the direction at a polar angle and azimuth around an
// axis, and uniform directions on the sphere. The conventions (basis orientation,
// azimuth φ = π(2u − 1), the clamps of u) are the shader's, so that a WGSL sample and
// its twin land on the same point.

export type Vec3 = readonly [number, number, number];

export interface OrthonormalBasis {
  tangent: Vec3;
  bitangent: Vec3;
}

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);

/** Duff et al. 2017, "Building an Orthonormal Basis, Revisited", listing 3. */
export function orthonormalBasis(n: Vec3): OrthonormalBasis {
  const [x, y, z] = n;
  const sign = z >= 0 ? 1 : -1;
  const a = -1 / (sign + z);
  const b = x * y * a;
  return {
    tangent: [1 + sign * x * x * a, sign * b, -sign * x],
    bitangent: [b, sign + y * y * a, -y],
  };
}

/** cosθ·axis + sinθ·(cos φ·tangent + sin φ·bitangent), φ = π(2·uPhi − 1). */
export function directionAroundAxis(
  axis: Vec3,
  cosTheta: number,
  sinTheta: number,
  uPhi: number,
): Vec3 {
  // u outside [0, 1] is clamped (the shader's φ would overflow).
  const phi = Math.PI * (2 * clamp(uPhi, 0, 1) - 1);
  const { tangent, bitangent } = orthonormalBasis(axis);
  const c = sinTheta * Math.cos(phi);
  const s = sinTheta * Math.sin(phi);
  return [0, 1, 2].map((k) => c * tangent[k]! + s * bitangent[k]! + cosTheta * axis[k]!) as [
    number,
    number,
    number,
  ];
}

/** z = 1 − 2u.x is uniform on [−1, 1] (Archimedes), φ = π(2u.y − 1); u clamped to [0, 1]². */
export function sampleUniformSphere(u: readonly [number, number]): Vec3 {
  const z = 1 - 2 * clamp(u[0], 0, 1);
  const r = Math.sqrt(Math.max(0, 1 - z * z));
  const phi = Math.PI * (2 * clamp(u[1], 0, 1) - 1);
  return [r * Math.cos(phi), r * Math.sin(phi), z];
}
