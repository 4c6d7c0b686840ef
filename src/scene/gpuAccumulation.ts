// The GPU store of a progressive render: per-pixel moments (shaders/moments.wesl) in a
// storage buffer that stays on the device across passes. The scene renderer encodes
// the accumulate kernel right after each pass of the scene kernel (encodeAdd); readouts
// get whole-image statistics from a one-workgroup reduction (64 bytes read back; its
// kernel is compiled on the first readout);
// widgets draw the moments straight into a canvas (accumulationView.ts); only the
// command line and the tests read the whole image, once, with readImage. Every buffer
// is made when the store is made: adding a pass or reducing allocates nothing.
import { gpuCore } from '../gpu/core.ts';
import { withErrorScopes } from '../gpu/errors.ts';
import { readStruct, wordsOf, writeStruct } from '../gpu/layout.ts';
import { sceneAccumulateKernel, sceneStatisticsKernel } from '../gpu/layouts.generated.ts';
import { linkLibraryKernel, type KernelLibrary } from '../gpu/link.ts';
import {
  finishStatistics,
  ImageAccumulator,
  type Accumulation,
  type ImageStatistics,
} from './accumulation.ts';

/** The kernels' structs, laid out from their WGSL declarations. */
const ACCUMULATE_PARAMS = sceneAccumulateKernel.AccumulateParams;
const STATISTICS_PARAMS = sceneStatisticsKernel.StatisticsParams;
const STATISTICS = sceneStatisticsKernel.Statistics;
/** Bytes per pixel of the moments (struct PixelMoments: mean, lookups, m2, capped). */
export const MOMENT_BYTES_PER_PIXEL = sceneAccumulateKernel.PixelMoments.size;
/** Bytes of struct Statistics in scene-statistics.wesl, read back per reduction. */
export const STATISTICS_BYTES = STATISTICS.size;
const ACCUMULATE_KERNEL = 'kernels/scene-accumulate.wesl';
const STATISTICS_KERNEL = 'kernels/scene-statistics.wesl';
const ACCUMULATE_WORKGROUP = 64;

/** The accumulate kernel, which every pass needs. */
interface Kernels {
  accumulateLayout: GPUBindGroupLayout;
  accumulate: GPUComputePipeline;
}

/** The reduction, which only readouts need (statistics()). */
interface StatisticsKernel {
  layout: GPUBindGroupLayout;
  pipeline: GPUComputePipeline;
}

const kernels = new WeakMap<GPUDevice, Promise<Kernels>>();
const statisticsKernels = new WeakMap<GPUDevice, Promise<StatisticsKernel>>();

function storage(binding: number, type: GPUBufferBindingType): GPUBindGroupLayoutEntry {
  return { binding, visibility: GPUShaderStage.COMPUTE, buffer: { type } };
}

/** A per-device promise, forgotten when it rejects so that a later call tries again. */
function oncePerDevice<T>(
  cache: WeakMap<GPUDevice, Promise<T>>,
  device: GPUDevice,
  make: () => Promise<T>,
): Promise<T> {
  let made = cache.get(device);
  if (!made) {
    const perDevice = make();
    made = perDevice;
    cache.set(device, perDevice);
    perDevice.catch(() => {
      if (cache.get(device) === perDevice) cache.delete(device);
    });
  }
  return made;
}

/** The accumulate pipeline, compiled once per device. */
function kernelsFor(device: GPUDevice, library: KernelLibrary): Promise<Kernels> {
  return oncePerDevice(kernels, device, async () => {
    const code = await linkLibraryKernel(library, ACCUMULATE_KERNEL);
    return withErrorScopes(device, 'accumulate kernel', async () => {
      // Layouts and pipelines from the GPU core's cache.
      const core = gpuCore(device);
      const accumulateLayout = core.bindGroupLayout([
        storage(0, 'read-only-storage'),
        storage(1, 'storage'),
        storage(2, 'uniform'),
      ]);
      const accumulate = await core.computePipelineAsync({
        code,
        entryPoint: 'accumulatePass',
        layout: core.pipelineLayout([accumulateLayout]),
      });
      return { accumulateLayout, accumulate };
    });
  });
}

/**
 * The reduction pipeline, compiled once per device on the first readout rather than with
 * the store: Dawn on SwiftShader took 3.8–4.3 s to compile it on a loaded 2-core machine
 * (its 256-wide tree reduction over workgroup arrays), against 1.1–1.3 s for the scene
 * kernel of a single-scattering box and 0.1 s for the accumulate kernel, and the command
 * line never reads statistics (issue 19: `render` start-up). A widget's first readout
 * waits for it instead of its first frame.
 */
function statisticsKernelFor(device: GPUDevice, library: KernelLibrary): Promise<StatisticsKernel> {
  return oncePerDevice(statisticsKernels, device, async () => {
    const code = await linkLibraryKernel(library, STATISTICS_KERNEL);
    return withErrorScopes(device, 'statistics kernel', async () => {
      const core = gpuCore(device);
      const layout = core.bindGroupLayout([
        storage(0, 'read-only-storage'),
        storage(1, 'read-only-storage'),
        storage(2, 'read-only-storage'),
        storage(3, 'storage'),
        storage(4, 'uniform'),
      ]);
      const pipeline = await core.computePipelineAsync({
        code,
        entryPoint: 'reduceStatistics',
        layout: core.pipelineLayout([layout]),
      });
      return { layout, pipeline };
    });
  });
}

export class GpuAccumulation implements Accumulation {
  samples = 0;
  /** The moments: read by the display pass (accumulationView.ts) and the reduction. */
  readonly moments: GPUBuffer;
  private readonly mask: GPUBuffer;
  private readonly statisticsBuffer: GPUBuffer;
  private readonly statisticsReadBack: GPUBuffer;
  private readonly statisticsParams: GPUBuffer;
  private readonly accumulateParams: GPUBuffer;
  private readonly accumulateParamWords = wordsOf(new ArrayBuffer(ACCUMULATE_PARAMS.size));
  private readonly statisticsParamWords = wordsOf(new ArrayBuffer(STATISTICS_PARAMS.size));
  /** Reduction bind groups per reference buffer (the image itself when there is none). */
  private readonly statisticsGroups = new Map<GPUBuffer, GPUBindGroup>();
  private accumulateGroup: { passOutput: GPUBuffer; group: GPUBindGroup } | null = null;
  /** Reductions share one read-back buffer: each waits for the one before. */
  private queue: Promise<unknown> = Promise.resolve();
  /** Whether a mask was set (without one, maskedLuminance is NaN). */
  private maskSet = false;
  private gone = false;

  private constructor(
    /** The device the moments live on. */
    readonly device: GPUDevice,
    private readonly kernels: Kernels,
    private readonly library: KernelLibrary,
    readonly width: number,
    readonly height: number,
    moments: GPUBuffer,
  ) {
    const pixels = width * height;
    this.moments = moments;
    this.mask = device.createBuffer({
      size: 4 * pixels,
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST,
    });
    this.statisticsBuffer = device.createBuffer({
      size: STATISTICS_BYTES,
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC,
    });
    this.statisticsReadBack = device.createBuffer({
      size: STATISTICS_BYTES,
      usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
    });
    this.statisticsParams = device.createBuffer({
      size: STATISTICS_PARAMS.size,
      usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
    });
    this.accumulateParams = device.createBuffer({
      size: ACCUMULATE_PARAMS.size,
      usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
    });
  }

  /**
   * Compiles the accumulate kernel without making a store (cached per device), so that a
   * caller can compile it while it compiles the scene kernel.
   */
  static async prepare(device: GPUDevice, library: KernelLibrary): Promise<void> {
    await kernelsFor(device, library);
  }

  /** An empty store of width × height pixels (its kernel compiled once per device). */
  static async create(
    device: GPUDevice,
    library: KernelLibrary,
    width: number,
    height: number,
  ): Promise<GpuAccumulation> {
    const compiled = await kernelsFor(device, library);
    return withErrorScopes(device, 'accumulation buffers', () => {
      const moments = device.createBuffer({
        size: MOMENT_BYTES_PER_PIXEL * width * height,
        usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST,
      });
      return new GpuAccumulation(device, compiled, library, width, height, moments);
    });
  }

  /**
   * Encodes, into the caller's compute pass, the addition of a pass of the scene kernel
   * (`passOutput`, PASS_WORDS_PER_PIXEL words per pixel, over `samples` samples) to the
   * moments; the sample count advances now, in encoding order.
   */
  encodeAdd(pass: GPUComputePassEncoder, passOutput: GPUBuffer, samples: number): void {
    if (samples <= 0) return;
    const pixels = this.width * this.height;
    if (this.accumulateGroup?.passOutput !== passOutput)
      this.accumulateGroup = {
        passOutput,
        group: this.device.createBindGroup({
          layout: this.kernels.accumulateLayout,
          entries: [
            { binding: 0, resource: { buffer: passOutput } },
            { binding: 1, resource: { buffer: this.moments } },
            { binding: 2, resource: { buffer: this.accumulateParams } },
          ],
        }),
      };
    const words = this.accumulateParamWords;
    const params = { pixels, samplesBefore: this.samples, samplesInPass: samples };
    writeStruct(ACCUMULATE_PARAMS, params, words);
    this.device.queue.writeBuffer(this.accumulateParams, 0, words.u32);
    pass.setPipeline(this.kernels.accumulate);
    pass.setBindGroup(0, this.accumulateGroup.group);
    pass.dispatchWorkgroups(Math.ceil(pixels / ACCUMULATE_WORKGROUP));
    this.samples += samples;
  }

  setMask(mask: Uint8Array | null): void {
    const pixels = this.width * this.height;
    if (mask && mask.length !== pixels) throw new Error('the mask has another size');
    const weights = new Float32Array(pixels);
    if (mask) for (let i = 0; i < pixels; i++) weights[i] = mask[i] ? 1 : 0;
    this.maskSet = mask !== null;
    this.device.queue.writeBuffer(this.mask, 0, weights);
  }

  /** True once destroy() was called (a view must not draw it any more). */
  get destroyed(): boolean {
    return this.gone;
  }

  statistics(reference?: Accumulation): Promise<ImageStatistics> {
    if (this.gone) return Promise.reject(new Error('the accumulation was destroyed'));
    if (reference !== undefined && !(reference instanceof GpuAccumulation))
      return Promise.reject(new Error('a GPU accumulation compares only with a GPU one'));
    if (reference && reference.width * reference.height !== this.width * this.height)
      return Promise.reject(new Error('the reference has another size'));
    const run = this.queue.then(() => this.reduce(reference));
    this.queue = run.catch(() => undefined);
    return run;
  }

  private async reduce(reference: GpuAccumulation | undefined): Promise<ImageStatistics> {
    const { device } = this;
    const kernel = await statisticsKernelFor(device, this.library);
    // The first readout waits for the compiler; the store may be gone by then.
    if (this.gone) throw new Error('the accumulation was destroyed');
    const samples = this.samples;
    const other = reference ?? this;
    let group = this.statisticsGroups.get(other.moments);
    if (!group) {
      group = device.createBindGroup({
        layout: kernel.layout,
        entries: [
          { binding: 0, resource: { buffer: this.moments } },
          { binding: 1, resource: { buffer: other.moments } },
          { binding: 2, resource: { buffer: this.mask } },
          { binding: 3, resource: { buffer: this.statisticsBuffer } },
          { binding: 4, resource: { buffer: this.statisticsParams } },
        ],
      });
      this.statisticsGroups.set(other.moments, group);
    }
    const params = this.statisticsParamWords;
    const pixels = this.width * this.height;
    writeStruct(STATISTICS_PARAMS, { pixels, samples, referenceSamples: other.samples }, params);
    device.queue.writeBuffer(this.statisticsParams, 0, params.u32);
    const encoder = device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    pass.setPipeline(kernel.pipeline);
    pass.setBindGroup(0, group);
    pass.dispatchWorkgroups(1);
    pass.end();
    encoder.copyBufferToBuffer(
      this.statisticsBuffer,
      0,
      this.statisticsReadBack,
      0,
      STATISTICS_BYTES,
    );
    device.queue.submit([encoder.finish()]);
    await this.statisticsReadBack.mapAsync(GPUMapMode.READ);
    const range = this.statisticsReadBack.getMappedRange();
    const s = readStruct(STATISTICS, wordsOf(range.slice(0)));
    this.statisticsReadBack.unmap();
    const wide = ([low, high]: [number, number]): number => high * 2 ** 32 + low;
    return finishStatistics(this.width * this.height, samples, {
      radiance: s.radiance,
      standardError: s.standardError,
      standardErrorSq: s.standardErrorSq,
      maxPixelError: s.maxPixelError,
      maskedLuminance: s.maskedLuminance,
      maskCount: this.maskSet ? s.maskCount : 0,
      squaredDifference: s.squaredDifference,
      referenceNoise: s.referenceNoise,
      referenceRadiance: s.referenceRadiance,
      lookups: wide(s.lookups),
      capped: wide(s.capped),
      hasReference: reference !== undefined,
    });
  }

  /** A frozen copy on the GPU: one buffer copy, no read-back. */
  snapshot(): GpuAccumulation {
    if (this.gone) throw new Error('the accumulation was destroyed');
    const { device } = this;
    const moments = device.createBuffer({
      size: this.moments.size,
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST,
    });
    const copy = new GpuAccumulation(
      device,
      this.kernels,
      this.library,
      this.width,
      this.height,
      moments,
    );
    const encoder = device.createCommandEncoder();
    encoder.copyBufferToBuffer(this.moments, 0, moments, 0, this.moments.size);
    encoder.copyBufferToBuffer(this.mask, 0, copy.mask, 0, this.mask.size);
    device.queue.submit([encoder.finish()]);
    copy.samples = this.samples;
    copy.maskSet = this.maskSet;
    return copy;
  }

  /** Reads the whole image back (once, on demand): the command line and the tests. */
  readImage(): Promise<ImageAccumulator> {
    if (this.gone) return Promise.reject(new Error('the accumulation was destroyed'));
    const run = this.queue.then(() => this.readAll());
    this.queue = run.catch(() => undefined);
    return run;
  }

  private async readAll(): Promise<ImageAccumulator> {
    const { device } = this;
    const readBack = device.createBuffer({
      size: this.moments.size,
      usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
    });
    try {
      const samples = this.samples;
      const encoder = device.createCommandEncoder();
      encoder.copyBufferToBuffer(this.moments, 0, readBack, 0, this.moments.size);
      device.queue.submit([encoder.finish()]);
      await readBack.mapAsync(GPUMapMode.READ);
      const bytes = readBack.getMappedRange().slice(0);
      const f = new Float32Array(bytes);
      const u = new Uint32Array(bytes);
      const pixels = this.width * this.height;
      const mean = new Float64Array(3 * pixels);
      const m2 = new Float64Array(3 * pixels);
      let lookups = 0;
      let capped = 0;
      for (let i = 0; i < pixels; i++) {
        const o = 8 * i;
        for (let c = 0; c < 3; c++) {
          mean[3 * i + c] = samples > 0 ? f[o + c]! : 0;
          m2[3 * i + c] = samples > 0 ? f[o + 4 + c]! : 0;
        }
        lookups += samples > 0 ? u[o + 3]! : 0;
        capped += samples > 0 ? u[o + 7]! : 0;
      }
      return ImageAccumulator.fromMoments(
        this.width,
        this.height,
        { samples, mean, m2 },
        lookups,
        capped,
      );
    } finally {
      readBack.destroy();
    }
  }

  /** The accumulate kernel overwrites the moments when the count before a pass is 0. */
  reset(): void {
    this.samples = 0;
  }

  /** Frees the buffers once the reductions and read-backs already asked for are done. */
  destroy(): void {
    if (this.gone) return;
    this.gone = true;
    void this.queue.then(() => this.free());
  }

  private free(): void {
    for (const buffer of [
      this.moments,
      this.mask,
      this.statisticsBuffer,
      this.statisticsReadBack,
      this.statisticsParams,
      this.accumulateParams,
    ])
      buffer.destroy();
    this.statisticsGroups.clear();
  }
}
