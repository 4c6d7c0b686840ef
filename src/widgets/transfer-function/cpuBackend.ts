// The two ways <sb-transfer-function> renders rows of its image, behind one
// interface (FrameRenderer): the GPU kernel (gpuBackend.ts, bands read back into
// the full image) and, without WebGPU, the float64 twin in model.ts at
// CPU_SIZE² pixels. Also the painting of images into 2D canvases.
import { cacheKey, workerJobs, type WorkerJobs } from '../../workers/compute.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import type { Rgb } from '../base/imagePanel.ts';
import { abortError, runInBands } from '../../gpu/bands.ts';
import type { VolumeRendererGpu } from './gpuBackend.ts';
import { rowsScene, type jobs as rowJobs, type RowsBand } from './jobs.ts';
import { CPU_SIZE, emptyImage, IMAGE_SIZE, type FrameInputs, type VolumeImage } from './model.ts';
import { context2d } from '../base/canvas2d.ts';

export interface RowsCost {
  milliseconds: number;
  /** How the time was measured, for the readout (timingLabel of `timing`). */
  how: string;
  timing: GpuTiming | 'cpu';
}

export interface FrameRenderer {
  readonly kind: 'gpu' | 'cpu';
  /** Image size (pixels per side). */
  readonly size: number;
  /** A blank image of `size`² pixels (default: this renderer's full size) and its precision. */
  blank(size?: number): VolumeImage;
  /** Renders rows [rowStart, rowEnd) into `image` and adds their statistics. */
  renderInto(
    image: VolumeImage,
    inputs: FrameInputs,
    stepVoxels: number,
    threshold: number,
    rowStart: number,
    rowEnd: number,
    /** An input: a CPU renderer drops the rows not yet marched and rejects (AbortError). */
    signal?: AbortSignal,
    /** March again even where the same rows were marched before (a timing, not a picture). */
    fresh?: boolean,
    /**
     * GPU bands in flight at once (default GPU_BANDS_IN_FLIGHT): 1 for work beside the
     * frames (the reference), so that an input's picture waits for one band of it at most.
     */
    inFlight?: number,
  ): Promise<RowsCost>;
}

/**
 * Rows per job of the CPU twin: ⌊8·Δs⌋ rows (1 to 16), about the same marching per
 * job whatever the step (≈ 8 × 64 rays of ~150 steps at Δs = 1 voxel, one row of
 * ~1200 steps for the ⅛-voxel reference), so that the one worker is never held long
 * by a stale job: an input drops the chunks not yet started, and the next picture
 * waits for one chunk at most.
 */
export function chunkRows(stepVoxels: number): number {
  return Math.min(16, Math.max(1, Math.floor(8 * stepVoxels)));
}

/**
 * Chunks kept by the worker's cache (LRU): a full frame is 4 to 64 chunks, the
 * reference 64 rows; a row is 1.5 kB of float64, so a few views' worth is small.
 */
const CPU_CACHED_CHUNKS = 256;
/** Counts the fresh (uncached) runs, for their cache keys. */
let freshRuns = 0;

/** The compute worker's jobs of this widget (jobs.ts), shared by every CpuRenderer. */
let cpuJobs: WorkerJobs<typeof rowJobs> | null = null;

/**
 * The float64 twin at CPU_SIZE² pixels (or a preview's fewer), marched in the compute
 * worker (jobs.ts) so that the page only copies bands (issue 23: a row of the fine-step
 * reference held the page for hundreds of ms under load); timed by the worker's clock.
 */
export class CpuRenderer implements FrameRenderer {
  readonly kind = 'cpu';
  readonly size = CPU_SIZE;

  blank(size = this.size): VolumeImage {
    return emptyImage(size, new Float64Array(3 * size * size));
  }

  /**
   * The rows in chunks of chunkRows(Δs), all queued at once so that the worker never
   * waits on the page; `signal` (an input) rejects with an AbortError and drops the
   * chunks not yet started. The time is the worker's marching, not the queueing.
   */
  async renderInto(
    image: VolumeImage,
    inputs: FrameInputs,
    stepVoxels: number,
    threshold: number,
    rowStart: number,
    rowEnd: number,
    signal?: AbortSignal,
    fresh = false,
  ): Promise<RowsCost> {
    cpuJobs ??= workerJobs<typeof rowJobs>('transfer-function', CPU_CACHED_CHUNKS);
    const jobs = cpuJobs;
    const { size } = image;
    const scene = rowsScene(inputs);
    const end = Math.min(rowEnd, size);
    const chunks: Promise<RowsBand>[] = [];
    const rows = chunkRows(stepVoxels);
    for (let start = rowStart; start < end; start += rows) {
      const args = [
        scene,
        size,
        stepVoxels,
        threshold,
        start,
        Math.min(start + rows, end),
      ] as const;
      // A cached band would repeat its first timing: a fresh one gets a key of its own.
      const key = fresh ? `${cacheKey('rows', args)}#${++freshRuns}` : undefined;
      chunks.push(jobs.run('rows', [...args], { signal, key }));
    }
    // All or nothing: an aborted call leaves `image` as it was (the reference resumes by bands).
    const bands = await Promise.all(chunks);
    let milliseconds = 0;
    let start = rowStart;
    for (const band of bands) {
      addBand(image, band, start);
      milliseconds += band.milliseconds;
      start += band.rows;
    }
    return { milliseconds, how: timingLabel('cpu'), timing: 'cpu' };
  }
}

/** Copies a band of rows starting at `rowStart` into `image` and adds its statistics. */
function addBand(
  image: VolumeImage,
  band: Omit<RowsBand, 'rgb' | 'stepsPerPixel' | 'plannedPerPixel' | 'milliseconds'> & {
    rgb: Float32Array | Float64Array;
    stepsPerPixel: Uint32Array;
    plannedPerPixel: Uint32Array;
  },
  rowStart: number,
): void {
  const { size } = image;
  const pixels = size * size;
  const bandPixels = band.rows * size;
  const offset = rowStart * size;
  for (let c = 0; c < 3; c++)
    image.rgb.set(band.rgb.subarray(c * bandPixels, (c + 1) * bandPixels), c * pixels + offset);
  image.stepsPerPixel.set(band.stepsPerPixel, offset);
  image.plannedPerPixel.set(band.plannedPerPixel, offset);
  image.steps += band.steps;
  image.plannedSteps += band.plannedSteps;
  image.terminatedRays += band.terminatedRays;
  image.cappedRays += band.cappedRays;
}

/**
 * GPU time one band of GpuRenderer may take (ms): a whole 160² frame in one dispatch
 * (126–166 ms on SwiftShader) held the next input's preview behind it (issue 23; bands.ts).
 */
export const GPU_BAND_BUDGET_MS = 15;
/**
 * GPU time one band of the work beside the frames may take (ms): the reference and the
 * saving measurement keep a band in flight each, and an input's preview queues behind
 * both (firstPictureProbe: a reference band of 79 ms and a saving band of 36 ms were in
 * flight when the input came).
 */
export const GPU_BACKGROUND_BAND_BUDGET_MS = 8;
/** Bands submitted before the first of them is read back (bands.ts). */
export const GPU_BANDS_IN_FLIGHT = 2;
/** Rows of the first bands, before any band of this renderer has been timed. */
const GPU_FIRST_BAND_ROWS = 8;

/**
 * The GPU kernel at IMAGE_SIZE² pixels (or a preview's fewer), timed on the GPU, in bands
 * of rows (runInBands) sized from the cost per ray and voxel of path measured before.
 */
export class GpuRenderer implements FrameRenderer {
  readonly kind = 'gpu';
  readonly size = IMAGE_SIZE;
  /**
   * Measured GPU ms per ray and voxel of path (rays × 1/Δs), by termination threshold (the
   * reference's smaller one marches further per ray: sized by the frames' cost, one of its
   * bands ran 164 ms), absent before the first band.
   */
  private readonly msPerRayVoxel = new Map<number, number>();
  /**
   * Measured GPU ms of each row of a full-size image at one voxel per step, by threshold:
   * rays through the phantom cost many times those beside it, so bands sized by the mean
   * row overran their budget (bands.ts rowMs).
   */
  private readonly rowMsPerVoxel = new Map<number, Float64Array>();

  constructor(private readonly gpu: VolumeRendererGpu) {}

  blank(size = this.size): VolumeImage {
    return emptyImage(size, new Float32Array(3 * size * size));
  }

  /**
   * Rows [rowStart, rowEnd) band by band; an aborted `signal` rejects with an AbortError
   * before the next band, leaving `image` as it was (bands are copied in once all are back).
   */
  async renderInto(
    image: VolumeImage,
    inputs: FrameInputs,
    stepVoxels: number,
    threshold: number,
    rowStart: number,
    rowEnd: number,
    signal?: AbortSignal,
    _fresh = false,
    inFlight = GPU_BANDS_IN_FLIGHT,
  ): Promise<RowsCost> {
    const { size } = image;
    const step = Math.max(stepVoxels, 1e-3);
    // A threshold not timed yet (the reference's first band, the saving measurement's
    // other mode) starts with a band of GPU_FIRST_BAND_ROWS rows at one voxel per step,
    // fewer at finer steps: sized from another threshold's cost, the reference's first band
    // ran 90 ms and the other mode's (no early termination) over 100 ms on SwiftShader.
    const known = this.msPerRayVoxel.get(threshold);
    const firstRows = Math.max(1, Math.round(GPU_FIRST_BAND_ROWS * Math.min(1, step)));
    const end = Math.min(rowEnd, size);
    // Per-row costs where every row of this call has been timed at this size.
    const perRow = size === this.size ? this.rowMsPerVoxel.get(threshold) : undefined;
    let rowMs: Float64Array | null = null;
    if (perRow) {
      rowMs = new Float64Array(end);
      for (let row = rowStart; row < end; row++) rowMs[row] = perRow[row]! / step;
      if (rowMs.subarray(rowStart, end).some((ms) => !(ms > 0))) rowMs = null;
    }
    const {
      bands,
      msPerRow,
      rowMs: measured,
    } = await runInBands(
      rowStart,
      end,
      {
        // Work beside the frames (one band in flight) in smaller bands: an input waits for it.
        budgetMs: inFlight === 1 ? GPU_BACKGROUND_BAND_BUDGET_MS : GPU_BAND_BUDGET_MS,
        firstRows,
        inFlight,
        msPerRow: known === undefined ? null : (known * size) / step,
        rowMs,
        ...(signal ? { signal } : {}),
      },
      (band) =>
        this.gpu.renderRows({
          inputs,
          size,
          stepVoxels,
          threshold,
          rowStart: band.start,
          rowEnd: band.start + band.rows,
        }),
    );
    if (msPerRow !== null) this.msPerRayVoxel.set(threshold, (msPerRow * step) / size);
    if (size === this.size) {
      let perRowNow = this.rowMsPerVoxel.get(threshold);
      if (!perRowNow) {
        perRowNow = new Float64Array(size);
        this.rowMsPerVoxel.set(threshold, perRowNow);
      }
      for (const band of bands)
        for (let row = band.start; row < band.start + band.rows; row++)
          perRowNow[row] = measured[row]! * step;
    }
    if (signal?.aborted) throw abortError('the rest of this picture');
    for (const band of bands) addBand(image, band, band.start);
    const milliseconds = bands.reduce((sum, band) => sum + band.milliseconds, 0);
    const timing = bands.some((band) => band.timing === 'gpu-wall') ? 'gpu-wall' : 'gpu-timestamp';
    return { milliseconds, how: timingLabel(timing), timing };
  }
}

/** One whole frame on a renderer at `size`² pixels (default: its full size): the image and its cost. */
export async function renderFrame(
  renderer: FrameRenderer,
  inputs: FrameInputs,
  stepVoxels: number,
  threshold: number,
  size = renderer.size,
  signal?: AbortSignal,
  fresh = false,
  /** GPU bands in flight (FrameRenderer.renderInto): 1 for work beside the frames. */
  inFlight?: number,
): Promise<{ image: VolumeImage } & RowsCost> {
  const image = renderer.blank(size);
  const cost = await renderer.renderInto(
    image,
    inputs,
    stepVoxels,
    threshold,
    0,
    size,
    signal,
    fresh,
    inFlight,
  );
  return { image, ...cost };
}

/** Paints size × size colours into a canvas, scaled to the canvas's size (nearest neighbour). */
export function paintImage(
  canvas: HTMLCanvasElement,
  size: number,
  colourAt: (index: number) => Rgb,
): void {
  const context = context2d(canvas);
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const image = context.createImageData(size, size);
  for (let index = 0; index < size * size; index++) {
    const rgb = colourAt(index);
    for (let c = 0; c < 3; c++) image.data[4 * index + c] = Math.round(rgb[c]!);
    image.data[4 * index + 3] = 255;
  }
  if (size === canvas.width && size === canvas.height) {
    context.putImageData(image, 0, 0);
    return;
  }
  const small = new OffscreenCanvas(size, size);
  context2d(small)?.putImageData(image, 0, 0);
  context.imageSmoothingEnabled = false;
  context.drawImage(small, 0, 0, canvas.width, canvas.height);
}
