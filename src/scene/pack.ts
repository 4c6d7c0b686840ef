// Packing a resolved scene into what the renderer kernel reads (shaders/integrator.wesl):
// SCENE_RECORDS records of four 32-bit words (header, camera, grid, majorant grid,
// media, lights, surfaces; integers stored as their u32 bits), and the grid's density
// and majorant samples for two r32float 3D textures. The same words, read back as f32,
// are the twin's SceneData, so the CPU renderer sees exactly the GPU's (f32) scene.
import {
  SCENE_BOUNDS_BOX,
  SCENE_BOUNDS_SPHERE,
  SCENE_CAMERA_RECORD,
  SCENE_GRID_RECORD,
  SCENE_LIGHTS_RECORD,
  SCENE_MAJORANT_RECORD,
  SCENE_MEDIA_RECORD,
  SCENE_MEDIUM_GRID,
  SCENE_MEDIUM_HOMOGENEOUS,
  SCENE_MEDIUM_PHASE,
  SCENE_ORDER_UNLIMITED,
  SCENE_RECORDS,
  SCENE_SURFACES_RECORD,
  type SceneData,
} from '../reference/integrator.ts';
import { CAMERA_ORTHOGRAPHIC, CAMERA_PERSPECTIVE } from '../reference/camera.ts';
import {
  LIGHT_DIRECTIONAL,
  LIGHT_ENVIRONMENT,
  LIGHT_POINT,
  LIGHT_SPOT,
} from '../reference/lights.ts';
import type { DensityGridData } from '../reference/medium.ts';
import { SURFACE_BOX, SURFACE_PLANE, SURFACE_SPHERE } from '../reference/surfaces.ts';
import { packPhase } from '../phase/registry.ts';
import type { ResolvedScene } from './load.ts';
import type { Conditions } from './plan.ts';

export interface PackedScene {
  /** SCENE_RECORDS·4 words; f32 and u32 views of one buffer. */
  records: Float32Array<ArrayBuffer>;
  words: Uint32Array<ArrayBuffer>;
  /** The density grid and its majorant grid (1×1×1 zero grids when the scene has none). */
  density: DensityGridData;
  majorant: DensityGridData;
  width: number;
  height: number;
  seed: number;
}

const EMPTY_GRID: DensityGridData = {
  grid: { dimensions: [1, 1, 1], boundsMin: [0, 0, 0], boundsMax: [1, 1, 1], densityScale: 0 },
  volume: new Float32Array(1),
};

export function packScene(resolved: ResolvedScene): PackedScene {
  const { scene, grid } = resolved;
  const buffer = new ArrayBuffer(SCENE_RECORDS * 16);
  const records = new Float32Array(buffer);
  const words = new Uint32Array(buffer);
  const put = (record: number, k: number, values: readonly number[]): void => {
    values.forEach((v, i) => (records[4 * record + k + i] = v));
  };
  const putWord = (record: number, k: number, value: number): void => {
    words[4 * record + k] = value >>> 0;
  };

  putWord(0, 0, scene.media.length);
  putWord(0, 1, scene.lights.length);
  putWord(0, 2, scene.surfaces.length);
  putWord(
    0,
    3,
    scene.scatteringOrder === 'unlimited' ? SCENE_ORDER_UNLIMITED : scene.scatteringOrder,
  );

  const c = SCENE_CAMERA_RECORD;
  const camera = scene.camera;
  put(c, 0, camera.position);
  put(c + 3, 0, [scene.image.width, scene.image.height]);
  if (camera.type === 'perspective') {
    putWord(c, 3, CAMERA_PERSPECTIVE);
    put(c + 1, 0, [...camera.target, camera.fovY]);
    put(c + 2, 0, camera.up);
  } else {
    putWord(c, 3, CAMERA_ORTHOGRAPHIC);
    put(c + 1, 0, camera.direction);
    put(c + 2, 0, [...camera.up, camera.width]);
    put(c + 3, 2, [camera.height]);
  }

  const putGrid = (record: number, data: DensityGridData, maxDensity: number): void => {
    data.grid.dimensions.forEach((n, a) => putWord(record, a, n));
    put(record, 3, [data.grid.densityScale]);
    put(record + 1, 0, [...data.grid.boundsMin, maxDensity]);
    put(record + 2, 0, data.grid.boundsMax);
  };
  const density = grid?.fine ?? EMPTY_GRID;
  const majorant = grid?.majorant ?? EMPTY_GRID;
  putGrid(SCENE_GRID_RECORD, density, grid?.maxDensity ?? 0);
  putGrid(SCENE_MAJORANT_RECORD, majorant, grid?.maxDensity ?? 0);

  scene.media.forEach((medium, i) => {
    const o = SCENE_MEDIA_RECORD + 6 * i;
    putWord(o, 0, medium.type === 'grid' ? SCENE_MEDIUM_GRID : SCENE_MEDIUM_HOMOGENEOUS);
    // The phase record (src/phase/registry.ts) in the w words SCENE_MEDIUM_PHASE names.
    const phase = packPhase(medium.phase);
    const slots = SCENE_MEDIUM_PHASE;
    putWord(o + slots.kind[0], slots.kind[1], phase.kind);
    slots.values.forEach(([record, k], n) => put(o + record, k, [phase.values[n]!]));
    putWord(o + slots.table[0], slots.table[1], phase.table);
    const bounds = medium.bounds;
    if (bounds.type === 'box') {
      putWord(o, 1, SCENE_BOUNDS_BOX);
      put(o + 1, 0, bounds.min);
      put(o + 2, 0, bounds.max);
    } else {
      putWord(o, 1, SCENE_BOUNDS_SPHERE);
      put(o + 1, 0, [...bounds.center, bounds.radius]);
      put(
        o + 2,
        0,
        bounds.center.map((x) => x + bounds.radius),
      );
    }
    put(o + 3, 0, medium.sigmaA);
    put(o + 4, 0, medium.sigmaS);
    put(o + 5, 0, medium.emission ?? [0, 0, 0]);
  });

  scene.lights.forEach((light, i) => {
    const o = SCENE_LIGHTS_RECORD + 4 * i;
    switch (light.type) {
      case 'directional':
        putWord(o, 0, LIGHT_DIRECTIONAL);
        put(o + 2, 0, light.direction);
        put(o + 3, 0, light.irradiance);
        break;
      case 'point':
        putWord(o, 0, LIGHT_POINT);
        put(o + 1, 0, light.position);
        put(o + 3, 0, light.intensity);
        break;
      case 'spot':
        putWord(o, 0, LIGHT_SPOT);
        put(o, 1, [
          Math.cos((light.outerAngle * Math.PI) / 180),
          Math.cos((light.innerAngle * Math.PI) / 180),
        ]);
        put(o + 1, 0, light.position);
        put(o + 2, 0, light.direction);
        put(o + 3, 0, light.intensity);
        break;
      case 'environment':
        putWord(o, 0, LIGHT_ENVIRONMENT);
        put(o + 3, 0, light.radiance);
        break;
    }
  });

  scene.surfaces.forEach((surface, i) => {
    const o = SCENE_SURFACES_RECORD + 4 * i;
    switch (surface.type) {
      case 'plane':
        putWord(o, 0, SURFACE_PLANE);
        put(o + 1, 0, surface.point);
        put(o + 2, 0, surface.normal);
        break;
      case 'sphere':
        putWord(o, 0, SURFACE_SPHERE);
        put(o + 1, 0, [...surface.center, surface.radius]);
        break;
      case 'box':
        putWord(o, 0, SURFACE_BOX);
        put(o + 1, 0, surface.min);
        put(o + 2, 0, surface.max);
        break;
    }
    put(o + 3, 0, surface.albedo);
  });

  return {
    records,
    words,
    density,
    majorant,
    width: scene.image.width,
    height: scene.image.height,
    seed: scene.seed,
  };
}

/** The twin's view of a packed scene, for a kernel linked with `conditions`. */
export function sceneData(packed: PackedScene, conditions: Conditions): SceneData {
  return {
    records: packed.records,
    words: packed.words,
    density: packed.density.volume,
    majorant: packed.majorant.volume,
    conditions,
    stats: { lookups: 0, capped: 0 },
  };
}
