// The second engine itself: that it is naga behind wgpu's Vulkan backend, that it
// rejects what Tint accepts in the one difference met so far (README, WGSL
// pitfalls), and that a missing driver fails loudly instead of skipping.
import { afterEach, describe, expect, it } from 'vitest';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { withEngineNote } from '../../src/grading/engineNotes.ts';
import { denoBinary, runOnWgpu, vulkanIcd } from '../support/denoGpu.ts';
import { nodeDevice } from '../support/nodeGpu.ts';

// A function whose body ends in a loop left only by `return`.
const ENDS_IN_LOOP = `
fn firstPowerAbove(x: f32) -> f32 {
  var p = 1.0;
  loop {
    if (p > x) { return p; }
    p *= 2.0;
  }
}
@compute @workgroup_size(1)
fn main() { _ = firstPowerAbove(3.0); }
`;
const BREAKS_THEN_RETURNS = ENDS_IN_LOOP.replace('{ return p; }', '{ break; }').replace(
  'p *= 2.0;\n  }\n}',
  'p *= 2.0;\n  }\n  return p;\n}',
);

async function tintMessages(code: string): Promise<GPUCompilationMessage[]> {
  const device = await nodeDevice();
  const info = await device.createShaderModule({ code }).getCompilationInfo();
  return [...info.messages];
}

describe('wgpu through Deno', () => {
  const saved = process.env.SB_WGPU_ICD;
  afterEach(() => {
    if (saved === undefined) delete process.env.SB_WGPU_ICD;
    else process.env.SB_WGPU_ICD = saved;
  });

  it('finds Deno and a Vulkan driver, and gets an adapter from it', async () => {
    expect(denoBinary(), 'Deno binary (npm install brings it)').not.toBeNull();
    expect(vulkanIcd(), 'Vulkan ICD manifest').not.toBeNull();
    const answer = await runOnWgpu({});
    expect(answer.engine.adapter).not.toBe('');
    expect(answer.engine.icd).toBe(vulkanIcd());
  });

  it('naga rejects a function that ends in a loop, which Tint accepts', async () => {
    const answer = await runOnWgpu({
      compile: [
        { name: 'ends in a loop', code: ENDS_IN_LOOP, compute: ['main'] },
        { name: 'breaks, then returns', code: BREAKS_THEN_RETURNS, compute: ['main'] },
      ],
    });
    const [endsInLoop, breaks] = answer.compile;
    const nagaErrors = endsInLoop?.messages.filter((m) => m.type === 'error') ?? [];
    expect(nagaErrors.map((m) => m.message).join('\n')).toMatch(/return.*None/);
    // The grader explains naga's message to a student in Firefox, and only that one.
    expect(withEngineNote(nagaErrors[0]?.message ?? '')).toMatch(/break.*return once after it/s);
    expect(withEngineNote('unknown identifier `x`')).toBe('unknown identifier `x`');
    expect(breaks?.messages.filter((m) => m.type === 'error')).toEqual([]);
    expect(breaks?.pipelines).toEqual([{ kind: 'compute', entry: 'main', error: null }]);
    // Tint: the first compiles without error; a return after the loop only warns.
    expect((await tintMessages(ENDS_IN_LOOP)).filter((m) => m.type === 'error')).toEqual([]);
    expect((await tintMessages(BREAKS_THEN_RETURNS)).map((m) => m.message)).toEqual([]);
  });

  it('fails with what to install when the Vulkan driver does not load', async () => {
    const manifest = join(mkdtempSync(join(tmpdir(), 'sb-icd-')), 'missing_icd.json');
    writeFileSync(
      manifest,
      JSON.stringify({
        file_format_version: '1.0.0',
        ICD: { library_path: '/nonexistent/libvulkan_missing.so', api_version: '1.3.0' },
      }),
    );
    process.env.SB_WGPU_ICD = manifest;
    await expect(runOnWgpu({})).rejects.toThrow(/no WebGPU adapter.*mesa-vulkan-drivers/s);
    process.env.SB_WGPU_ICD = join(tmpdir(), 'no-such-icd.json');
    await expect(runOnWgpu({})).rejects.toThrow(/need a Vulkan driver/);
  });
});
