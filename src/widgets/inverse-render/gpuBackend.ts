// GPU backend of <sb-inverse-render>: keeps the grid, Adam's moments, the gradient,
// the targets, the cameras and the loss history in GPU buffers for the whole run,
// and records K iterations (lossGradient, regularize, adam, advance; see
// shaders/kernels/inverse-render.wesl) into one timed compute pass. Only the loss
// history and, now and then, the rendered views are read back. The same class runs
// in the browser and, through Dawn, in the tests.
import type { Camera } from '../../reference/camera.ts';
import { gpuCore, mapRange } from '../../gpu/core.ts';
import { withErrorScopes } from '../../gpu/errors.ts';
import { packStruct, wordsOf, writeStruct } from '../../gpu/layout.ts';
import { inverseRenderKernel } from '../../gpu/layouts.generated.ts';
import {
  BACKGROUND,
  MAX_ITERATIONS,
  effectiveBatch,
  initialGrid,
  problemCameras,
  type Hyper,
  type Problem,
  type TrainReport,
  type Trainer,
  type ViewAngle,
} from './model.ts';

export const KERNEL = 'kernels/inverse-render.wesl';
const WORKGROUP = 64;
/** stats[0] iterations done, stats[1] dropped atomic adds, then the loss history. */
const STATS_LOSS_OFFSET = 2;
/** The kernel's uniform and camera records, laid out from their WGSL declarations. */
const PARAMS = inverseRenderKernel.InverseParams;
const CAMERA = inverseRenderKernel.Camera;
const ENTRY_POINTS = [
  'renderTarget',
  'renderField',
  'lossGradient',
  'regularize',
  'adam',
  'advance',
] as const;
type EntryPoint = (typeof ENTRY_POINTS)[number];

/** The camera structs as the kernel reads them (camera.wesl's Camera, one per view). */
export function packCameras(cameras: readonly Camera[]): Float32Array<ArrayBuffer> {
  const words = wordsOf(new ArrayBuffer(CAMERA.size * cameras.length));
  cameras.forEach((camera, i) => {
    const { position, projection, forward, right, up, halfExtent, imageSize } = camera;
    const values = { position, projection, forward, right, up, halfExtent, imageSize };
    writeStruct(CAMERA, values, words, CAMERA.size * i);
  });
  return words.f32;
}

export class InverseTrainerGpu implements Trainer {
  private readonly buffers: GPUBuffer[] = [];
  private readonly uniform: GPUBuffer;
  private readonly field: GPUBuffer;
  private readonly moments: GPUBuffer;
  private readonly gradient: GPUBuffer;
  private readonly targets: GPUBuffer;
  /** The preview targets' copy until read (renderPreviewTargets). */
  private previewTargets: GPUBuffer | null = null;
  /** The exact targets wait for the preview's read-back (submitExactTargets). */
  private exactTargetsPending = false;
  private readonly stats: GPUBuffer;
  private readonly image: GPUBuffer;
  private readonly cameras: GPUBuffer;
  private readonly bindGroup: GPUBindGroup;
  private readonly pipelines = new Map<EntryPoint, GPUComputePipeline>();
  private readonly voxels: number;
  private readonly trainPixels: number;
  private readonly allPixels: number;
  iteration = 0;

  private constructor(
    private readonly device: GPUDevice,
    code: string,
    public problem: Problem,
  ) {
    const n = problem.resolution;
    this.voxels = n ** 3;
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
    this.field = make(16 * this.voxels);
    this.moments = make(32 * this.voxels);
    this.gradient = make(16 * this.voxels);
    this.targets = make(12 * this.allPixels);
    this.cameras = make(CAMERA.size * problem.views.length);
    const cameras = this.cameras;
    this.stats = make(4 * (STATS_LOSS_OFFSET + MAX_ITERATIONS));
    this.image = make(12 * this.allPixels);

    // Layouts and pipelines from the GPU core (a second trainer of the same code reuses them).
    const core = gpuCore(device);
    const layout = core.bindGroupLayout([
      { binding: 0, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } },
      ...[1, 2, 3, 4, 6, 7].map((binding) => ({
        binding,
        visibility: GPUShaderStage.COMPUTE,
        buffer: { type: 'storage' as const },
      })),
      { binding: 5, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'read-only-storage' } },
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
        this.field,
        this.moments,
        this.gradient,
        this.targets,
        cameras,
        this.stats,
        this.image,
      ].map((buffer, binding) => ({ binding, resource: { buffer } })),
    });
    device.queue.writeBuffer(cameras, 0, packCameras(problemCameras(problem)));
    const initial = initialGrid(n, problem.seed).values;
    device.queue.writeBuffer(this.field, 0, new Float32Array(initial));
  }

  /**
   * Builds the buffers, uploads the initial grid and cameras, and renders the targets (with
   * `previewSteps`, a preview of them first: readPreviewTargets).
   */
  static async create(
    device: GPUDevice,
    code: string,
    problem: Problem,
    options: { previewSteps?: number } = {},
  ): Promise<InverseTrainerGpu> {
    const trainer = await withErrorScopes(
      device,
      'inverse-render setup',
      () => new InverseTrainerGpu(device, code, problem),
    );
    if (options.previewSteps === undefined) trainer.renderTargets();
    else {
      trainer.renderPreviewTargets(options.previewSteps);
      trainer.exactTargetsPending = true;
    }
    return trainer;
  }

  /**
   * Submits the exact targets that create({ previewSteps }) held back, once. They go to the
   * GPU after the preview has come back, not beside it: submitted together, the preview's
   * read-back often came back only with the exact targets (SwiftShader's threads took both
   * cores for their 169 ms dispatch, and the map's answer waited behind them: first picture
   * 88–264 ms in bench/firstPictureProbe.ts).
   */
  private submitExactTargets(): void {
    if (!this.exactTargetsPending) return;
    this.exactTargetsPending = false;
    this.renderTargets();
  }

  private renderTargets(): void {
    this.writeParams({ learningRate: 0, regularizer: 0, regularizerWeight: 0, batch: 1 });
    const encoder = this.device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    this.dispatch(pass, 'renderTarget', this.allPixels);
    pass.end();
    this.device.queue.submit([encoder.finish()]);
  }

  /**
   * The targets with `steps` samples per ray instead of TARGET_STEPS, copied into a buffer
   * of their own in the same submission, before the exact targets are submitted: they are
   * drawn (readPreviewTargets) while the GPU renders the exact ones. The
   * exact targets of 12 views took 169 ms in one dispatch on SwiftShader, the first picture
   * of a new problem waited for them (issue 23), and PREVIEW_TARGET_STEPS of 192 midpoint
   * samples of the smooth hidden volume look the same at 32² pixels (model.ts).
   */
  private renderPreviewTargets(steps: number): void {
    this.writeParams(
      { learningRate: 0, regularizer: 0, regularizerWeight: 0, batch: 1 },
      Math.max(1, Math.round(steps)),
    );
    const bytes = 12 * this.allPixels;
    const copy = this.device.createBuffer({
      size: bytes,
      usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
    });
    this.previewTargets = copy;
    const encoder = this.device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    this.dispatch(pass, 'renderTarget', this.allPixels);
    pass.end();
    encoder.copyBufferToBuffer(this.targets, 0, copy, 0, bytes);
    this.device.queue.submit([encoder.finish()]);
  }

  /** The preview targets of create({ previewSteps }), once; null without them. */
  async readPreviewTargets(): Promise<Float32Array | null> {
    const copy = this.previewTargets;
    if (!copy) return null;
    this.previewTargets = null;
    try {
      await copy.mapAsync(GPUMapMode.READ);
      return new Float32Array(copy.getMappedRange().slice(0));
    } finally {
      copy.destroy();
      // Also when the map failed: readTargets must find the exact targets on their way.
      this.submitExactTargets();
    }
  }

  async setNovelView(view: ViewAngle): Promise<void> {
    const views = [...this.problem.views.slice(0, this.problem.trainViews), view];
    this.problem = { ...this.problem, views };
    await withErrorScopes(this.device, 'inverse-render held-out view', () => {
      this.device.queue.writeBuffer(this.cameras, 0, packCameras(problemCameras(this.problem)));
      this.renderTargets();
    });
  }

  private writeParams(hyper: Hyper, targetSteps = 0): void {
    const p = this.problem;
    const params = packStruct(PARAMS, {
      resolution: p.resolution,
      size: p.size,
      trainViews: p.trainViews,
      steps: p.steps,
      renderViews: p.views.length,
      regularizer: hyper.regularizer,
      lossCapacity: MAX_ITERATIONS,
      batch: this.batchSize(hyper),
      background: BACKGROUND,
      lossWeight: 1 / (3 * this.batchSize(hyper)),
      learningRate: hyper.learningRate,
      regularizerWeight: hyper.regularizerWeight / this.voxels,
      seed: p.seed,
      targetSteps,
    });
    this.device.queue.writeBuffer(this.uniform, 0, params);
  }

  /** Rays per iteration: the requested batch, at most every training pixel. */
  private batchSize(hyper: Hyper): number {
    return effectiveBatch(hyper, this.trainPixels);
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
      'inverse-render.read',
      readBytes,
      GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
    );
    // Wall time from before the submit: popping the error scopes may already wait for the GPU.
    const start = performance.now();
    try {
      await withErrorScopes(this.device, 'inverse-render iterations', () => {
        this.writeParams(hyper);
        const encoder = this.device.createCommandEncoder();
        const pass = encoder.beginComputePass(timer.passDescriptor());
        for (let k = 0; k < iterations; k++) {
          this.dispatch(pass, 'lossGradient', this.batchSize(hyper));
          if (hyper.regularizer !== 0 && hyper.regularizerWeight !== 0)
            this.dispatch(pass, 'regularize', this.voxels);
          this.dispatch(pass, 'adam', this.voxels);
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

  /** The target images of every view (3 floats per pixel, views in order). */
  async readTargets(): Promise<Float32Array> {
    this.submitExactTargets();
    return new Float32Array(await this.read(this.targets, 12 * this.allPixels));
  }

  /** Renders the current grid from every view (training, then held-out) and reads it back. */
  async render(): Promise<{ image: Float32Array; gpuMs: number | null }> {
    return gpuCore(this.device)
      .lease()
      .run(async (lease) => {
        const timer = lease.timer();
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

  /** The current raw parameters, 4 per voxel. */
  async readField(): Promise<Float32Array> {
    return new Float32Array(await this.read(this.field, 16 * this.voxels));
  }

  /**
   * For the tests: ∂L/∂θ at the current parameters (data term, plus the regularizer
   * of `hyper`) and the data loss, without updating anything. The gradient buffer and
   * the loss slot are cleared again afterwards.
   */
  async lossAndGradient(hyper: Hyper): Promise<{ loss: number; gradient: Float32Array }> {
    this.writeParams(hyper);
    const encoder = this.device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    this.dispatch(pass, 'lossGradient', this.batchSize(hyper));
    if (hyper.regularizer !== 0 && hyper.regularizerWeight !== 0)
      this.dispatch(pass, 'regularize', this.voxels);
    pass.end();
    this.device.queue.submit([encoder.finish()]);
    const gradient = new Float32Array(await this.read(this.gradient, 16 * this.voxels));
    const slot = 4 * (STATS_LOSS_OFFSET + this.iteration);
    const stats = new Float32Array(await this.read(this.stats, slot + 4));
    const clear = this.device.createCommandEncoder();
    clear.clearBuffer(this.gradient);
    clear.clearBuffer(this.stats, slot, 4);
    this.device.queue.submit([clear.finish()]);
    return { loss: stats[STATS_LOSS_OFFSET + this.iteration]!, gradient };
  }

  /** For the tests: replaces the raw parameters (4 per voxel). */
  writeField(values: Float32Array<ArrayBuffer>): void {
    this.device.queue.writeBuffer(this.field, 0, values);
  }

  destroy(): void {
    for (const buffer of this.buffers) buffer.destroy();
    this.previewTargets?.destroy();
    this.previewTargets = null;
  }
}
