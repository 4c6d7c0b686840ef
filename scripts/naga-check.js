// The second WebGPU engine of the tests: wgpu with the naga shader compiler, as in
// Firefox, through Deno's navigator.gpu. Run by tests/support/denoGpu.ts as
//   deno run --allow-read --allow-env --unstable-webgpu scripts/naga-check.js
// with one JSON request on stdin; it answers one JSON object on stdout:
//   { engine: { adapter, fallback },
//     compile:  [{ name, messages: [{ type, line, column, message }],
//                  pipelines: [{ kind, entry, error }] }],
//     evaluate: [{ name, output: base64 u32 words | null, error }] }
// Requests: compile: [{ name, code, compute: [entry], render: [{ vertex, fragment, targets }] }]
//           evaluate: [{ name, code, entryPoint, inputs: [base64 u32 words], outputWords, workgroups }]
// Everything runs on one device, so a batch pays Deno's and the driver's start-up once.
// Plain JavaScript (not TypeScript) so that the Node project's type check, which has
// no Deno types, does not read it.
/* global Deno */

const decoder = new TextDecoder();

async function readStdin() {
  const chunks = [];
  for await (const chunk of Deno.stdin.readable) chunks.push(chunk);
  const bytes = new Uint8Array(chunks.reduce((n, c) => n + c.length, 0));
  let offset = 0;
  for (const chunk of chunks) {
    bytes.set(chunk, offset);
    offset += chunk.length;
  }
  return JSON.parse(decoder.decode(bytes));
}

function fromBase64(text) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return new Uint32Array(bytes.buffer, 0, bytes.length >> 2);
}

function toBase64(words) {
  const bytes = new Uint8Array(words.buffer, words.byteOffset, words.byteLength);
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000)
    binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}

/** Runs `make` inside a validation and an internal error scope; the first error's message or null. */
async function scoped(device, make) {
  device.pushErrorScope('validation');
  device.pushErrorScope('internal');
  let thrown = null;
  let value;
  try {
    value = make();
  } catch (error) {
    thrown = error instanceof Error ? error.message : String(error);
  }
  const internal = await device.popErrorScope();
  const validation = await device.popErrorScope();
  return { value, error: thrown ?? validation?.message ?? internal?.message ?? null };
}

async function compileOne(device, request) {
  const created = await scoped(device, () => device.createShaderModule({ code: request.code }));
  const module = created.value;
  const messages = [];
  if (module) {
    const info = await module.getCompilationInfo();
    for (const m of info.messages)
      messages.push({ type: m.type, line: m.lineNum, column: m.linePos, message: m.message });
  }
  if (created.error && !messages.some((m) => m.type === 'error'))
    messages.push({ type: 'error', line: 0, column: 0, message: created.error });
  const pipelines = [];
  if (module && !messages.some((m) => m.type === 'error')) {
    for (const entry of request.compute ?? []) {
      const { error } = await scoped(device, () =>
        device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint: entry } }),
      );
      pipelines.push({ kind: 'compute', entry, error });
    }
    for (const pair of request.render ?? []) {
      const { error } = await scoped(device, () =>
        device.createRenderPipeline({
          layout: 'auto',
          vertex: { module, entryPoint: pair.vertex },
          fragment: { module, entryPoint: pair.fragment, targets: pair.targets },
          primitive: { topology: 'triangle-list' },
        }),
      );
      pipelines.push({ kind: 'render', entry: `${pair.vertex} + ${pair.fragment}`, error });
    }
  }
  return { name: request.name, messages, pipelines };
}

async function evaluateOne(device, job) {
  const buffers = [];
  const track = (buffer) => {
    buffers.push(buffer);
    return buffer;
  };
  try {
    const made = await scoped(device, () => {
      const module = device.createShaderModule({ code: job.code });
      const pipeline = device.createComputePipeline({
        layout: 'auto',
        compute: { module, entryPoint: job.entryPoint },
      });
      const entries = job.inputs.map((text, binding) => {
        const data = fromBase64(text);
        const buffer = track(
          device.createBuffer({
            size: Math.max(4, data.byteLength),
            usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST,
          }),
        );
        if (data.length > 0) device.queue.writeBuffer(buffer, 0, data);
        return { binding, resource: { buffer } };
      });
      const size = Math.max(4, job.outputWords * 4);
      const output = track(
        device.createBuffer({ size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC }),
      );
      entries.push({ binding: job.inputs.length, resource: { buffer: output } });
      const readBack = track(
        device.createBuffer({ size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST }),
      );
      const bindGroup = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries });
      const encoder = device.createCommandEncoder();
      const pass = encoder.beginComputePass();
      pass.setPipeline(pipeline);
      pass.setBindGroup(0, bindGroup);
      const [x, y = 1, z = 1] = job.workgroups;
      pass.dispatchWorkgroups(x, y, z);
      pass.end();
      encoder.copyBufferToBuffer(output, 0, readBack, 0, size);
      device.queue.submit([encoder.finish()]);
      return readBack;
    });
    if (made.error) return { name: job.name, output: null, error: made.error };
    const readBack = made.value;
    await readBack.mapAsync(GPUMapMode.READ);
    const words = new Uint32Array(readBack.getMappedRange().slice(0, job.outputWords * 4));
    readBack.unmap();
    return { name: job.name, output: toBase64(words), error: null };
  } catch (error) {
    return {
      name: job.name,
      output: null,
      error: error instanceof Error ? error.message : String(error),
    };
  } finally {
    for (const buffer of buffers) buffer.destroy();
  }
}

async function main() {
  const request = await readStdin();
  if (!navigator.gpu) throw new Error('navigator.gpu is missing (run with --unstable-webgpu)');
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter)
    throw new Error(
      `no WebGPU adapter (VK_ICD_FILENAMES=${Deno.env.get('VK_ICD_FILENAMES') ?? 'unset'})`,
    );
  const device = await adapter.requestDevice();
  let lost = null;
  device.lost.then((info) => {
    lost = info.message;
  });
  const info = adapter.info ?? {};
  const engine = {
    adapter: [info.vendor, info.architecture, info.device, info.description]
      .filter(Boolean)
      .join(' '),
    fallback: Boolean(adapter.isFallbackAdapter ?? info.isFallbackAdapter),
  };
  const compile = [];
  for (const item of request.compile ?? []) compile.push(await compileOne(device, item));
  const evaluate = [];
  for (const job of request.evaluate ?? []) evaluate.push(await evaluateOne(device, job));
  const answer = JSON.stringify({ engine, lost, compile, evaluate });
  const bytes = new TextEncoder().encode(answer);
  // write() may take only part of a large buffer; loop until all of it is out.
  for (let offset = 0; offset < bytes.length;)
    offset += await Deno.stdout.write(bytes.subarray(offset));
  device.destroy();
}

try {
  await main();
} catch (error) {
  await Deno.stderr.write(
    new TextEncoder().encode(`naga-check: ${error instanceof Error ? error.message : error}\n`),
  );
  Deno.exit(1);
}
