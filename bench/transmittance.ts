// Benchmark: throughput of the library's transmittance functions on the GPU
// (one dispatch over N inputs, GPU timestamp or wall time) against the float64
// twin on the CPU, with the largest relative difference between the two.
import { linkKernel } from '../src/gpu/link.ts';
import { runCompute } from '../src/gpu/compute.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { opticalThicknessSine, transmittanceHomogeneous } from '../src/reference/transmittance.ts';
import { median, type BenchTable } from './table.ts';

interface Case {
  fn: string;
  args: number;
  wgslCall: string;
  twin: (a: Float32Array, i: number) => number;
}

const CASES: Case[] = [
  {
    fn: 'transmittanceHomogeneous',
    args: 2,
    wgslCall: 'transmittanceHomogeneous(x[2u * i], x[2u * i + 1u])',
    twin: (a, i) => transmittanceHomogeneous(a[2 * i] ?? 0, a[2 * i + 1] ?? 0),
  },
  {
    fn: 'opticalThicknessSine',
    args: 2,
    wgslCall: 'opticalThicknessSine(x[2u * i], 0.8, 3.0, 0.0, 0.0, x[2u * i + 1u])',
    twin: (a, i) => opticalThicknessSine(a[2 * i] ?? 0, 0.8, 3, 0, 0, a[2 * i + 1] ?? 0),
  },
];

export async function benchTransmittance(
  device: GPUDevice,
  options: { n: number; repeats: number },
): Promise<BenchTable> {
  const library = loadShaderLibrary(new URL('../shaders', import.meta.url).pathname);
  const rows: BenchTable['rows'] = [];
  for (const c of CASES) {
    const inputs = new Float32Array(c.args * options.n);
    for (let i = 0; i < inputs.length; i++) inputs[i] = ((i * 2654435761) % 1000003) / 100000;
    const code = await linkKernel(
      library,
      `import package::transmittance::${c.fn};
@group(0) @binding(0) var<storage, read> x: array<f32>;
@group(0) @binding(1) var<storage, read_write> y: array<f32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= ${options.n}u) { return; }
  y[i] = ${c.wgslCall};
}`,
    );
    const gpuTimes: number[] = [];
    let gpuOutput: Float32Array = new Float32Array(0);
    let timing = 'timestamp';
    for (let r = 0; r < options.repeats; r++) {
      const result = await runCompute(device, {
        code,
        inputs: [new Uint32Array(inputs.buffer)],
        outputWords: options.n,
        workgroups: [Math.ceil(options.n / 64)],
      });
      if (result.gpuMs === null) timing = 'wall';
      gpuTimes.push(result.gpuMs ?? result.wallMs);
      gpuOutput = new Float32Array(result.output.buffer);
    }
    const cpuTimes: number[] = [];
    const twin = new Float64Array(options.n);
    for (let r = 0; r < options.repeats; r++) {
      const start = performance.now();
      for (let i = 0; i < options.n; i++) twin[i] = c.twin(inputs, i);
      cpuTimes.push(performance.now() - start);
    }
    let worst = 0;
    for (let i = 0; i < options.n; i++) {
      const reference = twin[i] ?? 0;
      const difference = Math.abs((gpuOutput[i] ?? 0) - reference);
      if (reference > 1e-30) worst = Math.max(worst, difference / Math.abs(reference));
    }
    const gpuMs = median(gpuTimes);
    const cpuMs = median(cpuTimes);
    rows.push({
      function: c.fn,
      evaluations: options.n,
      [`gpu ms (${timing})`]: gpuMs,
      'cpu float64 ms': cpuMs,
      'gpu Mevals/s': options.n / gpuMs / 1e3,
      'cpu Mevals/s': options.n / cpuMs / 1e3,
      'cpu/gpu time': cpuMs / gpuMs,
      'max rel. difference (T > 1e-30)': worst,
    });
  }
  return {
    title: 'Transmittance functions: GPU (f32) vs float64 twin (CPU)',
    notes: [`Median of ${options.repeats} runs each; the same inputs on both sides.`],
    rows,
  };
}
