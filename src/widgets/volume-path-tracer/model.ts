// The model of <sb-volume-path-tracer>, free of the DOM and the GPU: the scene it
// renders (a cloud under sun and sky, as a scene description for src/scene/), the
// sizes and sample budgets of each backend, and the numbers it reports: the relative
// RMSE of an image against a reference with the reference's own noise removed, the
// brightness ratio of multiple to single scattering over the medium, and the mean
// per-pixel standard error.
import { plan, type Plan } from '../../scene/plan.ts';
import type { SceneDescription } from '../../scene/types.ts';
import { parseScene } from '../../scene/validate.ts';
import type { ParameterValues } from '../parameters.ts';

export type SceneChoice = 'sphere' | 'cloud';

export interface PathTracerInputs {
  scene: SceneChoice;
  /** Single-scattering albedo σs/σt. */
  albedo: number;
  /** Henyey–Greenstein mean cosine. */
  g: number;
  /** Optical thickness along a diameter, τ = σt·2R (at the grid's densest value). */
  density: number;
  /** Samples per pixel added to each image per frame. */
  spp: number;
}

export function inputsFrom(values: ParameterValues): PathTracerInputs {
  return {
    scene: values['scene'] === 'cloud' ? 'cloud' : 'sphere',
    albedo: Number(values['albedo']),
    g: Number(values['g']),
    density: Number(values['optical-thickness']),
    spp: Math.max(1, Math.round(Number(values['spp']))),
  };
}

/** What the images depend on (spp per frame only changes how fast they refine). */
export function sceneKey(inputs: PathTracerInputs): string {
  return `${inputs.scene}|${inputs.albedo}|${inputs.g}|${inputs.density}`;
}

/** Image size, sample budgets and pass sizes of one backend. */
export interface Budget {
  width: number;
  height: number;
  /** The progressive images stop refining here. */
  maxSpp: number;
  /** Samples per pixel of the converged reference (an independent seed). */
  referenceSpp: number;
  /** Reference samples per pixel per pass: one pass is added per frame. */
  referencePass: number;
  /** Largest spp per frame (the CPU twin blocks the page while it runs). */
  maxFrameSpp: number;
}

export const GPU_BUDGET: Budget = {
  width: 64,
  height: 64,
  maxSpp: 1024,
  referenceSpp: 8192,
  referencePass: 64,
  maxFrameSpp: 64,
};

/**
 * The float64 twin: a small image and short passes (about 5 µs per path at the default
 * settings, tens of milliseconds per pass). The passes run in the compute worker
 * (jobs.ts), one job at a time, so they stay short: a new input's first pass waits for
 * the one running.
 */
export const CPU_BUDGET: Budget = {
  width: 24,
  height: 24,
  maxSpp: 128,
  referenceSpp: 1024,
  referencePass: 4,
  maxFrameSpp: 4,
};

/** Seeds of the progressive images and of the reference: independent random streams. */
export const IMAGE_SEED = 1;
export const REFERENCE_SEED = 7919;

/** Radius (m) of the ball that bounds the medium, centred at the origin. */
export const RADIUS = 1;
/** Footprint (m) of the orthographic camera, square. */
export const FOOTPRINT = 2.4;
export const GRID_SIZE = 24;

/** The sun: direction of travel (from the upper right, in front) and irradiance (W/m²). */
export const SUN_DIRECTION: [number, number, number] = [-0.55, -0.65, -0.52];
export const SUN_IRRADIANCE: [number, number, number] = [3, 2.85, 2.6];
/** The sky: a uniform environment radiance (W/(m²·sr)), also the background. */
export const SKY_RADIANCE: [number, number, number] = [0.12, 0.2, 0.38];

/**
 * The puffy cloud: soft blobs (each (1 − (d/r)²)², a smooth bump) summed, capped at 1
 * and normalized so that the densest sample is exactly 1, on a GRID_SIZE³ grid that
 * fills the bounding cube of the ball; outside the ball the medium ends (sphere bounds).
 */
export function cloudDensity(n = GRID_SIZE): number[] {
  const blobs: [number, number, number, number][] = [
    [0, -0.15, 0, 0.6],
    [-0.45, -0.3, 0.1, 0.42],
    [0.45, -0.25, -0.1, 0.45],
    [0.15, 0.3, 0.1, 0.45],
    [-0.25, 0.25, -0.2, 0.38],
    [0.05, -0.05, 0.5, 0.35],
  ];
  const values: number[] = [];
  let largest = 0;
  for (let k = 0; k < n; k++)
    for (let j = 0; j < n; j++)
      for (let i = 0; i < n; i++) {
        // Cell-centred samples over [−R, R]³ (README "Scenes": x fastest).
        const p = [i, j, k].map((c) => (((c + 0.5) / n) * 2 - 1) * RADIUS);
        let d = 0;
        for (const [x, y, z, r] of blobs) {
          const q = ((p[0]! - x) ** 2 + (p[1]! - y) ** 2 + (p[2]! - z) ** 2) / (r * r);
          if (q < 1) d += (1 - q) ** 2;
        }
        d = Math.min(d, 1);
        largest = Math.max(largest, d);
        values.push(d);
      }
  return values.map((v) => v / largest);
}

let cachedCloud: number[] | null = null;

/**
 * The scene description of one image: the medium lit by the sun and the sky, seen by
 * an orthographic camera, with scattering order 1 (single scattering) or unlimited
 * (volumetric path tracing). Validated by parseScene, so a bad value throws with the
 * field named instead of rendering something else.
 */
export function buildScene(
  inputs: PathTracerInputs,
  order: 1 | 'unlimited',
  budget: Pick<Budget, 'width' | 'height'>,
  samplesPerPixel: number,
  seed: number,
): SceneDescription {
  // σt = τ/(2R); for the grid the coefficients are per unit density and the densest
  // sample is 1, so τ is the optical thickness of a diameter at that density.
  const sigmaT = inputs.density / (2 * RADIUS);
  const sigmaS = inputs.albedo * sigmaT;
  const sigmaA = sigmaT - sigmaS;
  const bounds = { type: 'sphere', center: [0, 0, 0], radius: RADIUS };
  const common = {
    bounds,
    sigmaA: [sigmaA, sigmaA, sigmaA],
    sigmaS: [sigmaS, sigmaS, sigmaS],
    phase: { type: 'henyey-greenstein', g: inputs.g },
  };
  const medium =
    inputs.scene === 'cloud'
      ? {
          type: 'grid',
          ...common,
          grid: {
            dimensions: [GRID_SIZE, GRID_SIZE, GRID_SIZE],
            density: (cachedCloud ??= cloudDensity()),
          },
        }
      : { type: 'homogeneous', ...common };
  return parseScene({
    name: `volume-path-tracer ${inputs.scene}, order ${order}`,
    image: { width: budget.width, height: budget.height },
    samplesPerPixel,
    seed,
    scatteringOrder: order,
    camera: {
      type: 'orthographic',
      position: [0, 0, 3],
      direction: [0, 0, -1],
      up: [0, 1, 0],
      width: FOOTPRINT,
      height: FOOTPRINT,
    },
    media: [medium],
    lights: [
      { type: 'directional', direction: SUN_DIRECTION, irradiance: SUN_IRRADIANCE },
      { type: 'environment', radiance: SKY_RADIANCE },
    ],
  });
}

/** The plans of the two images (single scattering, path tracing). */
export function plans(inputs: PathTracerInputs): { single: Plan; multiple: Plan } {
  const size = { width: 8, height: 8 };
  return {
    single: plan(buildScene(inputs, 1, size, 1, IMAGE_SEED)),
    multiple: plan(buildScene(inputs, 'unlimited', size, 1, IMAGE_SEED)),
  };
}

/**
 * Optical depth along the centre ray of every pixel (the camera looks along −z, x right,
 * row 0 at the top; README "Scenes"): the chord σt·2√(R² − r²) through the ball, or for
 * the grid a midpoint sum of σt·density over 4·GRID_SIZE steps through the ball, with
 * the density of the nearest sample (enough to tell thick from thin).
 */
export function viewDepth(inputs: PathTracerInputs, width: number, height: number): Float64Array {
  const sigmaT = inputs.density / (2 * RADIUS);
  const depth = new Float64Array(width * height);
  const steps = 4 * GRID_SIZE;
  const density = inputs.scene === 'cloud' ? (cachedCloud ??= cloudDensity()) : null;
  const cell = (c: number): number =>
    Math.min(GRID_SIZE - 1, Math.max(0, Math.floor(((c + RADIUS) / (2 * RADIUS)) * GRID_SIZE)));
  for (let j = 0; j < height; j++)
    for (let i = 0; i < width; i++) {
      const x = ((i + 0.5) / width - 0.5) * FOOTPRINT;
      const y = (0.5 - (j + 0.5) / height) * FOOTPRINT;
      const r2 = x * x + y * y;
      if (r2 >= RADIUS * RADIUS) continue;
      const half = Math.sqrt(RADIUS * RADIUS - r2);
      if (!density) {
        depth[j * width + i] = sigmaT * 2 * half;
        continue;
      }
      const dz = (2 * half) / steps;
      let tau = 0;
      for (let k = 0; k < steps; k++) {
        const z = -half + (k + 0.5) * dz;
        tau += density[cell(x) + GRID_SIZE * (cell(y) + GRID_SIZE * cell(z))]! * sigmaT * dz;
      }
      depth[j * width + i] = tau;
    }
  return depth;
}

/**
 * The pixels where the medium is optically thick, τ ≥ 1 along the view ray (or, for a
 * medium thinner than that everywhere, at least half its largest τ): there the sky seen
 * through the medium is small and the brightness is the medium's own scattered light.
 */
export function mediumMask(inputs: PathTracerInputs, width: number, height: number): Uint8Array {
  const depth = viewDepth(inputs, width, height);
  let largest = 0;
  for (const d of depth) largest = Math.max(largest, d);
  const threshold = Math.min(1, 0.5 * largest);
  return Uint8Array.from(depth, (d) => (d > 0 && d >= threshold ? 1 : 0));
}

const LUMA = [0.2126, 0.7152, 0.0722] as const;

/** Mean luminance over the masked pixels of an RGB-interleaved image. */
export function maskedLuminance(rgb: ArrayLike<number>, mask: Uint8Array): number {
  let sum = 0;
  let count = 0;
  for (let i = 0; i < mask.length; i++) {
    if (!mask[i]) continue;
    sum += LUMA[0] * rgb[3 * i]! + LUMA[1] * rgb[3 * i + 1]! + LUMA[2] * rgb[3 * i + 2]!;
    count++;
  }
  return count > 0 ? sum / count : NaN;
}

/**
 * Relative RMSE of an image against a reference: sqrt(mean (I − R)²)/mean R over all
 * pixels and channels. The reference is itself a Monte Carlo estimate from independent
 * samples, so E[(I − R)²] = Var I + Var R per pixel; subtracting the reference's own
 * squared standard error (its Var R estimate) leaves an unbiased estimate of the
 * image's mean squared error. NaN when the difference is within the reference's noise.
 */
export function relativeError(
  image: ArrayLike<number>,
  reference: ArrayLike<number>,
  referenceStandardError: ArrayLike<number>,
): number {
  let squared = 0;
  let noise = 0;
  let mean = 0;
  for (let k = 0; k < reference.length; k++) {
    squared += (image[k]! - reference[k]!) ** 2;
    noise += referenceStandardError[k]! ** 2;
    mean += reference[k]!;
  }
  const mse = (squared - noise) / reference.length;
  mean /= reference.length;
  return mse > 0 && mean > 0 ? Math.sqrt(mse) / mean : NaN;
}

/** Mean of the per-pixel standard errors over pixels and channels. */
export function meanStandardError(standardError: ArrayLike<number>): number {
  let sum = 0;
  for (let k = 0; k < standardError.length; k++) sum += standardError[k]!;
  return standardError.length > 0 ? sum / standardError.length : NaN;
}

/** Mean radiance over pixels and channels. */
export function meanRadiance(rgb: ArrayLike<number>): number {
  let sum = 0;
  for (let k = 0; k < rgb.length; k++) sum += rgb[k]!;
  return rgb.length > 0 ? sum / rgb.length : NaN;
}
