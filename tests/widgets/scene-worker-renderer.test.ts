// The scene widgets' CPU fallback with its passes in the compute worker
// (src/scene/workerRenderer.ts, passJob.ts, the widgets' jobs.ts), run through
// workerJobs as the views call it (in the page under Vitest, so the arguments must be
// cloneable and the job table must load by folder name): the same moments, bit for bit,
// as the in-page twin (CpuSceneRenderer) over the same passes; a pass abandoned by an
// input leaves the accumulation as it was; the scene hash tells scenes apart.
import { describe, expect, it } from 'vitest';
import { CpuSceneRenderer } from '../../src/scene/cpuRenderer.ts';
import { resolveScene } from '../../src/scene/load.ts';
import { packScene, sceneData } from '../../src/scene/pack.ts';
import { plan } from '../../src/scene/plan.ts';
import { WorkerSceneRenderer, sceneHash } from '../../src/scene/workerRenderer.ts';
import { parseScene } from '../../src/scene/validate.ts';
import { buildScene, type PathTracerInputs } from '../../src/widgets/volume-path-tracer/model.ts';
import type { jobs } from '../../src/widgets/volume-path-tracer/jobs.ts';
import { workerJobs } from '../../src/workers/compute.ts';

const INPUTS: PathTracerInputs = { scene: 'cloud', albedo: 0.9, g: 0.5, density: 6, spp: 4 };
const SIZE = { width: 6, height: 5 };

async function sceneOf(inputs: PathTracerInputs, order: 1 | 'unlimited') {
  const description = parseScene(buildScene(inputs, order, SIZE, 4, 3));
  const packed = packScene(await resolveScene(description));
  // Each renderer gets its own SceneData (the twin decodes records into it).
  return {
    packed,
    data: () => sceneData(packed, plan(description).conditions),
  };
}

describe('WorkerSceneRenderer', () => {
  const cpuJobs = workerJobs<typeof jobs>('volume-path-tracer');
  const live = new AbortController();

  it('accumulates the same moments as the in-page twin, pass by pass', async () => {
    const { packed, data } = await sceneOf(INPUTS, 'unlimited');
    const inPage = new CpuSceneRenderer(data(), packed.width, packed.height, packed.seed);
    const worker = new WorkerSceneRenderer(
      cpuJobs,
      data(),
      packed.width,
      packed.height,
      packed.seed,
      () => live.signal,
    );
    for (const [offset, samples] of [
      [0, 1],
      [1, 3],
      [4, 2],
    ] as const) {
      await inPage.renderPass(offset, samples);
      const output = await worker.renderPass(offset, samples);
      expect(output.milliseconds).toBeGreaterThanOrEqual(0);
    }
    const a = inPage.accumulation;
    const b = worker.accumulation;
    expect(b.samples).toBe(6);
    expect(Array.from(b.meanValues)).toEqual(Array.from(a.meanValues));
    expect(Array.from(b.m2)).toEqual(Array.from(a.m2));
    expect(b.lookups).toBe(a.lookups);
    expect(b.lookups).toBeGreaterThan(0); // the cloud's grid was looked up
    // Not a constant image: the moments carry the scene.
    expect(Math.max(...b.meanValues)).toBeGreaterThan(Math.min(...b.meanValues));
  });

  it('drops a pass whose input signal aborted and keeps the accumulation as it was', async () => {
    const { packed, data } = await sceneOf(INPUTS, 1);
    const input = new AbortController();
    const worker = new WorkerSceneRenderer(
      cpuJobs,
      data(),
      packed.width,
      packed.height,
      packed.seed,
      () => input.signal,
    );
    await worker.renderPass(0, 1);
    const before = Array.from(worker.accumulation.meanValues);
    const pending = worker.renderPass(1, 2);
    input.abort();
    await expect(pending).rejects.toThrow(/no longer needed/);
    expect(worker.accumulation.samples).toBe(1);
    expect(Array.from(worker.accumulation.meanValues)).toEqual(before);
  });

  it('tells scenes apart by their records, grids and conditions', async () => {
    const single = (await sceneOf(INPUTS, 1)).data();
    const multiple = (await sceneOf(INPUTS, 'unlimited')).data();
    const denser = (await sceneOf({ ...INPUTS, density: 7 }, 1)).data();
    const same = (await sceneOf(INPUTS, 1)).data();
    expect(sceneHash(same)).toBe(sceneHash(single));
    expect(sceneHash(multiple)).not.toBe(sceneHash(single));
    expect(sceneHash(denser)).not.toBe(sceneHash(single));
  });
});
