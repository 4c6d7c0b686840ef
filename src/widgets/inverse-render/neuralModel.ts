// The neural field of <sb-inverse-render> (model "hash grid + MLP"), independent of
// the backend: its initial parameters, the loss and gradient over a batch of training
// rays (src/reference/neural.ts), and the float64 optimizer that the CPU fallback runs
// and the tests hold the GPU against. The problem (hidden volume, cameras, targets,
// batches, loss, Adam) is the voxel grid's, from model.ts: only the model differs.
import type { Camera } from '../../reference/camera.ts';
import { cameraRay } from '../../reference/camera.ts';
import { adamStep, pixelLossGradient, pixelSquaredError } from '../../reference/inverse.ts';
import {
  NEURAL_B2,
  NEURAL_HIDDEN,
  NEURAL_INPUTS,
  NEURAL_MLP_SIZE,
  NEURAL_W2,
  marchRayNeural,
  marchRayNeuralGradient,
  neuralMlpOffset,
  neuralParameterCount,
  type NeuralField,
} from '../../reference/neural.ts';
import type { Vec3 } from '../../reference/phase.ts';
import { rngNextFloat, rngSeed } from '../../reference/rng.ts';
import {
  BACKGROUND,
  BOX_MAX,
  BOX_MIN,
  INITIAL_DENSITY,
  batchRays,
  problemCameras,
  type Hyper,
  type LossGradient,
  type Problem,
} from './model.ts';

/**
 * Half-width of the uniform initial table entries: Instant-NGP's U(−10⁻⁴, 10⁻⁴)
 * (Müller et al. 2022, §4), small enough that the start is the MLP's constant output
 * (an almost empty box, like the grid's start) and large enough to break symmetry.
 */
export const TABLE_INIT = 1e-4;

/**
 * The initial parameters: table entries uniform in ±TABLE_INIT; W₁ uniform in
 * ±√(6/16) (He et al. 2015 for ReLU, fan-in 16), b₁ = 0; W₂ uniform in ±√(6/(16 + 4))
 * (Glorot & Bengio 2010) and b₂ = (INITIAL_DENSITY, 0, 0, 0), so σt starts at the grid's
 * 0.067 m⁻¹ and the colour at grey. Each parameter i draws from the PCG stream
 * rngSeed(i, seed); the GPU path uploads exactly these numbers (rounded to f32).
 */
export function initialNeuralField(tableSize: number, seed: number): NeuralField {
  const values = new Float64Array(neuralParameterCount(tableSize));
  const offset = neuralMlpOffset(tableSize);
  for (let i = 0; i < values.length; i++) {
    const u = 2 * rngNextFloat({ value: rngSeed(i, seed ^ 0x5eed) }) - 1;
    const k = i - offset;
    if (k < 0) values[i] = TABLE_INIT * u;
    else if (k < NEURAL_HIDDEN * NEURAL_INPUTS) values[i] = Math.sqrt(6 / NEURAL_INPUTS) * u;
    else if (k < NEURAL_W2) values[i] = 0;
    else if (k < NEURAL_B2) values[i] = Math.sqrt(6 / (NEURAL_HIDDEN + 4)) * u;
    else values[i] = k === NEURAL_B2 ? INITIAL_DENSITY : 0;
  }
  return { tableSize, values, boxMin: BOX_MIN, boxMax: BOX_MAX };
}

/** Bytes of the model's parameters as the GPU stores them (f32). */
export function neuralBytes(tableSize: number): number {
  return 4 * neuralParameterCount(tableSize);
}

export { NEURAL_MLP_SIZE };

/** The ray of pixel (x, y) of a camera, through the pixel centre. */
function pixelRay(camera: Camera, x: number, y: number): { origin: Vec3; direction: Vec3 } {
  return cameraRay(camera, [x + 0.5, y + 0.5]);
}

/** Renders the neural field from the given cameras, 3 numbers per pixel, views in order. */
export function renderNeuralCpu(
  field: NeuralField,
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
        out.set(
          marchRayNeural(field, origin, direction, steps, BACKGROUND),
          3 * (view * pixels + y * size + x),
        );
      }
  });
  return out;
}

/** The mean squared error over the given training pixels (all by default), without the gradient. */
export function lossNeuralCpu(
  field: NeuralField,
  problem: Problem,
  targets: ArrayLike<number>,
  options: { cameras?: readonly Camera[]; rays?: readonly number[] } = {},
): number {
  const cameras = options.cameras ?? problemCameras(problem);
  const pixels = problem.size * problem.size;
  const rays = options.rays ?? Array.from({ length: problem.trainViews * pixels }, (_, i) => i);
  let sum = 0;
  for (const i of rays) {
    const pixel = i % pixels;
    const { origin, direction } = pixelRay(
      cameras[Math.floor(i / pixels)]!,
      pixel % problem.size,
      Math.floor(pixel / problem.size),
    );
    const radiance = marchRayNeural(field, origin, direction, problem.steps, BACKGROUND);
    const target: Vec3 = [targets[3 * i] ?? 0, targets[3 * i + 1] ?? 0, targets[3 * i + 2] ?? 0];
    sum += pixelSquaredError(radiance, target);
  }
  return sum / (3 * rays.length);
}

/**
 * The mean squared error over the given training pixels (all by default) and its
 * gradient with respect to every parameter of the neural field: the twin of the
 * kernel's lossGradient (same weight w = 1/(3·pixels)).
 */
export function lossAndGradientNeuralCpu(
  field: NeuralField,
  problem: Problem,
  targets: ArrayLike<number>,
  options: { cameras?: readonly Camera[]; rays?: readonly number[]; withMagnitude?: boolean } = {},
): LossGradient {
  const cameras = options.cameras ?? problemCameras(problem);
  const pixels = problem.size * problem.size;
  const rays = options.rays ?? Array.from({ length: problem.trainViews * pixels }, (_, i) => i);
  const weight = 1 / (3 * rays.length);
  const gradient = new Float64Array(field.values.length);
  const magnitude = options.withMagnitude ? new Float64Array(field.values.length) : undefined;
  let loss = 0;
  for (const i of rays) {
    const pixel = i % pixels;
    const { origin, direction } = pixelRay(
      cameras[Math.floor(i / pixels)]!,
      pixel % problem.size,
      Math.floor(pixel / problem.size),
    );
    const radiance = marchRayNeural(field, origin, direction, problem.steps, BACKGROUND);
    const target: Vec3 = [targets[3 * i] ?? 0, targets[3 * i + 1] ?? 0, targets[3 * i + 2] ?? 0];
    loss += weight * pixelSquaredError(radiance, target);
    marchRayNeuralGradient(
      field,
      origin,
      direction,
      problem.steps,
      BACKGROUND,
      pixelLossGradient(radiance, target, weight),
      gradient,
      magnitude,
    );
  }
  return magnitude ? { loss, gradient, magnitude } : { loss, gradient };
}

/** The float64 optimizer of the neural field: Adam on every parameter, the grid's batches. */
export class NeuralOptimizerCpu {
  readonly field: NeuralField;
  readonly cameras: Camera[];
  private readonly m: Float64Array;
  private readonly v: Float64Array;
  iteration = 0;

  constructor(
    readonly problem: Problem,
    readonly targets: Float64Array,
  ) {
    this.field = initialNeuralField(problem.tableSize, problem.seed);
    this.cameras = problemCameras(problem);
    this.m = new Float64Array(this.field.values.length);
    this.v = new Float64Array(this.field.values.length);
  }

  /** One iteration on its batch of rays; returns the batch's loss before the update. */
  step(hyper: Hyper): number {
    const { loss, gradient } = lossAndGradientNeuralCpu(this.field, this.problem, this.targets, {
      cameras: this.cameras,
      rays: batchRays(this.problem, hyper, this.iteration),
    });
    this.iteration += 1;
    const values = this.field.values;
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

  render(): Float64Array {
    return renderNeuralCpu(this.field, this.cameras, this.problem.size, this.problem.steps);
  }
}
