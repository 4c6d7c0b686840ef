// CPU backend of <sb-hg-lobe>: the float64 twins replay the kernel's PCG streams
// to build the same histogram, and a 2D canvas shows the same polar picture at
// reduced resolution. Used without WebGPU and after a device loss; the sampler is
// also the reference the GPU histogram is compared with.
import { hgEval, hgSampleMu, phaseIsotropic, rayleighEval } from '../../reference/phase.ts';
import { rngNextFloat, rngSeed } from '../../reference/rng.ts';
import {
  BIN_COUNT,
  binOf,
  polarLayout,
  radiusFor,
  type HgHistogram,
  type HgLobeInputs,
  type PolarLayout,
} from './model.ts';
import { context2d } from '../base/canvas2d.ts';

/**
 * The kernel's sampling pass in float64: sample i takes ξ from the stream
 * rngSeed(i, seed) and μ = hgSampleMu(g, ξ, 1 − ξ) (physics.md §2.4).
 */
export function sampleHistogramCpu(g: number, sampleCount: number, seed: number): HgHistogram {
  const start = performance.now();
  const histogram = emptyHistogram(sampleCount);
  accumulateSamples(histogram, g, 0, sampleCount, seed);
  histogram.milliseconds = performance.now() - start;
  return histogram;
}

function emptyHistogram(sampleCount: number): HgHistogram {
  return {
    bins: new Uint32Array(BIN_COUNT),
    sampleCount,
    sumMu: 0,
    sumMuSquared: 0,
    milliseconds: 0,
    timing: 'cpu',
  };
}

/** Adds samples first … end − 1 of the kernel's streams to a histogram. */
function accumulateSamples(
  histogram: HgHistogram,
  g: number,
  first: number,
  end: number,
  seed: number,
): void {
  const { bins } = histogram;
  let sumMu = 0;
  let sumMuSquared = 0;
  const state = { value: 0 };
  for (let i = first; i < end; i++) {
    state.value = rngSeed(i, seed);
    const xi = rngNextFloat(state);
    const { mu, onePlusMu } = hgSampleMu(g, xi, 1 - xi);
    bins[binOf(onePlusMu)]! += 1;
    sumMu += mu;
    sumMuSquared += mu * mu;
  }
  histogram.sumMu += sumMu;
  histogram.sumMuSquared += sumMuSquared;
}

/**
 * The same histogram as sampleHistogramCpu, computed in chunks of `chunk` samples
 * with a yield to the page after each, so that a sweep to 2^20 samples on the CPU
 * never freezes the page. The time counts the sampling only, not the yields.
 */
export async function sampleHistogramCpuInChunks(
  g: number,
  sampleCount: number,
  seed: number,
  chunk = 1 << 16,
): Promise<HgHistogram> {
  const histogram = emptyHistogram(sampleCount);
  for (let first = 0; first < sampleCount; first += chunk) {
    const start = performance.now();
    accumulateSamples(histogram, g, first, Math.min(first + chunk, sampleCount), seed);
    histogram.milliseconds += performance.now() - start;
    await new Promise((resolve) => setTimeout(resolve, 0));
  }
  return histogram;
}

interface LobeShape {
  radius: number;
  /** dR/dθ in pixels per radian. */
  slope: number;
}

/** R(θ) and R'(θ) for a phase function with value p and slope dp/dθ. */
function shape(p: number, dpdtheta: number, inputs: HgLobeInputs, layout: PolarLayout): LobeShape {
  const radius = radiusFor(p, inputs.scale, layout);
  if (inputs.scale === 'linear') return { radius, slope: layout.pixelsPerUnit * dpdtheta };
  return { radius, slope: radius > 0 ? (layout.pixelsPerUnit * dpdtheta) / (Math.LN10 * p) : 0 };
}

/** Distance from (r, θ) to the polar curve R(θ), to first order in the slope (negative inside). */
function distanceTo(r: number, lobe: LobeShape): number {
  return (r - lobe.radius) / Math.hypot(1, lobe.slope / Math.max(r, 0.5));
}

function smoothstep(edge0: number, edge1: number, x: number): number {
  const t = Math.min(Math.max((x - edge0) / (edge1 - edge0), 0), 1);
  return t * t * (3 - 2 * t);
}

/** 1 inside a line of half width w, fading over one output pixel of `pixel` canvas pixels. */
function line(distance: number, halfWidth: number, pixel: number): number {
  return 1 - smoothstep(halfWidth - 0.5 * pixel, halfWidth + 0.5 * pixel, Math.abs(distance));
}

function mix(a: number[], b: readonly number[], t: number): void {
  for (let i = 0; i < 3; i++) a[i] = a[i]! + (b[i]! - a[i]!) * t;
}

/**
 * The colour of the WGSL fragment shader lobeFragment at (px, py) canvas pixels from
 * the top left, in float64, display-encoded (gamma 2.2) in [0, 1]³; edges are
 * antialiased over `pixel` canvas pixels (the size of one output pixel).
 */
export function shadeLobe(
  px: number,
  py: number,
  inputs: HgLobeInputs,
  layout: PolarLayout,
  pixel = 1,
): [number, number, number] {
  const g = inputs.g;
  const x = px - layout.centreX;
  const y = layout.centreY - py;
  const r = Math.hypot(x, y);
  const theta = Math.atan2(Math.abs(y), x);
  const mu = Math.cos(theta);
  const sinTheta = Math.sin(theta);
  const color = [0.015, 0.02, 0.035];
  const ringSpacing = layout.ringStep * layout.pixelsPerUnit;
  const ringIndex = Math.round(r / ringSpacing);
  const ring = ringIndex >= 1 ? line(r - ringIndex * ringSpacing, 0.5, pixel) : 0;
  const rayStep = Math.PI / 6;
  const phi = Math.atan2(y, x);
  const ray = line(r * Math.sin(Math.abs(phi - Math.round(phi / rayStep) * rayStep)), 0.5, pixel);
  const grid = Math.max(ring, 0.6 * ray);
  color[0]! += 0.16 * grid;
  color[1]! += 0.18 * grid;
  color[2]! += 0.22 * grid;
  // The beam: a shaft left of x = −27 px and an arrowhead from there to x = −7 px.
  const shaft = line(y, 2, pixel) * (1 - smoothstep(-27 - 0.5 * pixel, -27 + 0.5 * pixel, x));
  const inHead = x >= -27 && x <= -7 ? 1 : 0;
  const head = inHead * (1 - smoothstep(-0.5 * pixel, 0.5 * pixel, Math.abs(y) - 0.45 * (-7 - x)));
  mix(color, [1, 0.93, 0.78], Math.max(shaft, head));
  // HG: p ∝ (1 + g² − 2gμ)^{-3/2}, so dp/dθ = −sinθ·3g·p/(1 + g² − 2gμ).
  const p = hgEval(g, mu);
  const lobe = shape(p, (-sinTheta * 3 * g * p) / (1 + g * g - 2 * g * mu), inputs, layout);
  const edge = distanceTo(r, lobe);
  mix(color, [0.85, 0.51, 0.17], 0.55 * (1 - smoothstep(-0.75 * pixel, 0.75 * pixel, edge)));
  mix(color, [1, 0.72, 0.38], line(edge, 0.75, pixel));
  if (inputs.compare !== 'none') {
    const rayleigh = inputs.compare === 'rayleigh';
    const q = rayleigh ? rayleighEval(mu) : phaseIsotropic();
    // Rayleigh: dp/dθ = −sinθ·3μ/(8π); isotropic: 0.
    const other = shape(q, rayleigh ? (-sinTheta * 3 * mu) / (8 * Math.PI) : 0, inputs, layout);
    mix(color, [0.45, 0.65, 1], line(distanceTo(r, other), 1, pixel));
  }
  mix(color, [1, 1, 1], 1 - smoothstep(2.5, 3.5, r));
  const encode = (c: number): number => Math.min(Math.max(c, 1e-6), 1) ** (1 / 2.2);
  return [encode(color[0]!), encode(color[1]!), encode(color[2]!)];
}

/**
 * The picture of the WGSL fragment shader lobeFragment for a canvas of canvasWidth ×
 * canvasHeight, in float64, at 1/scale resolution, as RGBA bytes (pure: it runs in the
 * compute worker, jobs.ts).
 */
export function polarPixels(
  inputs: HgLobeInputs,
  canvasWidth: number,
  canvasHeight: number,
  scale = 2,
): { pixels: Uint8ClampedArray<ArrayBuffer>; width: number; height: number } {
  const layout = polarLayout(inputs, canvasWidth, canvasHeight);
  const width = Math.max(1, Math.floor(canvasWidth / scale));
  const height = Math.max(1, Math.floor(canvasHeight / scale));
  const pixels = new Uint8ClampedArray(4 * width * height);
  for (let row = 0; row < height; row++) {
    for (let column = 0; column < width; column++) {
      const rgb = shadeLobe((column + 0.5) * scale, (row + 0.5) * scale, inputs, layout, scale);
      const offset = (row * width + column) * 4;
      for (let i = 0; i < 3; i++) pixels[offset + i] = Math.round(255 * rgb[i]!);
      pixels[offset + 3] = 255;
    }
  }
  return { pixels, width, height };
}

/** Shows polarPixels' bytes on the canvas, scaled up smoothly to its full size. */
export function paintPolar(
  canvas: HTMLCanvasElement,
  image: { pixels: Uint8ClampedArray<ArrayBuffer>; width: number; height: number },
): void {
  const context = context2d(canvas);
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const small = new OffscreenCanvas(image.width, image.height);
  context2d(small)?.putImageData(new ImageData(image.pixels, image.width, image.height), 0, 0);
  context.imageSmoothingEnabled = true;
  context.drawImage(small, 0, 0, canvas.width, canvas.height);
}

/** Draws the picture of the WGSL fragment shader lobeFragment, in float64, at 1/scale resolution. */
export function drawLobeCpu(canvas: HTMLCanvasElement, inputs: HgLobeInputs, scale = 2): void {
  paintPolar(canvas, polarPixels(inputs, canvas.width, canvas.height, scale));
}
