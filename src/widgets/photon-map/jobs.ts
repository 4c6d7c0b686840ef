// The CPU fallback's heavy work of <sb-photon-map>, run in the compute worker
// (src/workers/compute.ts) instead of on the page's thread: the float64 twin traces
// the photons, sorts them into the grid, renders the photon-map image and then path
// traces in equal time (a frame of the fallback, and each point of its sweep, took up
// to a second or more of the main thread). Pure functions of the inputs (seeded), so
// the worker's per-argument cache is safe; no DOM, no GPU.
import {
  buildGridCpu,
  gridFor,
  pathTraceCpu,
  photonMapImageCpu,
  tracePhotonsCpu,
  type PhotonInputs,
} from './model.ts';

/** What the CPU twin returns for one render (PhotonImages less what the page adds). */
export interface CpuPhotonImages {
  photonMap: Float64Array;
  pathTraced: Float64Array;
  pmMs: number;
  ptMs: number;
  ptSpp: number;
  stored: number;
  overflow: number;
  /** Stored photons for the camera view: x, y, z and 1 if through the glass, per photon. */
  view: Float32Array;
}

/**
 * The photon-mapped image at `inputs` (gather with `gatherSamples` jittered rays per
 * pixel), then path tracing of 1 path per pixel per pass until it has used as much time
 * as the photon map (or `ptSppTarget` paths per pixel when given; at most `maxSpp`).
 */
export function renderCpuImages(
  inputs: PhotonInputs,
  width: number,
  height: number,
  gatherSamples: number,
  ptSppTarget: number | null,
  maxSpp: number,
  viewCount: number,
): CpuPhotonImages {
  const start = performance.now();
  const set = tracePhotonsCpu(inputs);
  const sorted = buildGridCpu(set, gridFor(inputs.radius));
  const photonMap = photonMapImageCpu(
    inputs,
    set,
    sorted,
    width,
    height,
    gatherSamples,
    inputs.seed,
  );
  const pmMs = performance.now() - start;
  const sum = new Float64Array(width * height);
  let ptMs = 0;
  let spp = 0;
  for (let pass = 0; ; pass++) {
    const t0 = performance.now();
    const r = pathTraceCpu(inputs, width, height, 1, inputs.seed + 7919 * pass);
    ptMs += performance.now() - t0;
    for (let i = 0; i < sum.length; i++) sum[i]! += r.sum[i]!;
    spp += 1;
    if (ptSppTarget !== null ? spp >= ptSppTarget : ptMs >= pmMs || spp >= maxSpp) break;
  }
  const view = new Float32Array(Math.min(set.count, viewCount) * 4);
  for (let i = 0; i < view.length / 4; i++)
    view.set(
      [set.positions[3 * i]!, set.positions[3 * i + 1]!, set.positions[3 * i + 2]!, set.glass[i]!],
      4 * i,
    );
  return {
    photonMap,
    pathTraced: sum.map((s) => s / spp),
    pmMs,
    ptMs,
    ptSpp: spp,
    stored: set.count,
    overflow: set.overflow,
    view,
  };
}

export const jobs = { renderCpuImages };
