// GPU backend of <sb-beer-law>: the kernel in shaders/kernels/beer-law.wesl,
// linked against the shared library, samples T(s) in a compute pass (timed with
// timestamp queries where available) and draws the beam in a render pass.
import { runCompute } from '../../gpu/compute.ts';
import { withErrorScopes } from '../../gpu/errors.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { SHADER_LIBRARY } from '../../gpu/shaderSources.ts';
import {
  CURVE_SAMPLES,
  depthsFor,
  viewRange,
  type BeerLawInputs,
  type BeerLawResult,
} from './model.ts';
import { LAYER_THICKNESS, LAYER_WEIGHTS, PROFILE_IDS } from './profiles.ts';

const KERNEL = 'kernels/beer-law.wesl';
/** Byte size of BeerLawParams in the kernel (12 scalars + array<vec4f, 4>). */
const PARAMS_BYTES = 112;

export function packParams(
  inputs: BeerLawInputs,
  width: number,
  height: number,
): Uint32Array<ArrayBuffer> {
  const buffer = new ArrayBuffer(PARAMS_BYTES);
  const f32 = new Float32Array(buffer);
  const u32 = new Uint32Array(buffer);
  const [viewMin, viewMax] = viewRange(inputs.thickness);
  f32[0] = inputs.sigmaT;
  f32[1] = inputs.sigmaS;
  f32[2] = inputs.thickness;
  f32[3] = inputs.split;
  u32[4] = PROFILE_IDS[inputs.profile];
  u32[5] = CURVE_SAMPLES;
  u32[6] = LAYER_WEIGHTS.length;
  f32[7] = LAYER_THICKNESS;
  f32[8] = viewMin;
  f32[9] = viewMax;
  f32[10] = width;
  f32[11] = height;
  LAYER_WEIGHTS.forEach((weight, i) => {
    f32[12 + i] = weight;
  });
  return u32;
}

export class BeerLawGpu {
  private context: GPUCanvasContext | null = null;
  private pipeline: GPURenderPipeline | null = null;
  private uniform: GPUBuffer | null = null;
  private bindGroup: GPUBindGroup | null = null;
  private readonly format: GPUTextureFormat;

  constructor(
    private readonly gpu: GpuContext,
    private readonly canvas: HTMLCanvasElement,
  ) {
    this.format = navigator.gpu.getPreferredCanvasFormat();
  }

  private async ensurePipeline(): Promise<void> {
    if (this.pipeline) return;
    const { device } = this.gpu;
    const code = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
    const context = this.canvas.getContext('webgpu');
    if (!context) throw new Error('the canvas has no WebGPU context');
    context.configure({ device, format: this.format, alphaMode: 'opaque' });
    await withErrorScopes(device, 'beer-law render pipeline', () => {
      const module = device.createShaderModule({ code });
      this.pipeline = device.createRenderPipeline({
        layout: 'auto',
        vertex: { module, entryPoint: 'fullScreenVertex' },
        fragment: { module, entryPoint: 'beamFragment', targets: [{ format: this.format }] },
        primitive: { topology: 'triangle-list' },
      });
      this.uniform = device.createBuffer({
        size: PARAMS_BYTES,
        usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
      });
      this.bindGroup = device.createBindGroup({
        layout: this.pipeline.getBindGroupLayout(0),
        entries: [{ binding: 1, resource: { buffer: this.uniform } }],
      });
    });
    this.context = context;
  }

  async computeCurve(inputs: BeerLawInputs): Promise<BeerLawResult> {
    const code = await linkLibraryKernel(SHADER_LIBRARY, KERNEL);
    const n = CURVE_SAMPLES;
    const { output, gpuMs, wallMs } = await runCompute(this.gpu.device, {
      code,
      entryPoint: 'sampleTransmittance',
      inputs: [],
      outputWords: 2 * n + 3,
      workgroups: [Math.ceil(n / 64)],
      uniforms: packParams(inputs, this.canvas.width, this.canvas.height),
    });
    const values = new Float32Array(output.buffer);
    return {
      depths: depthsFor(inputs.thickness, n),
      transmittance: Float64Array.from(values.subarray(0, n)),
      opticalDepth: Float64Array.from(values.subarray(n, 2 * n)),
      exit: values[2 * n] ?? NaN,
      beforeSplit: values[2 * n + 1] ?? NaN,
      afterSplit: values[2 * n + 2] ?? NaN,
      milliseconds: gpuMs ?? wallMs,
      timing: gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
    };
  }

  async draw(inputs: BeerLawInputs): Promise<void> {
    await this.ensurePipeline();
    const { device } = this.gpu;
    if (!this.context || !this.pipeline || !this.uniform || !this.bindGroup) return;
    const params = packParams(inputs, this.canvas.width, this.canvas.height);
    await withErrorScopes(device, 'beer-law draw', () => {
      device.queue.writeBuffer(this.uniform as GPUBuffer, 0, params);
      const encoder = device.createCommandEncoder();
      const pass = encoder.beginRenderPass({
        colorAttachments: [
          {
            view: (this.context as GPUCanvasContext).getCurrentTexture().createView(),
            loadOp: 'clear',
            storeOp: 'store',
            clearValue: { r: 0, g: 0, b: 0, a: 1 },
          },
        ],
      });
      pass.setPipeline(this.pipeline as GPURenderPipeline);
      pass.setBindGroup(0, this.bindGroup);
      pass.draw(3);
      pass.end();
      device.queue.submit([encoder.finish()]);
    });
  }

  destroy(): void {
    this.uniform?.destroy();
    this.context?.unconfigure();
  }
}
