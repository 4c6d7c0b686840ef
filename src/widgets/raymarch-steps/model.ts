// What the raymarch-steps widget computes, independent of the backend: the
// volume along each pixel's ray (the float64 twin of pixelMedium in
// shaders/kernels/raymarch-steps.wesl), the marched image, its error against a
// converged reference, and the order of convergence fitted to a sweep over N.
import { sineMedium, type Medium1D } from '../../reference/medium.ts';
import {
  MARCH_JITTERED_RAY,
  MARCH_JITTERED_STRATA,
  MARCH_LEFT,
  MARCH_MIDPOINT,
  raymarchEmissionAbsorption,
  raymarchLinearized,
} from '../../reference/raymarch.ts';
import { rngSeed } from '../../reference/rng.ts';
import type { ParameterValues } from '../parameters.ts';
import { interpolate, type Rgb } from '../base/imagePanel.ts';
import { logLogSlope } from '../../statistics/regression.ts';
import { SWEEP_POINTS } from '../base/sweep.ts';

/** Image size of the GPU path; the CPU fallback draws 1/CPU_SCALE of it. */
export const IMAGE_WIDTH = 256;
export const IMAGE_HEIGHT = 160;
export const CPU_SCALE = 4;
/** Ray length d (m) and the radiance behind the volume. */
export const RAY_LENGTH = 2;
export const BACKGROUND = 0.2;
/**
 * Midpoint steps of the converged reference. Midpoint compositing converges as
 * O(h²) (physics.md §3: 2.23e-3 at N = 8, 8.76e-6 at N = 128), so at N = 1024 its
 * own error is 1/16 of the N = 256 error the sweep ends with.
 */
export const REFERENCE_STEPS = 1024;
/** The step counts of the convergence sweep. */
export const SWEEP_STEPS = SWEEP_POINTS;
/** Radiance mapped to the top of the colour scale. */
export const RADIANCE_SCALE = 2.5;

export const SCHEMES: Readonly<Record<string, number>> = {
  left: MARCH_LEFT,
  midpoint: MARCH_MIDPOINT,
  'jittered-ray': MARCH_JITTERED_RAY,
  'jittered-strata': MARCH_JITTERED_STRATA,
};

export interface MarchInputs {
  steps: number;
  placement: string;
  scheme: number;
  linear: boolean;
  density: number;
  seed: number;
}

export function inputsFrom(values: ParameterValues): MarchInputs {
  const placement = String(values['placement']);
  return {
    steps: Math.round(Number(values['steps'])),
    placement,
    scheme: SCHEMES[placement] ?? MARCH_LEFT,
    linear: values['update'] === 'linear',
    density: Number(values['density']),
    seed: Math.round(Number(values['seed'])),
  };
}

/**
 * The ray of the pixel centre (u, v) ∈ (0, 1)²: σt(s) = σ0(1 + 0.5 sin(3s + φ)) with
 * σ0 = σ̄(0.1 + 1.9 e^{−8((u−½)² + (v−½)²)}) and φ = 2πu + 3v, σa = σt, and
 * Le(s) = 1 + s·(1.5 − 2v). Written from the formula, not from the kernel.
 */
export function pixelRay(
  u: number,
  v: number,
  density: number,
): { medium: Medium1D; slope: number } {
  const r2 = (u - 0.5) ** 2 + (v - 0.5) ** 2;
  const sigma0 = density * (0.1 + 1.9 * Math.exp(-8 * r2));
  return { medium: sineMedium(sigma0, 0.5, 3, 2 * Math.PI * u + 3 * v), slope: 1.5 - 2 * v };
}

export interface MarchImage {
  width: number;
  height: number;
  /** Radiance per pixel, row-major from the top left. */
  radiance: Float64Array | Float32Array;
  /** Steps whose linear factor 1 − σt·h was negative and clamped, summed over the image. */
  clampedSteps: number;
  /** Pixels with at least one clamped step. */
  clampedPixels: number;
}

/**
 * The float64 twin of the kernel renderImage: the same rays, the same march from
 * src/reference/raymarch.ts and the same PCG stream per pixel (rngSeed(index, seed)).
 */
export function renderImageCpu(
  width: number,
  height: number,
  inputs: MarchInputs,
  steps = inputs.steps,
): MarchImage {
  const radiance = new Float64Array(width * height);
  let clampedSteps = 0;
  let clampedPixels = 0;
  const march = inputs.linear ? raymarchLinearized : raymarchEmissionAbsorption;
  for (let row = 0; row < height; row++) {
    for (let column = 0; column < width; column++) {
      const index = row * width + column;
      const { medium, slope } = pixelRay(
        (column + 0.5) / width,
        (row + 0.5) / height,
        inputs.density,
      );
      const state = { value: rngSeed(index, inputs.seed) };
      const result = march(
        medium,
        1,
        slope,
        0,
        BACKGROUND,
        RAY_LENGTH,
        steps,
        inputs.scheme,
        state,
      );
      radiance[index] = result.radiance;
      clampedSteps += result.clampedSteps;
      if (result.clampedSteps > 0) clampedPixels += 1;
    }
  }
  return { width, height, radiance, clampedSteps, clampedPixels };
}

const referenceCache = new Map<string, Float64Array>();

/** The converged reference image in float64 (midpoint, exact update, N = 1024), cached per size and σ̄. */
export function referenceImageCpu(width: number, height: number, density: number): Float64Array {
  const key = `${width}x${height},${density}`;
  let cached = referenceCache.get(key);
  if (!cached) {
    const inputs: MarchInputs = {
      steps: REFERENCE_STEPS,
      placement: 'midpoint',
      scheme: MARCH_MIDPOINT,
      linear: false,
      density,
      seed: 0,
    };
    cached = renderImageCpu(width, height, inputs).radiance as Float64Array;
    if (referenceCache.size > 16) referenceCache.clear();
    referenceCache.set(key, cached);
  }
  return cached;
}

/** Root-mean-square and largest absolute difference of two images: src/statistics. */
export { maxAbsoluteError as maxError, rmse } from '../../statistics/errors.ts';

/**
 * The least-squares slope of log RMSE against log N over the points with RMSE > 0:
 * RMSE ∝ N^slope, so left samples give ≈ −1 and midpoint samples ≈ −2 (physics.md §3).
 * Null with fewer than two usable points.
 */
export const convergenceSlope = logLogSlope;

/** A warm "fire" scale for radiance (dark red through orange to pale yellow), 8-bit sRGB. */
const RADIANCE_STOPS: readonly Rgb[] = [
  [8, 6, 20],
  [70, 16, 60],
  [160, 40, 40],
  [225, 110, 30],
  [250, 190, 70],
  [255, 245, 200],
];
/** A cool scale for the error (black, blue, cyan, white), so the two are not confused. */
const ERROR_STOPS: readonly Rgb[] = [
  [4, 6, 16],
  [25, 40, 120],
  [30, 120, 200],
  [90, 210, 220],
  [240, 255, 250],
];

export function radianceColour(radiance: number): Rgb {
  return interpolate(RADIANCE_STOPS, radiance / RADIANCE_SCALE);
}

export function errorColour(error: number, scale: number): Rgb {
  return interpolate(ERROR_STOPS, Math.sqrt(Math.abs(error) / scale));
}
