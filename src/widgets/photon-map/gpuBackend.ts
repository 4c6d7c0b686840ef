// GPU backend of <sb-photon-map>: the entry points of shaders/kernels/photon-map.wesl
// dispatched in one compute pass (dispatches in a pass see each other's storage
// writes): tracePhotons → countCells → prefixCells → scatterPhotons → gatherImage,
// timed as one span (timestamp queries, else wall time), so the photon-mapping time
// includes building the map. pathTrace runs alone, timed the same way. Pipelines,
// buffers and timers come from the GPU core (buffers leased per call, cleared to
// zero as new ones would be, and reused by the next call); the tests call the same
// functions on Dawn's device.
import { runInBands } from '../../gpu/bands.ts';
import { gpuCore, type Lease } from '../../gpu/core.ts';
import { withErrorScopes } from '../../gpu/errors.ts';
import { packStruct } from '../../gpu/layout.ts';
import { photonMapKernel } from '../../gpu/layouts.generated.ts';
import type { GpuTiming } from '../base/imageKernel.ts';
import {
  CAPACITY_PER_PHOTON,
  RECORD_WORDS,
  SCENE,
  cameraFrame,
  gridFor,
  sinThetaMax,
  stepSizeFor,
  type PhotonInputs,
} from './model.ts';

/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = photonMapKernel.PhotonParams;

export interface ParamsExtra {
  width: number;
  height: number;
  seed: number;
  samples: number;
  queryCount: number;
  /** gatherImage's band of rows [rowStart, rowEnd) (default: every row). */
  rowStart?: number;
  rowEnd?: number;
}

export function packParams(inputs: PhotonInputs, extra: ParamsExtra): Uint32Array<ArrayBuffer> {
  const grid = gridFor(inputs.radius);
  const frame = cameraFrame(extra.width, extra.height);
  const sigmaT = inputs.sigmaS + inputs.sigmaA;
  return packStruct(PARAMS, {
    boxMin: SCENE.boxMin,
    sigmaT,
    boxMax: SCENE.boxMax,
    albedo: inputs.sigmaS / sigmaT,
    sphereCenter: SCENE.sphereCenter,
    sphereRadius: SCENE.sphereRadius,
    sunDirection: SCENE.sunDirection,
    sinThetaMax: sinThetaMax(inputs),
    diskCenter: SCENE.diskCenter,
    diskRadius: SCENE.diskRadius,
    gridMin: grid.gridMin,
    cellSize: grid.cellSize,
    gridDims: grid.dims,
    eta: inputs.eta,
    cameraPosition: SCENE.cameraPosition,
    g: inputs.g,
    cameraRight: frame.right,
    irradiance: SCENE.irradiance,
    cameraUp: frame.up,
    radius: inputs.radius,
    cameraForward: frame.forward,
    stepSize: stepSizeFor(inputs.radius),
    width: extra.width,
    height: extra.height,
    seed: extra.seed >>> 0,
    photonCount: inputs.photons,
    capacity: CAPACITY_PER_PHOTON * inputs.photons,
    samples: extra.samples,
    queryCount: extra.queryCount,
    cellCount: grid.dims[0] * grid.dims[1] * grid.dims[2],
    rowStart: extra.rowStart ?? 0,
    rowEnd: extra.rowEnd ?? extra.height,
  });
}

/**
 * GPU time one band of gatherImage may take (ms): the gather is most of a photon-map frame
 * (≈ 150 ms of 190 at 64×48 on SwiftShader), cut into bands of rows (bands.ts).
 */
export const GATHER_BAND_BUDGET_MS = 20;
/** Rows of the first gather band, before any gather has been timed. */
const GATHER_FIRST_BAND_ROWS = 8;
/** GPU ms per pixel of the last gather band timed (any call): sizes the next gathers. */
let gatherMsPerPixel: number | null = null;

export interface PhotonMapGpuResult {
  image: Float32Array;
  stored: number;
  overflow: number;
  /** Up to `viewCount` stored photons (position xyz, glass interactions) in trace order. */
  view: Float32Array;
  milliseconds: number;
  timing: GpuTiming;
  /** Query results (sum, found) per query point, when queries were given. */
  queries: Float32Array;
}

/** Storage buffers are bound with their requested size, a multiple of 16 bytes. */
function storageBytes(bytes: number): number {
  return Math.max(16, Math.ceil(bytes / 16) * 16);
}

interface Bound {
  buffer: GPUBuffer;
  size: number;
}

/** A zeroed storage buffer of the lease for `purpose`. */
function storage(lease: Lease, purpose: string, bytes: number): Bound {
  const size = storageBytes(bytes);
  const usage = GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST;
  return { buffer: lease.buffer(`photon-map.${purpose}`, size, usage, true), size };
}

function readBuffer(device: GPUDevice, source: GPUBuffer, bytes: number): Promise<ArrayBuffer> {
  return gpuCore(device).read(source, bytes);
}

function pipeline(device: GPUDevice, code: string, entryPoint: string): GPUComputePipeline {
  return gpuCore(device).computePipeline({ code, entryPoint });
}

/**
 * Builds the photon map and renders the photon-map image (width × height, `samples`
 * jittered rays per pixel). Optional `photonsIn` replaces the traced photons (records
 * of RECORD_WORDS words; the tests' known distributions) and `queries` adds a grid
 * query at each point (x, y, z, toCamera xyz).
 */
export async function renderPhotonMapGpu(
  device: GPUDevice,
  code: string,
  inputs: PhotonInputs,
  width: number,
  height: number,
  samples: number,
  options: {
    photonsIn?: Float32Array<ArrayBuffer>;
    queries?: Float32Array<ArrayBuffer>;
    viewCount?: number;
    skipImage?: boolean;
    /** An input: the gather stops before its next band with an AbortError. */
    signal?: AbortSignal;
    /** Rows per gather band, instead of bands sized to GATHER_BAND_BUDGET_MS. */
    bandRows?: number;
  } = {},
): Promise<PhotonMapGpuResult> {
  const grid = gridFor(inputs.radius);
  const cells = grid.dims[0] * grid.dims[1] * grid.dims[2];
  const given = options.photonsIn ? options.photonsIn.length / RECORD_WORDS : 0;
  const capacity = options.photonsIn ? given : CAPACITY_PER_PHOTON * inputs.photons;
  const queryCount = options.queries ? options.queries.length / 6 : 0;
  const runInputs = options.photonsIn
    ? { ...inputs, photons: Math.ceil(given / CAPACITY_PER_PHOTON) }
    : inputs;
  const params = packParams(runInputs, { width, height, seed: inputs.seed, samples, queryCount });
  if (options.photonsIn) params[48] = capacity;
  return gpuCore(device)
    .lease()
    .run(async (lease) => {
      const timer = lease.timer();
      const uniform = {
        buffer: lease.upload('photon-map.params', params, GPUBufferUsage.UNIFORM),
        size: params.byteLength,
      };
      const photons = storage(lease, 'photons', capacity * RECORD_WORDS * 4);
      const counters = storage(lease, 'counters', 16);
      const cellCounts = storage(lease, 'cellCounts', cells * 4);
      const cellStart = storage(lease, 'cellStart', (cells + 1) * 4);
      const sorted = storage(lease, 'sorted', capacity * RECORD_WORDS * 4);
      const imageWords = Math.max(width * height, 2 * queryCount);
      const image = storage(lease, 'image', imageWords * 4);
      const queries = storage(lease, 'queries', Math.max(queryCount, 1) * 6 * 4);
      if (options.photonsIn) {
        device.queue.writeBuffer(photons.buffer, 0, options.photonsIn);
        device.queue.writeBuffer(counters.buffer, 0, new Uint32Array([given, 0, 0, 0]));
      }
      if (options.queries) device.queue.writeBuffer(queries.buffer, 0, options.queries);
      const resources: Record<number, Bound> = {
        0: uniform,
        1: photons,
        2: counters,
        3: cellCounts,
        4: cellStart,
        5: sorted,
        6: image,
        7: queries,
      };
      const bindings: Record<string, number[]> = {
        tracePhotons: [0, 1, 2],
        countCells: [0, 1, 2, 3],
        prefixCells: [0, 3, 4],
        scatterPhotons: [0, 1, 2, 3, 4, 5],
        gatherImage: [0, 4, 5, 6],
        queryPoints: [0, 4, 5, 6, 7],
      };
      const start = performance.now();
      const encodePass = (
        timer: ReturnType<typeof lease.timer>,
        uniform: Bound,
        entries: readonly (readonly [string, number, number])[],
      ): void => {
        const encoder = device.createCommandEncoder();
        const pass = encoder.beginComputePass(timer.passDescriptor());
        for (const [entry, x, y] of entries) {
          const p = pipeline(device, code, entry);
          const bound: Record<number, Bound> = { ...resources, 0: uniform };
          pass.setPipeline(p);
          pass.setBindGroup(
            0,
            gpuCore(device).bufferBindGroup(
              p,
              bindings[entry]!.map((binding) => ({ binding, ...bound[binding]! })),
            ),
          );
          pass.dispatchWorkgroups(Math.max(1, x), Math.max(1, y));
        }
        pass.end();
        timer.resolve(encoder);
        device.queue.submit([encoder.finish()]);
      };
      // The map: trace, histogram, prefix sums and the sort into cells (and the queries).
      const mapEntries: [string, number, number][] = [];
      if (!options.photonsIn) mapEntries.push(['tracePhotons', Math.ceil(inputs.photons / 64), 1]);
      mapEntries.push(['countCells', Math.ceil(capacity / 64), 1]);
      mapEntries.push(['prefixCells', 1, 1]);
      mapEntries.push(['scatterPhotons', Math.ceil(capacity / 64), 1]);
      // Queries write `image` too: callers that query skip the image (skipImage).
      if (queryCount > 0) mapEntries.push(['queryPoints', Math.ceil(queryCount / 64), 1]);
      const gatherEntry = (rows: number): [string, number, number] => [
        'gatherImage',
        Math.ceil(width / 8),
        Math.ceil(rows / 8),
      ];
      // A gather expected to fit the budget (a preview) goes in the map's own pass: bands
      // cost a read-back each (≈ 10–20 ms in Chrome on SwiftShader).
      const expected = gatherMsPerPixel === null ? null : gatherMsPerPixel * width * height;
      const oneBand =
        options.skipImage ||
        (options.bandRows === undefined &&
          expected !== null &&
          expected <= 1.5 * GATHER_BAND_BUDGET_MS);
      // Submitted together, read back together: the gather has a timer of its own, so
      // that the estimate is the gather's cost alone.
      const wholeGather = oneBand && !options.skipImage ? lease.timer() : null;
      await withErrorScopes(device, 'photon map', () => {
        encodePass(timer, uniform, mapEntries);
        if (wholeGather) encodePass(wholeGather, uniform, [gatherEntry(height)]);
      });
      const [mapMs, gatherMs] = await Promise.all([timer.read(), wholeGather?.read() ?? 0]);
      let gpuMs = mapMs === null || gatherMs === null ? null : mapMs + gatherMs;
      if (wholeGather && gatherMs !== null && gatherMs > 0)
        gatherMsPerPixel = gatherMs / (width * height);
      // Otherwise the gather, band by band (GATHER_BAND_BUDGET_MS), each with its own
      // parameters and timer, checking `signal` before each.
      if (!oneBand) {
        // One band at a time: the bands share the uniform of their rows (bands.ts).
        const { bands, msPerRow } = await runInBands(
          0,
          height,
          {
            budgetMs: GATHER_BAND_BUDGET_MS,
            firstRows: GATHER_FIRST_BAND_ROWS,
            inFlight: 1,
            msPerRow: gatherMsPerPixel === null ? null : gatherMsPerPixel * width,
            ...(options.bandRows !== undefined ? { fixedRows: options.bandRows } : {}),
            ...(options.signal ? { signal: options.signal } : {}),
          },
          async ({ start, rows }) => {
            const bandParams = packParams(runInputs, {
              width,
              height,
              seed: inputs.seed,
              samples,
              queryCount,
              rowStart: start,
              rowEnd: start + rows,
            });
            if (options.photonsIn) bandParams[48] = capacity;
            const bandUniform = {
              buffer: lease.upload('photon-map.params.band', bandParams, GPUBufferUsage.UNIFORM),
              size: bandParams.byteLength,
            };
            const bandTimer = lease.timer();
            await withErrorScopes(device, 'photon map gather', () =>
              encodePass(bandTimer, bandUniform, [gatherEntry(rows)]),
            );
            const ms = await bandTimer.read();
            return { gpuMs: ms, milliseconds: ms ?? 0 };
          },
        );
        if (msPerRow !== null) gatherMsPerPixel = msPerRow / width;
        for (const band of bands)
          gpuMs = band.gpuMs === null || gpuMs === null ? null : gpuMs + band.gpuMs;
      }
      const counterData = new Uint32Array(await readBuffer(device, counters.buffer, 4));
      const wallMs = performance.now() - start;
      const stored = Math.min(counterData[0]!, capacity);
      const imageData = new Float32Array(await readBuffer(device, image.buffer, imageWords * 4));
      const viewCount = Math.min(stored, options.viewCount ?? 0);
      const view = new Float32Array(viewCount * 4);
      if (viewCount > 0) {
        const raw = new Float32Array(
          await readBuffer(device, photons.buffer, viewCount * RECORD_WORDS * 4),
        );
        const rawU32 = new Uint32Array(raw.buffer);
        for (let i = 0; i < viewCount; i++) {
          view.set(raw.subarray(i * RECORD_WORDS, i * RECORD_WORDS + 3), 4 * i);
          view[4 * i + 3] = rawU32[i * RECORD_WORDS + 7]!;
        }
      }
      return {
        image: imageData.slice(0, width * height),
        stored,
        overflow: Math.max(0, counterData[0]! - capacity),
        view,
        milliseconds: gpuMs ?? wallMs,
        timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
        queries: imageData.slice(0, 2 * queryCount),
      };
    });
}

export interface PathTraceGpuResult {
  sum: Float32Array;
  sumSq: Float32Array;
  milliseconds: number;
  timing: GpuTiming;
}

/** One pass of `samples` paths per pixel with stream `seed` (sums and sums of squares). */
export async function pathTraceGpu(
  device: GPUDevice,
  code: string,
  inputs: PhotonInputs,
  width: number,
  height: number,
  samples: number,
  seed: number,
): Promise<PathTraceGpuResult> {
  const params = packParams(inputs, { width, height, seed, samples, queryCount: 0 });
  return gpuCore(device)
    .lease()
    .run(async (lease) => {
      const timer = lease.timer();
      const uniform = lease.upload('photon-map.params', params, GPUBufferUsage.UNIFORM);
      const image = storage(lease, 'image', 2 * width * height * 4);
      const start = performance.now();
      await withErrorScopes(device, 'path trace', () => {
        const p = pipeline(device, code, 'pathTrace');
        const encoder = device.createCommandEncoder();
        const pass = encoder.beginComputePass(timer.passDescriptor());
        pass.setPipeline(p);
        pass.setBindGroup(
          0,
          gpuCore(device).bufferBindGroup(p, [
            { binding: 0, buffer: uniform, size: params.byteLength },
            { binding: 6, ...image },
          ]),
        );
        pass.dispatchWorkgroups(Math.ceil(width / 8), Math.ceil(height / 8));
        pass.end();
        timer.resolve(encoder);
        device.queue.submit([encoder.finish()]);
      });
      const data = new Float32Array(await readBuffer(device, image.buffer, 2 * width * height * 4));
      const wallMs = performance.now() - start;
      const gpuMs = await timer.read();
      return {
        sum: data.slice(0, width * height),
        sumSq: data.slice(width * height, 2 * width * height),
        milliseconds: gpuMs ?? wallMs,
        timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
      };
    });
}
