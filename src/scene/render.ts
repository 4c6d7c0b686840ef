// The progressive render loop shared by both backends: passes of a few samples per
// pixel, each added by the renderer to its own Accumulation (on the GPU for the GPU
// renderer: nothing is read back per pass but the pass's timestamps), with the time of
// every pass (GPU timestamp queries, GPU wall time or CPU wall time) and a progress
// callback. The whole image is read back once, at the end.
import type { Accumulation, ImageAccumulator } from './accumulation.ts';

export type PassTiming = 'gpu-timestamp' | 'gpu-wall' | 'cpu';

export interface PassOutput {
  milliseconds: number;
  /** Defaults to the renderer's timing. */
  timing?: PassTiming;
}

export interface PassRenderer {
  readonly timing: PassTiming;
  /** Where the passes accumulate (destroyed with the renderer unless released). */
  readonly accumulation: Accumulation;
  /**
   * Samples sampleOffset … sampleOffset + samples − 1 of every pixel, added to the
   * accumulation (whose sample count grows by `samples`).
   */
  renderPass(sampleOffset: number, samples: number): Promise<PassOutput>;
  /** Frees the renderer but hands its accumulation to the caller, who destroys it. */
  release(): Accumulation;
  destroy(): void;
}

export interface PassRecord {
  sampleOffset: number;
  samples: number;
  milliseconds: number;
  timing: PassTiming;
}

export interface RenderProgress {
  samples: number;
  totalSamples: number;
  pass: number;
  passes: number;
  elapsedMs: number;
}

export interface RenderOptions {
  spp: number;
  /** Samples per pixel per pass (the last pass takes the rest). */
  samplesPerPass: number;
  onPass?: (progress: RenderProgress) => void;
  /** Stops after the current pass when it returns true. */
  cancelled?: () => boolean;
}

export interface RenderResult {
  /** The whole accumulated image, read back once at the end. */
  accumulator: ImageAccumulator;
  passes: PassRecord[];
  wallMs: number;
}

/** A pass size that keeps a pass near `budget` path samples (width·height·samples). */
export function samplesPerPassFor(
  width: number,
  height: number,
  spp: number,
  budget = 1 << 16,
): number {
  return Math.max(1, Math.min(spp, Math.floor(budget / (width * height))));
}

export async function renderProgressive(
  renderer: PassRenderer,
  width: number,
  height: number,
  options: RenderOptions,
): Promise<RenderResult> {
  const accumulation = renderer.accumulation;
  if (accumulation.width !== width || accumulation.height !== height)
    throw new Error('the renderer accumulates another image size');
  const passes: PassRecord[] = [];
  const perPass = Math.max(1, Math.floor(options.samplesPerPass));
  const count = Math.ceil(options.spp / perPass);
  const start = performance.now();
  for (let pass = 0; pass < count; pass++) {
    if (options.cancelled?.()) break;
    const sampleOffset = pass * perPass;
    const samples = Math.min(perPass, options.spp - sampleOffset);
    const output = await renderer.renderPass(sampleOffset, samples);
    passes.push({
      sampleOffset,
      samples,
      milliseconds: output.milliseconds,
      timing: output.timing ?? renderer.timing,
    });
    options.onPass?.({
      samples: accumulation.samples,
      totalSamples: options.spp,
      pass: pass + 1,
      passes: count,
      elapsedMs: performance.now() - start,
    });
  }
  const accumulator = await accumulation.readImage();
  return { accumulator, passes, wallMs: performance.now() - start };
}
