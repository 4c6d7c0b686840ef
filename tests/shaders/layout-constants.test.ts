// TypeScript constants that still mirror a WGSL declaration, named one by one and held
// equal to it, and the packed scene written by src/scene/pack.ts and read by the twin
// through the one layout derived from integrator.wesl's SceneRecords (no GPU needed).
import { describe, expect, it } from 'vitest';
import { evaluateInteger, parseDeclarations } from '../../src/gpu/layoutDerive.ts';
import { readStruct, wordsOf, type StructLayout } from '../../src/gpu/layout.ts';
import { KERNEL_LAYOUTS, transferFunctionKernel } from '../../src/gpu/layouts.generated.ts';
import {
  TRANSFER_FUNCTION_WORDS,
  TRANSFER_MAX_POINTS,
  packTransferFunction,
} from '../../src/reference/volume.ts';
import {
  SCENE_BOUNDS_BOX,
  SCENE_BOUNDS_SPHERE,
  SCENE_LAYOUT,
  SCENE_MAX_LIGHTS,
  SCENE_MAX_MEDIA,
  SCENE_MAX_SURFACES,
  SCENE_MEDIUM_GRID,
  SCENE_MEDIUM_HOMOGENEOUS,
  SCENE_ORDER_UNLIMITED,
  sceneCamera,
  sceneGrid,
  sceneHeader,
  sceneLight,
  sceneMedium,
  sceneSurface,
} from '../../src/reference/integrator.ts';
import {
  LIGHT_DIRECTIONAL,
  LIGHT_ENVIRONMENT,
  LIGHT_POINT,
  LIGHT_SPOT,
} from '../../src/reference/lights.ts';
import { SURFACE_BOX, SURFACE_PLANE, SURFACE_SPHERE } from '../../src/reference/surfaces.ts';
import { CAMERA_ORTHOGRAPHIC, CAMERA_PERSPECTIVE } from '../../src/reference/camera.ts';
import { SLAB_MAX_COLLISIONS, SLAB_MAX_BINS } from '../../src/reference/slab.ts';
import { SLAB_MAX_PHOTONS_PER_THREAD } from '../../src/subsurface/slabKernel.ts';
import { resolveScene } from '../../src/scene/load.ts';
import { packScene, sceneData } from '../../src/scene/pack.ts';
import { GENERAL_CONDITIONS } from '../../src/scene/plan.ts';
import { parseScene } from '../../src/scene/validate.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

/** The const declarations of library modules (the linker drops consts no code uses). */
const wgslConsts = (modules: readonly string[]): ReadonlyMap<string, string> =>
  parseDeclarations(modules.map((path) => SHADER_LIBRARY[path] ?? '').join('\n')).consts;

describe('TypeScript constants equal their WGSL declarations', () => {
  const mirrors: [string, string[], Record<string, number>][] = [
    [
      'the scene renderer',
      ['integrator.wesl', 'lights.wesl', 'surfaces.wesl', 'camera.wesl'],
      {
        SCENE_MAX_MEDIA,
        SCENE_MAX_LIGHTS,
        SCENE_MAX_SURFACES,
        SCENE_ORDER_UNLIMITED,
        SCENE_MEDIUM_HOMOGENEOUS,
        SCENE_MEDIUM_GRID,
        SCENE_BOUNDS_BOX,
        SCENE_BOUNDS_SPHERE,
        LIGHT_DIRECTIONAL,
        LIGHT_POINT,
        LIGHT_SPOT,
        LIGHT_ENVIRONMENT,
        SURFACE_PLANE,
        SURFACE_SPHERE,
        SURFACE_BOX,
        CAMERA_PERSPECTIVE,
        CAMERA_ORTHOGRAPHIC,
      },
    ],
    [
      'the slab kernel',
      ['kernels/slab.wesl', 'slab.wesl'],
      { SLAB_MAX_PHOTONS_PER_THREAD, SLAB_MAX_COLLISIONS, SLAB_MAX_BINS },
    ],
    ['the transfer-function kernel', ['volume.wesl'], { TRANSFER_MAX_POINTS }],
  ];
  it.each(mirrors)('%s: %j', (_, modules, constants) => {
    const consts = wgslConsts(modules);
    for (const [name, value] of Object.entries(constants)) {
      expect(consts.has(name), `${name} is declared in ${modules.join(', ')}`).toBe(true);
      expect(evaluateInteger(consts.get(name)!, consts), name).toBe(value);
    }
  });
});

describe('structs packed by hand-kept code or declared more than once', () => {
  it('TRANSFER_FUNCTION_WORDS and packTransferFunction match volume.wesl TransferFunction', () => {
    const layout = transferFunctionKernel.TransferFunction;
    expect(TRANSFER_FUNCTION_WORDS * 4).toBe(layout.size);
    const rgba = Array.from({ length: 5 }, (_, k): [number, number, number, number] => [
      k,
      k + 0.5,
      k + 0.25,
      1 - k / 8,
    ]);
    const values = [-3, -1, 0, 2, 7];
    const words = packTransferFunction({ count: 5, values, rgba });
    const read = readStruct(layout, wordsOf(words.buffer));
    expect(read.count).toBe(5);
    expect(read.values.flat().slice(0, 5)).toEqual(values);
    expect(read.rgba.slice(0, 5)).toEqual(rgba);
  });

  it('TranslucentParams is laid out alike in the three translucent kernels (one packer)', () => {
    const path = KERNEL_LAYOUTS['kernels/translucent-path.wesl'].TranslucentParams;
    expect(KERNEL_LAYOUTS['kernels/translucent-diffuse.wesl'].TranslucentParams).toEqual(path);
    expect(KERNEL_LAYOUTS['kernels/translucent-gather.wesl'].TranslucentParams).toEqual(path);
  });
});

describe('the packed scene: one layout for pack.ts, the twin and integrator.wesl', () => {
  const recordOf = (layout: StructLayout, member: string): number =>
    layout.members[member]!.offset / 16;

  it('keeps the 16-byte records where the scene format put them (header 0 … 131 records)', () => {
    // A change here changes the packed scene's bytes: make it on purpose, in the WGSL.
    expect(SCENE_LAYOUT.size).toBe(131 * 16);
    const records = ['header', 'camera', 'grid', 'majorant', 'media', 'lights', 'surfaces'];
    expect(records.map((m) => recordOf(SCENE_LAYOUT, m))).toEqual([0, 1, 5, 8, 11, 35, 67]);
    const m = SCENE_LAYOUT.members;
    expect([m.media.type.stride, m.lights.type.stride, m.surfaces.type.stride]).toEqual([
      96, 64, 64,
    ]);
  });

  it('reads back every field pack.ts wrote, for every light, surface, bounds and camera kind', async () => {
    const scene = parseScene({
      image: { width: 8, height: 6 },
      samplesPerPixel: 1,
      scatteringOrder: 'unlimited',
      camera: {
        type: 'orthographic',
        position: [0.5, 1, 3],
        direction: [0, 0, -1],
        up: [0, 1, 0],
        width: 2.5,
        height: 1.5,
      },
      media: [
        {
          type: 'homogeneous',
          bounds: { type: 'box', min: [-1, -1, -1], max: [1, 0.5, 1] },
          sigmaA: [0.1, 0.2, 0.3],
          sigmaS: [1, 2, 3],
          emission: [0.5, 0.25, 0.125],
          phase: { type: 'henyey-greenstein', g: 0.75 },
        },
        {
          type: 'homogeneous',
          bounds: { type: 'sphere', center: [3, 0, 0], radius: 0.5 },
          sigmaA: [1, 1, 1],
          sigmaS: [0, 0, 0],
        },
      ],
      lights: [
        { type: 'directional', direction: [0, -1, 0], irradiance: [1, 2, 3] },
        { type: 'point', position: [1, 2, 3], intensity: [4, 5, 6] },
        {
          type: 'spot',
          position: [0, 3, 0],
          direction: [0, -1, 0],
          intensity: [7, 8, 9],
          outerAngle: 60,
          innerAngle: 30,
        },
        { type: 'environment', radiance: [0.1, 0.2, 0.3] },
      ],
      surfaces: [
        { type: 'plane', point: [0, -1, 0], normal: [0, 1, 0], albedo: [0.5, 0.5, 0.5] },
        { type: 'sphere', center: [0, 2, 0], radius: 0.25, albedo: [0.25, 0.5, 0.75] },
        { type: 'box', min: [2, -1, -1], max: [3, 0, 1], albedo: [1, 0, 0] },
      ],
    });
    const data = sceneData(packScene(await resolveScene(scene)), GENERAL_CONDITIONS);
    expect(sceneHeader(data)).toEqual([2, 4, 3, SCENE_ORDER_UNLIMITED]);

    const camera = sceneCamera(data);
    expect(camera.projection).toBe(CAMERA_ORTHOGRAPHIC);
    expect(camera.position).toEqual([0.5, 1, 3]);
    expect(camera.imageSize).toEqual([8, 6]);
    expect(camera.halfExtent).toEqual([1.25, 0.75]);

    const fogMedium = sceneMedium(data, 0);
    expect(fogMedium).toMatchObject({
      kind: SCENE_MEDIUM_HOMOGENEOUS,
      shape: SCENE_BOUNDS_BOX,
      boundsA: [-1, -1, -1],
      boundsB: [1, 0.5, 1],
      sigmaA: [Math.fround(0.1), Math.fround(0.2), Math.fround(0.3)],
      sigmaS: [1, 2, 3],
      emission: [0.5, 0.25, 0.125],
    });
    expect(fogMedium.phase.values[0]).toBe(0.75);
    const ball = sceneMedium(data, 1);
    expect(ball).toMatchObject({
      shape: SCENE_BOUNDS_SPHERE,
      boundsA: [3, 0, 0],
      radius: 0.5,
      emission: [0, 0, 0],
    });

    expect(sceneLight(data, 0)).toMatchObject({ kind: LIGHT_DIRECTIONAL, direction: [0, -1, 0] });
    expect(sceneLight(data, 1)).toMatchObject({ kind: LIGHT_POINT, position: [1, 2, 3] });
    const spot = sceneLight(data, 2);
    expect(spot).toMatchObject({ kind: LIGHT_SPOT, value: [7, 8, 9] });
    expect(spot.cosOuter).toBeCloseTo(0.5, 6);
    expect(spot.cosInner).toBeCloseTo(Math.sqrt(3) / 2, 6);
    expect(sceneLight(data, 3)).toMatchObject({ kind: LIGHT_ENVIRONMENT });

    expect(sceneSurface(data, 0)).toMatchObject({ kind: SURFACE_PLANE, b: [0, 1, 0] });
    expect(sceneSurface(data, 1)).toMatchObject({ kind: SURFACE_SPHERE, radius: 0.25 });
    expect(sceneSurface(data, 2)).toMatchObject({ kind: SURFACE_BOX, a: [2, -1, -1] });
    expect(sceneGrid(data, 'grid').dimensions).toEqual([1, 1, 1]);
  });
});
