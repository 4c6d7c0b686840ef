// What the inverse-render widget computes, independent of the backend: the hidden
// volume (the float64 twin of hiddenScene in shaders/kernels/inverse-render.wesl),
// the cameras on their orbit, the target images, the grid's initial values, and the
// float64 optimizer that the CPU fallback runs and the tests hold the GPU against:
// the loss and its gradient over every training pixel (src/reference/inverse.ts),
// the regularizers and Adam.
import {
  cameraPerspective,
  cameraRay,
  orbitCameraPosition,
  type Camera,
} from '../../reference/camera.ts';
import {
  adamStep,
  compositeStep,
  marchRayGrid,
  marchRayGridGradient,
  marchSegment,
  pixelLossGradient,
  pixelSquaredError,
  sparsityGradient,
  sparsityPenalty,
  stratifiedSubsetIndex,
  totalVariationGradient,
  type ParameterGrid,
  type Vec4,
} from '../../reference/inverse.ts';
import type { Vec3 } from '../../reference/phase.ts';
import { rngNextFloat, rngSeed } from '../../reference/rng.ts';
import type { ParameterValues } from '../parameters.ts';

/** The volume's box (m); the cameras orbit its centre. */
export const BOX_MIN: Vec3 = [-1, -1, -1];
export const BOX_MAX: Vec3 = [1, 1, 1];
/** Orbit radius (m) and vertical field of view (degrees) of every camera. */
export const CAMERA_DISTANCE = 3.6;
export const CAMERA_FOV = 38;
/** Elevation (rad) of the training views, alternating above and below the equator. */
export const TRAIN_ELEVATION = 0.3;
/** Elevation (rad) of the held-out view: from above, where no training camera looks. */
export const NOVEL_ELEVATION = 0.75;
/** Azimuth (rad) of the first training view. */
export const FIRST_AZIMUTH = 0.35;
/** Midpoint samples per ray of the target images (a converged render of the hidden volume). */
export const TARGET_STEPS = 192;
/**
 * Samples per ray of the targets' preview (the first picture of a new problem on the GPU):
 * within 1/255 of the exact targets everywhere (tests/reference/inverse.test.ts), so the
 * preview looks the same on an 8-bit display. 48 cost the first picture 70–85 ms on
 * SwiftShader (issue 23).
 */
export const PREVIEW_TARGET_STEPS = 24;
/** Background radiance behind the box, per channel. */
export const BACKGROUND: Vec3 = [0.26, 0.28, 0.34];
/** Initial raw density: σt = 10·softplus(−5) = 0.067 m⁻¹, an almost empty box (τ ≈ 0.13 across). */
export const INITIAL_DENSITY = -5;
/** Half-width of the uniform noise added to the initial raw values (breaks symmetry). */
export const INITIAL_NOISE = 0.1;
/** Loss history capacity: the largest iteration budget of the widget. */
export const MAX_ITERATIONS = 4000;
/** Image size (pixels, square) of every view on the GPU, and of the CPU fallback. */
export const GPU_IMAGE_SIZE = 32;
export const CPU_IMAGE_SIZE = 20;
/** The CPU fallback optimizes at most this resolution (the twin in float64 is slow). */
export const CPU_MAX_RESOLUTION = 16;
/** The CPU fallback's neural field uses at most 2¹² entries per level. */
export const CPU_MAX_TABLE_LOG2 = 12;
/** Regularizer codes shared with the kernel (InverseParams.regularizer). */
export const REGULARIZERS: Readonly<Record<string, number>> = { none: 0, tv: 1, sparsity: 2 };

// ---------------------------------------------------------------------------
// The hidden volume: a tilted torus and three Gaussian blobs, each with its own
// colour. Extinction adds; the emitted colour at a point is the extinction-weighted
// mean of the colours of the shapes there (the emission of a mixture).

interface Blob {
  centre: Vec3;
  radius: number;
  sigma: number;
  colour: Vec3;
}

const BLOBS: readonly Blob[] = [
  { centre: [0.38, -0.3, 0.32], radius: 0.22, sigma: 14, colour: [1, 0.58, 0.12] },
  { centre: [-0.42, 0.34, -0.22], radius: 0.28, sigma: 5, colour: [0.06, 0.05, 0.1] },
  { centre: [-0.18, -0.46, -0.42], radius: 0.16, sigma: 16, colour: [0.92, 0.22, 0.58] },
];
const TORUS = {
  major: 0.55,
  minor: 0.14,
  sigma: 10,
  tilt: 0.45,
  colour: [0.15, 0.8, 0.72] as Vec3,
};

/** (σt in 1/m, emitted r, g, b) of the hidden volume at p (m). */
export function hiddenScene(p: Vec3): Vec4 {
  const cosTilt = Math.cos(TORUS.tilt);
  const sinTilt = Math.sin(TORUS.tilt);
  // Rotate about x by −tilt into the torus's frame (its axis is the frame's y).
  const y = cosTilt * p[1] + sinTilt * p[2];
  const z = -sinTilt * p[1] + cosTilt * p[2];
  const ring = Math.hypot(p[0], z) - TORUS.major;
  const torusSigma =
    TORUS.sigma * Math.exp(-(ring * ring + y * y) / (2 * TORUS.minor * TORUS.minor));
  let sigma = torusSigma;
  const weighted = [
    torusSigma * TORUS.colour[0],
    torusSigma * TORUS.colour[1],
    torusSigma * TORUS.colour[2],
  ];
  for (const blob of BLOBS) {
    const d2 =
      (p[0] - blob.centre[0]) ** 2 + (p[1] - blob.centre[1]) ** 2 + (p[2] - blob.centre[2]) ** 2;
    const s = blob.sigma * Math.exp(-d2 / (2 * blob.radius * blob.radius));
    sigma += s;
    for (let c = 0; c < 3; c++) weighted[c]! += s * blob.colour[c]!;
  }
  if (!(sigma > 1e-20)) return [0, 0, 0, 0];
  return [sigma, weighted[0]! / sigma, weighted[1]! / sigma, weighted[2]! / sigma];
}

// ---------------------------------------------------------------------------
// The problem a run solves.

export interface ViewAngle {
  azimuth: number;
  elevation: number;
}

/** The model fitted to the images: the voxel grid, or the neural field of neuralModel.ts. */
export type ModelKind = 'grid' | 'neural';

export interface Problem {
  model: ModelKind;
  /** Voxels per axis of the grid (model 'grid'). */
  resolution: number;
  /** Entries T per level of the hash tables (model 'neural'), a power of two. */
  tableSize: number;
  /** Training views, then (last) the held-out view. */
  views: ViewAngle[];
  trainViews: number;
  size: number;
  steps: number;
  seed: number;
}

export interface Hyper {
  learningRate: number;
  regularizer: number;
  regularizerWeight: number;
  /** Rays per iteration (a stratified random subset of the training pixels). */
  batch: number;
}

/** Rays per iteration: the requested batch, at most every training pixel. */
export function effectiveBatch(hyper: Hyper, trainPixels: number): number {
  return Math.max(1, Math.min(Math.round(hyper.batch), trainPixels));
}

/** The frame index of iteration t's random strata: t ^ (seed << 12), as in the kernel. */
export function batchFrame(iteration: number, seed: number): number {
  return (iteration ^ (seed << 12)) >>> 0;
}

/** Training views evenly spaced in azimuth, alternating ±TRAIN_ELEVATION. */
export function trainingViews(count: number): ViewAngle[] {
  return Array.from({ length: count }, (_, k) => ({
    azimuth: FIRST_AZIMUTH + (2 * Math.PI * k) / count,
    elevation: count === 1 || k % 2 === 0 ? TRAIN_ELEVATION : -TRAIN_ELEVATION,
  }));
}

export function problemFrom(values: ParameterValues, backend: 'gpu' | 'cpu'): Problem {
  const requested = Number(values['grid']) || 32;
  const resolution = backend === 'cpu' ? Math.min(requested, CPU_MAX_RESOLUTION) : requested;
  const trainViews = Math.max(1, Math.round(Number(values['views']) || 1));
  const novelAzimuth = (Number(values['novel']) * Math.PI) / 180;
  const model: ModelKind = values['model'] === 'neural' ? 'neural' : 'grid';
  const log2 = Math.round(Number(values['table']) || 12);
  const tableLog2 = Math.min(Math.max(log2, 8), backend === 'cpu' ? CPU_MAX_TABLE_LOG2 : 16);
  return {
    model,
    resolution,
    tableSize: 2 ** tableLog2,
    views: [...trainingViews(trainViews), { azimuth: novelAzimuth, elevation: NOVEL_ELEVATION }],
    trainViews,
    size: backend === 'cpu' ? CPU_IMAGE_SIZE : GPU_IMAGE_SIZE,
    steps: Math.max(1, Math.round(Number(values['steps']) || 1)),
    seed: Math.round(Number(values['seed']) || 0),
  };
}

export function hyperFrom(values: ParameterValues): Hyper {
  return {
    learningRate: Number(values['rate']),
    regularizer: REGULARIZERS[String(values['regularizer'])] ?? 0,
    regularizerWeight: Number(values['weight']),
    batch: Number(values['batch']),
  };
}

/**
 * Settings that define the optimization problem: changing one starts afresh. The
 * held-out view (the last one) is not among them; moving it keeps the fit.
 */
export function problemKey(problem: Problem): string {
  return JSON.stringify({ ...problem, views: problem.views.slice(0, problem.trainViews) });
}

/** What a batch of iterations reports, on either backend. */
export interface TrainReport {
  /** Data loss of each iteration run, in order (the loss before that iteration's update). */
  losses: Float32Array | Float64Array;
  /** Iterations done in total. */
  iteration: number;
  /** Atomic adds that hit their retry cap (the GPU path; expected 0). */
  dropped: number;
  /** GPU time of the iterations from timestamp queries, or null without them (and on the CPU). */
  gpuMs: number | null;
  /** Time the iterations took: submit to read-back on the GPU, computing time on the CPU. */
  wallMs: number;
}

/** A running optimization: the GPU trainer or the CPU fallback's worker. */
export interface Trainer {
  readonly problem: Problem;
  /** Target images of every view, 3 numbers per pixel. */
  readTargets(): Promise<ArrayLike<number>>;
  /**
   * A cheaper rendering of the targets (fewer samples per ray) made before the exact ones,
   * once; null when the trainer made none (issue 23: the first picture of a new problem).
   */
  readPreviewTargets?(): Promise<ArrayLike<number> | null>;
  /** Runs up to `count` more iterations (never past MAX_ITERATIONS). */
  train(count: number, hyper: Hyper): Promise<TrainReport>;
  /** The current grid rendered from every view. */
  render(): Promise<{ image: ArrayLike<number>; gpuMs: number | null }>;
  /** Moves the held-out camera (and renders its new target); the fit is kept. */
  setNovelView(view: ViewAngle): Promise<void>;
  destroy(): void;
}

/** The cameras of a problem's views (looking at the box centre, +y up). */
export function problemCameras(problem: Problem): Camera[] {
  return problem.views.map((view) =>
    cameraPerspective(
      orbitCameraPosition([0, 0, 0], CAMERA_DISTANCE, view.azimuth, view.elevation),
      [0, 0, 0],
      [0, 1, 0],
      CAMERA_FOV,
      problem.size,
      problem.size,
    ),
  );
}

/** The ray of pixel (x, y) of a camera, through the pixel centre. */
function pixelRay(camera: Camera, x: number, y: number): { origin: Vec3; direction: Vec3 } {
  return cameraRay(camera, [x + 0.5, y + 0.5]);
}

/**
 * The target images of every view (training views, then the held-out one) from the
 * hidden volume, marched with `steps` (TARGET_STEPS, or the preview's) midpoint samples:
 * 3 numbers per pixel, views one after the other, rows from the top. Twin of the
 * kernel's renderTarget.
 */
export function renderTargetsCpu(
  problem: Problem,
  cameras = problemCameras(problem),
  steps = TARGET_STEPS,
): Float64Array {
  const pixels = problem.size * problem.size;
  const out = new Float64Array(3 * pixels * cameras.length);
  cameras.forEach((camera, view) => {
    for (let y = 0; y < problem.size; y++)
      for (let x = 0; x < problem.size; x++) {
        const { origin, direction } = pixelRay(camera, x, y);
        const segment = marchSegment(BOX_MIN, BOX_MAX, origin, direction, steps);
        let state: Vec4 = [0, 0, 0, 1];
        for (let k = 0; k < segment.count; k++) {
          const t = segment.start + (k + 0.5) * segment.step;
          const sample = hiddenScene([
            origin[0] + t * direction[0],
            origin[1] + t * direction[1],
            origin[2] + t * direction[2],
          ]);
          state = compositeStep(state, sample, segment.step);
        }
        const o = 3 * (view * pixels + y * problem.size + x);
        for (let c = 0; c < 3; c++) out[o + c] = state[c]! + state[3] * BACKGROUND[c]!;
      }
  });
  return out;
}

/**
 * The initial raw parameters: ρ = INITIAL_DENSITY and e = 0 (grey emission), each
 * plus uniform noise of half-width INITIAL_NOISE from the PCG stream of voxel i
 * (rngSeed(i, seed), four draws). The GPU path uploads exactly these numbers.
 */
export function initialGrid(resolution: number, seed: number): ParameterGrid {
  const voxels = resolution ** 3;
  const values = new Float64Array(4 * voxels);
  for (let i = 0; i < voxels; i++) {
    const state = { value: rngSeed(i, seed) };
    for (let c = 0; c < 4; c++) {
      const noise = INITIAL_NOISE * (2 * rngNextFloat(state) - 1);
      values[4 * i + c] = (c === 0 ? INITIAL_DENSITY : 0) + noise;
    }
  }
  return { resolution, values, boxMin: BOX_MIN, boxMax: BOX_MAX };
}

/** Renders the grid from the given cameras (steps midpoint samples per ray), like renderTargetsCpu. */
export function renderGridCpu(
  grid: ParameterGrid,
  cameras: readonly Camera[],
  size: number,
  steps: number,
): Float64Array {
  const pixels = size * size;
  const out = new Float64Array(3 * pixels * cameras.length);
  cameras.forEach((camera, view) => {
    for (let y = 0; y < size; y++)
      for (let x = 0; x < size; x++) {
        const { origin, direction } = pixelRay(camera, x, y);
        const { radiance } = marchRayGrid(grid, origin, direction, steps, BACKGROUND);
        out.set(radiance, 3 * (view * pixels + y * size + x));
      }
  });
  return out;
}

/** Mean squared error over pixels and channels of view `view` (images as from renderGridCpu). */
export function viewError(
  image: ArrayLike<number>,
  target: ArrayLike<number>,
  view: number,
  pixels: number,
): number {
  let sum = 0;
  for (let i = 3 * view * pixels; i < 3 * (view + 1) * pixels; i++)
    sum += ((image[i] ?? 0) - (target[i] ?? 0)) ** 2;
  return sum / (3 * pixels);
}

export interface LossGradient {
  /** The data term: the mean squared error over training pixels and channels. */
  loss: number;
  /** ∂loss/∂θ, 4 numbers per voxel. */
  gradient: Float64Array;
  /** Σ|contribution| per parameter (only when asked for). */
  magnitude?: Float64Array;
}

/** The training pixels of iteration t's batch (flattened view-major indices), as the kernel picks them. */
export function batchRays(problem: Problem, hyper: Hyper, iteration: number): number[] {
  const total = problem.trainViews * problem.size * problem.size;
  const count = effectiveBatch(hyper, total);
  const frame = batchFrame(iteration, problem.seed);
  return Array.from({ length: count }, (_, j) => stratifiedSubsetIndex(j, count, total, frame));
}

/**
 * The mean squared error over the given training pixels (all of them by default;
 * flattened indices view·size² + row·size + column) and its gradient with respect
 * to every grid parameter: the twin of the kernel's lossGradient, whose loss weight
 * is w = 1/(3·pixels) likewise.
 */
export function lossAndGradientCpu(
  grid: ParameterGrid,
  problem: Problem,
  targets: ArrayLike<number>,
  options: { cameras?: readonly Camera[]; rays?: readonly number[]; withMagnitude?: boolean } = {},
): LossGradient {
  const cameras = options.cameras ?? problemCameras(problem);
  const pixels = problem.size * problem.size;
  const rays = options.rays ?? Array.from({ length: problem.trainViews * pixels }, (_, i) => i);
  const weight = 1 / (3 * rays.length);
  const gradient = new Float64Array(grid.values.length);
  const magnitude = options.withMagnitude ? new Float64Array(grid.values.length) : undefined;
  let loss = 0;
  for (const i of rays) {
    const pixel = i % pixels;
    const { origin, direction } = pixelRay(
      cameras[Math.floor(i / pixels)]!,
      pixel % problem.size,
      Math.floor(pixel / problem.size),
    );
    const { radiance } = marchRayGrid(grid, origin, direction, problem.steps, BACKGROUND);
    const target: Vec3 = [targets[3 * i] ?? 0, targets[3 * i + 1] ?? 0, targets[3 * i + 2] ?? 0];
    loss += weight * pixelSquaredError(radiance, target);
    const g = pixelLossGradient(radiance, target, weight);
    marchRayGridGradient(
      grid,
      origin,
      direction,
      problem.steps,
      BACKGROUND,
      g,
      gradient,
      magnitude,
    );
  }
  return magnitude ? { loss, gradient, magnitude } : { loss, gradient };
}

/**
 * The regularizer's value and its gradient added to `gradient`, per voxel (the twin
 * of the kernel's regularize): total variation of ρ over face-neighbour pairs, or
 * the Cauchy sparsity prior ln(1 + 2σt²), both times weight/voxels.
 */
export function addRegularizerCpu(
  grid: ParameterGrid,
  hyper: Hyper,
  gradient: Float64Array,
): number {
  if (hyper.regularizer === 0 || hyper.regularizerWeight === 0) return 0;
  const n = grid.resolution;
  const voxels = n ** 3;
  const scale = hyper.regularizerWeight / voxels;
  const rho = (x: number, y: number, z: number): number => grid.values[4 * ((z * n + y) * n + x)]!;
  let penalty = 0;
  for (let z = 0; z < n; z++)
    for (let y = 0; y < n; y++)
      for (let x = 0; x < n; x++) {
        const i = (z * n + y) * n + x;
        const value = rho(x, y, z);
        if (hyper.regularizer === 2) {
          penalty += scale * sparsityPenalty(value);
          gradient[4 * i]! += scale * sparsityGradient(value);
          continue;
        }
        let sum = 0;
        let count = 0;
        for (const [dx, dy, dz] of NEIGHBOURS) {
          const [a, b, c] = [x + dx, y + dy, z + dz];
          if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n) continue;
          const other = rho(a, b, c);
          sum += other;
          count += 1;
          // Each pair once in the penalty: the forward neighbours only.
          if (dx + dy + dz > 0) penalty += scale * (value - other) ** 2;
        }
        gradient[4 * i]! += scale * totalVariationGradient(value, sum, count);
      }
  return penalty;
}

const NEIGHBOURS: readonly (readonly [number, number, number])[] = [
  [1, 0, 0],
  [-1, 0, 0],
  [0, 1, 0],
  [0, -1, 0],
  [0, 0, 1],
  [0, 0, -1],
];

/**
 * The float64 optimizer: Adam on every parameter with the gradient of a batch of
 * rays, as the GPU runs it (same batches, same loss, same regularizers, same update).
 */
export class InverseOptimizerCpu {
  readonly grid: ParameterGrid;
  readonly cameras: Camera[];
  private readonly m: Float64Array;
  private readonly v: Float64Array;
  iteration = 0;

  constructor(
    readonly problem: Problem,
    readonly targets: Float64Array,
  ) {
    this.grid = initialGrid(problem.resolution, problem.seed);
    this.cameras = problemCameras(problem);
    this.m = new Float64Array(this.grid.values.length);
    this.v = new Float64Array(this.grid.values.length);
  }

  /** One iteration on its batch of rays; returns the batch's data loss before the update. */
  step(hyper: Hyper): number {
    const { loss, gradient } = lossAndGradientCpu(this.grid, this.problem, this.targets, {
      cameras: this.cameras,
      rays: batchRays(this.problem, hyper, this.iteration),
    });
    addRegularizerCpu(this.grid, hyper, gradient);
    this.iteration += 1;
    const values = this.grid.values;
    for (let i = 0; i < values.length; i++) {
      const [value, m, v] = adamStep(
        values[i]!,
        gradient[i]!,
        this.m[i]!,
        this.v[i]!,
        this.iteration,
        hyper.learningRate,
      );
      values[i] = value;
      this.m[i] = m;
      this.v[i] = v;
    }
    return loss;
  }

  /** Current renders of every view (training, then held-out). */
  render(): Float64Array {
    return renderGridCpu(this.grid, this.cameras, this.problem.size, this.problem.steps);
  }
}
