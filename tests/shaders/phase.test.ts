// WGSL phase module vs its float64 twin (physics.md §2), over the published tables:
// the HG values of §2.2 for both signs of g, the HG samples μ(ξ) of §2.4, the
// Rayleigh values of §2.6 and the §2.3 conformance vector. Direction convention:
// the one at the top of shaders/phase.wesl (wo, wi both point away; μ = −wo·wi).
import { describeShaderFunction, type ShaderCase } from '../support/shaderHarness.ts';
import {
  cbrtReal,
  hgEval,
  hgEvalTerms,
  hgSampleMu,
  phaseIsotropic,
  rayleighEval,
  rayleighSample,
  rayleighSampleMu,
  type Vec3,
} from '../../src/reference/phase.ts';
import { ONE_MINUS_EPSILON_F32 } from '../support/f32.ts';
import {
  asVec3,
  AZIMUTH_FREE,
  CBRT_SMALL,
  HG_EVAL_DIRECTIONS,
  HG_SAMPLE_MU,
  HG_VALUE,
  hgSampleWrapper,
  RAYLEIGH_SAMPLED_MU,
  SAMPLED_COMPLEMENTS,
  SAMPLED_MU,
  sampleArgs,
  TRIG_DIRECTION,
  twinHgSample,
  vec,
} from '../support/phaseHarness.ts';

const INV_FOUR_PI = 0.0795774715459477;
// Tolerances (HG_VALUE, SAMPLED_MU, …) are derived in tests/support/phaseHarness.ts.

// ---------------------------------------------------------------------------
// Published values
// ---------------------------------------------------------------------------
const MU_COLUMNS = [1, 0.5, 0, -0.5, -1];
/** physics.md §2.2, exact decimal g (mpmath, 30 digits). */
const HG_TABLE: readonly (readonly [number, readonly number[]])[] = [
  [
    0.3,
    [
      0.211123904101494, 0.103131394790625, 0.0636343747723979, 0.0441885069637756,
      0.0329610828888541,
    ],
  ],
  [
    0.5,
    [
      0.477464829275686, 0.0918881492369653, 0.0427057526050306, 0.0257806775110893,
      0.0176838825657661,
    ],
  ],
  [
    0.76,
    [
      2.43153385279285, 0.0454676723086372, 0.0169636263976477, 0.00940499886809252,
      0.0061656098821757,
    ],
  ],
  [
    0.9,
    [
      15.1197195937301, 0.0174173327314225, 0.00620906025796582, 0.00338914227398196,
      0.00220436209268553,
    ],
  ],
];
/**
 * physics.md §2.2 rows whose exact-decimal g rounds to an f32 that moves p by more
 * than 1e-6 relative (up to 1.7e-4 at g = 0.9999 away from μ = 1): the GPU and the
 * twin see f32(g), so these cells are checked against f32-g values (tests/reference
 * holds the twin to the exact-g values at 1e-12). Only the peaks are published for
 * f32 g (§2.2: 159079.462788454 and 15909417.9679941); the other cells come from
 * hgTextbook below.
 */
const HG_PEAK_F32_G: readonly (readonly [number, number | null])[] = [
  [0.99, null],
  [0.999, 159079.462788454],
  [0.9999, 15909417.9679941],
];

/**
 * HG in its textbook form, float64, at an f32 g: an independent value for the
 * table cells above. In float64 the textbook denominator loses at most
 * 2.2e-16·2/(1 − g)² ≈ 4e-8 relative (g = 0.9999, μ = 1), far below the tolerance.
 */
function hgTextbook(g: number, mu: number): number {
  return (1 - g * g) / (4 * Math.PI * Math.pow(1 + g * g - 2 * g * mu, 1.5));
}

function hgTableCases(): ShaderCase[] {
  const cases: ShaderCase[] = [];
  for (const [g, values] of HG_TABLE) {
    MU_COLUMNS.forEach((mu, k) => {
      const expected = values[k] as number;
      // Mirror: p(−g, −μ) = p(g, μ), the §2.2 rows for g and −g.
      cases.push({ name: `§2.2 g = ${g}, μ = ${mu}`, args: [g, mu], expected });
      cases.push({ name: `§2.2 g = ${-g}, μ = ${-mu} (mirror)`, args: [-g, -mu], expected });
    });
  }
  for (const [g, peak] of HG_PEAK_F32_G) {
    for (const sign of [1, -1]) {
      if (peak !== null)
        cases.push({
          name: `§2.2 g = ${sign * g} (f32-rounded), μ = ${sign}: the published f32-g peak ${peak}`,
          args: [sign * g, sign],
          expected: peak,
        });
      for (const mu of peak === null ? MU_COLUMNS : MU_COLUMNS.slice(1)) {
        cases.push({
          name: `g = ${sign * g} (f32-rounded), μ = ${sign * mu}: textbook float64 at f32 g`,
          args: [sign * g, sign * mu],
          expected: hgTextbook(Math.fround(g), mu),
        });
      }
    }
  }
  return cases;
}

// ---------------------------------------------------------------------------
// Henyey–Greenstein evaluation
// ---------------------------------------------------------------------------
describeShaderFunction({
  module: 'phase',
  fn: 'phaseIsotropic',
  args: ['u32'],
  result: 'f32',
  // phaseIsotropic takes no argument; the harness needs one input to bind.
  wrapper: {
    imports: ['phaseIsotropic'],
    wgsl: 'fn caseUnderTest(_unused: u32) -> f32 { return phaseIsotropic(); }',
  },
  twin: () => phaseIsotropic(),
  tolerance: { ulps: 1, reason: 'a constant rounded once to f32' },
  cases: [{ name: '1/(4π) (§2.1)', args: [0], expected: INV_FOUR_PI }],
});

describeShaderFunction({
  module: 'phase',
  fn: 'hgEval',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: hgEval,
  tolerance: HG_VALUE,
  cases: [
    { name: '§2.2 g = 0 is isotropic, μ = 1', args: [0, 1], expected: INV_FOUR_PI },
    { name: '§2.2 g = 0 is isotropic, μ = −0.3', args: [0, -0.3], expected: INV_FOUR_PI },
    ...hgTableCases(),
    { name: 'g = 0.99, μ = 1 − 2^-20 (near the peak)', args: [0.99, 1 - 2 ** -20] },
    { name: 'g = 0.999, μ = 1 − 2^-24 (next f32 below 1)', args: [0.999, 1 - 2 ** -24] },
    {
      name: 'g = −0.9999, μ = −1 + 2^-23 (near the backward peak)',
      args: [-0.9999, -1 + 2 ** -23],
    },
    { name: 'g = 1e-7 (almost isotropic), μ = 0.7', args: [1e-7, 0.7] },
    { name: 'μ = 1.5 is clamped to 1', args: [0.5, 1.5], expected: 0.477464829275686 },
    { name: 'μ = −3 is clamped to −1', args: [0.5, -3], expected: 0.0176838825657661 },
  ],
});

describeShaderFunction({
  module: 'phase',
  fn: 'hgEvalTerms',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: hgEvalTerms,
  tolerance: HG_VALUE,
  cases: [
    {
      name: 'g = 0.5 at the peak: 1 − μ = 0, 1 + μ = 2',
      args: [0.5, 0, 2],
      expected: 0.477464829275686,
    },
    {
      name: 'g = −0.5 at its peak: 1 − μ = 2, 1 + μ = 0',
      args: [-0.5, 2, 0],
      expected: 0.477464829275686,
    },
    { name: 'g = 0.999, 1 − μ = 5e-9 (directions 1e-4 rad apart)', args: [0.999, 5e-9, 2] },
    {
      name: 'g = 0.9999, 1 − μ = 1e-10: keeps digits a μ input would lose',
      args: [0.9999, 1e-10, 2],
    },
    { name: 'g = −0.9999, 1 + μ = 1e-10', args: [-0.9999, 2, 1e-10] },
    {
      name: 'g = 0.9, 1 − μ = 2: the far tail (§2.2 μ = −1)',
      args: [0.9, 2, 0],
      expected: 0.00220436209268553,
    },
    {
      name: 'g = 0.3, complement 0.5 (§2.2 μ = 0.5)',
      args: [0.3, 0.5, 1.5],
      expected: 0.103131394790625,
    },
  ],
});

// Vector arguments go through a wrapper (the harness passes array<f32, 3>).
const normalize = (v: readonly number[]): Vec3 => {
  const length = Math.hypot(v[0] ?? 0, v[1] ?? 0, v[2] ?? 0);
  return [(v[0] ?? 0) / length, (v[1] ?? 0) / length, (v[2] ?? 0) / length];
};
const f32Vec = (v: readonly number[]): Vec3 => asVec3(v.map(Math.fround));

// §9 row 5: directions 1e-4 rad apart, as f32 vectors.
const ANGLE = 1e-4;
const NEAR_WO: Vec3 = [0, 0, 1];
const NEAR_WI: Vec3 = f32Vec([-Math.sin(ANGLE), 0, -Math.cos(ANGLE)]);
const OBLIQUE_WO = normalize([0.3, -0.5, 0.81]);
const OBLIQUE_WI = normalize([-0.6, 0.2, 0.77]);

describeShaderFunction({
  ...HG_EVAL_DIRECTIONS,
  tolerance: HG_VALUE,
  cases: [
    {
      name: '§2.3 conformance: wo = (0,0,1), wi = (0,0,−1) is the forward peak, g = 0.5',
      args: [0.5, [0, 0, 1], [0, 0, -1]],
      expected: 0.477464829275686,
    },
    {
      name: '§2.3 conformance with g = −0.5: the same pair is the backward tail',
      args: [-0.5, [0, 0, 1], [0, 0, -1]],
      expected: 0.0176838825657661,
    },
    {
      name: 'wi = wo is backscattering (μ = −1), g = 0.5',
      args: [0.5, [0, 0, 1], [0, 0, 1]],
      expected: 0.0176838825657661,
    },
    {
      name: 'perpendicular directions are μ = 0, g = 0.3',
      args: [0.3, [1, 0, 0], [0, 1, 0]],
      expected: 0.0636343747723979,
    },
    {
      name: '§9 row 5: g = 0.999, directions 1e-4 rad apart (f32)',
      args: [0.999, NEAR_WO, NEAR_WI],
    },
    { name: 'oblique pair, g = 0.76', args: [0.76, OBLIQUE_WO, OBLIQUE_WI] },
    { name: 'oblique pair, g = −0.9', args: [-0.9, OBLIQUE_WO, OBLIQUE_WI] },
  ],
});

// ---------------------------------------------------------------------------
// Henyey–Greenstein sampling
// ---------------------------------------------------------------------------
const XI_COLUMNS = [0, 0.1, 0.25, 0.5, 0.75, 0.9, 1];
/** physics.md §2.4 reference samples μ(ξ), textbook mapping (ξ = 0 → μ = −1). */
const MU_SAMPLES: readonly (readonly [number, readonly number[]])[] = [
  [
    0.3,
    [-1, -0.572818559556787, -0.093598615916955, 0.4365, 0.773062381852552, 0.919055671175858, 1],
  ],
  [
    -0.3,
    [-1, -0.919055671175858, -0.773062381852552, -0.4365, 0.093598615916955, 0.572818559556787, 1],
  ],
  [
    0.9,
    [-1, 0.749744897959184, 0.939256198347107, 0.9855, 0.996016646848989, 0.998776365603029, 1],
  ],
  [
    0.999,
    [-1, 0.999950898100824, 0.999992516474534, 0.9999985005, 0.9999996110185, 0.999999882667332, 1],
  ],
  [
    1e-7,
    [-1, -0.799999945999994, -0.499999887499992, 1.5e-7, 0.500000112499993, 0.800000053999994, 1],
  ],
];

const muSampleCases: ShaderCase[] = [
  ...MU_SAMPLES.flatMap(([g, mus]) =>
    XI_COLUMNS.map((xi, k) => ({
      name: `§2.4 g = ${g}, ξ = ${xi}`,
      args: sampleArgs(g, xi),
      expected: mus[k] as number,
    })),
  ),
  ...[-0.9, -0.5, 0, 0.5, 0.76].map((g) => ({
    name: `median μ(½) = g(3 − g²)/2 at g = ${g} (§2.4)`,
    args: sampleArgs(g, 0.5),
    expected: (Math.fround(g) * (3 - Math.fround(g) ** 2)) / 2,
  })),
  {
    name: 'g = 0.9999, ξ = 0 gives −1 exactly (§9 row 7)',
    args: sampleArgs(0.9999, 0),
    expected: -1,
  },
  {
    name: 'g = −0.999, ξ = 1 − 2^-24 (§2.4 table: 0.999523719)',
    args: sampleArgs(-0.999, ONE_MINUS_EPSILON_F32),
    expected: 0.999523719,
  },
  { name: 'g = 0.999, ξ = 1 − 2^-24 stays ≤ 1', args: sampleArgs(0.999, ONE_MINUS_EPSILON_F32) },
  { name: 'g = 0 is 2ξ − 1 with no special case', args: sampleArgs(0, 0.3), expected: -0.4 },
];

describeShaderFunction({
  ...HG_SAMPLE_MU,
  tolerance: SAMPLED_MU,
  cases: muSampleCases,
});

describeShaderFunction({
  module: 'phase',
  fn: 'hgSampleMu',
  args: ['f32', 'f32', 'f32'],
  result: 'vec2f',
  wrapper: {
    imports: ['hgSampleMu'],
    wgsl: `fn caseUnderTest(g: f32, xi: f32, oneMinusXi: f32) -> vec2f {
  let s = hgSampleMu(g, xi, oneMinusXi);
  return vec2f(s.oneMinusMu, s.onePlusMu);
}`,
  },
  twin: (g: number, xi: number, oneMinusXi: number) => {
    const s = hgSampleMu(g, xi, oneMinusXi);
    return [s.oneMinusMu, s.onePlusMu];
  },
  tolerance: SAMPLED_COMPLEMENTS,
  cases: [
    ...MU_SAMPLES.flatMap(([g]) =>
      XI_COLUMNS.map((xi) => ({
        name: `complements (1 − μ, 1 + μ) at g = ${g}, ξ = ${xi}`,
        args: sampleArgs(g, xi),
      })),
    ),
    {
      name: 'g = 0.9999, ξ = 1 − 2^-24: 1 − μ ≈ 1e-15 keeps its digits',
      args: sampleArgs(0.9999, ONE_MINUS_EPSILON_F32),
    },
    {
      name: 'g = −0.9999, ξ = 2^-24: 1 + μ ≈ 1e-15 keeps its digits',
      args: sampleArgs(-0.9999, 2 ** -24),
    },
  ],
});

const SAMPLE_WOS: readonly Vec3[] = [
  [0, 0, 1],
  [0, 0, -1],
  OBLIQUE_WO,
  normalize([-0.9, 0.1, -0.05]),
];
const SAMPLE_US: readonly (readonly [number, number])[] = [
  [0.5, 0.5],
  [0.1, 0.9],
  [0.97, 0.03],
  [0, 0.25],
  [ONE_MINUS_EPSILON_F32, 0.75],
];

function directionCases(gs: readonly number[]): ShaderCase[] {
  const cases: ShaderCase[] = [];
  for (const g of gs)
    SAMPLE_WOS.forEach((wo, w) =>
      SAMPLE_US.forEach((u) =>
        cases.push({
          name: `g = ${g}, wo #${w}, u = (${u[0]}, ${u[1]})`,
          args: [g, wo, u[0], u[1]],
        }),
      ),
    );
  return cases;
}

const HG_DIRECTION_GS = [0, 0.3, -0.7, 0.9, 0.999];

describeShaderFunction({
  module: 'phase',
  fn: 'hgSample',
  args: ['f32', 'f32[3]', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: hgSampleWrapper('return s.wi;', 'vec3f'),
  twin: (g: number, wo: readonly number[], u0: number, u1: number) =>
    twinHgSample(g, wo, u0, u1).wi,
  tolerance: TRIG_DIRECTION,
  cases: directionCases(HG_DIRECTION_GS),
});

describeShaderFunction({
  module: 'phase',
  fn: 'hgSample',
  args: ['f32', 'f32[3]', 'f32', 'f32'],
  result: 'vec2f',
  // μ = −wo·wi and |wi|² do not depend on the azimuth, so they are held tightly.
  wrapper: hgSampleWrapper('return vec2f(-dot(w, s.wi), dot(s.wi, s.wi));', 'vec2f'),
  twin: (g: number, wo: readonly number[], u0: number, u1: number) => {
    const { wi } = twinHgSample(g, wo, u0, u1);
    return [
      -(wo[0]! * wi[0] + wo[1]! * wi[1] + wo[2]! * wi[2]),
      wi[0] ** 2 + wi[1] ** 2 + wi[2] ** 2,
    ];
  },
  tolerance: AZIMUTH_FREE,
  cases: directionCases(HG_DIRECTION_GS),
});

describeShaderFunction({
  module: 'phase',
  fn: 'hgSample',
  args: ['f32', 'f32[3]', 'f32', 'f32'],
  result: 'f32',
  wrapper: hgSampleWrapper('return s.pdf;', 'f32'),
  twin: (g: number, wo: readonly number[], u0: number, u1: number) =>
    twinHgSample(g, wo, u0, u1).pdf,
  tolerance: HG_VALUE,
  cases: [
    ...directionCases(HG_DIRECTION_GS),
    {
      name: 'g = 0.5, u.x = 1 − 2^-24 samples the peak: pdf ≈ 0.4775',
      args: [0.5, [0, 0, 1], ONE_MINUS_EPSILON_F32, 0.5],
    },
  ],
});

// ---------------------------------------------------------------------------
// Rayleigh
// ---------------------------------------------------------------------------
describeShaderFunction({
  module: 'phase',
  fn: 'rayleighEval',
  args: ['f32'],
  result: 'f32',
  twin: rayleighEval,
  // 3/(16π) rounded once, 1 + μ², one product: ≤ 3 ULP.
  tolerance: { ulps: 4, reason: 'a rounded constant times 1 + μ²: ≤ 3 ULP' },
  cases: [
    { name: '§2.6 p(0)', args: [0], expected: 0.0596831036594608 },
    { name: '§2.6 p(1)', args: [1], expected: 0.119366207318922 },
    { name: '§2.6 p(−1)', args: [-1], expected: 0.119366207318922 },
    { name: 'p(0.5) = 3/(16π)·1.25', args: [0.5], expected: (3 / (16 * Math.PI)) * 1.25 },
    { name: 'μ = 2 is clamped to 1', args: [2], expected: 0.119366207318922 },
  ],
});

describeShaderFunction({
  module: 'phase',
  fn: 'cbrtReal',
  args: ['f32'],
  result: 'f32',
  twin: cbrtReal,
  tolerance: CBRT_SMALL,
  cases: [
    { name: '∛0 = 0 without log2(0)', args: [0], expected: 0 },
    { name: '∛8 = 2', args: [8], expected: 2 },
    { name: '∛−8 = −2: negative radicand (§9 row 25)', args: [-8], expected: -2 },
    { name: '∛(2 − √5): the Cardano radicand at ξ = 1 (§2.6)', args: [2 - Math.sqrt(5)] },
    { name: '∛(−2 − √5) at ξ = 0', args: [-2 - Math.sqrt(5)] },
    { name: '∛−1e-6', args: [-1e-6], expected: -0.01 },
    { name: '∛−0.5', args: [-0.5] },
    {
      name: '∛−1e30 (large magnitude)',
      args: [-1e30],
      expected: -1e10,
      tolerance: { relative: 2e-5, reason: 'WGSL log2 3 ULP of log2(1e30) ≈ 100, through exp2' },
    },
  ],
});

describeShaderFunction({
  module: 'phase',
  fn: 'rayleighSampleMu',
  args: ['f32'],
  result: 'f32',
  twin: rayleighSampleMu,
  tolerance: RAYLEIGH_SAMPLED_MU,
  cases: [
    { name: 'ξ = 0 gives μ = −1', args: [0], expected: -1 },
    { name: 'ξ = ½ gives μ = 0 (symmetric)', args: [0.5], expected: 0 },
    { name: 'ξ = 1 gives μ = 1 (clamped against rounding)', args: [1], expected: 1 },
    { name: 'ξ = 1 − 2^-24', args: [ONE_MINUS_EPSILON_F32] },
    ...[0.05, 0.1, 0.25, 0.4, 0.6, 0.75, 0.9, 0.99].map((xi) => ({
      name: `ξ = ${xi}: solves (μ³ + 3μ + 4)/8 = ξ (§2.6)`,
      args: [xi],
    })),
  ],
});

const RAYLEIGH_WRAPPER = (body: string, result: string) => ({
  imports: ['rayleighSample'],
  wgsl: `fn caseUnderTest(wo: array<f32, 3>, u0: f32, u1: f32) -> ${result} {
  let w = ${vec('wo')};
  let s = rayleighSample(w, vec2f(u0, u1));
  ${body}
}`,
});
const rayleighCases: ShaderCase[] = SAMPLE_WOS.flatMap((wo, w) =>
  SAMPLE_US.map((u) => ({ name: `wo #${w}, u = (${u[0]}, ${u[1]})`, args: [wo, u[0], u[1]] })),
);
const twinRayleigh = (wo: readonly number[], u0: number, u1: number) =>
  rayleighSample(asVec3(wo), [u0, u1]);

describeShaderFunction({
  module: 'phase',
  fn: 'rayleighSample',
  args: ['f32[3]', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: RAYLEIGH_WRAPPER('return s.wi;', 'vec3f'),
  twin: (wo: readonly number[], u0: number, u1: number) => twinRayleigh(wo, u0, u1).wi,
  tolerance: TRIG_DIRECTION,
  cases: rayleighCases,
});

describeShaderFunction({
  module: 'phase',
  fn: 'rayleighSample',
  args: ['f32[3]', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: RAYLEIGH_WRAPPER('return vec3f(-dot(w, s.wi), dot(s.wi, s.wi), s.pdf);', 'vec3f'),
  twin: (wo: readonly number[], u0: number, u1: number) => {
    const { wi, pdf } = twinRayleigh(wo, u0, u1);
    return [
      -(wo[0]! * wi[0] + wo[1]! * wi[1] + wo[2]! * wi[2]),
      wi[0] ** 2 + wi[1] ** 2 + wi[2] ** 2,
      pdf,
    ];
  },
  // μ inherits the cube roots' 4e-6; |wi|² and the pdf (≤ 0.12) are O(1) roundings.
  tolerance: { absolute: 6e-6, reason: 'μ from two WGSL cube roots (4e-6) plus O(1) roundings' },
  cases: rayleighCases,
});
