// Draws a GPU accumulation (gpuAccumulation.ts) into a widget's WebGPU canvas with one
// full-screen render pass (shaders/kernels/scene-display.wesl): the tone-mapped mean,
// or the per-pixel standard error in false colour. Nothing is read back; the canvas
// holds one pixel per image pixel (CSS scales it). Per draw: one 32-byte uniform write
// and one render pass; the bind group of an accumulation is made once.
import { gpuCore } from '../gpu/core.ts';
import { withErrorScopes } from '../gpu/errors.ts';
import { wordsOf, writeStruct } from '../gpu/layout.ts';
import { sceneDisplayKernel } from '../gpu/layouts.generated.ts';
import { linkLibraryKernel, type KernelLibrary } from '../gpu/link.ts';
import { keepForPrint } from '../widgets/base/print.ts';
import type { GpuAccumulation } from './gpuAccumulation.ts';

const DISPLAY_KERNEL = 'kernels/scene-display.wesl';
/** The display pass's uniform, laid out from its WGSL declaration. */
const DISPLAY_PARAMS = sceneDisplayKernel.DisplayParams;

export type AccumulationPicture =
  | {
      kind: 'radiance';
      /** EV: radiance × 2^exposure before the sRGB encoding. */ exposure: number;
    }
  | { kind: 'standard-error'; /** Standard error shown as the top colour. */ scale: number };

interface DisplayPipeline {
  layout: GPUBindGroupLayout;
  pipeline: GPURenderPipeline;
}

/**
 * The display pipeline for a canvas format, from the GPU core's cache (the link is
 * cached by link.ts, the layouts and the pipeline by the core).
 */
async function displayPipeline(
  device: GPUDevice,
  library: KernelLibrary,
  format: GPUTextureFormat,
): Promise<DisplayPipeline> {
  const code = await linkLibraryKernel(library, DISPLAY_KERNEL);
  return withErrorScopes(device, 'accumulation display pipeline', async () => {
    const core = gpuCore(device);
    const visibility = GPUShaderStage.FRAGMENT;
    const layout = core.bindGroupLayout([
      { binding: 0, visibility, buffer: { type: 'read-only-storage' } },
      { binding: 1, visibility, buffer: { type: 'uniform' } },
    ]);
    const pipeline = await core.renderPipelineAsync({
      code,
      layout: core.pipelineLayout([layout]),
      vertex: { entryPoint: 'displayVertex' },
      fragment: { entryPoint: 'displayFragment', targets: [{ format }] },
      primitive: { topology: 'triangle-list' },
    });
    return { layout, pipeline };
  });
}

const contextKinds = new WeakMap<HTMLCanvasElement, '2d' | 'webgpu'>();

/**
 * The canvas to draw on with a `kind` context: `canvas` itself, or, when it already
 * has the other kind (a canvas keeps its first context: after a fall back from WebGPU
 * to the CPU, or back), a fresh copy put in its place. Callers keep the returned one.
 */
export function canvasForContext(
  canvas: HTMLCanvasElement,
  kind: '2d' | 'webgpu',
): HTMLCanvasElement {
  const used = contextKinds.get(canvas);
  if (used === undefined || used === kind) {
    contextKinds.set(canvas, kind);
    return canvas;
  }
  const fresh = canvas.cloneNode(false) as HTMLCanvasElement;
  canvas.replaceWith(fresh);
  contextKinds.set(fresh, kind);
  return fresh;
}

export class AccumulationView {
  private readonly uniform: GPUBuffer;
  private readonly words = wordsOf(new ArrayBuffer(DISPLAY_PARAMS.size));
  private readonly groups = new WeakMap<GPUBuffer, GPUBindGroup>();
  private last: { accumulation: GpuAccumulation; picture: AccumulationPicture } | null = null;
  private destroyed = false;

  private constructor(
    private readonly device: GPUDevice,
    private readonly context: GPUCanvasContext,
    private readonly display: DisplayPipeline,
  ) {
    this.uniform = device.createBuffer({
      size: DISPLAY_PARAMS.size,
      usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
    });
  }

  /** Configures `canvas` for WebGPU on `device`; the canvas must not have a 2D context. */
  static async create(
    device: GPUDevice,
    library: KernelLibrary,
    canvas: HTMLCanvasElement,
  ): Promise<AccumulationView> {
    const context = canvas.getContext('webgpu');
    if (!context) throw new Error('the canvas has no WebGPU context');
    const format = navigator.gpu.getPreferredCanvasFormat();
    context.configure({ device, format, alphaMode: 'opaque' });
    const view = new AccumulationView(
      device,
      context,
      await displayPipeline(device, library, format),
    );
    keepForPrint(canvas, () => view.redrawLast());
    return view;
  }

  /** Draws `accumulation` (the canvas must be sized to its width × height). */
  draw(accumulation: GpuAccumulation, picture: AccumulationPicture): Promise<void> {
    if (accumulation.destroyed) return Promise.resolve();
    this.last = { accumulation, picture };
    return withErrorScopes(this.device, 'accumulation display', () =>
      this.encode(accumulation, picture),
    );
  }

  /** Draws the last picture again, synchronously (printing: widgets/base/print.ts). */
  redrawLast(): void {
    if (this.destroyed || !this.last || this.last.accumulation.destroyed) return;
    this.encode(this.last.accumulation, this.last.picture);
  }

  private encode(accumulation: GpuAccumulation, picture: AccumulationPicture): void {
    const { device } = this;
    let group = this.groups.get(accumulation.moments);
    if (!group) {
      group = device.createBindGroup({
        layout: this.display.layout,
        entries: [
          { binding: 0, resource: { buffer: accumulation.moments } },
          { binding: 1, resource: { buffer: this.uniform } },
        ],
      });
      this.groups.set(accumulation.moments, group);
    }
    const radiance = picture.kind === 'radiance';
    const params = {
      width: accumulation.width,
      height: accumulation.height,
      mode: radiance ? 0 : 1,
      scale: radiance ? 2 ** picture.exposure : 1,
      samples: accumulation.samples,
      errorScale: picture.kind === 'standard-error' ? picture.scale : 1,
    };
    writeStruct(DISPLAY_PARAMS, params, this.words);
    device.queue.writeBuffer(this.uniform, 0, this.words.u32);
    const encoder = device.createCommandEncoder();
    const pass = encoder.beginRenderPass({
      colorAttachments: [
        {
          view: this.context.getCurrentTexture().createView(),
          loadOp: 'clear',
          storeOp: 'store',
          clearValue: { r: 0, g: 0, b: 0, a: 1 },
        },
      ],
    });
    pass.setPipeline(this.display.pipeline);
    pass.setBindGroup(0, group);
    pass.draw(3);
    pass.end();
    device.queue.submit([encoder.finish()]);
  }

  destroy(): void {
    this.destroyed = true;
    this.last = null;
    this.uniform.destroy();
    this.context.unconfigure();
  }
}
