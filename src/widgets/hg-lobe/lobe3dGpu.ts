// GPU backend of the 3D lobe of <sb-hg-lobe>: the render pipelines of
// shaders/kernels/hg-lobe-3d.wesl (the lobe evaluated by the library in the vertex
// shader, the beam arrow, the comparison lobe's wireframe and the faint "x-ray"
// passes for what the lobe hides), drawn with a depth buffer and 4× multisampling
// into a canvas that follows its CSS size and the device pixel ratio.
import { gpuCore } from '../../gpu/core.ts';
import { withErrorScopes } from '../../gpu/errors.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import { ARROW_VERTEX_COUNT, LOBE_VERTEX_COUNT, LOBE_VIEW, WIRE_VERTEX_COUNT } from './lobe3d.ts';
import { keepForPrint } from '../base/print.ts';

export const LOBE_3D_KERNEL = 'kernels/hg-lobe-3d.wesl';
export const LOBE_3D_SAMPLES = 4;
export const LOBE_3D_DEPTH_FORMAT: GPUTextureFormat = 'depth24plus';
/** The canvas's background, display-encoded: the polar plot's (0.015, 0.02, 0.035) at gamma 2.2. */
export const LOBE_3D_BACKGROUND: GPUColorDict = { r: 0.148, g: 0.169, b: 0.218, a: 1 };

/** Where one frame goes: a multisampled colour and depth target and the single-sample resolve target. */
export interface LobeTarget {
  color: GPUTextureView;
  resolve: GPUTextureView;
  depth: GPUTextureView;
}

const BLEND: GPUBlendState = {
  color: { srcFactor: 'src-alpha', dstFactor: 'one-minus-src-alpha', operation: 'add' },
  alpha: { srcFactor: 'one', dstFactor: 'one-minus-src-alpha', operation: 'add' },
};

interface PipelineSpec {
  vertex: string;
  fragment: string;
  topology: GPUPrimitiveTopology;
  /** Opaque surfaces write depth; lines and x-ray passes blend and test only. */
  pass: 'opaque' | 'visible' | 'hidden';
}

/** Draw order: opaque surfaces, then lines in front, then what the lobe hides, faint. */
const PIPELINES = {
  lobe: {
    vertex: 'lobeVertex',
    fragment: 'lobeFragment',
    topology: 'triangle-list',
    pass: 'opaque',
  },
  arrow: {
    vertex: 'arrowVertex',
    fragment: 'arrowFragment',
    topology: 'triangle-list',
    pass: 'opaque',
  },
  guide: {
    vertex: 'guideVertex',
    fragment: 'lineFragment',
    topology: 'line-list',
    pass: 'visible',
  },
  wire: { vertex: 'wireVertex', fragment: 'lineFragment', topology: 'line-list', pass: 'visible' },
  hiddenArrow: {
    vertex: 'arrowVertex',
    fragment: 'hiddenArrowFragment',
    topology: 'triangle-list',
    pass: 'hidden',
  },
  hiddenGuide: {
    vertex: 'guideVertex',
    fragment: 'hiddenLineFragment',
    topology: 'line-list',
    pass: 'hidden',
  },
  hiddenWire: {
    vertex: 'wireVertex',
    fragment: 'hiddenLineFragment',
    topology: 'line-list',
    pass: 'hidden',
  },
} as const satisfies Record<string, PipelineSpec>;

type PipelineName = keyof typeof PIPELINES;

/** The pipelines, the uniform buffer and its bind group; renders into any target of `format`. */
export class LobeRenderer {
  private constructor(
    private readonly device: GPUDevice,
    private readonly pipelines: Record<PipelineName, GPURenderPipeline>,
    private readonly uniform: GPUBuffer,
    private readonly bindGroup: GPUBindGroup,
  ) {}

  static async create(
    device: GPUDevice,
    code: string,
    format: GPUTextureFormat,
  ): Promise<LobeRenderer> {
    return withErrorScopes(device, 'hg-lobe 3D pipelines', () => {
      // Module, layouts and pipelines from the GPU core: both lobe views share them.
      const core = gpuCore(device);
      const bindGroupLayout = core.bindGroupLayout([
        {
          binding: 0,
          visibility: GPUShaderStage.VERTEX | GPUShaderStage.FRAGMENT,
          buffer: { type: 'uniform' },
        },
      ]);
      const layout = core.pipelineLayout([bindGroupLayout]);
      const make = (spec: PipelineSpec): GPURenderPipeline =>
        core.renderPipeline({
          code,
          label: 'hg-lobe-3d',
          layout,
          vertex: { entryPoint: spec.vertex },
          fragment: {
            entryPoint: spec.fragment,
            targets: [{ format, ...(spec.pass === 'opaque' ? {} : { blend: BLEND }) }],
          },
          primitive: { topology: spec.topology, cullMode: 'none' },
          depthStencil: {
            format: LOBE_3D_DEPTH_FORMAT,
            depthWriteEnabled: spec.pass === 'opaque',
            depthCompare:
              spec.pass === 'opaque' ? 'less' : spec.pass === 'visible' ? 'less-equal' : 'greater',
          },
          multisample: { count: LOBE_3D_SAMPLES },
        });
      const pipelines = Object.fromEntries(
        Object.entries(PIPELINES).map(([name, spec]) => [name, make(spec)]),
      ) as Record<PipelineName, GPURenderPipeline>;
      const uniform = device.createBuffer({
        size: LOBE_VIEW.size,
        usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
      });
      const bindGroup = device.createBindGroup({
        layout: bindGroupLayout,
        entries: [{ binding: 0, resource: { buffer: uniform } }],
      });
      return new LobeRenderer(device, pipelines, uniform, bindGroup);
    });
  }

  /** Records one frame: clear, lobe and arrow, lines in front, then the x-ray passes. */
  encode(
    encoder: GPUCommandEncoder,
    target: LobeTarget,
    view: Uint32Array<ArrayBuffer>,
    withCompare: boolean,
  ): void {
    this.device.queue.writeBuffer(this.uniform, 0, view.buffer, view.byteOffset, view.byteLength);
    const pass = encoder.beginRenderPass({
      colorAttachments: [
        {
          view: target.color,
          resolveTarget: target.resolve,
          loadOp: 'clear',
          storeOp: 'discard',
          clearValue: LOBE_3D_BACKGROUND,
        },
      ],
      depthStencilAttachment: {
        view: target.depth,
        depthLoadOp: 'clear',
        depthStoreOp: 'discard',
        depthClearValue: 1,
      },
    });
    pass.setBindGroup(0, this.bindGroup);
    const draw = (name: PipelineName, count: number): void => {
      pass.setPipeline(this.pipelines[name]);
      pass.draw(count);
    };
    draw('lobe', LOBE_VERTEX_COUNT);
    draw('arrow', ARROW_VERTEX_COUNT);
    draw('guide', 2);
    if (withCompare) draw('wire', WIRE_VERTEX_COUNT);
    draw('hiddenArrow', ARROW_VERTEX_COUNT);
    draw('hiddenGuide', 2);
    if (withCompare) draw('hiddenWire', WIRE_VERTEX_COUNT);
    pass.end();
  }

  destroy(): void {
    this.uniform.destroy();
  }
}

/** Multisampled colour and depth textures of one size, remade when the canvas is resized. */
interface Targets {
  width: number;
  height: number;
  color: GPUTexture;
  depth: GPUTexture;
}

/** The 3D lobe on a canvas: configures its WebGPU context and keeps the targets at its size. */
export class HgLobe3dGpu {
  private renderer: Promise<LobeRenderer> | null = null;
  private context: GPUCanvasContext | null = null;
  private targets: Targets | null = null;
  private readonly format = navigator.gpu.getPreferredCanvasFormat();
  /** The last frame, to draw it again for printing (widgets/base/print.ts). */
  private last: {
    renderer: LobeRenderer;
    view: Uint32Array<ArrayBuffer>;
    withCompare: boolean;
  } | null = null;

  constructor(
    private readonly gpu: GpuContext,
    private readonly canvas: HTMLCanvasElement,
  ) {
    keepForPrint(canvas, () => {
      if (this.last && this.context)
        this.encode(this.last.renderer, this.context, this.last.view, this.last.withCompare);
    });
  }

  private pipelines(): Promise<LobeRenderer> {
    this.renderer ??= linkLibraryKernel(STATIC_KERNELS, LOBE_3D_KERNEL).then((code) =>
      LobeRenderer.create(this.gpu.device, code, this.format),
    );
    this.renderer.catch(() => {
      this.renderer = null;
    });
    return this.renderer;
  }

  private targetsFor(width: number, height: number): Targets {
    if (this.targets && this.targets.width === width && this.targets.height === height)
      return this.targets;
    this.targets?.color.destroy();
    this.targets?.depth.destroy();
    const { device } = this.gpu;
    const texture = (format: GPUTextureFormat): GPUTexture =>
      device.createTexture({
        size: [width, height],
        format,
        sampleCount: LOBE_3D_SAMPLES,
        usage: GPUTextureUsage.RENDER_ATTACHMENT,
      });
    this.targets = {
      width,
      height,
      color: texture(this.format),
      depth: texture(LOBE_3D_DEPTH_FORMAT),
    };
    return this.targets;
  }

  /** Draws one frame at the canvas's current pixel size. */
  async draw(view: Uint32Array<ArrayBuffer>, withCompare: boolean): Promise<void> {
    const renderer = await this.pipelines();
    const { device } = this.gpu;
    if (!this.context) {
      const context = this.canvas.getContext('webgpu');
      if (!context) throw new Error('the 3D canvas has no WebGPU context');
      context.configure({ device, format: this.format, alphaMode: 'opaque' });
      this.context = context;
    }
    const context = this.context;
    this.last = { renderer, view: view.slice(), withCompare };
    await withErrorScopes(device, 'hg-lobe 3D draw', () =>
      this.encode(renderer, context, view, withCompare),
    );
  }

  /** Encodes and submits one frame (synchronous, so printing can copy it at once). */
  private encode(
    renderer: LobeRenderer,
    context: GPUCanvasContext,
    view: Uint32Array<ArrayBuffer>,
    withCompare: boolean,
  ): void {
    const targets = this.targetsFor(this.canvas.width, this.canvas.height);
    const encoder = this.gpu.device.createCommandEncoder();
    renderer.encode(
      encoder,
      {
        color: targets.color.createView(),
        resolve: context.getCurrentTexture().createView(),
        depth: targets.depth.createView(),
      },
      view,
      withCompare,
    );
    this.gpu.device.queue.submit([encoder.finish()]);
  }

  destroy(): void {
    this.last = null;
    void this.renderer?.then((renderer) => renderer.destroy());
    this.targets?.color.destroy();
    this.targets?.depth.destroy();
    this.context?.unconfigure();
  }
}
