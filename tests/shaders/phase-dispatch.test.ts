// The scene integrator's phase dispatch on the GPU (integrator.wesl mediumPhaseEval and
// mediumPhaseSample) against the twin's (src/reference/integrator.ts), for every entry
// of the phase-function registry and each of its examples, packed by packPhase: a tag,
// a parameter slot or a condition that differs between the registry, the WGSL and the
// twin shows here as a different value. Linked with the general conditions (every case)
// and with no phase condition (every kind falls back to the first entry). Then, per
// example, GPU samples of mediumPhaseSample against the twin's density (chi-square), so
// a new entry's WGSL sampler is checked over its whole domain, not only at a few points.
// Tabulated entries read their tables from the phase-table buffer packPhases builds,
// bound as the integrator's scenePhaseTables (group 0, binding 5) where the kernel
// declares it, and given to the twin as SceneData.phaseTables.
import { beforeAll, describe, expect, it } from 'vitest';
import { linkKernel } from '../../src/gpu/link.ts';
import {
  PHASE_CONDITIONS,
  PHASE_FUNCTIONS,
  PHASE_TABLE_WORDS,
  packPhases,
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
import {
  chiSquare,
  DirectionHistogramBuilder,
  expectedMuCounts,
  MU_BINS,
  PHI_BINS,
  phaseBreakpoints,
  phaseOfMu,
} from '../support/phaseStatistics.ts';
import { chiSquareSurvival } from '../../src/statistics/distributions.ts';

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

/** Every example of every entry, in order. */
const EXAMPLE_PHASES: PhaseDescription[] = PHASE_FUNCTIONS.flatMap((entry) =>
  entry.examples.map((example) => ({ type: entry.id, ...example }) as PhaseDescription),
);
/** Their records and the phase-table buffer of the tabulated ones. */
const PACKED = packPhases(EXAMPLE_PHASES);

/** Each example of each entry, at a few direction pairs and random pairs u. */
function dispatchCases(): DispatchCase[] {
  const wos = [unit([0.3, -0.5, 0.81]), unit([0, 0, 1]), unit([-0.9, 0.1, -0.05])];
  const cases: DispatchCase[] = [];
  let index = 0;
  for (const entry of PHASE_FUNCTIONS)
    for (const example of entry.examples) {
      const phase = PACKED.records[index++]!;
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

/** Packs one case: phase record, wo, wi, u and the table offset (see KERNEL). */
function packCase(c: DispatchCase, floats: Float32Array, words: Uint32Array, o: number): void {
  words[o] = c.phase.kind;
  floats.set(c.phase.values, o + 1);
  floats.set(c.wo, o + 4);
  floats.set(c.wi, o + 8);
  floats.set(c.u, o + 12);
  words[o + 14] = c.phase.table;
}

/**
 * Runs `code` (bindings group 1: input, then `count` vec4f results; group 0 binding 5: the
 * phase tables, where the code declares them) and reads them back.
 */
async function dispatch(
  code: string,
  input: ArrayBuffer,
  count: number,
  tables: Float32Array<ArrayBuffer>,
): Promise<Float32Array> {
  const device = await nodeDevice();
  const usage = GPUBufferUsage;
  const inputBuffer = device.createBuffer({
    size: input.byteLength,
    usage: usage.STORAGE | usage.COPY_DST,
  });
  device.queue.writeBuffer(inputBuffer, 0, input);
  const resultBytes = count * 16;
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
      { binding: 0, resource: { buffer: inputBuffer } },
      { binding: 1, resource: { buffer: results } },
    ],
  });
  const tableBuffer = device.createBuffer({
    size: Math.max(tables.byteLength, PHASE_TABLE_WORDS * 4),
    usage: usage.STORAGE | usage.COPY_DST,
  });
  if (tables.length > 0) device.queue.writeBuffer(tableBuffer, 0, tables);
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  if (code.includes('scenePhaseTables'))
    pass.setBindGroup(
      0,
      device.createBindGroup({
        layout: pipeline.getBindGroupLayout(0),
        entries: [{ binding: 5, resource: { buffer: tableBuffer } }],
      }),
    );
  pass.setBindGroup(1, bindGroup);
  pass.dispatchWorkgroups(Math.ceil(count / 64));
  pass.end();
  encoder.copyBufferToBuffer(results, 0, readback, 0, resultBytes);
  device.queue.submit([encoder.finish()]);
  const error = await device.popErrorScope();
  if (error) throw new Error(`phase dispatch kernel: ${error.message}`);
  await readback.mapAsync(GPUMapMode.READ);
  const output = new Float32Array(readback.getMappedRange().slice(0));
  readback.unmap();
  for (const buffer of [inputBuffer, results, readback, tableBuffer]) buffer.destroy();
  return output;
}

async function runOnGpu(
  conditions: Conditions,
  cases: readonly DispatchCase[],
): Promise<Float32Array> {
  const input = new ArrayBuffer(cases.length * CASE_WORDS * 4);
  const floats = new Float32Array(input);
  const words = new Uint32Array(input);
  cases.forEach((c, i) => packCase(c, floats, words, i * CASE_WORDS));
  return dispatch(
    await linkKernel(SHADER_LIBRARY, KERNEL, conditions),
    input,
    cases.length,
    PACKED.tables,
  );
}

function twinOf(conditions: Conditions, c: DispatchCase): number[] {
  const scene = { conditions, phaseTables: PACKED.tables } as unknown as SceneData;
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
    let output: Float32Array = new Float32Array(0);
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

// ---------------------------------------------------------------------------
// The GPU's samples of each entry against the twin's density (chi-square).
// ---------------------------------------------------------------------------
const GPU_SAMPLES = 1 << 16;
const SAMPLING_KERNEL = `import package::integrator::{SceneMedium, ScenePhase, mediumPhaseSample};
import package::rng::{rngNextFloat, rngSeed};

@group(1) @binding(0) var<storage, read> phaseCase: array<vec4f, 4>;
@group(1) @binding(1) var<storage, read_write> results: array<vec4f>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&results)) {
    return;
  }
  let r0 = phaseCase[0];
  let phase = ScenePhase(bitcast<u32>(r0.x), bitcast<u32>(phaseCase[3].z), r0.yzw);
  let medium = SceneMedium(0u, 0u, phase, vec3f(0.0), 0.0, vec3f(0.0), vec3f(0.0), vec3f(0.0), vec3f(0.0));
  var state = rngSeed(i, 9u);
  let u = vec2f(rngNextFloat(&state), rngNextFloat(&state));
  results[i] = vec4f(mediumPhaseSample(medium, phaseCase[1].xyz, u), 0.0);
}
`;
/** Two chi-square tests per example, family-wise α = 0.01. */
const GPU_ALPHA = 0.01 / (2 * PHASE_FUNCTIONS.reduce((n, e) => n + e.examples.length, 0));

describe(`integrator.wesl mediumPhaseSample on the GPU: ${GPU_SAMPLES} samples per example follow the twin's density`, () => {
  const wo = unit([0.3, -0.5, 0.81]);
  for (const entry of PHASE_FUNCTIONS)
    for (const example of entry.examples) {
      it(`${entry.id} ${JSON.stringify(example)} (χ² in μ, ${MU_BINS} bins, and in azimuth, ${PHI_BINS} bins)`, async () => {
        const { records, tables } = packPhases([
          { type: entry.id, ...example } as PhaseDescription,
        ]);
        const record = records[0]!;
        const input = new ArrayBuffer(CASE_WORDS * 4);
        const c: DispatchCase = { name: '', phase: record, wo, wi: wo, u: [0, 0] };
        packCase(c, new Float32Array(input), new Uint32Array(input), 0);
        const code = await linkKernel(SHADER_LIBRARY, SAMPLING_KERNEL, GENERAL_CONDITIONS);
        const output = await dispatch(code, input, GPU_SAMPLES, tables);
        const builder = new DirectionHistogramBuilder(wo);
        for (let i = 0; i < GPU_SAMPLES; i++)
          builder.add([output[4 * i]!, output[4 * i + 1]!, output[4 * i + 2]!]);
        const { mu, phi, lengthError } = builder.histogram;
        expect(lengthError, 'every wi is a unit vector (f32)').toBeLessThan(1e-5);
        const p = phaseOfMu(entry, record, wo, tables);
        const breakpoints = phaseBreakpoints(entry, record, tables);
        const muStatistic = chiSquare(mu, expectedMuCounts(p, GPU_SAMPLES, breakpoints));
        expect(
          chiSquareSurvival(muStatistic, MU_BINS - 1),
          `χ² in μ = ${muStatistic}`,
        ).toBeGreaterThan(GPU_ALPHA);
        const phiStatistic = chiSquare(
          phi,
          new Array<number>(PHI_BINS).fill(GPU_SAMPLES / PHI_BINS),
        );
        expect(
          chiSquareSurvival(phiStatistic, PHI_BINS - 1),
          `χ² in φ = ${phiStatistic}`,
        ).toBeGreaterThan(GPU_ALPHA);
      }, 60_000);
    }
});
