// Error against time of photon mapping and path tracing on <sb-photon-map>'s caustic
// scene (chapter 10, "Photon mapping and volume caustics"), on the GPU through Dawn:
// photon mapping at fixed gather radii over photon counts N (trace + grid sort +
// gather, timed as one pass), progressive photon mapping with the radius shrinking
// as r = r₀ (N/N₀)^(−1/7) through the widget's default (N₀, r₀) (chapter 10, "Bias
// versus variance": RMSE ∝ N^(−2/7)), and path tracing over paths per pixel (its
// passes summed). The notes give the fitted log–log slopes where a power law is
// expected (progressive: vs N and vs time; path tracing: vs time, −½) and, for each
// fixed radius, its plateau (the relative change over the last step of N). Errors are RMSE over the 64×48 image against the committed reference
// (public/photon-map/reference.bin); its own noise, √(mean SE²), is printed as the
// floor below which no error can be resolved. Times are medians of `repeats` runs.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { linkLibraryKernel } from '../src/gpu/link.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { pathTraceGpu, renderPhotonMapGpu } from '../src/widgets/photon-map/gpuBackend.ts';
import {
  DEFAULT_INPUTS,
  GPU_SIZE,
  PROGRESSIVE_RMSE_EXPONENT,
  parseReference,
  progressiveRadius,
  rmse,
} from '../src/widgets/photon-map/model.ts';
import { logLogSlope } from '../src/statistics/regression.ts';
import { median, type BenchTable } from './table.ts';

export interface PhotonBenchOptions {
  photonCounts: readonly number[];
  radii: readonly number[];
  spp: readonly number[];
  repeats: number;
}

export async function benchPhotons(
  device: GPUDevice,
  options: PhotonBenchOptions,
): Promise<BenchTable> {
  const library = loadShaderLibrary(fileURLToPath(new URL('../shaders', import.meta.url)));
  const code = await linkLibraryKernel(library, 'kernels/photon-map.wesl');
  const bytes = readFileSync(
    fileURLToPath(new URL('../public/photon-map/reference.bin', import.meta.url)),
  );
  const reference = parseReference(
    bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength),
  );
  const { width, height } = GPU_SIZE;
  let floor = 0;
  for (const se of reference.standardError) floor += se * se;
  floor = Math.sqrt(floor / reference.standardError.length);
  // The caustic: pixels the reference shows at least twice as bright as its median
  // (the focused cone below the ball and the sun seen through it); the rest is fog.
  const sortedRef = Array.from(reference.mean).sort((a, b) => a - b);
  const medianRef = sortedRef[Math.floor(sortedRef.length / 2)]!;
  const caustic = Array.from(reference.mean, (v) => v >= 2 * medianRef);
  const maskedRmse = (image: ArrayLike<number>, inside: boolean): number => {
    let s = 0;
    let n = 0;
    for (let i = 0; i < image.length; i++)
      if (caustic[i] === inside) {
        s += (image[i]! - reference.mean[i]!) ** 2;
        n++;
      }
    return Math.sqrt(s / Math.max(n, 1));
  };
  const causticPixels = caustic.filter(Boolean).length;
  const rows: BenchTable['rows'] = [];
  const photonMapRow = async (method: string, photons: number, radius: number) => {
    const times: number[] = [];
    let error = 0;
    let inCaustic = 0;
    let inFog = 0;
    let stored = 0;
    for (let k = 0; k < options.repeats; k++) {
      const r = await renderPhotonMapGpu(
        device,
        code,
        { ...DEFAULT_INPUTS, photons, radius, seed: 1 + k },
        width,
        height,
        1,
      );
      times.push(r.milliseconds);
      error += rmse(r.image, reference.mean) / options.repeats;
      inCaustic += maskedRmse(r.image, true) / options.repeats;
      inFog += maskedRmse(r.image, false) / options.repeats;
      stored = r.stored;
    }
    const row = {
      method,
      'N or spp': photons,
      'r (m)': radius,
      'stored photons': stored,
      'time (ms)': median(times),
      RMSE: error,
      'RMSE caustic': inCaustic,
      'RMSE fog': inFog,
    };
    rows.push(row);
    return row;
  };
  const plateaus: string[] = [];
  for (const radius of options.radii) {
    const series = [];
    for (const photons of options.photonCounts)
      series.push(await photonMapRow(`photon map, r = ${radius} m`, photons, radius));
    const last = series.at(-1)!;
    const before = series.at(-2);
    if (before)
      plateaus.push(
        `r = ${radius} m: RMSE ${last.RMSE.toExponential(2)} at N = ${last['N or spp']}, ${percent(last.RMSE / before.RMSE - 1)} over the last ${last['N or spp'] / before['N or spp']}× photons`,
      );
  }
  const progressive = [];
  for (const photons of options.photonCounts)
    progressive.push(
      await photonMapRow(
        'progressive photon map',
        photons,
        progressiveRadius(DEFAULT_INPUTS.radius, DEFAULT_INPUTS.photons, photons),
      ),
    );
  const pathTraced = [];
  for (const spp of options.spp) {
    const times: number[] = [];
    let error = 0;
    let inCaustic = 0;
    let inFog = 0;
    for (let k = 0; k < options.repeats; k++) {
      const sum = new Float64Array(width * height);
      let ms = 0;
      const passSpp = Math.min(spp, 16);
      for (let pass = 0; pass < spp / passSpp; pass++) {
        const r = await pathTraceGpu(
          device,
          code,
          DEFAULT_INPUTS,
          width,
          height,
          passSpp,
          1000 * k + pass + 1,
        );
        ms += r.milliseconds;
        for (let i = 0; i < sum.length; i++) sum[i]! += r.sum[i]!;
      }
      times.push(ms);
      const mean = sum.map((v) => v / spp);
      error += rmse(mean, reference.mean) / options.repeats;
      inCaustic += maskedRmse(mean, true) / options.repeats;
      inFog += maskedRmse(mean, false) / options.repeats;
    }
    const row = {
      method: 'path tracing',
      'N or spp': spp,
      'r (m)': null,
      'stored photons': null,
      'time (ms)': median(times),
      RMSE: error,
      'RMSE caustic': inCaustic,
      'RMSE fog': inFog,
    };
    rows.push(row);
    pathTraced.push(row);
  }
  const fit = (x: readonly number[], y: readonly number[]): string => {
    const s = logLogSlope(x, y);
    return s === null ? 'no fit' : s.toFixed(3).replace('-', '−');
  };
  return {
    title: 'Photon mapping vs path tracing on the volume caustic (error vs time)',
    notes: [
      `${width}×${height} pixels; reference: path tracing, ${reference.samples} spp; its noise floor √(mean SE²) = ${floor.toExponential(3)}.`,
      'Photon map time = trace + counting sort + gather (one ray per pixel); path tracing time = sum of its passes.',
      `RMSE is the mean over ${options.repeats} independent runs; times are their median. "caustic": the ${causticPixels} pixels where the reference is ≥ 2× its median; "fog": the other ${caustic.length - causticPixels}.`,
      `Progressive: r = ${DEFAULT_INPUTS.radius} m · (N/${DEFAULT_INPUTS.photons})^(−1/7). Fitted RMSE ∝ N^p: p = ${fit(
        progressive.map((r) => r['N or spp']),
        progressive.map((r) => r.RMSE),
      )} (expected −${(-PROGRESSIVE_RMSE_EXPONENT).toFixed(3)}); RMSE ∝ time^p: p = ${fit(
        progressive.map((r) => r['time (ms)']),
        progressive.map((r) => r.RMSE),
      )}.`,
      `Path tracing: RMSE ∝ time^p, p = ${fit(
        pathTraced.map((r) => r['time (ms)']),
        pathTraced.map((r) => r.RMSE),
      )} (expected −0.5); RMSE ∝ spp^p, p = ${fit(
        pathTraced.map((r) => r['N or spp']),
        pathTraced.map((r) => r.RMSE),
      )}.`,
      `Fixed radius, plateau: ${plateaus.join('; ')}.`,
    ],
    rows,
  };
}

function percent(change: number): string {
  return `${change >= 0 ? '+' : '−'}${Math.abs(100 * change).toFixed(0)} %`;
}
