// Hard cases of physics.md §9 (rows 12–16) and §4.5 for the tracking estimators,
// each run in both implementations, plus a fuzz over f32 extremes: never NaN or
// Inf, never an endless walk (every walk stops at maxSteps and says so), delta
// tracking and track length only ever 0 or 1, lookups never above maxSteps.
//
// A small kernel runs one case per invocation: `walks` walks seeded rngSeed(w, frame),
// reporting the sum, min and max of the estimates, the total and largest lookups,
// the number of capped walks and the stream state after the last walk (so a case can
// check that no random number was drawn). The twin replays the same seeds.
import fc from 'fast-check';
import { beforeAll, describe, expect, it } from 'vitest';
import { describeShaderFunction } from '../support/shaderHarness.ts';
import { linkKernel } from '../../src/gpu/link.ts';
import { runCompute } from '../../src/gpu/compute.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import {
  F32_MAX,
  F32_MIN_NORMAL,
  F32_MIN_SUBNORMAL,
  ONE_MINUS_EPSILON_F32,
} from '../support/f32.ts';
import {
  TRACKING_MAX_STEPS,
  deltaTrackingVariance,
  ratioTrackingVarianceHomogeneous,
  sampleFreeFlight,
  transmittanceTrackLength,
} from '../../src/reference/tracking.ts';
import {
  homogeneousMedium,
  MEDIUM_GRID,
  MEDIUM_HOMOGENEOUS,
  type Medium1D,
  sineMedium,
} from '../../src/reference/medium.ts';
import { rngSeed } from '../../src/reference/rng.ts';
import {
  ESTIMATORS,
  packWalkSetup,
  twinWalker,
  WALK_SETUP_WORDS,
  WALK_WGSL,
  type WalkSetup,
} from '../support/trackingKernel.ts';

/** A setup run as `walks` walks, walk w seeded with rngSeed(w, frame). */
interface StabilityCase extends WalkSetup {
  frame: number;
  walks: number;
}

interface Outcome {
  sum: number;
  min: number;
  max: number;
  lookups: number;
  maxLookups: number;
  capped: number;
  /** Stream state after the last walk. */
  state: number;
}

const CASE_WORDS = WALK_SETUP_WORDS + 2;
const OUTCOME_WORDS = 7;

const KERNEL = `
import package::rng::rngSeed;
import package::tracking::FREE_FLIGHT_NEVER;
${WALK_WGSL}
struct StabilityCase {
  setup: WalkSetup,
  frame: u32,
  walks: u32,
}

@group(0) @binding(0) var<storage, read> cases: array<StabilityCase>;
@group(0) @binding(1) var<storage, read_write> outputs: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&cases)) {
    return;
  }
  let c = cases[i];
  var sum = 0.0;
  var lo = FREE_FLIGHT_NEVER;
  var hi = -FREE_FLIGHT_NEVER;
  var lookups = 0u;
  var maxLookups = 0u;
  var capped = 0u;
  var state = 0u;
  for (var w = 0u; w < c.walks; w++) {
    state = rngSeed(w, c.frame);
    let r = estimateTransmittance(c.setup, &state);
    sum += r.estimate;
    lo = min(lo, r.estimate);
    hi = max(hi, r.estimate);
    lookups += r.lookups;
    maxLookups = max(maxLookups, r.lookups);
    capped += r.capped;
  }
  let o = ${OUTCOME_WORDS}u * i;
  outputs[o] = bitcast<u32>(sum);
  outputs[o + 1u] = bitcast<u32>(lo);
  outputs[o + 2u] = bitcast<u32>(hi);
  outputs[o + 3u] = lookups;
  outputs[o + 4u] = maxLookups;
  outputs[o + 5u] = capped;
  outputs[o + 6u] = state;
}
`;

function packCases(cases: readonly StabilityCase[]): Uint32Array {
  const words = new Uint32Array(cases.length * CASE_WORDS);
  cases.forEach((c, index) => {
    const o = index * CASE_WORDS;
    packWalkSetup(words, o, c);
    words[o + WALK_SETUP_WORDS] = c.frame;
    words[o + WALK_SETUP_WORDS + 1] = c.walks;
  });
  return words;
}

async function runGpu(cases: readonly StabilityCase[]): Promise<Outcome[]> {
  const device = await nodeDevice();
  const code = await linkKernel(SHADER_LIBRARY, KERNEL);
  const { output } = await runCompute(device, {
    code,
    inputs: [packCases(cases)],
    outputWords: cases.length * OUTCOME_WORDS,
    workgroups: [Math.ceil(cases.length / 64)],
  });
  const floats = new Float32Array(output.buffer);
  return cases.map((_, i) => {
    const o = i * OUTCOME_WORDS;
    return {
      sum: floats[o] ?? NaN,
      min: floats[o + 1] ?? NaN,
      max: floats[o + 2] ?? NaN,
      lookups: output[o + 3] ?? NaN,
      maxLookups: output[o + 4] ?? NaN,
      capped: output[o + 5] ?? NaN,
      state: output[o + 6] ?? NaN,
    };
  });
}

/** The same case on the twin, with every input rounded to f32 as the GPU sees it. */
function runTwin(c: StabilityCase): Outcome {
  const walk = twinWalker(c);
  const outcome: Outcome = {
    sum: 0,
    min: Infinity,
    max: -Infinity,
    lookups: 0,
    maxLookups: 0,
    capped: 0,
    state: 0,
  };
  for (let w = 0; w < c.walks; w++) {
    const state = { value: rngSeed(w, c.frame) };
    const r = walk(state);
    outcome.sum += r.estimate;
    outcome.min = Math.min(outcome.min, r.estimate);
    outcome.max = Math.max(outcome.max, r.estimate);
    outcome.lookups += r.lookups;
    outcome.maxLookups = Math.max(outcome.maxLookups, r.lookups);
    outcome.capped += r.capped;
    outcome.state = state.value;
  }
  return outcome;
}

// ---------------------------------------------------------------------------
// Named hard cases.

interface NamedCase {
  name: string;
  input: StabilityCase;
  /** Checks one implementation's outcome (called for the GPU and for the twin). */
  check: (outcome: Outcome, side: 'GPU' | 'twin') => void;
}

/** |mean − expected| < 5·sqrt(Var/walks): the statistical rows (p ≈ 5.7e-7 each). */
function expectMean(outcome: Outcome, walks: number, expected: number, variance: number): void {
  const mean = outcome.sum / walks;
  const bound = 5 * Math.sqrt(variance / walks);
  expect(Math.abs(mean - expected), `mean ${mean} vs ${expected} (5σ = ${bound})`).toBeLessThan(
    bound,
  );
}

const WALKS = 4096;
const empty = homogeneousMedium(0);
const dense = homogeneousMedium(2);

const NAMED: NamedCase[] = [
  {
    name: '§9 row 12: ratio tracking with σ̄ = σt = 1e6, d = 1 gives 0 after exactly one lookup (early exit)',
    input: {
      estimator: 'ratio',
      medium: homogeneousMedium(1e6),
      d: 1,
      sigmaMaj: 1e6,
      frame: 12,
      walks: 1000,
    },
    check: (o) => {
      expect(o.min).toBe(0);
      expect(o.max).toBe(0);
      expect(o.lookups).toBe(1000);
      expect(o.maxLookups).toBe(1);
      expect(o.capped).toBe(0);
    },
  },
  ...(['delta', 'ratio'] as const).map((estimator): NamedCase => ({
    name: `§9 row 13: ${estimator} tracking with σt ≡ 0, σ̄ = 2, d = 1.5 returns exactly 1 and spends E[lookups] = σ̄d = 3`,
    input: { estimator, medium: empty, d: 1.5, sigmaMaj: 2, frame: 13, walks: WALKS },
    check: (o) => {
      expect(o.min).toBe(1);
      expect(o.max).toBe(1);
      expect(o.capped).toBe(0);
      // Lookups are Poisson(3): 5σ of the mean over 4096 walks is 5·sqrt(3/4096).
      expect(Math.abs(o.lookups / WALKS - 3)).toBeLessThan(5 * Math.sqrt(3 / WALKS));
    },
  })),
  {
    name: '§9 row 13: residual ratio tracking with σt ≡ σc = 0 returns exactly 1',
    input: {
      estimator: 'residual',
      medium: empty,
      d: 1.5,
      sigmaControl: 0,
      sigmaMaj: 2,
      frame: 13,
      walks: WALKS,
    },
    check: (o) => {
      expect(o.min).toBe(1);
      expect(o.max).toBe(1);
    },
  },
  {
    name: '§9 row 13: unbiased ray marching with σt ≡ 0 returns exactly 1',
    input: {
      estimator: 'unbiasedRayMarching',
      medium: empty,
      d: 1.5,
      sigmaMaj: 2,
      frame: 13,
      walks: WALKS,
    },
    check: (o) => {
      expect(o.min).toBe(1);
      expect(o.max).toBe(1);
    },
  },
  ...(['delta', 'ratio', 'residual'] as const).map((estimator): NamedCase => ({
    name: `§9 row 14: ${estimator} tracking with majorant 0 gives T = 1 with no lookups and no random number drawn`,
    input: { estimator, medium: empty, d: 5, sigmaMaj: 0, frame: 14, walks: 64 },
    check: (o) => {
      expect(o.min).toBe(1);
      expect(o.max).toBe(1);
      expect(o.lookups).toBe(0);
      expect(o.capped).toBe(0);
      expect(o.state, 'stream untouched').toBe(rngSeed(63, 14));
    },
  })),
  {
    name: '§9 row 14: unbiased ray marching needs no majorant: σ̄ = 0 means one point per comb, still exact for σt ≡ 0',
    input: {
      estimator: 'unbiasedRayMarching',
      medium: empty,
      d: 5,
      sigmaMaj: 0,
      frame: 14,
      walks: 64,
    },
    check: (o) => {
      expect(o.min).toBe(1);
      expect(o.max).toBe(1);
      expect(o.maxLookups).toBeGreaterThanOrEqual(1);
    },
  },
  {
    name: '§9 row 15: delta tracking with σt = 2 > σ̄ = 1 is biased high, to e^{−1} = 0.36788 (not 0.135335)',
    input: { estimator: 'delta', medium: dense, d: 1, sigmaMaj: 1, frame: 15, walks: WALKS },
    check: (o) => {
      expectMean(o, WALKS, Math.exp(-1), deltaTrackingVariance(Math.exp(-1)));
      expect(o.sum / WALKS - Math.exp(-2)).toBeGreaterThan(0.15);
    },
  },
  {
    name: '§9 row 15: ratio tracking with σt = 2 > σ̄ = 1 is unbiased for 0.135335 with weights ±1 (variance 0.98)',
    input: { estimator: 'ratio', medium: dense, d: 1, sigmaMaj: 1, frame: 15, walks: WALKS },
    check: (o) => {
      expectMean(o, WALKS, Math.exp(-2), ratioTrackingVarianceHomogeneous(2, 1));
      expect(o.min).toBe(-1);
      expect(o.max).toBe(1);
    },
  },
  {
    name: '§9 row 15: unbiased ray marching gives 0.135335 for every walk (constant σt, zero variance)',
    input: {
      estimator: 'unbiasedRayMarching',
      medium: dense,
      d: 1,
      sigmaMaj: 1,
      frame: 15,
      walks: WALKS,
    },
    check: (o) => {
      // WGSL exp: 3 + 2·2 ULP, plus the comb sum and pivot average: 1e-6 relative.
      expect(Math.abs(o.min - Math.exp(-2))).toBeLessThan(1e-6 * Math.exp(-2));
      expect(Math.abs(o.max - Math.exp(-2))).toBeLessThan(1e-6 * Math.exp(-2));
    },
  },
  {
    name: '§9 row 16: the longest free path from the stream is finite: track length through d = 16 with σt = 1 transmits sometimes, never NaN',
    input: {
      estimator: 'trackLength',
      medium: homogeneousMedium(1),
      d: 16,
      sigmaMaj: 1,
      frame: 16,
      walks: WALKS,
    },
    check: (o) => {
      expect(o.min).toBe(0);
      expect(o.max).toBeLessThanOrEqual(1);
      expect(Number.isFinite(o.sum)).toBe(true);
    },
  },
  {
    name: '§4.5 loop cap: 100 expected lookups with maxSteps = 3 stop at 3 with capped = 1 on every walk',
    input: {
      estimator: 'ratio',
      medium: empty,
      d: 100,
      sigmaMaj: 1,
      frame: 17,
      walks: 256,
      maxSteps: 3,
    },
    check: (o) => {
      expect(o.capped).toBe(256);
      expect(o.lookups).toBe(3 * 256);
      expect(o.min).toBe(1);
    },
  },
  {
    name: '§4.5 loop cap with maxSteps = 0: unbiased ray marching reports capped and spends no lookups',
    input: {
      estimator: 'unbiasedRayMarching',
      medium: homogeneousMedium(1),
      d: 1,
      sigmaMaj: 1,
      frame: 18,
      walks: 64,
      maxSteps: 0,
    },
    check: (o) => {
      expect(o.capped).toBe(64);
      expect(o.lookups).toBe(0);
    },
  },
  // Null-scattering tracking (Miller et al. 2019) at β = 0 (delta tracking's P_n), 0.5 and 1
  // (ratio tracking's P_n = 1).
  ...[0, 0.5, 1].map((nullBlend): NamedCase => ({
    name: `null scattering, β = ${nullBlend}: σt ≡ 0 gives P_n = 1 and factor 1, so exactly 1, after E[lookups] = σ̄d = 3`,
    input: {
      estimator: 'nullScattering',
      medium: empty,
      d: 1.5,
      sigmaMaj: 2,
      nullBlend,
      frame: 23,
      walks: WALKS,
    },
    check: (o) => {
      expect(o.min).toBe(1);
      expect(o.max).toBe(1);
      expect(o.capped).toBe(0);
      expect(Math.abs(o.lookups / WALKS - 3)).toBeLessThan(5 * Math.sqrt(3 / WALKS));
    },
  })),
  ...[0, 0.5, 1].map((nullBlend): NamedCase => ({
    name: `null scattering, β = ${nullBlend}: σ̄ = 0 gives T = 1 with no lookup and no random number`,
    input: {
      estimator: 'nullScattering',
      medium: empty,
      d: 5,
      sigmaMaj: 0,
      nullBlend,
      frame: 24,
      walks: 64,
    },
    check: (o) => {
      expect(o.min).toBe(1);
      expect(o.max).toBe(1);
      expect(o.lookups).toBe(0);
      expect(o.state, 'stream untouched').toBe(rngSeed(63, 24));
    },
  })),
  ...(
    [
      // β, P_n = 1 − (1 − β)·σt/(|σn| + σt) with σt = 2, σ̄ = 1, and E[T̂²] = exp(σn²/(σ̄P_n) − σ̄).
      [0, 1 / 3],
      [0.5, 2 / 3],
      [1, 1],
    ] as const
  ).map(([nullBlend, pn]): NamedCase => ({
    name: `null scattering, β = ${nullBlend}: σt = 2 > σ̄ = 1 (σn = −1) stays unbiased for 0.135335 with factors −1/P_n = ${(-1 / pn).toFixed(2)}`,
    input: {
      estimator: 'nullScattering',
      medium: dense,
      d: 1,
      sigmaMaj: 1,
      nullBlend,
      frame: 25,
      walks: 4 * WALKS,
    },
    check: (o) => {
      const T = Math.exp(-2);
      expectMean(o, 4 * WALKS, T, Math.exp(1 / pn - 1) - T * T);
      // Weights are (−1/P_n)^k over k null vertices: negative for odd k, 1 for none.
      expect(o.min).toBeLessThanOrEqual(-1 / pn + 1e-5);
      expect(o.max).toBeGreaterThanOrEqual(1);
    },
  })),
  ...[0, 0.5].map((nullBlend): NamedCase => ({
    name: `null scattering, β = ${nullBlend}: σt = σ̄ = 1e6 has P_n = 1 − (1 − β), so β = 0 ends at the first collision with 0`,
    input: {
      estimator: 'nullScattering',
      medium: homogeneousMedium(1e6),
      d: 1,
      sigmaMaj: 1e6,
      nullBlend,
      frame: 26,
      walks: 1000,
    },
    check: (o) => {
      expect(o.min).toBe(0);
      expect(o.max).toBe(0);
      // β = 0: every collision is real; β = 0.5: a null vertex has factor σn/(σ̄P_n) = 0.
      expect(o.lookups).toBe(1000);
      expect(o.maxLookups).toBe(1);
    },
  })),
  {
    name: 'null scattering: the loop cap, σt ≡ 0 with 100 expected lookups and maxSteps = 3, stops at 3 with capped = 1',
    input: {
      estimator: 'nullScattering',
      medium: empty,
      d: 100,
      sigmaMaj: 1,
      nullBlend: 0.5,
      frame: 27,
      walks: 256,
      maxSteps: 3,
    },
    check: (o) => {
      expect(o.capped).toBe(256);
      expect(o.lookups).toBe(3 * 256);
      expect(o.min).toBe(1);
      expect(o.max).toBe(1);
    },
  },
];

describe('tracking hard cases (physics.md §9 rows 12–16, §4.5) in WGSL and in the twin', () => {
  let gpu: Outcome[] = [];
  beforeAll(async () => {
    gpu = await runGpu(NAMED.map((c) => c.input));
  }, 60_000);

  NAMED.forEach((named, index) => {
    it(named.name, () => {
      const g = gpu[index];
      expect(g, 'the GPU run completed').toBeDefined();
      if (!g) return;
      const t = runTwin(named.input);
      named.check(g, 'GPU');
      named.check(t, 'twin');
      // Same seeds, same stream: the walks agree (ties at thresholds aside, which
      // these homogeneous cases do not hit).
      expect(g.lookups, 'GPU and twin spend the same lookups').toBe(t.lookups);
      expect(g.capped).toBe(t.capped);
      expect(g.state, 'GPU and twin end on the same stream state').toBe(t.state);
    });
  });
});

describeShaderFunction({
  module: 'tracking',
  fn: 'sampleFreeFlight',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: sampleFreeFlight,
  tolerance: {
    relative: 1e-6,
    absolute: 5e-7,
    reason: 'WGSL log: 2^-21 absolute near 1, 3 ULP elsewhere; division 2.5 ULP',
  },
  cases: [
    {
      name: '§9 row 16: ξ = 1 − 2^-24 (from 0xFFFFFFFF) gives t = 16.6355/σ̄, finite',
      args: [1, ONE_MINUS_EPSILON_F32],
      expected: 16.635532333438686,
    },
    {
      name: '§9 row 14: σ̄ = 0 is never sampled: "never" = largest f32, not +∞',
      args: [0, 0.5],
      expected: F32_MAX,
    },
    {
      name: 'subnormal σ̄ (may flush to 0): "never", not +∞',
      args: [F32_MIN_SUBNORMAL, ONE_MINUS_EPSILON_F32],
      expected: F32_MAX,
    },
    {
      name: 'smallest normal σ̄: 16.6/σ̄ overflows f32, so "never"',
      args: [F32_MIN_NORMAL, ONE_MINUS_EPSILON_F32],
      expected: F32_MAX,
    },
  ],
});

describeShaderFunction({
  module: 'tracking',
  fn: 'transmittanceTrackLength',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: transmittanceTrackLength,
  tolerance: { ulps: 0, reason: 'a 0/1 decision, away from the threshold' },
  cases: [
    {
      name: '§9 row 16: the longest path 16.6355 passes d = 16 (σt = 1)',
      args: [1, 16, ONE_MINUS_EPSILON_F32],
      expected: 1,
    },
    {
      name: '§9 row 16: … but not d = 17',
      args: [1, 17, ONE_MINUS_EPSILON_F32],
      expected: 0,
    },
    {
      name: '§9 row 14: σt = 0 passes the largest f32 segment',
      args: [0, F32_MAX, 0.9],
      expected: 1,
    },
  ],
});

// ---------------------------------------------------------------------------
// Fuzz over f32 extremes.

const EXTREMES = [
  0,
  -0,
  F32_MIN_SUBNORMAL,
  F32_MIN_NORMAL,
  1e-30,
  1e-6,
  0.5,
  1,
  2,
  103.97,
  1e6,
  1e18,
  1e30,
  F32_MAX,
  -1,
  -F32_MAX,
];
const anyF32 = fc.oneof(
  fc.constantFrom(...EXTREMES),
  fc.float({ noNaN: true, noDefaultInfinity: true }),
);
/** Caps from none to the default; small ones make most walks hit them. */
const maxStepsArbitrary = fc.constantFrom(0, 1, 2, 16, 17, 1000, TRACKING_MAX_STEPS);

// The medium module's own domain: its sinusoid overflows for σ0 > FLT_MAX/2 and its
// sin/grid index need finite products k·s and s/h. Those are the medium module's hard
// cases; here σ0, k, h and d stay where the medium is finite, while the homogeneous
// medium (σt = σ0 exactly) takes every f32.
const boundedF32 = fc.oneof(
  fc.constantFrom(0, 1e-30, 1e-6, 0.5, 1, 2, 1e6, 1e18, 1e30, -1),
  fc.float({ min: Math.fround(-1e30), max: Math.fround(1e30), noNaN: true }),
);
const mediumArbitrary: fc.Arbitrary<Medium1D> = fc.oneof(
  anyF32.map(homogeneousMedium),
  fc
    .record({
      sigma0: boundedF32,
      amplitude: anyF32,
      frequency: fc.float({ min: 0, max: 1e6, noNaN: true }),
    })
    .map(({ sigma0, amplitude, frequency }) => sineMedium(sigma0, amplitude, frequency)),
  fc
    .record({
      cells: fc.array(anyF32, { minLength: 16, maxLength: 16 }),
      cellCount: fc.integer({ min: 0, max: 20 }),
      cellSize: fc.oneof(
        fc.constantFrom(0, -1, 1e-6, 0.25, 1e6),
        fc.float({ min: Math.fround(1e-6), max: 1e6, noNaN: true }),
      ),
    })
    .map(({ cells, cellCount, cellSize }): Medium1D => ({
      kind: MEDIUM_GRID,
      sigma0: 0,
      amplitude: 0,
      frequency: 0,
      phase: 0,
      cellSize,
      cellCount,
      cells,
    })),
);

const fuzzCases: StabilityCase[] = fc
  .sample(
    fc.record({
      estimator: fc.constantFrom(...ESTIMATORS),
      medium: mediumArbitrary,
      d: anyF32,
      sigmaMaj: anyF32,
      sigmaControl: anyF32,
      nullBlend: anyF32,
      frame: fc.integer({ min: 0, max: 0xffffffff }),
      maxSteps: maxStepsArbitrary,
    }),
    { numRuns: 1024, seed: 20261124 },
  )
  .map((c) => ({
    ...c,
    // Keep the products s·k and s/h finite for the heterogeneous media (see above).
    d: c.medium.kind === MEDIUM_HOMOGENEOUS ? c.d : Math.min(Math.abs(c.d), 1e30),
    walks: 2,
  }));

function checkInvariants(c: StabilityCase, o: Outcome, label: string): void {
  const maxSteps = c.maxSteps ?? TRACKING_MAX_STEPS;
  const what = `${label}: ${c.estimator} d=${c.d} σ̄=${c.sigmaMaj} σc=${c.sigmaControl} kind=${c.medium.kind} σ0=${c.medium.sigma0} maxSteps=${maxSteps}`;
  for (const x of [o.sum, o.min, o.max])
    expect(Number.isFinite(x), `${what}: estimate ${x} is finite`).toBe(true);
  expect(o.maxLookups, `${what}: lookups ≤ maxSteps`).toBeLessThanOrEqual(maxSteps);
  expect(o.capped, `${what}: capped counts walks`).toBeLessThanOrEqual(c.walks);
  if (c.estimator === 'delta' || c.estimator === 'trackLength') {
    expect([0, 1], `${what}: min ∈ {0, 1}`).toContain(o.min);
    expect([0, 1], `${what}: max ∈ {0, 1}`).toContain(o.max);
  }
  if (c.estimator === 'trackLength') expect(o.lookups).toBe(0);
}

describe('fuzz: tracking over f32 extremes never produces NaN/Inf, never loops forever, respects the cap', () => {
  let gpu: Outcome[] = [];
  beforeAll(async () => {
    gpu = await runGpu(fuzzCases);
  }, 60_000);

  it(`WGSL: ${fuzzCases.length} fuzzed cases (estimator, medium, d, σ̄, σc, maxSteps) stay finite and within the cap`, () => {
    expect(gpu.length).toBe(fuzzCases.length);
    fuzzCases.forEach((c, i) => {
      const o = gpu[i];
      expect(o).toBeDefined();
      if (o) checkInvariants(c, o, `GPU case ${i}`);
    });
  });

  it('twin: the same fuzzed cases stay finite and within the cap', () => {
    fuzzCases.forEach((c, i) => checkInvariants(c, runTwin(c), `twin case ${i}`));
  });

  it('the fuzz reaches the cap and the degenerate branches (it is not vacuous)', () => {
    const cappedCases = gpu.filter((o) => o.capped > 0).length;
    const noLookups = gpu.filter((o) => o.lookups === 0).length;
    expect(cappedCases).toBeGreaterThan(10);
    expect(noLookups).toBeGreaterThan(10);
    expect(gpu.length - cappedCases - noLookups).toBeGreaterThan(10);
  });
});
