// The CPU renderer: the float64 twin (src/reference/integrator.ts) over the same pixels
// and random streams as the kernel shaders/kernels/scene-render.wesl. It is the fallback
// where there is no WebGPU and the oracle the GPU is tested against; slow (one JS call
// tree per sample), so it suits small images.
import { cameraRay } from '../reference/camera.ts';
import { estimateRadiance, sceneCamera, type SceneData } from '../reference/integrator.ts';
import { pcgHash, rngNextFloat, rngSeed, type RngState } from '../reference/rng.ts';
import { ImageAccumulator, PASS_WORDS_PER_PIXEL, type Accumulation } from './accumulation.ts';
import type { PassOutput, PassRenderer } from './render.ts';

/** One sample of pixel (x, y): the kernel's stream rngSeed(i, pcgHash(seed) + s), jitter, ray. */
export function renderPixelSample(
  scene: SceneData,
  x: number,
  y: number,
  width: number,
  seed: number,
  sampleIndex: number,
): [number, number, number] {
  const camera = sceneCamera(scene);
  const state: RngState = {
    value: rngSeed(y * width + x, (pcgHash(seed) + sampleIndex) >>> 0),
  };
  const jitter: [number, number] = [rngNextFloat(state), rngNextFloat(state)];
  const ray = cameraRay(camera, [x + jitter[0], y + jitter[1]]);
  return estimateRadiance(scene, ray.origin, ray.direction, state);
}

/**
 * One pass of the twin: samples sampleOffset … sampleOffset + samples − 1 of every pixel,
 * as PASS_WORDS_PER_PIXEL sums per pixel (R, G, B, their squares, lookups, capped), the
 * words the GPU pass writes. A pure function of its arguments (the streams are keyed by
 * pixel, seed and sample index), so it can run in the compute worker
 * (src/scene/passJob.ts) as well as here; `out` is reused when given.
 */
export function renderPassSums(
  scene: SceneData,
  width: number,
  height: number,
  seed: number,
  sampleOffset: number,
  samples: number,
  out: Float64Array<ArrayBuffer> = new Float64Array(PASS_WORDS_PER_PIXEL * width * height),
): Float64Array<ArrayBuffer> {
  out.fill(0);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const o = PASS_WORDS_PER_PIXEL * (y * width + x);
      scene.stats.lookups = 0;
      scene.stats.capped = 0;
      for (let s = 0; s < samples; s++) {
        const radiance = renderPixelSample(scene, x, y, width, seed, sampleOffset + s);
        for (let c = 0; c < 3; c++) {
          out[o + c]! += radiance[c]!;
          out[o + 3 + c]! += radiance[c]! ** 2;
        }
      }
      out[o + 6] = scene.stats.lookups;
      out[o + 7] = scene.stats.capped;
    }
  }
  return out;
}

export class CpuSceneRenderer implements PassRenderer {
  readonly timing = 'cpu' as const;
  /** The float64 moments of every pass so far. */
  readonly accumulation: ImageAccumulator;
  /** One pass's sums, PASS_WORDS_PER_PIXEL per pixel, reused from pass to pass. */
  private readonly passSums: Float64Array<ArrayBuffer>;

  constructor(
    private readonly scene: SceneData,
    private readonly width: number,
    private readonly height: number,
    private readonly seed: number,
  ) {
    this.accumulation = new ImageAccumulator(width, height);
    this.passSums = new Float64Array(PASS_WORDS_PER_PIXEL * width * height);
  }

  renderPass(sampleOffset: number, samples: number): Promise<PassOutput> {
    const start = performance.now();
    const { scene, width, height, seed, passSums } = this;
    renderPassSums(scene, width, height, seed, sampleOffset, samples, passSums);
    this.accumulation.addPass(passSums, passSums, samples);
    return Promise.resolve({ milliseconds: performance.now() - start });
  }

  release(): Accumulation {
    return this.accumulation;
  }

  destroy(): void {}
}
