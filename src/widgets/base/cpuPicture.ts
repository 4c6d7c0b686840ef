// A CPU twin's picture for the fallback: painted by a job in the compute worker at
// the resolution of a Ladder rung (first a coarse one that fits the CPU's first-picture
// budget, then finer ones, refinement.ts), and scaled onto the canvas. The page only
// draws the finished pixels, so a slow CPU never blocks input.
import type { WorkerJobs } from '../../workers/compute.ts';
import { drawPixels } from './pixels.ts';
import {
  CPU_FIRST_PICTURE_MS,
  Ladder,
  type FrameRequest,
  type Refinement,
  type Rung,
} from './refinement.ts';

/** What a stage of the picture cost and which stage it is. */
export interface CpuPictureStage {
  width: number;
  height: number;
  /** Wall time from asking the worker to the pixels on the canvas (0 when cached). */
  milliseconds: number;
  refinement: Refinement;
}

/** The job that paints: (inputs, width, height) → RGBA pixels. */
type PaintJob<Inputs> = (
  inputs: Inputs,
  width: number,
  height: number,
) => Uint8ClampedArray<ArrayBuffer>;

/**
 * Paints `canvas` at 1/scale of its size for each of `scales` (coarse → fine; the last
 * is full quality), through the job `name` of a widget's jobs.ts.
 */
export class CpuPicture<Inputs, K extends string> {
  private readonly ladder: Ladder<number>;

  constructor(
    private readonly jobs: WorkerJobs<Record<K, PaintJob<Inputs>>>,
    private readonly name: K,
    canvasSize: { width: number; height: number },
    scales: readonly number[],
  ) {
    const rungs: Rung<number>[] = scales.map((scale, i) => {
      const { width, height } = sizeAt(canvasSize, scale);
      const last = i === scales.length - 1;
      return {
        value: scale,
        work: width * height,
        label: `${width}×${height} pixels${last ? '' : ` (1/${scale} of the canvas)`}`,
      };
    });
    this.ladder = new Ladder(rungs, CPU_FIRST_PICTURE_MS);
  }

  /** Paints the stage `request` asks for; throws an AbortError if the inputs changed meanwhile. */
  async draw(
    canvas: HTMLCanvasElement,
    inputs: Inputs,
    request: FrameRequest,
  ): Promise<CpuPictureStage> {
    const choice = this.ladder.pick(request);
    const { width, height } = sizeAt(canvas, choice.rung.value);
    // (inputs, width, height): what PaintJob takes; TypeScript cannot resolve the job
    // table's argument type for a generic K, hence `never` at the two calls.
    const args = [inputs, width, height] as never;
    const cached = this.jobs.cached(this.name, args) !== undefined;
    const start = performance.now();
    const pixels: Uint8ClampedArray<ArrayBuffer> = await this.jobs.run(this.name, args, {
      signal: request.signal,
    });
    drawPixels(canvas, pixels, width, height);
    const milliseconds = cached ? 0 : performance.now() - start;
    // A cached picture says nothing about the cost of painting one.
    if (!cached) this.ladder.record(choice.index, milliseconds);
    return { width, height, milliseconds, refinement: this.ladder.refinement(choice) };
  }
}

function sizeAt(
  size: { width: number; height: number },
  scale: number,
): { width: number; height: number } {
  return {
    width: Math.max(1, Math.floor(size.width / scale)),
    height: Math.max(1, Math.floor(size.height / scale)),
  };
}
