// A compute dispatch in one call: buffers in, one buffer out, with the GPU time
// from timestamp queries where the device has them and wall time otherwise. The
// pipeline comes from the device's GPU core (one cache for the project), and the
// buffers and the timer are leased from its pools, so repeated calls allocate
// nothing once warm.
import { gpuCore, mapRange, type Lease } from './core.ts';
import { withErrorScopes, type ScopeOptions } from './errors.ts';

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

/** A dispatch of a pipeline the caller already has (the grader compiles its own). */
export type PipelineJob = Omit<ComputeJob, 'code' | 'entryPoint'>;

export interface DispatchOptions extends ScopeOptions {
  /** Names the dispatch in error messages. */
  what: string;
  /** Time the pass with timestamp queries where available (default true). */
  timed?: boolean;
}

/** Storage buffers must be at least 4 bytes and a multiple of 4. */
function byteSize(words: number): number {
  return Math.max(4, words * 4);
}

export async function runCompute(device: GPUDevice, job: ComputeJob): Promise<ComputeResult> {
  const entryPoint = job.entryPoint ?? 'main';
  const what = `compute "${entryPoint}"`;
  // Compiled once per device off the queue, checked in its own error scopes (GpuCore).
  const pipeline = await gpuCore(device).checkedComputePipeline(
    { code: job.code, entryPoint },
    what,
  );
  return dispatch(device, () => pipeline, job, { what });
}

/**
 * Dispatches `pipeline` (layout 'auto' or one matching the bindings: inputs, output,
 * uniforms) once and reads the output back. Errors of the dispatch throw a GpuError
 * with their kind; `options.wait` wraps every wait on the device.
 */
export function runPipeline(
  device: GPUDevice,
  pipeline: GPUComputePipeline,
  job: PipelineJob,
  options: DispatchOptions,
): Promise<ComputeResult> {
  return dispatch(device, () => pipeline, job, options);
}

async function dispatch(
  device: GPUDevice,
  pipelineFor: () => GPUComputePipeline,
  job: PipelineJob,
  options: DispatchOptions,
): Promise<ComputeResult> {
  const core = gpuCore(device);
  return core.lease().run(async (lease: Lease) => {
    const timer = options.timed === false ? null : lease.timer();
    const outputSize = byteSize(job.outputWords);
    const readBack = await withErrorScopes(
      device,
      options.what,
      () => {
        const pipeline = pipelineFor();
        // Pooled buffers hold the previous job's data: every bound byte past the data
        // is cleared, so kernels see zeros as in new buffers (an output only partly
        // written, or accumulated into with atomics).
        const entries = job.inputs.map((data, binding) => {
          const size = byteSize(data.length);
          const upload = lease.upload(
            `compute.input${binding}`,
            data,
            GPUBufferUsage.STORAGE,
            size,
          );
          return { binding, buffer: upload, size };
        });
        // Cleared in the dispatch's own encoder (no extra submit).
        const output = lease.buffer(
          'compute.output',
          outputSize,
          GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST,
        );
        entries.push({ binding: job.inputs.length, buffer: output, size: outputSize });
        if (job.uniforms) {
          const size = Math.ceil(job.uniforms.byteLength / 16) * 16 || 16;
          const uniform = lease.upload(
            'compute.uniform',
            job.uniforms,
            GPUBufferUsage.UNIFORM,
            size,
          );
          entries.push({ binding: job.inputs.length + 1, buffer: uniform, size });
        }
        const readBack = lease.buffer(
          'compute.read',
          outputSize,
          GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
        );
        const bindGroup = core.bufferBindGroup(pipeline, entries);
        const encoder = device.createCommandEncoder();
        encoder.clearBuffer(output, 0, outputSize);
        const pass = encoder.beginComputePass(timer?.passDescriptor() ?? {});
        pass.setPipeline(pipeline);
        pass.setBindGroup(0, bindGroup);
        const [x, y = 1, z = 1] = job.workgroups;
        pass.dispatchWorkgroups(x, y, z);
        pass.end();
        timer?.resolve(encoder);
        encoder.copyBufferToBuffer(output, 0, readBack, 0, outputSize);
        device.queue.submit([encoder.finish()]);
        return readBack;
      },
      options,
    );
    const start = performance.now();
    const output = new Uint32Array(await mapRange(readBack, job.outputWords * 4, options.wait));
    const wallMs = performance.now() - start;
    const gpuMs = timer ? await timer.read() : null;
    return { output, gpuMs, wallMs };
  });
}
