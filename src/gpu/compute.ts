// A compute dispatch in one call: buffers in, one buffer out, with the GPU time
// from timestamp queries where the device has them and wall time otherwise.
// Pipelines are cached per device by source, as the WebGPU CTS does.
import { withErrorScopes } from './errors.ts';
import { GpuTimer } from './timing.ts';

export interface ComputeJob {
  /** Linked WGSL. Binding 0..n-1 of group 0 are `inputs`, binding n is the output. */
  code: string;
  entryPoint?: string;
  /** Read-only storage buffers (`var<storage, read>`), in binding order. */
  inputs: readonly Uint32Array[];
  /** Size of the read-write output buffer in 32-bit words. */
  outputWords: number;
  /** Number of workgroups in x, y, z. */
  workgroups: readonly [number, number?, number?];
  /** A uniform buffer bound after the output, if the kernel has one. */
  uniforms?: Uint32Array;
}

export interface ComputeResult {
  output: Uint32Array;
  /** GPU execution time in ms from timestamp queries, or null when unavailable. */
  gpuMs: number | null;
  /** Wall time from submit to results mapped, in ms. */
  wallMs: number;
}

const pipelineCache = new WeakMap<GPUDevice, Map<string, GPUComputePipeline>>();

function pipelineFor(device: GPUDevice, code: string, entryPoint: string): GPUComputePipeline {
  let perDevice = pipelineCache.get(device);
  if (!perDevice) {
    perDevice = new Map();
    pipelineCache.set(device, perDevice);
  }
  const key = `${entryPoint}\n${code}`;
  let pipeline = perDevice.get(key);
  if (!pipeline) {
    const module = device.createShaderModule({ code });
    pipeline = device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint } });
    perDevice.set(key, pipeline);
  }
  return pipeline;
}

/** Storage buffers must be at least 4 bytes and a multiple of 4. */
function byteSize(words: number): number {
  return Math.max(4, words * 4);
}

export async function runCompute(device: GPUDevice, job: ComputeJob): Promise<ComputeResult> {
  const entryPoint = job.entryPoint ?? 'main';
  const created: GPUBuffer[] = [];
  const track = (buffer: GPUBuffer): GPUBuffer => {
    created.push(buffer);
    return buffer;
  };
  const timer = new GpuTimer(device);
  try {
    const readBack = await withErrorScopes(device, `compute "${entryPoint}"`, () => {
      const pipeline = pipelineFor(device, job.code, entryPoint);
      const entries: GPUBindGroupEntry[] = job.inputs.map((data, binding) => {
        const buffer = track(
          device.createBuffer({
            size: byteSize(data.length),
            usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST,
          }),
        );
        if (data.length > 0)
          device.queue.writeBuffer(buffer, 0, data.buffer, data.byteOffset, data.byteLength);
        return { binding, resource: { buffer } };
      });
      const outputSize = byteSize(job.outputWords);
      const output = track(
        device.createBuffer({
          size: outputSize,
          usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC,
        }),
      );
      entries.push({ binding: job.inputs.length, resource: { buffer: output } });
      if (job.uniforms) {
        const uniform = track(
          device.createBuffer({
            size: Math.ceil(job.uniforms.byteLength / 16) * 16 || 16,
            usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
          }),
        );
        device.queue.writeBuffer(
          uniform,
          0,
          job.uniforms.buffer,
          job.uniforms.byteOffset,
          job.uniforms.byteLength,
        );
        entries.push({ binding: job.inputs.length + 1, resource: { buffer: uniform } });
      }
      const readBack = track(
        device.createBuffer({
          size: outputSize,
          usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
        }),
      );
      const bindGroup = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries });
      const encoder = device.createCommandEncoder();
      const pass = encoder.beginComputePass(timer.passDescriptor());
      pass.setPipeline(pipeline);
      pass.setBindGroup(0, bindGroup);
      const [x, y = 1, z = 1] = job.workgroups;
      pass.dispatchWorkgroups(x, y, z);
      pass.end();
      timer.resolve(encoder);
      encoder.copyBufferToBuffer(output, 0, readBack, 0, outputSize);
      device.queue.submit([encoder.finish()]);
      return readBack;
    });
    const start = performance.now();
    await readBack.mapAsync(GPUMapMode.READ);
    const wallMs = performance.now() - start;
    const output = new Uint32Array(readBack.getMappedRange().slice(0, job.outputWords * 4));
    readBack.unmap();
    const gpuMs = await timer.read();
    return { output, gpuMs, wallMs };
  } finally {
    timer.destroy();
    for (const buffer of created) buffer.destroy();
  }
}
