// The scene of <sb-single-scatter>, built from the widget's parameters: a plain
// SceneDescription (src/scene/types.ts) that the validator accepts and the planner
// (src/scene/plan.ts) reads. Nothing here renders; the element hands the scene to the
// scene engine (GPU kernel or float64 CPU twin) and compares the progressive image
// with a reference of the same scene with more samples and another seed.
import type { ParameterValues } from '../parameters.ts';
import type {
  LightDescription,
  MediumDescription,
  SceneDescription,
  SurfaceDescription,
  Vec3,
} from '../../scene/types.ts';

/** Image size on the GPU and in the CPU fallback (4:3, the camera's aspect ratio). */
export const GPU_WIDTH = 96;
export const GPU_HEIGHT = 72;
export const CPU_WIDTH = 64;
export const CPU_HEIGHT = 48;
/**
 * The reference has this many times the target samples: its noise inflates the measured
 * RMSE by √(1 + n/(8·target)), at most 6 % (at the target), less before.
 */
export const REFERENCE_FACTOR = 8;
/** The CPU twin stops at this many samples per pixel (its reference at 8× that). */
export const CPU_SPP_CAP = 128;
/** Seeds of the progressive image and of the reference: independent random streams. */
export const IMAGE_SEED = 1;
export const REFERENCE_SEED = 7919;
/** The smoke grid of public/volumes/ (mean density 0.2, peak 1.85) and its density scale. */
export const SMOKE_FILE = 'volumes/smoke-24.f32';
export const SMOKE_SCALE = 4;

export interface SingleScatterInputs {
  medium: 'fog' | 'smoke';
  light: 'spot' | 'directional';
  sigmaS: number;
  albedo: number;
  g: number;
  scattering: boolean;
  occluder: 'sphere' | 'box' | 'none';
  emission: boolean;
  floor: boolean;
  spp: number;
}

export function inputsFrom(values: ParameterValues): SingleScatterInputs {
  const num = (name: string, fallback: number): number =>
    typeof values[name] === 'number' ? values[name] : fallback;
  const str = (name: string): string => String(values[name] ?? '');
  return {
    medium: str('medium') === 'smoke' ? 'smoke' : 'fog',
    light: str('light') === 'directional' ? 'directional' : 'spot',
    sigmaS: num('sigma-s', 0.6),
    albedo: num('albedo', 0.9),
    g: num('g', 0.3),
    scattering: str('scattering') !== 'off',
    occluder: str('occluder') === 'box' ? 'box' : str('occluder') === 'none' ? 'none' : 'sphere',
    emission: str('emission') === 'on',
    floor: str('floor') !== 'off',
    spp: Math.round(num('spp', 256)),
  };
}

const normalize = (v: Vec3): Vec3 => {
  const length = Math.hypot(...v);
  return [v[0] / length, v[1] / length, v[2] / length];
};

/**
 * The spot light sits above the fog and above the top of the frame (a light in view would
 * be one pixel of unbounded radiance that dominates every error measure), aimed down
 * and to the right at the floor in front of the camera.
 */
const SPOT_POSITION: Vec3 = [-1, 3.2, 0];
const SPOT_AXIS: Vec3 = normalize([0.45, -1, 0]);
/** The directional light travels down and to the right (direction of travel). */
const SUN_DIRECTION: Vec3 = normalize([0.35, -0.7, 0.6]);
/**
 * The occluder's centre: 1.1 m down the spot's axis, just inside the fog, so its shadow
 * is a cone inside the lit cone (angular radius asin(0.25/1.1) ≈ 13° inside the 24° outer
 * angle); under the sun, high in the fog so the shaft crosses most of it.
 */
function occluderCentre(light: SingleScatterInputs['light']): Vec3 {
  if (light === 'spot')
    return [
      SPOT_POSITION[0] + 1.1 * SPOT_AXIS[0],
      SPOT_POSITION[1] + 1.1 * SPOT_AXIS[1],
      SPOT_POSITION[2] + 1.1 * SPOT_AXIS[2],
    ];
  return [-0.4, 1.9, -0.9];
}

/**
 * The scene for the given inputs. Coefficients: σs as set (scaled by SMOKE_SCALE per unit
 * density in the grid) and σa = σs(1 − α)/α; with scattering off, σs = 0 and σa takes the
 * whole σt, so the fog darkens the view exactly as much but scatters nothing.
 */
export function buildScene(
  inputs: SingleScatterInputs,
  options: { width: number; height: number; spp: number; seed: number },
): SceneDescription {
  const scale = inputs.medium === 'smoke' ? SMOKE_SCALE : 1;
  const sigmaS = inputs.sigmaS * scale;
  const sigmaT = sigmaS / inputs.albedo;
  const scatter = inputs.scattering ? sigmaS : 0;
  const absorb = sigmaT - scatter;
  const common = {
    sigmaA: [absorb, absorb, absorb] as [number, number, number],
    // A slightly bluish fog: shorter wavelengths scatter a little more.
    sigmaS: [0.9 * scatter, scatter, 1.1 * scatter] as [number, number, number],
    phase: { type: 'henyey-greenstein' as const, g: inputs.g },
    ...(inputs.emission ? { emission: [3, 1.2, 0.3] as [number, number, number] } : {}),
  };
  const medium: MediumDescription =
    inputs.medium === 'smoke'
      ? {
          type: 'grid',
          bounds: { type: 'box', min: [-1, 0, -1], max: [1, 2, 1] },
          ...common,
          grid: { dimensions: [24, 24, 24], file: SMOKE_FILE },
        }
      : {
          type: 'homogeneous',
          bounds: { type: 'box', min: [-3.5, 0, -2], max: [3.5, 2.6, 2] },
          ...common,
        };
  const light: LightDescription =
    inputs.light === 'spot'
      ? {
          type: 'spot',
          position: SPOT_POSITION,
          direction: SPOT_AXIS,
          intensity: [24, 22.5, 20.5],
          innerAngle: 16,
          outerAngle: 24,
        }
      : { type: 'directional', direction: SUN_DIRECTION, irradiance: [1.5, 1.45, 1.3] };
  const surfaces: SurfaceDescription[] = [];
  if (inputs.floor)
    surfaces.push({ type: 'plane', point: [0, 0, 0], normal: [0, 1, 0], albedo: [0.5, 0.5, 0.5] });
  const centre = occluderCentre(inputs.light);
  const size = inputs.light === 'spot' ? 0.25 : 0.6;
  if (inputs.occluder === 'sphere')
    surfaces.push({ type: 'sphere', center: centre, radius: size, albedo: [0.7, 0.3, 0.2] });
  else if (inputs.occluder === 'box')
    surfaces.push({
      type: 'box',
      min: [centre[0] - size, centre[1] - 0.6 * size, centre[2] - size],
      max: [centre[0] + size, centre[1] + 0.6 * size, centre[2] + size],
      albedo: [0.7, 0.3, 0.2],
    });
  return {
    name: 'single-scatter widget',
    image: { width: options.width, height: options.height },
    samplesPerPixel: options.spp,
    seed: options.seed,
    scatteringOrder: 1,
    camera: {
      type: 'perspective',
      position: [0, 1.3, 5.2],
      target: [0, 1.05, 0],
      up: [0, 1, 0],
      fovY: 38,
    },
    media: [medium],
    lights: [light],
    surfaces,
  };
}

/** A key that changes exactly when the scene changes (the spp target is not part of it). */
export function sceneKey(inputs: SingleScatterInputs): string {
  return JSON.stringify({ ...inputs, spp: null });
}

/** Root-mean-square difference over all pixels and channels: src/statistics. */
export { rmse } from '../../statistics/errors.ts';

/** Root-mean-square of the per-pixel standard errors (NaN entries, n < 2, are skipped). */
export function rmsStandardError(errors: ArrayLike<number>): number {
  let sum = 0;
  let count = 0;
  for (let i = 0; i < errors.length; i++) {
    const e = errors[i]!;
    if (Number.isFinite(e)) {
      sum += e * e;
      count++;
    }
  }
  return count > 0 ? Math.sqrt(sum / count) : NaN;
}

/** Display exposure: radiance × 2^EV before the sRGB tone map (image.ts toneMapRgba8). */
export const DISPLAY_EXPOSURE = 1;
