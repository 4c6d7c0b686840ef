// CPU backend of <sb-dipole-profile>, used without WebGPU or after a device loss: the
// curves from the float64 twins (model.ts) and the disc's pixels at reduced resolution,
// both computed in the compute worker (jobs.ts) and put on the page here, and the Monte
// Carlo replayed by the twin batch by batch, yielding to the page between slices so
// that a long run never freezes it.
import { runSlabCpuBatches, type SlabBatches, type SlabRun } from '../../subsurface/slabKernel.ts';
import {
  DISC_FRACTION,
  discColour,
  evaluateProfilesCpu,
  type CurveInputs,
  type ProfileCurves,
  type ProfileInputs,
} from './model.ts';

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
 */
export function discPixelsCpu(inputs: DiscInputs, size = CPU_DISC_SIZE): DiscPixels {
  const start = performance.now();
  const data = new Uint8ClampedArray(4 * size * size);
  const background = [0.018, 0.02, 0.026].map((v) => Math.round(255 * v ** (1 / 2.2)));
  const rim = DISC_FRACTION * inputs.view;
  const pixel = (2 * inputs.view) / size;
  // The colour depends on r only: cache it per ring of half a pixel.
  const rings = new Map<number, [number, number, number]>();
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const px = ((x + 0.5) / size - 0.5) * 2 * inputs.view;
      const py = ((y + 0.5) / size - 0.5) * 2 * inputs.view;
      const r = Math.hypot(px, py);
      const o = 4 * (y * size + x);
      let rgb: number[];
      if (r <= rim) {
        const ring = Math.round((2 * r) / pixel);
        let colour = rings.get(ring);
        if (!colour) {
          colour = discColour(inputs, (ring * pixel) / 2);
          rings.set(ring, colour);
        }
        rgb = colour.map((v) => Math.round(255 * v));
      } else {
        rgb = background;
      }
      if (Math.abs(r - rim) < 0.75 * pixel) rgb = rgb.map((v) => Math.round(0.3 * v + 0.7 * 182));
      data[o] = rgb[0]!;
      data[o + 1] = rgb[1]!;
      data[o + 2] = rgb[2]!;
      data[o + 3] = 255;
    }
  }
  return { pixels: data, size, milliseconds: performance.now() - start };
}

/** Puts a disc picture from discPixelsCpu on a 2D canvas. */
export function paintDiscPixels(canvas: HTMLCanvasElement, disc: DiscPixels): void {
  canvas.width = disc.size;
  canvas.height = disc.size;
  const context = canvas.getContext('2d');
  if (!context) return;
  context.putImageData(new ImageData(disc.pixels, disc.size, disc.size), 0, 0);
}

/** Longest stretch (ms) the fallback computes before it lets the page paint and take input. */
const SLICE_MS = 12;

/**
 * The twin's replay of a run, one batch at a time with pauses; `cancelled()` is checked
 * between batches. Returns the batches done and the CPU time spent computing.
 */
export async function monteCarloCpu(
  run: SlabRun,
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
  let slice = 0;
  for (let b = 0; b < run.batches; b++) {
    if (cancelled()) return { batches, milliseconds: busy, complete: false };
    const start = performance.now();
    batches = runSlabCpuBatches(run, b, b + 1, batches);
    const spent = performance.now() - start;
    busy += spent;
    slice += spent;
    if (slice > SLICE_MS && b + 1 < run.batches) {
      await new Promise((resolve) => setTimeout(resolve, 0));
      slice = 0;
    }
  }
  return { batches, milliseconds: busy, complete: true };
}
