// GPU backend of the neural field of <sb-inverse-render>: keeps the hash tables and
// MLP, Adam's moments, the gradient, the targets, the cameras and the loss history in
// GPU buffers for the whole run, and records K iterations (lossGradient, adam, advance;
// see shaders/kernels/neural-field.wesl) into one timed compute pass, as the voxel
// grid's InverseTrainerGpu does. The target images are the grid's: rendered by the
// inverse-render kernel's renderTarget (renderTargetsGpu), so both models fit the same
// numbers.
import { gpuCore, mapRange } from '../../gpu/core.ts';
import { withErrorScopes } from '../../gpu/errors.ts';
import { packStruct } from '../../gpu/layout.ts';
import { neuralFieldKernel } from '../../gpu/layouts.generated.ts';
import { neuralParameterCount } from '../../reference/neural.ts';
import { InverseTrainerGpu, packCameras } from './gpuBackend.ts';
import {
  BACKGROUND,
  MAX_ITERATIONS,
  effectiveBatch,
  problemCameras,
  type Hyper,
  type Problem,
  type TrainReport,
  type Trainer,
  type ViewAngle,
} from './model.ts';
import { initialNeuralField } from './neuralModel.ts';

export const NEURAL_KERNEL = 'kernels/neural-field.wesl';
const WORKGROUP = 64;
const STATS_LOSS_OFFSET = 2;
const PARAMS = neuralFieldKernel.NeuralParams;
const CAMERA = neuralFieldKernel.Camera;
const ENTRY_POINTS = ['renderField', 'lossGradient', 'adam', 'advance'] as const;
type EntryPoint = (typeof ENTRY_POINTS)[number];

/**
 * The target images of every view of a problem, rendered on the GPU by the voxel
 * grid's kernel (renderTarget of kernels/inverse-render.wesl, 192 samples per ray of
 * the hidden volume): a throw-away grid trainer of the smallest grid.
 */
export async function renderTargetsGpu(
  device: GPUDevice,
  gridCode: string,
  problem: Problem,
): Promise<Float32Array<ArrayBuffer>> {
  const grid = await InverseTrainerGpu.create(device, gridCode, {
    ...problem,
    model: 'grid',
    resolution: 2,
  });
  try {
    return new Float32Array(await grid.readTargets());
  } finally {
    grid.destroy();
  }
}

export class NeuralTrainerGpu implements Trainer {
  private readonly buffers: GPUBuffer[] = [];
  private readonly uniform: GPUBuffer;
  private readonly parameters: GPUBuffer;
  private readonly moments: GPUBuffer;
  private readonly gradient: GPUBuffer;
  private readonly targets: GPUBuffer;
  private readonly stats: GPUBuffer;
  private readonly image: GPUBuffer;
  private readonly cameras: GPUBuffer;
  private readonly bindGroup: GPUBindGroup;
  private readonly pipelines = new Map<EntryPoint, GPUComputePipeline>();
  private readonly count: number;
  private readonly trainPixels: number;
  private readonly allPixels: number;
  iteration = 0;

  private constructor(
    private readonly device: GPUDevice,
    code: string,
    public problem: Problem,
    private readonly gridCode: string,
  ) {
    this.count = neuralParameterCount(problem.tableSize);
    const pixels = problem.size * problem.size;
    this.trainPixels = problem.trainViews * pixels;
    this.allPixels = problem.views.length * pixels;
    const storage = GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST | GPUBufferUsage.COPY_SRC;
    const make = (bytes: number, usage = storage): GPUBuffer => {
      const buffer = device.createBuffer({ size: Math.max(16, bytes), usage });
      this.buffers.push(buffer);
      return buffer;
    };
    this.uniform = make(PARAMS.size, GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST);
    this.parameters = make(4 * this.count);
    this.moments = make(8 * this.count);
    this.gradient = make(4 * this.count);
    this.targets = make(12 * this.allPixels);
    this.cameras = make(CAMERA.size * problem.views.length);
    this.stats = make(4 * (STATS_LOSS_OFFSET + MAX_ITERATIONS));
    this.image = make(12 * this.allPixels);

    const core = gpuCore(device);
    const layout = core.bindGroupLayout([
      { binding: 0, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } },
      ...[1, 2, 3, 6, 7].map((binding) => ({
        binding,
        visibility: GPUShaderStage.COMPUTE,
        buffer: { type: 'storage' as const },
      })),
      ...[4, 5].map((binding) => ({
        binding,
        visibility: GPUShaderStage.COMPUTE,
        buffer: { type: 'read-only-storage' as const },
      })),
    ]);
    const pipelineLayout = core.pipelineLayout([layout]);
    for (const entryPoint of ENTRY_POINTS)
      this.pipelines.set(
        entryPoint,
        core.computePipeline({ code, entryPoint, layout: pipelineLayout }),
      );
    this.bindGroup = device.createBindGroup({
      layout,
      entries: [
        this.uniform,
        this.parameters,
        this.moments,
        this.gradient,
        this.targets,
        this.cameras,
        this.stats,
        this.image,
      ].map((buffer, binding) => ({ binding, resource: { buffer } })),
    });
    device.queue.writeBuffer(this.cameras, 0, packCameras(problemCameras(problem)));
    const initial = initialNeuralField(problem.tableSize, problem.seed).values;
    device.queue.writeBuffer(this.parameters, 0, new Float32Array(initial));
  }

  /**
   * Builds the buffers and uploads the initial field and the cameras; the targets come
   * from the grid's kernel (gridCode: kernels/inverse-render.wesl linked).
   */
  static async create(
    device: GPUDevice,
    code: string,
    gridCode: string,
    problem: Problem,
  ): Promise<NeuralTrainerGpu> {
    const targets = await renderTargetsGpu(device, gridCode, problem);
    return withErrorScopes(device, 'neural-field setup', () => {
      const trainer = new NeuralTrainerGpu(device, code, problem, gridCode);
      device.queue.writeBuffer(trainer.targets, 0, targets);
      return trainer;
    });
  }

  async setNovelView(view: ViewAngle): Promise<void> {
    const views = [...this.problem.views.slice(0, this.problem.trainViews), view];
    this.problem = { ...this.problem, views };
    const targets = await renderTargetsGpu(this.device, this.gridCode, this.problem);
    await withErrorScopes(this.device, 'neural-field held-out view', () => {
      this.device.queue.writeBuffer(this.cameras, 0, packCameras(problemCameras(this.problem)));
      this.device.queue.writeBuffer(this.targets, 0, targets);
    });
  }

  private writeParams(hyper: Hyper): void {
    const p = this.problem;
    const batch = effectiveBatch(hyper, this.trainPixels);
    const params = packStruct(PARAMS, {
      tableSize: p.tableSize,
      size: p.size,
      trainViews: p.trainViews,
      steps: p.steps,
      renderViews: p.views.length,
      lossCapacity: MAX_ITERATIONS,
      batch,
      seed: p.seed,
      background: BACKGROUND,
      lossWeight: 1 / (3 * batch),
      learningRate: hyper.learningRate,
      parameterCount: this.count,
    });
    this.device.queue.writeBuffer(this.uniform, 0, params);
  }

  private dispatch(pass: GPUComputePassEncoder, entryPoint: EntryPoint, threads: number): void {
    pass.setPipeline(this.pipelines.get(entryPoint)!);
    pass.setBindGroup(0, this.bindGroup);
    pass.dispatchWorkgroups(Math.max(1, Math.ceil(threads / WORKGROUP)));
  }

  /** Runs `count` iterations in one pass (capped by the loss history) and reads their losses. */
  async train(count: number, hyper: Hyper): Promise<TrainReport> {
    const iterations = Math.max(0, Math.min(count, MAX_ITERATIONS - this.iteration));
    const first = this.iteration;
    const lease = gpuCore(this.device).lease();
    const timer = lease.timer();
    const readBytes = 4 * (STATS_LOSS_OFFSET + Math.max(iterations, 1) + first);
    const readBack = lease.buffer(
      'neural-field.read',
      readBytes,
      GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
    );
    const start = performance.now();
    try {
      await withErrorScopes(this.device, 'neural-field iterations', () => {
        this.writeParams(hyper);
        const batch = effectiveBatch(hyper, this.trainPixels);
        const encoder = this.device.createCommandEncoder();
        const pass = encoder.beginComputePass(timer.passDescriptor());
        for (let k = 0; k < iterations; k++) {
          this.dispatch(pass, 'lossGradient', batch);
          this.dispatch(pass, 'adam', this.count);
          this.dispatch(pass, 'advance', 1);
        }
        pass.end();
        timer.resolve(encoder);
        encoder.copyBufferToBuffer(this.stats, 0, readBack, 0, readBytes);
        this.device.queue.submit([encoder.finish()]);
      });
      const words = new Uint32Array(await mapRange(readBack, readBytes));
      const wallMs = performance.now() - start;
      const losses = new Float32Array(words.buffer, 4 * (STATS_LOSS_OFFSET + first), iterations);
      this.iteration = words[0]!;
      const gpuMs = await timer.read();
      lease.release();
      return {
        losses: losses.slice(),
        iteration: this.iteration,
        dropped: words[1]!,
        gpuMs,
        wallMs,
      };
    } catch (error) {
      lease.discard();
      throw error;
    }
  }

  private read(source: GPUBuffer, bytes: number): Promise<ArrayBuffer> {
    return gpuCore(this.device).read(source, bytes);
  }

  async readTargets(): Promise<Float32Array> {
    return new Float32Array(await this.read(this.targets, 12 * this.allPixels));
  }

  /** Renders the current field from every view (training, then held-out) and reads it back. */
  async render(): Promise<{ image: Float32Array; gpuMs: number | null }> {
    return gpuCore(this.device)
      .lease()
      .run(async (lease) => {
        const timer = lease.timer();
        this.writeParams({ learningRate: 0, regularizer: 0, regularizerWeight: 0, batch: 1 });
        const encoder = this.device.createCommandEncoder();
        const pass = encoder.beginComputePass(timer.passDescriptor());
        this.dispatch(pass, 'renderField', this.allPixels);
        pass.end();
        timer.resolve(encoder);
        this.device.queue.submit([encoder.finish()]);
        const image = new Float32Array(await this.read(this.image, 12 * this.allPixels));
        return { image, gpuMs: await timer.read() };
      });
  }

  /** The current parameters (tables, then the MLP). */
  async readParameters(): Promise<Float32Array> {
    return new Float32Array(await this.read(this.parameters, 4 * this.count));
  }

  /**
   * For the tests: ∂L/∂θ at the current parameters and the data loss over a batch
   * (`hyper.batch`), without updating anything; the gradient and the loss slot are
   * cleared again afterwards.
   */
  async lossAndGradient(
    hyper: Hyper,
  ): Promise<{ loss: number; gradient: Float32Array; dropped: number }> {
    this.writeParams(hyper);
    const encoder = this.device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    this.dispatch(pass, 'lossGradient', effectiveBatch(hyper, this.trainPixels));
    pass.end();
    this.device.queue.submit([encoder.finish()]);
    const gradient = new Float32Array(await this.read(this.gradient, 4 * this.count));
    const slot = 4 * (STATS_LOSS_OFFSET + this.iteration);
    const stats = new Float32Array(await this.read(this.stats, slot + 4));
    const dropped = new Uint32Array(stats.buffer)[1]!;
    const clear = this.device.createCommandEncoder();
    clear.clearBuffer(this.gradient);
    clear.clearBuffer(this.stats, slot, 4);
    this.device.queue.submit([clear.finish()]);
    return { loss: stats[STATS_LOSS_OFFSET + this.iteration]!, gradient, dropped };
  }

  /** For the tests: replaces the parameters (tables, then the MLP). */
  writeParameters(values: Float32Array<ArrayBuffer>): void {
    this.device.queue.writeBuffer(this.parameters, 0, values);
  }

  destroy(): void {
    for (const buffer of this.buffers) buffer.destroy();
  }
}
