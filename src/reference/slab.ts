// Float64 twin of shaders/slab.wesl: one photon packet of a collimated beam through a
// slab or half-space with HG scattering and Fresnel boundaries (physics.md §7). The
// design (deterministic specular, survival weighting with Russian roulette, Fresnel
// reflect-or-leave by one random number, a fresh free path after a reflection) and the
// order in which random numbers are drawn are the shader's, stated at the top of
// shaders/slab.wesl, so that a seed replays the identical stream here; the arithmetic is
// float64 and written from the physics (positions advanced to the boundary plane by its
// depth, the Fresnel term and the HG sampler from their own twins).
import { fresnelDielectric } from './fresnel.ts';
import { hgSample, type Vec3 } from './phase.ts';
import { rngNextFloat, type RngState } from './rng.ts';
import { FREE_FLIGHT_NEVER, sampleFreeFlight } from './tracking.ts';

/** Same constants as the shader. */
export const SLAB_SEMI_INFINITE_THICKNESS = 1e30;
export const SLAB_MAX_COLLISIONS = 65536;
export const SLAB_ROULETTE_WEIGHT = Math.fround(1e-4);
export const SLAB_ROULETTE_SURVIVAL = Math.fround(0.1);
export const SLAB_EXIT_TOP = 0;
export const SLAB_EXIT_BOTTOM = 1;
export const SLAB_EXIT_ABSORBED = 2;
export const SLAB_EXIT_CAPPED = 3;
export const SLAB_MAX_BINS = 64;
export const SLAB_MAX_DISTANCE = 1e30;

/** Same fields as the WGSL struct SlabSetup. */
export interface SlabSetup {
  sigmaA: number;
  sigmaS: number;
  g: number;
  thickness: number;
  eta: number;
  incidenceCos: number;
  maxCollisions: number;
}

/** Same fields as the WGSL struct PhotonResult. */
export interface PhotonResult {
  exit: number;
  weight: number;
  radius: number;
  collisions: number;
}

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);
/** The shader clamps x and y to ±SLAB_MAX_DISTANCE (far from any profile). */
const clampDistance = (v: number): number => clamp(v, -SLAB_MAX_DISTANCE, SLAB_MAX_DISTANCE);

/** R_sp = F(μ0; η), the part of the beam the top surface reflects (physics.md §7). */
export function slabSpecularReflectance(eta: number, incidenceCos: number): number {
  return fresnelDielectric(incidenceCos, eta);
}

/** Snell's law: sin θt = sin θ0/η, direction (sin θt, 0, cos θt) with z into the medium. */
export function slabEntryDirection(eta: number, incidenceCos: number): Vec3 {
  const cos0 = clamp(incidenceCos, 0, 1);
  const sinT = Math.min(Math.sqrt(1 - cos0 * cos0) / clamp(eta, 0.015625, 64), 1);
  return [sinT, 0, Math.sqrt(1 - sinT * sinT)];
}

/** Distance along the direction to the plane it heads for, or FREE_FLIGHT_NEVER. */
export function slabDistanceToBoundary(z: number, uz: number, thickness: number): number {
  let distance: number;
  if (uz < 0) distance = Math.max(z, 0) / -uz;
  else if (uz > 0 && thickness < SLAB_SEMI_INFINITE_THICKNESS)
    distance = Math.max(thickness - z, 0) / uz;
  else return FREE_FLIGHT_NEVER;
  return Math.min(distance, FREE_FLIGHT_NEVER);
}

/** √(x² + y²) without overflow (Math.hypot scales internally). */
export function slabRadius(x: number, y: number): number {
  // Saturates at the largest f32, as the shader does (|x|, |y| near it gave Inf).
  return Math.min(Math.hypot(x, y), 3.4028234663852886e38);
}

/** One packet (physics.md §7); the expectation of the top weight is R_d, of the bottom weight T_t. */
export function slabPhotonWalk(setup: SlabSetup, state: RngState): PhotonResult {
  const sigmaA = Math.max(setup.sigmaA, 0);
  const sigmaS = Math.max(setup.sigmaS, 0);
  const sigmaT = sigmaA + sigmaS;
  const albedo = sigmaT > 0 ? sigmaS / sigmaT : 0;
  const thickness = Math.max(setup.thickness, 0);
  const eta = clamp(setup.eta, 0.015625, 64);
  const flights = clamp(Math.trunc(setup.maxCollisions), 1, SLAB_MAX_COLLISIONS);
  let [x, y, z] = [0, 0, 0];
  let [ux, uy, uz] = slabEntryDirection(eta, setup.incidenceCos);
  let weight = 1 - slabSpecularReflectance(eta, setup.incidenceCos);
  let collisions = 0;
  const end = (exit: number, w: number): PhotonResult => ({
    exit,
    weight: w,
    radius: slabRadius(x, y),
    collisions,
  });
  for (let flight = 0; flight < flights; flight++) {
    const freePath = sampleFreeFlight(sigmaT, rngNextFloat(state));
    const toBoundary = slabDistanceToBoundary(z, uz, thickness);
    if (freePath >= toBoundary) {
      if (toBoundary >= FREE_FLIGHT_NEVER) return end(SLAB_EXIT_BOTTOM, weight);
      const upwards = uz < 0;
      x = clampDistance(x + toBoundary * ux);
      y = clampDistance(y + toBoundary * uy);
      z = upwards ? 0 : thickness;
      // Leaving the medium: from index η into index 1, relative index 1/η.
      if (rngNextFloat(state) < fresnelDielectric(Math.abs(uz), 1 / eta)) {
        uz = -uz;
        continue;
      }
      return end(upwards ? SLAB_EXIT_TOP : SLAB_EXIT_BOTTOM, weight);
    }
    x = clampDistance(x + freePath * ux);
    y = clampDistance(y + freePath * uy);
    z = clamp(z + freePath * uz, 0, thickness);
    collisions += 1;
    weight *= albedo;
    if (weight <= 0) return end(SLAB_EXIT_ABSORBED, 0);
    if (weight < SLAB_ROULETTE_WEIGHT) {
      if (rngNextFloat(state) >= SLAB_ROULETTE_SURVIVAL) return end(SLAB_EXIT_ABSORBED, 0);
      weight /= SLAB_ROULETTE_SURVIVAL;
    }
    const u0 = rngNextFloat(state);
    const u1 = rngNextFloat(state);
    const wi = hgSample(setup.g, [-ux, -uy, -uz], [u0, u1]).wi;
    const norm = Math.hypot(wi[0], wi[1], wi[2]);
    [ux, uy, uz] = [wi[0] / norm, wi[1] / norm, wi[2] / norm];
  }
  return end(SLAB_EXIT_CAPPED, weight);
}

/** Radial bin: 0 below rMin, log-spaced 1 … bins − 1 up to rMax, bins at or beyond rMax. */
export function slabProfileBin(radius: number, rMin: number, rMax: number, bins: number): number {
  const count = clamp(Math.trunc(bins), 1, SLAB_MAX_BINS);
  if (radius >= rMax) return count;
  if (radius < rMin || count === 1) return 0;
  const position = ((count - 1) * Math.log(radius / rMin)) / Math.log(rMax / rMin);
  return Math.min(1 + Math.floor(Math.max(position, 0)), count - 1);
}

/** Inner edge of bin k (rMax for k ≥ bins). */
export function slabProfileBinEdge(k: number, rMin: number, rMax: number, bins: number): number {
  const count = clamp(Math.trunc(bins), 1, SLAB_MAX_BINS);
  if (k <= 0) return 0;
  if (k >= count) return rMax;
  return rMin * (rMax / rMin) ** ((k - 1) / (count - 1));
}
