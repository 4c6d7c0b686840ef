// The GPU execution core (src/gpu/core.ts) on Dawn: one pipeline per code and entry
// point, pooled buffers reused across runCompute calls (nothing created once warm),
// bindings sized to the job even when a pooled buffer is larger, concurrent calls
// kept apart, and a shader that does not compile reported once with the compiler's
// line numbers and not cached.
import { afterAll, describe, expect, it } from 'vitest';
import { runCompute } from '../../src/gpu/compute.ts';
import { gpuCore } from '../../src/gpu/core.ts';
import { GpuError, withErrorScopes } from '../../src/gpu/errors.ts';
import { prefixedDeclarations } from '../../src/gpu/libraryDeclarations.ts';
import { pcgHash } from '../../src/reference/rng.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

const AFFINE = `
@group(0) @binding(0) var<storage, read> x: array<u32>;
@group(0) @binding(1) var<storage, read_write> y: array<u32>;
@group(0) @binding(2) var<uniform> p: vec4u;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  // arrayLength sees the bound size, which must be the job's, not the pooled buffer's.
  if (id.x < arrayLength(&y)) { y[id.x] = x[id.x] * p.x + p.y + arrayLength(&x) * 1000u; }
}`;

function affineJob(words: number, scale: number, offset: number) {
  return {
    code: AFFINE,
    inputs: [new Uint32Array(words).map((_, i) => i)],
    outputWords: words,
    workgroups: [Math.ceil(words / 64)] as [number],
    uniforms: new Uint32Array([scale, offset, 0, 0]),
  };
}

function expected(words: number, scale: number, offset: number): number[] {
  return Array.from({ length: words }, (_, i) => i * scale + offset + words * 1000);
}

describe('GPU core', () => {
  it('reuses one pipeline and pooled buffers across runCompute calls', async () => {
    const device = await nodeDevice();
    const core = gpuCore(device);
    // Warm up at the largest size, then run smaller jobs: no new buffers, one pipeline.
    await runCompute(device, affineJob(200, 1, 0));
    const warm = core.created();
    for (const [words, scale, offset] of [
      [200, 3, 7],
      [17, 5, 1],
      [64, 2, 9],
    ] as const) {
      const { output } = await runCompute(device, affineJob(words, scale, offset));
      expect([...output]).toEqual(expected(words, scale, offset));
    }
    const after = core.created();
    expect(after.pooledBuffers).toBe(warm.pooledBuffers);
    expect(after.timers).toBe(warm.timers);
    expect(after.computePipelines).toBe(warm.computePipelines);
    expect(after.shaderModules).toBe(warm.shaderModules);
  });

  it('gives every job a zero output, as a new buffer would be', async () => {
    const device = await nodeDevice();
    // A histogram by atomicAdd: a pooled output still holding the last job's counts
    // would double them.
    const code = `
@group(0) @binding(0) var<storage, read> x: array<u32>;
@group(0) @binding(1) var<storage, read_write> counts: array<atomic<u32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  if (id.x < arrayLength(&x)) { atomicAdd(&counts[x[id.x] % 4u], 1u); }
}`;
    const job = {
      code,
      inputs: [new Uint32Array(100).map((_, i) => i)],
      outputWords: 4,
      workgroups: [2] as [number],
    };
    for (let k = 0; k < 3; k++) {
      const { output } = await runCompute(device, job);
      expect([...output]).toEqual([25, 25, 25, 25]);
    }
  });

  it('keeps concurrent calls apart', async () => {
    const device = await nodeDevice();
    const jobs = Array.from({ length: 6 }, (_, k) => affineJob(50 + 10 * k, k + 1, 3 * k));
    const results = await Promise.all(jobs.map((job) => runCompute(device, job)));
    results.forEach(({ output }, k) => {
      expect([...output]).toEqual(expected(50 + 10 * k, k + 1, 3 * k));
    });
  });

  it('reads a buffer back through the pooled read-back buffer', async () => {
    const device = await nodeDevice();
    const source = device.createBuffer({
      size: 64,
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST,
    });
    device.queue.writeBuffer(
      source,
      0,
      new Uint32Array(16).map((_, i) => 100 + i),
    );
    const data = new Uint32Array(await gpuCore(device).read(source, 12, 8));
    expect([...data]).toEqual([102, 103, 104]);
    source.destroy();
  });

  it('reports a compile error once, with line numbers, and does not cache it', async () => {
    const device = await nodeDevice();
    const core = gpuCore(device);
    const broken = `
@group(0) @binding(0) var<storage, read_write> y: array<u32>;
@compute @workgroup_size(1)
fn main() {
  y[0] = undefinedName;
}`;
    const attempt = () =>
      withErrorScopes(device, 'broken kernel', () =>
        core.computePipeline({ code: broken, entryPoint: 'main' }),
      );
    const error = await attempt().catch((e: unknown) => e);
    expect(error).toBeInstanceOf(GpuError);
    const gpuError = error as GpuError;
    expect(gpuError.kind).toBe('validation');
    expect(gpuError.message).toMatch(/^broken kernel: /);
    const note = gpuError.compilation.find((n) => n.type === 'error');
    expect(note?.line).toBe(5);
    expect(note?.message).toMatch(/undefinedName/);
    // Not cached: the next attempt compiles again and fails again.
    const before = core.created().shaderModules;
    await expect(attempt()).rejects.toBeInstanceOf(GpuError);
    expect(core.created().shaderModules).toBe(before + 1);
  });

  it('runCompute compiles off the queue: a compile error once per attempt, with line numbers; a good kernel once', async () => {
    const device = await nodeDevice();
    const core = gpuCore(device);
    const job = (body: string) => ({
      code: `
@group(0) @binding(0) var<storage, read_write> y: array<u32>;
@compute @workgroup_size(1)
fn main() {
  ${body}
}`,
      inputs: [],
      outputWords: 1,
      workgroups: [1] as [number],
    });
    const error = await runCompute(device, job('y[0] = undefinedName;')).catch((e: unknown) => e);
    expect(error).toBeInstanceOf(GpuError);
    const gpuError = error as GpuError;
    expect(gpuError.kind).toBe('validation');
    expect(gpuError.message).toMatch(/^compute "main": /);
    expect(gpuError.compilation.find((n) => n.type === 'error')?.line).toBe(5);
    // A failed compile is not kept: the next call compiles (and fails) again.
    const modules = core.created().shaderModules;
    await expect(runCompute(device, job('y[0] = undefinedName;'))).rejects.toBeInstanceOf(GpuError);
    expect(core.created().shaderModules).toBe(modules + 1);
    // A good kernel compiles once and is reused.
    const pipelines = core.created().computePipelines;
    for (let i = 0; i < 3; i++) {
      const result = await runCompute(device, job('y[0] = 4321u;'));
      expect([...result.output]).toEqual([4321]);
    }
    expect(core.created().computePipelines).toBe(pipelines + 1);
  });

  it('caches render pipelines by their state', async () => {
    const device = await nodeDevice();
    const core = gpuCore(device);
    const code = `
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
  return vec4f(f32(i) - 1.0, 0.0, 0.0, 1.0);
}
@fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }`;
    const request = (format: GPUTextureFormat) => ({
      code,
      vertex: { entryPoint: 'vs' },
      fragment: { entryPoint: 'fs', targets: [{ format }] },
    });
    const a = await withErrorScopes(device, 'render', () =>
      core.renderPipeline(request('rgba8unorm')),
    );
    const b = await withErrorScopes(device, 'render', () =>
      core.renderPipeline(request('rgba8unorm')),
    );
    const c = await withErrorScopes(device, 'render', () =>
      core.renderPipeline(request('bgra8unorm')),
    );
    expect(b).toBe(a);
    expect(c).not.toBe(a);
  });

  it("takes rng.wesl's pcgHash under a prefix, as the grader's harness does", async () => {
    const device = await nodeDevice();
    const hash = prefixedDeclarations(SHADER_LIBRARY, 'rng', ['pcgHash'], 'sbg_');
    // Its own dependencies come along renamed; nothing else of rng.wesl does.
    expect(hash).toMatch(/fn sbg_pcgOutput\(/);
    expect(hash).toMatch(/const sbg_PCG_MULTIPLIER/);
    expect(hash).not.toMatch(/\bpcgHash\b|rngNextFloat/);
    // A submission may declare pcgHash itself next to the harness's copy.
    const code = `${hash}
fn pcgHash(v: u32) -> u32 { return v; }
@group(0) @binding(0) var<storage, read> x: array<u32>;
@group(0) @binding(1) var<storage, read_write> y: array<u32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  if (id.x < arrayLength(&x)) { y[id.x] = sbg_pcgHash(x[id.x]) + pcgHash(0u); }
}`;
    const values = [0, 1, 2, 12345, 0xffffffff, 0x80000000];
    const { output } = await runCompute(device, {
      code,
      inputs: [new Uint32Array(values)],
      outputWords: values.length,
      workgroups: [1],
    });
    expect([...output]).toEqual(values.map((v) => pcgHash(v)));
  });
});
