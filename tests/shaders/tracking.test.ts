// WGSL tracking module vs its float64 twin (physics.md §1, §4). Two layers:
//  1. the scalar functions through the table-driven harness (free flight, track
//     length, null-collision weight, comb size), hard cases included;
//  2. the estimators through a custom kernel that runs many independent walks
//     (walk i seeded with rngSeed(i, frame)), whose statistics are checked against
//     the closed forms of §4 on the GPU, and whose walks are replayed seed by seed
//     on the twin, which draws the identical PCG stream.
//
// Statistics: fixed seeds; a mean passes when |mean − T| < 5·sqrt(Var/N) (+ the f32
// systematic allowance where the GPU's σt is itself approximate, see SINE_GPU_TAU_ERROR);
// a sample variance passes within 5 standard errors from the 4th-moment formula
// SE² = (μ4 − σ⁴(N−3)/(N−1))/N. Each check has two-sided p ≈ 5.7e-7, so the ~60 checks
// of this file stay far below α = 0.01 together (Bonferroni).
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
  FREE_FLIGHT_NEVER,
  TRACKING_MAX_STEPS,
  deltaTrackingVariance,
  expectedDeltaTrackingLookups,
  expectedRatioTrackingLookups,
  nullCollisionWeight,
  ratioTrackingVariance,
  ratioTrackingVarianceHomogeneous,
  sampleFreeFlight,
  transmittanceTrackLength,
  unbiasedRayMarchingCombSize,
  unbiasedRayMarchingExpectedOrder,
} from '../../src/reference/tracking.ts';
import {
  gridMedium,
  homogeneousMedium,
  mediumExtinction,
  mediumOpticalDepth,
  sineMedium,
} from '../../src/reference/medium.ts';
import { rngSeed } from '../../src/reference/rng.ts';
import { simpson } from '../support/quadrature.ts';
import { expectMean, expectVariance, moments } from '../support/statistics.ts';
import {
  packWalkSetup,
  twinWalker,
  WALK_SETUP_WORDS,
  WALK_WGSL,
  type WalkSetup,
} from '../support/trackingKernel.ts';

// ---------------------------------------------------------------------------
// 1. Scalar functions through the harness.

// −ln(1 − ξ): WGSL log has absolute error 2^-21 on [0.5, 2] and 3 ULP elsewhere, then
// one division (2.5 ULP) by σ̄ (physics.md §10). For σ̄ ≥ 1 the absolute part is
// ≤ 2^-21 ≈ 4.8e-7; cases with σ̄ < 1 scale it by 1/σ̄.
const FREE_FLIGHT_TOLERANCE = {
  relative: 1e-6,
  absolute: 5e-7,
  reason: 'WGSL log: 2^-21 absolute near 1, 3 ULP elsewhere; division 2.5 ULP',
};

describeShaderFunction({
  module: 'tracking',
  fn: 'sampleFreeFlight',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: sampleFreeFlight,
  tolerance: FREE_FLIGHT_TOLERANCE,
  cases: [
    { name: 'ξ = 0 gives t = 0', args: [1, 0], expected: 0 },
    { name: 'σ̄ = 2, ξ = 0.5 gives ln 2 / 2', args: [2, 0.5], expected: Math.LN2 / 2 },
    {
      name: '§9 row 16: ξ = 1 − 2^-24 gives the finite maximum 16.6355/σ̄',
      args: [1, ONE_MINUS_EPSILON_F32],
      expected: 16.635532333438686,
    },
    {
      name: 'ξ = 1 (a caller outside the stream) is clamped to 1 − 2^-24',
      args: [4, 1],
      expected: 16.635532333438686 / 4,
    },
    { name: 'ξ = 0.999: the relative-error branch of log', args: [3, 0.999] },
    { name: 'ξ = 1e-6: short path, absolute error', args: [1, 1e-6] },
    {
      name: 'σ̄ = 0.01: long path',
      args: [0.01, 0.75],
      tolerance: { relative: 1e-6, absolute: 5e-5, reason: '2^-21/σ̄ absolute (log near 1)' },
    },
    { name: 'σ̄ = 0 means no collisions: "never" = largest f32', args: [0, 0.5], expected: F32_MAX },
    { name: 'negative σ̄ is "never"', args: [-1, 0.5], expected: F32_MAX },
    {
      name: 'σ̄ = 1e-38: 16.6/σ̄ would overflow f32, so "never"',
      args: [1e-38, ONE_MINUS_EPSILON_F32],
      expected: F32_MAX,
    },
    {
      name: 'subnormal σ̄ (may be flushed to 0): "never"',
      args: [F32_MIN_SUBNORMAL, 0.5],
      expected: F32_MAX,
    },
    {
      name: 'σ̄ = 1e30: tiny but finite distance',
      args: [1e30, 0.5],
      tolerance: { relative: 1e-6, absolute: 1e-36, reason: '2^-21/σ̄ absolute (log near 1)' },
    },
    {
      name: 'largest σ̄: the distance is subnormal and may flush to 0',
      args: [F32_MAX, 0.5],
      tolerance: { absolute: F32_MIN_NORMAL, reason: 'subnormal results may flush to 0' },
    },
  ],
});

describeShaderFunction({
  module: 'tracking',
  fn: 'transmittanceTrackLength',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: transmittanceTrackLength,
  tolerance: { ulps: 0, reason: 'a 0/1 decision; cases are far from the threshold t = d' },
  cases: [
    { name: 'σt = 1, d = 1, ξ = 0.5: t = 0.69 < d, absorbed', args: [1, 1, 0.5], expected: 0 },
    { name: 'σt = 1, d = 1, ξ = 0.7: t = 1.20 ≥ d, transmitted', args: [1, 1, 0.7], expected: 1 },
    { name: 'σt = 0 transmits even the longest f32 segment', args: [0, F32_MAX, 0.3], expected: 1 },
    { name: 'd = 0 always transmits', args: [5, 0, 0], expected: 1 },
    {
      name: 'σt = 1e6, d = 1: even the longest free path (1.7e-5) is absorbed (§9 row 10)',
      args: [1e6, 1, ONE_MINUS_EPSILON_F32],
      expected: 0,
    },
  ],
});

describeShaderFunction({
  module: 'tracking',
  fn: 'nullCollisionWeight',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: nullCollisionWeight,
  tolerance: {
    relative: 5e-7,
    absolute: 1e-7,
    reason: 'one division (2.5 ULP) and one subtraction',
  },
  cases: [
    { name: 'σ = 0.5, σ̄ = 2 gives 0.75', args: [0.5, 2], expected: 0.75 },
    { name: 'σ = σ̄ gives exactly 0 (early exit of ratio tracking)', args: [1e6, 1e6], expected: 0 },
    { name: 'σ = 2 > σ̄ = 1 gives −1: negative, not clamped (§4.5)', args: [2, 1], expected: -1 },
    { name: 'residual σ − σc < 0 gives a weight above 1', args: [-0.5, 0.5], expected: 2 },
    { name: 'σ = 0 gives exactly 1 even for σ̄ = 0', args: [0, 0], expected: 1 },
    { name: 'σ̄ = 0 with σ > 0: ratio bounded by 2^20', args: [1, 0], expected: 1 - 2 ** 20 },
    {
      name: 'σ/σ̄ would overflow f32: bounded by 2^20',
      args: [F32_MAX, 1e-30],
      expected: 1 - 2 ** 20,
    },
    { name: 'σ/σ̄ = 0.3', args: [0.3, 1] },
  ],
});

describeShaderFunction({
  module: 'tracking',
  fn: 'unbiasedRayMarchingCombSize',
  args: ['f32', 'u32'],
  result: 'u32',
  twin: unbiasedRayMarchingCombSize,
  tolerance: { ulps: 0, reason: 'an integer; the table values are far from rounding ties' },
  cases: [
    ...(
      [
        [0, 1],
        [1, 4],
        [2, 5],
        [5, 10],
        [10, 15],
        [50, 50],
      ] as const
    ).map(([tauMaj, size]) => ({
      name: `§4.4 table: τ̄ = ${tauMaj} gives M = ${size}`,
      args: [tauMaj, TRACKING_MAX_STEPS],
      expected: size,
    })),
    {
      name: 'huge τ̄: M is limited so that 17 combs fit maxSteps',
      args: [F32_MAX, TRACKING_MAX_STEPS],
      expected: Math.floor(TRACKING_MAX_STEPS / 17),
    },
    { name: 'negative τ̄ is clamped to 0', args: [-5, TRACKING_MAX_STEPS], expected: 1 },
    { name: 'maxSteps = 0 still gives M = 1', args: [50, 0], expected: 1 },
  ],
});

// ---------------------------------------------------------------------------
// 2. Many walks on the GPU.

const WALK_KERNEL = `
import package::rng::rngSeed;
${WALK_WGSL}
struct WalkParams {
  walkCount: u32,
  frame: u32,
}

@group(0) @binding(0) var<storage, read> setup: WalkSetup;
@group(0) @binding(1) var<storage, read> params: WalkParams;
@group(0) @binding(2) var<storage, read_write> outputs: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= params.walkCount) {
    return;
  }
  var state = rngSeed(i, params.frame);
  let r = estimateTransmittance(setup, &state);
  outputs[3u * i] = bitcast<u32>(r.estimate);
  outputs[3u * i + 1u] = r.lookups;
  outputs[3u * i + 2u] = r.capped;
}
`;

/** A setup run as many walks, walk i seeded with rngSeed(i, frame). */
interface WalkConfig extends WalkSetup {
  frame: number;
}

interface Walks {
  estimates: number[];
  lookups: number[];
  capped: number[];
}

/** 2^18 walks per GPU run: 5σ of a delta-tracking mean at T = 0.13 is ±0.0033. */
const GPU_WALKS = 1 << 18;
/** Walks replayed on the twin, seed by seed. */
const TWIN_WALKS = 20_000;

async function gpuWalks(config: WalkConfig, walks = GPU_WALKS): Promise<Walks> {
  const device = await nodeDevice();
  const code = await linkKernel(SHADER_LIBRARY, WALK_KERNEL);
  const setup = new Uint32Array(WALK_SETUP_WORDS);
  packWalkSetup(setup, 0, config);
  const { output } = await runCompute(device, {
    code,
    inputs: [setup, new Uint32Array([walks, config.frame])],
    outputWords: 3 * walks,
    workgroups: [Math.ceil(walks / 64)],
  });
  const estimates = new Float32Array(output.buffer);
  const result: Walks = { estimates: [], lookups: [], capped: [] };
  for (let i = 0; i < walks; i++) {
    result.estimates.push(estimates[3 * i] ?? NaN);
    result.lookups.push(output[3 * i + 1] ?? NaN);
    result.capped.push(output[3 * i + 2] ?? NaN);
  }
  return result;
}

function twinWalks(config: WalkConfig, walks = TWIN_WALKS): Walks {
  const walk = twinWalker(config);
  const result: Walks = { estimates: [], lookups: [], capped: [] };
  for (let i = 0; i < walks; i++) {
    const r = walk({ value: rngSeed(i, config.frame) });
    result.estimates.push(r.estimate);
    result.lookups.push(r.lookups);
    result.capped.push(r.capped);
  }
  return result;
}

/**
 * Seed-by-seed agreement with the twin: same estimate (relative 1e-5, absolute 1e-6:
 * a product of ≲ 20 f32 factors of 3 ULP each, or one WGSL exp of 3 + 2|x| ULP),
 * same lookups, same cap flag. Returns the fraction of agreeing seeds.
 */
function agreement(gpu: Walks, twin: Walks): number {
  let agree = 0;
  twin.estimates.forEach((estimate, i) => {
    const g = gpu.estimates[i] ?? NaN;
    const close = Math.abs(g - estimate) <= 1e-5 * Math.abs(estimate) + 1e-6;
    if (close && gpu.lookups[i] === twin.lookups[i] && gpu.capped[i] === twin.capped[i]) agree++;
  });
  return agree / twin.estimates.length;
}

const allFinite = (walks: Walks): boolean => walks.estimates.every(Number.isFinite);

// The media of physics.md §4 (see tests/reference/tracking.test.ts).
const SINE = sineMedium(1, 0.5, 3);
const SINE_LENGTH = 2;
const SINE_T = 0.13443986429189056;
const GRID_CELLS = [0.5, 3, 0.2, 2, 0, 1.5, 4, 0.1];
const GRID = gridMedium(GRID_CELLS, 0.25);
const GRID_LENGTH = 2;
const GRID_T = Math.exp(-mediumOpticalDepth(GRID, 0, GRID_LENGTH));

// WGSL sin may be off by 2^-11 absolute (spec, "Floating Point Accuracy"; SwiftShader
// uses that latitude), so the GPU's σt(s) = σ0(1 + a sin(ks)) may differ from the exact
// one by σ0·a·2^-11 and its τ over [0, 2] by ≤ 2·0.5·2^-11 ≈ 4.9e-4; the mean it
// estimates then differs from T by ≤ T·4.9e-4 ≈ 6.6e-5. This allowance matters only
// for unbiased ray marching, whose standard error is ~1e-5.
const SINE_GPU_TAU_ERROR = 2 * 0.5 * 2 ** -11;
const SINE_SYSTEMATIC = SINE_T * SINE_GPU_TAU_ERROR;

/** ∫f(σ(s)) ds over the sinusoid, by Simpson's rule (2000 intervals: error < 1e-12). */
const sineIntegral = (f: (sigma: number) => number): number =>
  simpson((s) => f(mediumExtinction(SINE, s)), 0, SINE_LENGTH, 2000);

interface Experiment {
  config: WalkConfig;
  gpu: Walks;
  twin: Walks;
}

/** Runs a configuration on the GPU (2^18 walks) and replays its first seeds on the twin. */
function experiment(config: WalkConfig): () => Experiment {
  let result: Experiment | null = null;
  beforeAll(async () => {
    const gpu = await gpuWalks(config);
    result = { config, gpu, twin: twinWalks(config) };
  }, 60_000);
  return () => {
    if (!result) throw new Error('the GPU run did not complete');
    return result;
  };
}

describe('delta tracking on the GPU (physics.md §4.1)', () => {
  const homogeneous = experiment({
    estimator: 'delta',
    medium: homogeneousMedium(1),
    d: 1,
    sigmaMaj: 2,
    frame: 101,
  });
  const sine = experiment({
    estimator: 'delta',
    medium: SINE,
    d: SINE_LENGTH,
    sigmaMaj: 1.5,
    frame: 102,
  });
  const grid = experiment({
    estimator: 'delta',
    medium: GRID,
    d: GRID_LENGTH,
    sigmaMaj: 4,
    frame: 103,
  });

  it('homogeneous σ = 1, d = 1, σ̄ = 2: unbiased, Var = T(1 − T), lookups (σ̄/σ)(1 − e^{−σd})', () => {
    const { gpu } = homogeneous();
    const T = Math.exp(-1);
    expectMean(moments(gpu.estimates), T, deltaTrackingVariance(T));
    expectVariance(moments(gpu.estimates), deltaTrackingVariance(T));
    expectMean(moments(gpu.lookups), expectedDeltaTrackingLookups(1, 2, 1));
    expect(gpu.estimates.every((x) => x === 0 || x === 1)).toBe(true);
    expect(gpu.capped.every((c) => c === 0)).toBe(true);
  });

  it('homogeneous: the GPU and the twin draw the same walk for ≥ 99% of seeds', () => {
    const { gpu, twin } = homogeneous();
    expect(agreement(gpu, twin)).toBeGreaterThanOrEqual(0.99);
  });

  it('smooth sinusoid (σ̄ = 1.5): unbiased for T = 0.134440 with Var = T(1 − T)', () => {
    const { gpu } = sine();
    expectMean(moments(gpu.estimates), SINE_T, deltaTrackingVariance(SINE_T), SINE_SYSTEMATIC);
    expectVariance(moments(gpu.estimates), deltaTrackingVariance(SINE_T));
  });

  it('sharp-edged grid (σ̄ = max cell = 4): unbiased with Var = T(1 − T)', () => {
    const { gpu } = grid();
    expectMean(moments(gpu.estimates), GRID_T, deltaTrackingVariance(GRID_T));
    expectVariance(moments(gpu.estimates), deltaTrackingVariance(GRID_T));
  });

  it('heterogeneous media: the twin replays the GPU walks seed by seed (≥ 99%; misses are sin-error or cell-edge ties)', () => {
    expect(agreement(sine().gpu, sine().twin)).toBeGreaterThanOrEqual(0.99);
    expect(agreement(grid().gpu, grid().twin)).toBeGreaterThanOrEqual(0.99);
  });
});

describe('ratio tracking on the GPU (physics.md §4.2)', () => {
  const homogeneous = experiment({
    estimator: 'ratio',
    medium: homogeneousMedium(1),
    d: 1,
    sigmaMaj: 2,
    frame: 111,
  });
  const sine = experiment({
    estimator: 'ratio',
    medium: SINE,
    d: SINE_LENGTH,
    sigmaMaj: 1.5,
    frame: 112,
  });
  const grid = experiment({
    estimator: 'ratio',
    medium: GRID,
    d: GRID_LENGTH,
    sigmaMaj: 4,
    frame: 113,
  });

  it('homogeneous σ = 1, d = 1, σ̄ = 2: unbiased, Var = e^{−2τ}(e^{τ²/τ̄} − 1) = 0.087795, lookups σ̄d', () => {
    const { gpu } = homogeneous();
    const variance = ratioTrackingVarianceHomogeneous(1, 2);
    expectMean(moments(gpu.estimates), Math.exp(-1), variance);
    expectVariance(moments(gpu.estimates), variance);
    expectMean(moments(gpu.lookups), expectedRatioTrackingLookups(2, 1), 2);
  });

  it('homogeneous: the GPU and the twin agree seed by seed for ≥ 99% of seeds', () => {
    const { gpu, twin } = homogeneous();
    expect(agreement(gpu, twin)).toBeGreaterThanOrEqual(0.99);
  });

  it('smooth sinusoid, σ̄ = 1.5: unbiased with Var = T²(exp(∫σ²/σ̄) − 1) = 0.064260', () => {
    const { gpu } = sine();
    const variance = ratioTrackingVariance(
      SINE_T,
      sineIntegral((s) => (s * s) / 1.5),
    );
    expect(variance).toBeCloseTo(0.06426, 5);
    expectMean(moments(gpu.estimates), SINE_T, variance, SINE_SYSTEMATIC);
    expectVariance(moments(gpu.estimates), variance);
    expectMean(moments(gpu.lookups), 1.5 * SINE_LENGTH, 1.5 * SINE_LENGTH);
  });

  it('sharp-edged grid, σ̄ = 4: unbiased with the closed-form variance, estimates in [0, 1]', () => {
    const { gpu } = grid();
    const integral = GRID_CELLS.reduce((a, s) => a + (0.25 * s * s) / 4, 0);
    const variance = ratioTrackingVariance(GRID_T, integral);
    expectMean(moments(gpu.estimates), GRID_T, variance);
    expectVariance(moments(gpu.estimates), variance);
    expect(gpu.estimates.every((x) => x >= 0 && x <= 1)).toBe(true);
  });
});

describe('residual ratio tracking on the GPU (physics.md §4.3)', () => {
  const homogeneous = experiment({
    estimator: 'residual',
    medium: homogeneousMedium(1.3),
    d: 2,
    sigmaControl: 1,
    sigmaMaj: 0.5,
    frame: 121,
  });
  const sine = experiment({
    estimator: 'residual',
    medium: SINE,
    d: SINE_LENGTH,
    sigmaControl: 1,
    sigmaMaj: 0.5,
    frame: 122,
  });
  const grid = experiment({
    estimator: 'residual',
    medium: GRID,
    d: GRID_LENGTH,
    sigmaControl: 1.4125,
    sigmaMaj: 2.6,
    frame: 123,
  });

  it('homogeneous σt = 1.3, σc = 1, σ̄r = 0.5: unbiased with Var = T²(e^{(σt−σc)²d/σ̄r} − 1)', () => {
    const { gpu } = homogeneous();
    const T = Math.exp(-2.6);
    const variance = ratioTrackingVariance(T, (0.3 * 0.3 * 2) / 0.5);
    expectMean(moments(gpu.estimates), T, variance);
    expectVariance(moments(gpu.estimates), variance);
    expectMean(moments(gpu.lookups), 0.5 * 2, 0.5 * 2);
  });

  it('homogeneous: the GPU and the twin agree seed by seed for ≥ 99% of seeds', () => {
    const { gpu, twin } = homogeneous();
    expect(agreement(gpu, twin)).toBeGreaterThanOrEqual(0.99);
  });

  it('sinusoid, σc = 1, σ̄r = 0.5: unbiased with Var = 0.012399 (5× below ratio tracking)', () => {
    const { gpu } = sine();
    const variance = ratioTrackingVariance(
      SINE_T,
      sineIntegral((s) => (s - 1) ** 2 / 0.5),
    );
    expect(variance).toBeCloseTo(0.012399, 6);
    expectMean(moments(gpu.estimates), SINE_T, variance, SINE_SYSTEMATIC);
    expectVariance(moments(gpu.estimates), variance);
  });

  it('sharp-edged grid, σc = 1.4125 (the mean), σ̄r = 2.6: unbiased with the closed-form variance', () => {
    const { gpu } = grid();
    const integral = GRID_CELLS.reduce((a, s) => a + (0.25 * (s - 1.4125) ** 2) / 2.6, 0);
    const variance = ratioTrackingVariance(GRID_T, integral);
    expectMean(moments(gpu.estimates), GRID_T, variance);
    expectVariance(moments(gpu.estimates), variance);
  });
});

describe('unbiased ray marching on the GPU (Kettunen et al. 2021, physics.md §4.4)', () => {
  const constant = experiment({
    estimator: 'unbiasedRayMarching',
    medium: homogeneousMedium(1.3),
    d: 2,
    sigmaMaj: 1.3,
    frame: 131,
  });
  const sine = experiment({
    estimator: 'unbiasedRayMarching',
    medium: SINE,
    d: SINE_LENGTH,
    sigmaMaj: 1.5,
    frame: 132,
  });
  const grid = experiment({
    estimator: 'unbiasedRayMarching',
    medium: GRID,
    d: GRID_LENGTH,
    sigmaMaj: 4,
    frame: 133,
  });

  it('zero variance for constant σt = 1.3, d = 2: every estimate is e^{−2.6} (within 1e-6 relative)', () => {
    const { gpu } = constant();
    // WGSL exp at x = −2.6: 3 + 2·2.6 ≈ 8 ULP; the comb sum σt·d/M of M equal terms and
    // the pivot average 1/(N+1)·Σ add a few ULP: 1e-6 relative ≈ 17 ULP.
    const T = 0.07427357821433388;
    const worst = gpu.estimates.reduce((a, x) => Math.max(a, Math.abs(x - T)), 0);
    expect(worst, 'largest deviation from e^{−2.6}').toBeLessThan(1e-6 * T);
    expect(moments(gpu.estimates).variance).toBeLessThan((1e-6 * T) ** 2);
  });

  it('constant σt: the GPU and the twin agree seed by seed for ≥ 99% of seeds', () => {
    const { gpu, twin } = constant();
    expect(agreement(gpu, twin)).toBeGreaterThanOrEqual(0.99);
  });

  it('draws orders with E[N] = 0.31945: mean lookups / M − 1 (M = 7 for τ̄ = 3)', () => {
    const { gpu } = sine();
    const combSize = unbiasedRayMarchingCombSize(3, TRACKING_MAX_STEPS);
    expect(combSize).toBe(7);
    const orders = gpu.lookups.map((l) => l / combSize - 1);
    expect(orders.every(Number.isInteger)).toBe(true);
    expect(orders.includes(1)).toBe(false); // orders 1..K = 2 come together
    expectMean(moments(orders), unbiasedRayMarchingExpectedOrder());
  });

  it('smooth sinusoid: unbiased, with > 100× lower variance than ratio tracking (§4.4)', () => {
    const { gpu } = sine();
    expectMean(moments(gpu.estimates), SINE_T, undefined, SINE_SYSTEMATIC);
    expect(moments(gpu.estimates).variance).toBeLessThan(0.06426 / 100);
    expect(gpu.capped.every((c) => c === 0)).toBe(true);
  });

  it('sharp-edged grid: unbiased', () => {
    expectMean(moments(grid().gpu.estimates), GRID_T);
  });

  it('heterogeneous media: the twin tracks the GPU per seed (same lookups; estimates within the sin error)', () => {
    for (const { gpu, twin } of [sine(), grid()]) {
      let agree = 0;
      twin.estimates.forEach((estimate, i) => {
        // Same order and comb size; estimates differ by at most T·δτ with δτ from
        // the GPU's sin (2^-11·σ0·a·d) or a comb point on a cell edge.
        if (
          gpu.lookups[i] === twin.lookups[i] &&
          Math.abs((gpu.estimates[i] ?? NaN) - estimate) < 1e-3
        )
          agree++;
      });
      expect(agree / twin.estimates.length).toBeGreaterThanOrEqual(0.99);
    }
  });
});

describe('track-length estimator on the GPU (physics.md §4.1)', () => {
  const homogeneous = experiment({
    estimator: 'trackLength',
    medium: homogeneousMedium(1),
    d: 1,
    sigmaMaj: 1,
    frame: 141,
  });

  it('σt = 1, d = 1: unbiased for e^{−1} with Var = T(1 − T)', () => {
    const { gpu } = homogeneous();
    const T = Math.exp(-1);
    expectMean(moments(gpu.estimates), T, deltaTrackingVariance(T));
    expectVariance(moments(gpu.estimates), deltaTrackingVariance(T));
  });

  it('the GPU and the twin agree seed by seed for ≥ 99% of seeds', () => {
    const { gpu, twin } = homogeneous();
    expect(agreement(gpu, twin)).toBeGreaterThanOrEqual(0.99);
  });
});

describe('failure modes of physics.md §4.5 on the GPU', () => {
  const deltaDense = experiment({
    estimator: 'delta',
    medium: homogeneousMedium(2),
    d: 1,
    sigmaMaj: 1,
    frame: 151,
  });
  const ratioDense = experiment({
    estimator: 'ratio',
    medium: homogeneousMedium(2),
    d: 1,
    sigmaMaj: 1,
    frame: 152,
  });
  const deltaEmpty = experiment({
    estimator: 'delta',
    medium: homogeneousMedium(0),
    d: 2,
    sigmaMaj: 1.5,
    frame: 153,
  });
  const ratioEmpty = experiment({
    estimator: 'ratio',
    medium: homogeneousMedium(0),
    d: 2,
    sigmaMaj: 1.5,
    frame: 154,
  });
  const noMajorant = (['delta', 'ratio', 'residual'] as const).map((estimator) =>
    experiment({
      estimator,
      medium: homogeneousMedium(0),
      d: 5,
      sigmaMaj: 0,
      frame: 155,
    }),
  );
  const capped = experiment({
    estimator: 'ratio',
    medium: homogeneousMedium(0),
    d: 100,
    sigmaMaj: 1,
    maxSteps: 10,
    frame: 156,
  });
  const sometimesCapped = experiment({
    estimator: 'delta',
    medium: homogeneousMedium(1),
    d: 1,
    sigmaMaj: 2,
    maxSteps: 2,
    frame: 157,
  });

  it('delta tracking with σt = 2 > σ̄ = 1 is biased high: exp(−∫min(σt, σ̄)) = 0.36788 instead of 0.135335', () => {
    const { gpu } = deltaDense();
    const biased = Math.exp(-1);
    expectMean(moments(gpu.estimates), biased, deltaTrackingVariance(biased));
    expect(moments(gpu.estimates).mean - Math.exp(-2)).toBeGreaterThan(0.2);
  });

  it('ratio tracking with σt = 2 > σ̄ = 1 stays unbiased (weights −1) with variance 0.9817', () => {
    const { gpu } = ratioDense();
    const variance = ratioTrackingVarianceHomogeneous(2, 1);
    expect(variance).toBeCloseTo(0.9817, 4);
    expectMean(moments(gpu.estimates), Math.exp(-2), variance);
    expectVariance(moments(gpu.estimates), variance);
    expect(gpu.estimates.every((x) => x === 1 || x === -1)).toBe(true);
  });

  it('σt ≡ 0 with σ̄ > 0: delta and ratio tracking give exactly 1 (zero variance) and spend Poisson(σ̄d) lookups', () => {
    for (const { gpu } of [deltaEmpty(), ratioEmpty()]) {
      expect(gpu.estimates.every((x) => x === 1)).toBe(true);
      expectMean(moments(gpu.lookups), 3, 3);
    }
  });

  it('σ̄ = 0: T = 1 without sampling — no lookups (delta, ratio and residual tracking)', () => {
    for (const run of noMajorant) {
      const { gpu } = run();
      expect(gpu.estimates.every((x) => x === 1)).toBe(true);
      expect(gpu.lookups.every((l) => l === 0)).toBe(true);
    }
  });

  it('the loop cap: 100 expected lookups with maxSteps = 10 stop at 10 with capped = 1', () => {
    const { gpu, twin } = capped();
    expect(gpu.capped.every((c) => c === 1)).toBe(true);
    expect(gpu.lookups.every((l) => l === 10)).toBe(true);
    expect(gpu.estimates.every((x) => x === 1)).toBe(true);
    expect(agreement(gpu, twin)).toBe(1);
  });

  it('the loop cap is counted, not silent: maxSteps = 2 caps some walks, and the twin counts the same ones', () => {
    const { gpu, twin } = sometimesCapped();
    const gpuCapped = gpu.capped.slice(0, TWIN_WALKS).filter((c) => c === 1).length;
    const twinCapped = twin.capped.filter((c) => c === 1).length;
    expect(gpuCapped).toBeGreaterThan(0);
    expect(Math.abs(gpuCapped - twinCapped)).toBeLessThanOrEqual(0.01 * TWIN_WALKS);
    expect(gpu.lookups.every((l) => l <= 2)).toBe(true);
  });

  it('every estimate of every run is finite', () => {
    for (const run of [deltaDense, ratioDense, deltaEmpty, ratioEmpty, capped, sometimesCapped])
      expect(allFinite(run().gpu)).toBe(true);
    expect(FREE_FLIGHT_NEVER).toBe(F32_MAX);
  });
});
