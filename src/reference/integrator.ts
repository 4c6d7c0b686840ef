// Float64 twin of shaders/integrator.wesl: the emission–absorption, single-scattering
// and path-tracing estimators of a packed scene. The WGSL module reads its scene from
// module-scope bindings; here they are the first argument, `scene` (SceneData: the same
// packed f32 records, the grid's samples, the link conditions the kernel was specialized
// with, and counters). Each function draws its random numbers in the same order as the
// shader, so a sample replays the GPU's PCG stream; f32 rounding makes long paths
// diverge, which is why the tests compare images by z-scores, not bit for bit.
//
// Honouring the conditions makes the twin both the oracle of any specialized kernel and
// the CPU fallback that runs only the planned effects.
import {
  cameraOrthographic,
  cameraPerspective,
  CAMERA_ORTHOGRAPHIC,
  type Camera,
} from './camera.ts';
import { RAY_T_LIMIT, rayBoxExit, rayBoxSegment, raySphereSegment } from './geometry.ts';
import {
  LIGHT_DIRECTIONAL,
  LIGHT_ENVIRONMENT,
  LIGHT_POINT,
  LIGHT_SPOT,
  lightSampleDirectional,
  lightSamplePoint,
  lightSampleSpot,
  type Light,
  type LightSample,
} from './lights.ts';
import {
  gridDensityTrilinear,
  gridHasVolume,
  gridMajorantAlongSegment,
  type DensityGrid,
} from './medium.ts';
import { dispatchedPhase, phaseTableAt, type PhaseRecord } from '../phase/registry.ts';
import type { PhaseTable } from './mie.ts';
import type { Vec3 } from './directions.ts';
import { rngNextFloat, type RngState } from './rng.ts';
import { equiangularSample } from './scatter.ts';
import {
  SURFACE_NO_HIT,
  lambertianBrdf,
  sampleCosineHemisphere,
  surfaceHitDistance,
  surfaceNormalFacing,
  surfaceOffsetOrigin,
  type Surface,
} from './surfaces.ts';
import { TRACKING_MAX_STEPS, sampleFreeFlight } from './tracking.ts';
import { F32_MAX, transmittanceHomogeneous } from './transmittance.ts';
import { readStruct, wordsOf, type UnpackedValue } from '../gpu/layout.ts';
import { sceneRenderKernel } from '../gpu/layouts.generated.ts';

/**
 * The packed scene (integrator.wesl SceneRecords): every record offset, the medium
 * record's phase words and the capacities come from the WGSL declaration, derived into
 * src/gpu/layouts.generated.ts; src/scene/pack.ts writes with the same layout.
 */
export const SCENE_LAYOUT = sceneRenderKernel.SceneRecords;
export const SCENE_MAX_MEDIA = SCENE_LAYOUT.members.media.type.count;
export const SCENE_MAX_LIGHTS = SCENE_LAYOUT.members.lights.type.count;
export const SCENE_MAX_SURFACES = SCENE_LAYOUT.members.surfaces.type.count;
export const SCENE_ORDER_UNLIMITED = 0xffffffff;
export const SCENE_MEDIUM_HOMOGENEOUS = 0;
export const SCENE_MEDIUM_GRID = 1;
export const SCENE_BOUNDS_BOX = 0;
export const SCENE_BOUNDS_SPHERE = 1;
export const PATH_MAX_VERTICES = 1024;
/** Roulette plays after this scattering order and later (integrator.wesl ROULETTE_START_ORDER). */
export const ROULETTE_START_ORDER = 3;
export const FLIGHT_PASSED = 0;
export const FLIGHT_ABSORBED = 1;
export const FLIGHT_SCATTERED = 2;
export const SEGMENT_MAX_POINTS = 9;
export const VERTEX_MEDIUM = 0;
export const VERTEX_SURFACE = 1;
export const VERTEX_LIGHTS_ALL = 0xffffffff;
export const VERTEX_LIGHTS_DISTANT = 0xfffffffe;

type Rgb = [number, number, number];

/** The GPU's bound resources and link conditions, for the twin. */
export interface SceneData {
  /** The packed SceneRecords (SCENE_LAYOUT) as f32, and the same words as u32. */
  records: Float32Array;
  words: Uint32Array;
  /** Samples of the density grid and of its majorant grid (x fastest). */
  density: Float32Array;
  majorant: Float32Array;
  /**
   * The phase-table buffer (src/phase/registry.ts packPhases; integrator.wesl
   * scenePhaseTables): the tables of the tabulated phase functions, as f32.
   */
  phaseTables: Float32Array;
  /** The WESL conditions the kernel was linked with (absent names are false). */
  conditions: Readonly<Record<string, boolean>>;
  /** Counters of the current pixel, as sceneLookups and sceneCapped. */
  stats: { lookups: number; capped: number };
  /** Decoded records, filled on first use. */
  cache?: {
    records: UnpackedValue<typeof SCENE_LAYOUT>;
    media: SceneMedium[];
    lights: Light[];
    surfaces: Surface[];
    grids: { grid: DensityGrid; majorant: DensityGrid };
  };
}

export interface SceneMedium {
  kind: number;
  shape: number;
  phase: PhaseRecord;
  boundsA: Vec3;
  radius: number;
  boundsB: Vec3;
  sigmaA: Rgb;
  sigmaS: Rgb;
  emission: Rgb;
}

export interface SegmentList {
  count: number;
  media: number[];
  segments: [number, number][];
}

export interface SurfaceHit {
  t: number;
  index: number;
}

export interface SegmentPoints {
  count: number;
  t: number[];
  transmittance: Rgb[];
}

export interface SegmentWalk {
  transmittance: Rgb;
  emitted: Rgb;
  scatterT: number;
  scatterWeight: Rgb;
}

export interface Vertex {
  position: Vec3;
  kind: number;
  wo: Vec3;
  medium: number;
  normal: Vec3;
  lights: number;
  albedo: Vec3;
}

export interface FreeFlight {
  t: number;
  event: number;
  weight: Rgb;
  emitted: Rgb;
}

const on = (scene: SceneData, name: string): boolean => scene.conditions[name] === true;
const add = (a: Rgb, b: Rgb): Rgb => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const mul = (a: Rgb, b: Rgb): Rgb => [a[0] * b[0], a[1] * b[1], a[2] * b[2]];
const scale = (a: Rgb, s: number): Rgb => [a[0] * s, a[1] * s, a[2] * s];
const anyPositive = (a: readonly number[]): boolean => a[0]! > 0 || a[1]! > 0 || a[2]! > 0;
const allZero = (a: Rgb): boolean => a[0] === 0 && a[1] === 0 && a[2] === 0;
const at = (o: Vec3, d: Vec3, t: number): Vec3 => [
  o[0] + t * d[0],
  o[1] + t * d[1],
  o[2] + t * d[2],
];
const neg = (v: Vec3): Vec3 => [-v[0], -v[1], -v[2]];
const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const clampRgb = (a: Rgb): Rgb => a.map((x) => Math.min(Math.max(x, 0), 1)) as Rgb;

export function maxComponent(v: readonly number[]): number {
  return Math.max(v[0]!, v[1]!, v[2]!);
}

export function averageComponent(v: readonly number[]): number {
  // Finite like the shader's: the mean of f32 channels saturates below the largest f32.
  const mean = (v[0]! + v[1]! + v[2]!) / 3;
  return Math.min(Math.max(mean, -3.4028216409684243e38), 3.4028216409684243e38);
}

export function sceneHeader(scene: SceneData): [number, number, number, number] {
  const [media, lights, surfaces, order] = decoded(scene).records.header;
  return [media!, lights!, surfaces!, order!];
}

export function sceneCamera(scene: SceneData): Camera {
  const c = decoded(scene).records.camera;
  const [width, height] = c.imageSize;
  if (c.projection === CAMERA_ORTHOGRAPHIC)
    return cameraOrthographic(c.position, c.look, c.up, c.width, c.height, width, height);
  return cameraPerspective(c.position, c.look, c.up, c.fovY, width, height);
}

/** The records read once per SceneData at the offsets of SCENE_LAYOUT (as sceneMedium etc.). */
function decoded(scene: SceneData): NonNullable<SceneData['cache']> {
  if (scene.cache) return scene.cache;
  const { words } = scene;
  const records = readStruct(SCENE_LAYOUT, wordsOf(words.buffer), words.byteOffset);
  const media = records.media.map((r): SceneMedium => ({
    kind: r.kind,
    shape: r.shape,
    phase: {
      kind: r.phaseKind,
      values: [r.phaseValue0, r.phaseValue1, r.phaseValue2],
      table: r.phaseTable,
    },
    boundsA: r.boundsA,
    radius: r.radius,
    boundsB: r.boundsB,
    sigmaA: r.sigmaA,
    sigmaS: r.sigmaS,
    emission: r.emission,
  }));
  const lights = records.lights.map((r): Light => ({
    kind: r.kind,
    cosOuter: r.cosOuter,
    cosInner: r.cosInner,
    position: r.position,
    direction: r.direction,
    value: r.value,
  }));
  const surfaces = records.surfaces.map((r): Surface => ({
    kind: r.kind,
    a: r.a,
    radius: r.radius,
    b: r.b,
    albedo: r.albedo,
  }));
  const grid = (r: typeof records.grid): DensityGrid => ({
    dimensions: r.dimensions,
    densityScale: r.densityScale,
    boundsMin: r.boundsMin,
    boundsMax: r.boundsMax,
  });
  scene.cache = {
    records,
    media,
    lights,
    surfaces,
    grids: { grid: grid(records.grid), majorant: grid(records.majorant) },
  };
  return scene.cache;
}

/** The density grid or its majorant grid (integrator.wesl sceneGrid of that record). */
export function sceneGrid(scene: SceneData, which: 'grid' | 'majorant'): DensityGrid {
  return decoded(scene).grids[which];
}

export function sceneMedium(scene: SceneData, index: number): SceneMedium {
  return decoded(scene).media[index]!;
}

export function sceneLight(scene: SceneData, index: number): Light {
  return decoded(scene).lights[index]!;
}

export function sceneSurface(scene: SceneData, index: number): Surface {
  return decoded(scene).surfaces[index]!;
}

export function mediumSegment(
  medium: SceneMedium,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): [number, number] {
  const segment =
    medium.shape === SCENE_BOUNDS_SPHERE
      ? raySphereSegment(medium.boundsA, medium.radius, origin, direction, tMin, tMax)
      : rayBoxSegment(medium.boundsA, medium.boundsB, origin, direction, tMin, tMax);
  return [segment[0], segment[1]];
}

/**
 * The part [0, t1] of a ray from a position inside the one medium (integrator.wesl
 * oneMediumSegmentFrom): rayBoxExit for a box, mediumSegment for a ball.
 */
export function oneMediumSegmentFrom(
  medium: SceneMedium,
  position: Vec3,
  direction: Vec3,
  tMax: number,
): [number, number] {
  if (medium.shape === SCENE_BOUNDS_SPHERE)
    return mediumSegment(medium, position, direction, 0, tMax);
  return [0, rayBoxExit(medium.boundsA, medium.boundsB, position, direction, tMax)];
}

/** What the one-medium kernels read once per invocation (integrator.wesl oneMediumLoad). */
export interface OneMediumRecords {
  medium: SceneMedium;
  firstLight: Light;
  maxOrder: number;
}

/** The one-medium kernels' records: medium 0, light 0 and the maximum scattering order. */
export function oneMediumLoad(scene: SceneData): OneMediumRecords {
  return {
    medium: sceneMedium(scene, 0),
    firstLight: sceneLight(scene, 0),
    maxOrder: sceneHeader(scene)[3],
  };
}

/**
 * What the linked estimator reads before its sample loop (integrator.wesl
 * integratorInvocationStart): the one-medium records under those kernels, else nothing.
 */
export function integratorInvocationStart(scene: SceneData): OneMediumRecords | null {
  return on(scene, 'oneHomogeneousMedium') || on(scene, 'oneGridMedium')
    ? oneMediumLoad(scene)
    : null;
}

/**
 * What integrator.wesl sceneGridLoad derives once per invocation from the scene's grid
 * records (SceneGridCache and sceneMajorantGrid): the map p ↦ u = p ⊙ toSample + offset to
 * the continuous sample coordinate, which regroups gridTrilinearCorners'
 * (p − b_min)/(b_max − b_min) ⊙ n − ½; the largest sample index; the buffer strides; the
 * majorant grid's largest density. A grid without volume gets an empty box (every lookup
 * outside, density 0) and a one-cell unit majorant grid of densityScale 0 (every majorant 0).
 * The twin's own lookups use gridDensityTrilinear directly; this mirrors what the kernel
 * caches, for the tests.
 */
export interface SceneGridCache {
  boundsMin: Vec3;
  majorantMax: number;
  boundsMax: Vec3;
  toSample: Vec3;
  offset: Vec3;
  lastSample: Vec3;
  lastIndex: Vec3;
  strides: Vec3;
  majorantGrid: DensityGrid;
}

export function sceneGridLoad(scene: SceneData): SceneGridCache {
  const grid = sceneGrid(scene, 'grid');
  const majorant = sceneGrid(scene, 'majorant');
  const hasVolume = gridHasVolume(grid);
  const [nx, ny] = grid.dimensions;
  const perAxis = (f: (a: 0 | 1 | 2) => number): Vec3 => [f(0), f(1), f(2)];
  const toSample = perAxis((a) => grid.dimensions[a] / (grid.boundsMax[a] - grid.boundsMin[a]));
  const last = perAxis((a) => Math.max(grid.dimensions[a], 1) - 1);
  return {
    boundsMin: hasVolume ? grid.boundsMin : [1, 1, 1],
    majorantMax: decoded(scene).records.majorant.maxDensity,
    boundsMax: hasVolume ? grid.boundsMax : [-1, -1, -1],
    toSample,
    offset: perAxis((a) => -grid.boundsMin[a] * toSample[a] - 0.5),
    lastSample: last,
    lastIndex: last,
    strides: [1, nx, nx * ny],
    majorantGrid:
      hasVolume && gridHasVolume(majorant)
        ? majorant
        : { dimensions: [1, 1, 1], boundsMin: [0, 0, 0], boundsMax: [1, 1, 1], densityScale: 0 },
  };
}

export function mediumDensity(scene: SceneData, medium: SceneMedium, p: Vec3): number {
  if (on(scene, 'gridMedia') && medium.kind === SCENE_MEDIUM_GRID) {
    scene.stats.lookups += 1;
    return sceneGridDensity(scene, sceneGrid(scene, 'grid'), p);
  }
  return 1;
}

/**
 * The scene grid's trilinear density (medium.ts gridDensityTrilinear). The WGSL reads the
 * samples clamped and scaled when uploaded (gridScaledSamples) and blends those, from
 * corners and weights it derives once per invocation (sceneGridLoad); the twin blends
 * scene.density through the same clamp and scales the result: the same value up to f32
 * rounding.
 */
export function sceneGridDensity(scene: SceneData, grid: DensityGrid, p: Vec3): number {
  return gridDensityTrilinear(grid, scene.density, p);
}

export function mediumMajorant(
  scene: SceneData,
  medium: SceneMedium,
  origin: Vec3,
  direction: Vec3,
  segment: readonly [number, number],
): number {
  const sigmaT = maxComponent(add(medium.sigmaA, medium.sigmaS));
  if (on(scene, 'gridMedia') && medium.kind === SCENE_MEDIUM_GRID) {
    // The segment lies in the medium's bounds, which the grid fills.
    const majorant = gridMajorantAlongSegment(
      sceneGrid(scene, 'majorant'),
      scene.majorant,
      origin,
      direction,
      segment,
    );
    if (majorant.capped !== 0) return decoded(scene).records.majorant.maxDensity * sigmaT;
    return majorant.majorant * sigmaT;
  }
  return sigmaT;
}

export function transmittanceBeer(sigmaT: Rgb, distance: number): Rgb {
  return sigmaT.map((s) => transmittanceHomogeneous(s, distance)) as Rgb;
}

export function segmentWalk(
  scene: SceneData,
  medium: SceneMedium,
  origin: Vec3,
  direction: Vec3,
  segment: readonly [number, number],
  majorant: number,
  emit: boolean,
  scatter: boolean,
  points: SegmentPoints,
  state: RngState,
): SegmentWalk {
  const sigmaT = add(medium.sigmaA, medium.sigmaS);
  const count = Math.min(points.count, SEGMENT_MAX_POINTS);
  const walk: SegmentWalk = {
    transmittance: [1, 1, 1],
    emitted: [0, 0, 0],
    scatterT: -1,
    scatterWeight: [0, 0, 0],
  };
  if (on(scene, 'homogeneousClosedForm') && medium.kind === SCENE_MEDIUM_HOMOGENEOUS) {
    const length = segment[1] - segment[0];
    for (let i = 0; i < count; i++)
      points.transmittance[i] = transmittanceBeer(sigmaT, points.t[i]! - segment[0]);
    walk.transmittance = transmittanceBeer(sigmaT, length);
    if (emit) walk.emitted = emissionClosedForm(medium, length);
    if (scatter && length >= TRUNCATED_EXPONENTIAL_MIN_LENGTH) {
      const rate = averageComponent(sigmaT);
      const s = sampleTruncatedExponential(rate, length, rngNextFloat(state));
      walk.scatterT = segment[0] + s;
      walk.scatterWeight = scale(
        mul(transmittanceBeer(sigmaT, s), medium.sigmaS),
        1 / truncatedExponentialPdf(rate, length, s),
      );
    }
    return walk;
  }
  for (let i = 0; i < count; i++) points.transmittance[i] = [1, 1, 1];
  if (!(majorant > 0) || !(segment[1] > segment[0])) return walk;
  // Ratio tracking with collision estimators; a weighted reservoir keeps one collision.
  let reservoir = 0;
  let chosen = 0;
  let t = segment[0];
  for (let steps = 0; ; steps++) {
    const flight = sampleFreeFlight(majorant, rngNextFloat(state));
    if (flight >= segment[1] - t) break;
    if (steps >= TRACKING_MAX_STEPS) {
      scene.stats.capped += 1;
      break;
    }
    t += flight;
    const density = mediumDensity(scene, medium, at(origin, direction, t));
    if (emit)
      walk.emitted = add(
        walk.emitted,
        scale(mul(mul(walk.transmittance, medium.sigmaA), medium.emission), density / majorant),
      );
    if (scatter) {
      const g = scale(mul(walk.transmittance, medium.sigmaS), density / majorant);
      const w = averageComponent(g);
      if (w > 0) {
        reservoir += w;
        if (rngNextFloat(state) * reservoir < w) {
          walk.scatterT = t;
          walk.scatterWeight = g;
          chosen = w;
        }
      }
    }
    const factor = sigmaT.map((s) => Math.max(1 - (density * s) / majorant, 0)) as Rgb;
    walk.transmittance = mul(walk.transmittance, factor);
    for (let i = 0; i < count; i++)
      if (t < points.t[i]!) points.transmittance[i] = mul(points.transmittance[i]!, factor);
    if (allZero(walk.transmittance)) break;
  }
  if (chosen > 0) walk.scatterWeight = scale(walk.scatterWeight, reservoir / chosen);
  return walk;
}

export function sceneSegments(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  tMax: number,
): SegmentList {
  const list: SegmentList = { count: 0, media: [], segments: [] };
  if (!on(scene, 'media')) return list;
  const count = Math.min(sceneHeader(scene)[0], SCENE_MAX_MEDIA);
  const found: { index: number; segment: [number, number] }[] = [];
  for (let i = 0; i < count; i++) {
    const segment = mediumSegment(sceneMedium(scene, i), origin, direction, 0, tMax);
    if (segment[0] < segment[1]) found.push({ index: i, segment });
  }
  // A stable sort by entry: the same order as the shader's insertion sort.
  found.sort((a, b) => a.segment[0] - b.segment[0]);
  for (const f of found) {
    list.media.push(f.index);
    list.segments.push(f.segment);
  }
  list.count = found.length;
  return list;
}

export function closestSurface(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  tMax: number,
): SurfaceHit {
  const hit: SurfaceHit = { t: SURFACE_NO_HIT, index: 0 };
  if (!on(scene, 'surfaces')) return hit;
  const count = Math.min(sceneHeader(scene)[2], SCENE_MAX_SURFACES);
  for (let i = 0; i < count; i++) {
    const t = surfaceHitDistance(
      sceneSurface(scene, i),
      origin,
      direction,
      0,
      Math.min(tMax, hit.t),
    );
    if (t < hit.t) {
      hit.t = t;
      hit.index = i;
    }
  }
  return hit;
}

export function sceneTransmittance(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  tMax: number,
  state: RngState,
): Rgb {
  let transmittance: Rgb = [1, 1, 1];
  if (!on(scene, 'media')) return transmittance;
  const count = Math.min(sceneHeader(scene)[0], SCENE_MAX_MEDIA);
  for (let i = 0; i < count; i++) {
    const medium = sceneMedium(scene, i);
    const segment = mediumSegment(medium, origin, direction, 0, tMax);
    if (segment[0] < segment[1]) {
      transmittance = mul(
        transmittance,
        segmentTransmittance(scene, medium, origin, direction, segment, state),
      );
      if (allZero(transmittance)) return transmittance;
    }
  }
  return transmittance;
}

/**
 * The transmittance of one medium's segment (integrator.wesl segmentTransmittance):
 * segmentWalk's transmittance without emission, scattering or view points (the same
 * draws, lookups and caps): Beer's law under the closed form for a homogeneous medium,
 * else ratio tracking with the segment's majorant.
 */
export function segmentTransmittance(
  scene: SceneData,
  medium: SceneMedium,
  origin: Vec3,
  direction: Vec3,
  segment: readonly [number, number],
  state: RngState,
): Rgb {
  const sigmaT = add(medium.sigmaA, medium.sigmaS);
  if (on(scene, 'homogeneousClosedForm') && medium.kind === SCENE_MEDIUM_HOMOGENEOUS)
    return transmittanceBeer(sigmaT, segment[1] - segment[0]);
  let transmittance: Rgb = [1, 1, 1];
  const majorant = mediumMajorant(scene, medium, origin, direction, segment);
  if (!(majorant > 0) || !(segment[1] > segment[0])) return transmittance;
  let t = segment[0];
  for (let steps = 0; ; steps++) {
    const flight = sampleFreeFlight(majorant, rngNextFloat(state));
    if (flight >= segment[1] - t) break;
    if (steps >= TRACKING_MAX_STEPS) {
      scene.stats.capped += 1;
      break;
    }
    t += flight;
    const density = mediumDensity(scene, medium, at(origin, direction, t));
    transmittance = transmittance.map(
      (x, c) => Math.max(1 - (density * sigmaT[c]!) / majorant, 0) * x,
    ) as Rgb;
    if (allZero(transmittance)) break;
  }
  return transmittance;
}

export function shadowTransmittance(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  distance: number,
  state: RngState,
): Rgb {
  if (
    on(scene, 'surfaces') &&
    closestSurface(scene, origin, direction, distance).t < SURFACE_NO_HIT
  )
    return [0, 0, 0];
  return sceneTransmittance(scene, origin, direction, distance, state);
}

/**
 * Table `index` of the scene's phase-table buffer, as integrator.wesl's private copy
 * scenePhaseTable after scenePhaseTableLoad (the f32 words widened to f64, memoised; the
 * tabulated entries' twins read it the same way).
 */
export function scenePhaseTableLoad(scene: SceneData, index: number): PhaseTable {
  return phaseTableAt(scene.phaseTables, index);
}

/** The medium's phase function (src/phase/registry.ts), as the kernel's conditions allow. */
export function mediumPhaseEval(scene: SceneData, medium: SceneMedium, wo: Vec3, wi: Vec3): number {
  return dispatchedPhase(medium.phase.kind, scene.conditions).twin.eval(
    medium.phase,
    wo,
    wi,
    scene.phaseTables,
  );
}

export function mediumPhaseSample(
  scene: SceneData,
  medium: SceneMedium,
  wo: Vec3,
  u: readonly [number, number],
): Vec3 {
  return dispatchedPhase(medium.phase.kind, scene.conditions).twin.sample(
    medium.phase,
    wo,
    u,
    scene.phaseTables,
  );
}

const NO_LIGHT: LightSample = { direction: [0, 0, 1], distance: 0, irradiance: [0, 0, 0] };

export function deltaLightSample(scene: SceneData, light: Light, p: Vec3): LightSample {
  if (on(scene, 'lightDirectional') && light.kind === LIGHT_DIRECTIONAL)
    return lightSampleDirectional(light);
  if (on(scene, 'lightPoint') && light.kind === LIGHT_POINT) return lightSamplePoint(light, p);
  if (on(scene, 'lightSpot') && light.kind === LIGHT_SPOT) return lightSampleSpot(light, p);
  return NO_LIGHT;
}

export function environmentRadiance(scene: SceneData): Rgb {
  let radiance: Rgb = [0, 0, 0];
  const count = Math.min(sceneHeader(scene)[1], SCENE_MAX_LIGHTS);
  for (let i = 0; i < count; i++) {
    const light = sceneLight(scene, i);
    if (light.kind === LIGHT_ENVIRONMENT)
      radiance = add(radiance, light.value.map((v) => Math.max(v, 0)) as Rgb);
  }
  return radiance;
}

export function mediumVertex(p: Vec3, direction: Vec3, medium: number, lights: number): Vertex {
  return {
    position: p,
    kind: VERTEX_MEDIUM,
    wo: neg(direction),
    medium,
    normal: [0, 0, 1],
    lights,
    albedo: [0, 0, 0],
  };
}

export function surfaceVertex(surface: Surface, origin: Vec3, direction: Vec3, t: number): Vertex {
  const p = at(origin, direction, t);
  const normal = surfaceNormalFacing(surface, p, direction);
  return {
    position: surfaceOffsetOrigin(p, normal),
    kind: VERTEX_SURFACE,
    wo: neg(direction),
    medium: 0,
    normal,
    lights: VERTEX_LIGHTS_ALL,
    albedo: surface.albedo,
  };
}

export function vertexDirectLighting(scene: SceneData, vertex: Vertex, state: RngState): Rgb {
  let radiance: Rgb = [0, 0, 0];
  if (!(on(scene, 'lightDirectional') || on(scene, 'lightPoint') || on(scene, 'lightSpot')))
    return radiance;
  const count = Math.min(sceneHeader(scene)[1], SCENE_MAX_LIGHTS);
  for (let i = 0; i < count; i++) {
    const light = sceneLight(scene, i);
    const local = light.kind === LIGHT_POINT || light.kind === LIGHT_SPOT;
    if (
      (vertex.lights === VERTEX_LIGHTS_DISTANT && local) ||
      (vertex.lights < SCENE_MAX_LIGHTS && i !== vertex.lights)
    )
      continue;
    const sample = deltaLightSample(scene, light, vertex.position);
    let response: Rgb = [0, 0, 0];
    if (vertex.kind === VERTEX_SURFACE) {
      if (on(scene, 'surfaceScattering'))
        response = scale(
          lambertianBrdf(vertex.albedo) as Rgb,
          Math.max(dot(vertex.normal, sample.direction), 0),
        );
    } else if (on(scene, 'volumeScattering')) {
      const p = mediumPhaseEval(
        scene,
        sceneMedium(scene, vertex.medium),
        vertex.wo,
        sample.direction,
      );
      response = [p, p, p];
    }
    const unshadowed = mul(response, sample.irradiance as Rgb);
    if (anyPositive(unshadowed)) {
      const shadow = shadowTransmittance(
        scene,
        vertex.position,
        sample.direction,
        sample.distance,
        state,
      );
      radiance = add(radiance, mul(unshadowed, shadow));
    }
  }
  return radiance;
}

export function vertexSampleDirection(
  scene: SceneData,
  vertex: Vertex,
  u: readonly [number, number],
): Vec3 {
  if (vertex.kind === VERTEX_SURFACE) return sampleCosineHemisphere(vertex.normal, u);
  return mediumPhaseSample(scene, sceneMedium(scene, vertex.medium), vertex.wo, u);
}

export function vertexScatterWeight(vertex: Vertex): Rgb {
  return vertex.kind === VERTEX_SURFACE ? clampRgb(vertex.albedo as Rgb) : [1, 1, 1];
}

/** Segments shorter than the smallest normal f32 are empty (the GPU may flush them to 0). */
export const TRUNCATED_EXPONENTIAL_MIN_LENGTH = 2 ** -126;

/**
 * Inverse CDF of the truncated exponential: s = −ln(1 − u(1 − e^{−kL}))/k, with u clamped
 * to [0, 1 − 2^-24] as in the shader; an empty segment (L < 2^-126, also L ≤ 0) gives 0.
 */
export function sampleTruncatedExponential(rate: number, length: number, u: number): number {
  if (!(length >= TRUNCATED_EXPONENTIAL_MIN_LENGTH)) return 0;
  const k = Math.max(rate, 0);
  const xi = Math.min(Math.max(u, 0), 1 - 2 ** -24);
  if (k === 0) return xi * length;
  return Math.min(Math.max(-Math.log1p(xi * Math.expm1(-k * length)) / k, 0), length);
}

/**
 * k e^{−ks}/(1 − e^{−kL}) on [0, L], the uniform 1/L when k = 0, 0 outside the support
 * (L ≤ 0, s < 0, s > L); capped at the largest f32 like the shader's saturating division.
 */
export function truncatedExponentialPdf(rate: number, length: number, s: number): number {
  if (!(length >= TRUNCATED_EXPONENTIAL_MIN_LENGTH) || s < 0 || s > length) return 0;
  const k = Math.max(rate, 0);
  const density = k === 0 ? 1 / length : (k * Math.exp(-k * s)) / -Math.expm1(-k * length);
  return Math.min(density, F32_MAX);
}

export function mediumEmits(scene: SceneData, medium: SceneMedium): boolean {
  return on(scene, 'emission') && anyPositive(medium.emission) && anyPositive(medium.sigmaA);
}

/** ∫₀^L e^{−σt s} σa Le ds = (σa/σt)(1 − e^{−σt L}) Le, written with expm1 (σt = 0: σa L Le). */
export function emissionClosedForm(medium: SceneMedium, length: number): Rgb {
  return medium.sigmaA.map((a, c) => {
    const sigmaT = a + medium.sigmaS[c]!;
    const integral = sigmaT > 0 ? -Math.expm1(-sigmaT * length) / sigmaT : length;
    return a * integral * medium.emission[c]!;
  }) as Rgb;
}

const emptyPoints = (): SegmentPoints => ({ count: 0, t: [], transmittance: [] });

export function estimateEmissionAbsorption(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  state: RngState,
): Rgb {
  let radiance: Rgb = [0, 0, 0];
  if (!(on(scene, 'emission') || on(scene, 'lightEnvironment'))) return radiance;
  const hit = closestSurface(scene, origin, direction, RAY_T_LIMIT);
  const list = sceneSegments(scene, origin, direction, Math.min(hit.t, RAY_T_LIMIT));
  let transmittance: Rgb = [1, 1, 1];
  for (let k = 0; k < list.count; k++) {
    const medium = sceneMedium(scene, list.media[k]!);
    const segment = list.segments[k]!;
    const majorant = mediumMajorant(scene, medium, origin, direction, segment);
    const emits = mediumEmits(scene, medium);
    const walk = segmentWalk(
      scene,
      medium,
      origin,
      direction,
      segment,
      majorant,
      emits,
      false,
      emptyPoints(),
      state,
    );
    radiance = add(radiance, mul(transmittance, walk.emitted));
    transmittance = mul(transmittance, walk.transmittance);
  }
  if (on(scene, 'lightEnvironment') && hit.t === SURFACE_NO_HIT)
    radiance = add(radiance, mul(transmittance, environmentRadiance(scene)));
  return radiance;
}

export function equiangularSegmentSample(
  position: Vec3,
  origin: Vec3,
  direction: Vec3,
  segment: readonly [number, number],
  xi: number,
): [number, number] {
  const tClosest = dot(
    [position[0] - origin[0], position[1] - origin[1], position[2] - origin[2]],
    direction,
  );
  const closest = at(origin, direction, tClosest);
  const h = Math.hypot(
    closest[0] - position[0],
    closest[1] - position[1],
    closest[2] - position[2],
  );
  const thetaA = Math.atan2(segment[0] - tClosest, h);
  const thetaB = Math.atan2(segment[1] - tClosest, h);
  const [t, pdf] = equiangularSample(h, thetaA, thetaB, xi);
  if (!(pdf > 0))
    return [
      segment[0] + xi * (segment[1] - segment[0]),
      // 1/(t1 − t0), capped at the largest f32 like the shader (an empty segment gives it).
      segment[1] > segment[0] ? Math.min(1 / (segment[1] - segment[0]), F32_MAX) : F32_MAX,
    ];
  return [Math.min(Math.max(tClosest + t, segment[0]), segment[1]), pdf];
}

export function estimateSingleScattering(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  state: RngState,
): Rgb {
  const firstOrder = sceneHeader(scene)[3] >= 1;
  const equiangular = on(scene, 'equiangular');
  const secondary = on(scene, 'lightEnvironment') || on(scene, 'emission');
  const hit = closestSurface(scene, origin, direction, RAY_T_LIMIT);
  const list = sceneSegments(scene, origin, direction, Math.min(hit.t, RAY_T_LIMIT));
  let radiance: Rgb = [0, 0, 0];
  let transmittance: Rgb = [1, 1, 1];
  for (let k = 0; k <= list.count; k++) {
    // The segment's vertices: t, weight (in points.transmittance) and the lights each takes.
    const points = emptyPoints();
    const pdf: number[] = [];
    const lights: number[] = [];
    let vertices = 0;
    let segmentT: Rgb = [1, 1, 1];
    if (k < list.count) {
      const medium = sceneMedium(scene, list.media[k]!);
      const segment = list.segments[k]!;
      const majorant = mediumMajorant(scene, medium, origin, direction, segment);
      const scatters = on(scene, 'volumeScattering') && firstOrder && anyPositive(medium.sigmaS);
      // Equiangular points in homogeneous media only (the shader's comment says why).
      const local = equiangular && scatters && medium.kind === SCENE_MEDIUM_HOMOGENEOUS;
      const sharedLights = local ? VERTEX_LIGHTS_DISTANT : VERTEX_LIGHTS_ALL;
      if (local) {
        const count = Math.min(sceneHeader(scene)[1], SCENE_MAX_LIGHTS);
        for (let i = 0; i < count; i++) {
          const light = sceneLight(scene, i);
          if (light.kind !== LIGHT_POINT && light.kind !== LIGHT_SPOT) continue;
          const [t, p] = equiangularSegmentSample(
            light.position,
            origin,
            direction,
            segment,
            rngNextFloat(state),
          );
          points.t.push(t);
          pdf.push(p);
          lights.push(i);
          points.count += 1;
        }
      }
      const walk = segmentWalk(
        scene,
        medium,
        origin,
        direction,
        segment,
        majorant,
        mediumEmits(scene, medium),
        scatters,
        points,
        state,
      );
      radiance = add(radiance, mul(transmittance, walk.emitted));
      segmentT = walk.transmittance;
      for (let i = 0; i < points.count; i++) {
        const density = mediumDensity(scene, medium, at(origin, direction, points.t[i]!));
        points.transmittance[i] = scale(
          mul(mul(transmittance, points.transmittance[i]!), medium.sigmaS),
          density / pdf[i]!,
        );
      }
      vertices = points.count;
      if (walk.scatterT >= 0) {
        points.t[vertices] = walk.scatterT;
        points.transmittance[vertices] = mul(transmittance, walk.scatterWeight);
        lights[vertices] = sharedLights;
        vertices += 1;
      }
    } else if (hit.t === SURFACE_NO_HIT) {
      if (on(scene, 'lightEnvironment'))
        radiance = add(radiance, mul(transmittance, environmentRadiance(scene)));
    } else if (on(scene, 'surfaceScattering') && firstOrder) {
      vertices = 1;
    }
    for (let i = 0; i < vertices; i++) {
      let vertex: Vertex;
      let weight = transmittance;
      if (k < list.count) {
        vertex = mediumVertex(
          at(origin, direction, points.t[i]!),
          direction,
          list.media[k]!,
          lights[i]!,
        );
        weight = points.transmittance[i]!;
      } else {
        vertex = surfaceVertex(sceneSurface(scene, hit.index), origin, direction, hit.t);
      }
      radiance = add(radiance, mul(weight, vertexDirectLighting(scene, vertex, state)));
      if (secondary && vertex.lights >= SCENE_MAX_LIGHTS) {
        const wi = vertexSampleDirection(scene, vertex, [rngNextFloat(state), rngNextFloat(state)]);
        const arriving = estimateEmissionAbsorption(scene, vertex.position, wi, state);
        radiance = add(radiance, mul(mul(weight, vertexScatterWeight(vertex)), arriving));
      }
    }
    transmittance = mul(transmittance, segmentT);
  }
  return radiance;
}

export function mediumFreeFlight(
  scene: SceneData,
  medium: SceneMedium,
  origin: Vec3,
  direction: Vec3,
  segment: readonly [number, number],
  throughput: Rgb,
  state: RngState,
): FreeFlight {
  const flight: FreeFlight = {
    t: segment[1],
    event: FLIGHT_PASSED,
    weight: [...throughput],
    emitted: [0, 0, 0],
  };
  const majorant = mediumMajorant(scene, medium, origin, direction, segment);
  if (!(majorant > 0)) return flight;
  const emission = on(scene, 'emission');
  // A real collision at t ends the flight there.
  const end = (t: number, event: number, weight: Rgb): FreeFlight => ({
    ...flight,
    t,
    event,
    weight,
  });
  let t = segment[0];
  for (let steps = 0; ; steps++) {
    const step = sampleFreeFlight(majorant, rngNextFloat(state));
    if (step >= segment[1] - t) return flight;
    if (steps >= TRACKING_MAX_STEPS) {
      scene.stats.capped += 1;
      return flight;
    }
    t += step;
    const density = mediumDensity(scene, medium, at(origin, direction, t));
    if (on(scene, 'grayMedia') && !emission) {
      // Gray σa, σs: the general test below in scalars (integrator.wesl mediumFreeFlight),
      // except that a throughput of 0 goes on rather than being absorbed.
      const sigmaT = density * (medium.sigmaA[0] + medium.sigmaS[0]);
      const real = rngNextFloat(state) * majorant < sigmaT || sigmaT >= majorant;
      if (real && !(medium.sigmaS[0] > 0)) return end(t, FLIGHT_ABSORBED, flight.weight);
      if (real)
        return end(
          t,
          FLIGHT_SCATTERED,
          scale(flight.weight, medium.sigmaS[0] / (medium.sigmaA[0] + medium.sigmaS[0])),
        );
      continue;
    }
    const sigmaA = scale(medium.sigmaA, density);
    const sigmaS = scale(medium.sigmaS, density);
    const sigmaN = sigmaA.map((a, c) => Math.max(majorant - a - sigmaS[c]!, 0)) as Rgb;
    if (emission)
      flight.emitted = add(
        flight.emitted,
        scale(mul(mul(flight.weight, sigmaA), medium.emission), 1 / majorant),
      );
    const pa = averageComponent(mul(sigmaA, flight.weight));
    const ps = averageComponent(mul(sigmaS, flight.weight));
    const pn = averageComponent(mul(sigmaN, flight.weight));
    const total = pa + ps + pn;
    const xi = rngNextFloat(state) * total;
    // A real collision scatters with the albedo as weight; it absorbs only where nothing
    // scatters (integrator.wesl mediumFreeFlight).
    const real = xi < pa + ps || pn <= 0;
    if (!(total > 0) || (real && !(ps > 0))) return end(t, FLIGHT_ABSORBED, flight.weight);
    if (real)
      return end(
        t,
        FLIGHT_SCATTERED,
        scale(mul(flight.weight, sigmaS), total / (majorant * (pa + ps))),
      );
    flight.weight = scale(mul(flight.weight, sigmaN), total / (majorant * pn));
  }
}

/**
 * A path of the path tracers between two of its segments (integrator.wesl TracedPath):
 * where it stands and where it goes, its order and segment count, its throughput and the
 * radiance gathered so far. The kernel advances one a segment at a time (path regeneration).
 */
export interface TracedPath {
  origin: Vec3;
  order: number;
  direction: Vec3;
  segments: number;
  weight: Rgb;
  radiance: Rgb;
}

export function tracedPathStart(origin: Vec3, direction: Vec3): TracedPath {
  return { origin, order: 0, direction, segments: 0, weight: [1, 1, 1], radiance: [0, 0, 0] };
}

/**
 * One segment of the volumetric path tracer (integrator.wesl pathTracingStep): free flights
 * through the media in order, then at a scattering event (medium or surface) next-event
 * estimation, a sampled direction and Russian roulette. True when the path has ended.
 */
export function pathTracingStep(scene: SceneData, path: TracedPath, state: RngState): boolean {
  path.segments += 1;
  const rayOrigin = path.origin;
  const rayDirection = path.direction;
  const hit = closestSurface(scene, rayOrigin, rayDirection, RAY_T_LIMIT);
  const list = sceneSegments(scene, rayOrigin, rayDirection, Math.min(hit.t, RAY_T_LIMIT));
  let event = FLIGHT_PASSED;
  let eventT = 0;
  let eventMedium = 0;
  for (let k = 0; k < list.count; k++) {
    const flight = mediumFreeFlight(
      scene,
      sceneMedium(scene, list.media[k]!),
      rayOrigin,
      rayDirection,
      list.segments[k]!,
      path.weight,
      state,
    );
    if (on(scene, 'emission')) path.radiance = add(path.radiance, flight.emitted);
    path.weight = flight.weight;
    if (flight.event !== FLIGHT_PASSED) {
      event = flight.event;
      eventT = flight.t;
      eventMedium = list.media[k]!;
      break;
    }
  }
  if (event === FLIGHT_ABSORBED) return true;
  if (event === FLIGHT_PASSED && hit.t === SURFACE_NO_HIT) {
    if (on(scene, 'lightEnvironment'))
      path.radiance = add(path.radiance, mul(path.weight, environmentRadiance(scene)));
    return true;
  }
  path.order += 1;
  if (path.order > sceneHeader(scene)[3]) return true;
  let vertex: Vertex;
  if (event === FLIGHT_SCATTERED) {
    if (!on(scene, 'volumeScattering')) return true;
    vertex = mediumVertex(
      at(rayOrigin, rayDirection, eventT),
      rayDirection,
      eventMedium,
      VERTEX_LIGHTS_ALL,
    );
  } else {
    if (!on(scene, 'surfaceScattering')) return true;
    vertex = surfaceVertex(sceneSurface(scene, hit.index), rayOrigin, rayDirection, hit.t);
  }
  path.radiance = add(path.radiance, mul(path.weight, vertexDirectLighting(scene, vertex, state)));
  path.weight = mul(path.weight, vertexScatterWeight(vertex));
  path.direction = vertexSampleDirection(scene, vertex, [rngNextFloat(state), rngNextFloat(state)]);
  path.origin = vertex.position;
  return tracedPathRoulette(scene, path, state);
}

/**
 * The end of a path tracer's segment after its vertex (integrator.wesl tracedPathRoulette):
 * from the ROULETTE_START_ORDER-th scattering on, Russian roulette with survival
 * q = min(1, max channel of w), survivors w /= q, the number drawn only when it plays;
 * then the cap of PATH_MAX_VERTICES segments (counted). True when the path ends here.
 */
export function tracedPathRoulette(scene: SceneData, path: TracedPath, state: RngState): boolean {
  const survival = Math.min(maxComponent(path.weight), 1);
  if (survival < 1 && path.order >= ROULETTE_START_ORDER) {
    if (!(rngNextFloat(state) < survival)) return true;
    path.weight = scale(path.weight, 1 / survival);
  }
  if (path.segments >= PATH_MAX_VERTICES) {
    scene.stats.capped += 1;
    return true;
  }
  return false;
}

/** Volumetric path tracing of a camera ray, segment by segment (pathTracingStep). */
export function estimatePathTracing(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  state: RngState,
): Rgb {
  const path = tracedPathStart(origin, direction);
  while (!pathTracingStep(scene, path, state));
  return path.radiance;
}

// The one-medium estimators (plan condition oneHomogeneousMedium: one homogeneous medium
// under delta lights, nothing else in the scene). Written from the closed forms of
// physics.md §5 and the path-tracing recursion, not from the general code: at a point x
// of the medium, next-event estimation gives Σ_ℓ p(ω_o, ω_ℓ) E_ℓ e^{−σt d_ℓ}, with d_ℓ
// the length of the shadow ray inside the medium. They must draw the same random
// numbers, in the same order, as the general estimators for such a scene, and
// tests/reference/scene-one-medium.test.ts holds the two equal sample by sample.

export function oneMediumDirectLighting(
  scene: SceneData,
  medium: SceneMedium,
  position: Vec3,
  wo: Vec3,
  state: RngState,
): Rgb {
  // The kernel drops the loop under the plan's oneLight; one light gives the same sum.
  let radiance: Rgb = [0, 0, 0];
  const count = Math.min(sceneHeader(scene)[1], SCENE_MAX_LIGHTS);
  for (let i = 0; i < count; i++)
    radiance = add(
      radiance,
      oneMediumLightContribution(scene, medium, sceneLight(scene, i), position, wo, state),
    );
  return radiance;
}

/**
 * One light's term of oneMediumDirectLighting, p(ωo, ωℓ)·Eℓ·Tℓ. The kernel evaluates
 * Beer's law without branches (an empty segment has d = 0, T = 1); the result is the same.
 */
export function oneMediumLightContribution(
  scene: SceneData,
  medium: SceneMedium,
  light: Light,
  position: Vec3,
  wo: Vec3,
  state: RngState,
): Rgb {
  const sample = deltaLightSample(scene, light, position);
  // A surface between the point and the light blocks it (shadowTransmittance).
  if (
    on(scene, 'surfaces') &&
    closestSurface(scene, position, sample.direction, sample.distance).t < SURFACE_NO_HIT
  )
    return [0, 0, 0];
  const phase = mediumPhaseEval(scene, medium, wo, sample.direction);
  const unshadowed = sample.irradiance.map((e) => e * phase) as Rgb;
  if (!anyPositive(unshadowed)) return [0, 0, 0];
  const segment = oneMediumSegmentFrom(medium, position, sample.direction, sample.distance);
  const shadow: Rgb =
    segment[0] < segment[1]
      ? segmentTransmittance(scene, medium, position, sample.direction, segment, state)
      : [1, 1, 1];
  return mul(unshadowed, shadow);
}

/**
 * Single scattering in one homogeneous medium, among surfaces if the scene has them: the
 * view ray stops at the closest surface, the medium's part is oneMediumScatteredAlong and
 * the surface's point is lit by vertexDirectLighting through T of the medium's part;
 * estimateSingleScattering's vertices, random numbers and order for this scene.
 */
export function estimateSingleScatteringOneMedium(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  state: RngState,
): Rgb {
  const medium = sceneMedium(scene, 0);
  const hit: SurfaceHit = on(scene, 'surfaces')
    ? closestSurface(scene, origin, direction, RAY_T_LIMIT)
    : { t: SURFACE_NO_HIT, index: 0 };
  const segment = mediumSegment(medium, origin, direction, 0, Math.min(hit.t, RAY_T_LIMIT));
  const radiance = oneMediumScatteredAlong(scene, medium, origin, direction, segment, state);
  if (!on(scene, 'surfaceScattering') || !(hit.t < SURFACE_NO_HIT) || sceneHeader(scene)[3] < 1)
    return radiance;
  // An empty medium segment (the ray misses the medium) lets everything through.
  const crossed = segment[0] < segment[1] ? segment[1] - segment[0] : 0;
  const vertex = surfaceVertex(sceneSurface(scene, hit.index), origin, direction, hit.t);
  return add(
    radiance,
    mul(
      transmittanceBeer(add(medium.sigmaA, medium.sigmaS), crossed),
      oneMediumSurfaceLighting(scene, medium, vertex),
    ),
  );
}

/**
 * vertexDirectLighting at a surface vertex of the one-medium kernel: every delta light's
 * (ρ/π)·max(0, n·ω)·E, blocked by any surface before the light and seen through Beer's law
 * over the shadow ray's part in the medium.
 */
export function oneMediumSurfaceLighting(
  scene: SceneData,
  medium: SceneMedium,
  vertex: Vertex,
): Rgb {
  let radiance: Rgb = [0, 0, 0];
  if (!(on(scene, 'lightDirectional') || on(scene, 'lightPoint') || on(scene, 'lightSpot')))
    return radiance;
  const sigmaT = add(medium.sigmaA, medium.sigmaS);
  const count = Math.min(sceneHeader(scene)[1], SCENE_MAX_LIGHTS);
  for (let i = 0; i < count; i++) {
    const sample = deltaLightSample(scene, sceneLight(scene, i), vertex.position);
    const unshadowed = mul(
      scale(
        lambertianBrdf(vertex.albedo) as Rgb,
        Math.max(dot(vertex.normal, sample.direction), 0),
      ),
      sample.irradiance as Rgb,
    );
    if (
      !anyPositive(unshadowed) ||
      closestSurface(scene, vertex.position, sample.direction, sample.distance).t < SURFACE_NO_HIT
    )
      continue;
    const segment = mediumSegment(medium, vertex.position, sample.direction, 0, sample.distance);
    radiance = add(
      radiance,
      mul(unshadowed, transmittanceBeer(sigmaT, Math.max(segment[1] - segment[0], 0))),
    );
  }
  return radiance;
}

/**
 * The medium's part of estimateSingleScatteringOneMedium on the view segment [t₀, t₁]: one
 * point t = t₀ + s, s drawn from the exponential of the mean σt truncated to the segment's
 * length, weighted T(s)·σs / pdf(s) and lit by oneMediumDirectLighting. With the plan's
 * equiangular sampling, each point or spot light first gets its own equiangular point, lit
 * by it alone (oneMediumEquiangularPoint), and the free-flight point takes the distant
 * lights only: estimateSingleScattering's vertices for this scene, in its order.
 */
export function oneMediumScatteredAlong(
  scene: SceneData,
  medium: SceneMedium,
  origin: Vec3,
  direction: Vec3,
  segment: readonly [number, number],
  state: RngState,
): Rgb {
  const [enter, exit] = segment;
  const length = exit - enter;
  const scatters = sceneHeader(scene)[3] >= 1 && anyPositive(medium.sigmaS);
  const equiangular = on(scene, 'equiangular');
  if (!(enter < exit) || !scatters) return [0, 0, 0];
  if (!equiangular && length < TRUNCATED_EXPONENTIAL_MIN_LENGTH) return [0, 0, 0];
  const count = Math.min(sceneHeader(scene)[1], SCENE_MAX_LIGHTS);
  const local = (light: Light): boolean => light.kind === LIGHT_POINT || light.kind === LIGHT_SPOT;
  let radiance: Rgb = [0, 0, 0];
  if (equiangular)
    for (let i = 0; i < count; i++) {
      const light = sceneLight(scene, i);
      if (local(light))
        radiance = add(
          radiance,
          oneMediumEquiangularPoint(scene, medium, light, origin, direction, segment, state),
        );
    }
  if (length < TRUNCATED_EXPONENTIAL_MIN_LENGTH) return radiance;
  const sigmaT = add(medium.sigmaA, medium.sigmaS);
  const rate = averageComponent(sigmaT);
  const s = sampleTruncatedExponential(rate, length, rngNextFloat(state));
  const weight = scale(
    mul(transmittanceBeer(sigmaT, s), medium.sigmaS),
    1 / truncatedExponentialPdf(rate, length, s),
  );
  const position = at(origin, direction, enter + s);
  if (!equiangular)
    return mul(weight, oneMediumDirectLighting(scene, medium, position, neg(direction), state));
  let distant: Rgb = [0, 0, 0];
  for (let i = 0; i < count; i++) {
    const light = sceneLight(scene, i);
    if (!local(light))
      distant = add(
        distant,
        oneMediumLightContribution(scene, medium, light, position, neg(direction), state),
      );
  }
  return add(radiance, mul(weight, distant));
}

/**
 * The equiangular point of one point or spot light on the view segment (integrator.wesl
 * oneMediumEquiangularPoint): t from equiangularSegmentSample, weighted T(t − t₀)·σs / p(t)
 * and lit by that light alone.
 */
export function oneMediumEquiangularPoint(
  scene: SceneData,
  medium: SceneMedium,
  light: Light,
  origin: Vec3,
  direction: Vec3,
  segment: readonly [number, number],
  state: RngState,
): Rgb {
  const [t, pdf] = equiangularSegmentSample(
    light.position,
    origin,
    direction,
    segment,
    rngNextFloat(state),
  );
  const sigmaT = add(medium.sigmaA, medium.sigmaS);
  const weight = scale(mul(transmittanceBeer(sigmaT, t - segment[0]), medium.sigmaS), 1 / pdf);
  return mul(
    weight,
    oneMediumLightContribution(
      scene,
      medium,
      light,
      at(origin, direction, t),
      neg(direction),
      state,
    ),
  );
}

/**
 * One segment of the one-medium path tracer (integrator.wesl oneMediumPathStep): a free
 * flight (mediumFreeFlight), and at a scattering event next-event estimation
 * (oneMediumDirectLighting), phase sampling and Russian roulette; a path that leaves the
 * medium escapes (the scene has no environment and no surface). True when it has ended.
 */
export function oneMediumPathStep(scene: SceneData, path: TracedPath, state: RngState): boolean {
  const medium = oneMediumLoad(scene).medium;
  path.segments += 1;
  const segment = mediumSegment(medium, path.origin, path.direction, 0, RAY_T_LIMIT);
  if (!(segment[0] < segment[1])) return true;
  const flight = mediumFreeFlight(
    scene,
    medium,
    path.origin,
    path.direction,
    segment,
    path.weight,
    state,
  );
  path.weight = flight.weight;
  if (flight.event !== FLIGHT_SCATTERED) return true;
  path.order += 1;
  if (path.order > sceneHeader(scene)[3]) return true;
  const position = at(path.origin, path.direction, flight.t);
  const wo = neg(path.direction);
  path.radiance = add(
    path.radiance,
    mul(path.weight, oneMediumDirectLighting(scene, medium, position, wo, state)),
  );
  path.direction = mediumPhaseSample(scene, medium, wo, [rngNextFloat(state), rngNextFloat(state)]);
  path.origin = position;
  return tracedPathRoulette(scene, path, state);
}

/** Volumetric path tracing in one medium (homogeneous or grid), segment by segment. */
export function estimatePathTracingOneMedium(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  state: RngState,
): Rgb {
  const path = tracedPathStart(origin, direction);
  while (!oneMediumPathStep(scene, path, state));
  return path.radiance;
}

/** One segment of the path tracer the plan linked (integrator.wesl tracedPathStep). */
export function tracedPathStep(scene: SceneData, path: TracedPath, state: RngState): boolean {
  return on(scene, 'oneHomogeneousMedium') || on(scene, 'oneGridMedium')
    ? oneMediumPathStep(scene, path, state)
    : pathTracingStep(scene, path, state);
}

export function estimateRadiance(
  scene: SceneData,
  origin: Vec3,
  direction: Vec3,
  state: RngState,
): Rgb {
  const oneMedium = on(scene, 'oneHomogeneousMedium');
  if (on(scene, 'pathTracing'))
    return oneMedium || on(scene, 'oneGridMedium')
      ? estimatePathTracingOneMedium(scene, origin, direction, state)
      : estimatePathTracing(scene, origin, direction, state);
  if (on(scene, 'volumeScattering') && oneMedium)
    return estimateSingleScatteringOneMedium(scene, origin, direction, state);
  if (on(scene, 'volumeScattering') || on(scene, 'surfaceScattering'))
    return estimateSingleScattering(scene, origin, direction, state);
  return estimateEmissionAbsorption(scene, origin, direction, state);
}
