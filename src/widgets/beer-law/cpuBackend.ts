// CPU backend of <sb-beer-law>: the float64 twins compute the curve, and a 2D
// canvas shows the beam at reduced resolution. Used without WebGPU and after a
// device loss; also the reference the GPU numbers are compared with.
import { transmittanceFromOpticalThickness } from '../../reference/transmittance.ts';
import {
  CURVE_SAMPLES,
  depthsFor,
  viewRange,
  type BeerLawInputs,
  type BeerLawResult,
} from './model.ts';
import { extinctionAt, opticalDepth } from './profiles.ts';

export function computeCurveCpu(inputs: BeerLawInputs): BeerLawResult {
  const start = performance.now();
  const depths = depthsFor(inputs.thickness, CURVE_SAMPLES);
  const tau = depths.map((s) => opticalDepth(inputs.profile, inputs.sigmaT, 0, s));
  const transmittance = tau.map(transmittanceFromOpticalThickness);
  const T = (a: number, b: number): number =>
    transmittanceFromOpticalThickness(opticalDepth(inputs.profile, inputs.sigmaT, a, b));
  const result = {
    depths,
    transmittance,
    opticalDepth: tau,
    exit: T(0, inputs.thickness),
    beforeSplit: T(0, inputs.split),
    afterSplit: T(inputs.split, inputs.thickness),
  };
  return { ...result, milliseconds: performance.now() - start, timing: 'cpu' };
}

/**
 * The same picture as the WGSL fragment shader, in float64, as RGBA pixels of a
 * width × height image (no DOM: the compute worker runs it, jobs.ts).
 */
export function paintBeam(
  inputs: BeerLawInputs,
  width: number,
  height: number,
): Uint8ClampedArray<ArrayBuffer> {
  const image = { data: new Uint8ClampedArray(width * height * 4) };
  const [viewMin, viewMax] = viewRange(inputs.thickness);
  const d = inputs.thickness;
  const albedo = inputs.sigmaT > 0 ? inputs.sigmaS / inputs.sigmaT : 0;
  const pixel = (viewMax - viewMin) / width;
  for (let x = 0; x < width; x++) {
    const s = viewMin + ((x + 0.5) / width) * (viewMax - viewMin);
    const inside = s >= 0 && s <= d;
    const sigma = inside ? extinctionAt(inputs.profile, inputs.sigmaT, s) : 0;
    const intensity = transmittanceFromOpticalThickness(
      opticalDepth(inputs.profile, inputs.sigmaT, 0, Math.min(Math.max(s, 0), d)),
    );
    for (let yIndex = 0; yIndex < height; yIndex++) {
      const y = ((yIndex + 0.5) / height - 0.5) * 2;
      let r = 0.015;
      let g = 0.02;
      let b = 0.035;
      if (inside) {
        const haze = 1 - Math.exp(-0.35 * sigma);
        r += 0.1 * haze;
        g += 0.16 * haze;
        b += 0.28 * haze;
      }
      const core = Math.exp((-y * y) / 0.018) * intensity;
      r += core;
      g += 0.86 * core;
      b += 0.6 * core;
      if (inside && inputs.sigmaT > 0) {
        const glow = albedo * (1 - Math.exp(-0.6 * sigma)) * intensity * Math.exp((-y * y) / 0.12);
        r += 0.35 * glow;
        g += 0.55 * glow;
        b += glow;
      }
      if (Math.min(Math.abs(s), Math.abs(s - d)) < 1.5 * pixel) {
        r = r * 0.4 + 0.45;
        g = g * 0.4 + 0.47;
        b = b * 0.4 + 0.51;
      }
      if (
        Math.abs(s - inputs.split) < 1.2 * pixel &&
        (((yIndex + 0.5) / height) * 14) % 1 < 0.55 &&
        d > 0
      ) {
        r = r * 0.15 + 0.81;
        g = g * 0.15 + 0.47;
        b = b * 0.15 + 0.3;
      }
      const offset = (yIndex * width + x) * 4;
      image.data[offset] = 255 * Math.min(1, r) ** (1 / 2.2);
      image.data[offset + 1] = 255 * Math.min(1, g) ** (1 / 2.2);
      image.data[offset + 2] = 255 * Math.min(1, b) ** (1 / 2.2);
      image.data[offset + 3] = 255;
    }
  }
  return image.data;
}
