// Float64 twin of shaders/dielectric.wesl: refraction at a smooth dielectric boundary
// (Snell's law in vector form), convention eta = n_t/n_i as in fresnel.ts.
/**
 * Refracted unit direction (Snell: n_i sin θi = n_t sin θt, with the tangential component
 * scaled by 1/η and the normal one set to −cos θt), and 1; under total internal reflection
 * the mirror direction and 0. `incident` travels toward the boundary, `normal` faces it.
 */
export function refractDirection(
  incident: readonly number[],
  normal: readonly number[],
  eta: number,
): [number, number, number, number] {
  const e = Math.min(Math.max(eta, 0.015625), 64);
  const [ix, iy, iz] = [incident[0] ?? 0, incident[1] ?? 0, incident[2] ?? 0];
  const [nx, ny, nz] = [normal[0] ?? 0, normal[1] ?? 0, normal[2] ?? 0];
  const cosI = Math.min(Math.max(-(ix * nx + iy * ny + iz * nz), 0), 1);
  const sinT2 = (1 - cosI * cosI) / (e * e);
  if (sinT2 >= 1) return [ix + 2 * cosI * nx, iy + 2 * cosI * ny, iz + 2 * cosI * nz, 0];
  const cosT = Math.sqrt(1 - sinT2);
  const k = cosI / e - cosT;
  const t: [number, number, number] = [ix / e + k * nx, iy / e + k * ny, iz / e + k * nz];
  const length = Math.hypot(t[0], t[1], t[2]);
  return [t[0] / length, t[1] / length, t[2] / length, 1];
}
