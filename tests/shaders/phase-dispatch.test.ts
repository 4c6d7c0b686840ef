// The scene integrator's phase dispatch on the GPU (integrator.wesl mediumPhaseEval and
// mediumPhaseSample) against the twin's (src/reference/integrator.ts), for every entry
// of the phase-function registry and each of its examples, packed by packPhase: a tag,
// a parameter slot or a condition that differs between the registry, the WGSL and the
// twin shows here as a different value. Linked with the general conditions (every case)
// and with no phase condition (every kind falls back to the first entry).
import { beforeAll, describe, expect, it } from 'vitest';
import { linkKernel } from '../../src/gpu/link.ts';
import {
  PHASE_CONDITIONS,
  PHASE_FUNCTIONS,
  packPhase,
  type PhaseDescription,
  type PhaseRecord,
} from '../../src/phase/registry.ts';
import { directionAroundAxis, type Vec3 } from '../../src/reference/directions.ts';
import {
  mediumPhaseEval,
  mediumPhaseSample,
  type SceneData,
  type SceneMedium,
} from '../../src/reference/integrator.ts';
import { GENERAL_CONDITIONS, type Conditions } from '../../src/scene/plan.ts';
import { HG_VALUE, TRIG_DIRECTION } from '../support/phaseHarness.ts';
import { withinTolerance } from '../support/shaderHarness.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

// One case: the phase record (kind as u32 bits, three values, table), wo, wi, u.
const CASE_WORDS = 16;
const KERNEL = `import package::integrator::{SceneMedium, ScenePhase, mediumPhaseEval, mediumPhaseSample};

@group(1) @binding(0) var<storage, read> cases: array<vec4f>;
@group(1) @binding(1) var<storage, read_write> results: array<vec4f>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&results)) {
    return;
  }
  let r0 = cases[4u * i];
  let phase = ScenePhase(bitcast<u32>(r0.x), bitcast<u32>(cases[4u * i + 3u].z), r0.yzw);
  let medium = SceneMedium(0u, 0u, phase, vec3f(0.0), 0.0, vec3f(0.0), vec3f(0.0), vec3f(0.0), vec3f(0.0));
  let wo = cases[4u * i + 1u].xyz;
  let wi = cases[4u * i + 2u].xyz;
  let u = cases[4u * i + 3u].xy;
  results[i] = vec4f(mediumPhaseSample(medium, wo, u), mediumPhaseEval(medium, wo, wi));
}
`;

interface DispatchCase {
  name: string;
  phase: PhaseRecord;
  wo: Vec3;
  wi: Vec3;
  u: [number, number];
}

const f32 = (v: readonly number[]): number[] => v.map(Math.fround);
const unit = (v: readonly number[]): Vec3 => {
  const n = Math.hypot(...v);
  return f32(v.map((c) => c / n)) as unknown as Vec3;
};

/** Each example of each entry, at a few direction pairs and random pairs u. */
function dispatchCases(): DispatchCase[] {
  const wos = [unit([0.3, -0.5, 0.81]), unit([0, 0, 1]), unit([-0.9, 0.1, -0.05])];
  const cases: DispatchCase[] = [];
  for (const entry of PHASE_FUNCTIONS)
    for (const example of entry.examples) {
      const phase = packPhase({ type: entry.id, ...example } as PhaseDescription);
      const f32Phase: PhaseRecord = {
        ...phase,
        values: f32(phase.values) as unknown as PhaseRecord['values'],
      };
      wos.forEach((wo, w) =>
        [0.95, 0.3, -0.2, -0.9].forEach((mu, m) => {
          const travel: Vec3 = [-wo[0], -wo[1], -wo[2]];
          const wi = f32(directionAroundAxis(travel, mu, Math.sqrt(1 - mu * mu), 0.1 + 0.2 * m));
          cases.push({
            name: `${entry.id} ${JSON.stringify(example)}, wo #${w}, μ = ${mu}`,
            phase: f32Phase,
            wo,
            wi: wi as unknown as Vec3,
            u: f32([0.07 + 0.29 * m, 0.61 - 0.13 * w]) as [number, number],
          });
        }),
      );
    }
  return cases;
}

async function runOnGpu(
  conditions: Conditions,
  cases: readonly DispatchCase[],
): Promise<Float32Array> {
  const device = await nodeDevice();
  const code = await linkKernel(SHADER_LIBRARY, KERNEL, conditions);
  const input = new ArrayBuffer(cases.length * CASE_WORDS * 4);
  const floats = new Float32Array(input);
  const words = new Uint32Array(input);
  cases.forEach((c, i) => {
    const o = i * CASE_WORDS;
    words[o] = c.phase.kind;
    floats.set(c.phase.values, o + 1);
    floats.set(c.wo, o + 4);
    floats.set(c.wi, o + 8);
    floats.set(c.u, o + 12);
    words[o + 14] = c.phase.table;
  });
  const usage = GPUBufferUsage;
  const casesBuffer = device.createBuffer({
    size: input.byteLength,
    usage: usage.STORAGE | usage.COPY_DST,
  });
  device.queue.writeBuffer(casesBuffer, 0, input);
  const resultBytes = cases.length * 16;
  const results = device.createBuffer({ size: resultBytes, usage: usage.STORAGE | usage.COPY_SRC });
  const readback = device.createBuffer({
    size: resultBytes,
    usage: usage.MAP_READ | usage.COPY_DST,
  });
  device.pushErrorScope('validation');
  const pipeline = device.createComputePipeline({
    layout: 'auto',
    compute: { module: device.createShaderModule({ code }), entryPoint: 'main' },
  });
  const bindGroup = device.createBindGroup({
    layout: pipeline.getBindGroupLayout(1),
    entries: [
      { binding: 0, resource: { buffer: casesBuffer } },
      { binding: 1, resource: { buffer: results } },
    ],
  });
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  pass.setBindGroup(1, bindGroup);
  pass.dispatchWorkgroups(Math.ceil(cases.length / 64));
  pass.end();
  encoder.copyBufferToBuffer(results, 0, readback, 0, resultBytes);
  device.queue.submit([encoder.finish()]);
  const error = await device.popErrorScope();
  if (error) throw new Error(`phase dispatch kernel: ${error.message}`);
  await readback.mapAsync(GPUMapMode.READ);
  const output = new Float32Array(readback.getMappedRange().slice(0));
  readback.unmap();
  for (const buffer of [casesBuffer, results, readback]) buffer.destroy();
  return output;
}

function twinOf(conditions: Conditions, c: DispatchCase): number[] {
  const scene = { conditions } as unknown as SceneData;
  const medium = { phase: c.phase } as unknown as SceneMedium;
  return [
    ...mediumPhaseSample(scene, medium, c.wo, c.u),
    mediumPhaseEval(scene, medium, c.wo, c.wi),
  ];
}

const withoutPhases: Conditions = {
  ...GENERAL_CONDITIONS,
  ...Object.fromEntries(PHASE_CONDITIONS.map((c) => [c, false])),
};

for (const [label, conditions] of [
  ['general conditions', GENERAL_CONDITIONS],
  ['no phase condition (fallback)', withoutPhases],
] as const) {
  describe(`integrator.wesl phase dispatch vs twin, ${label}`, () => {
    const cases = dispatchCases();
    let output = new Float32Array(0);
    beforeAll(async () => {
      output = await runOnGpu(conditions, cases);
    }, 60_000);

    cases.forEach((c, i) =>
      it(c.name, () => {
        const twin = twinOf(conditions, c);
        const gpu = [...output.subarray(4 * i, 4 * i + 4)];
        for (let k = 0; k < 3; k++)
          expect(
            withinTolerance(gpu[k]!, twin[k]!, TRIG_DIRECTION),
            `sampled wi[${k}]: GPU ${gpu[k]} vs twin ${twin[k]}`,
          ).toBe(true);
        expect(
          withinTolerance(gpu[3]!, twin[3]!, HG_VALUE),
          `phase value: GPU ${gpu[3]} vs twin ${twin[3]}`,
        ).toBe(true);
      }),
    );
  });
}
