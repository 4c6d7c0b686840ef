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
  const context = canvas.getContext('2d');
  if (!context) return;
  const data = context.createImageData(size, size);
  for (let p = 0; p < size * size; p++) {
    for (let c = 0; c < 3; c++) data.data[4 * p + c] = toneByte(image[3 * p + c]!, exposure);
    data.data[4 * p + 3] = 255;
  }
  context.putImageData(data, 0, 0);
}
