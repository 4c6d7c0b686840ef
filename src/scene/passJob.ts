// The CPU twin's render pass as a compute-worker job (src/workers/compute.ts): the
// scene widgets' CPU fallback (volume-path-tracer, single-scatter) renders its passes
// off the page's thread, where a pass blocked the page for up to ~0.6 s during a drag
// (issue 23). Each widget's jobs.ts exports `scenePass`. The scene travels with every
// pass (structured clone: the records and grids, kilobytes to a few hundred); the worker
// keeps the last few scenes by their hash so that their decoded records (SceneData.cache)
// are built once, not per pass.
import type { SceneData } from '../reference/integrator.ts';
import { renderPassSums } from './cpuRenderer.ts';

/** Scenes the worker keeps decoded (a couple of widgets, each an image and a reference). */
const KEPT_SCENES = 8;
const scenes = new Map<string, SceneData>();

function keptScene(hash: string, scene: SceneData): SceneData {
  const kept = scenes.get(hash);
  if (kept) {
    scenes.delete(hash);
    scenes.set(hash, kept);
    return kept;
  }
  scenes.set(hash, scene);
  while (scenes.size > KEPT_SCENES) scenes.delete(scenes.keys().next().value!);
  return scene;
}

/** One pass's sums (renderPassSums) and its time in the worker. */
export interface ScenePassResult {
  sums: Float64Array;
  milliseconds: number;
}

/**
 * Renders one pass of `scene` (identified by `hash`, sceneHash) off the page's thread.
 * Deterministic in its arguments, so the worker's per-argument cache is safe.
 */
export function scenePass(
  hash: string,
  scene: SceneData,
  width: number,
  height: number,
  seed: number,
  sampleOffset: number,
  samples: number,
): ScenePassResult {
  const start = performance.now();
  const sums = renderPassSums(keptScene(hash, scene), width, height, seed, sampleOffset, samples);
  return { sums, milliseconds: performance.now() - start };
}

/** The job table a scene widget's jobs.ts exports. */
export const scenePassJobs = { scenePass } as const;
