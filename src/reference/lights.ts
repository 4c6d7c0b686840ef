// Float64 twin of shaders/lights.wesl: what a point receives from a directional, point
// or spot light (the environment is sampled by the integrators). Written from the
// radiometry: a beam of irradiance E delivers E; a point source of intensity I delivers
// I/r² across a surface perpendicular to the direction toward it; a spot scales I by a
// smoothstep of the angle off its axis.
import type { Vec3 } from './phase.ts';

export const LIGHT_DIRECTIONAL = 0;
export const LIGHT_POINT = 1;
export const LIGHT_SPOT = 2;
export const LIGHT_ENVIRONMENT = 3;
export const LIGHT_DISTANCE_INFINITE = 1e17;
export const LIGHT_MIN_DISTANCE_SQUARED = 1e-12;

/** Same fields as the WGSL struct Light (without its padding). */
export interface Light {
  kind: number;
  cosOuter: number;
  cosInner: number;
  position: Vec3;
  /** Unit direction of travel (directional light, spot axis). */
  direction: Vec3;
  /** E (W/m²), I (W/sr) or L (W/(m²·sr)) per RGB channel. */
  value: Vec3;
}

export interface LightSample {
  direction: Vec3;
  distance: number;
  irradiance: Vec3;
}

const NONE: LightSample = { direction: [0, 0, 1], distance: 0, irradiance: [0, 0, 0] };
const positive = (v: Vec3): Vec3 => [Math.max(v[0], 0), Math.max(v[1], 0), Math.max(v[2], 0)];

export function spotFalloff(cosTheta: number, cosOuter: number, cosInner: number): number {
  if (cosTheta >= cosInner) return 1;
  if (cosTheta <= cosOuter) return 0;
  const s = (cosTheta - cosOuter) / (cosInner - cosOuter);
  return s * s * (3 - 2 * s);
}

export function lightSampleDirectional(light: Light): LightSample {
  const [x, y, z] = light.direction;
  return {
    direction: [-x, -y, -z],
    distance: LIGHT_DISTANCE_INFINITE,
    irradiance: positive(light.value),
  };
}

export function lightSamplePoint(light: Light, p: Vec3): LightSample {
  const offset: Vec3 = [
    light.position[0] - p[0],
    light.position[1] - p[1],
    light.position[2] - p[2],
  ];
  const r2 = offset[0] ** 2 + offset[1] ** 2 + offset[2] ** 2;
  if (!(r2 >= LIGHT_MIN_DISTANCE_SQUARED)) return NONE;
  const r = Math.sqrt(r2);
  const [a, b, c] = positive(light.value);
  return {
    direction: [offset[0] / r, offset[1] / r, offset[2] / r],
    distance: r,
    irradiance: [a / r2, b / r2, c / r2],
  };
}

export function lightSampleSpot(light: Light, p: Vec3): LightSample {
  const sample = lightSamplePoint(light, p);
  // The receiver sits at −direction from the light; the angle off the axis is measured there.
  const cosTheta = -(
    sample.direction[0] * light.direction[0] +
    sample.direction[1] * light.direction[1] +
    sample.direction[2] * light.direction[2]
  );
  const f = spotFalloff(cosTheta, light.cosOuter, light.cosInner);
  const [a, b, c] = sample.irradiance;
  return { ...sample, irradiance: [a * f, b * f, c * f] };
}
