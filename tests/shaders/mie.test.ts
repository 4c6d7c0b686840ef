// WGSL tabulated phase function (shaders/mie.wesl) vs its float64 twin
// (src/reference/mie.ts) on Mie tables built by the twin's series: a fog droplet
// (x = 10), a cloud droplet whose forward peak is 10⁶ times its back (x = 1000), and
// absorbing soot. The table is rounded to f32 before both sides see it (the harness
// rounds every argument), so the two differ only by their arithmetic.
//
// Each case carries its 8 KB table, which SwiftShader and lavapipe compile and copy
// slowly, so the library's six functions run in two wrappers (two kernels per engine):
// the evaluation with both interval searches, and the two samplers.
import { describeShaderFunction, type ShaderCase } from '../support/shaderHarness.ts';
import {
  mieTabulatePhase,
  PHASE_TABLE_NODES,
  phaseTableCdfInterval,
  phaseTableInterval,
  phaseTabulatedEval,
  phaseTabulatedEvalTerms,
  phaseTabulatedSample,
  phaseTabulatedSampleMu,
  type PhaseTable,
  type Vec3,
} from '../../src/reference/mie.ts';
import { ONE_MINUS_EPSILON_F32 } from '../support/f32.ts';

const FOG = mieTabulatePhase(10, { n: 1.33, kappa: 0 });
const CLOUD = mieTabulatePhase(1000, { n: 1.33, kappa: 0 });
const SOOT = mieTabulatePhase(3, { n: 1.75, kappa: 0.44 });
const TABLES = [
  ['fog x = 10', FOG],
  ['cloud x = 1000', CLOUD],
  ['soot x = 3', SOOT],
] as const;

const tableArgs = (t: PhaseTable): number[][] => [
  Array.from(t.oneMinusMu),
  Array.from(t.onePlusMu),
  Array.from(t.pdf),
  Array.from(t.cdf),
];
const tableFromArgs = (a: number[], b: number[], c: number[], d: number[]): PhaseTable => ({
  oneMinusMu: Float64Array.from(a),
  onePlusMu: Float64Array.from(b),
  pdf: Float64Array.from(c),
  cdf: Float64Array.from(d),
});
const TABLE_TYPE = `f32[${PHASE_TABLE_NODES}]` as const;
const TABLE_PARAMETERS = `nodeOneMinusMu: array<f32, ${PHASE_TABLE_NODES}>, nodeOnePlusMu: array<f32, ${PHASE_TABLE_NODES}>, nodePdf: array<f32, ${PHASE_TABLE_NODES}>, nodeCdf: array<f32, ${PHASE_TABLE_NODES}>`;
// Element by element: whole-array assignments become 513 unrolled copies each in SPIR-V,
// which SwiftShader compiles slowly.
const FILL_TABLE = `  var table: PhaseTable;
  var a = nodeOneMinusMu;
  var b = nodeOnePlusMu;
  var c = nodePdf;
  var d = nodeCdf;
  for (var k = 0u; k < ${PHASE_TABLE_NODES}u; k++) {
    table.oneMinusMu[k] = a[k];
    table.onePlusMu[k] = b[k];
    table.pdf[k] = c[k];
    table.cdf[k] = d[k];
  }`;

// The nodes of the default grid, as μ (the first few are 1e-5 rad apart).
const nodeMu = (t: PhaseTable, k: number): number => 1 - t.oneMinusMu[k]!;

/**
 * Case args: the table, μ for phaseTabulatedEval, (1 − μ, 1 + μ) for phaseTabulatedEvalTerms
 * and for phaseTableInterval, and ξ for phaseTableCdfInterval. Result: the two
 * evaluations and the two interval indices (as f32, exact for indices ≤ 511).
 */
const evalCase = (
  name: string,
  t: PhaseTable,
  mu: number,
  oneMinusMu: number,
  onePlusMu: number,
  xi: number,
): ShaderCase => ({
  name,
  args: [...tableArgs(t), mu, oneMinusMu, onePlusMu, xi],
});

const evalCases: ShaderCase[] = TABLES.flatMap(([name, t]) => [
  {
    ...evalCase(`${name}: μ = 1 and 1 − μ = 0, the forward node; ξ = 0`, t, 1, 0, 2, 0),
    expected: [Math.fround(t.pdf[0]!), Math.fround(t.pdf[0]!), 0, 0],
  },
  evalCase(`${name}: μ = −1 and 1 + μ = 0, the backward node; ξ = 1`, t, -1, 2, 0, 1),
  evalCase(`${name}: μ = 1.5 is clamped to 1; 1 − μ = 3 is clamped to 2`, t, 1.5, 3, 0, 0.5),
  // 1e-5 rad from forward: 1 − μ = 5e-11, which 1 − f32(μ) cannot express (it rounds to 0).
  evalCase(
    `${name}: μ = 1 − 2⁻²⁴·8, inside the forward peak; 1 − μ = 5e-11 (θ = 1e-5 rad)`,
    t,
    1 - 8 * 2 ** -24,
    5e-11,
    2 - 5e-11,
    1e-7,
  ),
  evalCase(
    `${name}: μ = 0.999; 1 + μ = 5e-11 (1e-5 rad from the back)`,
    t,
    0.999,
    2 - 5e-11,
    5e-11,
    0.999999,
  ),
  evalCase(`${name}: μ = 0.5; 1 − μ = 1e-6`, t, 0.5, 1e-6, 2 - 1e-6, 0.25),
  evalCase(`${name}: μ = 0 (90°); 1 − μ = 0.75`, t, 0, 0.75, 1.25, 0.9),
  evalCase(
    `${name}: μ = cos 138° (the rainbow); 1 − μ at node 300 exactly`,
    t,
    Math.cos((138 * Math.PI) / 180),
    t.oneMinusMu[300]!,
    t.onePlusMu[300]!,
    0.75,
  ),
  evalCase(
    `${name}: μ = −0.99999 (next to the glory); μ at node 200 exactly`,
    t,
    -0.99999,
    1 - nodeMu(t, 200),
    1 + nodeMu(t, 200),
    0.01,
  ),
]);

describeShaderFunction({
  module: 'mie',
  fn: 'phaseTabulatedEval',
  args: [TABLE_TYPE, TABLE_TYPE, TABLE_TYPE, TABLE_TYPE, 'f32', 'f32', 'f32', 'f32'],
  result: 'vec4f',
  twin: ((
    a: number[],
    b: number[],
    c: number[],
    d: number[],
    mu: number,
    oneMinusMu: number,
    onePlusMu: number,
    xi: number,
  ) => {
    const table = tableFromArgs(a, b, c, d);
    return [
      phaseTabulatedEval(table, mu),
      phaseTabulatedEvalTerms(table, oneMinusMu, onePlusMu),
      phaseTableInterval(table, Math.min(Math.max(oneMinusMu, 0), 2)),
      phaseTableCdfInterval(table, xi),
    ];
  }) as (...args: never[]) => readonly number[],
  tolerance: {
    relative: 2e-5,
    reason:
      'a weight from one f32 subtraction and division of complements (≈ 3 ulp) applied to p_{k+1} − p_k, which is at most a few times p where the nodes resolve the lobe; the interval indices (≤ 511) must agree exactly, which this relative bound enforces',
  },
  wrapper: {
    imports: [
      'PhaseTable',
      'phaseTabulatedEval',
      'phaseTabulatedEvalTerms',
      'phaseTableInterval',
      'phaseTableCdfInterval',
    ],
    wgsl: `fn caseUnderTest(${TABLE_PARAMETERS}, mu: f32, oneMinusMu: f32, onePlusMu: f32, xi: f32) -> vec4f {
${FILL_TABLE}
  return vec4f(
    phaseTabulatedEval(&table, mu),
    phaseTabulatedEvalTerms(&table, oneMinusMu, onePlusMu),
    f32(phaseTableInterval(&table, clamp(oneMinusMu, 0.0, 2.0))),
    f32(phaseTableCdfInterval(&table, xi)),
  );
}`,
  },
  cases: evalCases,
});

const WO: Vec3 = [0.3, -0.5, 0.81].map((c) => Math.fround(c / Math.hypot(0.3, 0.5, 0.81))) as [
  number,
  number,
  number,
];
const XIS = [0, 1e-7, 0.01, 0.25, 0.5, 0.75, 0.97, 0.999, ONE_MINUS_EPSILON_F32, 1];
describeShaderFunction({
  module: 'mie',
  fn: 'phaseTabulatedSampleMu',
  args: [TABLE_TYPE, TABLE_TYPE, TABLE_TYPE, TABLE_TYPE, 'f32', 'f32'],
  result: 'vec4f',
  twin: ((a: number[], b: number[], c: number[], d: number[], xi: number, u1: number) => {
    const table = tableFromArgs(a, b, c, d);
    const s = phaseTabulatedSampleMu(table, xi);
    const sample = phaseTabulatedSample(table, WO, [xi, u1]);
    const w = sample.wi;
    return [s.mu, s.onePlusMu, -(WO[0] * w[0] + WO[1] * w[1] + WO[2] * w[2]), sample.pdf];
  }) as (...args: never[]) => readonly number[],
  tolerance: {
    relative: 1e-4,
    absolute: 2e-6,
    reason:
      'r from one f32 division of CDF differences (the CDF near 1 has 6e-8 spacing, so r moves by ~1e-6 of an interval holding 1e-2 of the mass), a square root and a lerp of node complements; −wo·wi through the frame of directionAroundAxis (a few ulp); the pdf is a lerp of a steep lobe at the sampled complements (relative 1e-4)',
  },
  wrapper: {
    imports: ['PhaseTable', 'phaseTabulatedSampleMu', 'phaseTabulatedSample'],
    wgsl: `fn caseUnderTest(${TABLE_PARAMETERS}, xi: f32, u1: f32) -> vec4f {
${FILL_TABLE}
  let wo = vec3f(${WO.map((c) => c.toPrecision(9)).join(', ')});
  let s = phaseTabulatedSampleMu(&table, xi);
  let sample = phaseTabulatedSample(&table, wo, vec2f(xi, u1));
  return vec4f(s.mu, s.onePlusMu, -dot(wo, sample.wi), sample.pdf);
}`,
  },
  cases: TABLES.flatMap(([name, t]) =>
    XIS.map((xi) => ({
      name: `${name}: ξ = ${xi} (sampleMu, and sample with u = (ξ, 0.3) around an oblique wo)`,
      args: [...tableArgs(t), xi, 0.3],
      ...(xi === 0 ? { expected: [1, 2, 1, Math.fround(t.pdf[0]!)] } : {}),
    })),
  ),
});
