// The GPU execution core: one context per device that every GPU user of the project
// goes through (widgets, the scene renderer, the CLI, the grader). It holds
//  - the one cache of shader modules and compute/render pipelines, keyed by code,
//    entry points, layout and fixed state (compiling is the slow part; the WebGPU CTS
//    and webgpu-samples cache the same way), bounded so that a page grading many
//    submissions does not grow without end;
//  - bind group and pipeline layouts, cached by their entries, so that explicit
//    layouts have stable identities (a pipeline's key names its layout);
//  - grow-only pools of buffers keyed by purpose and usage, and of timestamp timers,
//    leased for one job and given back after it, so that repeated dispatches allocate
//    nothing once warm;
//  - read-back through a pooled MAP_READ buffer.
// Error scopes live in errors.ts; what the core creates inside a scope is reported to
// it, so a failed compile names the compiler's messages and is not cached.
import { GpuError, noteCreated, withErrorScopes } from './errors.ts';
import { GpuTimer } from './timing.ts';

/** Most entries kept per cache before the least recently used is dropped. */
const CACHE_LIMIT = 192;
/** Most idle buffers kept per purpose; more are destroyed when given back. */
const IDLE_BUFFERS_PER_PURPOSE = 4;
const IDLE_TIMERS = 4;
/** Pooled buffers are at least this many bytes and grow in powers of two. */
const MIN_POOLED_BYTES = 256;

/** A Map that drops its least recently used entry past `limit`. */
class LruCache<V> {
  private readonly entries = new Map<string, V>();
  constructor(private readonly limit: number) {}

  get(key: string): V | undefined {
    const value = this.entries.get(key);
    if (value !== undefined) {
      this.entries.delete(key);
      this.entries.set(key, value);
    }
    return value;
  }

  set(key: string, value: V): void {
    this.entries.delete(key);
    this.entries.set(key, value);
    if (this.entries.size > this.limit) {
      const oldest = this.entries.keys().next().value;
      if (oldest !== undefined) this.entries.delete(oldest);
    }
  }

  delete(key: string, value?: V): void {
    if (value === undefined || this.entries.get(key) === value) this.entries.delete(key);
  }

  get size(): number {
    return this.entries.size;
  }
}

/** Stable small ids for GPU objects, so keys can name a layout or a buffer. */
const ids = new WeakMap<object, number>();
let nextId = 1;
function idOf(object: object): number {
  let id = ids.get(object);
  if (id === undefined) {
    id = nextId++;
    ids.set(object, id);
  }
  return id;
}

function layoutKey(layout: GPUPipelineLayout | 'auto' | undefined): string {
  return layout === undefined || layout === 'auto' ? 'auto' : `layout${idOf(layout)}`;
}

export interface ComputePipelineRequest {
  /** Linked WGSL. */
  code: string;
  entryPoint: string;
  /** 'auto' (default) or a layout from `pipelineLayout()`. */
  layout?: GPUPipelineLayout | 'auto';
  label?: string;
}

/** A render pipeline descriptor whose stages name entry points of one shader module. */
export interface RenderPipelineRequest {
  code: string;
  label?: string;
  layout?: GPUPipelineLayout | 'auto';
  vertex: { entryPoint: string; buffers?: GPUVertexBufferLayout[] };
  fragment?: { entryPoint: string; targets: GPUColorTargetState[] };
  primitive?: GPUPrimitiveState;
  depthStencil?: GPUDepthStencilState;
  multisample?: GPUMultisampleState;
}

/** How many of each thing the core has created (for tests and the benchmark). */
export interface CoreCounts {
  shaderModules: number;
  computePipelines: number;
  renderPipelines: number;
  pooledBuffers: number;
  timers: number;
}

interface PooledBuffer {
  buffer: GPUBuffer;
  key: string;
  /** Created for this lease (so still zero, as WebGPU initializes new buffers). */
  fresh: boolean;
}

/**
 * Buffers and timers held for one job. Give them back with `release()` when the job
 * succeeded; `discard()` destroys them instead (after a failure a buffer may still be
 * mapped, pending or in use by a dispatch that never ended).
 */
export class Lease {
  private readonly buffers: PooledBuffer[] = [];
  private readonly timers: GpuTimer[] = [];
  private done = false;

  constructor(private readonly core: GpuCore) {}

  /**
   * A buffer of at least `bytes` for `purpose` with `usage`; bind it with its `size`
   * (a pooled buffer may be larger, and arrayLength() sees the bound size). A reused
   * buffer holds the last job's data; with `zeroed`, its first `bytes` read as zero, as
   * in a new buffer (cleared by a submit queued now, so before later queue writes).
   */
  buffer(purpose: string, bytes: number, usage: GPUBufferUsageFlags, zeroed = false): GPUBuffer {
    const pooled = this.core.takeBuffer(
      purpose,
      bytes,
      zeroed ? usage | GPUBufferUsage.COPY_DST : usage,
    );
    this.buffers.push(pooled);
    if (zeroed && !pooled.fresh && bytes > 0) {
      const { device } = this.core;
      const encoder = device.createCommandEncoder();
      encoder.clearBuffer(pooled.buffer, 0, Math.ceil(bytes / 4) * 4);
      device.queue.submit([encoder.finish()]);
    }
    return pooled.buffer;
  }

  /** A buffer holding `data` (written through the queue), zero past it up to `bytes`. */
  upload(
    purpose: string,
    data: ArrayBufferView,
    usage: GPUBufferUsageFlags,
    bytes = data.byteLength,
  ): GPUBuffer {
    const size = Math.max(bytes, data.byteLength);
    const buffer = this.buffer(
      purpose,
      size,
      usage | GPUBufferUsage.COPY_DST,
      size > data.byteLength,
    );
    if (data.byteLength > 0)
      this.core.device.queue.writeBuffer(buffer, 0, data.buffer, data.byteOffset, data.byteLength);
    return buffer;
  }

  /** A timestamp timer (or one that reads null without timestamp queries). */
  timer(): GpuTimer {
    const timer = this.core.takeTimer();
    this.timers.push(timer);
    return timer;
  }

  release(): void {
    if (this.done) return;
    this.done = true;
    for (const pooled of this.buffers) this.core.giveBuffer(pooled);
    for (const timer of this.timers) this.core.giveTimer(timer);
  }

  discard(): void {
    if (this.done) return;
    this.done = true;
    for (const { buffer } of this.buffers) buffer.destroy();
    for (const timer of this.timers) timer.destroy();
  }

  /** Runs `job` with this lease: released when it resolves, discarded when it throws. */
  async run<T>(job: (lease: Lease) => Promise<T>): Promise<T> {
    try {
      const value = await job(this);
      this.release();
      return value;
    } catch (error) {
      this.discard();
      throw error;
    }
  }
}

export class GpuCore {
  private readonly modules = new LruCache<GPUShaderModule>(CACHE_LIMIT);
  private readonly computePipelines = new LruCache<GPUComputePipeline>(CACHE_LIMIT);
  private readonly asyncComputePipelines = new LruCache<Promise<GPUComputePipeline>>(CACHE_LIMIT);
  private readonly checkedComputePipelines = new LruCache<Promise<GPUComputePipeline>>(CACHE_LIMIT);
  private readonly renderPipelines = new LruCache<GPURenderPipeline>(CACHE_LIMIT);
  private readonly asyncRenderPipelines = new LruCache<Promise<GPURenderPipeline>>(CACHE_LIMIT);
  private readonly bindGroupLayouts = new Map<string, GPUBindGroupLayout>();
  private readonly pipelineLayouts = new Map<string, GPUPipelineLayout>();
  private readonly bindGroups = new WeakMap<
    object,
    { layouts: Map<number, GPUBindGroupLayout>; groups: LruCache<GPUBindGroup> }
  >();
  private readonly idleBuffers = new Map<string, GPUBuffer[]>();
  private readonly idleTimers: GpuTimer[] = [];
  private readonly counts: CoreCounts = {
    shaderModules: 0,
    computePipelines: 0,
    renderPipelines: 0,
    pooledBuffers: 0,
    timers: 0,
  };

  constructor(readonly device: GPUDevice) {}

  /** Whether passes can be timed with timestamp queries on this device. */
  get hasTimestamps(): boolean {
    return this.device.features.has('timestamp-query');
  }

  created(): Readonly<CoreCounts> {
    return { ...this.counts };
  }

  /** The shader module of `code` (cached by code). */
  shaderModule(code: string, label?: string): GPUShaderModule {
    let module = this.modules.get(code);
    if (!module) {
      const made = this.device.createShaderModule(label === undefined ? { code } : { label, code });
      module = made;
      this.counts.shaderModules++;
      this.modules.set(code, made);
      noteCreated(this.device, { module: made, onFailure: () => this.modules.delete(code, made) });
    }
    return module;
  }

  /** A compute pipeline, cached by code, entry point and layout. */
  computePipeline(request: ComputePipelineRequest): GPUComputePipeline {
    const key = `${request.entryPoint}\n${layoutKey(request.layout)}\n${request.code}`;
    let pipeline = this.computePipelines.get(key);
    if (!pipeline) {
      const made = this.device.createComputePipeline(this.computeDescriptor(request));
      pipeline = made;
      this.counts.computePipelines++;
      this.computePipelines.set(key, made);
      noteCreated(this.device, { onFailure: () => this.computePipelines.delete(key, made) });
    }
    return pipeline;
  }

  /**
   * The same, compiled without blocking (createComputePipelineAsync); a failed compile
   * rejects with the device's GPUPipelineError and is not cached.
   */
  computePipelineAsync(request: ComputePipelineRequest): Promise<GPUComputePipeline> {
    const key = `${request.entryPoint}\n${layoutKey(request.layout)}\n${request.code}`;
    let pipeline = this.asyncComputePipelines.get(key);
    if (!pipeline) {
      const made = this.device.createComputePipelineAsync(this.computeDescriptor(request));
      pipeline = made;
      this.counts.computePipelines++;
      this.asyncComputePipelines.set(key, made);
      const forget = (): void => this.asyncComputePipelines.delete(key, made);
      made.catch(forget);
      noteCreated(this.device, { onFailure: forget });
    }
    return pipeline;
  }

  /**
   * computePipelineAsync checked once in its own error scopes (runCompute): compiled off the
   * device's queue, where a synchronous pipeline compiles on the queue itself, so every later
   * submission (an input's first picture, on any widget of the page) waits for it. In Chrome
   * on SwiftShader translucent-render's path-traced reference compiled for about 0.5 s
   * right after the widget settled, and an input in that window waited for all of it
   * (bench/firstPictureProbe.ts). A shader that does not compile is a validation GpuError
   * with the compiler's messages, as inside a dispatch's scopes; later calls find the
   * resolved promise and add no round trip; a failure is forgotten, so a later call retries.
   */
  checkedComputePipeline(
    request: ComputePipelineRequest,
    what: string,
  ): Promise<GPUComputePipeline> {
    const key = `${request.entryPoint}\n${layoutKey(request.layout)}\n${request.code}`;
    let pipeline = this.checkedComputePipelines.get(key);
    if (!pipeline) {
      const made = withErrorScopes(this.device, what, () =>
        this.computePipelineAsync(request),
      ).catch((error: unknown) => {
        this.checkedComputePipelines.delete(key, made);
        throw pipelineFailure(error, what);
      });
      pipeline = made;
      this.checkedComputePipelines.set(key, made);
    }
    return pipeline;
  }

  private computeDescriptor(request: ComputePipelineRequest): GPUComputePipelineDescriptor {
    return {
      ...(request.label === undefined ? {} : { label: request.label }),
      layout: request.layout ?? 'auto',
      compute: {
        module: this.shaderModule(request.code, request.label),
        entryPoint: request.entryPoint,
      },
    };
  }

  private renderKey(request: RenderPipelineRequest): string {
    // The label names the pipeline in messages only; the first creator's label stays.
    const { code, layout, ...state } = request;
    return `${layoutKey(layout)}\n${JSON.stringify({ ...state, label: undefined })}\n${code}`;
  }

  private renderDescriptor(request: RenderPipelineRequest): GPURenderPipelineDescriptor {
    const { code, layout, label, ...state } = request;
    const module = this.shaderModule(code, label);
    return {
      ...(label === undefined ? {} : { label }),
      layout: layout ?? 'auto',
      vertex: { module, ...state.vertex },
      ...(state.fragment ? { fragment: { module, ...state.fragment } } : {}),
      ...(state.primitive ? { primitive: state.primitive } : {}),
      ...(state.depthStencil ? { depthStencil: state.depthStencil } : {}),
      ...(state.multisample ? { multisample: state.multisample } : {}),
    };
  }

  /** A render pipeline, cached by code, layout and every field of the descriptor. */
  renderPipeline(request: RenderPipelineRequest): GPURenderPipeline {
    const key = this.renderKey(request);
    let pipeline = this.renderPipelines.get(key);
    if (!pipeline) {
      const made = this.device.createRenderPipeline(this.renderDescriptor(request));
      pipeline = made;
      this.counts.renderPipelines++;
      this.renderPipelines.set(key, made);
      noteCreated(this.device, { onFailure: () => this.renderPipelines.delete(key, made) });
    }
    return pipeline;
  }

  /** The same, compiled without blocking; a failed compile rejects and is not cached. */
  renderPipelineAsync(request: RenderPipelineRequest): Promise<GPURenderPipeline> {
    const key = this.renderKey(request);
    let pipeline = this.asyncRenderPipelines.get(key);
    if (!pipeline) {
      const made = this.device.createRenderPipelineAsync(this.renderDescriptor(request));
      pipeline = made;
      this.counts.renderPipelines++;
      this.asyncRenderPipelines.set(key, made);
      const forget = (): void => this.asyncRenderPipelines.delete(key, made);
      made.catch(forget);
      noteCreated(this.device, { onFailure: forget });
    }
    return pipeline;
  }

  /** A bind group layout with these entries (one object per distinct list). */
  bindGroupLayout(entries: GPUBindGroupLayoutEntry[]): GPUBindGroupLayout {
    const key = JSON.stringify(entries);
    let layout = this.bindGroupLayouts.get(key);
    if (!layout) {
      layout = this.device.createBindGroupLayout({ entries });
      this.bindGroupLayouts.set(key, layout);
    }
    return layout;
  }

  /** A pipeline layout of these bind group layouts (one object per distinct list). */
  pipelineLayout(bindGroupLayouts: GPUBindGroupLayout[]): GPUPipelineLayout {
    const key = bindGroupLayouts.map(idOf).join(',');
    let layout = this.pipelineLayouts.get(key);
    if (!layout) {
      layout = this.device.createPipelineLayout({ bindGroupLayouts });
      this.pipelineLayouts.set(key, layout);
    }
    return layout;
  }

  /**
   * A bind group of sized buffer bindings, cached by the buffers and sizes: with
   * pooled buffers, repeated jobs bind the same group. `owner` is an explicit layout,
   * or a pipeline whose group `group` layout is used (read once per pipeline: an
   * 'auto' layout object is new at every getBindGroupLayout call).
   */
  bufferBindGroup(
    owner: GPUBindGroupLayout | GPUComputePipeline | GPURenderPipeline,
    entries: readonly { binding: number; buffer: GPUBuffer; size: number }[],
    group = 0,
  ): GPUBindGroup {
    let cached = this.bindGroups.get(owner);
    if (!cached) {
      cached = { layouts: new Map(), groups: new LruCache(16) };
      this.bindGroups.set(owner, cached);
    }
    let layout = 'getBindGroupLayout' in owner ? cached.layouts.get(group) : owner;
    if (!layout) {
      layout = (owner as GPUComputePipeline | GPURenderPipeline).getBindGroupLayout(group);
      cached.layouts.set(group, layout);
    }
    const key = `${group}|${entries.map((e) => `${e.binding}:${idOf(e.buffer)}:${e.size}`).join(',')}`;
    let bindGroup = cached.groups.get(key);
    if (!bindGroup) {
      bindGroup = this.device.createBindGroup({
        layout,
        entries: entries.map(({ binding, buffer, size }) => ({
          binding,
          resource: { buffer, offset: 0, size },
        })),
      });
      cached.groups.set(key, bindGroup);
    }
    return bindGroup;
  }

  /** Buffers and timers for one job; see Lease. */
  lease(): Lease {
    return new Lease(this);
  }

  /** @internal Lease's side of the buffer pool. */
  takeBuffer(purpose: string, bytes: number, usage: GPUBufferUsageFlags): PooledBuffer {
    const key = `${purpose}|${usage}`;
    const idle = this.idleBuffers.get(key);
    const fitting = idle?.findIndex((buffer) => buffer.size >= bytes) ?? -1;
    if (idle && fitting >= 0)
      return { buffer: idle.splice(fitting, 1)[0] as GPUBuffer, key, fresh: false };
    // Grow-only: an idle buffer too small for this job is replaced by a larger one.
    const smaller = idle?.shift();
    smaller?.destroy();
    let size = MIN_POOLED_BYTES;
    while (size < bytes) size *= 2;
    this.counts.pooledBuffers++;
    return { buffer: this.device.createBuffer({ label: purpose, size, usage }), key, fresh: true };
  }

  /** @internal */
  giveBuffer(pooled: PooledBuffer): void {
    let idle = this.idleBuffers.get(pooled.key);
    if (!idle) this.idleBuffers.set(pooled.key, (idle = []));
    if (idle.length >= IDLE_BUFFERS_PER_PURPOSE || pooled.buffer.mapState !== 'unmapped')
      pooled.buffer.destroy();
    else idle.push(pooled.buffer);
  }

  /** @internal */
  takeTimer(): GpuTimer {
    const timer = this.idleTimers.pop();
    if (timer) return timer;
    this.counts.timers++;
    return new GpuTimer(this.device);
  }

  /** @internal */
  giveTimer(timer: GpuTimer): void {
    if (this.idleTimers.length >= IDLE_TIMERS) timer.destroy();
    else this.idleTimers.push(timer);
  }

  /**
   * Copies `bytes` of `source` (a COPY_SRC buffer) from `offset` into a pooled
   * read-back buffer and returns them; submitted after any work already queued.
   */
  async read(source: GPUBuffer, bytes: number, offset = 0): Promise<ArrayBuffer> {
    // copyBufferToBuffer moves multiples of 4 bytes.
    const copyBytes = Math.ceil(bytes / 4) * 4;
    return this.lease().run(async (lease) => {
      const readBack = lease.buffer(
        'core.read',
        Math.max(4, copyBytes),
        GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
      );
      const encoder = this.device.createCommandEncoder();
      if (copyBytes > 0) encoder.copyBufferToBuffer(source, offset, readBack, 0, copyBytes);
      this.device.queue.submit([encoder.finish()]);
      return mapRange(readBack, bytes);
    });
  }

  /** Destroys every idle buffer and timer (the caches stay). */
  trim(): void {
    for (const idle of this.idleBuffers.values()) for (const buffer of idle) buffer.destroy();
    this.idleBuffers.clear();
    for (const timer of this.idleTimers) timer.destroy();
    this.idleTimers.length = 0;
  }
}

/** Maps a MAP_READ buffer, copies its first `bytes` out and unmaps it. */
export async function mapRange(
  buffer: GPUBuffer,
  bytes: number,
  wait: <T>(promise: Promise<T>) => Promise<T> = (promise) => promise,
): Promise<ArrayBuffer> {
  await wait(buffer.mapAsync(GPUMapMode.READ, 0, Math.ceil(Math.max(bytes, 4) / 4) * 4));
  const data = buffer.getMappedRange(0, Math.ceil(Math.max(bytes, 4) / 4) * 4).slice(0, bytes);
  buffer.unmap();
  return data;
}

const cores = new WeakMap<GPUDevice, GpuCore>();

/** The device's core (one per device; a new device after a loss gets a new one). */
export function gpuCore(device: GPUDevice): GpuCore {
  let core = cores.get(device);
  if (!core) {
    core = new GpuCore(device);
    cores.set(device, core);
  }
  return core;
}

/**
 * A rejected createComputePipelineAsync (a GPUPipelineError, reason "validation" or
 * "internal") as the GpuError an error scope would have given; other errors unchanged.
 */
function pipelineFailure(error: unknown, what: string): unknown {
  if (error instanceof GpuError || typeof error !== 'object' || error === null) return error;
  const reason = (error as { reason?: unknown }).reason;
  if (reason !== 'validation' && reason !== 'internal') return error;
  const message = (error as { message?: unknown }).message;
  return new GpuError(what, reason, typeof message === 'string' ? message : String(error));
}
