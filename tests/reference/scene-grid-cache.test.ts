// What the scene kernel derives once per invocation from its grid records (integrator.wesl
// sceneGridLoad, twin sceneGridLoad): the regrouped map from a point to the continuous sample
// coordinate equals gridTrilinearCorners' formula, and a grid whose box is flat once packed
// in f32 becomes an empty box with majorant 0 (no lookup inside, no tracking).
import { describe, expect, it } from 'vitest';
import {
  mediumDensity,
  mediumMajorant,
  sceneGrid,
  sceneGridLoad,
  sceneMedium,
} from '../../src/reference/integrator.ts';
import { packScene, sceneData } from '../../src/scene/pack.ts';
import { plan } from '../../src/scene/plan.ts';
import { sceneFrom } from '../support/sceneRender.ts';

function gridSceneJson(min: number[], max: number[]) {
  return {
    image: { width: 4, height: 4 },
    samplesPerPixel: 4,
    seed: 1,
    scatteringOrder: 'unlimited',
    camera: {
      type: 'perspective',
      position: [0.5, 0.5, 6],
      target: [0.5, 0.5, 0],
      up: [0, 1, 0],
      fovY: 40,
    },
    media: [
      {
        type: 'grid',
        bounds: { type: 'box', min, max },
        sigmaA: [0.2, 0.2, 0.2],
        sigmaS: [1, 1, 1],
        phase: { type: 'isotropic' },
        grid: {
          dimensions: [4, 3, 5],
          density: Array.from({ length: 60 }, (_, i) => ((i * 37) % 11) / 10),
        },
      },
    ],
    lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
  };
}

async function data(json: unknown) {
  const resolved = await sceneFrom(json);
  return sceneData(packScene(resolved), plan(resolved.scene).conditions);
}

describe('sceneGridLoad (the scene kernel’s grid cache)', () => {
  it('p ⊙ toSample + offset is gridTrilinearCorners’ (p − b_min)/(b_max − b_min) ⊙ n − ½', async () => {
    const scene = await data(gridSceneJson([-1, 0, -3], [2, 1, -1]));
    const grid = sceneGrid(scene, 'grid');
    const cache = sceneGridLoad(scene);
    expect(cache.lastIndex).toEqual([3, 2, 4]);
    expect(cache.strides).toEqual([1, 4, 12]);
    expect(cache.majorantGrid).toEqual(sceneGrid(scene, 'majorant'));
    for (let k = 0; k < 200; k++) {
      const p = [0, 1, 2].map(
        (a) =>
          grid.boundsMin[a as 0] +
          ((k * (a + 3) * 0.6180339887) % 1) * (grid.boundsMax[a as 0] - grid.boundsMin[a as 0]),
      );
      for (const a of [0, 1, 2] as const) {
        const u = p[a]! * cache.toSample[a] + cache.offset[a];
        const corners =
          ((p[a]! - grid.boundsMin[a]) / (grid.boundsMax[a] - grid.boundsMin[a])) *
            grid.dimensions[a] -
          0.5;
        expect(Math.abs(u - corners)).toBeLessThan(1e-12);
      }
    }
  });

  it('a box flat in f32 (max = min + 1e-9): an empty box and a majorant of 0, so no medium', async () => {
    const scene = await data(gridSceneJson([0, 0, 1], [1, 1, 1 + 1e-9]));
    const cache = sceneGridLoad(scene);
    expect(cache.boundsMin[0]).toBeGreaterThan(cache.boundsMax[0]);
    expect(cache.majorantGrid.densityScale).toBe(0);
    const medium = sceneMedium(scene, 0);
    expect(mediumDensity(scene, medium, [0.5, 0.5, 1])).toBe(0);
    expect(mediumMajorant(scene, medium, [0.5, 0.5, 0], [0, 0, 1], [1, 1])).toBe(0);
  });
});
