// What <sb-chromatic-media> computes, independent of the backend: the medium from the
// parameters, the float64 twin of shaders/kernels/chromatic-media.wesl (renderChromaticCpu,
// the same walks with the same random-number draws per pixel), and the statistics of the
// accumulated sums: per-channel standard error, the colour noise (the delta-method standard
// error of the chromaticity) and the error against a reference picture.
import {
  CHROMATIC_SCATTERED,
  deltaFreeFlight,
  heroChannelWeights,
  heroEventLogPdfs,
  spectralFreeFlight,
  type ChromaticMedium,
  type Rgb,
} from '../../reference/chromatic.ts';
import { raySphereSegment } from '../../reference/geometry.ts';
import { hgEvalDirections, hgSample, type Vec3 } from '../../reference/phase.ts';
import { rngNextFloat, rngSeed, type RngState } from '../../reference/rng.ts';
import { TRACKING_MAX_STEPS } from '../../reference/tracking.ts';
import { packStruct } from '../../gpu/layout.ts';
import { chromaticMediaKernel } from '../../gpu/layouts.generated.ts';
import type { ParameterValues } from '../parameters.ts';

/** The estimators in the order of the kernel's index. */
export const ESTIMATORS = ['oneChannel', 'hero', 'spectral'] as const;
export type EstimatorName = (typeof ESTIMATORS)[number];
export const ESTIMATOR_LABELS: Record<EstimatorName, string> = {
  oneChannel: 'One channel at a time',
  hero: 'Hero wavelength',
  spectral: 'Spectral tracking',
};
/** Kernel index of each estimator (3 would be spectral tracking's max scheme). */
export const ESTIMATOR_INDEX: Record<EstimatorName, number> = {
  oneChannel: 0,
  hero: 1,
  spectral: 2,
};

/** Picture side on the GPU and on the CPU fallback. */
export const GPU_SIZE = 64;
export const CPU_SIZE = 24;
/** Half the picture's width (m): the sphere of radius 1 with a margin. */
export const EXTENT = 1.15;
/** Unit vector towards the light: above, to the left, in front. */
export const LIGHT_DIRECTION: Vec3 = normalize([-0.55, 0.6, 0.58]);
/** Words per pixel of the kernel's output: nine sums, lookups, capped walks, samples. */
export const PIXEL_WORDS = 12;
/** The reference picture has this many times the samples of each estimator (frames offset). */
export const REFERENCE_FACTOR = 4;
/** Frame numbers of the reference's passes start here (independent streams). */
export const REFERENCE_FRAME_OFFSET = 1 << 20;
const MAX_VERTICES = 256;
const ROULETTE_AFTER = 3;

function normalize(v: Vec3): Vec3 {
  const n = Math.hypot(v[0], v[1], v[2]);
  return [v[0] / n, v[1] / n, v[2] / n];
}

export interface ChromaticInputs {
  spread: number;
  density: number;
  albedo: number;
  g: number;
  spp: number;
  target: number;
  exposure: number;
}

export function inputsFrom(values: ParameterValues): ChromaticInputs {
  const number = (name: string, fallback: number): number => {
    const v = values[name];
    return typeof v === 'number' && Number.isFinite(v) ? v : fallback;
  };
  return {
    spread: number('spread', 16),
    density: number('density', 2),
    albedo: number('albedo', 0.9),
    g: number('g', 0),
    spp: Math.max(1, Math.round(number('spp', 4))),
    target: Math.max(1, Math.round(number('target', 64))),
    exposure: number('exposure', 2),
  };
}

/** σt = σt,g·(s^-½, 1, s^½): red and blue a factor √s either side of green. */
export function mediumOf(inputs: ChromaticInputs): ChromaticMedium {
  const root = Math.sqrt(Math.max(inputs.spread, 1));
  return {
    sigmaT: [inputs.density / root, inputs.density, inputs.density * root],
    densityBase: 1,
    albedo: [inputs.albedo, inputs.albedo, inputs.albedo],
    densitySlope: 0,
  };
}

/** The key of what the accumulation depends on (a change starts it again). */
export const accumulationKey = (inputs: ChromaticInputs): string =>
  [inputs.spread, inputs.density, inputs.albedo, inputs.g].join(',');

/** The kernel's ChromaticParams, laid out from its WGSL declaration (layouts.generated.ts). */
export function packParams(
  inputs: ChromaticInputs,
  estimator: number,
  size: number,
  spp: number,
  frame: number,
): Uint32Array<ArrayBuffer> {
  const m = mediumOf(inputs);
  return packStruct(chromaticMediaKernel.ChromaticParams, {
    medium: m,
    lightDirection: LIGHT_DIRECTION,
    g: inputs.g,
    width: size,
    height: size,
    spp,
    frame,
    estimator,
    extent: EXTENT,
  });
}

const f32 = Math.fround;
const f32Medium = (m: ChromaticMedium): ChromaticMedium => ({
  sigmaT: m.sigmaT.map(f32) as Rgb,
  densityBase: f32(m.densityBase),
  albedo: m.albedo.map(f32) as Rgb,
  densitySlope: f32(m.densitySlope),
});

function exitDistance(p: Vec3, w: Vec3): number {
  const segment = raySphereSegment([0, 0, 0], 1, p, w, 0, 1e9);
  return Math.max(segment[1], 0);
}

interface Walk {
  radiance: Rgb;
  lookups: number;
  capped: number;
}

/** The twin of the kernel's walk(): the same draws in the same order. */
function walk(
  m: ChromaticMedium,
  g: number,
  origin: Vec3,
  start: Vec3,
  estimator: number,
  channel: number,
  state: RngState,
): Walk {
  const result: Walk = { radiance: [0, 0, 0], lookups: 0, capped: 0 };
  let p = origin;
  let direction = start;
  let weight: Rgb = [1, 1, 1];
  let logPdfs: Rgb = [0, 0, 0];
  const hero = estimator === 1 ? Math.min(Math.floor(rngNextFloat(state) * 3), 2) : channel;
  const mask: Rgb = estimator === 0 ? [0, 0, 0] : [1, 1, 1];
  if (estimator === 0) mask[channel] = 1;
  for (let vertex = 0; vertex <= MAX_VERTICES; vertex++) {
    if (vertex === MAX_VERTICES) {
      result.capped = 1;
      break;
    }
    const d = exitDistance(p, direction);
    let t: number;
    let scattered: boolean;
    if (estimator <= 1) {
      const flight = deltaFreeFlight(m, m.sigmaT[hero]!, d, state, TRACKING_MAX_STEPS);
      result.lookups += flight.lookups;
      result.capped = Math.max(result.capped, flight.capped);
      t = flight.t;
      scattered = flight.event === CHROMATIC_SCATTERED;
      if (scattered) {
        weight = [weight[0] * m.albedo[0], weight[1] * m.albedo[1], weight[2] * m.albedo[2]];
        if (estimator === 1) {
          const step = heroEventLogPdfs(m, t, true);
          logPdfs = [logPdfs[0] + step[0], logPdfs[1] + step[1], logPdfs[2] + step[2]];
        }
      }
    } else {
      const flight = spectralFreeFlight(m, d, weight, estimator - 2, state, TRACKING_MAX_STEPS);
      result.lookups += flight.lookups;
      result.capped = Math.max(result.capped, flight.capped);
      t = flight.t;
      weight = flight.weight;
      scattered = flight.event === CHROMATIC_SCATTERED;
    }
    if (!scattered) break;
    p = [p[0] + t * direction[0], p[1] + t * direction[1], p[2] + t * direction[2]];
    const back: Vec3 = [-direction[0], -direction[1], -direction[2]];
    const distance = exitDistance(p, LIGHT_DIRECTION);
    const phase = hgEvalDirections(g, back, LIGHT_DIRECTION);
    const heroWeights = estimator === 1 ? heroChannelWeights(logPdfs, hero) : [1, 1, 1];
    for (let c = 0; c < 3; c++) {
      const light = phase * Math.exp(-m.sigmaT[c]! * m.densityBase * distance);
      result.radiance[c]! += weight[c]! * light * heroWeights[c]! * mask[c]!;
    }
    direction = hgSample(g, back, [rngNextFloat(state), rngNextFloat(state)]).wi;
    if (vertex + 1 >= ROULETTE_AFTER) {
      const live = estimator === 0 ? weight[channel]! : Math.max(...weight);
      const q = Math.min(1, live);
      if (!(rngNextFloat(state) < q)) break;
      weight = [weight[0] / q, weight[1] / q, weight[2] / q];
    }
  }
  return result;
}

/** Per-pixel sums of one pass (PIXEL_WORDS per pixel) and the CPU time it took. */
export interface PassSums {
  sums: Float64Array<ArrayBuffer>;
  milliseconds: number;
}

/**
 * One pass of `spp` samples per pixel of estimator `estimator` (kernel index) on a size × size
 * picture, in float64: the twin of renderChromatic.
 */
export function renderChromaticCpu(
  inputs: ChromaticInputs,
  estimator: number,
  size: number,
  spp: number,
  frame: number,
): PassSums {
  const start = performance.now();
  const m = f32Medium(mediumOf(inputs));
  const g = f32(inputs.g);
  const sums = new Float64Array(PIXEL_WORDS * size * size);
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const index = y * size + x;
      const state = { value: rngSeed(index, frame) };
      const u = ((x + 0.5) / size) * 2 - 1;
      const v = 1 - ((y + 0.5) / size) * 2;
      const origin: Vec3 = [u * EXTENT, v * EXTENT, 2];
      const direction: Vec3 = [0, 0, -1];
      const segment = raySphereSegment([0, 0, 0], 1, origin, direction, 0, 10);
      const o = PIXEL_WORDS * index;
      if (segment[0] <= segment[1]) {
        const entry: Vec3 = [origin[0], origin[1], origin[2] - segment[0]];
        for (let s = 0; s < spp; s++) {
          const radiance: Rgb = [0, 0, 0];
          const walks = estimator === 0 ? 3 : 1;
          for (let c = 0; c < walks; c++) {
            const w = walk(m, g, entry, direction, estimator, c, state);
            for (let k = 0; k < 3; k++) radiance[k]! += w.radiance[k]!;
            sums[o + 9]! += w.lookups;
            sums[o + 10]! += w.capped;
          }
          const [r, gr, b] = radiance;
          const add = [r, gr, b, r * r, gr * gr, b * b, r * gr, gr * b, b * r];
          for (let k = 0; k < 9; k++) sums[o + k]! += add[k]!;
        }
      }
      sums[o + 11] = spp;
    }
  }
  return { sums, milliseconds: performance.now() - start };
}

/** Running sums of an estimator over passes (per pixel) and its total time. */
export interface Accumulation {
  size: number;
  sums: Float64Array;
  samples: number;
  milliseconds: number;
  passes: number;
}

export function emptyAccumulation(size: number): Accumulation {
  return {
    size,
    sums: new Float64Array(PIXEL_WORDS * size * size),
    samples: 0,
    milliseconds: 0,
    passes: 0,
  };
}

export function accumulate(
  a: Accumulation,
  pass: ArrayLike<number>,
  spp: number,
  ms: number,
): void {
  for (let i = 0; i < a.sums.length; i++) {
    if (i % PIXEL_WORDS === 11) continue;
    a.sums[i]! += pass[i] ?? 0;
  }
  a.samples += spp;
  a.milliseconds += ms;
  a.passes++;
}

/** The numbers an estimator's picture reports. */
export interface EstimatorStats {
  /** RMS over the sphere's pixels of the standard error of the mean, per channel. */
  channelSe: Rgb;
  /** RMS over the lit pixels of the chromaticity's standard error (delta method), ×1000. */
  colourNoise: number;
  /** RMS over the sphere's pixels of (mean − reference), over the three channels. */
  rmsError: number;
  /** Mean per-sample variance over pixels and channels × ms per sample per pixel. */
  varianceTime: number;
  /** Density lookups per sample per pixel. */
  lookupsPerSample: number;
  capped: number;
}

/** Per-pixel means (RGB, size² × 3). */
export function means(a: Accumulation): Float64Array {
  const n = a.size * a.size;
  const out = new Float64Array(3 * n);
  if (a.samples === 0) return out;
  for (let i = 0; i < n; i++)
    for (let c = 0; c < 3; c++) out[3 * i + c] = a.sums[PIXEL_WORDS * i + c]! / a.samples;
  return out;
}

/** Pixels whose centre sees the sphere. */
export function insideSphere(size: number): boolean[] {
  const inside: boolean[] = [];
  for (let y = 0; y < size; y++)
    for (let x = 0; x < size; x++) {
      const u = (((x + 0.5) / size) * 2 - 1) * EXTENT;
      const v = (1 - ((y + 0.5) / size) * 2) * EXTENT;
      inside.push(u * u + v * v <= 1);
    }
  return inside;
}

export function estimatorStats(a: Accumulation, reference: Float64Array | null): EstimatorStats {
  const n = a.samples;
  const inside = insideSphere(a.size);
  const mean = means(a);
  const se2: Rgb = [0, 0, 0];
  let pixels = 0;
  let colour2 = 0;
  let colourPixels = 0;
  let error2 = 0;
  let variance = 0;
  let lookups = 0;
  let capped = 0;
  const top = Math.max(...mean);
  for (let i = 0; i < inside.length; i++) {
    const o = PIXEL_WORDS * i;
    lookups += a.sums[o + 9]!;
    capped += a.sums[o + 10]!;
    if (!inside[i] || n < 2) continue;
    pixels++;
    const m: Rgb = [mean[3 * i]!, mean[3 * i + 1]!, mean[3 * i + 2]!];
    // Covariance of the means: (E[xy] − E[x]E[y])/(N − 1).
    const cov = (j: number, k: number, sum: number): number =>
      (a.sums[o + sum]! / n - m[j]! * m[k]!) / (n - 1);
    const C = [
      [cov(0, 0, 3), cov(0, 1, 6), cov(0, 2, 8)],
      [cov(0, 1, 6), cov(1, 1, 4), cov(1, 2, 7)],
      [cov(0, 2, 8), cov(1, 2, 7), cov(2, 2, 5)],
    ];
    for (let c = 0; c < 3; c++) {
      se2[c] = se2[c]! + Math.max(C[c]![c]!, 0);
      variance += Math.max(C[c]![c]!, 0) * n;
    }
    const s = m[0] + m[1] + m[2];
    // Chromaticity (x, y) = (r, g)/(r + g + b); its gradients, then ∇ᵀC∇ (delta method).
    if (s > 0.02 * top && top > 0) {
      const gx = [(m[1] + m[2]) / s ** 2, -m[0] / s ** 2, -m[0] / s ** 2];
      const gy = [-m[1] / s ** 2, (m[0] + m[2]) / s ** 2, -m[1] / s ** 2];
      let vx = 0;
      let vy = 0;
      for (let j = 0; j < 3; j++)
        for (let k = 0; k < 3; k++) {
          vx += gx[j]! * C[j]![k]! * gx[k]!;
          vy += gy[j]! * C[j]![k]! * gy[k]!;
        }
      colour2 += Math.max(vx, 0) + Math.max(vy, 0);
      colourPixels++;
    }
    if (reference) {
      for (let c = 0; c < 3; c++) error2 += (m[c]! - reference[3 * i + c]!) ** 2;
    }
  }
  const p = Math.max(pixels, 1);
  const msPerSample = n > 0 ? a.milliseconds / n : 0;
  return {
    channelSe: se2.map((x) => Math.sqrt(x / p)) as Rgb,
    colourNoise: 1000 * Math.sqrt(colour2 / Math.max(colourPixels, 1)),
    rmsError: reference ? Math.sqrt(error2 / (3 * p)) : NaN,
    varianceTime: (variance / (3 * p)) * msPerSample,
    lookupsPerSample: n > 0 ? lookups / (n * inside.length) : 0,
    capped,
  };
}

/** sRGB-ish bytes of the per-pixel means at `exposure` stops (x/(1+x) tone curve, gamma 2.2). */
export function toPixels(
  mean: Float64Array,
  size: number,
  exposure: number,
): Uint8ClampedArray<ArrayBuffer> {
  const out = new Uint8ClampedArray(4 * size * size);
  const scale = 2 ** exposure;
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) {
      const v = Math.max(mean[3 * i + c]! * scale, 0);
      out[4 * i + c] = 255 * (v / (1 + v)) ** (1 / 2.2);
    }
    out[4 * i + 3] = 255;
  }
  return out;
}
