// The progressive render loop shared by both backends: passes of a few samples per
// pixel, each added to an ImageAccumulator, with the time of every pass (GPU timestamp
// queries, GPU wall time or CPU wall time) and a progress callback.
import { ImageAccumulator } from './accumulation.ts';

export type PassTiming = 'gpu-timestamp' | 'gpu-wall' | 'cpu';

export interface PassOutput {
  /** PASS_WORDS_PER_PIXEL words per pixel, read as floats (sums) and as u32 (counters). */
  floats: ArrayLike<number>;
  words: ArrayLike<number>;
  milliseconds: number;
  /** Defaults to the renderer's timing. */
  timing?: PassTiming;
}

export interface PassRenderer {
  readonly timing: PassTiming;
  /** Samples sampleOffset … sampleOffset + samples − 1 of every pixel. */
  renderPass(sampleOffset: number, samples: number): Promise<PassOutput>;
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
  const accumulator = new ImageAccumulator(width, height);
  const passes: PassRecord[] = [];
  const perPass = Math.max(1, Math.floor(options.samplesPerPass));
  const count = Math.ceil(options.spp / perPass);
  const start = performance.now();
  for (let pass = 0; pass < count; pass++) {
    if (options.cancelled?.()) break;
    const sampleOffset = pass * perPass;
    const samples = Math.min(perPass, options.spp - sampleOffset);
    const output = await renderer.renderPass(sampleOffset, samples);
    accumulator.addPass(output.floats, output.words, samples);
    passes.push({
      sampleOffset,
      samples,
      milliseconds: output.milliseconds,
      timing: output.timing ?? renderer.timing,
    });
    options.onPass?.({
      samples: accumulator.samples,
      totalSamples: options.spp,
      pass: pass + 1,
      passes: count,
      elapsedMs: performance.now() - start,
    });
  }
  return { accumulator, passes, wallMs: performance.now() - start };
}
