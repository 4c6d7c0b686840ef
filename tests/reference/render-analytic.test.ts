// The scene renderer's float64 twin (src/reference/integrator.ts, the CPU backend)
// against analytic results:
//  - physics.md §5: single scattering in a homogeneous slab under a directional light has a
//    closed form; the specialized estimator (Beer's-law shadow rays), the general path
//    tracer at order 1 (tracking) and a constant density grid (ratio-tracked shadow rays,
//    reservoir-chosen scattering points) must all reproduce it;
//  - a point light seen through a homogeneous medium: equiangular sampling against
//    Simpson quadrature of the single-scattering integral;
//  - emission–absorption of a homogeneous slab: exact, zero variance;
//  - the white furnace: a non-absorbing medium (albedo 1) in a uniform environment returns
//    the environment's radiance in every pixel, whatever its chromatic σs and its HG lobe
//    (unbiased Russian roulette and spectral tracking); with absorption, energy goes down;
//  - every example scene: the specialized plan and the general kernel agree (z-scores).
// Statistical checks: tests/support/sceneRender.ts (|z| < 6 per value, pooled |z| < 5).
import { describe, expect, it } from 'vitest';
import { renderScene, type SceneRenderOptions } from '../../src/scene/renderScene.ts';
import type { ResolvedScene } from '../../src/scene/load.ts';
import {
  pointLightExact,
  pointLightScene,
  slabExact,
  slabScene,
} from '../support/analyticScenes.ts';
import {
  EXAMPLE_SCENES,
  estimateOf,
  exampleScene,
  expectAgreement,
  expectMatchesExact,
  sceneFrom,
  type ImageEstimate,
} from '../support/sceneRender.ts';

const f32 = Math.fround;
const cpu = async (
  scene: ResolvedScene,
  options: SceneRenderOptions = {},
): Promise<ImageEstimate> => estimateOf(await renderScene(scene, { kind: 'cpu' }, options));

describe('physics.md §5: single scattering in a homogeneous slab (CPU twin)', () => {
  it("specialized: truncated free flights and Beer's-law shadow rays", async () => {
    const estimate = await cpu(await sceneFrom(slabScene('homogeneous')));
    expectMatchesExact(estimate, (_, c) => slabExact(c), 'slab, plan', 1e-6 * slabExact(0));
  });

  it('general kernel: the path tracer at order 1 with tracking everywhere', async () => {
    const estimate = await cpu(await sceneFrom(slabScene('homogeneous')), {
      kernel: 'general',
      spp: 256,
    });
    expectMatchesExact(estimate, (_, c) => slabExact(c), 'slab, general', 1e-6 * slabExact(0));
  });

  it('a constant density grid: ratio-tracked shadow rays, reservoir-chosen scattering points', async () => {
    const estimate = await cpu(await sceneFrom(slabScene('grid')), { spp: 128 });
    expectMatchesExact(estimate, (_, c) => slabExact(c), 'slab, grid', 1e-6 * slabExact(0));
  });

  it('higher orders add light: order 2 is brighter than order 1 in every channel', async () => {
    const one = await cpu(await sceneFrom(slabScene('homogeneous', 1)), { kernel: 'general' });
    const two = await cpu(await sceneFrom(slabScene('homogeneous', 2)), { kernel: 'general' });
    const mean = (e: ImageEstimate, c: number) =>
      e.mean.filter((_, k) => k % 3 === c).reduce((a, b) => a + b) / 16;
    for (let c = 0; c < 3; c++) expect(mean(two, c)).toBeGreaterThan(mean(one, c));
  });
});

describe('a point light in a homogeneous medium: equiangular sampling vs quadrature', () => {
  const scene = pointLightScene;
  const exact = pointLightExact;

  it('the specialized kernel (equiangular sample, Beer shadow ray)', async () => {
    const estimate = await cpu(await sceneFrom(scene));
    expectMatchesExact(estimate, (_, c) => exact(c), 'point light, plan', 1e-6 * exact(0));
  });

  it('the general kernel (free-flight sampling, next-event estimation)', async () => {
    const estimate = await cpu(await sceneFrom(scene), { kernel: 'general' });
    expectMatchesExact(estimate, (_, c) => exact(c), 'point light, general', 1e-6 * exact(0));
  });
});

describe('emission–absorption of a homogeneous slab', () => {
  const SIGMA_A = [0.5, 1, 2];
  const SIGMA_S = [0.25, 0, 0.5];
  const EMISSION = [3, 2, 1];
  const BACKGROUND = [0.1, 0.2, 0.3];
  const scene = {
    image: { width: 2, height: 2 },
    samplesPerPixel: 8,
    scatteringOrder: 0,
    camera: {
      type: 'orthographic',
      position: [0, 2, 0],
      direction: [0, -1, 0],
      up: [0, 0, -1],
      width: 1,
      height: 1,
    },
    media: [
      {
        type: 'homogeneous',
        bounds: { type: 'box', min: [-10, 0, -10], max: [10, 1, 10] },
        sigmaA: SIGMA_A,
        sigmaS: SIGMA_S,
        emission: EMISSION,
      },
    ],
    lights: [{ type: 'environment', radiance: BACKGROUND }],
  };
  // L = Le σa/σt (1 − e^{−σt}) + e^{−σt} L_env through the unit thickness, on the f32 inputs.
  const exact = (c: number): number => {
    const sigmaA = f32(SIGMA_A[c]!);
    const sigmaT = f32(sigmaA + f32(SIGMA_S[c]!));
    return (
      (f32(EMISSION[c]!) * sigmaA * -Math.expm1(-sigmaT)) / sigmaT +
      Math.exp(-sigmaT) * f32(BACKGROUND[c]!)
    );
  };

  it('the closed form is exact: zero variance, agreement to 1e-12', async () => {
    const estimate = await cpu(await sceneFrom(scene));
    for (let k = 0; k < estimate.mean.length; k++) {
      // The standard error is rounding in Σx² − n·mean² only (its square root: ~√ε·L).
      expect(estimate.se[k]).toBeLessThan(1e-7 * exact(k % 3));
      expect(Math.abs(estimate.mean[k]! - exact(k % 3))).toBeLessThan(1e-12);
    }
  });

  it('the general kernel (spectral tracking, collision estimator) agrees within its error', async () => {
    const estimate = await cpu(await sceneFrom(scene), { kernel: 'general', spp: 512 });
    expectMatchesExact(estimate, (_, c) => exact(c), 'emission, general', 1e-9);
  });
});

describe('the white furnace and energy conservation', () => {
  it('albedo 1 in a uniform environment: every pixel equals the environment (unbiased roulette)', async () => {
    const scene = await exampleScene('white-furnace', {
      image: { width: 8, height: 8 },
      samplesPerPixel: 64,
    });
    const estimate = await cpu(scene);
    expectMatchesExact(estimate, () => 1, 'white furnace', 1e-9);
  });

  it('with absorption no pixel exceeds the environment, and the ball is darker', async () => {
    const json = {
      image: { width: 8, height: 8 },
      samplesPerPixel: 64,
      scatteringOrder: 'unlimited',
    };
    const scene = await exampleScene('white-furnace', json);
    scene.scene.media[0]!.sigmaA = [1, 0.5, 0.3];
    const estimate = await cpu(scene);
    for (let k = 0; k < estimate.mean.length; k++)
      expect(estimate.mean[k]!).toBeLessThanOrEqual(1 + 6 * estimate.se[k]! + 1e-9);
    // Pixels whose whole footprint (0.3 m squares of the 2.4 m view) lies inside the unit ball.
    const inside = Array.from({ length: 64 }, (_, i) => i).filter((i) => {
      const x = Math.abs(((i % 8) - 3.5) * 0.3) + 0.15;
      const y = Math.abs((Math.floor(i / 8) - 3.5) * 0.3) + 0.15;
      return Math.hypot(x, y) < 1;
    });
    expect(inside.length).toBe(24);
    for (let c = 0; c < 3; c++) {
      let sum = 0;
      let variance = 0;
      for (const i of inside) {
        sum += estimate.mean[3 * i + c]!;
        variance += estimate.se[3 * i + c]! ** 2;
      }
      const n = inside.length;
      expect(sum / n).toBeLessThan(1 - 5 * (Math.sqrt(variance) / n));
    }
  });
});

describe('specialized plan vs general kernel on every example scene (CPU twin)', () => {
  it.each(EXAMPLE_SCENES)('%s', async (name) => {
    const scene = await exampleScene(name, { image: { width: 8, height: 8 }, samplesPerPixel: 64 });
    const specialized = await cpu(scene);
    const general = await cpu(scene, { kernel: 'general' });
    expectAgreement(specialized, general, name);
  });
});
