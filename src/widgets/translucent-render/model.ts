// The model of <sb-translucent-render>: its parameters turned into the scene of
// src/subsurface/translucent.ts, and the tone mapping of the three pictures.
import type { ParameterValues } from '../parameters.ts';
import { findMaterial } from '../../subsurface/materials.ts';
import {
  IMAGE_MARGIN,
  lightDirection,
  type TranslucentScene,
} from '../../subsurface/translucent.ts';
import { TRANSLUCENT_RENDER } from './schema.ts';
import { context2d } from '../base/canvas2d.ts';

export const TRANSLUCENT_DEFAULTS: ParameterValues = Object.fromEntries(
  TRANSLUCENT_RENDER.parameters.map((p) => [p.name, p.default]),
);

export function sceneFromValues(values: ParameterValues): TranslucentScene {
  const material = findMaterial(String(values['material'])) ?? findMaterial('skin1')!;
  const radius = Number(values['radius']);
  return {
    size: Number(values['size']),
    radius,
    view: IMAGE_MARGIN * radius,
    sigmaSPrime: material.sigmaSPrime,
    sigmaA: material.sigmaA,
    eta: material.eta,
    g: Number(values['g']),
    toLight: lightDirection(Number(values['light-angle'])),
    irradiance: 1,
  };
}

/** ε from its slider (log₁₀ scale). */
export const epsilonOf = (values: ParameterValues): number => 10 ** Number(values['log-epsilon']);

/** Irradiance sample count n = 2^(log₂ n). */
export const sampleCountOf = (values: ParameterValues): number => 2 ** Number(values['samples']);

/** A key of everything the path-traced reference depends on (it restarts when this changes). */
export function referenceKey(values: ParameterValues): string {
  return ['material', 'radius', 'light-angle', 'size', 'g', 'seed'].map((k) => values[k]).join('|');
}

/** Linear radiance × 2^EV to an sRGB byte. */
export function toneByte(radiance: number, exposure: number): number {
  const v = Math.min(Math.max(radiance * 2 ** exposure, 0), 1);
  const s = v <= 0.0031308 ? 12.92 * v : 1.055 * v ** (1 / 2.4) - 0.055;
  return Math.round(255 * s);
}

/** Paints an RGB radiance image into a canvas (background where mask and image are 0). */
export function paintImage(
  canvas: HTMLCanvasElement,
  image: ArrayLike<number>,
  size: number,
  exposure: number,
): void {
  canvas.width = size;
  canvas.height = size;
  const context = context2d(canvas);
  if (!context) return;
  const data = context.createImageData(size, size);
  for (let p = 0; p < size * size; p++) {
    for (let c = 0; c < 3; c++) data.data[4 * p + c] = toneByte(image[3 * p + c]!, exposure);
    data.data[4 * p + 3] = 255;
  }
  context.putImageData(data, 0, 0);
}

/** An image's error against a Monte Carlo reference, with the reference's own noise removed. */
export interface NoisyReferenceError {
  /** √(max(0, MSE estimate)) / mean reference, the MSE estimate with the noise subtracted. */
  relativeRmse: number;
  /** The plain relative RMSE against the noisy reference, √mean((a − r̂)²) / mean r̂. */
  rawRelativeRmse: number;
  /** The reference's RMS standard error relative to its mean: the noise that was subtracted. */
  referenceNoise: number;
  /** Σa / Σr̂ − 1, the error of the mean brightness (the noise averages out of it). */
  meanError: number;
  /** Whether the subtracted estimate went negative: the error is below what the noise can resolve. */
  belowNoise: boolean;
}

/**
 * Error of `image` against a path-traced reference of per-value mean r̂ and standard error
 * SE = s/√n, over the pixels where `mask` is set. A noisy reference inflates the plain MSE:
 * with r̂ = r + noise of variance Var r̂, E[(a − r̂)²] = (a − r)² + Var r̂, and the sample
 * variance s² (with n − 1) is unbiased whatever the distribution of the walks, so E[SE²] = Var r̂.
 * Hence mean((a − r̂)² − SE²) is an unbiased estimate of the MSE against the noise-free image,
 * and we report its square root (clamped at 0; the root itself is then slightly biased low). We subtract instead of
 * only flagging the error as provisional because a young reference (3 spp, ~90 % noise) would
 * otherwise show about √(e² + noise²), the noise and not the method's error; the subtracted noise
 * is shown with the number so a reader sees how much was removed. Values whose SE is not finite
 * (fewer than two samples) count with SE = 0.
 */
export function errorAgainstNoisyReference(
  image: ArrayLike<number>,
  referenceMean: ArrayLike<number>,
  referenceSe: ArrayLike<number>,
  mask: Uint8Array,
): NoisyReferenceError {
  let squares = 0;
  let noise = 0;
  let sum = 0;
  let sumReference = 0;
  let count = 0;
  mask.forEach((inside, p) => {
    if (!inside) return;
    for (let c = 0; c < 3; c++) {
      const a = image[3 * p + c]!;
      const r = referenceMean[3 * p + c]!;
      const se = referenceSe[3 * p + c]!;
      squares += (a - r) ** 2;
      noise += Number.isFinite(se) ? se * se : 0;
      sum += a;
      sumReference += r;
      count += 1;
    }
  });
  if (count === 0 || !(sumReference > 0))
    return {
      relativeRmse: NaN,
      rawRelativeRmse: NaN,
      referenceNoise: NaN,
      meanError: NaN,
      belowNoise: false,
    };
  const meanReference = sumReference / count;
  const mse = (squares - noise) / count;
  return {
    relativeRmse: Math.sqrt(Math.max(0, mse)) / meanReference,
    rawRelativeRmse: Math.sqrt(squares / count) / meanReference,
    referenceNoise: Math.sqrt(noise / count) / meanReference,
    meanError: sum / sumReference - 1,
    belowNoise: mse <= 0,
  };
}
