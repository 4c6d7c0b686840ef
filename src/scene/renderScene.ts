// One call to render a resolved scene on either backend: plan it, pack it, specialize
// the kernel (or use the general one) and run the progressive loop. Used by the command
// line, the benchmarks, the tests and (later) the chapter 9–10 widgets.
import type { KernelLibrary } from '../gpu/link.ts';
import { CpuSceneRenderer } from './cpuRenderer.ts';
import { GpuSceneRenderer } from './gpuRenderer.ts';
import type { ResolvedScene } from './load.ts';
import { packScene, sceneData } from './pack.ts';
import { GENERAL_CONDITIONS, plan, type Conditions, type Plan } from './plan.ts';
import {
  renderProgressive,
  samplesPerPassFor,
  type PassRenderer,
  type RenderProgress,
  type RenderResult,
} from './render.ts';

export type Backend = { kind: 'gpu'; device: GPUDevice; library: KernelLibrary } | { kind: 'cpu' };

export interface SceneRenderOptions {
  /** Samples per pixel; the scene's samplesPerPixel when absent. */
  spp?: number;
  /** 'plan' (default): the specialized kernel; 'general': every effect, general methods. */
  kernel?: 'plan' | 'general';
  samplesPerPass?: number;
  onPass?: (progress: RenderProgress) => void;
  cancelled?: () => boolean;
}

export interface SceneRender extends RenderResult {
  plan: Plan;
  conditions: Conditions;
  backend: 'gpu' | 'cpu';
  spp: number;
  /** The linked WGSL (GPU backend only). */
  code: string | null;
}

export async function renderScene(
  resolved: ResolvedScene,
  backend: Backend,
  options: SceneRenderOptions = {},
): Promise<SceneRender> {
  const scenePlan = plan(resolved.scene);
  const conditions = options.kernel === 'general' ? GENERAL_CONDITIONS : scenePlan.conditions;
  const packed = packScene(resolved);
  const spp = options.spp ?? resolved.scene.samplesPerPixel;
  const renderer: PassRenderer =
    backend.kind === 'gpu'
      ? await GpuSceneRenderer.create(backend.device, backend.library, packed, conditions)
      : new CpuSceneRenderer(
          sceneData(packed, conditions),
          packed.width,
          packed.height,
          packed.seed,
        );
  try {
    const result = await renderProgressive(renderer, packed.width, packed.height, {
      spp,
      samplesPerPass:
        options.samplesPerPass ??
        samplesPerPassFor(
          packed.width,
          packed.height,
          spp,
          backend.kind === 'gpu' ? 1 << 16 : 1 << 12,
        ),
      ...(options.onPass ? { onPass: options.onPass } : {}),
      ...(options.cancelled ? { cancelled: options.cancelled } : {}),
    });
    return {
      ...result,
      plan: scenePlan,
      conditions,
      backend: backend.kind,
      spp: result.accumulator.samples,
      code: renderer instanceof GpuSceneRenderer ? renderer.code : null,
    };
  } finally {
    renderer.destroy();
  }
}
