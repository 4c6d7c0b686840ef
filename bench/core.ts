// Benchmark: the GPU execution core's per-call overhead. runCompute on a tiny job
// (256 words in, 256 out, 4 workgroups) back to back, so the time is what the
// helper itself costs (buffers, bind group, timer, submit, read-back) rather than
// the kernel. Also counts the buffers and query sets the device creates per call.
import { runCompute } from '../src/gpu/compute.ts';
import { median, type BenchTable } from './table.ts';

const WORDS = 256;
const CODE = `
@group(0) @binding(0) var<storage, read> x: array<u32>;
@group(0) @binding(1) var<storage, read_write> y: array<u32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  if (id.x < ${WORDS}u) { y[id.x] = x[id.x] * 3u + 1u; }
}`;

/** Counts createBuffer and createQuerySet calls on the device while `body` runs. */
async function counting<T>(
  device: GPUDevice,
  body: () => Promise<T>,
): Promise<{ value: T; buffers: number; querySets: number }> {
  const createBuffer = device.createBuffer.bind(device);
  const createQuerySet = device.createQuerySet.bind(device);
  let buffers = 0;
  let querySets = 0;
  device.createBuffer = (descriptor) => (buffers++, createBuffer(descriptor));
  device.createQuerySet = (descriptor) => (querySets++, createQuerySet(descriptor));
  try {
    return { value: await body(), buffers, querySets };
  } finally {
    device.createBuffer = createBuffer;
    device.createQuerySet = createQuerySet;
  }
}

export async function benchCore(
  device: GPUDevice,
  options: { calls: number; repeats: number },
): Promise<BenchTable> {
  const input = new Uint32Array(WORDS).map((_, i) => i);
  const job = {
    code: CODE,
    inputs: [input],
    outputWords: WORDS,
    workgroups: [WORDS / 64] as [number],
  };
  // Compile once and check the answer before timing.
  const first = await runCompute(device, job);
  if (first.output[10] !== 31)
    throw new Error(`core bench kernel gave ${first.output[10]}, not 31`);
  const rates: number[] = [];
  let perCall = { buffers: 0, querySets: 0 };
  for (let r = 0; r < options.repeats; r++) {
    const counted = await counting(device, async () => {
      const start = performance.now();
      for (let k = 0; k < options.calls; k++) await runCompute(device, job);
      return performance.now() - start;
    });
    rates.push((1000 * options.calls) / counted.value);
    perCall = {
      buffers: counted.buffers / options.calls,
      querySets: counted.querySets / options.calls,
    };
  }
  return {
    title: 'GPU core: runCompute calls per second on a tiny job',
    notes: [
      `${options.calls} sequential runCompute calls of a ${WORDS}-word job per repeat, median of ${options.repeats} repeats.`,
      'Buffers and query sets: created by the device per call in the timed loop (the compile is outside it).',
      `Timer: ${device.features.has('timestamp-query') ? 'timestamp queries' : 'none (wall time only)'}.`,
    ],
    rows: [
      {
        'calls/s': median(rates),
        'ms/call': 1000 / median(rates),
        'buffers/call': perCall.buffers,
        'query sets/call': perCall.querySets,
      },
    ],
  };
}
