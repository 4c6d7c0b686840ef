// The scene kernel (shaders/kernels/scene-render.wesl + shaders/integrator.wesl) on the
// GPU through Dawn, against the float64 twin and against closed forms:
//  - physics.md §5 (single scattering in a homogeneous slab) and a point light seen through a
//    homogeneous medium (equiangular sampling vs quadrature) on the GPU;
//  - GPU vs twin images on the same samples for one scene per integrator (per-pixel
//    z-scores from both standard errors, tests/support/sceneRender.ts), including the
//    general kernel; f32 rounding makes some paths diverge, so agreement is statistical;
//  - the white furnace on the GPU: every pixel equals the environment;
//  - specialized vs general kernels on the GPU (different code, different random numbers);
//    the §5 slab runs the one-medium kernels (plan condition oneHomogeneousMedium), and a
//    small grid the one-medium path tracer (oneGridMedium).
// Images are small (8×8, a few dozen samples) because SwiftShader runs WebGPU on the CPU;
// each distinct kernel is compiled once (the pipeline cache is per device).
import { beforeAll, describe, expect, it } from 'vitest';
import type { ResolvedScene } from '../../src/scene/load.ts';
import { GpuSceneRenderer } from '../../src/scene/gpuRenderer.ts';
import { packScene } from '../../src/scene/pack.ts';
import { plan } from '../../src/scene/plan.ts';
import { renderProgressive } from '../../src/scene/render.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { buildScene } from '../../src/widgets/single-scatter/model.ts';
import type { SceneRenderOptions } from '../../src/scene/renderScene.ts';
import {
  pointLightExact,
  pointLightScene,
  slabExact,
  slabScene,
} from '../support/analyticScenes.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import {
  boxSceneJson,
  cpuEstimate,
  gpuEstimate,
  exampleScene,
  expectAgreement,
  expectMatchesExact,
  sceneFrom,
  type ImageEstimate,
} from '../support/sceneRender.ts';

let device: GPUDevice;
beforeAll(async () => {
  device = await nodeDevice();
}, 60_000);

const gpu = (scene: ResolvedScene, options?: SceneRenderOptions): Promise<ImageEstimate> =>
  gpuEstimate(device, scene, options);
const cpu = cpuEstimate;

const SMALL = { image: { width: 8, height: 8 }, samplesPerPixel: 32 };
// Linking and compiling a kernel in SwiftShader takes seconds on a loaded machine.
const GPU_TIMEOUT = 180_000;

describe('scene kernel on the GPU', () => {
  it(
    'physics.md §5: the specialized kernel matches the homogeneous-slab closed form',
    async () => {
      const estimate = await gpu(await sceneFrom(slabScene('homogeneous')));
      // f32 allowance: exp and divisions of a few ULP each, a few hundred in a sample.
      expectMatchesExact(estimate, (_, c) => slabExact(c), 'slab on the GPU', 2e-5 * slabExact(0));
    },
    GPU_TIMEOUT,
  );

  it(
    'equiangular sampling for a point light (the one-medium kernel): GPU = quadrature, GPU = twin, and = the general kernel',
    async () => {
      const scene = await sceneFrom({ ...pointLightScene, samplesPerPixel: 1024 });
      expect(plan(scene.scene).conditions).toMatchObject({
        equiangular: true,
        oneHomogeneousMedium: true,
      });
      const estimate = await gpu(scene);
      expectMatchesExact(
        estimate,
        (_, c) => pointLightExact(c),
        'point light on the GPU',
        2e-5 * pointLightExact(0),
      );
      expectAgreement(estimate, await cpu(scene), 'point light, GPU vs twin');
      expectAgreement(
        estimate,
        await gpu(scene, { kernel: 'general', spp: 1024 }),
        'point light, one-medium vs general kernel',
      );
    },
    GPU_TIMEOUT,
  );

  it(
    'single scattering among surfaces (the single-scatter widget: fog, spot light, floor, sphere) in the one-medium kernel: GPU = twin, and = the general kernel',
    async () => {
      const scene = await sceneFrom(
        buildScene(
          {
            medium: 'fog',
            light: 'spot',
            sigmaS: 0.6,
            albedo: 0.9,
            g: 0.3,
            scattering: true,
            occluder: 'sphere',
            emission: false,
            floor: true,
            spp: 64,
          },
          { width: 8, height: 8, spp: 1024, seed: 3 },
        ),
      );
      expect(plan(scene.scene).conditions).toMatchObject({
        oneHomogeneousMedium: true,
        surfaceScattering: true,
        equiangular: true,
      });
      const specialized = await gpu(scene);
      expectAgreement(specialized, await cpu(scene), 'single-scatter scene, GPU vs twin');
      // The general kernel has no equiangular points (other random numbers, a noisier
      // estimate of the spot's cone): many samples, as for the point light above.
      expectAgreement(
        specialized,
        await gpu(scene, { kernel: 'general', spp: 1024 }),
        'single-scatter scene, one-medium vs general kernel',
      );
    },
    GPU_TIMEOUT,
  );

  it(
    'gray media (one exponential per shadow ray): the one-medium path tracer and single scattering, GPU = twin',
    async () => {
      const gray = (order: number | 'unlimited') =>
        boxSceneJson({
          order,
          phase: { type: 'henyey-greenstein', g: 0.6 },
          sigmaA: [0.1, 0.1, 0.1],
          sigmaS: [1.5, 1.5, 1.5],
          size: 8,
          samplesPerPixel: 64,
          seed: 9,
        });
      for (const order of ['unlimited', 1] as const) {
        const scene = await sceneFrom(gray(order));
        const conditions = plan(scene.scene).conditions;
        expect(conditions).toMatchObject({ grayMedia: true, oneHomogeneousMedium: true });
        expectAgreement(
          await gpu(scene),
          await cpu(scene),
          `gray box, order ${order}, GPU vs twin`,
        );
        // One exponential for three equal channels is the same arithmetic, and the free
        // flight's scalar test the same decisions (σt = σ̄ in a homogeneous medium: every
        // tentative collision is real): the kernel with and without grayMedia gives the same
        // image, bit for bit for single scattering, within f32 rounding of the albedo weight
        // (σs/σt against σs·total/(σ̄·(Pa + Ps))) for path tracing.
        const image = async (grayMedia: boolean) => {
          const packed = packScene(scene);
          const renderer = await GpuSceneRenderer.create(device, SHADER_LIBRARY, packed, {
            ...conditions,
            grayMedia,
          });
          try {
            const result = await renderProgressive(renderer, packed.width, packed.height, {
              spp: 16,
              samplesPerPass: 16,
            });
            return Array.from(result.accumulator.mean());
          } finally {
            renderer.destroy();
          }
        };
        const [withGray, without] = [await image(true), await image(false)];
        if (order === 1) expect(withGray).toEqual(without);
        else
          withGray.forEach((v, i) =>
            expect(Math.abs(v - without[i]!), `value ${i}`).toBeLessThanOrEqual(1e-5 * without[i]!),
          );
      }
    },
    GPU_TIMEOUT,
  );

  it(
    'single scattering in a grid with spot and point lights over a floor: GPU = twin',
    async () => {
      const scene = await exampleScene('smoke-spotlight', SMALL);
      expectAgreement(await gpu(scene), await cpu(scene), 'smoke-spotlight');
    },
    GPU_TIMEOUT,
  );

  it(
    'emission–absorption in a grid: GPU = twin, and the specialized kernel = the general one',
    async () => {
      const scene = await exampleScene('emissive-smoke', SMALL);
      const specialized = await gpu(scene);
      expectAgreement(specialized, await cpu(scene), 'emissive-smoke, GPU vs twin');
      expectAgreement(
        specialized,
        await gpu(scene, { kernel: 'general', spp: 64 }),
        'emissive-smoke, specialized vs general',
      );
    },
    GPU_TIMEOUT,
  );

  it(
    'path tracing, white furnace: GPU = twin, and every pixel equals the environment',
    async () => {
      const scene = await exampleScene('white-furnace', SMALL);
      const estimate = await gpu(scene);
      expectMatchesExact(estimate, () => 1, 'white furnace on the GPU', 1e-5);
      expectAgreement(estimate, await cpu(scene), 'white furnace, GPU vs twin');
    },
    GPU_TIMEOUT,
  );

  it(
    'the general kernel (path tracer, grid, sun, sky, floor): GPU = twin',
    async () => {
      const scene = await exampleScene('cloud-sky', { ...SMALL, samplesPerPixel: 16 });
      expectAgreement(
        await gpu(scene, { kernel: 'general' }),
        await cpu(scene, { kernel: 'general' }),
        'cloud-sky, general kernel',
      );
    },
    GPU_TIMEOUT,
  );

  it(
    'the one-medium path tracer (homogeneous slab, sun and a point light, all orders): GPU = twin, and = the general kernel',
    async () => {
      const json = slabScene('homogeneous', 'unlimited');
      const scene = await sceneFrom({
        ...json,
        lights: [
          ...json.lights,
          { type: 'point', position: [0.2, 0.6, 0.1], intensity: [0.3, 0.2, 0.1] },
        ],
      });
      const specialized = await gpu(scene);
      expectAgreement(specialized, await cpu(scene), 'one-medium path tracer, GPU vs twin');
      expectAgreement(
        specialized,
        await gpu(scene, { kernel: 'general', spp: 128 }),
        'one-medium path tracer vs general kernel',
      );
    },
    GPU_TIMEOUT,
  );

  it(
    'the one-medium path tracer in a grid (sun and a point light, all orders): GPU = twin, and = the general kernel; chromatic and gray media',
    async () => {
      // A 3³ grid with empty, thin and dense cells (delta tracking meets null collisions,
      // ratio-tracked shadow rays start and end inside the medium at the point light).
      const density = Array.from({ length: 27 }, (_, i) => [0, 0.2, 1, 3][(i * 7) % 4]!);
      // A 4×3×2 grid (x fastest) as well, dense only in sample (0, 0, 1): a lookup that
      // swapped axes or strides would put the dense sample elsewhere.
      const nonCubic = Array.from({ length: 24 }, (_, i) => (i === 12 ? 6 : 0.05 * (i % 5)));
      const gridScene = (
        sigmaA: number[],
        sigmaS: number[],
        shape: 'cubic' | 'non-cubic' = 'cubic',
      ) =>
        sceneFrom({
          image: { width: 6, height: 6 },
          samplesPerPixel: 48,
          seed: 3,
          scatteringOrder: 'unlimited',
          camera: {
            type: 'perspective',
            position: [0.4, 0.3, 3.2],
            target: [0, 0, 0],
            up: [0, 1, 0],
            fovY: 40,
          },
          media: [
            {
              type: 'grid',
              bounds: { type: 'box', min: [-1, -1, -1], max: [1, 1, 1] },
              sigmaA,
              sigmaS,
              phase: { type: 'henyey-greenstein', g: 0.5 },
              grid:
                shape === 'cubic'
                  ? { dimensions: [3, 3, 3], density }
                  : { dimensions: [4, 3, 2], density: nonCubic },
            },
          ],
          lights: [
            { type: 'directional', direction: [0.3, -0.9, -0.2], irradiance: [2, 2, 2] },
            { type: 'point', position: [0.2, 0.5, 0.1], intensity: [0.3, 0.2, 0.1] },
          ],
        });
      // Gray media take the free flight's scalar test (plan condition grayMedia).
      for (const [name, sigmaA, sigmaS, gray, shape] of [
        ['chromatic', [0.2, 0.1, 0.6], [1.5, 2, 0.8], false, 'cubic'],
        ['gray', [0.3, 0.3, 0.3], [1.5, 1.5, 1.5], true, 'cubic'],
        ['gray 4×3×2', [0.3, 0.3, 0.3], [1.5, 1.5, 1.5], true, 'non-cubic'],
      ] as const) {
        const scene = await gridScene([...sigmaA], [...sigmaS], shape);
        const conditions = plan(scene.scene).conditions;
        expect(conditions, 'the plan picks it').toMatchObject({
          oneGridMedium: true,
          grayMedia: gray,
        });
        const specialized = await gpu(scene);
        expectAgreement(
          specialized,
          await cpu(scene),
          `${name} one-grid-medium path tracer, GPU vs twin`,
        );
        expectAgreement(
          specialized,
          await gpu(scene, { kernel: 'general' }),
          `${name} one-grid-medium path tracer vs general kernel`,
        );
      }
    },
    GPU_TIMEOUT,
  );

  it(
    'a grid record without volume under a valid medium box (the kernel’s empty-box and zero-majorant substitution): no medium, every pixel 0, GPU = twin',
    async () => {
      // Scenes cannot make this (validation wants dimensions ≥ 1 and the grid fills its
      // medium's bounds), so the grid record is changed by hand: the medium's segments stay
      // non-empty and reach the lookups and the DDA, which must see no density and a
      // majorant of 0.
      const scene = await sceneFrom({
        image: { width: 4, height: 4 },
        samplesPerPixel: 8,
        seed: 2,
        scatteringOrder: 'unlimited',
        camera: {
          type: 'orthographic',
          position: [0.5, 0.5, 3],
          direction: [0, 0, -1],
          up: [0, 1, 0],
          width: 1,
          height: 1,
        },
        media: [
          {
            type: 'grid',
            bounds: { type: 'box', min: [0, 0, 0], max: [1, 1, 1] },
            sigmaA: [0.2, 0.2, 0.2],
            sigmaS: [5, 5, 5],
            phase: { type: 'isotropic' },
            grid: { dimensions: [2, 2, 2], density: [1, 2, 3, 4, 5, 6, 7, 8] },
          },
        ],
        lights: [{ type: 'directional', direction: [0, 0, -1], irradiance: [1, 1, 1] }],
      });
      expect(plan(scene.scene).conditions.oneGridMedium).toBe(true);
      // The fine grid gets no samples along x (gridHasVolume is false), its box and the
      // majorant grid stay as they were: without the substitution, a lookup would read the
      // buffer's one sample (1) and the DDA find a majorant, and the medium would scatter.
      const grid = scene.grid!;
      const flattened = {
        ...scene,
        grid: {
          ...grid,
          fine: {
            ...grid.fine,
            grid: { ...grid.fine.grid, dimensions: [0, 2, 2] as [number, number, number] },
          },
        },
      };
      const zeros = new Array(4 * 4 * 3).fill(0);
      expect(Array.from((await gpu(flattened)).mean)).toEqual(zeros);
      expect(Array.from((await cpu(flattened)).mean)).toEqual(zeros);
      // The same scene unflattened is lit: the test looks where light would be.
      expect(Math.max(...(await gpu(scene)).mean)).toBeGreaterThan(0.01);
    },
    GPU_TIMEOUT,
  );

  it(
    'specialized (single scattering, Beer) vs general (path tracer at order 1, tracking) on the §5 slab',
    async () => {
      const scene = await sceneFrom(slabScene('homogeneous'));
      const general = await gpu(scene, { kernel: 'general', spp: 256 });
      expectAgreement(await gpu(scene), general, 'slab, specialized vs general');
      expectMatchesExact(
        general,
        (_, c) => slabExact(c),
        'slab, general kernel',
        2e-5 * slabExact(0),
      );
    },
    GPU_TIMEOUT,
  );
});
