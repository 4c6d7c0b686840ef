// CPU backend of <sb-vre-ray>: the float64 twin of the kernel's march draws the
// plot, and a 2D canvas shows the ray at reduced resolution. Used without WebGPU
// and after a device loss; the kernel test compares the GPU with it.
import { mediumExtinction, mediumOpticalDepth } from '../../reference/medium.ts';
import { transmittanceFromOpticalThickness } from '../../reference/transmittance.ts';
import {
  MARCH_STEPS,
  depthsFor,
  mediumFor,
  viewRange,
  type VreRayInputs,
  type VreRayResult,
} from './model.ts';

/**
 * The march of shaders/kernels/vre-ray.wesl in float64, from physics.md §3: n
 * midpoint steps of h = d/n with exact exponential steps, so each step adds
 * T·(1 − e^{−σt h})·source and multiplies T by e^{−σt h}.
 */
export function marchRayCpu(inputs: VreRayInputs, steps = MARCH_STEPS): VreRayResult {
  const start = performance.now();
  const medium = mediumFor(inputs);
  const h = inputs.length / steps;
  const albedo = Math.min(Math.max(inputs.albedo, 0), 1);
  const emittedSource = (1 - albedo) * Math.max(inputs.emission, 0);
  const scatteredSource = albedo * Math.max(inputs.inscatter, 0);
  const emitted = new Float64Array(steps + 1);
  const inscattered = new Float64Array(steps + 1);
  const transmittance = new Float64Array(steps + 1);
  transmittance[0] = 1;
  let T = 1;
  let e = 0;
  let q = 0;
  for (let i = 0; i < steps; i++) {
    const x = mediumExtinction(medium, (i + 0.5) * h) * h;
    const opacity = -Math.expm1(-x);
    e += T * opacity * emittedSource;
    q += T * opacity * scatteredSource;
    T *= Math.exp(-x);
    emitted[i + 1] = e;
    inscattered[i + 1] = q;
    transmittance[i + 1] = T;
  }
  return {
    depths: depthsFor(inputs.length, steps),
    emitted,
    inscattered,
    transmittance,
    total: e + q + T * Math.max(inputs.background, 0),
    milliseconds: performance.now() - start,
    timing: 'cpu',
  };
}

/** Exposure of the picture's lower half, as SOURCE_GAIN in the kernel; display only. */
const SOURCE_GAIN = 2.5;

/**
 * The same picture as the WGSL fragment shader, in float64, as RGBA pixels of a
 * width × height image (no DOM: the compute worker runs it, jobs.ts).
 */
export function paintRay(
  inputs: VreRayInputs,
  width: number,
  height: number,
): Uint8ClampedArray<ArrayBuffer> {
  const image = { data: new Uint8ClampedArray(width * height * 4) };
  const [viewMin, viewMax] = viewRange(inputs.length);
  const d = inputs.length;
  const medium = mediumFor(inputs);
  const albedo = Math.min(Math.max(inputs.albedo, 0), 1);
  const pixel = (viewMax - viewMin) / width;
  const margin = (-viewMin / (viewMax - viewMin)) * width;
  const radius = 0.42 * Math.min(margin, 0.5 * height);
  for (let x = 0; x < width; x++) {
    const u = (x + 0.5) / width;
    const s = viewMin + u * (viewMax - viewMin);
    const T = transmittanceFromOpticalThickness(
      mediumOpticalDepth(medium, 0, Math.min(Math.max(s, 0), d)),
    );
    const sigma = s >= 0 && s <= d ? mediumExtinction(medium, s) : 0;
    for (let yIndex = 0; yIndex < height; yIndex++) {
      const y = (yIndex + 0.5) / height;
      const upper = y < 0.5;
      let c = [0.015, 0.02, 0.035];
      const add = (rgb: readonly number[], k: number): void => {
        c = c.map((v, i) => v + (rgb[i] ?? 0) * k);
      };
      if (s >= 0 && s <= d) {
        if (upper) add([0.45, 0.5, 0.6], 1 - Math.exp(-0.5 * sigma));
        else {
          add(
            [1, 0.55, 0.2],
            1 - Math.exp(-SOURCE_GAIN * T * sigma * (1 - albedo) * inputs.emission),
          );
          add([0.3, 0.55, 1], 1 - Math.exp(-SOURCE_GAIN * T * sigma * albedo * inputs.inscatter));
        }
      } else if (s > d) {
        add([0.9, 0.92, 0.95], 1 - Math.exp(-inputs.background * (upper ? 1 : T)));
      } else {
        const qx = (u * width - 0.5 * margin) / Math.max(radius, 1);
        const qy = ((y - 0.5) * height) / Math.max(radius, 1);
        const r = Math.hypot(qx, qy);
        if (Math.abs(qy) < 0.6 * (1 - qx * qx) && Math.abs(qx) < 1) c = [0.85, 0.87, 0.9];
        if (r < 0.4) c = [0.2, 0.35, 0.6];
        if (r < 0.18) c = [0.02, 0.02, 0.03];
      }
      if (Math.min(Math.abs(s), Math.abs(s - d)) < 1.5 * pixel || Math.abs(y - 0.5) < 1 / height)
        c = c.map((v, i) => v * 0.4 + 0.6 * ([0.75, 0.78, 0.85][i] ?? 0));
      const offset = (yIndex * width + x) * 4;
      for (let i = 0; i < 3; i++)
        image.data[offset + i] = 255 * Math.min(Math.max(c[i] ?? 0, 1e-6), 1) ** (1 / 2.2);
      image.data[offset + 3] = 255;
    }
  }
  return image.data;
}
