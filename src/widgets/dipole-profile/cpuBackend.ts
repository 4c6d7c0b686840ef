// CPU backend of <sb-dipole-profile>, used without WebGPU or after a device loss: the
// curves from the float64 twins (model.ts) and the disc's pixels at reduced resolution,
// both computed in the compute worker (jobs.ts) and put on the page here, and the Monte
// Carlo replayed by the twin in chunks of batches, also in the worker, so that a long
// run never holds the page.
import {
  appendBatches,
  runSlabCpuBatches,
  type SlabBatches,
  type SlabRun,
} from '../../subsurface/slabKernel.ts';
import {
  DISC_FRACTION,
  discColour,
  evaluateProfilesCpu,
  type CurveInputs,
  type ProfileCurves,
  type ProfileInputs,
} from './model.ts';
import { context2d } from '../base/canvas2d.ts';

/** Side of the disc picture drawn by the CPU (the GPU draws DISC_SIZE). */
export const CPU_DISC_SIZE = 160;

export function curvesCpu(inputs: CurveInputs): { curves: ProfileCurves; milliseconds: number } {
  const start = performance.now();
  const curves = evaluateProfilesCpu(inputs);
  return { curves, milliseconds: performance.now() - start };
}

/** What the disc picture depends on (a cache key of the worker job holds nothing else). */
export type DiscInputs = Pick<
  ProfileInputs,
  'sigmaSPrime' | 'sigmaA' | 'eta' | 'exposure' | 'view'
>;

/** The disc picture's RGBA bytes (size × size) and the float64 time they took (ms). */
export interface DiscPixels {
  pixels: Uint8ClampedArray<ArrayBuffer>;
  size: number;
  milliseconds: number;
}

/**
 * The lit disc (the twin of discFragment) as RGBA bytes of size × size pixels: pure, so
 * it runs in the compute worker (jobs.ts) and the page only puts the bytes on a canvas.
 * The colour depends on r only, so it is computed once per ring of half a pixel and
 * kept as bytes; the loop over the pixels then only looks up and writes (no arrays per
 * pixel: with three small arrays allocated per pixel the 160² disc took 90–160 ms in
 * the worker, most of the CPU fallback's first picture after an input, issue 23).
 */
export function discPixelsCpu(inputs: DiscInputs, size = CPU_DISC_SIZE): DiscPixels {
  const start = performance.now();
  const data = new Uint8ClampedArray(4 * size * size);
  const background = [0.018, 0.02, 0.026].map((v) => Math.round(255 * v ** (1 / 2.2)));
  const rim = DISC_FRACTION * inputs.view;
  const pixel = (2 * inputs.view) / size;
  // Ring k (r ≈ k·pixel/2) → its colour's bytes at 3k…3k+2 (−1: not computed yet).
  const rings = new Int16Array(3 * (Math.ceil((2 * rim) / pixel) + 2)).fill(-1);
  const rimBlend = (v: number): number => Math.round(0.3 * v + 0.7 * 182);
  for (let y = 0; y < size; y++) {
    const py = ((y + 0.5) / size - 0.5) * 2 * inputs.view;
    for (let x = 0; x < size; x++) {
      const px = ((x + 0.5) / size - 0.5) * 2 * inputs.view;
      const r = Math.sqrt(px * px + py * py);
      const o = 4 * (y * size + x);
      let red = background[0]!;
      let green = background[1]!;
      let blue = background[2]!;
      if (r <= rim) {
        const ring = 3 * Math.round((2 * r) / pixel);
        if (rings[ring]! < 0) {
          const colour = discColour(inputs, ((ring / 3) * pixel) / 2);
          for (let c = 0; c < 3; c++) rings[ring + c] = Math.round(255 * colour[c]!);
        }
        red = rings[ring]!;
        green = rings[ring + 1]!;
        blue = rings[ring + 2]!;
      }
      if (Math.abs(r - rim) < 0.75 * pixel) {
        red = rimBlend(red);
        green = rimBlend(green);
        blue = rimBlend(blue);
      }
      data[o] = red;
      data[o + 1] = green;
      data[o + 2] = blue;
      data[o + 3] = 255;
    }
  }
  return { pixels: data, size, milliseconds: performance.now() - start };
}

/** Puts a disc picture from discPixelsCpu on a 2D canvas. */
export function paintDiscPixels(canvas: HTMLCanvasElement, disc: DiscPixels): void {
  canvas.width = disc.size;
  canvas.height = disc.size;
  const context = context2d(canvas);
  if (!context) return;
  context.putImageData(new ImageData(disc.pixels, disc.size, disc.size), 0, 0);
}

/**
 * Worker time one job of the Monte Carlo replay aims at (ms). The compute worker runs one
 * job at a time, so an input's curves and disc wait for at most one such chunk.
 */
const CHUNK_MS = 40;

/** One chunk of the replay: batches [first, last) of every channel, and its float64 time (ms). */
export interface SlabChunk {
  batches: SlabBatches;
  milliseconds: number;
}

/** The twin's batches [first, last) of `run` (the job jobs.ts runs in the compute worker). */
export function slabChunkCpu(run: SlabRun, first: number, last: number): SlabChunk {
  const start = performance.now();
  const batches = runSlabCpuBatches(run, first, last);
  return { batches, milliseconds: performance.now() - start };
}

/** Runs a chunk of batches off the page (the view passes the compute worker's job). */
export type SlabChunkRunner = (run: SlabRun, first: number, last: number) => Promise<SlabChunk>;

/**
 * The twin's replay of a run in chunks of batches computed by `runChunk` (in the compute
 * worker, so the page's thread only appends their sums: issue 23, no main-thread task
 * over 50 ms; on the page the replay held 60–130 ms tasks with its garbage collection).
 * Each chunk is sized to CHUNK_MS from the cost of the last, and the next one is asked
 * for before the current one is back, so that the worker does not wait while the page
 * takes a result (an input's jobs then wait for at most two chunks). `cancelled()` is
 * checked between chunks, and an abort of a chunk's job (the reader's next input) ends
 * the replay with the batches done so far. Returns them and the worker's float64 time.
 */
export async function monteCarloCpu(
  run: SlabRun,
  runChunk: SlabChunkRunner,
  cancelled: () => boolean,
): Promise<{ batches: SlabBatches; milliseconds: number; complete: boolean }> {
  let batches: SlabBatches = {
    channels: run.channels.map(() => ({
      walks: [],
      reflected: [],
      transmitted: [],
      unscattered: [],
      cappedWeight: [],
      collisions: [],
      capped: [],
      profile: [],
    })),
  };
  let busy = 0;
  let perBatch = 0;
  const ask = (first: number): { first: number; last: number; result: Promise<SlabChunk> } => {
    const size = perBatch > 0 ? Math.max(1, Math.floor(CHUNK_MS / perBatch)) : 1;
    const last = Math.min(first + size, run.batches);
    const result = runChunk(run, first, last);
    // Awaited in its turn; until then a rejection (an abort) must not go unhandled.
    result.catch(() => undefined);
    return { first, last, result };
  };
  let current = run.batches > 0 ? ask(0) : null;
  while (current) {
    if (cancelled()) return { batches, milliseconds: busy, complete: false };
    const ahead = current.last < run.batches ? ask(current.last) : null;
    let chunk: SlabChunk;
    try {
      chunk = await current.result;
    } catch (error) {
      if (error instanceof DOMException && error.name === 'AbortError')
        return { batches, milliseconds: busy, complete: false };
      throw error;
    }
    batches = appendBatches(batches, chunk.batches);
    busy += chunk.milliseconds;
    perBatch = chunk.milliseconds / (current.last - current.first);
    current = ahead;
  }
  return { batches, milliseconds: busy, complete: true };
}
