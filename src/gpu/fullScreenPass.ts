// A full-screen render pass onto a canvas: one triangle, one uniform buffer,
// one fragment shader that computes every pixel. The widgets' pictures are all
// of this shape, so the canvas configuration, the pipeline and the error
// scopes live here once.
import { gpuCore } from './core.ts';
import type { GpuContext } from './device.ts';
import { withErrorScopes } from './errors.ts';
import type { GpuTimer } from './timing.ts';
import { keepForPrint } from '../widgets/base/print.ts';

export interface FullScreenPassOptions {
  /** Names the pass in error messages, e.g. "beer-law". */
  label: string;
  /** Linked WGSL holding both entry points. */
  code: string;
  vertexEntry: string;
  fragmentEntry: string;
  /** Size of the uniform struct in bytes; bound at `uniformBinding` of group 0. */
  uniformBytes: number;
  uniformBinding?: number;
}

export class FullScreenPass {
  private readonly context: GPUCanvasContext;
  private readonly pipeline: GPURenderPipeline;
  private readonly uniform: GPUBuffer;
  private readonly bindGroup: GPUBindGroup;
  /** The last frame's uniforms, to draw it again for printing (widgets/base/print.ts). */
  private lastUniforms: Uint8Array<ArrayBuffer> | null = null;
  private destroyed = false;

  private constructor(
    private readonly gpu: GpuContext,
    private readonly label: string,
    parts: {
      context: GPUCanvasContext;
      pipeline: GPURenderPipeline;
      uniform: GPUBuffer;
      bindGroup: GPUBindGroup;
    },
  ) {
    this.context = parts.context;
    this.pipeline = parts.pipeline;
    this.uniform = parts.uniform;
    this.bindGroup = parts.bindGroup;
  }

  static async create(
    gpu: GpuContext,
    canvas: HTMLCanvasElement,
    options: FullScreenPassOptions,
  ): Promise<FullScreenPass> {
    const { device } = gpu;
    const context = canvas.getContext('webgpu');
    if (!context) throw new Error('the canvas has no WebGPU context');
    const format = navigator.gpu.getPreferredCanvasFormat();
    context.configure({ device, format, alphaMode: 'opaque' });
    const parts = await withErrorScopes(device, `${options.label} render pipeline`, () => {
      const pipeline = gpuCore(device).renderPipeline({
        code: options.code,
        label: options.label,
        vertex: { entryPoint: options.vertexEntry },
        fragment: { entryPoint: options.fragmentEntry, targets: [{ format }] },
        primitive: { topology: 'triangle-list' },
      });
      const uniform = device.createBuffer({
        size: Math.ceil(options.uniformBytes / 16) * 16,
        usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
      });
      const bindGroup = device.createBindGroup({
        layout: pipeline.getBindGroupLayout(0),
        entries: [{ binding: options.uniformBinding ?? 1, resource: { buffer: uniform } }],
      });
      return { context, pipeline, uniform, bindGroup };
    });
    const pass = new FullScreenPass(gpu, options.label, parts);
    keepForPrint(canvas, () => pass.redrawLast());
    return pass;
  }

  /**
   * Uploads the uniforms and draws the full-screen triangle into the canvas. With
   * `timing`, it draws the same picture in `passes` render passes (default 1) of one
   * submit and the timer spans them all (read it with `timer.read()`): timestamps are
   * quantized (100 µs in Chrome), so a fast picture is timed over several passes.
   */
  async draw(
    uniforms: ArrayBufferView<ArrayBuffer>,
    timing?: { timer: GpuTimer; passes?: number },
  ): Promise<void> {
    const passes = Math.max(1, Math.round(timing?.passes ?? 1));
    const { device } = this.gpu;
    this.lastUniforms = new Uint8Array(
      uniforms.buffer,
      uniforms.byteOffset,
      uniforms.byteLength,
    ).slice();
    await withErrorScopes(device, `${this.label} draw`, () => this.encode(passes, timing?.timer));
  }

  /**
   * Draws the last frame again, synchronously: a presented WebGPU canvas no longer
   * holds its picture, so printing re-draws it and copies the canvas in the same task.
   */
  redrawLast(): void {
    if (this.destroyed || !this.lastUniforms) return;
    this.encode(1);
  }

  /** Encodes and submits `passes` draws of the last uniforms (all synchronous). */
  private encode(passes: number, timer?: GpuTimer): void {
    const { device } = this.gpu;
    const uniforms = this.lastUniforms;
    if (uniforms)
      device.queue.writeBuffer(this.uniform, 0, uniforms.buffer, 0, uniforms.byteLength);
    const encoder = device.createCommandEncoder();
    const view = this.context.getCurrentTexture().createView();
    for (let k = 0; k < passes; k++) {
      const timestampWrites = timer?.renderPassTimestamps(k === 0, k === passes - 1);
      const pass = encoder.beginRenderPass({
        colorAttachments: [
          {
            view,
            loadOp: 'clear',
            storeOp: 'store',
            clearValue: { r: 0, g: 0, b: 0, a: 1 },
          },
        ],
        ...(timestampWrites ? { timestampWrites } : {}),
      });
      pass.setPipeline(this.pipeline);
      pass.setBindGroup(0, this.bindGroup);
      pass.draw(3);
      pass.end();
    }
    timer?.resolve(encoder);
    device.queue.submit([encoder.finish()]);
  }

  destroy(): void {
    this.destroyed = true;
    this.uniform.destroy();
    this.context.unconfigure();
  }
}
