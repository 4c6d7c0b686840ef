// The one-medium estimators (plan conditions oneHomogeneousMedium, oneGridMedium) against the general
// ones, both float64 twins: for a scene of one homogeneous medium under delta lights they
// must compute the same radiance from the same random numbers, sample by sample (the
// WGSL kernels rely on it: tests/shaders/scene-render.test.ts compares the GPU with the
// twin statistically). Equal draws are checked through the generator's final state.
import { describe, expect, it } from 'vitest';
import { cameraRay } from '../../src/reference/camera.ts';
import { estimateRadiance, sceneCamera, type SceneData } from '../../src/reference/integrator.ts';
import { pcgHash, rngNextFloat, rngSeed, type RngState } from '../../src/reference/rng.ts';
import { packScene, sceneData } from '../../src/scene/pack.ts';
import { plan, type Conditions } from '../../src/scene/plan.ts';
import { boxSceneJson, sceneFrom } from '../support/sceneRender.ts';

const SIZE = 8;
const SAMPLES = 6;

function boxScene(order: number | 'unlimited', phase: Record<string, unknown>, pointLight = true) {
  // Channels differ (chromatic σt, a strongly absorbing blue) so that the mean-rate free
  // flights carry spectral weights, as in the issue-19 box.
  return boxSceneJson({
    order,
    phase,
    sigmaA: [0.25, 0.1, 1.5],
    sigmaS: [1, 1.98, 0.6],
    size: SIZE,
    samplesPerPixel: SAMPLES,
    seed: 5,
    pointLight,
  });
}

/** A spot light above the box, its cone across the box's top. */
const SPOT = {
  type: 'spot',
  position: [0.6, 2.5, 0.3],
  direction: [-0.2, -1, -0.1],
  intensity: [4, 3, 2],
  innerAngle: 20,
  outerAngle: 35,
};

/** The box's medium as a 3³ grid with empty, thin and dense cells (null collisions). */
function gridBoxScene(order: number | 'unlimited') {
  const scene = boxScene(order, { type: 'henyey-greenstein', g: 0.5 });
  const density = Array.from({ length: 27 }, (_, i) => [0, 0.2, 1, 3][(i * 7) % 4]!);
  return {
    ...scene,
    media: [{ ...scene.media[0]!, type: 'grid', grid: { dimensions: [3, 3, 3], density } }],
  };
}

async function twins(
  json: unknown,
  condition: 'oneHomogeneousMedium' | 'oneGridMedium' | 'grayMedia' = 'oneHomogeneousMedium',
  also: Partial<Conditions> = {},
): Promise<{ specialized: SceneData; general: SceneData }> {
  const resolved = await sceneFrom(json);
  const conditions = { ...plan(resolved.scene).conditions, ...also };
  expect(conditions[condition], `the plan picks the specialized code (${condition})`).toBe(true);
  const packed = packScene(resolved);
  return {
    specialized: sceneData(packed, conditions),
    general: sceneData(packed, { ...conditions, [condition]: false }),
  };
}

/** One camera sample of pixel (x, y) as the kernel draws it; returns radiance and final state. */
function sample(scene: SceneData, x: number, y: number, s: number): [number[], number] {
  const state: RngState = { value: rngSeed(y * SIZE + x, (pcgHash(5) + s) >>> 0) };
  const jitter: [number, number] = [rngNextFloat(state), rngNextFloat(state)];
  const ray = cameraRay(sceneCamera(scene), [x + jitter[0], y + jitter[1]]);
  return [estimateRadiance(scene, ray.origin, ray.direction, state), state.value];
}

function expectSameSamples(specialized: SceneData, general: SceneData): number {
  let nonZero = 0;
  for (let y = 0; y < SIZE; y++)
    for (let x = 0; x < SIZE; x++)
      for (let s = 0; s < SAMPLES; s++) {
        const [a, stateA] = sample(specialized, x, y, s);
        const [b, stateB] = sample(general, x, y, s);
        expect(stateA, `pixel ${x},${y} sample ${s}: same random numbers`).toBe(stateB);
        for (let c = 0; c < 3; c++) {
          // Same operations up to their order (sums of lights, products of weights).
          expect(Math.abs(a[c]! - b[c]!)).toBeLessThanOrEqual(1e-12 * Math.abs(b[c]!) + 1e-300);
          if (b[c]! > 0) nonZero += 1;
        }
      }
  return nonZero;
}

describe('one-medium estimators = general estimators, sample by sample (float64 twins)', () => {
  it('single scattering, Henyey–Greenstein g = 0.6, under the sun', async () => {
    const { specialized, general } = await twins(
      boxScene(1, { type: 'henyey-greenstein', g: 0.6 }, false),
    );
    expect(specialized.conditions.equiangular).toBe(false);
    // The test must see light: most samples scatter toward a lit point.
    expect(expectSameSamples(specialized, general)).toBeGreaterThan(SIZE * SIZE * SAMPLES);
  });

  it('single scattering with equiangular points: the sun and a point light inside the box', async () => {
    const { specialized, general } = await twins(
      boxScene(1, { type: 'henyey-greenstein', g: 0.6 }),
    );
    expect(specialized.conditions.equiangular).toBe(true);
    expect(expectSameSamples(specialized, general)).toBeGreaterThan(SIZE * SIZE * SAMPLES);
  });

  it('single scattering with equiangular points: a point light alone, and a spot light with the sun', async () => {
    const scene = boxScene(1, { type: 'isotropic' });
    const [sun, point] = scene.lights;
    const alone = await twins({ ...scene, lights: [point] });
    expect(alone.specialized.conditions.oneLight).toBe(true);
    expect(expectSameSamples(alone.specialized, alone.general)).toBeGreaterThan(SIZE * SIZE);
    const withSpot = await twins({ ...scene, lights: [SPOT, sun] });
    expect(expectSameSamples(withSpot.specialized, withSpot.general)).toBeGreaterThan(SIZE * SIZE);
  });

  it('single scattering among surfaces: a floor inside the box, a sphere across its face, black and grey (the single-scatter widget’s scene)', async () => {
    const scene = boxScene(1, { type: 'henyey-greenstein', g: 0.3 });
    const [sun, point] = scene.lights;
    const surfaces = [
      // Inside the medium: view rays stop in it, and it shadows points above it.
      { type: 'plane', point: [0, -0.6, 0], normal: [0, 1, 0], albedo: [0.5, 0.5, 0.5] },
      // Half in, half out: shadow rays and view rays cross its edge of the box.
      { type: 'sphere', center: [0.2, 0.9, 0.1], radius: 0.35, albedo: [0.7, 0.3, 0.2] },
      { type: 'box', min: [-0.9, -0.6, -0.5], max: [-0.5, -0.2, -0.1], albedo: [0, 0, 0] },
    ];
    for (const lights of [[SPOT, sun], [point], [sun]]) {
      const { specialized, general } = await twins({ ...scene, lights, surfaces });
      expect(specialized.conditions.surfaces).toBe(true);
      expect(specialized.conditions.surfaceScattering).toBe(true);
      expect(expectSameSamples(specialized, general)).toBeGreaterThan(SIZE * SIZE);
    }
    // A view from inside the box toward the floor, so that every view ray hits a surface in it.
    const inside = {
      ...scene,
      camera: { ...scene.camera, position: [0.1, 0.5, 0.8], target: [0, -0.6, 0] },
      lights: [SPOT, sun],
      surfaces,
    };
    const { specialized, general } = await twins(inside);
    expect(expectSameSamples(specialized, general)).toBeGreaterThan(SIZE * SIZE * SAMPLES);
  });

  it('path tracing with surfaces keeps the general kernel (the one-medium path tracer has no surface bounces)', async () => {
    const resolved = await sceneFrom({
      ...boxScene('unlimited', { type: 'isotropic' }),
      surfaces: [
        { type: 'plane', point: [0, -0.6, 0], normal: [0, 1, 0], albedo: [0.5, 0.5, 0.5] },
      ],
    });
    expect(plan(resolved.scene).conditions.oneHomogeneousMedium).toBe(false);
  });

  it('path tracing, all orders, Henyey–Greenstein g = −0.3 (Russian roulette and spectral weights)', async () => {
    const { specialized, general } = await twins(
      boxScene('unlimited', { type: 'henyey-greenstein', g: -0.3 }),
    );
    expect(expectSameSamples(specialized, general)).toBeGreaterThan(SIZE * SIZE * SAMPLES);
  });

  it('path tracing to order 3, isotropic', async () => {
    const { specialized, general } = await twins(boxScene(3, { type: 'isotropic' }));
    expect(expectSameSamples(specialized, general)).toBeGreaterThan(SIZE * SIZE * SAMPLES);
  });

  it('path tracing in one grid medium, all orders (delta tracking, ratio-tracked shadow rays)', async () => {
    const { specialized, general } = await twins(gridBoxScene('unlimited'), 'oneGridMedium');
    expect(expectSameSamples(specialized, general)).toBeGreaterThan(SIZE * SIZE * SAMPLES);
    // The draws include lookups: the same count on both sides.
    expect(specialized.stats.lookups).toBe(general.stats.lookups);
    expect(specialized.stats.lookups).toBeGreaterThan(0);
  });

  it('gray media: the free flight’s scalar test (plan condition grayMedia) = the spectral one, in the one-grid and the general path tracer', async () => {
    const scene = gridBoxScene('unlimited');
    const gray = {
      ...scene,
      media: [{ ...scene.media[0]!, sigmaA: [0.3, 0.3, 0.3], sigmaS: [1.7, 1.7, 1.7] }],
    };
    for (const also of [{}, { oneGridMedium: false }]) {
      const { specialized, general } = await twins(gray, 'grayMedia', also);
      expect(expectSameSamples(specialized, general)).toBeGreaterThan(SIZE * SIZE * SAMPLES);
      expect(specialized.stats.lookups).toBe(general.stats.lookups);
      expect(specialized.stats.lookups).toBeGreaterThan(0);
    }
  });
});
