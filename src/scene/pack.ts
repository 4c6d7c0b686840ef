// Packing a resolved scene into what the renderer kernel reads (shaders/integrator.wesl):
// the SceneRecords struct (header, camera, grid, majorant grid, media, lights, surfaces;
// integers stored as their u32 bits) at the offsets derived from its WGSL declaration
// (SCENE_LAYOUT), and the grid's density and majorant samples for two r32float 3D
// textures, and the phase-table buffer of the tabulated phase functions (Mie; built
// here from the media's parameters, src/phase/registry.ts packPhases). The same words,
// read back as f32, are the twin's SceneData, so the CPU renderer sees exactly the GPU's
// (f32) scene.
import { packStruct, type PackValue } from '../gpu/layout.ts';
import {
  SCENE_BOUNDS_BOX,
  SCENE_BOUNDS_SPHERE,
  SCENE_LAYOUT,
  SCENE_MEDIUM_GRID,
  SCENE_MEDIUM_HOMOGENEOUS,
  SCENE_ORDER_UNLIMITED,
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
import { packPhases } from '../phase/registry.ts';
import type { ResolvedScene } from './load.ts';
import type { Conditions } from './plan.ts';

export interface PackedScene {
  /** SCENE_LAYOUT.size bytes; f32 and u32 views of one buffer. */
  records: Float32Array<ArrayBuffer>;
  words: Uint32Array<ArrayBuffer>;
  /** The density grid and its majorant grid (1×1×1 zero grids when the scene has none). */
  density: DensityGridData;
  majorant: DensityGridData;
  /** The phase-table buffer (PHASE_TABLE_WORDS f32 per table; empty without tables). */
  phaseTables: Float32Array<ArrayBuffer>;
  width: number;
  height: number;
  seed: number;
}

const EMPTY_GRID: DensityGridData = {
  grid: { dimensions: [1, 1, 1], boundsMin: [0, 0, 0], boundsMax: [1, 1, 1], densityScale: 0 },
  volume: new Float32Array(1),
};

type Records = PackValue<typeof SCENE_LAYOUT>;
type Members<T> = T extends readonly (infer E)[] ? E : never;
const ZERO3 = [0, 0, 0] as const;

export function packScene(resolved: ResolvedScene): PackedScene {
  const { scene, grid } = resolved;
  const camera = scene.camera;
  const imageSize = [scene.image.width, scene.image.height];
  const cameraRecord: Records['camera'] =
    camera.type === 'perspective'
      ? {
          position: camera.position,
          projection: CAMERA_PERSPECTIVE,
          look: camera.target,
          fovY: camera.fovY,
          up: camera.up,
          width: 0,
          imageSize,
          height: 0,
        }
      : {
          position: camera.position,
          projection: CAMERA_ORTHOGRAPHIC,
          look: camera.direction,
          fovY: 0,
          up: camera.up,
          width: camera.width,
          imageSize,
          height: camera.height,
        };

  const gridRecord = (data: DensityGridData, maxDensity: number): Records['grid'] => ({
    dimensions: data.grid.dimensions,
    densityScale: data.grid.densityScale,
    boundsMin: data.grid.boundsMin,
    maxDensity,
    boundsMax: data.grid.boundsMax,
  });
  const density = grid?.fine ?? EMPTY_GRID;
  const majorant = grid?.majorant ?? EMPTY_GRID;

  const phases = packPhases(scene.media.map((medium) => medium.phase));
  const media = scene.media.map((medium, index): Members<Records['media']> => {
    // The phase record (src/phase/registry.ts) in the words SceneMediumRecord gives it.
    const phase = phases.records[index]!;
    const bounds = medium.bounds;
    const sphere = bounds.type === 'sphere';
    return {
      kind: medium.type === 'grid' ? SCENE_MEDIUM_GRID : SCENE_MEDIUM_HOMOGENEOUS,
      shape: sphere ? SCENE_BOUNDS_SPHERE : SCENE_BOUNDS_BOX,
      phaseKind: phase.kind,
      phaseValue0: phase.values[0],
      boundsA: sphere ? bounds.center : bounds.min,
      radius: sphere ? bounds.radius : 0,
      boundsB: sphere ? bounds.center.map((x) => x + bounds.radius) : bounds.max,
      phaseValue1: phase.values[1],
      sigmaA: medium.sigmaA,
      phaseValue2: phase.values[2],
      sigmaS: medium.sigmaS,
      phaseTable: phase.table,
      emission: medium.emission ?? ZERO3,
    };
  });

  const lights = scene.lights.map((light): Members<Records['lights']> => {
    const none = { cosOuter: 0, cosInner: 0, position: ZERO3, direction: ZERO3 };
    switch (light.type) {
      case 'directional':
        return {
          ...none,
          kind: LIGHT_DIRECTIONAL,
          direction: light.direction,
          value: light.irradiance,
        };
      case 'point':
        return { ...none, kind: LIGHT_POINT, position: light.position, value: light.intensity };
      case 'spot':
        return {
          kind: LIGHT_SPOT,
          cosOuter: Math.cos((light.outerAngle * Math.PI) / 180),
          cosInner: Math.cos((light.innerAngle * Math.PI) / 180),
          position: light.position,
          direction: light.direction,
          value: light.intensity,
        };
      case 'environment':
        return { ...none, kind: LIGHT_ENVIRONMENT, value: light.radiance };
    }
  });

  const surfaces = scene.surfaces.map((surface): Members<Records['surfaces']> => {
    const albedo = surface.albedo;
    switch (surface.type) {
      case 'plane':
        return { kind: SURFACE_PLANE, a: surface.point, radius: 0, b: surface.normal, albedo };
      case 'sphere':
        return {
          kind: SURFACE_SPHERE,
          a: surface.center,
          radius: surface.radius,
          b: ZERO3,
          albedo,
        };
      case 'box':
        return { kind: SURFACE_BOX, a: surface.min, radius: 0, b: surface.max, albedo };
    }
  });

  const words = packStruct(SCENE_LAYOUT, {
    header: [
      scene.media.length,
      scene.lights.length,
      scene.surfaces.length,
      scene.scatteringOrder === 'unlimited' ? SCENE_ORDER_UNLIMITED : scene.scatteringOrder,
    ],
    camera: cameraRecord,
    grid: gridRecord(density, grid?.maxDensity ?? 0),
    majorant: gridRecord(majorant, grid?.maxDensity ?? 0),
    media,
    lights,
    surfaces,
  });
  const records = new Float32Array(words.buffer);

  return {
    records,
    words,
    density,
    majorant,
    phaseTables: phases.tables,
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
    phaseTables: packed.phaseTables,
    conditions,
    stats: { lookups: 0, capped: 0 },
  };
}
