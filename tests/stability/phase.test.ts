// Hard cases of physics.md §9 that concern phase functions (rows 1–9, 24, 25),
// each run in both implementations (WGSL through Dawn, and the float64 twin),
// with what goes wrong otherwise shown on float32 emulations of the naive forms;
// then a fuzz over f32 extremes: never NaN or Inf, μ ∈ [−1, 1], p ≥ 0.
// Direction convention: the one at the top of shaders/phase.wesl.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  describeShaderFunction,
  evaluateTable,
  type ShaderCase,
  type Tolerance,
} from '../support/shaderHarness.ts';
import {
  cbrtReal,
  HG_MAX_ABS_G,
  hgEval,
  hgEvalDirections,
  hgEvalTerms,
  hgSample,
  hgSampleMu,
  rayleighEval,
  rayleighSample,
  rayleighSampleMu,
  type Vec3,
} from '../../src/reference/phase.ts';
import {
  F32_MAX,
  F32_MIN_NORMAL,
  F32_MIN_SUBNORMAL,
  ONE_MINUS_EPSILON_F32,
} from '../support/f32.ts';
import {
  asVec3,
  CBRT_SMALL,
  HG_EVAL_DIRECTIONS,
  HG_SAMPLE_MU,
  HG_VALUE,
  hgSampleWrapper,
  RAYLEIGH_SAMPLED_MU,
  SAMPLED_MU,
  sampleArgs,
  twinHgSample,
  vec,
} from '../support/phaseHarness.ts';

// Tolerances: the budgets derived in tests/support/phaseHarness.ts (physics.md §10).
const EXACT: Tolerance = {
  ulps: 0,
  reason: 'the zero complement is exactly 0, so μ = ∓1 exactly (§2.4)',
};

const f = Math.fround;
const G_MAX = HG_MAX_ABS_G;
/** HG endpoint closed forms (§2.2): p(1) = (1+g)/(4π(1−g)²), p(−1) = (1−g)/(4π(1+g)²). */
const hgForwardPeak = (g: number): number => (1 + g) / (4 * Math.PI * (1 - g) ** 2);
const hgBackwardTail = (g: number): number => (1 - g) / (4 * Math.PI * (1 + g) ** 2);

/** The textbook HG value with every operation rounded to f32 (numpy-style, §2.5). */
function naiveHgF32(g: number, mu: number): number {
  const denominator = f(f(1 + f(g * g)) - f(f(2 * g) * mu));
  return f(f(1 - f(g * g)) / f(f(4 * f(Math.PI)) * f(denominator ** 1.5)));
}

/** The textbook HG inverse CDF with every operation rounded to f32 (§2.4). */
function textbookSampleF32(g: number, xi: number): number {
  const ratio = f(f(1 - f(g * g)) / f(f(1 - g) + f(f(2 * g) * xi)));
  return f(f(1 / f(2 * g)) * f(f(1 + f(g * g)) - f(ratio * ratio)));
}

// ---------------------------------------------------------------------------
// Rows 1–5: HG evaluation
// ---------------------------------------------------------------------------
const FORWARD_PAIR: [Vec3, Vec3] = [
  [0, 0, 1],
  [0, 0, -1],
];
// Row 5: directions 1e-4 rad apart, stored as f32 vectors (wi = −wo tilted by 1e-4).
const TILTED_WI: Vec3 = [f(-Math.sin(1e-4)), 0, f(-Math.cos(1e-4))];
/** HG at f32(0.999) for the exact angle between (0,0,1) and the f32 TILTED_WI. */
const ROW5_EXPECTED = (() => {
  const angle = Math.atan2(-TILTED_WI[0], -TILTED_WI[2]);
  const oneMinusMu = 2 * Math.sin(angle / 2) ** 2;
  const g = f(0.999);
  return ((1 - g) * (1 + g)) / (4 * Math.PI * ((1 - g) ** 2 + 2 * g * oneMinusMu) ** 1.5);
})();

describeShaderFunction({
  module: 'phase',
  fn: 'hgEval',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: hgEval,
  tolerance: HG_VALUE,
  cases: [
    {
      name: '§9 row 1: g = 0.999, μ = 1 → 159079.462788 for f32(0.999) (exact g: 159075.365620349)',
      args: [0.999, 1],
      expected: 159079.462788454,
    },
    {
      name: '§9 row 2: g = 0.9999, μ = 1 → 15909417.968 for f32 g (the naive f32 denominator is 0)',
      args: [0.9999, 1],
      expected: 15909417.9679941,
    },
    {
      name: '§9 row 3: g = 0.999, μ = −1 (far tail; 1.99142771851027e-5 at exact g, here at f32 g)',
      args: [0.999, -1],
      expected: hgBackwardTail(f(0.999)),
    },
    {
      name: '§9 row 3: g = −0.999, μ = +1 is the same far tail (sign-convention check)',
      args: [-0.999, 1],
      expected: hgBackwardTail(f(0.999)),
    },
    ...[-1, -0.3, 0, 0.5, 1].map((mu) => ({
      name: `§9 row 4: g = 0, μ = ${mu} → 1/(4π)`,
      args: [0, mu],
      expected: 0.0795774715459477,
    })),
    {
      name: '§9 row 24: g = 1 (a delta) is clamped to HG_MAX_ABS_G: finite forward peak ≈ 1.6e9',
      args: [1, 1],
      expected: hgForwardPeak(G_MAX),
    },
    {
      name: '§9 row 24: g = −1 is clamped to −HG_MAX_ABS_G: finite backward peak',
      args: [-1, -1],
      expected: hgForwardPeak(G_MAX),
    },
    {
      name: '§9 row 24: g = 1, μ = −1: the clamped lobe’s tail',
      args: [1, -1],
      expected: hgBackwardTail(G_MAX),
    },
    {
      name: '§9 row 24: g = 7 (out of range) behaves as the clamp',
      args: [7, 0.3],
      expected: hgEval(G_MAX, f(0.3)),
    },
  ],
});

describeShaderFunction({
  ...HG_EVAL_DIRECTIONS,
  tolerance: HG_VALUE,
  cases: [
    {
      name: '§9 row 1 with vectors: g = 0.999, wo = (0,0,1), wi = (0,0,−1) (dot = −1, forward)',
      args: [0.999, ...FORWARD_PAIR],
      expected: 159079.462788454,
    },
    {
      name: '§9 row 5: g = 0.999, directions 1e-4 rad apart → ≈ 156725 for f32 g (156721.045 at exact g), not the 159079 of f32 1 − dot',
      args: [0.999, FORWARD_PAIR[0], TILTED_WI],
      expected: ROW5_EXPECTED,
    },
  ],
});

describe('§9 rows 1, 2, 5: what goes wrong otherwise (float32 emulation of the naive forms)', () => {
  it('row 1: the textbook denominator in f32 is 10% low at g = 0.999, μ = 1 (143141.5)', () => {
    const naive = naiveHgF32(f(0.999), 1);
    expect(naive / 159079.462788454 - 1).toBeLessThan(-0.09);
    expect(Math.abs(hgEval(f(0.999), 1) / 159079.462788454 - 1)).toBeLessThan(1e-12);
  });

  it('row 2: the textbook denominator in f32 is exactly 0 at g = 0.9999, μ = 1', () => {
    expect(f(f(1 + f(f(0.9999) ** 2)) - f(2 * f(0.9999)))).toBe(0);
    expect(Number.isFinite(naiveHgF32(f(0.9999), 1))).toBe(false);
  });

  it('row 5: 1 − dot in f32 rounds to 0 and gives the peak 159079 (+1.5%), ½|wo + wi|² keeps 5e-9', () => {
    const dot = f(FORWARD_PAIR[0][2] * TILTED_WI[2]);
    expect(f(1 + dot)).toBe(0);
    const viaDot = hgEvalTerms(f(0.999), f(1 + dot), 2);
    expect(viaDot / ROW5_EXPECTED - 1).toBeGreaterThan(0.014);
    const robust = hgEvalDirections(f(0.999), FORWARD_PAIR[0], TILTED_WI);
    expect(Math.abs(robust / ROW5_EXPECTED - 1)).toBeLessThan(1e-8);
  });
});

// ---------------------------------------------------------------------------
// Rows 6–9, 24: HG sampling
// ---------------------------------------------------------------------------
const endpointCases: ShaderCase[] = [-0.9999, -0.5, 0, 1e-7, 0.3, 0.999, 0.9999].flatMap((g) => [
  {
    name: `§9 row 7: g = ${g}, ξ = 0 → μ = −1 exactly`,
    args: sampleArgs(g, 0),
    expected: -1,
    tolerance: EXACT,
  },
  {
    name: `§9 row 7: g = ${g}, ξ = 1 → μ = +1 exactly`,
    args: sampleArgs(g, 1),
    expected: 1,
    tolerance: EXACT,
  },
]);

describeShaderFunction({
  ...HG_SAMPLE_MU,
  tolerance: SAMPLED_MU,
  cases: [
    {
      name: '§9 row 6: g = 1e-7, ξ = 0.25 → μ = −0.4999998875 (≈ 2ξ − 1; the f32 textbook gives −1.19)',
      args: sampleArgs(1e-7, 0.25),
      expected: -0.4999998875,
    },
    ...endpointCases,
    {
      name: '§9 row 7: g = 0.999, ξ = 1 − 2^-24 stays ≤ 1 (the symmetric form can give 1 + 1 ulp)',
      args: sampleArgs(0.999, ONE_MINUS_EPSILON_F32),
    },
    {
      name: '§9 row 8: g = 0.9, ξ = ½ → median g(3 − g²)/2 = 0.9855',
      args: sampleArgs(0.9, 0.5),
      expected: 0.9855,
    },
    {
      name: '§9 row 8: g = −0.9, ξ = ½ → −0.9855',
      args: sampleArgs(-0.9, 0.5),
      expected: -0.9855,
    },
    {
      name: '§9 row 24: g = 1 is clamped: ξ = ½ gives the median of the clamped lobe',
      args: sampleArgs(1, 0.5),
      expected: (G_MAX * (3 - G_MAX * G_MAX)) / 2,
    },
    {
      name: '§9 row 24: g = −1 is clamped: ξ = ½ gives the mirrored median',
      args: sampleArgs(-1, 0.5),
      expected: (-G_MAX * (3 - G_MAX * G_MAX)) / 2,
    },
  ],
});

// Row 9: the mean of μ over 4096 stratified ξ_k = (k + ½)/4096 is g. Summed in
// 64 blocks of 64 on the GPU: each block sum (≤ 64) carries ≤ 63·ulp(64)/2 =
// 2.4e-4, scaled by 1/4096, and 64 additions of partial means ≤ 1 add ≤ 64·2^-24:
// ≤ 7.6e-6 worst case against the float64 twin. The midpoint rule itself is off by
// 1.8e-7 at |g| = 0.9 and 1.8e-5 at g = 0.999 (steep μ(ξ) near ξ = 0).
const STRATA = 4096;
const stratifiedMeanTwin = (g: number): number => {
  let sum = 0;
  for (let k = 0; k < STRATA; k++) {
    const xi = f((k + 0.5) / STRATA);
    sum += hgSampleMu(g, xi, f(1 - xi)).mu;
  }
  return sum / STRATA;
};
describeShaderFunction({
  module: 'phase',
  fn: 'hgSampleMu',
  args: ['f32'],
  result: 'f32',
  wrapper: {
    imports: ['hgSampleMu'],
    wgsl: `fn caseUnderTest(g: f32) -> f32 {
  var mean = 0.0;
  for (var block = 0u; block < 64u; block++) {
    var sum = 0.0;
    for (var k = 0u; k < 64u; k++) {
      let xi = (f32(block * 64u + k) + 0.5) / ${STRATA}.0;
      sum += hgSampleMu(g, xi, 1.0 - xi).mu;
    }
    mean += sum / ${STRATA}.0;
  }
  return mean;
}`,
  },
  twin: stratifiedMeanTwin,
  tolerance: {
    absolute: 1e-5,
    reason: 'f32 sums of 4096 terms (≤ 7.6e-6) + midpoint rule (≤ 1.8e-7)',
  },
  cases: [
    ...[-0.9, -0.5, 0, 0.5, 0.9].map((g) => ({
      name: `§9 row 9: ⟨μ⟩ = g over stratified ξ, g = ${g} (a sign error gives −g)`,
      args: [g],
      expected: f(g),
    })),
    {
      name: '§9 row 9: ⟨μ⟩ = g at g = 0.999',
      args: [0.999],
      expected: f(0.999),
      tolerance: { absolute: 3e-5, reason: 'midpoint rule 1.8e-5 at g = 0.999 + f32 sums 7.6e-6' },
    },
  ],
});

describe('§9 row 7 over a sweep of g: the endpoints are exact on both sides', () => {
  // The complement that is not 0 at an endpoint is 2(1 ± g)²·…/D², which rounds
  // to 2 ± 1 ulp for many f32 g (e.g. g = 0.058, 0.104, 0.15): μ must then come
  // from the complement that is exactly 0, as §2.4 prescribes.
  const gs = Array.from({ length: 199 }, (_, k) => (k - 99) / 100);
  it('ξ = 0 → μ = −1 and ξ = 1 → μ = +1 exactly for g = −0.99, −0.98, …, 0.99', async () => {
    const outcomes = await evaluateTable({
      ...HG_SAMPLE_MU,
      tolerance: EXACT,
      cases: gs.flatMap((g) => [
        { name: `g = ${g}, ξ = 0`, args: sampleArgs(g, 0) },
        { name: `g = ${g}, ξ = 1`, args: sampleArgs(g, 1) },
      ]),
    });
    outcomes.forEach(({ gpu, twin }, i) => {
      const expected = i % 2 === 0 ? -1 : 1;
      const g = gs[Math.floor(i / 2)];
      expect(gpu[0], `GPU, g = ${g}`).toBe(expected);
      expect(twin[0], `twin, g = ${g}`).toBe(expected);
    });
  });
});

describe('§9 rows 6, 7: what goes wrong otherwise (float32 textbook inverse CDF)', () => {
  it('row 6: g = 1e-7, ξ = 0.25 gives −1.19 (outside [−1, 1]) in f32, the robust form −0.49999989', () => {
    expect(textbookSampleF32(f(1e-7), 0.25)).toBeLessThan(-1.1);
    expect(Math.abs(hgSampleMu(f(1e-7), 0.25, 0.75).mu + 0.4999998875)).toBeLessThan(1e-9);
  });

  it('row 7: g = 0.9999, ξ = 0 gives −1.0002 in f32 (NaN in sin θ without a guard); the robust form −1', () => {
    expect(textbookSampleF32(f(0.9999), 0)).toBeLessThan(-1);
    expect(hgSampleMu(f(0.9999), 0, 1).mu).toBe(-1);
  });
});

describeShaderFunction({
  module: 'phase',
  fn: 'hgSample',
  args: ['f32', 'f32', 'f32'],
  result: 'vec2f',
  wrapper: {
    imports: ['hgSample'],
    wgsl: `fn caseUnderTest(g: f32, u0: f32, u1: f32) -> vec2f {
  let s = hgSample(g, vec3f(0.0, 0.0, 1.0), vec2f(u0, u1));
  return vec2f(s.wi.z, s.pdf);
}`,
  },
  twin: (g: number, u0: number, u1: number) => {
    const s = hgSample(g, [0, 0, 1], [u0, u1]);
    return [s.wi[2], s.pdf];
  },
  tolerance: HG_VALUE,
  cases: [
    {
      name: '§9 row 24: g = 1, ξ → 1 samples straight on (wi.z = −1 for wo = +z) with the finite clamped peak pdf',
      args: [1, ONE_MINUS_EPSILON_F32, 0.5],
      expected: [-1, hgForwardPeak(G_MAX)],
    },
    {
      name: '§9 row 24: g = −1, ξ = 0 samples straight back (wi = wo) with a finite pdf',
      args: [-1, 0, 0.5],
      expected: [1, hgForwardPeak(G_MAX)],
    },
  ],
});

// ---------------------------------------------------------------------------
// Row 25: Rayleigh through a real cube root
// ---------------------------------------------------------------------------
/** The root of (μ³ + 3μ + 4)/8 = ξ by bisection: independent of both implementations. */
function rayleighRootByBisection(xi: number): number {
  let lo = -1;
  let hi = 1;
  for (let i = 0; i < 200; i++) {
    const mid = (lo + hi) / 2;
    if ((mid ** 3 + 3 * mid + 4) / 8 < xi) lo = mid;
    else hi = mid;
  }
  return (lo + hi) / 2;
}

describeShaderFunction({
  module: 'phase',
  fn: 'rayleighSampleMu',
  args: ['f32'],
  result: 'f32',
  twin: rayleighSampleMu,
  tolerance: RAYLEIGH_SAMPLED_MU,
  cases: [0, 0.01, 0.1, 0.25, 0.5, 0.75, 0.9, ONE_MINUS_EPSILON_F32, 1].map((xi) => ({
    name: `§9 row 25: ξ = ${xi}, the radicand z − √(z²+1) < 0 needs ∛ of a negative number`,
    args: [xi],
    expected: rayleighRootByBisection(f(xi)),
  })),
});

describeShaderFunction({
  module: 'phase',
  fn: 'cbrtReal',
  args: ['f32'],
  result: 'f32',
  twin: cbrtReal,
  tolerance: CBRT_SMALL,
  cases: [
    {
      name: '§9 row 25: ∛−8 = −2 (pow(−8, 1/3) is NaN or indeterminate)',
      args: [-8],
      expected: -2,
    },
    {
      name: '§9 row 25: ∛−(2 + √5) = −φ (golden ratio), ξ = 0',
      args: [-2 - Math.sqrt(5)],
      expected: -(1 + Math.sqrt(5)) / 2,
    },
    {
      name: '§9 row 25: ∛(2 − √5) = 1 − φ, ξ = 1',
      args: [2 - Math.sqrt(5)],
      expected: (1 - Math.sqrt(5)) / 2,
    },
    { name: '∛0 = 0 (no log2(0))', args: [0], expected: 0 },
    {
      name: '∛ of the smallest subnormal is finite (the GPU may flush it to 0 first)',
      args: [-F32_MIN_SUBNORMAL],
      tolerance: {
        absolute: 2.3e-13,
        reason: 'WGSL may flush subnormals to 0; ∛ of any subnormal is below ∛2^-126 ≈ 2.3e-13',
      },
    },
  ],
});

describe('§9 row 25: what goes wrong otherwise', () => {
  it('pow of a negative base with exponent 1/3 is NaN (IEEE, numpy; indeterminate in WGSL)', () => {
    expect(Number.isNaN(Math.pow(-8, 1 / 3))).toBe(true);
    expect(cbrtReal(-8)).toBe(-2);
  });
});

// ---------------------------------------------------------------------------
// Fuzz over f32 extremes, both implementations
// ---------------------------------------------------------------------------
const EXTREME_G = [
  0,
  -0,
  F32_MIN_SUBNORMAL,
  -F32_MIN_SUBNORMAL,
  F32_MIN_NORMAL,
  -F32_MIN_NORMAL,
  1e-7,
  -1e-7,
  0.99999,
  -0.99999,
  ONE_MINUS_EPSILON_F32,
  -ONE_MINUS_EPSILON_F32,
  1,
  -1,
  1.5,
  -3,
  F32_MAX,
  -F32_MAX,
];
const EXTREME_XI = [0, F32_MIN_SUBNORMAL, F32_MIN_NORMAL, 2 ** -24, 0.5, ONE_MINUS_EPSILON_F32, 1];
const EXTREME_MU = [
  -1,
  -ONE_MINUS_EPSILON_F32,
  -0,
  0,
  F32_MIN_SUBNORMAL,
  1 - 2 ** -24,
  1,
  -2,
  2,
  F32_MAX,
];

const gArbitrary = fc.oneof(
  fc.constantFrom(...EXTREME_G),
  fc.float({ min: -1, max: 1, noNaN: true }),
  fc.float({ noNaN: true, noDefaultInfinity: true }),
);
const xiArbitrary = fc.oneof(
  fc.constantFrom(...EXTREME_XI),
  fc.float({ min: 0, max: 1, noNaN: true }),
);
const muArbitrary = fc.oneof(
  fc.constantFrom(...EXTREME_MU),
  fc.float({ min: -1, max: 1, noNaN: true }),
);
const unitVector = fc
  .oneof(
    fc.constantFrom<Vec3>([0, 0, 1], [0, 0, -1], [1, 0, 0], [0, -1, 0], [-0, -0, -1], [0, 0, -0]),
    fc.tuple(
      fc.float({ min: -1, max: 1, noNaN: true }),
      fc.float({ min: -1, max: 1, noNaN: true }),
      fc.float({ min: -1, max: 1, noNaN: true }),
    ),
  )
  .map((v): Vec3 => {
    const n = Math.hypot(...v);
    return n > 1e-3 ? [v[0] / n, v[1] / n, v[2] / n] : [0, 0, 1];
  });
const SEED = 20261124;
const FUZZ_RUNS = 512;
const isFiniteAll = (values: readonly number[]): boolean => values.every(Number.isFinite);

describe('fuzz over f32 extremes: never NaN or Inf, μ ∈ [−1, 1], p ≥ 0 (WGSL and twin)', () => {
  it(`hgEval and hgEvalTerms: ${FUZZ_RUNS} (g, μ) and (g, 1 − μ, 1 + μ) triples`, async () => {
    const pairs = fc.sample(fc.tuple(gArbitrary, muArbitrary), { numRuns: FUZZ_RUNS, seed: SEED });
    const evals = await evaluateTable({
      module: 'phase',
      fn: 'hgEval',
      args: ['f32', 'f32'],
      result: 'f32',
      twin: hgEval,
      tolerance: HG_VALUE,
      cases: pairs.map(([g, mu], i) => ({ name: `fuzz ${i}`, args: [g, mu] })),
    });
    const terms = fc.sample(fc.tuple(gArbitrary, muArbitrary, muArbitrary), {
      numRuns: FUZZ_RUNS,
      seed: SEED + 1,
    });
    const termEvals = await evaluateTable({
      module: 'phase',
      fn: 'hgEvalTerms',
      args: ['f32', 'f32', 'f32'],
      result: 'f32',
      twin: hgEvalTerms,
      tolerance: HG_VALUE,
      // Complements are ≥ 0 by construction; |x| keeps 0, subnormals, 2 and F32_MAX.
      cases: terms.map(([g, a, b], i) => ({
        name: `fuzz ${i}`,
        args: [g, Math.abs(a), Math.abs(b)],
      })),
    });
    for (const [i, outcome] of [...evals, ...termEvals].entries()) {
      const values = [...outcome.gpu, ...outcome.twin];
      expect(
        isFiniteAll(values) && values.every((p) => p >= 0),
        `case ${i}: ${values.join(', ')}`,
      ).toBe(true);
    }
  });

  it(`hgSampleMu: ${FUZZ_RUNS} (g, ξ) pairs give μ ∈ [−1, 1] and complements in [0, 2]`, async () => {
    const pairs = fc.sample(fc.tuple(gArbitrary, xiArbitrary), {
      numRuns: FUZZ_RUNS,
      seed: SEED + 2,
    });
    const outcomes = await evaluateTable({
      module: 'phase',
      fn: 'hgSampleMu',
      args: ['f32', 'f32', 'f32'],
      result: 'vec3f',
      wrapper: {
        imports: ['hgSampleMu'],
        wgsl: `fn caseUnderTest(g: f32, xi: f32, oneMinusXi: f32) -> vec3f {
  let s = hgSampleMu(g, xi, oneMinusXi);
  return vec3f(s.mu, s.oneMinusMu, s.onePlusMu);
}`,
      },
      twin: (g: number, xi: number, oneMinusXi: number) => {
        const s = hgSampleMu(g, xi, oneMinusXi);
        return [s.mu, s.oneMinusMu, s.onePlusMu];
      },
      tolerance: SAMPLED_MU,
      cases: pairs.map(([g, xi], i) => ({ name: `fuzz ${i}`, args: sampleArgs(g, xi) })),
    });
    for (const [i, { gpu, twin }] of outcomes.entries()) {
      for (const [mu, oneMinusMu, onePlusMu] of [gpu, twin] as number[][]) {
        const ok =
          isFiniteAll([mu ?? NaN, oneMinusMu ?? NaN, onePlusMu ?? NaN]) &&
          (mu ?? NaN) >= -1 &&
          (mu ?? NaN) <= 1 &&
          (oneMinusMu ?? NaN) >= 0 &&
          (oneMinusMu ?? NaN) <= 2 &&
          (onePlusMu ?? NaN) >= 0 &&
          (onePlusMu ?? NaN) <= 2;
        expect(
          ok,
          `case ${i} (g, ξ) = ${pairs[i]?.join(', ')}: ${mu}, ${oneMinusMu}, ${onePlusMu}`,
        ).toBe(true);
      }
    }
  });

  it(`hgSample and rayleighSample: ${FUZZ_RUNS} (g, wo, u) give unit wi and a finite pdf > 0`, async () => {
    const inputs = fc.sample(fc.tuple(gArbitrary, unitVector, xiArbitrary, xiArbitrary), {
      numRuns: FUZZ_RUNS,
      seed: SEED + 3,
    });
    const common = {
      args: ['f32', 'f32[3]', 'f32', 'f32'] as const,
      result: 'vec4f' as const,
      tolerance: HG_VALUE,
    };
    const hg = await evaluateTable({
      ...common,
      module: 'phase',
      fn: 'hgSample',
      wrapper: hgSampleWrapper('return vec4f(s.wi, s.pdf);', 'vec4f'),
      twin: (g: number, wo: readonly number[], u0: number, u1: number) => {
        const s = twinHgSample(g, wo, u0, u1);
        return [...s.wi, s.pdf];
      },
      cases: inputs.map(([g, wo, u0, u1], i) => ({ name: `fuzz ${i}`, args: [g, wo, u0, u1] })),
    });
    const rayleigh = await evaluateTable({
      ...common,
      module: 'phase',
      fn: 'rayleighSample',
      wrapper: {
        imports: ['rayleighSample'],
        wgsl: `fn caseUnderTest(_g: f32, wo: array<f32, 3>, u0: f32, u1: f32) -> vec4f {
  let s = rayleighSample(${vec('wo')}, vec2f(u0, u1));
  return vec4f(s.wi, s.pdf);
}`,
      },
      twin: (_g: number, wo: readonly number[], u0: number, u1: number) => {
        const s = rayleighSample(asVec3(wo), [u0, u1]);
        return [...s.wi, s.pdf];
      },
      cases: inputs.map(([g, wo, u0, u1], i) => ({ name: `fuzz ${i}`, args: [g, wo, u0, u1] })),
    });
    for (const [i, { gpu, twin }] of [...hg, ...rayleigh].entries()) {
      for (const values of [gpu, twin]) {
        const [x = NaN, y = NaN, z = NaN, pdf = NaN] = values;
        // f32 unit vectors: 2e-6 covers the rounding of the basis and the renormalised azimuth.
        const ok = isFiniteAll(values) && Math.abs(Math.hypot(x, y, z) - 1) < 2e-6 && pdf > 0;
        expect(ok, `case ${i}: ${values.join(', ')}`).toBe(true);
      }
    }
  });

  it(`rayleighEval and rayleighSampleMu: ${FUZZ_RUNS} μ and ξ values stay finite, p ∈ [3/(16π), 3/(8π)], μ ∈ [−1, 1]`, async () => {
    const values = fc.sample(
      fc.oneof(muArbitrary, xiArbitrary, fc.float({ noNaN: true, noDefaultInfinity: true })),
      { numRuns: FUZZ_RUNS, seed: SEED + 4 },
    );
    const evals = await evaluateTable({
      module: 'phase',
      fn: 'rayleighEval',
      args: ['f32'],
      result: 'f32',
      twin: rayleighEval,
      tolerance: HG_VALUE,
      cases: values.map((v, i) => ({ name: `fuzz ${i}`, args: [v] })),
    });
    const samples = await evaluateTable({
      module: 'phase',
      fn: 'rayleighSampleMu',
      args: ['f32'],
      result: 'f32',
      twin: rayleighSampleMu,
      tolerance: SAMPLED_MU,
      cases: values.map((v, i) => ({ name: `fuzz ${i}`, args: [v] })),
    });
    for (const { gpu, twin } of evals)
      for (const p of [...gpu, ...twin])
        expect(p >= 3 / (16 * Math.PI) - 1e-8 && p <= 3 / (8 * Math.PI) + 1e-8).toBe(true);
    for (const { gpu, twin } of samples)
      for (const mu of [...gpu, ...twin]) expect(mu >= -1 && mu <= 1).toBe(true);
  });
});
