// CPU backend of <sb-rayleigh-sky>: the float64 twin of the kernel's fragment
// shader computes the same panorama (in the compute worker, jobs.ts), shown on a 2D
// canvas at the resolution of its refinement stage. Used without WebGPU and after a
// device loss.
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
import { context2d } from '../base/canvas2d.ts';

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

/**
 * The panorama of skyFragment in float64 at width × height pixels, as RGBA bytes
 * (pure: it runs in the compute worker, see jobs.ts).
 */
export function skyPixels(
  inputs: SkyInputs,
  width: number,
  height: number,
): Uint8ClampedArray<ArrayBuffer> {
  const sun = sunTransmittance(inputs.sinSun, inputs.sunSteps, inputs.scattering);
  const pixels = new Uint8ClampedArray(4 * width * height);
  for (let row = 0; row < height; row++) {
    for (let column = 0; column < width; column++) {
      const rgb = shadeSky(column + 0.5, row + 0.5, width, height, inputs, sun);
      const offset = (row * width + column) * 4;
      for (let i = 0; i < 3; i++) pixels[offset + i] = Math.round(255 * rgb[i]!);
      pixels[offset + 3] = 255;
    }
  }
  return pixels;
}

/**
 * Shows RGBA bytes of width × height on a 2D canvas at that size (the canvas's CSS
 * size stays: the browser scales the picture up smoothly, as the sky is smooth).
 */
export function paintSky(
  canvas: HTMLCanvasElement,
  pixels: Uint8ClampedArray<ArrayBuffer>,
  width: number,
  height: number,
): void {
  if (canvas.width !== width) canvas.width = width;
  if (canvas.height !== height) canvas.height = height;
  const context = context2d(canvas);
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  context.putImageData(new ImageData(pixels, width, height), 0, 0);
}
