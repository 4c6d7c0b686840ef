// The scene description: plain JSON-compatible data (README "Scenes" documents every
// field, unit and convention). validateScene (validate.ts) turns unknown JSON into a
// SceneDescription or a list of errors that name the field and the allowed range.
// Units: lengths in m, coefficients in 1/m, angles in degrees, irradiance in W/m²,
// intensity in W/sr, radiance in W/(m²·sr), all colours linear RGB.
import type { PhaseDescription } from '../phase/registry.ts';

export type Vec3 = [number, number, number];
export type Rgb = [number, number, number];

/** Capacities of the renderer (shaders/integrator.wesl SCENE_MAX_*). */
export const SCENE_LIMITS = {
  media: 4,
  gridMedia: 1,
  lights: 8,
  surfaces: 16,
  /** Per side; 2048² pixels × 32 bytes is the default WebGPU storage binding limit (128 MiB). */
  imageSize: 2048,
  samplesPerPixel: 1_000_000,
  /** Largest finite scattering order; "unlimited" is also accepted. */
  scatteringOrder: 1000,
  gridDimension: 256,
  /** |coordinate| ≤ this (m): f32 keeps 0.06 m resolution there. */
  coordinate: 1e6,
  coefficient: 1e6,
  /** Irradiance, intensity, radiance and emission (SI units above). */
  lightValue: 1e9,
} as const;

export interface PerspectiveCameraDescription {
  type: 'perspective';
  position: Vec3;
  target: Vec3;
  up: Vec3;
  /** Vertical field of view, degrees. */
  fovY: number;
}

export interface OrthographicCameraDescription {
  type: 'orthographic';
  /** Centre of the footprint (m). */
  position: Vec3;
  /** Direction of view (any length). */
  direction: Vec3;
  up: Vec3;
  /** Footprint width and height (m), whatever the image's aspect ratio. */
  width: number;
  height: number;
}

export type CameraDescription = PerspectiveCameraDescription | OrthographicCameraDescription;

export type BoundsDescription =
  { type: 'box'; min: Vec3; max: Vec3 } | { type: 'sphere'; center: Vec3; radius: number };

/** One variant per phase function of src/phase/registry.ts, e.g. { type: 'henyey-greenstein', g }. */
export type { PhaseDescription };

export interface GridDescription {
  /** Samples per axis (cell-centred, x fastest), filling the bounds' bounding box. */
  dimensions: [number, number, number];
  /** Inline densities (dimensionless, ≥ 0), nx·ny·nz of them, x fastest. */
  density?: number[];
  /** Or a raw little-endian float32 file under public/, e.g. "volumes/smoke-24.f32". */
  file?: string;
}

interface MediumCommon {
  bounds: BoundsDescription;
  /** Absorption coefficient per channel (1/m; for a grid, per unit density). */
  sigmaA: Rgb;
  /** Scattering coefficient per channel (1/m; for a grid, per unit density). */
  sigmaS: Rgb;
  /** Optional; isotropic when absent. */
  phase: PhaseDescription;
  /** Optional emitted radiance Le (W/(m²·sr)); the source term is σa·Le. */
  emission?: Rgb;
}

export interface HomogeneousMediumDescription extends MediumCommon {
  type: 'homogeneous';
}

export interface GridMediumDescription extends MediumCommon {
  type: 'grid';
  grid: GridDescription;
}

export type MediumDescription = HomogeneousMediumDescription | GridMediumDescription;

export type LightDescription =
  /** direction: the direction of TRAVEL of the light; irradiance perpendicular to the beam. */
  | { type: 'directional'; direction: Vec3; irradiance: Rgb }
  | { type: 'point'; position: Vec3; intensity: Rgb }
  /** Half-angles in degrees; full intensity inside innerAngle, none beyond outerAngle. */
  | {
      type: 'spot';
      position: Vec3;
      direction: Vec3;
      intensity: Rgb;
      innerAngle: number;
      outerAngle: number;
    }
  | { type: 'environment'; radiance: Rgb };

export type SurfaceDescription =
  | { type: 'plane'; point: Vec3; normal: Vec3; albedo: Rgb }
  | { type: 'sphere'; center: Vec3; radius: number; albedo: Rgb }
  | { type: 'box'; min: Vec3; max: Vec3; albedo: Rgb };

export interface SceneDescription {
  name?: string;
  description?: string;
  image: { width: number; height: number };
  samplesPerPixel: number;
  /** Seed of the random streams (optional, 0 when absent). */
  seed: number;
  /** 0 = emission–absorption only, 1 = single scattering, N, or "unlimited". */
  scatteringOrder: number | 'unlimited';
  camera: CameraDescription;
  media: MediumDescription[];
  lights: LightDescription[];
  surfaces: SurfaceDescription[];
}
