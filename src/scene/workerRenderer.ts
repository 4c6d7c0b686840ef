// The CPU twin's PassRenderer with its passes in the compute worker (passJob.ts): the
// page keeps the float64 accumulation (adding a pass is a few thousand additions) and
// the worker traces the paths, so a pass never blocks the page. A pass is abandoned
// when the input signal of the moment it was asked for aborts (the reader moved on):
// queued, it is dropped; running, its result is ignored and the accumulation is left
// as it was.
import type { SceneData } from '../reference/integrator.ts';
import type { WorkerJobs } from '../workers/compute.ts';
import { ImageAccumulator, type Accumulation } from './accumulation.ts';
import type { scenePassJobs } from './passJob.ts';
import type { PassOutput, PassRenderer } from './render.ts';

/** FNV-1a over 32-bit words: identifies a scene's records, grids, tables and conditions. */
function fnv(hash: number, words: ArrayLike<number>): number {
  let h = hash;
  for (let i = 0; i < words.length; i++) {
    h ^= words[i]!;
    h = Math.imul(h, 0x01000193) >>> 0;
  }
  return h;
}

/**
 * A hash of everything a pass depends on in the scene (records, grids, phase tables,
 * conditions).
 */
export function sceneHash(scene: SceneData): string {
  const u32 = (array: Float32Array): Uint32Array =>
    new Uint32Array(array.buffer, array.byteOffset, array.length);
  let h = 0x811c9dc5;
  h = fnv(h, scene.words);
  h = fnv(h, u32(scene.density));
  h = fnv(h, u32(scene.majorant));
  h = fnv(h, u32(scene.phaseTables));
  const conditions = Object.entries(scene.conditions)
    .filter(([, on]) => on)
    .map(([name]) => name)
    .sort()
    .join(',');
  return `${h.toString(16)}-${scene.words.length}-${scene.density.length}-${conditions}`;
}

export class WorkerSceneRenderer implements PassRenderer {
  readonly timing = 'cpu' as const;
  readonly accumulation: ImageAccumulator;
  private readonly hash: string;
  private destroyed = false;

  /**
   * `signal()` gives the signal a pass listens to (the view's current input signal); the
   * scene must not carry decoded records (a fresh sceneData()), so that it clones small.
   */
  constructor(
    private readonly jobs: WorkerJobs<typeof scenePassJobs>,
    private readonly scene: SceneData,
    private readonly width: number,
    private readonly height: number,
    private readonly seed: number,
    private readonly signal: () => AbortSignal,
  ) {
    this.accumulation = new ImageAccumulator(width, height);
    this.hash = sceneHash(scene);
  }

  async renderPass(sampleOffset: number, samples: number): Promise<PassOutput> {
    const { hash, scene, width, height, seed } = this;
    const result = await this.jobs.run(
      'scenePass',
      [hash, scene, width, height, seed, sampleOffset, samples],
      {
        signal: this.signal(),
        // The scene's hash stands for the scene in the cache key (JSON of its grids
        // would cost more than the pass).
        key: `scenePass(${hash},${width}x${height},${seed},${sampleOffset},${samples})`,
      },
    );
    if (this.destroyed) throw new DOMException('the renderer was destroyed', 'AbortError');
    this.accumulation.addPass(result.sums, result.sums, samples);
    return { milliseconds: result.milliseconds };
  }

  release(): Accumulation {
    this.destroyed = true;
    return this.accumulation;
  }

  destroy(): void {
    this.destroyed = true;
  }
}
