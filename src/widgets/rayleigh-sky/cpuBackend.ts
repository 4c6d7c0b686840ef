// CPU backend of <sb-rayleigh-sky>: the float64 twin of the kernel's fragment
// shader draws the same panorama on a 2D canvas at reduced resolution. Used
// without WebGPU and after a device loss.
import {
  ELEVATION_MAX_DEG,
  ELEVATION_MIN_DEG,
  SUN_ENLARGEMENT,
  SUN_RADIUS_DEG,
  exposureScale,
  panoramaAngles,
  skyRadiance,
  srgbEncode,
  sunTransmittance,
  type Rgb,
  type SkyInputs,
} from './model.ts';

function smoothstep(edge0: number, edge1: number, x: number): number {
  const t = Math.min(Math.max((x - edge0) / (edge1 - edge0), 0), 1);
  return t * t * (3 - 2 * t);
}

/**
 * The colour of the WGSL fragment shader skyFragment at (px, py) canvas pixels from
 * the top left of a width × height panorama, in float64, sRGB-encoded in [0, 1]³.
 * `sun` is the direct-sun transmittance (computed once per frame).
 */
export function shadeSky(
  px: number,
  py: number,
  width: number,
  height: number,
  inputs: SkyInputs,
  sun: Rgb,
): Rgb {
  const { elevation, azimuth } = panoramaAngles(px, py, width, height);
  const pixelDeg = (ELEVATION_MAX_DEG - ELEVATION_MIN_DEG) / height;
  if (elevation < 0) {
    const horizon = 1 - smoothstep(0.5 * pixelDeg, 1.5 * pixelDeg, (-elevation * 180) / Math.PI);
    const ground = [0.045, 0.04, 0.035].map((g) => srgbEncode(g + (0.55 - g) * horizon));
    return ground as Rgb;
  }
  const view = [
    Math.cos(elevation) * Math.cos(azimuth),
    Math.sin(elevation),
    Math.cos(elevation) * Math.sin(azimuth),
  ];
  const sunDirection = [inputs.cosSun, inputs.sinSun, 0];
  const nu = view[0]! * sunDirection[0]! + view[1]! * sunDirection[1]!;
  const radiance = skyRadiance(
    view[1]!,
    inputs.sinSun,
    nu,
    inputs.steps,
    inputs.sunSteps,
    inputs.scattering,
  );
  const k = exposureScale(inputs.exposure);
  const color = radiance.map((l) => 1 - Math.exp(-k * l));
  const chord = Math.hypot(
    view[0]! - sunDirection[0]!,
    view[1]! - sunDirection[1]!,
    view[2]! - sunDirection[2]!,
  );
  const degrees = Math.PI / 180;
  const edge = 2 * Math.sin(0.5 * SUN_ENLARGEMENT * SUN_RADIUS_DEG * degrees);
  const disc =
    1 - smoothstep(edge - 0.5 * pixelDeg * degrees, edge + 0.5 * pixelDeg * degrees, chord);
  return color.map((c, i) => srgbEncode(c + (sun[i]! - c) * disc)) as Rgb;
}

/** Draws the panorama of skyFragment in float64 at 1/scale resolution; returns the time (ms). */
export function drawSkyCpu(canvas: HTMLCanvasElement, inputs: SkyInputs, scale = 4): number {
  const start = performance.now();
  const context = canvas.getContext('2d');
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const width = Math.max(1, Math.floor(canvas.width / scale));
  const height = Math.max(1, Math.floor(canvas.height / scale));
  const sun = sunTransmittance(inputs.sinSun, inputs.sunSteps, inputs.scattering);
  const image = context.createImageData(width, height);
  for (let row = 0; row < height; row++) {
    for (let column = 0; column < width; column++) {
      const rgb = shadeSky(column + 0.5, row + 0.5, width, height, inputs, sun);
      const offset = (row * width + column) * 4;
      for (let i = 0; i < 3; i++) image.data[offset + i] = Math.round(255 * rgb[i]!);
      image.data[offset + 3] = 255;
    }
  }
  const small = new OffscreenCanvas(width, height);
  small.getContext('2d')?.putImageData(image, 0, 0);
  context.imageSmoothingEnabled = true;
  context.drawImage(small, 0, 0, canvas.width, canvas.height);
  return performance.now() - start;
}
