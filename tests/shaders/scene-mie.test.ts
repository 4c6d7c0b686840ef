// A Lorenz–Mie medium (src/phase/registry.ts `mie`) in the scene kernel on the GPU
// (Dawn; SwiftShader without a GPU): the phase-table buffer bound at integrator.wesl
// binding 5 and read through the entry's WGSL case, against the float64 twin and the
// closed form.
//  - the physics.md §5 slab with Bohren & Huffman's sphere (x = 3, m = 1.55): the
//    single-scattering kernel matches the closed form with the phase function of the Mie
//    series (the table's error at that angle allowed), and the twin;
//  - the example scene public/scenes/mie-fog.json (path tracer, x = 57 droplets, sun, sky,
//    floor): GPU = twin on the same samples, and the specialized kernel = the general one
//    (per-pixel z-scores from both standard errors, tests/support/sceneRender.ts).
// Small images and few samples: SwiftShader runs WebGPU on the CPU.
import { beforeAll, describe, it } from 'vitest';
import type { ResolvedScene } from '../../src/scene/load.ts';
import type { SceneRenderOptions } from '../../src/scene/renderScene.ts';
import {
  BH_SPHERE,
  bhSphereSlabPhase,
  mieSlabSystematic,
  slabExact,
  slabScene,
} from '../support/analyticScenes.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import {
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

// Linking and compiling a kernel in SwiftShader takes seconds to minutes on a loaded machine.
const GPU_TIMEOUT = 300_000;

describe('a Mie medium in the scene kernel on the GPU', () => {
  it(
    'physics.md §5 slab with a Mie phase function: GPU = closed form (series phase) and = twin',
    async () => {
      const scene = await sceneFrom(slabScene('homogeneous', 1, BH_SPHERE));
      const estimate = await gpu(scene);
      const { series } = bhSphereSlabPhase();
      // f32 allowance as for the HG slab (tests/shaders/scene-render.test.ts).
      expectMatchesExact(
        estimate,
        (_, c) => slabExact(c, series),
        'Mie slab on the GPU',
        mieSlabSystematic(2e-5),
      );
      expectAgreement(estimate, await cpu(scene), 'Mie slab, GPU vs twin');
    },
    GPU_TIMEOUT,
  );

  it(
    'mie-fog (path tracer): GPU = twin, and the specialized kernel = the general one',
    async () => {
      const scene = await exampleScene('mie-fog', {
        image: { width: 8, height: 8 },
        samplesPerPixel: 32,
      });
      const specialized = await gpu(scene);
      expectAgreement(specialized, await cpu(scene), 'mie-fog, GPU vs twin');
      expectAgreement(
        specialized,
        await gpu(scene, { kernel: 'general', spp: 64 }),
        'mie-fog, specialized vs general',
      );
    },
    GPU_TIMEOUT,
  );
});
