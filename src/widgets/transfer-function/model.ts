// What <sb-transfer-function> computes, independent of the backend: the transfer
// function from the widget's parameters (six opacity control points in HU and a
// colour map, merged into one piecewise-linear table for shaders/volume.wesl),
// the presets, the camera, the float64 image (the twin of
// shaders/kernels/transfer-function.wesl), its error against a reference and the
// early-termination bias bound.
import {
  cameraPerspective,
  cameraRay,
  orbitCameraPosition,
  type Camera,
} from '../../reference/camera.ts';
import { makeDensityGrid, type DensityGridData, type Vec3 } from '../../reference/medium.ts';
import {
  makeTransferFunction,
  TRANSFER_MAX_POINTS,
  volumeRaymarch,
  type TransferFunction,
} from '../../reference/volume.ts';
import type { ParameterValues } from '../parameters.ts';
import { interpolate, type Rgb } from '../base/imagePanel.ts';
import { CONTROL_POINTS } from './schema.ts';
import {
  CT_RESCALE_INTERCEPT,
  PHANTOM_HALF_EXTENT,
  PHANTOM_SIZE,
  phantomVolume,
} from './phantom.ts';

/** Image size of the GPU path (square); the CPU fallback draws CPU_SIZE². */
export const IMAGE_SIZE = 160;
export const CPU_SIZE = 64;
/** Orbit camera: distance from the volume's centre (m) and vertical field of view (°). */
export const CAMERA_DISTANCE = 0.47;
export const CAMERA_FOV_DEGREES = 30;
/** One voxel (m): the reference step Δs₀ of the opacities. */
export const VOXEL = (2 * PHANTOM_HALF_EXTENT) / PHANTOM_SIZE;
/** Radiance behind the volume (display units), seen through T. */
export const BACKGROUND: readonly [number, number, number] = [0.035, 0.04, 0.055];
/**
 * The fine-step reference: Δs = 1/8 voxel. Midpoint compositing converges as
 * O(Δs²) once the step resolves the data and the transfer function (chapter 5; for
 * the default preset the twin at 32×32 pixels measures RMSE 2.8e-3, 1.0e-3 and
 * 2.6e-4 at Δs = 1, ½ and ¼ voxel against Δs = 1/32), so the reference's own error,
 * about 6e-5, is about 1/16 of the error at the sweep's finest step (½ voxel).
 */
export const REFERENCE_STEP_VOXELS = 1 / 8;
/** The reference terminates at T < 1e-6: it drops at most 1e-6 of the brightest emission. */
export const REFERENCE_EPSILON = 1e-6;
/** The sweep's samples per voxel 1/Δs (Δs = 4, 2, 1, ½ voxel). */
export const SWEEP_SAMPLES_PER_VOXEL = [0.25, 0.5, 1, 2] as const;
/**
 * Rows per dispatch of the reference, so that it shows progress and can be cancelled: a
 * band is 4/160 of the image at 8× the steps, ≈ ⅕ of a frame, so a reader's input waits
 * behind at most that much GPU work before its first picture (issue 23; was 16 rows).
 */
export const REFERENCE_BAND_ROWS = 4;

export interface ControlPoint {
  hu: number;
  opacity: number;
  /** The parameter index (1-based: hu-1, opacity-1, …) the point comes from. */
  index: number;
}

export interface ColourMap {
  label: string;
  stops: readonly Rgb[];
}

/** Colour maps as sRGB stops in [0, 1], used as emission colours. */
export const COLOUR_MAPS: Readonly<Record<string, ColourMap>> = {
  tissue: {
    label: 'tissue',
    stops: [
      [0.78, 0.26, 0.18],
      [0.92, 0.47, 0.33],
      [0.98, 0.74, 0.58],
      [1, 0.93, 0.82],
      [1, 1, 1],
    ],
  },
  bone: {
    label: 'bone',
    stops: [
      [0.2, 0.22, 0.34],
      [0.45, 0.5, 0.62],
      [0.72, 0.79, 0.82],
      [1, 1, 0.97],
    ],
  },
  viridis: {
    label: 'viridis',
    stops: [
      [0.267, 0.005, 0.329],
      [0.275, 0.196, 0.494],
      [0.212, 0.361, 0.553],
      [0.153, 0.498, 0.557],
      [0.122, 0.631, 0.529],
      [0.29, 0.757, 0.427],
      [0.627, 0.855, 0.224],
      [0.992, 0.906, 0.145],
    ],
  },
  grey: {
    label: 'grey',
    stops: [
      [0.3, 0.3, 0.3],
      [1, 1, 1],
    ],
  },
};

// The transfer-function presets live in presets.ts (free of the volume code, so that
// widget.ts can list them); re-exported for model's callers.
export { TRANSFER_PRESETS, presetValues, type TransferPreset } from './presets.ts';

/**
 * The control points from the parameters (each already clamped to its range), in
 * increasing order of value. Points out of order (a hand-edited link) are sorted and
 * reported: the opacity curve needs non-decreasing values.
 */
export function controlPointsFrom(values: ParameterValues): {
  points: ControlPoint[];
  reordered: boolean;
} {
  const given = Array.from({ length: CONTROL_POINTS }, (_, index) => ({
    hu: Number(values[`hu-${index + 1}`]),
    opacity: Number(values[`opacity-${index + 1}`]),
    index: index + 1,
  }));
  const points = [...given].sort((a, b) => a.hu - b.hu);
  return { points, reordered: points.some((p, index) => p !== given[index]) };
}

/** Opacity of the piecewise-linear curve at v (flat beyond the end points; right value at a jump). */
export function opacityAt(points: readonly ControlPoint[], v: number): number {
  const first = points[0];
  if (!first) return 0;
  if (v < first.hu) return first.opacity;
  for (let k = 1; k < points.length; k++) {
    const a = points[k - 1]!;
    const b = points[k]!;
    if (v < b.hu) return a.opacity + ((v - a.hu) / (b.hu - a.hu)) * (b.opacity - a.opacity);
  }
  return points[points.length - 1]!.opacity;
}

/**
 * The values the colour map spans: from the point where the opacity starts to rise
 * (the point before the first non-zero opacity) to the last point where the opacity
 * changes. Falls back to the first and last points when that range is empty.
 */
export function colourDomain(points: readonly ControlPoint[]): [number, number] {
  const first = points.findIndex((p) => p.opacity > 0);
  let low = first > 0 ? points[first - 1]!.hu : (points[0]?.hu ?? 0);
  let high = low;
  for (let k = 1; k < points.length; k++)
    if (points[k]!.opacity !== points[k - 1]!.opacity) high = points[k]!.hu;
  if (!(high > low)) {
    low = points[0]?.hu ?? 0;
    high = points[points.length - 1]?.hu ?? low;
  }
  if (!(high > low)) high = low + 1;
  return [low, high];
}

/** The emission colour at v: the colour map over the colour domain, clamped at its ends. */
export function colourAt(map: ColourMap, domain: readonly [number, number], v: number): Rgb {
  return interpolate(map.stops, (v - domain[0]) / (domain[1] - domain[0]));
}

/**
 * One piecewise-linear table for shaders/volume.wesl holding both curves: the opacity
 * control points (with the colour at each) and the colour map's stops (with the
 * opacity there). Between consecutive entries both the colour and the opacity are
 * linear, so the table reproduces both curves exactly. 6 + 8 ≤ 16 entries.
 */
export function buildTransferFunction(
  points: readonly ControlPoint[],
  colormap: string,
): TransferFunction {
  const map = COLOUR_MAPS[colormap] ?? COLOUR_MAPS['tissue']!;
  const domain = colourDomain(points);
  const stops = map.stops.map(
    (_, k) => domain[0] + ((domain[1] - domain[0]) * k) / (map.stops.length - 1),
  );
  const entries = [
    ...points.map((p, order) => ({ value: p.hu, opacity: p.opacity, order })),
    ...stops
      .filter((value) => !points.some((p) => p.hu === value))
      .map((value) => ({ value, opacity: opacityAt(points, value), order: CONTROL_POINTS })),
  ].sort((a, b) => a.value - b.value || a.order - b.order);
  if (entries.length > TRANSFER_MAX_POINTS)
    throw new Error(`the transfer function needs ${entries.length} points`);
  return makeTransferFunction(
    entries.map((e) => ({
      value: e.value,
      color: colourAt(map, domain, e.value),
      opacity: e.opacity,
    })),
  );
}

/** A compact key of everything the picture depends on except the step and termination. */
export function sceneKey(inputs: FrameInputs): string {
  return JSON.stringify([inputs.points, inputs.colormap, inputs.azimuth, inputs.elevation]);
}

export interface FrameInputs {
  points: ControlPoint[];
  colormap: string;
  tf: TransferFunction;
  /** Step in voxels. */
  step: number;
  termination: boolean;
  epsilon: number;
  /** Camera angles in degrees. */
  azimuth: number;
  elevation: number;
  /** What the right-hand image shows: 'error' or 'steps'. */
  panel: string;
}

export function inputsFrom(values: ParameterValues): FrameInputs & { reordered: boolean } {
  const { points, reordered } = controlPointsFrom(values);
  const colormap = String(values['colormap']);
  return {
    points,
    reordered,
    colormap,
    tf: buildTransferFunction(points, colormap),
    step: Number(values['step']),
    termination: values['termination'] !== 'off',
    epsilon: Number(values['epsilon']),
    azimuth: Number(values['azimuth']),
    elevation: Number(values['elevation']),
    panel: String(values['panel']),
  };
}

/** The threshold the march uses: ε with early termination, 0 (never stops) without. */
export function thresholdOf(inputs: FrameInputs): number {
  return inputs.termination ? inputs.epsilon : 0;
}

/**
 * The bias bound of early termination (chapter 7): a ray stopped with T < ε misses
 * T·L_rest, where the rest of the ray, an emission–absorption integral over emissions
 * ≤ L_max followed by the background, has L_rest ≤ max(L_max, L_bg). The kernel adds
 * T·L_bg in its place, so a pixel is off by less than ε·max(L_max, L_bg), per channel.
 */
export function terminationBiasBound(inputs: FrameInputs): number {
  if (!inputs.termination) return 0;
  const brightest = Math.max(...BACKGROUND, ...inputs.tf.rgba.flatMap((q) => [q[0], q[1], q[2]]));
  return inputs.epsilon * brightest;
}

let grid: DensityGridData | null = null;

/** The phantom as a density grid: stored values, densityScale 1 (DICOM rescale slope). */
export function phantomGrid(): DensityGridData {
  if (!grid) {
    const h = PHANTOM_HALF_EXTENT;
    grid = makeDensityGrid(
      phantomVolume().stored,
      [PHANTOM_SIZE, PHANTOM_SIZE, PHANTOM_SIZE],
      [-h, -h, -h],
      [h, h, h],
      1,
    );
  }
  return grid;
}

/**
 * The orbit camera of an image of size² pixels (float64; the kernel receives it
 * built): looking at the volume's centre from CAMERA_DISTANCE, y up.
 */
export function frameCamera(azimuth: number, elevation: number, size: number): Camera {
  return cameraPerspective(
    cameraPosition(azimuth, elevation),
    [0, 0, 0],
    [0, 1, 0],
    CAMERA_FOV_DEGREES,
    size,
    size,
  );
}

/** The orbit camera's position (m) for angles in degrees. */
export function cameraPosition(azimuth: number, elevation: number): Vec3 {
  return orbitCameraPosition(
    [0, 0, 0],
    CAMERA_DISTANCE,
    (azimuth * Math.PI) / 180,
    (elevation * Math.PI) / 180,
  );
}

/** An image as three colour planes and per-pixel march statistics, rows [rowStart, rowEnd). */
export interface VolumeImage {
  size: number;
  /** r, g, b planes of size² values each (display units, background included). */
  rgb: Float32Array | Float64Array;
  /** Steps taken, summed over the pixels. */
  steps: number;
  /** Steps the rays' segments have without early termination, summed. */
  plannedSteps: number;
  /** Rays stopped by early termination. */
  terminatedRays: number;
  /** Rays whose step count hit VOLUME_MAX_STEPS. */
  cappedRays: number;
  /** Steps taken by each pixel's ray, and the steps its segment has without termination. */
  stepsPerPixel: Uint32Array;
  plannedPerPixel: Uint32Array;
}

export function emptyImage(size: number, rgb: Float32Array | Float64Array): VolumeImage {
  return {
    size,
    rgb,
    steps: 0,
    plannedSteps: 0,
    terminatedRays: 0,
    cappedRays: 0,
    stepsPerPixel: new Uint32Array(size * size),
    plannedPerPixel: new Uint32Array(size * size),
  };
}

/**
 * The float64 twin of the kernel's renderImage for rows [rowStart, rowEnd) of a
 * size × size image (into `image`, which accumulates the statistics): the same
 * orbit camera, the same rays through pixel centres and volumeRaymarch from
 * src/reference/volume.ts.
 */
export function renderRowsCpu(
  image: VolumeImage,
  inputs: FrameInputs,
  stepVoxels: number,
  threshold: number,
  rowStart: number,
  rowEnd: number,
): void {
  const { size } = image;
  const data = phantomGrid();
  const camera = frameCamera(inputs.azimuth, inputs.elevation, size);
  const pixels = size * size;
  for (let row = rowStart; row < Math.min(rowEnd, size); row++) {
    for (let column = 0; column < size; column++) {
      const ray = cameraRay(camera, [column + 0.5, row + 0.5]);
      const result = volumeRaymarch(
        data.grid,
        data.volume,
        CT_RESCALE_INTERCEPT,
        inputs.tf,
        VOXEL,
        ray.origin,
        ray.direction,
        stepVoxels * VOXEL,
        threshold,
      );
      const index = row * size + column;
      for (let c = 0; c < 3; c++)
        image.rgb[c * pixels + index] =
          result.color[c as 0 | 1 | 2] + result.transmittance * BACKGROUND[c]!;
      image.stepsPerPixel[index] = result.steps;
      image.plannedPerPixel[index] = result.plannedSteps;
      image.steps += result.steps;
      image.plannedSteps += result.plannedSteps;
      image.terminatedRays += result.terminated;
      image.cappedRays += result.capped;
    }
  }
}

/** The whole image on the CPU (float64). */
export function renderImageCpu(
  size: number,
  inputs: FrameInputs,
  stepVoxels = inputs.step,
  threshold = thresholdOf(inputs),
): VolumeImage {
  const image = emptyImage(size, new Float64Array(3 * size * size));
  renderRowsCpu(image, inputs, stepVoxels, threshold, 0, size);
  return image;
}

/** Root-mean-square and largest difference over all pixels and channels: src/statistics. */
export { maxAbsoluteError as maxError, rmse } from '../../statistics/errors.ts';

/** 8-bit sRGB of pixel `index` of an image's planes (display values clamped to [0, 1]). */
export function pixelColour(rgb: ArrayLike<number>, pixels: number, index: number): Rgb {
  const channel = (c: number): number => 255 * Math.min(Math.max(rgb[c * pixels + index]!, 0), 1);
  return [channel(0), channel(1), channel(2)];
}

/** The error scale of the error image (black → blue → cyan → white), as in chapter 5. */
const ERROR_STOPS: readonly Rgb[] = [
  [4, 6, 16],
  [25, 40, 120],
  [30, 120, 200],
  [90, 210, 220],
  [240, 255, 250],
];

export function errorColour(error: number, scale: number): Rgb {
  return interpolate(ERROR_STOPS, Math.sqrt(Math.abs(error) / scale));
}

/** Largest per-pixel error (max over channels) of an image against its reference, per pixel. */
export function pixelErrors(
  image: ArrayLike<number>,
  reference: ArrayLike<number>,
  pixels: number,
): Float64Array {
  const errors = new Float64Array(pixels);
  for (let c = 0; c < 3; c++)
    for (let i = 0; i < pixels; i++)
      errors[i] = Math.max(
        errors[i]!,
        Math.abs(image[c * pixels + i]! - reference[c * pixels + i]!),
      );
  return errors;
}
