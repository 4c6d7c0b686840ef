// The scene of <sb-translucent-room> (chapter 12): a translucent sphere of a measured material
// (Jensen et al. 2001, per mm) resting on the floor of the Cornell-box-like room of
// shaders/room.wesl, lit by the square emitter in its ceiling, seen through the open front by a
// pinhole camera. Here: the scene and its parameter block, the sphere-pixel mask the errors are
// measured over, and the float64 twins of the two kernels, shaders/kernels/translucent-room-
// path.wesl (the volumetric path-traced reference) and translucent-room-dipole.wesl (pass 1:
// irradiance samples by path tracing the room; pass 2: the picture with the dipole BSSRDF
// summed over them). The twins draw their own random numbers from the same PCG streams but do
// not replay the shader's f32 paths; tests compare them statistically.
import { bssrdfExitFactor, fibonacciSpherePoint } from '../reference/bssrdf.ts';
import { refractDirection } from '../reference/dielectric.ts';
import { dipoleParameters, dipoleProfile, type DipoleParameters } from '../reference/dipole.ts';
import { sampleUniformSphere } from '../reference/directions.ts';
import { fresnelDielectric } from '../reference/fresnel.ts';
import { raySphereSegment, segmentIsEmpty } from '../reference/geometry.ts';
import { pcgHash, rngNextFloat, rngSeed, type RngState } from '../reference/rng.ts';
import {
  roomWallAlbedo,
  roomWallHit,
  roomWallNormal,
  squareLightGeometry,
  squareLightPoint,
  type Vec3,
} from '../reference/room.ts';
import { sampleCosineHemisphere } from '../reference/surfaces.ts';
import { packStruct } from '../gpu/layout.ts';
import { translucentRoomPathKernel } from '../gpu/layouts.generated.ts';
import type { SubsurfaceMaterial } from './materials.ts';

export interface RoomScene {
  /** Image side in pixels. */
  size: number;
  /** Sphere radius R (mm); the room's half-side is ROOM_SCALE · R. */
  radius: number;
  halfSize: number;
  sigmaSPrime: readonly [number, number, number];
  sigmaA: readonly [number, number, number];
  eta: number;
  /** 0 Cornell colours, 1 white, 2 black (roomWallAlbedo). */
  walls: number;
  /** Half-side a of the ceiling emitter (mm). */
  lightHalf: number;
  /** Emitted radiance L_e of the emitter. */
  emission: number;
}

/** The room is this many sphere radii across, half-side: the sphere fills 40 % of its width. */
export const ROOM_SCALE = 2.5;
/** The emitter's half-side as a fraction of the room's. */
export const LIGHT_FRACTION = 0.5;
/**
 * L_e: the emitter's irradiance at the floor's centre is π L_e F, F ≈ 0.22 the form factor of
 * the emitter seen from there (half-side h/2 at distance 2h), so L_e = 12 puts a white floor's
 * radiance there near 0.6. The emitter is large (a quarter of the ceiling) because the
 * reference can reach it from inside the sphere only by chance, after the refraction out.
 */
export const EMISSION = 12;
/** Cap on scattering events of one walk inside the sphere, and on surface events of a path. */
export const WALK_CAP = 100000;
export const SURFACE_CAP = 64;
/** Words per irradiance sample (3 vec4f): (p − centre, ΔA), (E, 0), (direct part of E, 0). */
export const SAMPLE_FLOATS = 12;

export function roomScene(
  material: Pick<SubsurfaceMaterial, 'sigmaSPrime' | 'sigmaA' | 'eta'>,
  radius: number,
  walls: number,
  size: number,
): RoomScene {
  const halfSize = ROOM_SCALE * radius;
  return {
    size,
    radius,
    halfSize,
    sigmaSPrime: material.sigmaSPrime,
    sigmaA: material.sigmaA,
    eta: material.eta,
    walls,
    lightHalf: LIGHT_FRACTION * halfSize,
    emission: EMISSION,
  };
}

export const ROOM_PARAMS = translucentRoomPathKernel.RoomParams;

export function packRoomParams(
  scene: RoomScene,
  extra: {
    count?: number;
    seed?: number;
    offset?: number;
    samples?: number;
    rowStart?: number;
  } = {},
): Uint32Array<ArrayBuffer> {
  return packStruct(ROOM_PARAMS, {
    size: scene.size,
    count: extra.count ?? 0,
    seed: extra.seed ?? 0,
    offset: extra.offset ?? 0,
    radius: scene.radius,
    halfSize: scene.halfSize,
    eta: scene.eta,
    walls: scene.walls,
    sigmaSPrime: [...scene.sigmaSPrime, scene.lightHalf],
    sigmaA: [...scene.sigmaA, scene.emission],
    samples: extra.samples ?? 0,
    maxBounces: WALK_CAP,
    surfaceBounces: SURFACE_CAP,
    rowStart: extra.rowStart ?? 0,
  });
}

export const sphereCentre = (scene: RoomScene): Vec3 => [0, scene.radius - scene.halfSize, 0];

/** The camera ray through image point (u, v) ∈ [0, 1]² (v down), from the open front. */
export function cameraRay(scene: RoomScene, u: number, v: number): { origin: Vec3; dir: Vec3 } {
  const h = scene.halfSize;
  const origin: Vec3 = [h * (2 * u - 1), h * (1 - 2 * v), h];
  return { origin, dir: normalize([origin[0], origin[1], origin[2] - 3 * h]) };
}

/**
 * Pixels whose whole footprint sees the sphere (its four corners do: the sphere's image is
 * convex, and nothing stands between it and the camera). The errors are measured over these.
 */
export function sphereMask(scene: RoomScene): Uint8Array {
  const mask = new Uint8Array(scene.size * scene.size);
  const c = sphereCentre(scene);
  const hits = (u: number, v: number): boolean => {
    const { origin, dir } = cameraRay(scene, u, v);
    return !segmentIsEmpty(raySphereSegment(c, scene.radius, origin, dir, 0, 1e30));
  };
  for (let j = 0; j < scene.size; j++)
    for (let i = 0; i < scene.size; i++) {
      const [u0, u1, v0, v1] = [i, i + 1, j, j + 1].map((x) => x / scene.size) as Vec3 & number[];
      mask[j * scene.size + i] =
        hits(u0, v0) && hits(u1!, v0) && hits(u0, v1!) && hits(u1!, v1!) ? 1 : 0;
    }
  return mask;
}

const dot = (a: readonly number[], b: readonly number[]): number =>
  a[0]! * b[0]! + a[1]! * b[1]! + a[2]! * b[2]!;
const normalize = (v: readonly number[]): Vec3 => {
  const n = Math.hypot(v[0]!, v[1]!, v[2]!);
  return [v[0]! / n, v[1]! / n, v[2]! / n];
};
const along = (o: readonly number[], t: number, d: readonly number[]): Vec3 => [
  o[0]! + t * d[0]!,
  o[1]! + t * d[1]!,
  o[2]! + t * d[2]!,
];
const uniform2 = (rng: RngState): [number, number] => [rngNextFloat(rng), rngNextFloat(rng)];
const streamOf = (index: number, seed: number, sample: number): RngState => ({
  value: rngSeed(index, (pcgHash(seed) + sample) >>> 0),
});

/** The emitter's next-event estimate at a wall point for albedo 1: L_e G A/π, shadowed by the sphere. */
function lightEstimate(scene: RoomScene, p: Vec3, n: Vec3, rng: RngState): number {
  const a = scene.lightHalf;
  const y = squareLightPoint(scene.halfSize, a, uniform2(rng));
  const geometry = squareLightGeometry(p, n, y);
  if (geometry <= 0) return 0;
  const w: Vec3 = [y[0] - p[0], y[1] - p[1], y[2] - p[2]];
  const distance = Math.hypot(...w);
  const dir = normalize(w);
  if (!segmentIsEmpty(raySphereSegment(sphereCentre(scene), scene.radius, p, dir, 0, distance)))
    return 0;
  return (scene.emission * geometry * 4 * a * a) / Math.PI;
}

const onLight = (scene: RoomScene, p: Vec3): boolean =>
  Math.abs(p[0]) <= scene.lightHalf && Math.abs(p[2]) <= scene.lightHalf;

/**
 * The analog random walk inside the sphere (twin of walkInside): the exit point and direction
 * and the walk's weight, or weight 0 when it was absorbed (or the cap ended it: capped).
 */
function walkInside(
  scene: RoomScene,
  p: Vec3,
  dIn: Vec3,
  sigmaS: number,
  sigmaA: number,
  rng: RngState,
): { position: Vec3; direction: Vec3; weight: number; capped: number } {
  const c = sphereCentre(scene);
  const R = scene.radius;
  const sigmaT = sigmaS + sigmaA;
  let pos = p;
  let d = dIn;
  let beta = 1;
  let scatterings = 0;
  for (let event = 0; event < WALK_CAP; event++) {
    const exit = raySphereSegment(c, R, pos, d, 0, 1e30)[1];
    const t = -Math.log(1 - rngNextFloat(rng)) / Math.max(sigmaT, 1e-30);
    if (t >= exit) {
      const normal = normalize(along(pos, exit, d).map((x, k) => x - c[k]!));
      const cosOut = Math.max(dot(d, normal), 0);
      if (rngNextFloat(rng) < fresnelDielectric(cosOut, 1 / scene.eta)) {
        pos = along(c, R * (1 - 1e-5), normal);
        d = normalize(along(d, -2 * cosOut, normal));
        continue;
      }
      const out = refractDirection(d, [-normal[0], -normal[1], -normal[2]], 1 / scene.eta);
      return {
        position: along(c, R + 1e-4 * scene.halfSize, normal),
        direction: [out[0], out[1], out[2]],
        weight: beta,
        capped: 0,
      };
    }
    pos = along(pos, t, d);
    beta *= sigmaS / sigmaT;
    d = [...sampleUniformSphere(uniform2(rng))];
    scatterings += 1;
    if (scatterings >= 16) {
      const survive = Math.min(1, beta);
      if (rngNextFloat(rng) >= survive)
        return { position: pos, direction: d, weight: 0, capped: 0 };
      beta /= survive;
    }
  }
  return { position: pos, direction: d, weight: 0, capped: 1 };
}

/**
 * How the sphere looks to a path: 'volume' traces the random walk in channel `channel` (the
 * reference); otherwise the dipole radiance from irradiance samples (F_t/(π(1 − F_dr)) M_o).
 */
type SphereModel =
  | { kind: 'volume'; channel: number }
  | { kind: 'dipole'; samples: Float32Array; count: number; dipoles: DipoleParameters[] };

/** M_o(x) = Σ R_d(‖x − p_i‖) ΔA E_i per channel (x relative to the centre): the direct sum. */
export function roomExitance(
  samples: ArrayLike<number>,
  count: number,
  dipoles: readonly DipoleParameters[],
  x: readonly number[],
): Vec3 {
  const m: Vec3 = [0, 0, 0];
  for (let i = 0; i < count; i++) {
    const o = SAMPLE_FLOATS * i;
    const r = Math.hypot(x[0]! - samples[o]!, x[1]! - samples[o + 1]!, x[2]! - samples[o + 2]!);
    for (let k = 0; k < 3; k++) {
      const power = samples[o + 3]! * samples[o + 4 + k]!;
      if (power > 0) m[k] = m[k]! + power * dipoleProfile(dipoles[k]!, r);
    }
  }
  return m;
}

/**
 * One path through the room (twin of tracePath and tracePathRgb). With a 'volume' sphere the
 * radiance is of one channel (in all three slots); with a 'dipole' sphere it is RGB.
 */
function tracePath(
  scene: RoomScene,
  origin: Vec3,
  dir: Vec3,
  firstSpecular: boolean,
  sphere: SphereModel,
  rng: RngState,
): { radiance: Vec3; capped: number } {
  const c = sphereCentre(scene);
  const R = scene.radius;
  let o = origin;
  let d = dir;
  const beta: Vec3 = [1, 1, 1];
  const radiance: Vec3 = [0, 0, 0];
  const add = (scale: number, v: readonly number[]): void => {
    for (let k = 0; k < 3; k++) radiance[k] = radiance[k]! + scale * beta[k]! * v[k]!;
  };
  const channelOf = (v: Vec3): Vec3 =>
    sphere.kind === 'volume' ? [v[sphere.channel]!, v[sphere.channel]!, v[sphere.channel]!] : v;
  let specular = firstSpecular;
  let wallBounces = 0;
  for (let event = 0; event < SURFACE_CAP; event++) {
    const hit = raySphereSegment(c, R, o, d, 0, 1e30);
    const [tWall, faceValue] = roomWallHit(scene.halfSize, o, d);
    if (!segmentIsEmpty(hit) && hit[0] < tWall) {
      const p = along(o, hit[0], d);
      const n = normalize(p.map((x, k) => x - c[k]!));
      const cosI = Math.max(-dot(d, n), 0);
      const reflect = (): void => {
        d = normalize(along(d, 2 * cosI, n));
        o = along(c, R + 1e-4 * scene.halfSize, n);
        specular = true;
      };
      if (sphere.kind === 'dipole') {
        const m = roomExitance(sphere.samples, sphere.count, sphere.dipoles, [
          n[0] * R,
          n[1] * R,
          n[2] * R,
        ]);
        add(bssrdfExitFactor(cosI, scene.eta), m);
        if (rngNextFloat(rng) >= fresnelDielectric(cosI, scene.eta)) return { radiance, capped: 0 };
        reflect();
        continue;
      }
      if (rngNextFloat(rng) < fresnelDielectric(cosI, scene.eta)) {
        reflect();
        continue;
      }
      const inside = refractDirection(d, n, scene.eta);
      const walk = walkInside(
        scene,
        along(c, R * (1 - 1e-5), n),
        [inside[0], inside[1], inside[2]],
        scene.sigmaSPrime[sphere.channel]!,
        scene.sigmaA[sphere.channel]!,
        rng,
      );
      if (walk.weight <= 0) return { radiance, capped: walk.capped };
      for (let k = 0; k < 3; k++) beta[k] = beta[k]! * walk.weight;
      o = walk.position;
      d = walk.direction;
      specular = true;
      continue;
    }
    if (faceValue === 5) return { radiance, capped: 0 };
    const p = along(o, tWall, d);
    if (faceValue === 1 && onLight(scene, p)) {
      if (specular) add(scene.emission, [1, 1, 1]);
      return { radiance, capped: 0 };
    }
    const albedo = channelOf(roomWallAlbedo(faceValue, scene.walls));
    if (albedo.every((x) => x <= 0)) return { radiance, capped: 0 };
    const n = roomWallNormal(faceValue);
    add(lightEstimate(scene, p, n, rng), albedo);
    for (let k = 0; k < 3; k++) beta[k] = beta[k]! * albedo[k]!;
    d = [...sampleCosineHemisphere(n, uniform2(rng))];
    o = along(p, 1e-4 * scene.halfSize, n);
    specular = false;
    wallBounces += 1;
    if (wallBounces >= 3) {
      const survive = Math.min(1, Math.max(...beta));
      if (rngNextFloat(rng) >= survive) return { radiance, capped: 0 };
      for (let k = 0; k < 3; k++) beta[k] = beta[k]! / survive;
    }
  }
  return { radiance, capped: 1 };
}

/** Per pixel Σ L (RGB), Σ L² (RGB), capped, as the kernels write them (7 floats a pixel). */
function renderSums(
  scene: RoomScene,
  options: { samples: number; offset: number; seed: number },
  pixelValue: (origin: Vec3, dir: Vec3, rng: RngState) => { value: Vec3; capped: number },
): Float32Array {
  const out = new Float32Array(7 * scene.size * scene.size);
  for (let j = 0; j < scene.size; j++)
    for (let i = 0; i < scene.size; i++) {
      const pixel = j * scene.size + i;
      for (let k = 0; k < options.samples; k++) {
        const rng = streamOf(pixel, options.seed, options.offset + k);
        const u = (i + rngNextFloat(rng)) / scene.size;
        const v = (j + rngNextFloat(rng)) / scene.size;
        const { origin, dir } = cameraRay(scene, u, v);
        const { value, capped } = pixelValue(origin, dir, rng);
        for (let c = 0; c < 3; c++) {
          out[7 * pixel + c] = out[7 * pixel + c]! + value[c]!;
          out[7 * pixel + 3 + c] = out[7 * pixel + 3 + c]! + value[c]! ** 2;
        }
        out[7 * pixel + 6] = out[7 * pixel + 6]! + capped;
      }
    }
  return out;
}

/** Twin of roomPathMain: the volumetric path-traced reference, one path per channel. */
export function roomPathCpu(
  scene: RoomScene,
  options: { samples: number; offset: number; seed: number },
): Float32Array {
  return renderSums(scene, options, (origin, dir, rng) => {
    const value: Vec3 = [0, 0, 0];
    let capped = 0;
    for (let channel = 0; channel < 3; channel++) {
      const r = tracePath(scene, origin, dir, true, { kind: 'volume', channel }, rng);
      value[channel] = r.radiance[channel]!;
      capped += r.capped;
    }
    return { value, capped };
  });
}

const dipolesOfRoom = (scene: RoomScene): DipoleParameters[] =>
  [0, 1, 2].map((c) => dipoleParameters(scene.sigmaSPrime[c]!, scene.sigmaA[c]!, scene.eta));

/** Twin of dipoleMain: the picture with the dipole sphere, from irradiance samples. */
export function roomDipoleCpu(
  scene: RoomScene,
  samples: Float32Array,
  options: { samples: number; offset: number; seed: number },
): Float32Array {
  const sphere: SphereModel = {
    kind: 'dipole',
    samples,
    count: samples.length / SAMPLE_FLOATS,
    dipoles: dipolesOfRoom(scene),
  };
  return renderSums(scene, options, (origin, dir, rng) => {
    const r = tracePath(scene, origin, dir, true, sphere, rng);
    return { value: r.radiance, capped: r.capped };
  });
}

/**
 * Twin of irradianceMain: n irradiance samples with `rays` rays each, the sphere seen by the
 * room's paths through the dipole from `previous` (empty: only its mirror reflection).
 * 12 floats per sample.
 */
export function roomIrradianceCpu(
  scene: RoomScene,
  count: number,
  rays: number,
  seed: number,
  previous: Float32Array,
): Float32Array {
  const out = new Float32Array(SAMPLE_FLOATS * count);
  const sphere: SphereModel = {
    kind: 'dipole',
    samples: previous,
    count: previous.length / SAMPLE_FLOATS,
    dipoles: dipolesOfRoom(scene),
  };
  const c = sphereCentre(scene);
  const R = scene.radius;
  const a = scene.lightHalf;
  for (let i = 0; i < count; i++) {
    const normal: Vec3 = [...fibonacciSpherePoint(i, count)];
    const p = along(c, R, normal);
    const start = along(p, 1e-4 * scene.halfSize, normal);
    const direct: Vec3 = [0, 0, 0];
    const total: Vec3 = [0, 0, 0];
    for (let k = 0; k < rays; k++) {
      const rng = streamOf(i, seed, k);
      const y = squareLightPoint(scene.halfSize, a, uniform2(rng));
      const geometry = squareLightGeometry(p, normal, y);
      if (geometry > 0) {
        const cosP = dot(normal, normalize(y.map((v, m) => v - p[m]!)));
        const e = scene.emission * geometry * 4 * a * a * (1 - fresnelDielectric(cosP, scene.eta));
        for (let m = 0; m < 3; m++) direct[m] = direct[m]! + e;
      }
      const w: Vec3 = [...sampleCosineHemisphere(normal, uniform2(rng))];
      const cosW = Math.min(Math.max(dot(w, normal), 0), 1);
      const incoming = tracePath(scene, start, w, false, sphere, rng).radiance;
      const t = Math.PI * (1 - fresnelDielectric(cosW, scene.eta));
      for (let m = 0; m < 3; m++) total[m] = total[m]! + t * incoming[m]!;
    }
    const o = SAMPLE_FLOATS * i;
    const n = Math.max(rays, 1);
    out.set([R * normal[0], R * normal[1], R * normal[2], (4 * Math.PI * R * R) / count], o);
    for (let m = 0; m < 3; m++) {
      out[o + 4 + m] = (total[m]! + direct[m]!) / n;
      out[o + 8 + m] = direct[m]! / n;
    }
  }
  return out;
}

/**
 * The share of the sphere's transmitted power ΣΔA·E that came indirectly (off the walls or
 * back from the sphere), per channel and over the three channels together.
 */
export function indirectShare(samples: ArrayLike<number>): { channels: Vec3; all: number } {
  const total = [0, 0, 0];
  const direct = [0, 0, 0];
  for (let o = 0; o + SAMPLE_FLOATS <= samples.length; o += SAMPLE_FLOATS)
    for (let k = 0; k < 3; k++) {
      total[k] = total[k]! + samples[o + 3]! * samples[o + 4 + k]!;
      direct[k] = direct[k]! + samples[o + 3]! * samples[o + 8 + k]!;
    }
  const share = (t: number, d: number): number => (t > 0 ? 1 - d / t : NaN);
  return {
    channels: [
      share(total[0]!, direct[0]!),
      share(total[1]!, direct[1]!),
      share(total[2]!, direct[2]!),
    ],
    all: share(total[0]! + total[1]! + total[2]!, direct[0]! + direct[1]! + direct[2]!),
  };
}

/**
 * The sphere's power budget in the reference's physics, independent of any camera: light
 * tracing of the emitter's direct light. `photons` photons leave the emitter (area A = 4a²,
 * radiance L_e, so power Φ = π L_e A) from uniform points in cosine-weighted directions; a
 * photon that reaches the sphere enters it with probability 1 − F (Fresnel) and then walks as
 * in walkInside. Per channel: `entered`, the power refracted into the sphere (the light-traced
 * twin of Σ_i E_i ΔA with black walls) and `left`, the power that comes out through the
 * boundary again, counted at the crossing. Walls play no part (each photon stops at its first
 * wall), so the numbers compare with the dipole's budget for the black room.
 */
export function roomPowerBudgetCpu(
  scene: RoomScene,
  photons: number,
  seed: number,
): { entered: Vec3; left: Vec3; leftSquares: Vec3; photons: number } {
  const c = sphereCentre(scene);
  const R = scene.radius;
  const a = scene.lightHalf;
  const power = Math.PI * scene.emission * 4 * a * a;
  const entered: Vec3 = [0, 0, 0];
  const left: Vec3 = [0, 0, 0];
  const leftSquares: Vec3 = [0, 0, 0];
  for (let k = 0; k < photons; k++) {
    const rng = streamOf(k, seed, 0);
    const y = squareLightPoint(scene.halfSize, a, uniform2(rng));
    const d: Vec3 = [...sampleCosineHemisphere([0, -1, 0], uniform2(rng))];
    const hit = raySphereSegment(c, R, y, d, 0, 1e30);
    if (segmentIsEmpty(hit) || hit[0] >= roomWallHit(scene.halfSize, y, d)[0]) continue;
    const n = normalize(along(y, hit[0], d).map((x, m) => x - c[m]!));
    const cosI = Math.max(-dot(d, n), 0);
    if (rngNextFloat(rng) < fresnelDielectric(cosI, scene.eta)) continue;
    const inside = refractDirection(d, n, scene.eta);
    for (let channel = 0; channel < 3; channel++) {
      entered[channel] = entered[channel]! + power / photons;
      const walk = walkInside(
        scene,
        along(c, R * (1 - 1e-5), n),
        [inside[0], inside[1], inside[2]],
        scene.sigmaSPrime[channel]!,
        scene.sigmaA[channel]!,
        rng,
      );
      const w = (walk.weight * power) / photons;
      left[channel] = left[channel]! + w;
      leftSquares[channel] = leftSquares[channel]! + w * w;
    }
  }
  return { entered, left, leftSquares, photons };
}

/**
 * The dipole's power budget from irradiance samples: `entered` = Σ_i E_i ΔA, and `left`, the
 * exitance of eq. room-dipole integrated over the sphere, 4πR² · mean M_o(x) over `points`
 * uniform random points x (not the samples' own points: there the term i = j, R_d(0) ΔA E_i,
 * would count a sample's whole neighbourhood at the profile's peak). bssrdfExitFactor is
 * normalized so that ∫ L_o cos θ dω = M_o, so `left` is the power the dipole sphere sends into
 * the room; `leftSquares` gives its Monte Carlo error.
 */
export function roomDipolePowerBudget(
  scene: RoomScene,
  samples: Float32Array,
  points: number,
  seed: number,
): { entered: Vec3; left: Vec3; leftSquares: Vec3 } {
  const count = samples.length / SAMPLE_FLOATS;
  const dipoles = dipolesOfRoom(scene);
  const area = 4 * Math.PI * scene.radius ** 2;
  const entered: Vec3 = [0, 0, 0];
  const left: Vec3 = [0, 0, 0];
  const leftSquares: Vec3 = [0, 0, 0];
  for (let i = 0; i < count; i++)
    for (let k = 0; k < 3; k++)
      entered[k] =
        entered[k]! + samples[SAMPLE_FLOATS * i + 3]! * samples[SAMPLE_FLOATS * i + 4 + k]!;
  for (let j = 0; j < points; j++) {
    const x = sampleUniformSphere(uniform2(streamOf(j, seed, 0))).map((v) => v * scene.radius);
    const m = roomExitance(samples, count, dipoles, x);
    for (let k = 0; k < 3; k++) {
      const w = (area * m[k]!) / points;
      left[k] = left[k]! + w;
      leftSquares[k] = leftSquares[k]! + w * w;
    }
  }
  return { entered, left, leftSquares };
}
