// Helpers for the scene renderer tests: example scenes from public/scenes/ shrunk to
// test size, and comparisons of Monte Carlo images by z-scores.
//
// Two estimates a, b of the same image (each pixel and channel a mean with its standard
// error) agree when (1) every per-pixel z = (a − b)/sqrt(se_a² + se_b² + f²) has |z| < 6,
// (2) the image-wide mean difference per channel, z-scored with the summed variances (a
// sum of independent pixel differences, Gaussian by the central limit theorem), has
// |z| < 5, and (3) the mean of z² stays below 1 + 6·sqrt(2/N). f = 1e-3 × the largest
// pixel value is a floor for rare-event pixels: where nearly every sample is 0 the sample
// standard error is itself unreliable (often exactly 0), which would make any
// difference look infinitely significant. Per-value tail probabilities: P(|z| > 6) ≈ 2e-9
// for a Gaussian (larger for the heavier tails of a 16-sample t statistic, still < 1e-4
// over a test's few thousand values); P(|z| > 5) = 5.7e-7.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { expect } from 'vitest';
import { resolveScene, type ResolvedScene } from '../../src/scene/load.ts';
import { nodeFileReader } from '../../src/scene/loadNode.ts';
import {
  renderScene,
  type SceneRender,
  type SceneRenderOptions,
} from '../../src/scene/renderScene.ts';
import { parseScene } from '../../src/scene/validate.ts';
import { SHADER_LIBRARY } from './shaderLibrary.ts';

export const SCENES_DIRECTORY = fileURLToPath(new URL('../../public/scenes/', import.meta.url));

export const EXAMPLE_SCENES = [
  'fog-slab',
  'emissive-smoke',
  'smoke-spotlight',
  'cloud-sky',
  'white-furnace',
  'rayleigh-haze',
  'spheres-on-floor',
  'mie-fog',
] as const;

export function exampleSceneJson(name: string): Record<string, unknown> {
  return JSON.parse(readFileSync(`${SCENES_DIRECTORY}${name}.json`, 'utf8')) as Record<
    string,
    unknown
  >;
}

/** An example scene with the image size and samples replaced (and other fields merged). */
export async function exampleScene(
  name: string,
  overrides: Record<string, unknown> = {},
): Promise<ResolvedScene> {
  return resolveScene(parseScene({ ...exampleSceneJson(name), ...overrides }), nodeFileReader);
}

/** A scene from JSON-compatible data, resolved (grid files under public/). */
/**
 * The homogeneous box [−1, 1]³ seen in perspective from (0.3, 0.4, 3.2), lit by a sun from
 * above and (unless `pointLight` is false) a point light inside it, whose shadow rays
 * start and end in the medium: the one-medium kernels' test scene
 * (tests/reference/scene-one-medium.test.ts, tests/shaders/scene-render.test.ts).
 */
export function boxSceneJson(options: {
  order: number | 'unlimited';
  phase: Record<string, unknown>;
  sigmaA: readonly number[];
  sigmaS: readonly number[];
  size: number;
  samplesPerPixel: number;
  seed: number;
  pointLight?: boolean;
}) {
  return {
    image: { width: options.size, height: options.size },
    samplesPerPixel: options.samplesPerPixel,
    seed: options.seed,
    scatteringOrder: options.order,
    camera: {
      type: 'perspective',
      position: [0.3, 0.4, 3.2],
      target: [0, 0, 0],
      up: [0, 1, 0],
      fovY: 45,
    },
    media: [
      {
        type: 'homogeneous',
        bounds: { type: 'box', min: [-1, -1, -1], max: [1, 1, 1] },
        sigmaA: [...options.sigmaA],
        sigmaS: [...options.sigmaS],
        phase: options.phase,
      },
    ],
    lights: [
      { type: 'directional', direction: [0.3, -0.9, -0.2], irradiance: [2, 2, 2] },
      ...(options.pointLight === false
        ? []
        : [{ type: 'point', position: [0.2, 0.5, 0.1], intensity: [0.3, 0.2, 0.1] }]),
    ],
  };
}

export function sceneFrom(json: unknown): Promise<ResolvedScene> {
  return resolveScene(parseScene(json), nodeFileReader);
}

export interface ImageEstimate {
  width: number;
  height: number;
  mean: Float64Array;
  se: Float64Array;
  samples: number;
}

export function estimateOf(render: SceneRender): ImageEstimate {
  const acc = render.accumulator;
  return {
    width: acc.width,
    height: acc.height,
    mean: acc.mean(),
    se: acc.standardError(),
    samples: acc.samples,
  };
}

/** The scene rendered by the WGSL kernel on `device` (Dawn in the tests), as an estimate. */
export async function gpuEstimate(
  device: GPUDevice,
  scene: ResolvedScene,
  options: SceneRenderOptions = {},
): Promise<ImageEstimate> {
  return estimateOf(
    await renderScene(scene, { kind: 'gpu', device, library: SHADER_LIBRARY }, options),
  );
}

/** The scene rendered by the float64 twin, as an estimate. */
export async function cpuEstimate(
  scene: ResolvedScene,
  options: SceneRenderOptions = {},
): Promise<ImageEstimate> {
  return estimateOf(await renderScene(scene, { kind: 'cpu' }, options));
}

export interface Agreement {
  maxAbsZ: number;
  meanZ2: number;
  globalZ: number[];
  n: number;
}

export function compareEstimates(a: ImageEstimate, b: ImageEstimate): Agreement {
  let largest = 0;
  for (const v of b.mean) largest = Math.max(largest, Math.abs(v));
  const floor = 1e-3 * largest;
  let maxAbsZ = 0;
  let sumZ2 = 0;
  let n = 0;
  const difference = [0, 0, 0];
  const variance = [0, 0, 0];
  for (let k = 0; k < a.mean.length; k++) {
    const d = a.mean[k]! - b.mean[k]!;
    const s2 = a.se[k]! ** 2 + b.se[k]! ** 2;
    const z = d / Math.sqrt(s2 + floor * floor);
    if (Number.isFinite(z)) {
      maxAbsZ = Math.max(maxAbsZ, Math.abs(z));
      sumZ2 += z * z;
      n++;
    }
    difference[k % 3]! += d;
    variance[k % 3]! += s2 + floor * floor;
  }
  return {
    maxAbsZ,
    meanZ2: sumZ2 / Math.max(n, 1),
    globalZ: difference.map((d, c) => d / Math.sqrt(variance[c]!)),
    n,
  };
}

export function expectAgreement(a: ImageEstimate, b: ImageEstimate, label: string): Agreement {
  const result = compareEstimates(a, b);
  const text = `${label}: ${JSON.stringify(result)}`;
  expect(result.n, text).toBe(a.mean.length);
  expect(result.maxAbsZ, text).toBeLessThan(6);
  for (const z of result.globalZ) expect(Math.abs(z), text).toBeLessThan(5);
  expect(result.meanZ2, text).toBeLessThan(1 + 6 * Math.sqrt(2 / result.n));
  return result;
}

/**
 * The estimate against exact values per pixel and channel: |z| < 6 per value, with the
 * standard error of the estimate plus an absolute allowance `systematic` (stated by the
 * caller, e.g. f32 rounding on the GPU), and the pooled z over all pixels < 5.
 */
export function expectMatchesExact(
  estimate: ImageEstimate,
  exact: (pixel: number, channel: number) => number,
  label: string,
  systematic = 0,
): void {
  const pixels = estimate.width * estimate.height;
  for (let c = 0; c < 3; c++) {
    let difference = 0;
    let variance = 0;
    for (let i = 0; i < pixels; i++) {
      const k = 3 * i + c;
      const expected = exact(i, c);
      const d = estimate.mean[k]! - expected;
      const bound = 6 * estimate.se[k]! + systematic;
      expect(
        Math.abs(d),
        `${label}: pixel ${i} channel ${c}: ${estimate.mean[k]} ± ${estimate.se[k]} vs ${expected}`,
      ).toBeLessThanOrEqual(bound);
      difference += d;
      variance += estimate.se[k]! ** 2;
    }
    const pooled = Math.abs(difference) / Math.sqrt(variance + (pixels * systematic) ** 2);
    if (Number.isFinite(pooled)) expect(pooled, `${label}: channel ${c} pooled z`).toBeLessThan(5);
  }
}
