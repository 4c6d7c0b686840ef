// The transfer-function GPU renderer's bands (issue 23): a frame is cut into dispatches of
// about GPU_BAND_BUDGET_MS each, at most GPU_BANDS_IN_FLIGHT submitted at once, so that an
// input waits for little GPU work before its preview; an input between bands rejects with
// an AbortError and leaves the image as it was. The GPU is a fake here: what is tested is
// the cutting, the ordering and the bookkeeping, not the kernel (transfer-function-kernel).
import { describe, expect, it } from 'vitest';
import { parseParameters } from '../../src/widgets/parameters.ts';
import {
  GPU_BACKGROUND_BAND_BUDGET_MS,
  GPU_BAND_BUDGET_MS,
  GPU_BANDS_IN_FLIGHT,
  GpuRenderer,
} from '../../src/widgets/transfer-function/cpuBackend.ts';
import type {
  GpuRows,
  RowsRequest,
  VolumeRendererGpu,
} from '../../src/widgets/transfer-function/gpuBackend.ts';
import { inputsFrom } from '../../src/widgets/transfer-function/model.ts';
import { TRANSFER_FUNCTION } from '../../src/widgets/transfer-function/schema.ts';

/** A GPU whose rows cost `msPerRayVoxel`·rays/Δs and hold recognisable values. */
class FakeGpu {
  requests: RowsRequest[] = [];
  inFlight = 0;
  largestInFlight = 0;
  constructor(
    private readonly msPerRayVoxel: number,
    /** The cost of a row relative to the others (rays through the phantom cost more). */
    private readonly rowWeight: (row: number) => number = () => 1,
  ) {}

  /** What rows [start, end) of a size-wide image cost at Δs = step voxels (ms). */
  cost(start: number, end: number, size: number, step: number): number {
    let weight = 0;
    for (let row = start; row < end; row++) weight += this.rowWeight(row);
    return (this.msPerRayVoxel * size * weight) / step;
  }

  async renderRows(request: RowsRequest): Promise<GpuRows> {
    this.requests.push(request);
    this.inFlight += 1;
    this.largestInFlight = Math.max(this.largestInFlight, this.inFlight);
    await new Promise((resolve) => setTimeout(resolve, 1));
    this.inFlight -= 1;
    const rows = request.rowEnd - request.rowStart;
    const pixels = rows * request.size;
    const rgb = new Float32Array(3 * pixels);
    // Each pixel's red holds its row, green its column: a misplaced band shows.
    for (let i = 0; i < pixels; i++) {
      rgb[i] = request.rowStart + Math.floor(i / request.size);
      rgb[pixels + i] = i % request.size;
    }
    return {
      size: request.size,
      rgb,
      steps: pixels,
      plannedSteps: 2 * pixels,
      terminatedRays: 0,
      cappedRays: 0,
      stepsPerPixel: new Uint32Array(pixels).fill(1),
      plannedPerPixel: new Uint32Array(pixels).fill(2),
      rowStart: request.rowStart,
      rows,
      milliseconds: this.cost(request.rowStart, request.rowEnd, request.size, request.stepVoxels),
      timing: 'gpu-timestamp',
    };
  }
}

const { values } = parseParameters(TRANSFER_FUNCTION.parameters, () => undefined);
const inputs = inputsFrom(values);

function renderer(gpu: FakeGpu): GpuRenderer {
  return new GpuRenderer(gpu as unknown as VolumeRendererGpu);
}

describe('transfer-function GPU bands', () => {
  it('covers every row once, in place, with the statistics and time of all bands', async () => {
    const gpu = new FakeGpu(0.01);
    const r = renderer(gpu);
    const image = r.blank(64);
    const cost = await r.renderInto(image, inputs, 1, 0.01, 0, 64);
    const starts = gpu.requests.map((q) => q.rowStart);
    expect(starts[0]).toBe(0);
    gpu.requests.forEach((q, i) => {
      expect(q.rowEnd).toBeGreaterThan(q.rowStart);
      if (i > 0) expect(q.rowStart).toBe(gpu.requests[i - 1]!.rowEnd);
    });
    expect(gpu.requests.at(-1)?.rowEnd).toBe(64);
    const pixels = 64 * 64;
    for (let i = 0; i < pixels; i++) {
      expect(image.rgb[i]).toBe(Math.floor(i / 64));
      expect(image.rgb[pixels + i]).toBe(i % 64);
    }
    expect(image.steps).toBe(pixels);
    expect(image.plannedSteps).toBe(2 * pixels);
    expect(cost.milliseconds).toBeCloseTo(0.01 * pixels, 9);
  });

  it('sizes bands from the measured cost to the budget, per voxel of step', async () => {
    // 160-pixel rows at 0.01 ms per ray and voxel: 1.6 ms per row at Δs = 1 voxel.
    const gpu = new FakeGpu(0.01);
    const r = renderer(gpu);
    await r.renderInto(r.blank(160), inputs, 1, 0.01, 0, 160);
    const later = gpu.requests.slice(GPU_BANDS_IN_FLIGHT, -1);
    expect(later.length).toBeGreaterThan(0);
    for (const q of later) expect(q.rowEnd - q.rowStart).toBe(Math.floor(GPU_BAND_BUDGET_MS / 1.6));
    // A reference step of ⅛ voxel costs 8× per row: bands of one row (12.8 ms).
    gpu.requests = [];
    await r.renderInto(r.blank(160), inputs, 0.125, 0.01, 0, 4);
    for (const q of gpu.requests) expect(q.rowEnd - q.rowStart).toBe(1);
  });

  it('cuts by the measured cost of each row, and the work beside the frames in smaller bands', async () => {
    // Rows 60–99 (rays through the phantom) cost 10× the others: 16 ms per row there.
    const gpu = new FakeGpu(0.01, (row) => (row >= 60 && row < 100 ? 10 : 1));
    const r = renderer(gpu);
    // Timed row by row over two frames (a first band's time is spread over its rows).
    for (let i = 0; i < 2; i++) await r.renderInto(r.blank(160), inputs, 1, 0.01, 0, 160);
    // Every band of several rows within its budget (a last sliver may add half of it).
    const fits = (budget: number) => {
      for (const q of gpu.requests) {
        const ms = gpu.cost(q.rowStart, q.rowEnd, 160, 1);
        if (q.rowEnd - q.rowStart > 1)
          expect(ms, `rows ${q.rowStart}–${q.rowEnd}`).toBeLessThanOrEqual(1.5 * budget);
      }
    };
    gpu.requests = [];
    await r.renderInto(r.blank(160), inputs, 1, 0.01, 0, 160);
    fits(GPU_BAND_BUDGET_MS);
    // The cheap rows still go in bands of about the budget, the dear ones one by one.
    const cheapRows = Math.floor(GPU_BAND_BUDGET_MS / 1.6);
    expect(gpu.requests.some((q) => q.rowEnd - q.rowStart >= cheapRows - 1)).toBe(true);
    const dear = gpu.requests.filter((q) => q.rowStart >= 60 && q.rowEnd <= 100);
    expect(dear.length).toBeGreaterThan(30);
    expect(dear.every((q) => q.rowEnd - q.rowStart === 1)).toBe(true);
    // One band in flight (the reference, the saving measurement): the smaller budget.
    gpu.requests = [];
    await r.renderInto(r.blank(160), inputs, 1, 0.01, 0, 160, undefined, false, 1);
    fits(GPU_BACKGROUND_BAND_BUDGET_MS);
    expect(gpu.requests.some((q) => q.rowEnd - q.rowStart > 1)).toBe(true);
  });

  it(`never has more than ${GPU_BANDS_IN_FLIGHT} bands in flight`, async () => {
    const gpu = new FakeGpu(0.01);
    const r = renderer(gpu);
    await r.renderInto(r.blank(160), inputs, 1, 0.01, 0, 160);
    expect(gpu.requests.length).toBeGreaterThan(GPU_BANDS_IN_FLIGHT);
    expect(gpu.largestInFlight).toBe(GPU_BANDS_IN_FLIGHT);
  });

  it('an input between bands rejects with an AbortError, submits no more and leaves the image as it was', async () => {
    const gpu = new FakeGpu(0.01);
    const r = renderer(gpu);
    await r.renderInto(r.blank(160), inputs, 1, 0.01, 0, 160); // measured: small bands now
    gpu.requests = [];
    const image = r.blank(160);
    const controller = new AbortController();
    const render = r.renderInto(image, inputs, 1, 0.01, 0, 160, controller.signal);
    controller.abort();
    await expect(render).rejects.toMatchObject({ name: 'AbortError' });
    expect(gpu.requests.length).toBeLessThanOrEqual(GPU_BANDS_IN_FLIGHT);
    expect(image.steps).toBe(0);
    expect(Array.from(image.rgb).every((v) => v === 0)).toBe(true);
  });
});
