// What the delta-tracking widget computes, independent of the backend: the
// medium along each pixel's ray (the float64 twin of pixelMedium in
// shaders/kernels/delta-tracking.wesl), the image of mean transmittance
// estimates with their per-pixel variance, the exact transmittance it is
// compared with, and the statistics the widget prints.
import {
  mediumMajorant,
  mediumOpticalDepth,
  sineMedium,
  type Medium1D,
} from '../../reference/medium.ts';
import { MARCH_JITTERED_RAY, raymarchOpticalDepth } from '../../reference/raymarch.ts';
import { rngSeed } from '../../reference/rng.ts';
import { rmse } from '../../statistics/errors.ts';
import {
  TRACKING_MAX_STEPS,
  transmittanceDeltaTracking,
  transmittanceRatioTracking,
  transmittanceResidualRatioTracking,
  transmittanceUnbiasedRayMarching,
  type TransmittanceEstimate,
} from '../../reference/tracking.ts';
import type { ParameterValues } from '../parameters.ts';
import { interpolate, type Rgb } from '../base/imagePanel.ts';

/** Image size of the GPU path; the CPU fallback draws 1/CPU_SCALE of it. */
export const IMAGE_WIDTH = 128;
export const IMAGE_HEIGHT = 80;
export const CPU_SCALE = 4;
/** Ray length d (m) through the slab. */
export const RAY_LENGTH = 2;
/** Cap on the samples per pixel, as SPP_MAX in the kernel. */
export const SPP_MAX = 1024;
/** Estimator codes shared with the kernel (DeltaParams.estimator). */
export const ESTIMATORS: Readonly<Record<string, number>> = {
  biased: 0,
  delta: 1,
  ratio: 2,
  residual: 3,
  urm: 4,
};

export const ESTIMATOR_NAMES: Readonly<Record<string, string>> = {
  biased: 'biased exp(−τ̂)',
  delta: 'delta tracking',
  ratio: 'ratio tracking',
  residual: 'residual ratio tracking',
  urm: 'unbiased ray marching',
};

/** Factor applied to the tight majorant max σt = σ0(1 + a) (physics.md §4.5). */
export const MAJORANT_SCALES: Readonly<Record<string, number>> = {
  tight: 1,
  loose: 3,
  low: 0.5,
};

export interface TrackingInputs {
  estimator: string;
  code: number;
  spp: number;
  majorant: string;
  majorantScale: number;
  seed: number;
  /** One estimator in detail, or all five compared at equal samples and equal time. */
  view: 'single' | 'compare';
  /** What the comparison's ten images show. */
  grid: 'estimate' | 'variance';
}

export function inputsFrom(values: ParameterValues): TrackingInputs {
  const estimator = String(values['estimator']);
  const majorant = String(values['majorant']);
  return {
    estimator,
    code: ESTIMATORS[estimator] ?? 1,
    spp: Math.max(1, Math.round(Number(values['spp']))),
    majorant,
    majorantScale: MAJORANT_SCALES[majorant] ?? 1,
    seed: Math.round(Number(values['seed'])),
    view: values['view'] === 'compare' ? 'compare' : 'single',
    grid: values['grid'] === 'variance' ? 'variance' : 'estimate',
  };
}

/** The same inputs with another estimator (the comparison renders all five). */
export function withEstimator(inputs: TrackingInputs, estimator: string): TrackingInputs {
  return { ...inputs, estimator, code: ESTIMATORS[estimator] ?? 1 };
}

/**
 * The slab along the ray of the pixel centre (u, v) ∈ (0, 1)²:
 * σt(s) = σ0(1 + 0.5 sin(3s + φ)) with σ0 = 0.2 + 2.2 e^{−5((u−½)² + (v−½)²)} and
 * φ = 2πu + 3v, so T ranges from about 0.5 at the corners to below 0.01 in the
 * middle. Written from the formula, not from the kernel.
 */
export function pixelMedium(u: number, v: number): Medium1D {
  const r2 = (u - 0.5) ** 2 + (v - 0.5) ** 2;
  return sineMedium(0.2 + 2.2 * Math.exp(-5 * r2), 0.5, 3, 2 * Math.PI * u + 3 * v);
}

/**
 * One estimate of T over [0, RAY_LENGTH] with the library's estimator (the twin of
 * estimateOnce in the kernel). The majorant is the tight σ0(1 + a) times the scale;
 * residual ratio tracking uses the control σc = σ0 (the mean of the sinusoid) and the
 * residual majorant scale·σ0·a (= max|σt − σc| when tight). The biased estimator is
 * exp(−τ̂) of one jittered step (physics.md §3: 0.172054 instead of 0.134440 at σ0 = 1).
 */
export function estimateOnce(
  medium: Medium1D,
  inputs: TrackingInputs,
  state: { value: number },
): TransmittanceEstimate {
  const sigmaMaj = inputs.majorantScale * mediumMajorant(medium, 0, RAY_LENGTH);
  switch (inputs.code) {
    case 0: {
      const tau = raymarchOpticalDepth(medium, RAY_LENGTH, 1, MARCH_JITTERED_RAY, state);
      return { estimate: Math.exp(-tau), lookups: 1, capped: 0 };
    }
    case 2:
      return transmittanceRatioTracking(medium, RAY_LENGTH, sigmaMaj, state, TRACKING_MAX_STEPS);
    case 3:
      return transmittanceResidualRatioTracking(
        medium,
        RAY_LENGTH,
        medium.sigma0,
        inputs.majorantScale * medium.sigma0 * medium.amplitude,
        state,
        TRACKING_MAX_STEPS,
      );
    case 4:
      return transmittanceUnbiasedRayMarching(
        medium,
        RAY_LENGTH,
        sigmaMaj,
        state,
        TRACKING_MAX_STEPS,
      );
    default:
      return transmittanceDeltaTracking(medium, RAY_LENGTH, sigmaMaj, state, TRACKING_MAX_STEPS);
  }
}

export interface TrackingImage {
  width: number;
  height: number;
  spp: number;
  /** Mean of the spp estimates per pixel, row-major from the top left. */
  mean: Float64Array | Float32Array;
  /** Mean of the squared estimates per pixel. */
  meanSquare: Float64Array | Float32Array;
  /** Density lookups summed over the image and the samples. */
  lookups: number;
  /** Estimates cut short by a cap (TRACKING_MAX_STEPS or the URM order cap). */
  capped: number;
}

/** A TrackingImage of zeros with float64 planes, for renderRowsCpu to fill. */
export function emptyImageCpu(
  width: number,
  height: number,
  requestedSpp: number,
): TrackingImage & { mean: Float64Array; meanSquare: Float64Array } {
  const spp = Math.min(Math.max(Math.round(requestedSpp), 1), SPP_MAX);
  const pixels = width * height;
  return {
    width,
    height,
    spp,
    mean: new Float64Array(pixels),
    meanSquare: new Float64Array(pixels),
    lookups: 0,
    capped: 0,
  };
}

/**
 * Rows rowStart … rowEnd − 1 of the float64 twin of the kernel renderImage, into
 * image: the same rays, the same estimators and the same PCG stream per pixel
 * (rngSeed(index, seed)), consumed by image.spp estimates in turn. Every pixel has
 * its own stream, so an image rendered in slices (the CPU fallback yields to the
 * page between them) is identical to one rendered at once.
 */
export function renderRowsCpu(
  image: TrackingImage & { mean: Float64Array; meanSquare: Float64Array },
  inputs: TrackingInputs,
  rowStart: number,
  rowEnd: number,
): void {
  const { width, height, spp } = image;
  for (let row = rowStart; row < Math.min(rowEnd, height); row++) {
    for (let column = 0; column < width; column++) {
      const index = row * width + column;
      const medium = pixelMedium((column + 0.5) / width, (row + 0.5) / height);
      const state = { value: rngSeed(index, inputs.seed) };
      let sum = 0;
      let sumSquares = 0;
      for (let k = 0; k < spp; k++) {
        const result = estimateOnce(medium, inputs, state);
        sum += result.estimate;
        sumSquares += result.estimate ** 2;
        image.lookups += result.lookups;
        image.capped += result.capped;
      }
      image.mean[index] = sum / spp;
      image.meanSquare[index] = sumSquares / spp;
    }
  }
}

/** The whole image at once on the CPU (the kernel tests' twin; spp clamped as in the kernel). */
export function renderImageCpu(
  width: number,
  height: number,
  inputs: TrackingInputs,
  requestedSpp = inputs.spp,
): TrackingImage {
  const image = emptyImageCpu(width, height, requestedSpp);
  renderRowsCpu(image, inputs, 0, height);
  return image;
}

const exactCache = new Map<string, Float64Array>();

/** The exact T = e^{−τ} per pixel from the closed-form optical depth, cached per size. */
export function exactImage(width: number, height: number): Float64Array {
  const key = `${width}x${height}`;
  let cached = exactCache.get(key);
  if (!cached) {
    cached = new Float64Array(width * height);
    for (let row = 0; row < height; row++)
      for (let column = 0; column < width; column++) {
        const medium = pixelMedium((column + 0.5) / width, (row + 0.5) / height);
        cached[row * width + column] = Math.exp(-mediumOpticalDepth(medium, 0, RAY_LENGTH));
      }
    exactCache.set(key, cached);
  }
  return cached;
}

/** Per-pixel sample variance of one estimate, n/(n − 1)·(m₂ − m₁²); 0 for spp = 1. */
export function sampleVariance(image: TrackingImage): Float64Array {
  const variance = new Float64Array(image.mean.length);
  if (image.spp < 2) return variance;
  const n = image.spp;
  for (let i = 0; i < variance.length; i++)
    variance[i] = Math.max((image.meanSquare[i]! - image.mean[i]! ** 2) * (n / (n - 1)), 0);
  return variance;
}

export interface ImageStatistics {
  /** Root-mean-square of mean − T over the pixels. */
  rmse: number;
  /** Mean over the pixels of mean − T, and its standard error from the sample variances. */
  bias: number;
  biasError: number;
  /** Mean density lookups per estimate. */
  lookupsPerEstimate: number;
  /** Largest per-pixel sample variance. */
  largestVariance: number;
}

export function imageStatistics(
  image: TrackingImage,
  exact: ArrayLike<number>,
  variance: ArrayLike<number>,
): ImageStatistics {
  const pixels = exact.length;
  let sum = 0;
  let varianceSum = 0;
  let largest = 0;
  for (let i = 0; i < pixels; i++) {
    sum += image.mean[i]! - exact[i]!;
    varianceSum += variance[i]!;
    largest = Math.max(largest, variance[i]!);
  }
  return {
    rmse: rmse(image.mean, exact),
    bias: sum / pixels,
    // Var(mean of the pixel means) = Σ Var_p/spp / P².
    biasError: Math.sqrt(varianceSum / image.spp) / pixels,
    lookupsPerEstimate: image.lookups / (pixels * image.spp),
    largestVariance: largest,
  };
}

/** Transmittance: opaque (dark slate) through a blue haze to clear (near white). */
const TRANSMITTANCE_STOPS: readonly Rgb[] = [
  [10, 12, 24],
  [30, 50, 100],
  [70, 120, 180],
  [150, 195, 225],
  [240, 248, 255],
];
/** Variance: a warm scale, so it is not confused with the transmittance. */
const VARIANCE_STOPS: readonly Rgb[] = [
  [8, 6, 20],
  [80, 20, 70],
  [170, 50, 40],
  [235, 140, 40],
  [255, 240, 190],
];

/** T on a square-root scale over [0, 1], so the dense core keeps its structure. */
export function transmittanceColour(t: number): Rgb {
  return interpolate(TRANSMITTANCE_STOPS, Math.sqrt(Math.min(Math.max(t, 0), 1)));
}

export function varianceColour(variance: number, scale: number): Rgb {
  return interpolate(VARIANCE_STOPS, Math.sqrt(Math.max(variance, 0) / scale));
}
