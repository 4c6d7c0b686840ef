// WGSL tabulated phase function (shaders/mie.wesl) vs its float64 twin
// (src/reference/mie.ts) on Mie tables built by the twin's series: a fog droplet
// (x = 10), a cloud droplet whose forward peak is 10⁶ times its back (x = 1000), and
// absorbing soot. The table is rounded to f32 before both sides see it, so the two
// differ only by their arithmetic.
//
// Not through tests/support/shaderHarness.ts: there every case carries its arguments,
// and an 8 KB table per case made SwiftShader and lavapipe take minutes to compile and
// copy. Here the table is bound once as a storage buffer, as the widget's kernel binds
// it (kernels/mie-lobe.wesl), and each invocation copies it into the private variable
// the library's pointer parameters take. wgpu/naga compiles the module in
// tests/naga/compile.test.ts.
import { beforeAll, describe, expect, it } from 'vitest';
import { runCompute } from '../../src/gpu/compute.ts';
import { linkKernel } from '../../src/gpu/link.ts';
import {
  mieTabulatePhase,
  PHASE_TABLE_NODES,
  phaseTableCdfInterval,
  phaseTableInterval,
  phaseTableToF32,
  phaseTabulatedEval,
  phaseTabulatedEvalTerms,
  phaseTabulatedSample,
  phaseTabulatedSampleMu,
  type PhaseTable,
  type Vec3,
} from '../../src/reference/mie.ts';
import { packTable } from '../../src/widgets/mie-lobe/gpuBackend.ts';
import { ONE_MINUS_EPSILON_F32 } from '../support/f32.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const f = Math.fround;
const WO: Vec3 = [0.3, -0.5, 0.81].map((c) => f(c / Math.hypot(0.3, 0.5, 0.81))) as [
  number,
  number,
  number,
];
const U1 = 0.3;

/** Per case: (μ, 1 − μ, 1 + μ, ξ) in; eight results out (see OUTPUTS). */
const KERNEL = `
import package::mie::{PhaseTable, PHASE_TABLE_NODES, phaseTabulatedEval, phaseTabulatedEvalTerms, phaseTableInterval, phaseTableCdfInterval, phaseTabulatedSampleMu, phaseTabulatedSample};

@group(0) @binding(0) var<storage, read> table: PhaseTable;
@group(0) @binding(1) var<storage, read> cases: array<vec4f>;
@group(0) @binding(2) var<storage, read_write> results: array<f32>;

var<private> local: PhaseTable;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&cases)) {
    return;
  }
  for (var k = 0u; k < PHASE_TABLE_NODES; k++) {
    local.oneMinusMu[k] = table.oneMinusMu[k];
    local.onePlusMu[k] = table.onePlusMu[k];
    local.pdf[k] = table.pdf[k];
    local.cdf[k] = table.cdf[k];
  }
  let c = cases[i];
  let wo = vec3f(${WO.map((v) => v.toPrecision(9)).join(', ')});
  let s = phaseTabulatedSampleMu(&local, c.w);
  let sample = phaseTabulatedSample(&local, wo, vec2f(c.w, ${U1}));
  let base = 8u * i;
  results[base] = phaseTabulatedEval(&local, c.x);
  results[base + 1u] = phaseTabulatedEvalTerms(&local, c.y, c.z);
  results[base + 2u] = f32(phaseTableInterval(&local, c.y));
  results[base + 3u] = f32(phaseTableCdfInterval(&local, c.w));
  results[base + 4u] = s.mu;
  results[base + 5u] = s.onePlusMu;
  results[base + 6u] = -dot(wo, sample.wi);
  results[base + 7u] = sample.pdf;
}
`;

const OUTPUTS = [
  'phaseTabulatedEval(μ)',
  'phaseTabulatedEvalTerms(1 − μ, 1 + μ)',
  'phaseTableInterval(1 − μ)',
  'phaseTableCdfInterval(ξ)',
  'phaseTabulatedSampleMu(ξ).mu',
  'phaseTabulatedSampleMu(ξ).onePlusMu',
  '−wo·wi of phaseTabulatedSample(wo, (ξ, 0.3))',
  'phaseTabulatedSample(wo, (ξ, 0.3)).pdf',
] as const;

function twinOutputs(table: PhaseTable, c: readonly number[]): number[] {
  const [mu, t, u, xi] = c as [number, number, number, number];
  const s = phaseTabulatedSampleMu(table, xi);
  const sample = phaseTabulatedSample(table, WO, [xi, U1]);
  const w = sample.wi;
  return [
    phaseTabulatedEval(table, mu),
    phaseTabulatedEvalTerms(table, t, u),
    phaseTableInterval(table, t),
    phaseTableCdfInterval(table, xi),
    s.mu,
    s.onePlusMu,
    -(WO[0] * w[0] + WO[1] * w[1] + WO[2] * w[2]),
    sample.pdf,
  ];
}

/**
 * Tolerances per output. Evaluations: a weight from one f32 subtraction and division
 * of complements (≈ 3 ulp) applied to p_{k+1} − p_k, a few times p where the nodes
 * resolve the lobe: relative 2e-5. Interval indices: comparisons of the same f32
 * values, exact. Samples: r from one f32 division of CDF differences (the CDF near 1 has
 * 6e-8 spacing, so r moves by ~1e-6 of an interval holding 1e-2 of the mass), a square
 * root and a lerp of node complements: absolute 2e-6 or relative 1e-4 on μ and 1 + μ;
 * the pdf at the sample is a lerp of a steep lobe: relative 1e-4.
 */
const TOLERANCES: readonly { relative: number; absolute: number }[] = [
  { relative: 2e-5, absolute: 0 },
  { relative: 2e-5, absolute: 0 },
  { relative: 0, absolute: 0 },
  { relative: 0, absolute: 0 },
  { relative: 1e-4, absolute: 2e-6 },
  { relative: 1e-4, absolute: 2e-6 },
  { relative: 1e-4, absolute: 2e-6 },
  { relative: 1e-4, absolute: 0 },
];

const TABLES = [
  ['fog x = 10', mieTabulatePhase(10, { n: 1.33, kappa: 0 })],
  ['cloud x = 1000', mieTabulatePhase(1000, { n: 1.33, kappa: 0 })],
  ['soot x = 3', mieTabulatePhase(3, { n: 1.75, kappa: 0.44 })],
] as const;

/** (name, μ, 1 − μ, 1 + μ, ξ), each rounded to f32 as the GPU sees it. */
function casesFor(table: PhaseTable): [string, number, number, number, number][] {
  const list: [string, number, number, number, number][] = [
    ['μ = 1, 1 − μ = 0 (forward node), ξ = 0', 1, 0, 2, 0],
    ['μ = −1, 1 + μ = 0 (backward node), ξ = 1', -1, 2, 0, 1],
    ['μ = 1.5 clamped, ξ = 1 − 2⁻²⁴', 1.5, 0, 2, ONE_MINUS_EPSILON_F32],
    // 1e-5 rad from forward: 1 − μ = 5e-11, which 1 − f32(μ) cannot express.
    ['μ = 1 − 2⁻²⁴·8; 1 − μ = 5e-11 (θ = 1e-5 rad); ξ = 1e-7', 1 - 8 * 2 ** -24, 5e-11, 2, 1e-7],
    ['μ = 0.999; 1 + μ = 5e-11 (1e-5 rad from the back); ξ = 0.999999', 0.999, 2, 5e-11, 0.999999],
    ['μ = 0.5; 1 − μ = 1e-6; ξ = 0.25', 0.5, 1e-6, 2, 0.25],
    ['μ = 0 (90°); 1 − μ = 0.75; ξ = 0.5', 0, 0.75, 1.25, 0.5],
    [
      'μ = cos 138° (rainbow); 1 − μ at node 300; ξ = 0.9',
      Math.cos((138 * Math.PI) / 180),
      table.oneMinusMu[300]!,
      table.onePlusMu[300]!,
      0.9,
    ],
    [
      'μ = −0.99999 (glory side); 1 − μ at node 200; ξ = 0.01',
      -0.99999,
      table.oneMinusMu[200]!,
      table.onePlusMu[200]!,
      0.01,
    ],
    ['μ = −0.3; ξ = 0.97', -0.3, 1.3, 0.7, 0.97],
  ];
  return list.map(([name, ...values]) => [
    name,
    ...(values.map(f) as [number, number, number, number]),
  ]);
}

describe('shaders/mie.wesl on the GPU (Dawn) vs the float64 twin, one table bound per dispatch', () => {
  const gpu = new Map<string, Float32Array>();
  beforeAll(async () => {
    const device = await nodeDevice();
    const code = await linkKernel(SHADER_LIBRARY, KERNEL);
    for (const [name, built] of TABLES) {
      const table = phaseTableToF32(built);
      const cases = casesFor(table);
      const { output } = await runCompute(device, {
        code,
        inputs: [
          packTable(table),
          new Uint32Array(Float32Array.from(cases.flatMap(([, ...v]) => v)).buffer),
        ],
        outputWords: 8 * cases.length,
        workgroups: [1],
      });
      gpu.set(name, new Float32Array(output.buffer, output.byteOffset, output.length));
    }
  }, 180_000);

  it(`the table struct has ${PHASE_TABLE_NODES} nodes per column`, () => {
    expect(packTable(phaseTableToF32(TABLES[0][1])).length).toBe(4 * PHASE_TABLE_NODES);
  });

  for (const [name, built] of TABLES) {
    const table = phaseTableToF32(built);
    casesFor(table).forEach(([caseName, ...args], index) => {
      it(`${name}: ${caseName}`, () => {
        const results = gpu.get(name);
        expect(results, 'the GPU ran').toBeDefined();
        const twin = twinOutputs(table, args);
        twin.forEach((expected, k) => {
          const actual = results![8 * index + k]!;
          const { relative, absolute } = TOLERANCES[k]!;
          expect(Number.isFinite(actual), `${OUTPUTS[k]} is finite`).toBe(true);
          expect(
            Math.abs(actual - expected) <= Math.max(absolute, relative * Math.abs(expected)),
            `${OUTPUTS[k]}: GPU ${actual} vs twin ${expected}`,
          ).toBe(true);
        });
        // The published end points: ξ = 0 samples μ = 1 exactly and ξ = 1 samples μ = −1.
        if (args[3] === 0) expect(results![8 * index + 4]).toBe(1);
        if (args[3] === 1) expect(results![8 * index + 4]).toBe(-1);
      });
    });
  }
});
