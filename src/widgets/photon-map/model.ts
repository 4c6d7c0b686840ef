// The scene of <sb-photon-map> and the float64 CPU twin of its whole pipeline
// (shaders/kernels/photon-map.wesl): photon tracing, the uniform grid, the
// photon-map image (volume radiance estimate, eq:photon-volume-estimate) and the
// unbiased path tracer. The same PCG streams and the same order of random numbers
// as the kernels; the library functions are the twins in src/reference/.
import {
  rayBoxSegment,
  raySphereSegment,
  segmentIsEmpty,
  RAY_T_LIMIT,
} from '../../reference/geometry.ts';
import { hgEvalDirections, hgSample, type Vec3 } from '../../reference/phase.ts';
import {
  dielectricScatter,
  photonCellCoord,
  photonCellIndex,
  photonKernel,
  photonPower,
  sunConeSampleCosine,
  sunConeSampleUniform,
  sunConeSolidAngle,
  sunRadiance,
} from '../../reference/photons.ts';
import { rngNextFloat, rngSeed, type RngState } from '../../reference/rng.ts';

/** The fixed scene: fog box, glass ball, sun from straight above, camera from the side. */
export const SCENE = {
  boxMin: [-0.8, -0.8, -0.5] as Vec3,
  boxMax: [0.8, 0.8, 0.5] as Vec3,
  sphereCenter: [0, 0.35, 0] as Vec3,
  sphereRadius: 0.3,
  /** Direction of travel of the sunlight. */
  sunDirection: [0, -1, 0] as Vec3,
  /** Irradiance on a plane perpendicular to the sun, W/m². */
  irradiance: 1,
  /**
   * The emission disc: above the box, perpendicular to the sun. It covers the box's
   * shadow except thin slivers at the bottom of the vertical corner edges (full cover
   * needs 0.943 m + 1.35 m·tan 4° = 1.037 m); there, below y ≈ 0.03 m, part of the sun's
   * cone is not emitted and the photon map is slightly too dark.
   */
  diskCenter: [0, 0.85, 0] as Vec3,
  diskRadius: 1.0,
  cameraPosition: [0, 0, 3.1] as Vec3,
  cameraTarget: [0, 0, 0] as Vec3,
  fovYDegrees: 34,
};

export const RECORD_WORDS = 8;
/** Image size of the GPU widget and of the reference (the CPU fallback halves it). */
export const GPU_SIZE = { width: 64, height: 48 } as const;
export const CPU_SIZE = { width: 32, height: 24 } as const;
/** Photon slots per emitted photon: about 0.44 are stored per photon here (overflow is counted and shown). */
export const CAPACITY_PER_PHOTON = 2;
/** Grid cells per axis at most; the cell grows past r when r is tiny. */
export const MAX_CELLS_PER_AXIS = 96;

export interface PhotonInputs {
  sigmaS: number;
  sigmaA: number;
  g: number;
  eta: number;
  sunAngleDegrees: number;
  photons: number;
  radius: number;
  seed: number;
}

export interface Grid {
  gridMin: Vec3;
  cellSize: number;
  dims: [number, number, number];
}

export function gridFor(radius: number): Grid {
  const extent = [0, 1, 2].map((k) => SCENE.boxMax[k]! - SCENE.boxMin[k]!);
  const cellSize = Math.max(radius, Math.max(...extent) / MAX_CELLS_PER_AXIS);
  const dims = extent.map((e) => Math.max(1, Math.ceil(e / cellSize))) as [number, number, number];
  return { gridMin: SCENE.boxMin, cellSize, dims };
}

export interface CameraFrame {
  forward: Vec3;
  right: Vec3;
  up: Vec3;
}

/** Pinhole frame: right and up scaled to the half-extents of the image plane at distance 1. */
export function cameraFrame(width: number, height: number): CameraFrame {
  const f = normalize(sub(SCENE.cameraTarget, SCENE.cameraPosition));
  const r = normalize(cross(f, [0, 1, 0]));
  const u = cross(r, f);
  const tanY = Math.tan((SCENE.fovYDegrees * Math.PI) / 360);
  const tanX = (tanY * width) / height;
  return { forward: f, right: scale(r, tanX), up: scale(u, tanY) };
}

export const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];
export const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
export const normalize = (a: Vec3): Vec3 => scale(a, 1 / Math.hypot(a[0], a[1], a[2]));

export function sinThetaMax(inputs: PhotonInputs): number {
  return Math.sin((inputs.sunAngleDegrees * Math.PI) / 180);
}

/** Stored photons: position, power and direction of travel, as flat arrays. */
export interface PhotonSet {
  count: number;
  positions: Float64Array;
  powers: Float64Array;
  directions: Float64Array;
  /** Reflections and refractions on the glass before each photon's collision. */
  glass: Uint32Array;
  /** Collisions beyond the capacity (lost; the readout reports them). */
  overflow: number;
  emittedPower: number;
}

const rand = (state: RngState): number => rngNextFloat(state);

function sphereHit(origin: Vec3, direction: Vec3, inside: boolean): number {
  const seg = raySphereSegment(
    SCENE.sphereCenter,
    SCENE.sphereRadius,
    origin,
    direction,
    1e-4,
    RAY_T_LIMIT,
  );
  if (segmentIsEmpty(seg)) return RAY_T_LIMIT;
  return inside ? seg[1] : seg[0];
}

const sphereNormal = (p: Vec3): Vec3 => normalize(sub(p, SCENE.sphereCenter));
const fogSegment = (o: Vec3, d: Vec3) =>
  rayBoxSegment(SCENE.boxMin, SCENE.boxMax, o, d, 0, RAY_T_LIMIT);

/** Twin of tracePhotons: every collision in the fog is stored. */
export function tracePhotonsCpu(
  inputs: PhotonInputs,
  capacity = CAPACITY_PER_PHOTON * inputs.photons,
): PhotonSet {
  const sigmaT = inputs.sigmaS + inputs.sigmaA;
  const albedo = inputs.sigmaS / sigmaT;
  const sinMax = sinThetaMax(inputs);
  const axis = SCENE.sunDirection;
  const helper: Vec3 = Math.abs(axis[0]) > 0.9 ? [0, 0, 1] : [1, 0, 0];
  const e1 = normalize(cross(axis, helper));
  const e2 = cross(axis, e1);
  const area = Math.PI * SCENE.diskRadius ** 2;
  const power = photonPower(SCENE.irradiance, area, inputs.photons);
  const positions: number[] = [];
  const powers: number[] = [];
  const directions: number[] = [];
  const glassCounts: number[] = [];
  let stored = 0;
  let overflow = 0;
  for (let i = 0; i < inputs.photons; i++) {
    const state = { value: rngSeed(i, inputs.seed) };
    const rDisc = SCENE.diskRadius * Math.sqrt(rand(state));
    const phi = 2 * Math.PI * rand(state);
    let position = add(
      SCENE.diskCenter,
      add(scale(e1, rDisc * Math.cos(phi)), scale(e2, rDisc * Math.sin(phi))),
    );
    const u0 = rand(state);
    const u1 = rand(state);
    let direction = sunConeSampleCosine(axis, sinMax, [u0, u1]);
    let inside = false;
    let glass = 0;
    for (let event = 0; event < 256; event++) {
      const tSphere = sphereHit(position, direction, inside);
      if (inside) {
        position = add(position, scale(direction, tSphere));
        const n = sphereNormal(position);
        direction = dielectricScatter(direction, n, inputs.eta, rand(state));
        inside = dot(direction, n) < 0;
        glass++;
        continue;
      }
      const fog = fogSegment(position, direction);
      if (segmentIsEmpty(fog)) break;
      const tCollision = fog[0] - Math.log(1 - rand(state)) / sigmaT;
      if (tCollision < Math.min(tSphere, fog[1])) {
        position = add(position, scale(direction, tCollision));
        if (stored < capacity) {
          positions.push(...position);
          powers.push(power);
          directions.push(...direction);
          glassCounts.push(glass);
          stored++;
        } else overflow++;
        if (rand(state) >= albedo) break;
        const u2 = rand(state);
        const u3 = rand(state);
        direction = hgSample(inputs.g, scale(direction, -1), [u2, u3]).wi;
        continue;
      }
      if (tSphere < fog[1]) {
        position = add(position, scale(direction, tSphere));
        const n = sphereNormal(position);
        direction = dielectricScatter(direction, n, inputs.eta, rand(state));
        inside = dot(direction, n) < 0;
        glass++;
        continue;
      }
      break;
    }
  }
  return {
    count: stored,
    positions: Float64Array.from(positions),
    powers: Float64Array.from(powers),
    directions: Float64Array.from(directions),
    glass: Uint32Array.from(glassCounts),
    overflow,
    emittedPower: power * inputs.photons,
  };
}

/** Counting sort of the photons by cell (the twin of countCells, prefixCells, scatterPhotons). */
export interface SortedPhotons {
  grid: Grid;
  cellStart: Uint32Array;
  order: Uint32Array;
}

export function buildGridCpu(set: PhotonSet, grid: Grid): SortedPhotons {
  const cells = grid.dims[0] * grid.dims[1] * grid.dims[2];
  const counts = new Uint32Array(cells);
  const cellOf = new Uint32Array(set.count);
  for (let i = 0; i < set.count; i++) {
    const p: Vec3 = [set.positions[3 * i]!, set.positions[3 * i + 1]!, set.positions[3 * i + 2]!];
    const c = photonCellIndex(
      photonCellCoord(p, grid.gridMin, grid.cellSize, grid.dims),
      grid.dims,
    );
    cellOf[i] = c;
    counts[c]! += 1;
  }
  const cellStart = new Uint32Array(cells + 1);
  for (let c = 0; c < cells; c++) cellStart[c + 1] = cellStart[c]! + counts[c]!;
  const cursor = cellStart.slice(0, cells);
  const order = new Uint32Array(set.count);
  for (let i = 0; i < set.count; i++) order[cursor[cellOf[i]!]!++] = i;
  return { grid, cellStart, order };
}

/** Σ p ΔΦ K over photons within r (3×3×3 cells) and how many were found. */
export function gatherCpu(
  set: PhotonSet,
  sorted: SortedPhotons,
  x: Vec3,
  toCamera: Vec3,
  g: number,
  radius: number,
): { sum: number; found: number } {
  const { grid } = sorted;
  const centre = photonCellCoord(x, grid.gridMin, grid.cellSize, grid.dims);
  let sum = 0;
  let found = 0;
  for (let dz = -1; dz <= 1; dz++)
    for (let dy = -1; dy <= 1; dy++)
      for (let dx = -1; dx <= 1; dx++) {
        const c: [number, number, number] = [centre[0] + dx, centre[1] + dy, centre[2] + dz];
        if (c.some((v, k) => v < 0 || v >= grid.dims[k]!)) continue;
        const cell = photonCellIndex(c, grid.dims);
        for (let s = sorted.cellStart[cell]!; s < sorted.cellStart[cell + 1]!; s++) {
          const i = sorted.order[s]!;
          const d = sub(
            [set.positions[3 * i]!, set.positions[3 * i + 1]!, set.positions[3 * i + 2]!],
            x,
          );
          const k = photonKernel(dot(d, d), radius);
          if (k > 0) {
            const travel: Vec3 = [
              set.directions[3 * i]!,
              set.directions[3 * i + 1]!,
              set.directions[3 * i + 2]!,
            ];
            sum += hgEvalDirections(g, toCamera, scale(travel, -1)) * set.powers[i]! * k;
            found++;
          }
        }
      }
  return { sum, found };
}

/** Brute force: every stored photon within r of x (the grid test's oracle). */
export function bruteForceCpu(set: PhotonSet, x: Vec3, toCamera: Vec3, g: number, radius: number) {
  let sum = 0;
  let found = 0;
  for (let i = 0; i < set.count; i++) {
    const d = sub([set.positions[3 * i]!, set.positions[3 * i + 1]!, set.positions[3 * i + 2]!], x);
    const k = photonKernel(dot(d, d), radius);
    if (k > 0) {
      const travel: Vec3 = [
        set.directions[3 * i]!,
        set.directions[3 * i + 1]!,
        set.directions[3 * i + 2]!,
      ];
      sum += hgEvalDirections(g, toCamera, scale(travel, -1)) * set.powers[i]! * k;
      found++;
    }
  }
  return { sum, found };
}

function cameraDirection(
  frame: CameraFrame,
  width: number,
  height: number,
  px: number,
  py: number,
): Vec3 {
  const nx = (2 * px) / width - 1;
  const ny = 1 - (2 * py) / height;
  return normalize(add(frame.forward, add(scale(frame.right, nx), scale(frame.up, ny))));
}

/** Whether a camera path leaving along `direction` looks into the sun's disc (light travels along −direction). */
function seesSun(direction: Vec3, sinMax: number): boolean {
  return -dot(direction, SCENE.sunDirection) >= Math.sqrt(Math.max(0, 1 - sinMax * sinMax));
}

/**
 * Exponent of the progressive radius schedule. Chapter 10, "Bias versus variance":
 * the bias of the volume radiance estimate grows like r² and its variance like
 * 1/(N r³); minimising r⁴ + c/(N r³) gives r ∝ N^(−1/7), and then the RMSE falls as
 * N^(−2/7) (Hachisuka et al. 2008; Knaus & Zwicker 2011).
 */
export const PROGRESSIVE_RADIUS_EXPONENT = -1 / 7;
/** The RMSE rate that schedule gives, N^(−2/7). */
export const PROGRESSIVE_RMSE_EXPONENT = -2 / 7;

/** Progressive gather radius r_k = r₀ (N_k/N₀)^(−1/7): equal to r₀ at N₀, shrinking as N grows. */
export function progressiveRadius(radius0: number, photons0: number, photons: number): number {
  return radius0 * (photons / photons0) ** PROGRESSIVE_RADIUS_EXPONENT;
}

/** Step of the photon-map march: half the gather radius, at most 5 cm. */
export function stepSizeFor(radius: number): number {
  return Math.min(0.05, 0.5 * radius);
}

/** Twin of gatherImage: mean photon-map radiance of `samples` jittered rays per pixel. */
export function photonMapImageCpu(
  inputs: PhotonInputs,
  set: PhotonSet,
  sorted: SortedPhotons,
  width: number,
  height: number,
  samples: number,
  seed: number,
  pixels?: readonly number[],
): Float64Array {
  const sigmaT = inputs.sigmaS + inputs.sigmaA;
  const albedo = inputs.sigmaS / sigmaT;
  const frame = cameraFrame(width, height);
  const step = stepSizeFor(inputs.radius);
  const out = new Float64Array(width * height);
  const list = pixels ?? Array.from({ length: width * height }, (_, i) => i);
  for (const index of list) {
    const x = index % width;
    const y = Math.floor(index / width);
    const state = { value: rngSeed(index, seed) };
    let total = 0;
    for (let s = 0; s < samples; s++) {
      const px = x + rand(state);
      const py = y + rand(state);
      let origin = SCENE.cameraPosition;
      let direction = cameraDirection(frame, width, height, px, py);
      let throughput = 1;
      let radiance = 0;
      let inside = false;
      for (let bounce = 0; bounce <= 8; bounce++) {
        const tSphere = sphereHit(origin, direction, inside);
        if (!inside) {
          const fog = fogSegment(origin, direction);
          if (!segmentIsEmpty(fog)) {
            const a = fog[0];
            const b = Math.min(fog[1], tSphere);
            if (b > a) {
              const steps = Math.max(1, Math.ceil((b - a) / step));
              const h = (b - a) / steps;
              const back = scale(direction, -1);
              for (let j = 0; j < steps; j++) {
                const t = a + (j + rand(state)) * h;
                const g = gatherCpu(
                  set,
                  sorted,
                  add(origin, scale(direction, t)),
                  back,
                  inputs.g,
                  inputs.radius,
                );
                radiance += throughput * Math.exp(-sigmaT * (t - a)) * albedo * g.sum * h;
              }
              throughput *= Math.exp(-sigmaT * (b - a));
            }
          }
        }
        if (tSphere >= RAY_T_LIMIT) break; // no glint: see pathRadianceCpu
        origin = add(origin, scale(direction, tSphere));
        const n = sphereNormal(origin);
        direction = dielectricScatter(direction, n, inputs.eta, rand(state));
        inside = dot(direction, n) < 0;
      }
      total += radiance;
    }
    out[index] = total / Math.max(samples, 1);
  }
  return out;
}

/** One unbiased path sample (twin of pathRadiance). */
export function pathRadianceCpu(
  inputs: PhotonInputs,
  origin0: Vec3,
  direction0: Vec3,
  state: RngState,
): number {
  const sigmaT = inputs.sigmaS + inputs.sigmaA;
  const albedo = inputs.sigmaS / sigmaT;
  const sinMax = sinThetaMax(inputs);
  const sunL = sunRadiance(SCENE.irradiance, sinMax);
  const omega = sunConeSolidAngle(sinMax);
  let origin = origin0;
  let direction = direction0;
  let throughput = 1;
  let radiance = 0;
  // The sun seen through the glass without a collision (the glint on the ball) is
  // left out of both images, as in the kernel.
  let specular = false;
  let collided = false;
  let inside = false;
  const matched = Math.fround(inputs.eta) === 1;
  for (let event = 0; event < 256; event++) {
    const tSphere = sphereHit(origin, direction, inside);
    if (inside) {
      origin = add(origin, scale(direction, tSphere));
      const n = sphereNormal(origin);
      direction = dielectricScatter(direction, n, inputs.eta, rand(state));
      inside = dot(direction, n) < 0;
      continue;
    }
    const fog = fogSegment(origin, direction);
    let tCollision = RAY_T_LIMIT;
    if (!segmentIsEmpty(fog)) {
      tCollision = fog[0] - Math.log(1 - rand(state)) / sigmaT;
      if (tCollision >= fog[1]) tCollision = RAY_T_LIMIT;
    }
    if (tCollision < tSphere) {
      origin = add(origin, scale(direction, tCollision));
      throughput *= albedo;
      const u0 = rand(state);
      const u1 = rand(state);
      const toSun = scale(sunConeSampleUniform(SCENE.sunDirection, sinMax, [u0, u1]), -1);
      // Glass blocks the shadow ray; an index-matched sphere is a clear hole in the fog.
      const sphereSeg = raySphereSegment(
        SCENE.sphereCenter,
        SCENE.sphereRadius,
        origin,
        toSun,
        0,
        RAY_T_LIMIT,
      );
      const crosses = !segmentIsEmpty(sphereSeg);
      if (!crosses || matched) {
        const exit = fogSegment(origin, toSun);
        const clear = crosses ? sphereSeg[1] - sphereSeg[0] : 0;
        const transmittance = Math.exp(-sigmaT * Math.max(0, exit[1] - clear));
        radiance +=
          throughput *
          hgEvalDirections(inputs.g, scale(direction, -1), toSun) *
          sunL *
          omega *
          transmittance;
      }
      if (throughput < 0.1) {
        if (rand(state) >= throughput * 10) return radiance;
        throughput = 0.1;
      }
      const u2 = rand(state);
      const u3 = rand(state);
      direction = hgSample(inputs.g, scale(direction, -1), [u2, u3]).wi;
      specular = false;
      collided = true;
      continue;
    }
    if (tSphere < RAY_T_LIMIT) {
      origin = add(origin, scale(direction, tSphere));
      const n = sphereNormal(origin);
      direction = dielectricScatter(direction, n, inputs.eta, rand(state));
      inside = dot(direction, n) < 0;
      specular = specular || !matched;
      continue;
    }
    if (collided && specular && seesSun(direction, sinMax)) radiance += throughput * sunL;
    return radiance;
  }
  return radiance;
}

/** Twin of pathTrace over chosen pixels: sums and sums of squares of `samples` paths. */
export function pathTraceCpu(
  inputs: PhotonInputs,
  width: number,
  height: number,
  samples: number,
  seed: number,
  pixels?: readonly number[],
): { sum: Float64Array; sumSq: Float64Array } {
  const frame = cameraFrame(width, height);
  const sum = new Float64Array(width * height);
  const sumSq = new Float64Array(width * height);
  const list = pixels ?? Array.from({ length: width * height }, (_, i) => i);
  for (const index of list) {
    const x = index % width;
    const y = Math.floor(index / width);
    const state = { value: rngSeed(index, seed) };
    for (let s = 0; s < samples; s++) {
      const px = x + rand(state);
      const py = y + rand(state);
      const l = pathRadianceCpu(
        inputs,
        SCENE.cameraPosition,
        cameraDirection(frame, width, height, px, py),
        state,
      );
      sum[index]! += l;
      sumSq[index]! += l * l;
    }
  }
  return { sum, sumSq };
}

/** Root-mean-square difference of two images (over all pixels): src/statistics. */
export { rmse } from '../../statistics/errors.ts';

/** Box-filter downsampling by an integer factor (the CPU fallback's reference). */
export function downsample(
  image: ArrayLike<number>,
  width: number,
  height: number,
  factor: number,
): Float64Array {
  const w = Math.floor(width / factor);
  const h = Math.floor(height / factor);
  const out = new Float64Array(w * h);
  for (let y = 0; y < height - (height % factor); y++)
    for (let x = 0; x < width - (width % factor); x++)
      out[Math.floor(y / factor) * w + Math.floor(x / factor)]! +=
        image[y * width + x]! / (factor * factor);
  return out;
}

export const DEFAULT_INPUTS: PhotonInputs = {
  sigmaS: 0.6,
  sigmaA: 0.06,
  g: 0.3,
  eta: 1.5,
  sunAngleDegrees: 4,
  photons: 1 << 16,
  radius: 0.04,
  seed: 1,
};

/** Stream offset of the reference's passes (scripts/photon-map-reference.ts). */
export const REFERENCE_SEED = 1 << 20;

export interface PhotonReference {
  width: number;
  height: number;
  samples: number;
  mean: Float32Array;
  standardError: Float32Array;
}

/** Parses public/photon-map/reference.bin (header: width, height, spp, seed). */
export function parseReference(buffer: ArrayBuffer): PhotonReference {
  const [width, height, samples] = new Uint32Array(buffer, 0, 4) as unknown as [
    number,
    number,
    number,
  ];
  const pixels = width * height;
  return {
    width,
    height,
    samples,
    mean: new Float32Array(buffer.slice(16, 16 + 4 * pixels)),
    standardError: new Float32Array(buffer.slice(16 + 4 * pixels, 16 + 8 * pixels)),
  };
}
