// Float64 twin of shaders/bssrdf.wesl: the per-sample and per-node arithmetic of Jensen &
// Buhler 2002's two-pass hierarchical integration (irradiance samples on a sphere, the
// octree refinement criterion, the exitant-radiance factor). Written from the formulas
// (physics.md §6.1; chapter 11 "From a profile to a picture").
import { fresnelDielectric, fresnelDiffuseReflectanceExternal } from './fresnel.ts';

type Vec3 = readonly [number, number, number];

const GOLDEN_ANGLE = Math.PI * (3 - Math.sqrt(5));

/** Fibonacci-lattice point i of n on the unit sphere: z = 1 − (2i+1)/n, φ = i·π(3 − √5). */
export function fibonacciSpherePoint(index: number, count: number): [number, number, number] {
  const n = Math.max(count, 1);
  const z = 1 - (2 * index + 1) / n;
  const phi = (index * GOLDEN_ANGLE) % (2 * Math.PI);
  const rho = Math.sqrt(Math.max(0, (1 - z) * (1 + z)));
  return [rho * Math.cos(phi), rho * Math.sin(phi), z];
}

/** Transmitted irradiance per unit beam irradiance: max(0, n·l)·(1 − F_r(n·l, η)). */
export function irradianceSample(normal: Vec3, toLight: Vec3, eta: number): number {
  const c = normal[0] * toLight[0] + normal[1] * toLight[1] + normal[2] * toLight[2];
  if (c <= 0) return 0;
  return c * (1 - fresnelDielectric(Math.min(c, 1), eta));
}

/** Jensen–Buhler criterion: use the node whole when ΔA/‖x − p̄‖² < ε and x is outside its box. */
export function gatherAcceptsNode(
  area: number,
  centroid: Vec3,
  boxMin: Vec3,
  boxMax: Vec3,
  x: Vec3,
  epsilon: number,
): boolean {
  const inside = x.every((v, k) => v >= boxMin[k]! && v <= boxMax[k]!);
  if (inside) return false;
  const d2 = (x[0] - centroid[0]) ** 2 + (x[1] - centroid[1]) ** 2 + (x[2] - centroid[2]) ** 2;
  return area < epsilon * d2;
}

/** L_o / M_o = (1 − F_r(cos θo, η)) / (π (1 − F_dr^ext(η))), so that ∫ L_o cos θ dω = M_o. */
export function bssrdfExitFactor(cosO: number, eta: number): number {
  if (cosO <= 0) return 0;
  const external = fresnelDiffuseReflectanceExternal(eta);
  return (1 - fresnelDielectric(Math.min(cosO, 1), eta)) / (Math.PI * (1 - external));
}
